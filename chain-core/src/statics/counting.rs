//! Maxwell-Calladine counting (paper Sec. VII-A; Kane and Lubensky 2014), for any
//! [`SpringNetwork`].
//!
//! The compatibility matrix `C` (`m x n` for `m` springs and `n` degrees of freedom; a chain's is
//! `(n - 1) x n`, `C[p][i] = dl_p / d(r_i theta_i)`) maps displacements to spring extensions. Its
//! null space holds the **zero modes** (displacements that stretch no spring) and the null space
//! of `C^T` the **states of self-stress** (tensions in equilibrium with no load). With
//! `rank C = rho`, there are `n - rho` zero modes and `m - rho` self-stresses, so
//! `N_zero - N_selfstress = n - m` on every configuration, whatever its geometry (1 for a chain).
//!
//! The rank comes from the singular values of `C` with the tolerance
//! `max(n, m) * epsilon * sigma_max` (the usual numerical-rank rule). A chain's `C` is bidiagonal:
//! its singular values and null spaces come from its Golub-Kahan tridiagonal (bisection on Sturm
//! counts to relative accuracy, inverse iteration; `linalg/golub_kahan.rs`), O(n) per count and
//! O(n^2) in all, stoppable ([`maxwell_calladine_with`]). Any other layout (a network's sparse
//! `C`) goes through a dense SVD up to [`MAX_DENSE_SVD_SIDE`], and beyond it through the sparse
//! path ([`maxwell_calladine_sparse`]: inertia counts of `C^T C - tau I` and `C C^T - tau I` by a
//! sparse `LBL^T` choose the candidates, shift-invert subspace iteration their vectors, and the
//! singular values of `C` on their span decide with the same rule; stoppable). In the dense SVD the vectors of both null
//! spaces are singular vectors of `C` with a row of zeros appended (square, so that its
//! decomposition holds all right vectors; nalgebra's decomposition with vectors is less
//! accurate in its singular values, 1e-5 to 3e-3 seen, so the values come from a decomposition
//! without vectors): the `n - rank` right vectors that `C` maps nearest to zero are the zero
//! modes, and the `n - rank` left ones that `C^T` maps nearest to zero span the self-stresses and
//! the appended row's axis, which is taken out. Eigenvectors of `C^T C` would be cheaper but
//! cannot tell apart singular values below `sqrt(epsilon) sigma_max`: a singular value of 3e-14,
//! just above the rank tolerance, left a "zero mode" with `|C z| = 3e-14`, a mix of the null
//! vector and its neighbour (found by a mirror-symmetry audit; the singular vectors give
//! `|C z| ~ epsilon sigma_max`). The **tensional modes** of a chain are eigenvectors of the
//! tridiagonal `C C^T`.

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::DMatrix;

use super::error::StaticsError;
use super::validate;
use crate::linalg;
use crate::linalg::golub_kahan::{GolubKahan, NullSpaces, REFINED};
use crate::linalg::sparse::null_space;
use crate::model::layout::bidiagonal_parts;
use crate::model::{ChainModel, CompatibilityLayout, SpringNetwork};

/// The outcome of the counting at one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Counting {
    /// Degrees of freedom (the rotors of a chain).
    pub rotors: usize,
    /// Springs (constraints).
    pub springs: usize,
    /// Singular values of `C`, descending: all of them, except on the sparse path
    /// ([`maxwell_calladine_sparse`]), which gives only its candidates': the singular values of
    /// `C` on the span of the eigenvectors of `C^T C` below its threshold, the zero modes' and
    /// any other too small for the Gram matrix to resolve.
    pub singular_values: Vec<f64>,
    /// Singular values at or below this count as zero.
    pub tolerance: f64,
    /// The largest singular value of `C`: the first of `singular_values` on the dense and chain
    /// paths; by power iteration on `C^T C` on the sparse path (approached from below).
    pub largest_singular_value: f64,
    /// Rank of the compatibility matrix.
    pub rank: usize,
    /// Orthonormal basis of the zero modes (rotor displacements `r_i dtheta_i`).
    pub zero_modes: Vec<Vec<f64>>,
    /// Orthonormal basis of the states of self-stress (spring tensions).
    pub self_stresses: Vec<Vec<f64>>,
}

