//! The singular values of a sparse `C` on a subspace, to the dense rule's accuracy: the refinement
//! of [`null_space`](super::null_space)'s candidates.
//!
//! The Gram matrix `C^T C` resolves a singular value `sigma` only down to `sqrt(tau)`, the square
//! root of its rounding (about `5e-6 ||C||` at 1000 rows). Given an orthonormal basis `V` (`n x p`)
//! of the candidates, the eigenvectors of `C^T C` below `tau`, the matrix `C V` (`m x p`) is formed
//! directly from `C`'s entries, so each of its entries is within about `eps ||C||` of the exact
//! product; its Householder QR (`C V = Q R`, backward stable) and the SVD of the small `p x p`
//! factor `R` then give singular values within a few `eps ||C||` of those of `C V`, which are those
//! of `C` on the subspace: a singular value far below `sqrt(tau)` is resolved to the dense SVD's
//! accuracy, not the Gram matrix's. (The subspace itself is that of the Gram matrix: a candidate
//! vector carries components of the next singular vectors of size `eps ||C||^2 / sigma_next^2`,
//! which add about `eps ||C||^2 / sigma_next` to the values; below the dense rule's tolerance while
//! the next singular value above `sqrt(tau)` is more than `||C|| / max(n, m)`.)
//!
//! The dense rule needs `sigma_max = ||C||_2`: `largest_singular_value` estimates it by power
//! iteration on `C^T C` (a lower bound, converged to [`POWER_TOLERANCE`]).

use alloc::vec::Vec;

use nalgebra::DMatrix;

use super::lblt::try_vec;
use super::null_space::Rows;
use crate::linalg::LinalgError;
use crate::math;

/// At most this many power iterations for `sigma_max`: each costs two products with the sparse
/// `C`, so 200 of them cost less than one factorization; the estimate is a lower bound at every
/// step, and the rank rule depends on it only for a singular value within that bound's error of
/// `max(n, m) eps sigma_max`.
pub const POWER_ITERATIONS: usize = 200;

/// The power iteration stops when `||C^T C x||` grows by less than this fraction in one step.
pub const POWER_TOLERANCE: f64 = 1e-6;

/// `sigma_max(C)` by power iteration on `C^T C` from the subspace iteration's fixed pseudo-random
/// start (never orthogonal to the top singular vector by accident, as a constant vector on a
/// lattice is), asking `stop` at each step. `t` is `C^T` by rows.
///
/// # Errors
/// A failed allocation, or `Stopped` when `stop` answered yes.
pub(crate) fn largest_singular_value(
    c: Rows<'_>,
    t: Rows<'_>,
    stop: &mut dyn FnMut() -> bool,
) -> Result<f64, LinalgError> {
    let n = c.columns;
    let mut x = super::eigen::start_block(n, 1)?;
    let mut y = try_vec(c.rows())?;
    y.resize(c.rows(), 0.0);
    let mut z = try_vec(n)?;
    z.resize(n, 0.0);
    let mut lambda = 0.0f64;
    normalise(&mut x);
    for done in 0..POWER_ITERATIONS {
        if stop() {
            return Err(LinalgError::Stopped { what: "power iterations", done, of: POWER_ITERATIONS });
        }
        c.mul_vec(&x, &mut y);
        t.mul_vec(&y, &mut z);
        // ||A x|| for a unit x is a lower bound of A's largest eigenvalue, and at least x^T A x.
        let next = normalise(&mut z);
        core::mem::swap(&mut x, &mut z);
        if next <= lambda * (1.0 + POWER_TOLERANCE) || next == 0.0 {
            lambda = lambda.max(next);
            break;
        }
        lambda = next;
    }
    Ok(math::sqrt(lambda))
}

/// The singular values of `C` on the span of the orthonormal `basis` (each of `c.columns`
/// entries), ascending, and the combinations of the basis that `C` maps to the values at or below
/// `tolerance`: an orthonormal basis of that part of the span.
#[derive(Clone, Debug)]
pub(crate) struct OnSubspace {
    /// The singular values of `C V`, ascending, one per basis vector.
    pub values: Vec<f64>,
    /// The unit vectors `V w` of the values at or below the tolerance.
    pub vectors: Vec<Vec<f64>>,
}

/// [`OnSubspace`] of `c` and `basis`.
///
/// # Errors
/// A failed allocation of `C V` or of the vectors, or an SVD of `R` that did not converge in
/// `6 p^2` sweeps (LAPACK's `dbdsqr` bound).
pub(crate) fn on_subspace(c: Rows<'_>, basis: &[&[f64]], tolerance: f64) -> Result<OnSubspace, LinalgError> {
    let (m, p) = (c.rows(), basis.len());
    if p == 0 {
        return Ok(OnSubspace { values: Vec::new(), vectors: Vec::new() });
    }
    // C V by columns (nalgebra's order), padded with zero rows to at least p so that R is p x p;
    // zero rows add no singular value C V does not have (its rank is at most m).
    let rows = m.max(p);
    let mut cv = try_vec(rows.saturating_mul(p))?;
    cv.resize(rows * p, 0.0);
    for (column, v) in cv.chunks_exact_mut(rows).zip(basis) {
        c.mul_vec(v, &mut column[..m]);
    }
    // The QR works in the moved buffer; R and the SVD's matrices are p x p, at most the p rows
    // of C V just allocated.
    let r = DMatrix::from_vec(rows, p, cv).qr().r();
    let budget = 6 * p * p;
    let failed = || LinalgError::NoConvergence { iterations: budget, index: 0, residual: f64::NAN };
    // The values from the decomposition without vectors (nalgebra's values are less accurate
    // with them: `statics::counting`), the vectors chosen by what R does to them.
    let mut values: Vec<f64> = r
        .clone()
        .try_svd(false, false, f64::EPSILON, budget)
        .ok_or_else(failed)?
        .singular_values
        .iter()
        .copied()
        .collect();
    values.sort_by(f64::total_cmp);
    let zero = values.iter().filter(|&&s| s <= tolerance).count();
    let full = r.clone().try_svd(false, true, f64::EPSILON, budget).ok_or_else(failed)?;
    let v_t = full.v_t.ok_or_else(failed)?;
    let mut scored: Vec<(f64, usize)> = (0..p).map(|j| ((&r * v_t.row(j).transpose()).norm(), j)).collect();
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = c.columns;
    let mut vectors = try_vec(zero)?;
    for &(_, j) in &scored[..zero] {
        let mut v = try_vec(n)?;
        v.resize(n, 0.0);
        for (b, &w) in basis.iter().zip(v_t.row(j).iter()) {
            v.iter_mut().zip(b.iter()).for_each(|(v, b)| *v += w * b);
        }
        normalise(&mut v);
        vectors.push(v);
    }
    Ok(OnSubspace { values, vectors })
}

/// Scales `v` to unit length and returns its length (unchanged when 0).
fn normalise(v: &mut [f64]) -> f64 {
    let norm = math::sqrt(v.iter().map(|x| x * x).sum::<f64>());
    if norm > 0.0 {
        v.iter_mut().for_each(|x| *x /= norm);
    }
    norm
}
