//! The x86-64 vector types: four lanes of AVX2 + FMA, eight lanes of AVX-512F.
//!
//! Their operations are `#[inline(always)]` functions without target features that call the
//! intrinsics: they are only ever inlined into [`run_avx2`] / [`run_avx512`], which carry the
//! features, so the intrinsics inline there too and the whole lane-generic body is compiled for
//! the level. The types are crate-private and created only inside those two functions, which
//! [`super::dispatch`] calls only after run-time detection: that is what makes the `unsafe`
//! intrinsic calls below sound.

use core::arch::x86_64::*;
use core::mem::MaybeUninit;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::trig::{self, Trig};
use super::{Lane, Vector, WithLanes};

/// Runs `work` with four lanes.
///
/// # Safety
/// The CPU must support AVX2 and FMA.
#[target_feature(enable = "avx2,fma")]
pub(super) unsafe fn run_avx2<W: WithLanes>(work: W) -> W::Output {
    work.run::<F64x4>()
}

/// Runs `work` with eight lanes.
///
/// # Safety
/// The CPU must support AVX-512F, AVX2 and FMA.
#[target_feature(enable = "avx512f,avx2,fma")]
pub(super) unsafe fn run_avx512<W: WithLanes>(work: W) -> W::Output {
    work.run::<F64x8>()
}

/// `sin_cos` of a slice with four lanes, compiled once (the drivers call it per chunk).
///
/// # Safety
/// The CPU must support AVX2 and FMA.
#[target_feature(enable = "avx2,fma")]
#[inline(never)]
pub(super) unsafe fn sin_cos_avx2(theta: &[f64], sin: &mut [MaybeUninit<f64>], cos: &mut [MaybeUninit<f64>]) {
    super::sin_cos_loop::<F64x4>(theta, sin, cos);
}

/// `sin_cos` of a slice with eight lanes, compiled once.
///
/// # Safety
/// The CPU must support AVX-512F, AVX2 and FMA.
#[target_feature(enable = "avx512f,avx2,fma")]
#[inline(never)]
pub(super) unsafe fn sin_cos_avx512(
    theta: &[f64],
    sin: &mut [MaybeUninit<f64>],
    cos: &mut [MaybeUninit<f64>],
) {
    super::sin_cos_loop::<F64x8>(theta, sin, cos);
}

/// The rare vectors of [`trig::with_scalar_lanes`], out of the hot loop.
///
/// # Safety
/// The CPU must support AVX2 and FMA.
#[cold]
#[target_feature(enable = "avx2,fma")]
#[inline(never)]
unsafe fn with_scalar_lanes_avx2(x: F64x4) -> (F64x4, F64x4) {
    trig::with_scalar_lanes(x)
}

/// # Safety
/// The CPU must support AVX-512F, AVX2 and FMA.
#[cold]
#[target_feature(enable = "avx512f,avx2,fma")]
#[inline(never)]
unsafe fn with_scalar_lanes_avx512(x: F64x8) -> (F64x8, F64x8) {
    trig::with_scalar_lanes(x)
}

#[derive(Clone, Copy)]
#[repr(transparent)]
pub(crate) struct F64x4(__m256d);

#[derive(Clone, Copy)]
#[repr(transparent)]
pub(crate) struct F64x8(__m512d);

