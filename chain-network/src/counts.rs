//! Maxwell-Calladine counts of a patch: zero modes `N0 = dof - rank C` and states of
//! self-stress `Nss = bonds - rank C`, with rigid motions counted as zero modes, and the index
//! theorem `N0 - Nss = dof - bonds` checked on every answer (Calladine 1978; Kane and Lubensky
//! eq. 1).
//!
//! **Rank rule**: singular values above `1e-9` times the largest ([`crate::linalg::rank`]).
//!
//! - **Periodic patches** are counted through their Bloch blocks: on an `N1 x N2` torus the
//!   compatibility matrix is unitarily block-diagonal, one block `Q(k)` per wave vector with
//!   `k . a_i = 2 pi m_i / N_i`, so its singular values are those of the `N1 N2` small blocks
//!   (the null space is the union of the blocks' null spaces, each Bloch wave
//!   `u e^{i k . R}`). `Q(-k)` is the complex conjugate of `Q(k)` and has the same singular
//!   values, so only half of the blocks are decomposed.
//! - **Free patches** up to [`MAX_DENSE_FREE_SIDE`] rows or columns are counted by a singular
//!   value decomposition of the whole compatibility matrix (singular values only, 2 threads). Not
//!   through `C^T C` alone, which squares the `1e-9` threshold below rounding, and not by an
//!   unpivoted QR, which misses null vectors that decay against the elimination order (as
//!   polarized lattices' edge modes do). Larger free patches take chain-core's sparse, stoppable
//!   count ([`chain_core::statics::counting::maxwell_calladine_sparse`] on the patch's
//!   [`NetworkModel`] at its reference configuration): the Gram matrices' inertia chooses the
//!   candidates and the singular values of `C` on their span decide, with chain-core's rule
//!   (`max(n, m) eps sigma_max`, below this module's `1e-9 sigma_max`: a singular value between
//!   the two is counted in the rank there); a dense SVD of that size cannot be stopped and takes
//!   minutes.
//!
//! Every count asks its stop question ([`counts_with`], [`null_spaces_with`]) before each Bloch
//! block or decomposition; Python's `Network.counts` and `.null_spaces` pass Ctrl-C.

use crate::bloch;
use crate::compatibility::bond_rows;
use crate::error::NetworkError;
use crate::linalg::{self, RANK_TOLERANCE};
use crate::model::NetworkModel;
use crate::patch::{Boundary, Patch};
use chain_core::statics::counting::{Counting, maxwell_calladine_sparse};
use faer::{Mat, c64};
use std::f64::consts::TAU;

/// How a count was obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// `blocks` Bloch blocks of a periodic patch, of which `decomposed` were decomposed (the rest
    /// are complex conjugates).
    BlochBlocks {
        /// Blocks in all (`N1 N2`).
        blocks: usize,
        /// Blocks decomposed.
        decomposed: usize,
    },
    /// One singular value decomposition of the whole compatibility matrix.
    DenseSvd,
    /// chain-core's sparse count (a free patch above [`MAX_DENSE_FREE_SIDE`]).
    Sparse,
}

/// The most rows or columns of a free patch's compatibility matrix counted by a dense SVD
/// (singular values only, about 0.3 s at 1024 in release); larger free patches take the sparse,
/// stoppable path. Vectors ([`null_spaces`]) are computed densely up to the same side.
pub const MAX_DENSE_FREE_SIDE: usize = 1024;

/// The stop question of [`counts`] and [`null_spaces`]: never.
fn never() -> bool {
    false
}

/// The error of a count stopped by its question.
fn stopped(what: &'static str, done: usize, of: usize) -> NetworkError {
    NetworkError::Statics(chain_core::linalg::LinalgError::Stopped { what, done, of }.into())
}

