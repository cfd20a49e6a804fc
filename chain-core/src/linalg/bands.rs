//! What every algorithm of this module shares: checking the two bands, exact power-of-two
//! scaling, the norm and the Gershgorin interval, and a few vector helpers.
//!
//! The algorithms run on the matrix scaled by a power of two `s` that brings its largest entry
//! into `[1, 2)`. Such a scaling is exact (only entries below `2^-1022 s^-1` lose bits), and it
//! keeps squares of entries (Sturm counts), rotations (QL) and pivots (elimination) far from
//! overflow and underflow whatever the units of the stiffness.

use alloc::vec::Vec;

use super::error::{Input, LinalgError};
use crate::math;

/// Checks that `off` has `diag.len() - 1` entries (none for an empty or 1x1 matrix) and that
/// every entry is finite.
pub(crate) fn check_bands(diag: &[f64], off: &[f64]) -> Result<(), LinalgError> {
    if off.len() != diag.len().saturating_sub(1) {
        return Err(LinalgError::DimensionMismatch { diag: diag.len(), off: off.len() });
    }
    check_finite(Input::Diag, diag)?;
    check_finite(Input::Off, off)
}

/// The first non-finite entry of `values`, as an error.
pub(crate) fn check_finite(input: Input, values: &[f64]) -> Result<(), LinalgError> {
    // A branch-free pass first (it vectorises; the checks run on every count and solve of the
    // analyses' inner loops), the search for the culprit only when there is one.
    if values.iter().fold(true, |ok, v| ok & v.is_finite()) {
        return Ok(());
    }
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(LinalgError::NotFinite { input, index, value: values[index] }),
        None => Ok(()),
    }
}

/// Checks that `lo..hi` is a range of eigenvalue indices of an `n x n` matrix.
pub(crate) fn check_range(lo: usize, hi: usize, n: usize) -> Result<(), LinalgError> {
    if lo > hi || hi > n { Err(LinalgError::IndexOutOfRange { lo, hi, n }) } else { Ok(()) }
}

/// `s T` (and `s shift`), for the power of two `s` that brings the largest of `|T_ij|` and
/// `|shift|` into `[1, 2)`.
pub(crate) struct Scaled {
    pub diag: Vec<f64>,
    pub off: Vec<f64>,
    pub shift: f64,
    pub scale: f64,
}

impl Scaled {
    /// Expects finite entries (see [`check_bands`]).
    pub fn new(diag: &[f64], off: &[f64], shift: f64) -> Self {
        let largest = diag.iter().chain(off).fold(shift.abs(), |m, x| m.max(x.abs()));
        let scale = power_of_two_scale(largest);
        Self {
            diag: diag.iter().map(|x| x * scale).collect(),
            off: off.iter().map(|x| x * scale).collect(),
            shift: shift * scale,
            scale,
        }
    }

    /// `||sT||_1 = ||sT||_inf`, the largest absolute row sum: a bound on every eigenvalue.
    pub fn norm(&self) -> f64 {
        (0..self.diag.len()).map(|i| self.diag[i].abs() + self.radius(i)).fold(0.0, f64::max)
    }

    /// The Gershgorin interval of `sT`: it holds every eigenvalue (`(0, 0)` if there are none).
    pub fn gershgorin(&self) -> (f64, f64) {
        if self.diag.is_empty() {
            return (0.0, 0.0);
        }
        (0..self.diag.len()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
            let r = self.radius(i);
            (lo.min(self.diag[i] - r), hi.max(self.diag[i] + r))
        })
    }

    /// `||(sT - lambda I) v||_2` for a unit vector `v` (whose residual cannot overflow).
    pub fn residual(&self, lambda: f64, v: &[f64]) -> f64 {
        let n = self.diag.len();
        let mut sum = 0.0;
        for i in 0..n {
            let mut r = (self.diag[i] - lambda) * v[i];
            if i > 0 {
                r += self.off[i - 1] * v[i - 1];
            }
            if i + 1 < n {
                r += self.off[i] * v[i + 1];
            }
            sum += r * r;
        }
        math::sqrt(sum)
    }

    fn radius(&self, i: usize) -> f64 {
        let left = if i > 0 { self.off[i - 1].abs() } else { 0.0 };
        left + self.off.get(i).map_or(0.0, |o| o.abs())
    }
}