/// The arithmetic operators and per-lane scalar functions of one vector type.
macro_rules! vector_ops {
    ($t:ident, $n:literal, add: $add:ident, sub: $sub:ident, mul: $mul:ident, div: $div:ident,
     sqrt: $sqrt:ident, set1: $set1:ident, load: $load:ident, store: $store:ident, fma: $fma:ident,
     slice: $slice:ident) => {
        impl Add for $t {
            type Output = $t;
            #[inline(always)]
            fn add(self, o: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $add(self.0, o.0) })
            }
        }
        impl Sub for $t {
            type Output = $t;
            #[inline(always)]
            fn sub(self, o: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $sub(self.0, o.0) })
            }
        }
        impl Mul for $t {
            type Output = $t;
            #[inline(always)]
            fn mul(self, o: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $mul(self.0, o.0) })
            }
        }
        impl Div for $t {
            type Output = $t;
            #[inline(always)]
            fn div(self, o: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $div(self.0, o.0) })
            }
        }
        impl Neg for $t {
            type Output = $t;
            #[inline(always)]
            fn neg(self) -> $t {
                // Flips the sign bit, exactly like scalar negation (also of zeros and NaNs).
                $t::xor_bits(self, i64::MIN)
            }
        }
        impl $t {
            #[inline(always)]
            fn map(self, f: impl Fn(f64) -> f64) -> $t {
                let mut a = [0.0; $n];
                self.store(&mut a);
                for v in &mut a {
                    *v = f(*v);
                }
                $t::load(&a)
            }
        }
        impl Lane for $t {
            #[inline(always)]
            fn splat(x: f64) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $set1(x) })
            }
            #[inline(always)]
            fn sqrt(self) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $sqrt(self.0) })
            }
            #[inline(always)]
            fn powi(self, n: i32) -> $t {
                self.map(|x| crate::math::powi(x, n))
            }
            #[inline(always)]
            fn exp(self) -> $t {
                self.map(crate::math::exp)
            }
            #[inline(always)]
            fn ln(self) -> $t {
                self.map(crate::math::ln)
            }
            #[inline(always)]
            fn sin(self) -> $t {
                self.map(crate::math::sin)
            }
            #[inline(always)]
            fn cos(self) -> $t {
                self.map(crate::math::cos)
            }
        }
        impl Vector for $t {
            const LANES: usize = $n;
            #[inline(always)]
            fn load(s: &[f64]) -> $t {
                let s: &[f64; $n] = s[..$n].try_into().unwrap();
                // SAFETY: `s` has $n readable values; see the module documentation.
                $t(unsafe { $load(s.as_ptr()) })
            }
            #[inline(always)]
            fn store_uninit(self, s: &mut [MaybeUninit<f64>]) {
                let s: &mut [MaybeUninit<f64>; $n] = (&mut s[..$n]).try_into().unwrap();
                // SAFETY: `s` has $n writable values (of `f64`'s layout); see the module
                // documentation.
                unsafe { $store(s.as_mut_ptr().cast::<f64>(), self.0) }
            }
            #[inline(always)]
            fn load_partial(s: &[f64]) -> $t {
                let len = s.len().min($n);
                // SAFETY: the mask covers the `len` readable values only; masked lanes are not
                // read. See the module documentation.
                $t(unsafe { $t::masked_load(s.as_ptr(), len) })
            }
            #[inline(always)]
            fn store_partial_uninit(self, s: &mut [MaybeUninit<f64>]) {
                let len = s.len().min($n);
                // SAFETY: as in `load_partial`, for writes.
                unsafe { self.masked_store(s.as_mut_ptr().cast::<f64>(), len) }
            }
            #[inline(always)]
            fn sum(self) -> f64 {
                let mut a = [0.0; $n];
                self.store(&mut a);
                a.iter().sum()
            }
            #[inline(always)]
            fn sin_cos(self) -> ($t, $t) {
                trig::sin_cos(self)
            }
            // Pairs help at four lanes only (`trig::sin_cos_pair`).
            const PAIR_TRIG: bool = $n == 4;
            #[inline(always)]
            fn sin_cos_pair(self, other: $t) -> (($t, $t), ($t, $t)) {
                trig::sin_cos_pair(self, other)
            }
            #[inline(always)]
            fn sin_cos_slice(theta: &[f64], sin: &mut [MaybeUninit<f64>], cos: &mut [MaybeUninit<f64>]) {
                // SAFETY: values of this type exist only at its level (module doc).
                unsafe { $slice(theta, sin, cos) }
            }
            #[inline(always)]
            fn previous_lane(self, previous: $t) -> $t {
                $t::shift_back(self, previous)
            }
            #[inline(always)]
            fn keep_lanes(self, lanes: u8) -> $t {
                $t::masked(self, lanes)
            }
            #[inline(always)]
            fn lane(self, i: usize) -> f64 {
                let mut a = [0.0; $n];
                self.store(&mut a);
                a[i]
            }
        }
        impl $t {
            #[inline(always)]
            fn fma(self, b: $t, c: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $fma(self.0, b.0, c.0) })
            }
        }
    };
}

