//! Sturm counts: the number of eigenvalues of a symmetric tridiagonal `T` below `x`, from the
//! inertia of `T - x I = L D L^T` (Sylvester's law of inertia).
//!
//! The pivots obey `q_0 = d_0 - x`, `q_j = d_j - e_{j-1}^2 / q_{j-1} - x`, and the count is the
//! number of negative `q_j` (Golub & Van Loan, *Matrix Computations*, 4th ed., Sec. 8.4;
//! Parlett, *The Symmetric Eigenvalue Problem*, Ch. 3). A pivot smaller in magnitude than
//! `pivmin = safe_min * max(1, max e_j^2)` is replaced by `+-pivmin`, as in LAPACK's `dstebz`,
//! so no division overflows and no NaN appears; an exactly zero pivot becomes `+pivmin` (as if
//! `x` were a hair smaller), so an eigenvalue equal to `x` is not counted. In floating point the
//! count is exact for a matrix whose entries differ from `T`'s by a few ulps (Kahan), and in
//! this form, in IEEE arithmetic, it is monotone in `x` (Demmel, Dhillon & Ren, *ETNA* 3, 1995),
//! which is what bisection needs.
//!
//! Cost: O(n), one division per row. The division's latency sets the speed, so bisection counts
//! at several points in one pass (`Sturm::counts`), their recurrences overlapping.

use alloc::vec::Vec;
use core::iter;

use super::bands::{self, Scaled};

/// The number of eigenvalues of the symmetric tridiagonal matrix (`diag`, `off`) strictly below
/// `x`: with `x = 0` the Morse index. O(n), without allocating.
///
/// The count does not check its input, so it never fails: if `off` does not have
/// `diag.len() - 1` entries the matrix is read as the leading block both bands describe, and a
/// non-finite entry or `x` makes the count meaningless (check with [`try_count_below`] where
/// input may be bad).
pub fn count_below(diag: &[f64], off: &[f64], x: f64) -> usize {
    let n = diag.len().min(off.len() + 1);
    let (diag, off) = (&diag[..n], &off[..n.saturating_sub(1)]);
    let largest_off = off.iter().fold(0.0, |m: f64, e| m.max(e.abs()));
    let s = bands::power_of_two_scale(diag.iter().fold(largest_off, |m, d| m.max(d.abs())));
    let rows = diag.iter().zip(iter::once(&0.0).chain(off)).map(|(&d, &e)| (d * s, (e * s) * (e * s)));
    counts(rows, [x * s], pivmin(largest_off * s))[0]
}

/// [`count_below`] with its input checked: lengths, and finite entries and `x`.
pub fn try_count_below(diag: &[f64], off: &[f64], x: f64) -> Result<usize, super::LinalgError> {
    bands::check_bands(diag, off)?;
    bands::check_finite(super::Input::Shift, &[x])?;
    Ok(count_below(diag, off, x))
}

/// A matrix prepared for many Sturm counts: scaled, with the squared off-diagonal.
pub(crate) struct Sturm {
    /// The scaled matrix: counts take scaled points.
    pub matrix: Scaled,
    /// `e_{j-1}^2` for row `j`, and `0` for row 0.
    off_squared: Vec<f64>,
    /// The smallest pivot magnitude a count lets through.
    pub pivmin: f64,
    /// The Gershgorin interval of the scaled matrix, widened by the rounding of a count.
    pub bounds: (f64, f64),
}

impl Sturm {
    /// Expects finite entries and `off.len() + 1 == diag.len()` (or both empty).
    pub fn new(diag: &[f64], off: &[f64]) -> Self {
        let matrix = Scaled::new(diag, off, 0.0);
        let off_squared: Vec<f64> = iter::once(0.0).chain(matrix.off.iter().map(|e| e * e)).collect();
        let pivmin = pivmin(matrix.off.iter().fold(0.0, |m: f64, e| m.max(e.abs())));
        let (lo, hi) = matrix.gershgorin();
        // dstebz's widening: a count at the exact Gershgorin bound may be off by rounding.
        let norm = lo.abs().max(hi.abs());
        let fudge = 2.1 * (f64::EPSILON * norm * diag.len() as f64 + 2.0 * pivmin);
        Self { matrix, off_squared, pivmin, bounds: (lo - fudge, hi + fudge) }
    }

    /// The number of eigenvalues of the scaled matrix strictly below the scaled point `x`.
    pub fn count(&self, x: f64) -> usize {
        self.counts([x])[0]
    }

    /// [`Sturm::count`] at `K` points in one pass.
    pub fn counts<const K: usize>(&self, xs: [f64; K]) -> [usize; K] {
        let rows = self.matrix.diag.iter().copied().zip(self.off_squared.iter().copied());
        counts(rows, xs, self.pivmin)
    }
}

/// `safe_min * max(1, max e_j^2)`: no `e_j^2 / q` with `|q| >= pivmin` overflows.
fn pivmin(largest_off: f64) -> f64 {
    f64::MIN_POSITIVE * (largest_off * largest_off).max(1.0)
}

/// The Sturm counts at the points `xs`, from the rows `(d_j, e_{j-1}^2)` (`e_{-1} = 0`). The `K`
/// recurrences are independent, so their divisions overlap in the pipeline: a pass with a few
/// points costs little more than a pass with one, whose speed the division's latency sets.
fn counts<const K: usize>(rows: impl Iterator<Item = (f64, f64)>, xs: [f64; K], pivmin: f64) -> [usize; K] {
    let mut q = [1.0; K];
    let mut count = [0; K];
    for (d, e2) in rows {
        for k in 0..K {
            let mut p = d - e2 / q[k] - xs[k];
            if p.abs() < pivmin {
                p = if p < 0.0 { -pivmin } else { pivmin };
            }
            count[k] += usize::from(p < 0.0);
            q[k] = p;
        }
    }
    count
}
