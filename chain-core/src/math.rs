//! The few transcendental functions generated code calls: `std`'s when the `std` feature is on
//! (they compile to the platform's libm, and `sqrt` to one instruction), the pure-Rust `libm`
//! crate otherwise, so the same generated code builds on `no_std` targets.

#[cfg(feature = "std")]
mod imp {
    #[inline(always)]
    /// `(sin x, cos x)` of `x` in radians, in one call.
    pub fn sin_cos(x: f64) -> (f64, f64) {
        x.sin_cos()
    }
    #[inline(always)]
    /// Square root.
    pub fn sqrt(x: f64) -> f64 {
        x.sqrt()
    }
    #[inline(always)]
    /// Sine of `x` in radians.
    pub fn sin(x: f64) -> f64 {
        x.sin()
    }
    #[inline(always)]
    /// Cosine of `x` in radians.
    pub fn cos(x: f64) -> f64 {
        x.cos()
    }
    #[inline(always)]
    /// Exponential `e^x`.
    pub fn exp(x: f64) -> f64 {
        x.exp()
    }
    #[inline(always)]
    /// Natural logarithm.
    pub fn ln(x: f64) -> f64 {
        x.ln()
    }
    #[inline(always)]
    /// `x^n` for an integer `n`.
    pub fn powi(x: f64, n: i32) -> f64 {
        x.powi(n)
    }
    #[inline(always)]
    /// Angle of the point `(x, y)` from the `+x` axis, radians in `[-pi, pi]`.
    pub fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
}

#[cfg(not(feature = "std"))]
mod imp {
    #[inline(always)]
    /// `(sin x, cos x)` of `x` in radians, in one call.
    pub fn sin_cos(x: f64) -> (f64, f64) {
        libm::sincos(x)
    }
    #[inline(always)]
    /// Square root.
    pub fn sqrt(x: f64) -> f64 {
        libm::sqrt(x)
    }
    #[inline(always)]
    /// Sine of `x` in radians.
    pub fn sin(x: f64) -> f64 {
        libm::sin(x)
    }
    #[inline(always)]
    /// Cosine of `x` in radians.
    pub fn cos(x: f64) -> f64 {
        libm::cos(x)
    }
    #[inline(always)]
    /// Exponential `e^x`.
    pub fn exp(x: f64) -> f64 {
        libm::exp(x)
    }
    #[inline(always)]
    /// Natural logarithm.
    pub fn ln(x: f64) -> f64 {
        libm::log(x)
    }
    #[inline(always)]
    /// `x^n` for an integer `n`.
    pub fn powi(x: f64, n: i32) -> f64 {
        libm::pow(x, f64::from(n))
    }
    #[inline(always)]
    /// Angle of the point `(x, y)` from the `+x` axis, radians in `[-pi, pi]`.
    pub fn atan2(y: f64, x: f64) -> f64 {
        libm::atan2(y, x)
    }
}

pub use imp::*;

/// `sin[i], cos[i] = sin_cos(theta[i])` for every angle: the one entry point through which
/// generated code and the kernel drivers take the sines and cosines of a whole chain.
///
/// It runs at the widest vector level the CPU offers ([`crate::simd`], detected at run time): a
/// polynomial over 4 (AVX2 + FMA) or 8 (AVX-512F) lanes, within 2 ulp of the correctly rounded
/// values (measured: `docs/benchmarks.md`), and [`sin_cos`] itself on other machines and without
/// `std`. Angles beyond `simd::VECTOR_SIN_COS_LIMIT`, NaN and the infinities always get
/// [`sin_cos`]'s result. An angle's result does not depend on where it sits in `theta`.
///
/// # Panics
/// If `sin` or `cos` is shorter than `theta` (a programming error).
#[inline]
pub fn sin_cos_into(theta: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    crate::simd::sin_cos_into(theta, sin, cos);
}

/// The sign of `x` with `sign(0) = 0` (and NaN for NaN): unlike `f64::signum`, zero is neither side.
#[inline]
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        x * 0.0
    }
}