vector_ops!(F64x4, 4, add: _mm256_add_pd, sub: _mm256_sub_pd, mul: _mm256_mul_pd, div: _mm256_div_pd,
    sqrt: _mm256_sqrt_pd, set1: _mm256_set1_pd, load: _mm256_loadu_pd, store: _mm256_storeu_pd,
    fma: _mm256_fmadd_pd, slice: sin_cos_avx2);
vector_ops!(F64x8, 8, add: _mm512_add_pd, sub: _mm512_sub_pd, mul: _mm512_mul_pd, div: _mm512_div_pd,
    sqrt: _mm512_sqrt_pd, set1: _mm512_set1_pd, load: _mm512_loadu_pd, store: _mm512_storeu_pd,
    fma: _mm512_fmadd_pd, slice: sin_cos_avx512);

// SAFETY (every `unsafe` block below): see the module documentation.

impl F64x4 {
    /// Lanes `i < len` have all bits set.
    #[inline(always)]
    fn lane_mask(len: usize) -> __m256i {
        unsafe { _mm256_cmpgt_epi64(_mm256_set1_epi64x(len as i64), _mm256_setr_epi64x(0, 1, 2, 3)) }
    }
    #[inline(always)]
    unsafe fn masked_load(p: *const f64, len: usize) -> __m256d {
        unsafe { _mm256_maskload_pd(p, F64x4::lane_mask(len)) }
    }
    #[inline(always)]
    unsafe fn masked_store(self, p: *mut f64, len: usize) {
        unsafe { _mm256_maskstore_pd(p, F64x4::lane_mask(len), self.0) }
    }
    #[inline(always)]
    fn xor_bits(self, bits: i64) -> F64x4 {
        F64x4(unsafe { _mm256_xor_pd(self.0, _mm256_castsi256_pd(_mm256_set1_epi64x(bits))) })
    }
    /// `[previous_3, self_0, self_1, self_2]`.
    #[inline(always)]
    fn shift_back(self, previous: F64x4) -> F64x4 {
        unsafe {
            let middle = _mm256_permute2f128_pd::<0x21>(previous.0, self.0); // [p2, p3, s0, s1]
            F64x4(_mm256_shuffle_pd::<0b0101>(middle, self.0))
        }
    }
    /// The lanes whose bit is set in `lanes`, `+0` in the others.
    #[inline(always)]
    fn masked(self, lanes: u8) -> F64x4 {
        unsafe {
            let bits = _mm256_setr_epi64x(1, 2, 4, 8);
            let set = _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(i64::from(lanes)), bits), bits);
            F64x4(_mm256_and_pd(self.0, _mm256_castsi256_pd(set)))
        }
    }
}

impl Trig for F64x4 {
    #[inline(always)]
    fn mul_add(self, b: F64x4, c: F64x4) -> F64x4 {
        self.fma(b, c)
    }
    #[inline(always)]
    fn quadrant(t: F64x4, s: F64x4, c: F64x4) -> (F64x4, F64x4) {
        unsafe {
            let q = _mm256_castpd_si256(t.0);
            let one = _mm256_set1_epi64x(1);
            let two = _mm256_set1_epi64x(2);
            // blendv selects by the sign bit: bit 0 of q moved there.
            let swap = _mm256_castsi256_pd(_mm256_slli_epi64::<63>(_mm256_and_si256(q, one)));
            let sin_sign = _mm256_castsi256_pd(_mm256_slli_epi64::<62>(_mm256_and_si256(q, two)));
            let cos_sign =
                _mm256_castsi256_pd(_mm256_slli_epi64::<62>(_mm256_and_si256(_mm256_add_epi64(q, one), two)));
            let sin = _mm256_xor_pd(_mm256_blendv_pd(s.0, c.0, swap), sin_sign);
            let cos = _mm256_xor_pd(_mm256_blendv_pd(c.0, s.0, swap), cos_sign);
            (F64x4(sin), F64x4(cos))
        }
    }
    #[inline(always)]
    fn or_sign(h: F64x4, s: F64x4) -> F64x4 {
        unsafe { F64x4(_mm256_or_pd(s.0, _mm256_and_pd(h.0, _mm256_set1_pd(-0.0)))) }
    }
    #[inline(always)]
    fn any_outside(x: F64x4) -> bool {
        unsafe {
            let abs = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x.0);
            let outside = _mm256_cmp_pd::<_CMP_NLE_UQ>(abs, _mm256_set1_pd(trig::LIMIT));
            _mm256_movemask_pd(outside) != 0
        }
    }
    #[inline(always)]
    fn with_scalar_lanes(x: F64x4) -> (F64x4, F64x4) {
        unsafe { with_scalar_lanes_avx2(x) }
    }
}

