//! Arithmetic over several `f64` lanes at once, chosen at run time.
//!
//! A default build targets baseline x86-64 (SSE2), so vector instructions are used only if the
//! code asks the CPU at run time what it has. This module does that once, caches the answer, and
//! runs the lane-generic code of its callers at the widest [`Level`] the machine supports:
//!
//! | level | lanes | needs |
//! |---|---|---|
//! | [`Level::Avx512`] | 8 | AVX-512F (and AVX2 + FMA) |
//! | [`Level::Avx2`] | 4 | AVX2 + FMA |
//! | [`Level::Scalar`] | 1 | nothing: `crate::math` (the platform's libm with `std`, `libm` without) |
//!
//! Without `std` there is no run-time detection: the level is what the build targets
//! (`-C target-feature` / `target-cpu`), which is scalar for a default `no_std` build.
//! Other architectures (aarch64 included) run the scalar level: NEON's two `f64` lanes were not
//! worth a third vector type here.
//!
//! What lives here:
//! - [`Lane`], the arithmetic the rendered per-spring kernels (`crate::kernel`) are generic over,
//!   implemented for `f64` and for the vector types;
//! - [`sin_cos_into`], the sines and cosines of many angles (a polynomial over the lanes,
//!   `trig.rs`; the error bound and how it was measured are there);
//! - the dispatch that instantiates a caller's lane-generic code inside a function compiled for
//!   the level's target features, so everything it inlines uses them.

use core::mem::MaybeUninit;
use core::ops::{Add, Div, Mul, Neg, Sub};

use crate::math;

// Only the x86-64 vector types use the polynomial; elsewhere only its limit is read.
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
mod trig;
#[cfg(target_arch = "x86_64")]
mod x86;

/// The vector instruction sets the lane-generic code can run at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Level {
    /// One lane, `crate::math` functions (the reference every other level is tested against).
    Scalar,
    /// Four lanes of AVX2 with fused multiply-add.
    Avx2,
    /// Eight lanes of AVX-512F.
    Avx512,
}

impl Level {
    /// Every level, narrowest first.
    pub const ALL: [Level; 3] = [Level::Scalar, Level::Avx2, Level::Avx512];

    /// `f64` lanes per operation.
    pub fn lanes(self) -> usize {
        match self {
            Level::Scalar => 1,
            Level::Avx2 => 4,
            Level::Avx512 => 8,
        }
    }

    /// A short name for tables and benchmark labels.
    pub fn name(self) -> &'static str {
        match self {
            Level::Scalar => "scalar",
            Level::Avx2 => "avx2",
            Level::Avx512 => "avx512",
        }
    }

    /// Whether this machine can run the level.
    pub fn is_supported(self) -> bool {
        self as u8 <= detected() as u8
    }
}

/// The widest level this machine supports (detected once, then cached).
pub fn detected() -> Level {
    use core::sync::atomic::{AtomicU8, Ordering};
    // 0: not yet detected; otherwise 1 + the level.
    static DETECTED: AtomicU8 = AtomicU8::new(0);
    match DETECTED.load(Ordering::Relaxed) {
        0 => {
            let level = detect();
            DETECTED.store(level as u8 + 1, Ordering::Relaxed);
            level
        }
        v => Level::ALL[usize::from(v - 1)],
    }
}

#[cfg(all(target_arch = "x86_64", feature = "std"))]
fn detect() -> Level {
    if std::is_x86_feature_detected!("avx512f")
        && std::is_x86_feature_detected!("avx2")
        && std::is_x86_feature_detected!("fma")
    {
        Level::Avx512
    } else if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
        Level::Avx2
    } else {
        Level::Scalar
    }
}

/// Without `std` there is no detection: the level is what the build targets.
#[cfg(not(all(target_arch = "x86_64", feature = "std")))]
fn detect() -> Level {
    if cfg!(all(
        target_arch = "x86_64",
        target_feature = "avx512f",
        target_feature = "avx2",
        target_feature = "fma"
    )) {
        Level::Avx512
    } else if cfg!(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma")) {
        Level::Avx2
    } else {
        Level::Scalar
    }
}

