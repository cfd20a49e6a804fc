//! Solving `(T - sigma I) x = b` for a symmetric tridiagonal `T`, positive definite or not, by
//! Gaussian elimination with partial pivoting: LAPACK's `dgtsv`, split into its factorisation
//! `dgttrf` and solve `dgttrs` so that inverse iteration can reuse the factors (Golub & Van Loan,
//! *Matrix Computations*, 4th ed., Sec. 4.3, banded Gaussian elimination with partial pivoting;
//! Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., Ch. 9).
//!
//! `P (T - sigma I) = L U` with `L` unit lower bidiagonal (multipliers at most 1 in magnitude)
//! and `U` upper triangular with two superdiagonals (the second one filled in by row
//! interchanges). The growth factor is at most 2 here, so the solve is backward stable whatever
//! the inertia, unlike `L D L^T` without pivoting, which fails on zero and tiny pivots.
//!
//! Cost: O(n): about `8n` flops to factor and `7n` to solve.

use alloc::vec::Vec;

use super::bands::{self, Scaled};
use super::error::{Input, LinalgError};

/// Solves `T x = b` for the symmetric tridiagonal `T` = (`diag`, `off`) by Gaussian elimination
/// with partial pivoting. O(n).
///
/// Fails with [`LinalgError::Singular`] if a pivot is exactly zero or the solution overflows.
pub fn solve(diag: &[f64], off: &[f64], rhs: &[f64]) -> Result<Vec<f64>, LinalgError> {
    solve_shifted(diag, off, 0.0, rhs)
}

/// Solves `(T - shift I) x = b` for the symmetric tridiagonal `T` = (`diag`, `off`). O(n).
pub fn solve_shifted(diag: &[f64], off: &[f64], shift: f64, rhs: &[f64]) -> Result<Vec<f64>, LinalgError> {
    bands::check_bands(diag, off)?;
    bands::check_finite(Input::Shift, &[shift])?;
    if rhs.len() != diag.len() {
        return Err(LinalgError::RhsMismatch { n: diag.len(), rhs: rhs.len() });
    }
    bands::check_finite(Input::Rhs, rhs)?;
    // Scaling by a power of two (exact) keeps `d_i - shift` and the fill-in finite.
    let scaled = Scaled::new(diag, off, shift);
    let lu = TridiagonalLu::factor(&scaled.diag, &scaled.off, scaled.shift);
    let singular = |lu: &TridiagonalLu| {
        let (row, pivot) = lu.smallest_pivot();
        LinalgError::Singular { row, pivot: pivot / scaled.scale }
    };
    if lu.u0.contains(&0.0) {
        return Err(singular(&lu));
    }
    let mut x = rhs.to_vec();
    lu.solve_in_place(&mut x);
    // (sT - s shift) y = b  <=>  (T - shift) (s y) = b.
    x.iter_mut().for_each(|v| *v *= scaled.scale);
    if x.iter().any(|v| !v.is_finite()) {
        return Err(singular(&lu));
    }
    Ok(x)
}

/// The factors `P (T - shift I) = L U` of a symmetric tridiagonal `T` (LAPACK `dgttrf`).
pub(crate) struct TridiagonalLu {
    /// The diagonal of `U` (the pivots).
    pub u0: Vec<f64>,
    /// The first superdiagonal of `U`.
    u1: Vec<f64>,
    /// The second superdiagonal of `U`: fill-in where rows were interchanged.
    u2: Vec<f64>,
    /// The multipliers: `l[i]` eliminates row `i + 1` (after any interchange) with row `i`.
    l: Vec<f64>,
    /// Whether rows `i` and `i + 1` were interchanged at step `i`.
    swapped: Vec<bool>,
}

impl TridiagonalLu {
    /// Expects `off.len() + 1 == diag.len()` (or both empty).
    pub fn factor(diag: &[f64], off: &[f64], shift: f64) -> Self {
        let n = diag.len();
        let mut u0: Vec<f64> = diag.iter().map(|d| d - shift).collect();
        let mut u1 = off.to_vec();
        let mut u2 = alloc::vec![0.0; n.saturating_sub(2)];
        let mut l = off.to_vec();
        let mut swapped = alloc::vec![false; n.saturating_sub(1)];
        for i in 0..n.saturating_sub(1) {
            // Row i is [.. u0[i] u1[i] 0], row i + 1 is [.. l[i] (= sub-diagonal) u0[i+1] u1[i+1]].
            let sub = l[i];
            if u0[i].abs() >= sub.abs() {
                // A zero column (u0[i] = sub = 0) needs no elimination: l[i] stays 0.
                if u0[i] != 0.0 {
                    let fact = sub / u0[i];
                    l[i] = fact;
                    u0[i + 1] -= fact * u1[i];
                }
            } else {
                let fact = u0[i] / sub;
                u0[i] = sub;
                l[i] = fact;
                let above = u1[i];
                u1[i] = u0[i + 1];
                u0[i + 1] = above - fact * u0[i + 1];
                if i + 2 < n {
                    u2[i] = u1[i + 1];
                    u1[i + 1] *= -fact;
                }
                swapped[i] = true;
            }
        }
        Self { u0, u1, u2, l, swapped }
    }

    /// The pivot of least magnitude and its row (`(0, 0.0)` for an empty matrix).
    pub fn smallest_pivot(&self) -> (usize, f64) {
        self.u0
            .iter()
            .copied()
            .enumerate()
            .fold((0, 0.0), |best, (i, p)| if i == 0 || p.abs() < best.1.abs() { (i, p) } else { best })
    }

    /// Replaces pivots smaller in magnitude than `tiny` by `+-tiny` (an exact zero by `+tiny`):
    /// inverse iteration solves with `T - lambda I` at an eigenvalue, which is singular to
    /// working precision, and a perturbation of `U` of size `tiny` changes only the scaling of
    /// the (huge) solution, not its direction (Parlett Sec. 4.3; LAPACK `dlagts`, `job = -1`).
    pub fn perturb_small_pivots(&mut self, tiny: f64) {
        for p in &mut self.u0 {
            if p.abs() < tiny {
                *p = if *p < 0.0 { -tiny } else { tiny };
            }
        }
    }

    /// Overwrites `b` with `(L U)^{-1} P b`, the solution (LAPACK `dgttrs`). Zero pivots give
    /// infinities, which the callers check for.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let n = self.u0.len();
        for i in 0..n.saturating_sub(1) {
            if self.swapped[i] {
                let above = b[i];
                b[i] = b[i + 1];
                b[i + 1] = above - self.l[i] * b[i];
            } else {
                b[i + 1] -= self.l[i] * b[i];
            }
        }
        for i in (0..n).rev() {
            let mut v = b[i];
            if i + 1 < n {
                v -= self.u1[i] * b[i + 1];
            }
            if i + 2 < n {
                v -= self.u2[i] * b[i + 2];
            }
            b[i] = v / self.u0[i];
        }
    }
}