impl F64x8 {
    #[inline(always)]
    unsafe fn masked_load(p: *const f64, len: usize) -> __m512d {
        unsafe { _mm512_maskz_loadu_pd(super::first_lanes(len), p) }
    }
    #[inline(always)]
    unsafe fn masked_store(self, p: *mut f64, len: usize) {
        unsafe { _mm512_mask_storeu_pd(p, super::first_lanes(len), self.0) }
    }
    /// `[previous_7, self_0, ..., self_6]`.
    #[inline(always)]
    fn shift_back(self, previous: F64x8) -> F64x8 {
        unsafe {
            F64x8(_mm512_castsi512_pd(_mm512_alignr_epi64::<7>(
                _mm512_castpd_si512(self.0),
                _mm512_castpd_si512(previous.0),
            )))
        }
    }
    /// The lanes whose bit is set in `lanes`, `+0` in the others.
    #[inline(always)]
    fn masked(self, lanes: u8) -> F64x8 {
        F64x8(unsafe { _mm512_maskz_mov_pd(lanes, self.0) })
    }
    #[inline(always)]
    fn xor_bits(self, bits: i64) -> F64x8 {
        F64x8(unsafe {
            _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(self.0), _mm512_set1_epi64(bits)))
        })
    }
}

impl Trig for F64x8 {
    #[inline(always)]
    fn mul_add(self, b: F64x8, c: F64x8) -> F64x8 {
        self.fma(b, c)
    }
    #[inline(always)]
    fn quadrant(t: F64x8, s: F64x8, c: F64x8) -> (F64x8, F64x8) {
        unsafe {
            let q = _mm512_castpd_si512(t.0);
            let one = _mm512_set1_epi64(1);
            let two = _mm512_set1_epi64(2);
            let swap = _mm512_test_epi64_mask(q, one);
            let sin_sign = _mm512_slli_epi64::<62>(_mm512_and_si512(q, two));
            let cos_sign = _mm512_slli_epi64::<62>(_mm512_and_si512(_mm512_add_epi64(q, one), two));
            let sin = _mm512_castpd_si512(_mm512_mask_blend_pd(swap, s.0, c.0));
            let cos = _mm512_castpd_si512(_mm512_mask_blend_pd(swap, c.0, s.0));
            (
                F64x8(_mm512_castsi512_pd(_mm512_xor_si512(sin, sin_sign))),
                F64x8(_mm512_castsi512_pd(_mm512_xor_si512(cos, cos_sign))),
            )
        }
    }
    #[inline(always)]
    fn or_sign(h: F64x8, s: F64x8) -> F64x8 {
        unsafe {
            // s | (h & sign) in one instruction (truth table 0xF8 = A | (B & C)).
            F64x8(_mm512_castsi512_pd(_mm512_ternarylogic_epi64::<0xF8>(
                _mm512_castpd_si512(s.0),
                _mm512_castpd_si512(h.0),
                _mm512_set1_epi64(i64::MIN),
            )))
        }
    }
    #[inline(always)]
    fn any_outside(x: F64x8) -> bool {
        unsafe {
            let abs =
                _mm512_castsi512_pd(_mm512_and_si512(_mm512_castpd_si512(x.0), _mm512_set1_epi64(i64::MAX)));
            _mm512_cmp_pd_mask::<_CMP_NLE_UQ>(abs, _mm512_set1_pd(trig::LIMIT)) != 0
        }
    }
    #[inline(always)]
    fn with_scalar_lanes(x: F64x8) -> (F64x8, F64x8) {
        unsafe { with_scalar_lanes_avx512(x) }
    }
}