/// The counts of a patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Counts {
    /// Degrees of freedom.
    pub dof: usize,
    /// Bonds.
    pub bonds: usize,
    /// Rank of the compatibility matrix.
    pub rank: usize,
    /// Zero modes `N0 = dof - rank` (rigid motions included).
    pub zero_modes: usize,
    /// States of self-stress `Nss = bonds - rank`.
    pub self_stresses: usize,
    /// The largest singular value (on the sparse path by power iteration, from below).
    pub largest_singular_value: f64,
    /// The smallest singular value counted in the rank (`None` if the rank is 0; on the sparse
    /// path the smallest among its candidates, `None` if every candidate was zero).
    pub smallest_kept: Option<f64>,
    /// The largest singular value counted as zero (`None` if none is): with `smallest_kept`, how
    /// clear the decision at the threshold (`1e-9 * largest`; on the sparse path chain-core's
    /// `max(n, m) eps * largest`) was.
    pub largest_dropped: Option<f64>,
    /// How the singular values were obtained.
    pub method: Method,
}

impl Counts {
    fn new(
        dof: usize,
        bonds: usize,
        singular: impl Iterator<Item = (f64, usize)> + Clone,
        largest: f64,
        method: Method,
    ) -> Result<Self, NetworkError> {
        let threshold = RANK_TOLERANCE * largest;
        let mut rank = 0;
        let (mut kept, mut dropped): (Option<f64>, Option<f64>) = (None, None);
        for (s, weight) in singular {
            if s > threshold {
                rank += weight;
                kept = Some(kept.map_or(s, |k: f64| k.min(s)));
            } else {
                dropped = Some(dropped.map_or(s, |d: f64| d.max(s)));
            }
        }
        let counts = Counts {
            dof,
            bonds,
            rank,
            zero_modes: dof - rank,
            self_stresses: bonds - rank,
            largest_singular_value: largest,
            smallest_kept: kept,
            largest_dropped: dropped,
            method,
        };
        counts.check_index_theorem()?;
        Ok(counts)
    }

    /// The index theorem `N0 - Nss = dof - bonds` (Calladine; Kane and Lubensky eq. 1), and
    /// `rank <= min(dof, bonds)`.
    pub fn check_index_theorem(&self) -> Result<(), NetworkError> {
        let ok = self.rank <= self.dof.min(self.bonds)
            && self.zero_modes as i64 - self.self_stresses as i64 == self.dof as i64 - self.bonds as i64;
        if ok {
            Ok(())
        } else {
            Err(NetworkError::IndexTheorem {
                zero_modes: self.zero_modes,
                self_stresses: self.self_stresses,
                dof: self.dof,
                bonds: self.bonds,
            })
        }
    }
}

/// The Bloch blocks of a periodic patch: for each wave vector on the patch's grid, its phases,
/// and whether its conjugate partner `-k` is a different grid point.
fn bloch_grid(patch: &Patch) -> Vec<([usize; 2], [f64; 2], bool)> {
    let [n1, n2] = patch.cells();
    let mut out = Vec::with_capacity(n1 * n2 / 2 + 2);
    for m2 in 0..n2 {
        for m1 in 0..n1 {
            let partner = [(n1 - m1) % n1, (n2 - m2) % n2];
            let me = m1 + n1 * m2;
            let them = partner[0] + n1 * partner[1];
            if them < me {
                continue; // decomposed as its partner
            }
            let theta = [TAU * m1 as f64 / n1 as f64, TAU * m2 as f64 / n2 as f64];
            out.push(([m1, m2], theta, them != me));
        }
    }
    out
}

/// The counts of a patch: through Bloch blocks if periodic, one dense SVD if free (the sparse
/// path above [`MAX_DENSE_FREE_SIDE`]).
pub fn counts(patch: &Patch) -> Result<Counts, NetworkError> {
    counts_with(patch, &mut never)
}