#[cfg(feature = "std")]
std::thread_local! {
    static FORCED: core::cell::Cell<Option<Level>> = const { core::cell::Cell::new(None) };
}

/// The level the lane-generic code runs at on this thread: [`detected`], unless a test forced
/// another with [`with_level`].
#[inline]
pub fn level() -> Level {
    #[cfg(feature = "std")]
    if let Some(forced) = FORCED.with(|f| f.get()) {
        return forced;
    }
    detected()
}

/// Runs `f` with every dispatched call on this thread at `level`, so tests and benchmarks can
/// exercise each level the machine supports. `None` (and `f` is not run) if the machine cannot
/// run `level`. Not part of the stable API.
#[doc(hidden)]
#[cfg(feature = "std")]
pub fn with_level<R>(level: Level, f: impl FnOnce() -> R) -> Option<R> {
    struct Restore(Option<Level>);
    impl Drop for Restore {
        fn drop(&mut self) {
            FORCED.with(|f| f.set(self.0));
        }
    }
    if !level.is_supported() {
        return None;
    }
    let _restore = Restore(FORCED.with(|f| f.replace(Some(level))));
    Some(f())
}

/// The arithmetic of the rendered per-spring kernels: `f64`, or several `f64` lanes at once.
///
/// Every operation is the IEEE-754 operation lane by lane (the vector `+ - * /` and `sqrt` are
/// correctly rounded like the scalar ones, and nothing is contracted into fused multiply-adds),
/// so a kernel gives bit-identical results at every lane width for the same inputs. The
/// functions without a vector instruction (`powi`, `exp`, `ln`, `sin`, `cos`: only custom laws
/// use them) apply `crate::math`'s scalar function to each lane.
pub trait Lane:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// Square root, lane by lane.
    fn sqrt(self) -> Self;
    /// `x^n` for an integer `n`, lane by lane.
    fn powi(self, n: i32) -> Self;
    /// Exponential, lane by lane.
    fn exp(self) -> Self;
    /// Natural logarithm, lane by lane.
    fn ln(self) -> Self;
    /// Sine (radians), lane by lane.
    fn sin(self) -> Self;
    /// Cosine (radians), lane by lane.
    fn cos(self) -> Self;
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        math::sqrt(self)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> f64 {
        math::powi(self, n)
    }
    #[inline(always)]
    fn exp(self) -> f64 {
        math::exp(self)
    }
    #[inline(always)]
    fn ln(self) -> f64 {
        math::ln(self)
    }
    #[inline(always)]
    fn sin(self) -> f64 {
        math::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> f64 {
        math::cos(self)
    }
}

