//! All eigenvalues, and if wanted all eigenvectors, by the implicit QL iteration with
//! Wilkinson shifts (Golub & Van Loan, *Matrix Computations*, 4th ed., Sec. 8.3, Algorithm
//! 8.3.2 in its QL form; Parlett, *The Symmetric Eigenvalue Problem*, Ch. 8; Bowdler, Martin,
//! Reinsch & Wilkinson, *Numer. Math.* 11, 1968, EISPACK's `tql2`, LAPACK's `dsteqr`, and
//! *Numerical Recipes*' `tqli`, whose loop this follows).
//!
//! Each sweep applies `T <- Q^T T Q` for the QL factorisation `T - mu I = Q L`, chasing the bulge
//! from the bottom of an unreduced block up to its top by Givens rotations, without forming
//! `T - mu I`. The shift `mu` is the eigenvalue of the top 2x2 block nearer `d_l` (Wilkinson's),
//! so the top off-diagonal entry goes to zero cubically in practice and the iteration converges
//! for every symmetric tridiagonal matrix. An off-diagonal entry with
//! `|e_m| <= eps (|d_m| + |d_{m+1}|)` is set to zero, splitting the matrix. The result is
//! backward stable: each eigenvalue is exact for a matrix within a few `eps ||T||` of `T`.
//!
//! Cost: about 2 sweeps per eigenvalue, each O(n): O(n^2) for the eigenvalues alone (`n` square
//! roots per sweep), plus `6n` flops per rotation, so O(n^3) (about `3 n^3`), to accumulate the
//! eigenvectors (applied in cache-sized batches, see `Rotations`). An iteration budget of `30 n`
//! sweeps (LAPACK's) guards against the unforeseen.

use alloc::vec::Vec;

use nalgebra::DMatrix;

use super::bands::{self, Scaled};
use super::bisection::eigenvalues_in_index_range;
use super::error::LinalgError;
use crate::allocation::{try_filled, try_vec};

/// All eigenvalues of the symmetric tridiagonal matrix (`diag`, `off`), ascending, by the implicit
/// QL iteration. O(n^2).
pub fn eigenvalues_ql(diag: &[f64], off: &[f64]) -> Result<Vec<f64>, LinalgError> {
    eigenvalues_ql_with(diag, off, &mut || false)
}

/// [`eigenvalues_ql`] with a stop question, asked at every QL iteration (O(n) each).
pub(crate) fn eigenvalues_ql_with(
    diag: &[f64],
    off: &[f64],
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<f64>, LinalgError> {
    bands::check_bands(diag, off)?;
    let (mut d, mut e, scale) = prepare(diag, off);
    implicit_ql(&mut d, &mut e, None, scale, stop)?;
    let mut values: Vec<f64> = d.iter().map(|x| x / scale).collect();
    values.sort_by(f64::total_cmp);
    Ok(values)
}

/// All eigenvalues, ascending: the implicit QL iteration, falling back to bisection should QL
/// ever exhaust its iteration budget. O(n^2).
pub fn eigenvalues(diag: &[f64], off: &[f64]) -> Result<Vec<f64>, LinalgError> {
    match eigenvalues_ql(diag, off) {
        Err(LinalgError::NoConvergence { .. }) => eigenvalues_in_index_range(diag, off, 0, diag.len()),
        result => result,
    }
}

/// All eigenvalues, ascending, and the orthonormal eigenvectors as the columns of a matrix in
/// the same order, by the implicit QL iteration with the rotations accumulated. Each vector has
/// its entry of largest magnitude positive. O(n^3) time and O(n^2) memory: for `n` up to a few
/// thousand; for a few eigenpairs of a long chain use
/// [`lowest_eigenpairs`](super::lowest_eigenpairs).
pub fn eigenpairs(diag: &[f64], off: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>), LinalgError> {
    eigenpairs_with(diag, off, &mut || false)
}

/// [`eigenpairs`] with a stop question, asked at every QL iteration (O(n^2) each with the
/// vectors): a yes ends the call with [`LinalgError::Stopped`]. The two `n x n` matrices (the
/// rotations and the sorted vectors) are allocated fallibly before the iteration:
/// [`LinalgError::OutOfMemory`] with the bytes of one of them.
pub fn eigenpairs_with(
    diag: &[f64],
    off: &[f64],
    stop: &mut dyn FnMut() -> bool,
) -> Result<(Vec<f64>, DMatrix<f64>), LinalgError> {
    bands::check_bands(diag, off)?;
    let n = diag.len();
    let (mut d, mut e, scale) = prepare(diag, off);
    let what = "the eigenvectors";
    let mut z = DMatrix::from_vec(n, n, try_filled(n.saturating_mul(n), 0.0, what)?);
    z.fill_diagonal(1.0);
    let mut sorted = try_vec(n.saturating_mul(n), what)?;
    let mut rotations = Rotations::new(z.as_mut_slice(), n);
    implicit_ql(&mut d, &mut e, Some(&mut rotations), scale, stop)?;
    rotations.apply();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| d[i].total_cmp(&d[j]));
    let values = order.iter().map(|&i| d[i] / scale).collect();
    for &col in &order {
        sorted.extend_from_slice(&z.as_slice()[col * n..(col + 1) * n]);
    }
    drop(z);
    let mut vectors = DMatrix::from_vec(n, n, sorted);
    // n = 0 has no columns (and chunks_exact_mut refuses a zero length).
    for column in vectors.as_mut_slice().chunks_exact_mut(n.max(1)) {
        bands::orient(column);
    }
    Ok((values, vectors))
}