impl Counting {
    /// `N_zero - N_selfstress`, which must equal `n - (n - 1) = 1`.
    pub fn index(&self) -> isize {
        self.zero_modes.len() as isize - self.self_stresses.len() as isize
    }
}

/// A tensional mode: an eigenvector of `C C^T` (spring tensions), with its eigenvalue.
#[derive(Clone, Debug, PartialEq)]
pub struct TensionalMode {
    /// Its eigenvalue.
    pub eigenvalue: f64,
    /// Spring tensions, one per spring.
    pub tensions: Vec<f64>,
}

/// The bands of a chain's `C` at `theta`: `(C[p][p], C[p][p + 1])`.
pub fn compatibility<M: ChainModel + ?Sized>(model: &M, theta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let m = model.spring_count();
    let mut values = vec![0.0; 2 * m];
    model.compatibility_into(theta, &mut values);
    let (left, right) = bidiagonal_parts(m, &values);
    (left.to_vec(), right.to_vec())
}

/// A compatibility matrix by rows, from any layout: each row's `(column, value)` entries,
/// ascending.
struct Rows {
    columns: usize,
    starts: Vec<usize>,
    entries: Vec<(usize, f64)>,
}

impl Rows {
    /// `C` of `model` at `theta`, checked: `theta` one finite value per degree of freedom, every
    /// entry finite (a model whose parameters make a spring of zero length gives NaN), the layout
    /// well formed.
    fn of<M: SpringNetwork + ?Sized>(model: &M, theta: &[f64]) -> Result<Self, StaticsError> {
        validate::angles(model, theta)?;
        let (n, m) = (model.dof_count(), model.spring_count());
        // Sized by the network: allocated fallibly (`LinalgError::OutOfMemory`).
        let what = "the compatibility matrix";
        let oom =
            |e: crate::allocation::AllocationError| StaticsError::from(crate::linalg::LinalgError::from(e));
        let mut values =
            crate::allocation::try_filled(model.compatibility_values(), 0.0, what).map_err(oom)?;
        model.compatibility_into(theta, &mut values);
        validate::finite("the compatibility matrix", &values)?;
        let mut starts = crate::allocation::try_vec(m + 1, what).map_err(oom)?;
        starts.push(0);
        let mut entries = crate::allocation::try_vec(values.len().max(2 * m), what).map_err(oom)?;
        match model.compatibility_layout() {
            CompatibilityLayout::Bidiagonal => {
                let (left, right) = bidiagonal_parts(m, &values);
                for p in 0..m {
                    entries.extend([(p, left[p]), (p + 1, right[p])]);
                    starts.push(entries.len());
                }
            }
            CompatibilityLayout::Sparse(pattern) => {
                pattern.check(false).map_err(crate::linalg::LinalgError::from)?;
                entries.extend(pattern.columns.iter().copied().zip(values.iter().copied()));
                starts.clear();
                starts.extend_from_slice(pattern.row_starts);
            }
        }
        if starts.len() != m + 1 || entries.iter().any(|&(c, _)| c >= n) {
            let what = "the compatibility matrix's rows";
            return Err(StaticsError::WrongLength { what, len: starts.len() - 1, expected: m });
        }
        Ok(Self { columns: n, starts, entries })
    }

    fn rows(&self) -> usize {
        self.starts.len() - 1
    }

    fn row(&self, p: usize) -> &[(usize, f64)] {
        &self.entries[self.starts[p]..self.starts[p + 1]]
    }

    fn to_dense(&self) -> DMatrix<f64> {
        let mut c = DMatrix::zeros(self.rows(), self.columns);
        for p in 0..self.rows() {
            for &(i, v) in self.row(p) {
                c[(p, i)] = v;
            }
        }
        c
    }

    /// `|C v|^2`.
    fn residual(&self, v: &[f64]) -> f64 {
        (0..self.rows()).map(|p| self.row(p).iter().fold(0.0, |s, &(i, c)| s + c * v[i])).map(|x| x * x).sum()
    }

