//! Eigenvalues by bisection on Sturm counts: the `k`-th smallest eigenvalue `lambda_k` is the
//! point where the count of eigenvalues below `x` ([`count_below`](super::count_below)) steps
//! from `k` to `k + 1`.
//!
//! Each eigenvalue's interval starts as the Gershgorin interval and shrinks until its width is
//! `max(eps ||T||, 2 eps |lambda|)`, as in LAPACK's `dstebz` with its default tolerance. Each
//! pass counts at the three quarter points at once, which costs about one count and quarters
//! the interval: about 27 passes per eigenvalue, each O(n). A count also narrows the intervals
//! of the other wanted eigenvalues, so eigenvalues close together share their first passes
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., Sec. 8.4; Parlett, *The Symmetric
//! Eigenvalue Problem*, Ch. 3; Kahan, *Accurate eigenvalues of a symmetric tri-diagonal
//! matrix*, Stanford CS report 41, 1966). The result has an absolute error of a few
//! `eps ||T||`, whatever the gaps.
//!
//! Cost: O(n) per pass, at most about `27 (hi - lo)` passes, so O(n (hi - lo)).

use alloc::vec;
use alloc::vec::Vec;

use super::bands;
use super::error::LinalgError;
use super::sturm::Sturm;

/// Eigenvalues `lo..hi` (0-based, ascending: `lo = 0` is the smallest) of the symmetric
/// tridiagonal matrix (`diag`, `off`), by bisection, each to a few `eps ||T||`. O(n (hi - lo)).
pub fn eigenvalues_in_index_range(
    diag: &[f64],
    off: &[f64],
    lo: usize,
    hi: usize,
) -> Result<Vec<f64>, LinalgError> {
    bands::check_bands(diag, off)?;
    bands::check_range(lo, hi, diag.len())?;
    let sturm = Sturm::new(diag, off);
    let values = bisect(&sturm, lo, hi, Accuracy::Absolute, &mut || false)?;
    Ok(values.into_iter().map(|x| x / sturm.matrix.scale).collect())
}

/// How far [`bisect`] narrows each eigenvalue's interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Accuracy {
    /// To a few `eps ||T||` (`dstebz`'s default): what the entries of any symmetric tridiagonal
    /// matrix determine.
    Absolute,
    /// To a few `eps |lambda|`, down to the pivot floor `pivmin`: for a matrix whose entries
    /// determine its eigenvalues to relative accuracy, such as the Golub-Kahan matrix of a
    /// bidiagonal (zero diagonal: a count in floating point is exact for off-diagonal entries
    /// perturbed by a few ulps each, which moves every singular value by a few ulps of itself;
    /// Demmel & Kahan, *SIAM J. Sci. Stat. Comput.* 11, 1990, Sec. 5).
    Relative,
}

/// Eigenvalues `lo..hi` of the scaled matrix held by `sturm`, ascending, to `accuracy`. `stop`
/// is asked before each eigenvalue's refinement: a yes ends the bisection with
/// [`LinalgError::Stopped`].
pub(crate) fn bisect(
    sturm: &Sturm,
    lo: usize,
    hi: usize,
    accuracy: Accuracy,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<f64>, LinalgError> {
    let (bottom, top) = sturm.bounds;
    let abstol = match accuracy {
        Accuracy::Absolute => (f64::EPSILON * bottom.abs().max(top.abs())).max(sturm.pivmin),
        Accuracy::Relative => sturm.pivmin,
    };
    let m = hi - lo;
    // left[t] <= lambda_{lo + t} < right[t]: count(left) <= lo + t < count(right).
    let mut left = vec![bottom; m];
    let mut right = vec![top; m];
    for t in 0..m {
        if stop() {
            return Err(LinalgError::Stopped { what: "eigenvalues", done: t, of: m });
        }
        loop {
            let (a, b) = (left[t], right[t]);
            let mid = 0.5 * (a + b);
            if b - a <= abstol.max(2.0 * f64::EPSILON * a.abs().max(b.abs())) || mid <= a || mid >= b {
                break;
            }
            // Three points in one pass (Sturm::counts) quarter the interval for the price of
            // about one count. `count` eigenvalues lie below a point x: those of index < count
            // are below it, the others above. Intervals of eigenvalues already found stay.
            let quarter = 0.25 * (b - a);
            let points = [a + quarter, mid, b - quarter];
            for (x, count) in points.into_iter().zip(sturm.counts(points)) {
                let split = count.saturating_sub(lo).clamp(t, m);
                right[t..split].iter_mut().for_each(|r| *r = r.min(x));
                left[split..].iter_mut().for_each(|l| *l = l.max(x));
            }
        }
    }
    Ok(left.iter().zip(&right).map(|(a, b)| 0.5 * (a + b)).collect())
}