/// The scaled diagonal, the scaled off-diagonal padded with a zero to length `n`, and the scale.
fn prepare(diag: &[f64], off: &[f64]) -> (Vec<f64>, Vec<f64>, f64) {
    let Scaled { diag, mut off, scale, .. } = Scaled::new(diag, off, 0.0);
    off.push(0.0);
    (diag, off, scale)
}

/// Below this an off-diagonal entry of the scaled matrix (largest entry in `[1, 2)`) is zero,
/// whatever the diagonal: it keeps the shift's `(d_{l+1} - d_l) / 2 e_l` finite.
const TINY: f64 = f64::MIN_POSITIVE / f64::EPSILON;

/// Diagonalises the scaled tridiagonal matrix in place: `d` becomes the eigenvalues (unsorted),
/// `e` (length `n`, `e[i]` coupling rows `i` and `i + 1`, `e[n - 1] = 0`) is destroyed, and the
/// rotations are recorded in `rotations`, if given. `stop` is asked before every iteration.
fn implicit_ql(
    d: &mut [f64],
    e: &mut [f64],
    mut rotations: Option<&mut Rotations<'_>>,
    scale: f64,
    stop: &mut dyn FnMut() -> bool,
) -> Result<(), LinalgError> {
    let n = d.len();
    let budget = 30 * n;
    let mut iterations = 0;
    for l in 0..n {
        loop {
            // The unreduced block l..=m ends at the first negligible e[m].
            let mut m = l;
            while m + 1 < n {
                let magnitude = e[m].abs();
                if magnitude <= f64::EPSILON * (d[m].abs() + d[m + 1].abs()) || magnitude <= TINY {
                    break;
                }
                m += 1;
            }
            if m == l {
                break;
            }
            if iterations == budget {
                return Err(LinalgError::NoConvergence {
                    iterations,
                    index: l,
                    residual: e[l].abs() / scale,
                });
            }
            if stop() {
                return Err(LinalgError::Stopped { what: "eigenvalues", done: l, of: n });
            }
            iterations += 1;
            // The Wilkinson shift mu, entering as g = d_m - mu.
            let mut g = (d[l + 1] - d[l]) / (2.0 * e[l]);
            let mut r = bands::hypot(g, 1.0);
            g = d[m] - d[l] + e[l] / (g + if g >= 0.0 { r } else { -r });
            let (mut s, mut c, mut p) = (1.0, 1.0, 0.0);
            let mut underflow = false;
            for i in (l..m).rev() {
                let f = s * e[i];
                let b = c * e[i];
                r = bands::hypot(f, g);
                e[i + 1] = r;
                if r == 0.0 {
                    // The bulge underflowed: undo the last partial update and sweep again.
                    d[i + 1] -= p;
                    e[m] = 0.0;
                    underflow = true;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - p;
                r = (d[i] - g) * s + 2.0 * c * b;
                p = s * r;
                d[i + 1] = g + p;
                g = c * r - b;
                if let Some(rotations) = rotations.as_deref_mut() {
                    rotations.push(i, c, s);
                }
            }
            if !underflow {
                d[l] -= p;
                e[l] = g;
                e[m] = 0.0;
            }
        }
    }
    Ok(())
}

/// The rotations of the iteration, to be applied to the columns of the eigenvector matrix.
///
/// Applied one by one, they would stream the whole `n x n` matrix through the cache once per
/// sweep, and for `n` in the thousands memory, not arithmetic, would set the speed. They do not
/// feed back into the iteration, so they are kept in batches, and each batch is applied to a few
/// rows at a time, which stay in cache for the whole batch (the idea of LAPACK's `dlasr` and of
/// Van Zee, van de Geijn & Quintana-Orti, *ACM TOMS* 40, 2014).
struct Rotations<'a> {
    /// The column-major `n x n` eigenvector matrix.
    z: &'a mut [f64],
    n: usize,
    /// `(i, c, s)`: columns `i` and `i + 1` become `c z_i - s z_{i+1}` and `s z_i + c z_{i+1}`.
    pending: Vec<(usize, f64, f64)>,
}

impl<'a> Rotations<'a> {
    /// Rotations per batch (384 KiB of them).
    const BATCH: usize = 1 << 14;
    /// Rows per block: 2 KiB of each column, long enough to hide the per-rotation overhead; a
    /// block of a matrix of a few thousand columns then stays in the outer caches.
    const ROWS: usize = 256;

    fn new(z: &'a mut [f64], n: usize) -> Self {
        Self { z, n, pending: Vec::with_capacity(Self::BATCH) }
    }

    fn push(&mut self, i: usize, c: f64, s: f64) {
        self.pending.push((i, c, s));
        if self.pending.len() == Self::BATCH {
            self.apply();
        }
    }

    /// Applies the pending rotations, in order, one block of rows at a time.
    fn apply(&mut self) {
        let n = self.n;
        for start in (0..n).step_by(Self::ROWS) {
            let rows = start..(start + Self::ROWS).min(n);
            for &(i, c, s) in &self.pending {
                let (head, tail) = self.z.split_at_mut((i + 1) * n);
                let left = &mut head[i * n..][rows.clone()];
                let right = &mut tail[rows.clone()];
                for (zi, zj) in left.iter_mut().zip(right) {
                    let f = *zj;
                    *zj = s * *zi + c * f;
                    *zi = c * *zi - s * f;
                }
            }
        }
        self.pending.clear();
    }
}