    /// `|C^T u|^2` for `u` with one entry per row (and any more, ignored).
    fn transpose_residual(&self, u: &[f64]) -> f64 {
        let mut out = vec![0.0; self.columns];
        for (p, &up) in u.iter().enumerate().take(self.rows()) {
            for &(i, c) in self.row(p) {
                out[i] += c * up;
            }
        }
        out.iter().map(|x| x * x).sum()
    }
}

/// Maxwell-Calladine counting at `theta`; `tolerance` overrides the numerical-rank rule.
///
/// # Errors
/// `theta` not one finite value per degree of freedom, a compatibility matrix that is not finite
/// or not well formed, a `tolerance` that is not finite and `>= 0`, a null space or a matrix too
/// large, or a failed decomposition (each iteration bounded); beyond [`MAX_DENSE_SVD_SIDE`] those
/// of [`maxwell_calladine_sparse`].
pub fn maxwell_calladine<M: SpringNetwork + ?Sized>(
    model: &M,
    theta: &[f64],
    tolerance: Option<f64>,
) -> Result<Counting, StaticsError> {
    maxwell_calladine_with(model, theta, tolerance, &mut || false)
}

/// The side of the largest compatibility matrix (its rows or columns, whichever are more) that a
/// network's counting decomposes densely: 512; larger ones take the sparse path
/// ([`maxwell_calladine_sparse`]). The SVD with vectors of the padded square matrix
/// cannot be stopped and grows as the cube of the side: 1.5 s at 512, 12 s at 1024 (nalgebra,
/// release build, AMD EPYC Zen 4, one core; `examples/counting_time.rs dense N`). A chain (the
/// bidiagonal layout) has no such bound: its counting takes O(n) per Sturm count.
pub const MAX_DENSE_SVD_SIDE: usize = 512;