/// What the drivers need beyond [`Lane`]: loads, stores, a horizontal sum and `sin_cos`.
/// Implemented by `f64` (one lane) and the crate-private vector types, whose values exist only
/// inside code running at their level. Hidden: public only for chain-network's bond drivers.
#[doc(hidden)]
pub trait Vector: Lane {
    /// Lanes per value.
    const LANES: usize;
    /// The first `LANES` entries of `s`.
    fn load(s: &[f64]) -> Self;
    /// Writes the lanes to the first `LANES` entries of `s`.
    #[inline(always)]
    fn store(self, s: &mut [f64]) {
        self.store_uninit(as_uninit(s));
    }
    /// Writes the lanes to the first `LANES` entries of `s`, which need not be initialized.
    fn store_uninit(self, s: &mut [MaybeUninit<f64>]);
    /// The entries of `s` (fewer than `LANES`) in the first lanes, zeros in the others; memory
    /// past `s` is not touched (masked loads).
    fn load_partial(s: &[f64]) -> Self;
    /// Writes the first `min(s.len(), LANES)` lanes to `s` (masked stores).
    #[inline(always)]
    fn store_partial(self, s: &mut [f64]) {
        self.store_partial_uninit(as_uninit(s));
    }
    /// [`Vector::store_partial`] to entries that need not be initialized.
    fn store_partial_uninit(self, s: &mut [MaybeUninit<f64>]);
    /// The sum of the lanes.
    fn sum(self) -> f64;
    /// Sine and cosine of every lane.
    fn sin_cos(self) -> (Self, Self);
    /// Whether [`sin_cos_loop`] takes two values at a time through [`Vector::sin_cos_pair`]
    /// (where that is faster: AVX2).
    const PAIR_TRIG: bool = false;
    /// Sine and cosine of two values (the same bits as two calls of [`Vector::sin_cos`]).
    #[inline(always)]
    fn sin_cos_pair(self, other: Self) -> ((Self, Self), (Self, Self)) {
        (self.sin_cos(), other.sin_cos())
    }
    /// `sin[i], cos[i] = sin_cos(theta[i])` over a slice, `LANES` angles at a time, compiled once
    /// per level (not inlined into every driver). The outputs need not be initialized: the
    /// kernel drivers' buffers are not (zeroing them cost 4-8 % of energy + gradient of 60
    /// rotors, docs/benchmarks.md, eighth round).
    fn sin_cos_slice(theta: &[f64], sin: &mut [MaybeUninit<f64>], cos: &mut [MaybeUninit<f64>]);
    /// `[previous_{LANES-1}, self_0, ..., self_{LANES-2}]`: the left neighbour of every lane.
    fn previous_lane(self, previous: Self) -> Self;
    /// The lanes whose bit is set in `lanes` (bit `i` for lane `i`), `+0` in the others (NaN
    /// included: a dropped lane is gone, whatever it held).
    fn keep_lanes(self, lanes: u8) -> Self;
    /// The first `count` lanes, zeros in the others.
    #[inline(always)]
    fn keep_first(self, count: usize) -> Self {
        self.keep_lanes(first_lanes(count))
    }
    /// Lane `i`.
    fn lane(self, i: usize) -> f64;
}

impl Vector for f64 {
    const LANES: usize = 1;
    #[inline(always)]
    fn load(s: &[f64]) -> f64 {
        s[0]
    }
    #[inline(always)]
    fn store_uninit(self, s: &mut [MaybeUninit<f64>]) {
        s[0].write(self);
    }
    #[inline(always)]
    fn load_partial(s: &[f64]) -> f64 {
        s.first().copied().unwrap_or(0.0)
    }
    #[inline(always)]
    fn store_partial_uninit(self, s: &mut [MaybeUninit<f64>]) {
        if let Some(x) = s.first_mut() {
            x.write(self);
        }
    }
    #[inline(always)]
    fn sum(self) -> f64 {
        self
    }
    #[inline(always)]
    fn sin_cos(self) -> (f64, f64) {
        math::sin_cos(self)
    }
    #[inline(always)]
    fn sin_cos_slice(theta: &[f64], sin: &mut [MaybeUninit<f64>], cos: &mut [MaybeUninit<f64>]) {
        sin_cos_loop::<f64>(theta, sin, cos);
    }
    #[inline(always)]
    fn previous_lane(self, previous: f64) -> f64 {
        previous
    }
    #[inline(always)]
    fn keep_lanes(self, lanes: u8) -> f64 {
        if lanes & 1 == 1 { self } else { 0.0 }
    }
    #[inline(always)]
    fn lane(self, _i: usize) -> f64 {
        self
    }
}

/// The bits of lanes `0 .. count` (all eight from `count >= 8` on).
#[inline(always)]
pub(crate) fn first_lanes(count: usize) -> u8 {
    ((1u32 << count.min(8)) - 1) as u8
}

/// Lane-generic work handed to [`dispatch`]: `run::<V>` is instantiated once per level, inside a
/// function compiled with that level's target features.
///
/// Hidden: public only for chain-network's bond drivers.
#[doc(hidden)]
pub trait WithLanes {
    /// What the work returns.
    type Output;
    /// The work at lane type `V`.
    fn run<V: Vector>(self) -> Self::Output;
}