/// [`counts`] with a stop question, asked before each Bloch block, before the dense SVD and
/// throughout the sparse path; a yes is `NetworkError::Statics` holding `LinalgError::Stopped`.
pub fn counts_with(patch: &Patch, stop: &mut dyn FnMut() -> bool) -> Result<Counts, NetworkError> {
    let cell = patch.cell();
    let (dof, bonds) = (patch.dof(), patch.bonds().len());
    match patch.boundary() {
        Boundary::Periodic => {
            let rows = bond_rows(cell);
            let grid = bloch_grid(patch);
            let mut q = Mat::<c64>::zeros(cell.bonds().len(), cell.dof());
            let mut values: Vec<(f64, usize)> =
                Vec::with_capacity(grid.len() * cell.dof().min(cell.bonds().len()));
            for (done, &(_, theta, paired)) in grid.iter().enumerate() {
                if stop() {
                    return Err(stopped("Bloch blocks", done, grid.len()));
                }
                bloch::fill(&rows, theta, &mut q);
                let s = linalg::singular_values("Bloch block Q(k)", q.as_ref())?;
                values.extend(s.into_iter().map(|s| (s, if paired { 2 } else { 1 })));
            }
            let largest = values.iter().map(|v| v.0).fold(0.0, f64::max);
            let method = Method::BlochBlocks { blocks: patch.cell_count(), decomposed: grid.len() };
            Counts::new(dof, bonds, values.into_iter(), largest, method)
        }
        Boundary::Free if dof.max(bonds) > MAX_DENSE_FREE_SIDE => Ok(sparse(patch, stop)?.0),
        Boundary::Free => {
            if stop() {
                return Err(stopped("SVDs", 0, 1));
            }
            let c = patch.compatibility_matrix()?;
            let s = linalg::singular_values("compatibility matrix", c.as_ref())?;
            let largest = s.first().copied().unwrap_or(0.0);
            Counts::new(dof, bonds, s.into_iter().map(|s| (s, 1)), largest, Method::DenseSvd)
        }
    }
}

/// A free patch counted by chain-core's sparse path on its model at the reference
/// configuration, with the counting (its null vectors in the model's coordinates: a rotor's
/// angle, where the patch's columns take its tip's arc length).
fn sparse(patch: &Patch, stop: &mut dyn FnMut() -> bool) -> Result<(Counts, Counting), NetworkError> {
    let model = NetworkModel::builder(patch).build()?;
    let counting = maxwell_calladine_sparse(&model, &model.reference(), None, stop)?;
    let (dof, bonds) = (patch.dof(), patch.bonds().len());
    // The candidates' singular values, descending: the zero modes' are the last `dof - rank`.
    let (mut kept, mut dropped): (Option<f64>, Option<f64>) = (None, None);
    for &s in &counting.singular_values {
        if s > counting.tolerance {
            kept = Some(kept.map_or(s, |k| k.min(s)));
        } else {
            dropped = Some(dropped.map_or(s, |d| d.max(s)));
        }
    }
    let counts = Counts {
        dof,
        bonds,
        rank: counting.rank,
        zero_modes: dof - counting.rank,
        self_stresses: bonds - counting.rank,
        largest_singular_value: counting.largest_singular_value,
        smallest_kept: kept,
        largest_dropped: dropped,
        method: Method::Sparse,
    };
    counts.check_index_theorem()?;
    Ok((counts, counting))
}

/// Zero modes and states of self-stress as real orthonormal vectors (columns).
#[derive(Clone, Debug)]
pub struct NullSpaces {
    /// The counts they come with.
    pub counts: Counts,
    /// Zero modes: `dof x N0`, orthonormal columns with `C u = 0` (to the rank rule).
    pub zero_modes: Mat<f64>,
    /// States of self-stress: `bonds x Nss`, orthonormal columns with `C^T s = 0`.
    pub self_stresses: Mat<f64>,
}

/// The largest patch whose vectors are computed (a full SVD keeps two square matrices).
pub const MAX_VECTOR_DOF: usize = 6000;