/// [`maxwell_calladine`] with a stop question: a chain's counting (the bidiagonal layout) asks it
/// before each singular value's bisection and each null vector's inverse iteration (each O(n))
/// and ends with [`LinalgError::Stopped`](crate::linalg::LinalgError::Stopped) on a yes (Python's
/// Ctrl-C stops `Chain.maxwell_calladine` this way); a network's dense SVD, up to
/// [`MAX_DENSE_SVD_SIDE`], asks it once before it starts; beyond it, the sparse path
/// ([`maxwell_calladine_sparse`]) asks it before each factorization and at each subspace
/// iteration.
///
/// A chain's singular values come from its Golub-Kahan tridiagonal (`linalg/golub_kahan.rs`),
/// each to a few ulps of itself, O(n) per Sturm count and O(n^2) for all of them; its null
/// spaces from inverse iteration there, O(n) per vector.
///
/// # Errors
/// As [`maxwell_calladine`], and `Stopped` when `stop` answered yes.
pub fn maxwell_calladine_with<M: SpringNetwork + ?Sized>(
    model: &M,
    theta: &[f64],
    tolerance: Option<f64>,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Counting, StaticsError> {
    if let Some(t) = tolerance {
        validate::non_negative("tolerance", t)?;
    }
    let (n, m) = (model.dof_count(), model.spring_count());
    if matches!(model.compatibility_layout(), CompatibilityLayout::Bidiagonal) && n == m + 1 {
        validate::angles(model, theta)?;
        let mut values = vec![0.0; 2 * m];
        model.compatibility_into(theta, &mut values);
        validate::finite("the compatibility matrix", &values)?;
        let (left, right) = bidiagonal_parts(m, &values);
        return chain_counting(left, right, tolerance, stop);
    }
    let rows = Rows::of(model, theta)?;
    // The square matrix of the vectors' decomposition holds max(n, m)^2 numbers.
    let side = n.max(m);
    if side > MAX_DENSE_SVD_SIDE {
        return sparse_counting(&rows, tolerance, stop);
    }
    if stop() {
        return Err(crate::linalg::LinalgError::Stopped { what: "SVDs", done: 0, of: 2 }.into());
    }
    // The dense matrices here (C, its padded square and the SVD's) hold at most 512^2 values,
    // 2 MiB each (the side is bounded above), so they are allocated as nalgebra does.
    let c = rows.to_dense();
    // nalgebra's `singular_values()` iterates without a bound; LAPACK's `dbdsqr` allows
    // 6 n^2 sweeps, which is what this gives.
    let budget = 6 * n.max(m) * n.max(m);
    let failed = || StaticsError::NoConvergence {
        method: "SVD of the compatibility matrix",
        iterations: budget,
        residual: f64::NAN,
        tolerance: f64::EPSILON,
    };
    // The singular values alone: nalgebra's SVD of a non-square matrix is accurate only without
    // vectors (with them, 1e-5 off on a 59 x 60 `C` whose values agree to 3e-15 otherwise; the
    // same family as nalgebra issues #983 and #1211). A test compares them with the eigenvalues
    // of the tridiagonal `C C^T`.
    let values = c.clone().try_svd(false, false, f64::EPSILON, budget).ok_or_else(failed)?;
    let mut singular_values: Vec<f64> = values.singular_values.iter().copied().collect();
    singular_values.sort_by(|a, b| b.total_cmp(a));
    let sigma_max = singular_values.first().copied().unwrap_or(0.0);
    let tolerance = tolerance.unwrap_or(n.max(m) as f64 * f64::EPSILON * sigma_max);
    let rank = singular_values.iter().filter(|&&s| s > tolerance).count();
    // The vectors: `C` padded square with rows (or columns) of zeros, whose decomposition holds
    // every right and left vector. On the right, `side - rank` of them span the null space of the
    // padded `C`: the `n - rank` zero modes and, for a network with more springs than degrees of
    // freedom, the padded columns' axes; on the left, the self-stresses `[s; 0]` and the padded
    // rows' axes (a chain's one appended row `e_n`).
    let square = c.resize(side, side, 0.0);
    let full = square.try_svd(true, true, f64::EPSILON, budget).ok_or_else(failed)?;
    let (u, v_t) = (full.u.as_ref().ok_or_else(failed)?, full.v_t.as_ref().ok_or_else(failed)?);
    // Which vectors span the null spaces is read from what `C` does to them (`|C v|`, and
    // `|C^T u|` on the left, whose appended axis `e_n` gives 0), not from the singular values
    // this decomposition pairs them with: with vectors, nalgebra's values can be off (3e-3 seen
    // on the square `C` of a 41-rotor chain, which is why the values above come from the
    // vector-free decomposition).
    // The `side - rank` vectors of each side that the padded matrix maps nearest to zero span
    // the null space and the padded axes (which the residuals, reading only the first `n`
    // columns or `m` rows, map to zero); the axes are then taken out of the span.
    let right_vectors: Vec<Vec<f64>> = (0..side).map(|j| v_t.row(j).iter().copied().collect()).collect();
    let left_vectors: Vec<Vec<f64>> = (0..side).map(|j| u.column(j).iter().copied().collect()).collect();
    let zero_span = least(&right_vectors, side - rank, |v| rows.residual(v));
    let zero_modes = without_last_axes(zero_span, side - n).into_iter().map(oriented).collect();
    let stress_span = least(&left_vectors, side - rank, |u| rows.transpose_residual(u));
    let self_stresses = without_last_axes(stress_span, side - m).into_iter().map(oriented).collect();
    Ok(Counting {
        rotors: n,
        springs: m,
        singular_values,
        tolerance,
        largest_singular_value: sigma_max,
        rank,
        zero_modes,
        self_stresses,
    })
}

/// [`maxwell_calladine_with`] through the sparse path, whatever the size (above
/// [`MAX_DENSE_SVD_SIDE`] the counting takes it anyway), with the dense path's rule: a singular
/// value of `C` counts as zero at or below `tolerance`, by default `max(n, m) eps sigma_max`
/// (`sigma_max` by power iteration on `C^T C`).
///
/// The candidates are the eigenvalues of `C^T C` below
/// `tau = tolerance^2 + 128 max(n, m) eps ||C^T C||_inf`, counted by the inertia of the sparse
/// `LBL^T` of `C^T C - tau I` (Sylvester's law), their vectors by shift-invert block subspace
/// iteration (`linalg/sparse/`). The second term is twice the worst perturbation of an eigenvalue
/// by the Gram matrix's rounding and the factorization's accepted backward error
/// (`linalg::sparse::null_space`), so every singular value at or below the tolerance is a
/// candidate; but the Gram matrix cannot resolve singular values below about `sqrt(tau)`
/// (`5e-6 ||C||` at 1000 rows), so it does not decide. The singular values of `C` on the
/// candidates' span (`C V`, `m x p`, its QR and a `p x p` SVD: accurate to a few `eps ||C||`, where
/// the Gram matrix's are accurate to `sqrt(eps) ||C||`) decide, as the dense SVD's would; the
/// zero modes are the combinations of the candidates they call zero. The self-stresses are the same
/// on `C^T` with the candidates of `C C^T`, and the two counts are checked by the index theorem.
///
/// The stop question is asked at each power iteration, before each of the two factorizations and
/// at every iteration of the subspace iteration.
///
/// # Errors
/// As [`maxwell_calladine_with`]; a failed allocation (`LinalgError::OutOfMemory` with its
/// bytes), and `LinalgError::Missed` when the two counts break the index theorem or the
/// eigenvalues found disagree with the inertia count.
pub fn maxwell_calladine_sparse<M: SpringNetwork + ?Sized>(
    model: &M,
    theta: &[f64],
    tolerance: Option<f64>,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Counting, StaticsError> {
    if let Some(t) = tolerance {
        validate::non_negative("tolerance", t)?;
    }
    sparse_counting(&Rows::of(model, theta)?, tolerance, stop)
}

/// The sparse path of [`maxwell_calladine_sparse`] on `C` by rows.
fn sparse_counting(
    rows: &Rows,
    tolerance: Option<f64>,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Counting, StaticsError> {
    let c = null_space::Rows { columns: rows.columns, starts: &rows.starts, entries: &rows.entries };
    let found = null_space::null_spaces(c, tolerance, stop)?;
    let (n, m) = (rows.columns, rows.rows());
    let mut singular_values = found.right_values;
    singular_values.reverse();
    let rank = n - found.zero_modes.len();
    let zero_modes = found.zero_modes.into_iter().map(oriented).collect();
    let self_stresses = found.self_stresses.into_iter().map(oriented).collect();
    Ok(Counting {
        rotors: n,
        springs: m,
        singular_values,
        tolerance: found.tolerance,
        largest_singular_value: found.sigma_max,
        rank,
        zero_modes,
        self_stresses,
    })
}

/// The counting of a chain's `(n - 1) x n` bidiagonal `C` (`left` its diagonal, `right` its
/// superdiagonal, finite) through its Golub-Kahan tridiagonal.
fn chain_counting(
    left: &[f64],
    right: &[f64],
    tolerance: Option<f64>,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Counting, StaticsError> {
    let m = left.len();
    let n = m + 1;
    let gk = GolubKahan::new(left, right)?;
    let mut singular_values = gk.singular_values(stop)?;
    singular_values.reverse();
    let sigma_max = singular_values.first().copied().unwrap_or(0.0);
    let tolerance = tolerance.unwrap_or(n as f64 * f64::EPSILON * sigma_max);
    let rank = singular_values.iter().filter(|&&s| s > tolerance).count();
    // The singular values within 1e-2 sigma_max of zero: the vectors of B^T B (whose gaps are
    // squares) of values that close would mix with the null vectors, so they are computed with
    // them and separated by a Rayleigh-Ritz step.
    let near_bound = tolerance.max(REFINED * sigma_max);
    let near = singular_values.iter().filter(|&&s| s <= near_bound).count().max(m - rank);
    // The subspaces' vectors: 2 near + 1 of at most n entries.
    let cluster = 2 * near + 1;
    validate::at_most(
        "(2 singular values below 1e-2 sigma_max + 1) x n",
        cluster.saturating_mul(n),
        super::MAX_DENSE_VALUES,
    )?;
    let NullSpaces { right: zero_modes, left: self_stresses } =
        gk.null_spaces(m - rank, near, tolerance, stop)?;
    Ok(Counting {
        rotors: n,
        springs: m,
        singular_values,
        tolerance,
        largest_singular_value: sigma_max,
        rank,
        zero_modes: zero_modes.into_iter().map(oriented).collect(),
        self_stresses: self_stresses.into_iter().map(oriented).collect(),
    })
}

/// [`without_last_axis`] `count` times: the span without its last `count` axes (the padding of
/// the decomposition's square matrix), each vector `count` entries shorter.
fn without_last_axes(mut basis: Vec<Vec<f64>>, count: usize) -> Vec<Vec<f64>> {
    for _ in 0..count {
        basis = without_last_axis(&basis);
    }
    basis
}

/// An orthonormal basis of the vectors of `span(basis)` (orthonormal, each of length `n`, the
/// span holding the last axis `e_n`) that are orthogonal to `e_n`, with that last entry dropped:
/// one vector fewer. The combination along `e_n` is `x = h / |h|`, `h` the basis vectors' last
/// entries; the Householder reflection `H` that takes `x` to a multiple of `e_1` has its other
/// columns orthogonal to `x`, and those combinations of the basis are the answer.
fn without_last_axis(basis: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let q = basis.len();
    if q < 2 {
        return Vec::new();
    }
    let n = basis[0].len();
    let h: Vec<f64> = basis.iter().map(|b| b[n - 1]).collect();
    let size = crate::math::sqrt(h.iter().map(|x| x * x).sum());
    // v = x + sign(x_1) e_1 (no cancellation); H = I - 2 v v^T / (v^T v).
    let mut v: Vec<f64> = if size > 0.0 { h.iter().map(|x| x / size).collect() } else { vec![0.0; q] };
    v[0] += if v[0] < 0.0 { -1.0 } else { 1.0 };
    let vv: f64 = v.iter().map(|x| x * x).sum();
    (1..q)
        .map(|j| {
            // Column j of H, then the combination of the basis, without its last entry.
            let column: Vec<f64> =
                (0..q).map(|k| if k == j { 1.0 } else { 0.0 } - 2.0 * v[k] * v[j] / vv).collect();
            let mut s: Vec<f64> =
                (0..n - 1).map(|i| basis.iter().zip(&column).map(|(b, c)| b[i] * c).sum()).collect();
            let norm = crate::math::sqrt(s.iter().map(|x| x * x).sum());
            s.iter_mut().for_each(|x| *x /= norm);
            s
        })
        .collect()
}

/// The `count` vectors with the smallest `residual`, ascending.
fn least(vectors: &[Vec<f64>], count: usize, residual: impl Fn(&[f64]) -> f64) -> Vec<Vec<f64>> {
    let mut scored: Vec<(f64, &Vec<f64>)> = vectors.iter().map(|v| (residual(v), v)).collect();
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    scored.into_iter().take(count).map(|(_, v)| v.clone()).collect()
}

/// `v` with the sign that makes its largest entry (the first, on a tie) positive: a singular
/// vector's sign is arbitrary, and this gives one answer for one subspace of dimension 1.
fn oriented(mut v: Vec<f64>) -> Vec<f64> {
    let largest = v.iter().copied().fold(0.0f64, |best, x| if x.abs() > best.abs() { x } else { best });
    if largest < 0.0 {
        v.iter_mut().for_each(|x| *x = -*x);
    }
    v
}

/// `C C^T` as a tridiagonal matrix.
fn cct(left: &[f64], right: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let m = left.len();
    let diag = (0..m).map(|p| left[p] * left[p] + right[p] * right[p]).collect();
    let off = (0..m.saturating_sub(1)).map(|p| right[p] * left[p + 1]).collect();
    (diag, off)
}

/// The `count` softest tensional modes at `theta` (eigenvectors of `C C^T`, ascending).
pub fn tensional_modes<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    count: usize,
) -> Result<Vec<TensionalMode>, StaticsError> {
    validate::angles(model, theta)?;
    let (left, right) = compatibility(model, theta);
    validate::finite("the compatibility matrix's diagonal", &left)?;
    validate::finite("the compatibility matrix's superdiagonal", &right)?;
    let (diag, off) = cct(&left, &right);
    Ok(linalg::lowest_eigenpairs(&diag, &off, count.min(left.len()))?
        .into_iter()
        .map(|p| TensionalMode { eigenvalue: p.value, tensions: p.vector })
        .collect())
}