/// Runs `work` at [`level`].
#[inline(always)]
#[doc(hidden)]
pub fn dispatch<W: WithLanes>(work: W) -> W::Output {
    match level() {
        // SAFETY: `level()` returns a vector level only if the CPU supports it.
        #[cfg(target_arch = "x86_64")]
        Level::Avx512 => unsafe { x86::run_avx512(work) },
        #[cfg(target_arch = "x86_64")]
        Level::Avx2 => unsafe { x86::run_avx2(work) },
        _ => work.run::<f64>(),
    }
}

/// `sin[i], cos[i] = sin_cos(theta[i])` for `i < theta.len()` at `V`'s level (see
/// [`Vector::sin_cos_slice`]); `sin` and `cos` need not be initialized.
#[inline(always)]
pub(crate) fn sin_cos_lanes<V: Vector>(
    theta: &[f64],
    sin: &mut [MaybeUninit<f64>],
    cos: &mut [MaybeUninit<f64>],
) {
    V::sin_cos_slice(theta, sin, cos);
}

/// `s` as entries that need not be initialized, for the writers above.
#[inline(always)]
fn as_uninit(s: &mut [f64]) -> &mut [MaybeUninit<f64>] {
    // SAFETY: `MaybeUninit<f64>` has the layout of `f64`. The callers (this module's stores)
    // write only initialized values through the result, so `s` stays initialized.
    unsafe { &mut *(core::ptr::from_mut(s) as *mut [MaybeUninit<f64>]) }
}

/// The loop of [`Vector::sin_cos_slice`]: `V::LANES` angles at a time (two groups at once where
/// [`Vector::PAIR_TRIG`]). A short last group is padded with zeros, so an angle gets the same
/// result wherever it sits.
#[inline(always)]
pub(crate) fn sin_cos_loop<V: Vector>(
    theta: &[f64],
    sin: &mut [MaybeUninit<f64>],
    cos: &mut [MaybeUninit<f64>],
) {
    let n = theta.len();
    let (sin, cos) = (&mut sin[..n], &mut cos[..n]);
    let mut i = 0;
    while V::PAIR_TRIG && i + 2 * V::LANES <= n {
        let (x0, x1) = (V::load(&theta[i..i + V::LANES]), V::load(&theta[i + V::LANES..i + 2 * V::LANES]));
        let ((s0, c0), (s1, c1)) = x0.sin_cos_pair(x1);
        s0.store_uninit(&mut sin[i..i + V::LANES]);
        c0.store_uninit(&mut cos[i..i + V::LANES]);
        s1.store_uninit(&mut sin[i + V::LANES..i + 2 * V::LANES]);
        c1.store_uninit(&mut cos[i + V::LANES..i + 2 * V::LANES]);
        i += 2 * V::LANES;
    }
    // Ranges of exactly `V::LANES` under the loop's condition: the compiler drops their checks.
    while i + V::LANES <= n {
        let (s, c) = V::load(&theta[i..i + V::LANES]).sin_cos();
        s.store_uninit(&mut sin[i..i + V::LANES]);
        c.store_uninit(&mut cos[i..i + V::LANES]);
        i += V::LANES;
    }
    if i < n {
        let (s, c) = V::load_partial(&theta[i..]).sin_cos();
        s.store_partial_uninit(&mut sin[i..]);
        c.store_partial_uninit(&mut cos[i..]);
    }
}

/// `sin[i], cos[i] = sin_cos(theta[i])` for every angle, at [`level`]. See `math::sin_cos_into`.
pub fn sin_cos_into(theta: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    struct Work<'a>(&'a [f64], &'a mut [f64], &'a mut [f64]);
    impl WithLanes for Work<'_> {
        type Output = ();
        #[inline(always)]
        fn run<V: Vector>(self) {
            sin_cos_lanes::<V>(self.0, as_uninit(self.1), as_uninit(self.2));
        }
    }
    assert!(sin.len() >= theta.len() && cos.len() >= theta.len(), "one sine and one cosine per angle");
    dispatch(Work(theta, sin, cos));
}

/// The largest `|theta|` the vector `sin_cos` reduces itself; beyond it (and for NaN and the
/// infinities) a lane takes the scalar `crate::math::sin_cos`. See `trig.rs`.
pub const VECTOR_SIN_COS_LIMIT: f64 = trig::LIMIT;