/// The single-precision functions of chains declared with `float = f32` (generated code calls
/// them through `__private::math::single`), and of the `f32` branch solve: `std`'s `f32` methods
/// when the `std` feature is on, `libm`'s `sinf`, `cosf`, `sqrtf`, ... otherwise, as for `f64`.
/// The signatures never widen to `f64`, but the implementations may: `libm`'s `sincosf`, `sinf`
/// and `cosf` (a port of musl's) reduce the argument and evaluate their polynomial kernels in
/// `f64`, so on a Cortex-M4F, whose FPU is single precision, they link the soft-float `f64`
/// multiply and add. Measured under QEMU (docs/embedded.md) they are most of an `f32` Verlet
/// step's instructions; `sqrtf` and the arithmetic of the generated code are pure `f32`. `powi`
/// with `|n| > 2^24` also computes in `f64` (below).
pub mod single {
    #[cfg(feature = "std")]
    mod imp {
        /// `(sin x, cos x)`.
        #[inline(always)]
        pub fn sin_cos(x: f32) -> (f32, f32) {
            x.sin_cos()
        }
        /// The square root.
        #[inline(always)]
        pub fn sqrt(x: f32) -> f32 {
            x.sqrt()
        }
        /// The sine.
        #[inline(always)]
        pub fn sin(x: f32) -> f32 {
            x.sin()
        }
        /// The cosine.
        #[inline(always)]
        pub fn cos(x: f32) -> f32 {
            x.cos()
        }
        /// `e^x`.
        #[inline(always)]
        pub fn exp(x: f32) -> f32 {
            x.exp()
        }
        /// The natural logarithm.
        #[inline(always)]
        pub fn ln(x: f32) -> f32 {
            x.ln()
        }
        /// `x^n`.
        #[inline(always)]
        pub fn powi(x: f32, n: i32) -> f32 {
            x.powi(n)
        }
        /// The angle of the point `(x, y)`, in `(-pi, pi]`.
        #[inline(always)]
        pub fn atan2(y: f32, x: f32) -> f32 {
            y.atan2(x)
        }
    }

    #[cfg(not(feature = "std"))]
    mod imp {
        /// `(sin x, cos x)`.
        #[inline(always)]
        pub fn sin_cos(x: f32) -> (f32, f32) {
            libm::sincosf(x)
        }
        /// The square root.
        #[inline(always)]
        pub fn sqrt(x: f32) -> f32 {
            libm::sqrtf(x)
        }
        /// The sine.
        #[inline(always)]
        pub fn sin(x: f32) -> f32 {
            libm::sinf(x)
        }
        /// The cosine.
        #[inline(always)]
        pub fn cos(x: f32) -> f32 {
            libm::cosf(x)
        }
        /// `e^x`.
        #[inline(always)]
        pub fn exp(x: f32) -> f32 {
            libm::expf(x)
        }
        /// The natural logarithm.
        #[inline(always)]
        pub fn ln(x: f32) -> f32 {
            libm::logf(x)
        }
        /// `powf` with the exponent as an `f32`, exact for `|n| <= 2^24`; beyond, the `f32`
        /// exponent would be rounded, so the power is taken in `f64` and rounded once.
        #[inline(always)]
        pub fn powi(x: f32, n: i32) -> f32 {
            if n.unsigned_abs() <= 1 << 24 {
                libm::powf(x, n as f32)
            } else {
                libm::pow(f64::from(x), f64::from(n)) as f32
            }
        }
        /// The angle of the point `(x, y)`, in `(-pi, pi]`.
        #[inline(always)]
        pub fn atan2(y: f32, x: f32) -> f32 {
            libm::atan2f(y, x)
        }
    }

    pub use imp::*;

    /// `sin[i], cos[i] = sin_cos(theta[i])` for every angle: the `f32` twin of
    /// [`super::sin_cos_into`], one scalar call per angle (the vector `sin_cos` is `f64` only).
    ///
    /// # Panics
    /// If `sin` or `cos` is shorter than `theta` (a programming error).
    #[inline]
    pub fn sin_cos_into(theta: &[f32], sin: &mut [f32], cos: &mut [f32]) {
        assert!(sin.len() >= theta.len() && cos.len() >= theta.len(), "one sine and one cosine per angle");
        for ((t, s), c) in theta.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
            (*s, *c) = sin_cos(*t);
        }
    }
}