/// The power of two `2^k` with `largest * 2^k` in `[1, 2)` (`1` for `largest = 0`), `k` kept
/// within the normal exponents.
pub(crate) fn power_of_two_scale(largest: f64) -> f64 {
    if largest == 0.0 {
        return 1.0;
    }
    let biased = ((largest.to_bits() >> 52) & 0x7ff) as i32;
    // Subnormal numbers have biased exponent 0 and lie below 2^-1022.
    let exponent = if biased == 0 { -1022 } else { biased - 1023 };
    let k = (-exponent).clamp(-1022, 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `sqrt(a^2 + b^2)` without overflow or harmful underflow.
pub(crate) fn hypot(a: f64, b: f64) -> f64 {
    let (a, b) = (a.abs(), b.abs());
    let (big, small) = if a >= b { (a, b) } else { (b, a) };
    if big == 0.0 {
        return 0.0;
    }
    let r = small / big;
    big * math::sqrt(1.0 + r * r)
}

/// `||v||_2`, scaled by the largest entry so that it neither overflows nor underflows.
pub(crate) fn norm2(v: &[f64]) -> f64 {
    let big = v.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
    if big == 0.0 || !big.is_finite() {
        return big;
    }
    big * math::sqrt(v.iter().map(|x| (x / big) * (x / big)).sum::<f64>())
}

/// Scales `v` to unit 2-norm and returns the norm it had (zero or non-finite: `v` untouched).
pub(crate) fn normalize(v: &mut [f64]) -> f64 {
    let norm = norm2(v);
    if norm > 0.0 && norm.is_finite() {
        v.iter_mut().for_each(|x| *x /= norm);
    }
    norm
}

/// Flips `v` so that its entry of largest magnitude (the first, on ties) is positive, as
/// LAPACK's `dstein` does: eigenvectors come out the same from run to run and method to method.
pub(crate) fn orient(v: &mut [f64]) {
    let largest =
        v.iter().enumerate().fold((0, 0.0), |(j, m), (i, x)| if x.abs() > m { (i, x.abs()) } else { (j, m) });
    if v.get(largest.0).is_some_and(|&x| x < 0.0) {
        v.iter_mut().for_each(|x| *x = -*x);
    }
}

/// `a . b`.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_is_by_an_exact_power_of_two() {
        for largest in [1.0, 1.5, 3.0, 1e-300, 1e300, f64::MAX, 5e-324, 1e-310] {
            let s = power_of_two_scale(largest);
            assert_eq!(s.to_bits() & ((1 << 52) - 1), 0, "{largest}: {s} is a power of two");
            if (1e-300..1e300).contains(&largest) {
                assert!((1.0..2.0).contains(&(largest * s)), "{largest} * {s}");
            }
            assert!((largest * s).is_finite() && largest * s > 0.0);
        }
        assert_eq!(power_of_two_scale(0.0), 1.0);
        assert_eq!(power_of_two_scale(1.0), 1.0);
        assert_eq!(power_of_two_scale(0.75), 2.0);
    }

    #[test]
    fn hypot_neither_overflows_nor_underflows() {
        assert_eq!(hypot(3.0, -4.0), 5.0);
        assert_eq!(hypot(0.0, 0.0), 0.0);
        assert!((hypot(3e300, 4e300) / 5e300 - 1.0).abs() < 1e-15);
        assert!((hypot(3e-300, 4e-300) / 5e-300 - 1.0).abs() < 1e-15);
        assert!((norm2(&[3e200, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
    }

    #[test]
    fn orientation_makes_the_largest_entry_positive() {
        let mut v = [0.1, -0.9, 0.3];
        orient(&mut v);
        assert_eq!(v, [-0.1, 0.9, -0.3]);
        orient(&mut v);
        assert_eq!(v, [-0.1, 0.9, -0.3]);
    }
}
