//! The float type a chain computes in: `f64` (the default, every analysis) or `f32` (chains
//! declared with `float = f32`, for microcontrollers whose FPU is single precision).
//!
//! Everything that serves both types is generic over [`Real`]: the branch solve
//! ([`crate::branch`]), the banded matrices ([`crate::banded`]) and the no-alloc pieces of a
//! dynamics run ([`crate::embedded`]). The elementary functions go through [`crate::math`] for
//! `f64` and [`crate::math::single`] for `f32`, the same functions the generated code calls, so a
//! generic computation and the generated code of the same type agree to the last bit.
//!
//! Why a trait of our own rather than `num_traits::Float` or `nalgebra::RealField`: their `sin`,
//! `cos` and `atan2` resolve to `std` or `libm` by their own features, not by `rotor-chain`'s, and
//! the firmware-against-host check (docs/embedded.md) needs one choice for the whole chain.

use core::fmt::{Debug, Display, LowerExp};
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};
use core::str::FromStr;

use crate::math;

/// `f64` or `f32`: IEEE arithmetic, the few elementary functions the chain needs, formatting that
/// round-trips (`{:e}` prints the shortest digits that parse back to the same value), and the
/// conversions to and from `f64`.
pub trait Real:
    Copy
    + Default
    + PartialOrd
    + Debug
    + Display
    + LowerExp
    + FromStr
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + nalgebra::Scalar
{
    /// `"f64"` or `"f32"`, as written in the attribute's `float = ..` key.
    const NAME: &'static str;
    /// `0`.
    const ZERO: Self;
    /// `1`.
    const ONE: Self;
    /// The distance from 1 to the next larger number: `2^-52` or `2^-23`.
    const EPSILON: Self;

    /// `x` rounded to the nearest value of this type (exact for `f64`).
    fn of(x: f64) -> Self;

    /// The value as `f64` (exact for both types): for error messages, which carry `f64`s.
    fn widen(self) -> f64;

    /// A rotor index or count as a number (exact up to `2^24` for `f32`).
    fn of_index(i: usize) -> Self;

    /// The largest integer not above `self`, as an index (`self` must be finite and `>= 0`).
    fn floor_index(self) -> usize;

    /// The square root (`sqrt` or `sqrtf`).
    fn sqrt(self) -> Self;
    /// The exponential (`exp` or `expf`): the exact decay of a damped Verlet step.
    fn exp(self) -> Self;
    /// `(sin self, cos self)`, through [`crate::math`] or [`crate::math::single`].
    fn sin_cos(self) -> (Self, Self);
    /// The angle of the point `(x, self)`, in `(-pi, pi]`.
    fn atan2(self, x: Self) -> Self;
    /// The largest integer not above `self`.
    fn floor(self) -> Self;

    /// The absolute value.
    #[inline(always)]
    fn abs(self) -> Self {
        if self < Self::ZERO { -self } else { self }
    }

    /// The larger of the two; `other` if `self` is NaN.
    #[inline(always)]
    #[allow(clippy::eq_op)]
    fn max(self, other: Self) -> Self {
        if self >= other || other != other { self } else { other }
    }

    /// Neither NaN nor infinite.
    #[inline(always)]
    #[allow(clippy::eq_op)]
    fn is_finite(self) -> bool {
        self == self && (self - self) == Self::ZERO
    }
}

impl Real for f64 {
    const NAME: &'static str = "f64";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const EPSILON: Self = f64::EPSILON;

    #[inline(always)]
    fn of(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn widen(self) -> f64 {
        self
    }
    #[inline(always)]
    fn of_index(i: usize) -> Self {
        i as f64
    }
    #[inline(always)]
    fn floor_index(self) -> usize {
        libm::floor(self) as usize
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        math::sqrt(self)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        math::exp(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        math::sin_cos(self)
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        math::atan2(self, x)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        libm::floor(self)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
}

impl Real for f32 {
    const NAME: &'static str = "f32";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const EPSILON: Self = f32::EPSILON;

    #[inline(always)]
    fn of(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn widen(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn of_index(i: usize) -> Self {
        i as f32
    }
    #[inline(always)]
    fn floor_index(self) -> usize {
        libm::floorf(self) as usize
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        math::single::sqrt(self)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        math::single::exp(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        math::single::sin_cos(self)
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        math::single::atan2(self, x)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        libm::floorf(self)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn generic_checks<T: Real>() {
        assert_eq!(T::of(0.5).widen(), 0.5);
        assert_eq!(T::of(-2.0).abs().widen(), 2.0);
        assert!(!T::of(f64::NAN).is_finite() && !T::of(f64::INFINITY).is_finite());
        assert!(T::of(3.0).is_finite());
        assert_eq!(T::of(f64::NAN).max(T::ONE).widen(), 1.0);
        assert_eq!(T::ONE.max(T::of(f64::NAN)).widen(), 1.0);
        assert_eq!(T::of(4.75).floor_index(), 4);
        assert_eq!(T::of(2.25).sqrt().widen(), 1.5);
    }

    #[test]
    fn both_types_behave_alike() {
        generic_checks::<f64>();
        generic_checks::<f32>();
        assert_eq!(f32::of(0.1), 0.1f32);
        assert_eq!(f32::of(1e300), f32::INFINITY);
    }
}
