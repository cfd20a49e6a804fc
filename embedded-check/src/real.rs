//! The float type a run computes in.
//!
//! Everything in this crate is generic over [`Real`], so the same run serves an `f64` chain and an
//! `f32` chain: a Cortex-M4F has a single-precision FPU only, and `f64` is emulated in software
//! there. The chain itself decides the type through [`Model<T>`](crate::Model); the chains
//! `#[rotor_chain]` generates today compute in `f64`.

use core::fmt::{Debug, Display, LowerExp};
use core::str::FromStr;

use num_traits::Float;

/// `f64` or `f32`: arithmetic and `floor`/`sqrt` from [`num_traits::Float`] (backed by `libm`
/// without `std`), formatting that round-trips (`{:e}` prints the shortest digits that parse back
/// to the same value), and the two conversions a run needs.
pub trait Real: Float + Display + LowerExp + Debug + FromStr + 'static {
    /// `"f64"` or `"f32"`: written in the firmware's output so that the host compares like with like.
    const NAME: &'static str;

    /// A constant of the run, given in `f64` (exact for `f64`, rounded to nearest for `f32`).
    fn of(x: f64) -> Self;

    /// The value as `f64` (exact for both types), for error messages and comparisons.
    fn widen(self) -> f64;
}

impl Real for f64 {
    const NAME: &'static str = "f64";

    #[inline(always)]
    fn of(x: f64) -> Self {
        x
    }

    #[inline(always)]
    fn widen(self) -> f64 {
        self
    }
}

impl Real for f32 {
    const NAME: &'static str = "f32";

    #[inline(always)]
    fn of(x: f64) -> Self {
        x as f32
    }

    #[inline(always)]
    fn widen(self) -> f64 {
        f64::from(self)
    }
}