/// Zero modes and states of self-stress of a patch as real vectors.
///
/// Free patches: the singular vectors of the whole matrix. Periodic patches: from each block's
/// null vectors `v` the Bloch waves `v e^{i k . R}`; for a pair `k, -k` their real and imaginary
/// parts (orthogonal, of equal norm), for a real block (`2k` on the grid's origin) the real null
/// vectors of the real block; all normalised.
pub fn null_spaces(patch: &Patch) -> Result<NullSpaces, NetworkError> {
    null_spaces_with(patch, &mut never)
}

/// [`null_spaces`] with a stop question, asked as [`counts_with`] asks it. A free patch above
/// [`MAX_DENSE_FREE_SIDE`] takes the sparse path: its zero modes, found in the model's
/// coordinates (a rotor's angle), are taken to the patch's (the tip's arc length: times the
/// rotor's length) and orthonormalised again.
pub fn null_spaces_with(patch: &Patch, stop: &mut dyn FnMut() -> bool) -> Result<NullSpaces, NetworkError> {
    let (dof, bonds) = (patch.dof(), patch.bonds().len());
    if dof.max(bonds) > MAX_VECTOR_DOF {
        return Err(NetworkError::TooLarge {
            what: "zero-mode vectors",
            rows: bonds,
            cols: dof,
            limit: MAX_VECTOR_DOF * MAX_VECTOR_DOF,
        });
    }
    match patch.boundary() {
        Boundary::Free if dof.max(bonds) > MAX_DENSE_FREE_SIDE => {
            let (counts, counting) = sparse(patch, stop)?;
            let arc = arc_lengths(patch);
            let modes = Mat::<f64>::from_fn(dof, counting.zero_modes.len(), |i, j| {
                counting.zero_modes[j][i] * arc[i]
            });
            let stresses =
                Mat::<f64>::from_fn(bonds, counting.self_stresses.len(), |i, j| counting.self_stresses[j][i]);
            Ok(NullSpaces { counts, zero_modes: orthonormal(modes), self_stresses: stresses })
        }
        Boundary::Free => {
            if stop() {
                return Err(stopped("SVDs", 0, 1));
            }
            let c = patch.compatibility_matrix()?;
            let svd = linalg::full_svd("compatibility matrix", c.as_ref())?;
            let largest = svd.s.first().copied().unwrap_or(0.0);
            let counts = Counts::new(dof, bonds, svd.s.iter().map(|&s| (s, 1)), largest, Method::DenseSvd)?;
            Ok(NullSpaces {
                counts,
                zero_modes: svd.right_null(largest),
                self_stresses: svd.left_null(largest),
            })
        }
        Boundary::Periodic => periodic_null_spaces(patch, stop),
    }
}

/// Per degree of freedom of the patch, the factor from the model's coordinate to the patch's: 1
/// for a joint's, the rotor's length for a rotor's angle.
fn arc_lengths(patch: &Patch) -> Vec<f64> {
    let per_cell: Vec<f64> = patch
        .cell()
        .nodes()
        .iter()
        .flat_map(|node| match node.kind {
            crate::NodeKind::Rotor { length, .. } => vec![length],
            crate::NodeKind::Joint { .. } => vec![1.0, 1.0],
        })
        .collect();
    per_cell.iter().copied().cycle().take(patch.dof()).collect()
}

/// The columns of `a` orthonormalised (the thin `Q` of its QR decomposition).
fn orthonormal(a: Mat<f64>) -> Mat<f64> {
    if a.ncols() == 0 {
        return a;
    }
    a.qr().compute_thin_Q()
}

fn periodic_null_spaces(patch: &Patch, stop: &mut dyn FnMut() -> bool) -> Result<NullSpaces, NetworkError> {
    let cell = patch.cell();

    let grid = bloch_grid(patch);
    let mut blocks = Vec::with_capacity(grid.len());
    let mut largest: f64 = 0.0;
    for (done, &(m, theta, paired)) in grid.iter().enumerate() {
        if stop() {
            return Err(stopped("Bloch blocks", done, grid.len()));
        }
        let q = bloch::compatibility(cell, theta);
        let svd = linalg::full_svd("Bloch block Q(k)", q.as_ref())?;
        largest = largest.max(svd.s.first().copied().unwrap_or(0.0));
        blocks.push((m, theta, paired, svd));
    }
    let values = blocks
        .iter()
        .flat_map(|(_, _, paired, svd)| svd.s.iter().map(move |&s| (s, if *paired { 2 } else { 1 })));
    let counts = Counts::new(
        patch.dof(),
        patch.bonds().len(),
        values,
        largest,
        Method::BlochBlocks { blocks: patch.cell_count(), decomposed: grid.len() },
    )?;
    let mut modes: Vec<Vec<f64>> = Vec::with_capacity(counts.zero_modes);
    let mut stresses: Vec<Vec<f64>> = Vec::with_capacity(counts.self_stresses);
    let [n1, n2] = patch.cells();
    for (_, theta, paired, svd) in &blocks {
        let phase = |c: [usize; 2]| {
            let p = theta[0] * c[0] as f64 + theta[1] * c[1] as f64;
            c64::new(p.cos(), p.sin())
        };
        // Zero modes: per cell c, u_c = v e^{i k . c}.
        let right = svd.right_null(largest);
        let left = svd.left_null(largest);
        for (null, out, per_cell, is_mode) in
            [(&right, &mut modes, cell.dof(), true), (&left, &mut stresses, cell.bonds().len(), false)]
        {
            let len = if is_mode { patch.dof() } else { patch.bonds().len() };
            let cols = if *paired { complex_to_real(null) } else { real_basis(null) };
            for v in cols {
                let (mut re, mut im) = (vec![0.0; len], vec![0.0; len]);
                for c2 in 0..n2 {
                    for c1 in 0..n1 {
                        let z = phase([c1, c2]);
                        let base = (c1 + n1 * c2) * per_cell;
                        for (j, vj) in v.iter().enumerate() {
                            let w = *vj * z;
                            re[base + j] = w.re;
                            im[base + j] = w.im;
                        }
                    }
                }
                push_normalised(out, re);
                if *paired {
                    push_normalised(out, im);
                }
            }
        }
    }
    let to_mat = |v: &[Vec<f64>], rows: usize| Mat::<f64>::from_fn(rows, v.len(), |i, j| v[j][i]);
    if modes.len() != counts.zero_modes || stresses.len() != counts.self_stresses {
        return Err(NetworkError::IndexTheorem {
            zero_modes: modes.len(),
            self_stresses: stresses.len(),
            dof: patch.dof(),
            bonds: patch.bonds().len(),
        });
    }
    Ok(NullSpaces {
        counts,
        zero_modes: to_mat(&modes, patch.dof()),
        self_stresses: to_mat(&stresses, patch.bonds().len()),
    })
}

fn push_normalised(out: &mut Vec<Vec<f64>>, mut v: Vec<f64>) {
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    for x in &mut v {
        *x /= n;
    }
    out.push(v);
}

/// The columns of a complex null-space basis, as complex vectors.
fn complex_to_real(null: &Mat<c64>) -> Vec<Vec<c64>> {
    (0..null.ncols()).map(|j| (0..null.nrows()).map(|i| null[(i, j)]).collect()).collect()
}

/// A real basis of the null space of a real block (phases +-1) spanned by complex columns: the
/// real and imaginary parts of the columns span it; an SVD of `[Re | Im]` picks an orthonormal
/// real basis of the right dimension.
fn real_basis(null: &Mat<c64>) -> Vec<Vec<c64>> {
    let (n, d) = (null.nrows(), null.ncols());
    if d == 0 {
        return Vec::new();
    }
    let parts =
        Mat::<f64>::from_fn(n, 2 * d, |i, j| if j < d { null[(i, j)].re } else { null[(i, j - d)].im });
    let svd = linalg::full_svd("real null basis", parts.as_ref()).expect("a small SVD");
    (0..d).map(|j| (0..n).map(|i| c64::new(svd.u[(i, j)], 0.0)).collect()).collect()
}
