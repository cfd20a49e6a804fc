//! `sin_cos` over vector lanes: Cody-Waite reduction by `pi/2` with fused multiply-adds,
//! then minimax polynomials on `[-pi/4, pi/4]` (fdlibm's coefficients).
//!
//! Written here because no well-kept crate does it on stable Rust with run-time dispatch: the
//! SLEEF port (`sleef`) needs nightly `portable_simd`, `pulp` and `wide` have no trigonometry
//! (and `wide` picks its instructions at compile time), and the f32 SIMD crates do not help.
//!
//! **Reduction.** `k = round(x 2/pi)` (by the `1.5 * 2^52` trick, which also leaves `k mod 4` in
//! the low mantissa bits), then `r = x - k pi/2` with `pi/2 = P1 + P2 + P3` (three doubles, 159
//! bits), one fused multiply-add per term: `r1 = x - k P1` is exact (both terms are multiples of
//! `min(ulp(x), 2^-52)` and the result is below 1), `r2 = r1 - k P2` rounds once, to half an ulp
//! of `r2`, and `hi = r2 - k P3` once more, to half an ulp of `hi`. `k P3` is below `2^24
//! 2^-106.1 = 2^-82.1`, and the error left after it, about `|k| 2^-160`, is negligible. The
//! remainder of a double below [`LIMIT`] is never smaller than `6.19e-19 = 2^-60.5` unless it is
//! zero (at `x = 29 pi/2`, found by exact integer arithmetic over every `k` up to `2^24 2/pi`,
//! `tests/sin_cos.rs`), so `hi` is within one ulp of the true remainder in relative terms however
//! near `x` is to a multiple of `pi/2`. Where `|hi| >= 2^-28` the last step changes nothing (`k
//! P3` is below a quarter of an ulp of `hi`); it is there for the angles nearer a nonzero
//! multiple of `pi/2`, whose sine or cosine is about `hi` itself.
//!
//! `P2` is rounded toward zero, so that `P3` is positive: for `x = -0` (`k = +0`) every step is
//! then `-0 P + -0 = -0`, and the remainder keeps the sign of zero. (With `P2` rounded to nearest,
//! `P3` is negative, `-0 P3 = +0`, and `+0 + -0` rounds to `+0`.)
//!
//! Past `LIMIT` (and for NaN and the infinities) a lane is recomputed by the scalar
//! `crate::math::sin_cos` ([`with_scalar_lanes`]), so those angles give exactly what the scalar
//! path gives.
//!
//! **Polynomials**, on `[-pi/4, pi/4]`:
//! - `sin hi = hi + hi z S(z)` with `z = hi^2`, and the sign bit of `hi` or-ed back in, so that
//!   `sin(-0) = -0` (the sum gives `+0` there, and otherwise already has the sign of `hi`);
//! - `cos hi = 1 + (z^2 C(z) - z/2)`: the bracket lies in `[-0.31, 0]` and rounds to within
//!   `2^-55`, a quarter of an ulp of the result (`>= 0.70`).
//!
//! **History** (docs/benchmarks.md, fourth and thirteenth rounds). fdlibm's way, with the
//! remainder in double-double, the rounding error of `1 - z/2` carried and a compare-and-blend for
//! `-0`, took 46 vector operations per group of lanes: 83 ns for 60 angles at AVX-512. One double
//! without `k P3` took 34 (62 ns), but needed a second, double-double path for lanes within
//! `2^-28` of a nonzero multiple of `pi/2`, and three compares per vector to find them. The `k P3`
//! step (one operation) makes that path and those compares unnecessary: 60 ns. The error table on
//! 1.02e7 points (`examples/sin_cos_ulp.rs`) is unchanged to the last count, with 1 ulp the
//! largest error in every range, and every figure of the paper and the 400 x 400 phase diagrams
//! come out bit for bit as before.
//!
//! The polynomials are fdlibm's minimax ones (coefficients as in the `libm` crate), evaluated by
//! Horner's rule with fused multiply-adds.
//!
//! **Measured** against correctly rounded `sin` and `cos` (`dashu-float`, Ziv's method):
//! `cargo run --release -p rotor-chain-core --example sin_cos_ulp` (1.02e7 points over three ranges;
//! numbers in `docs/benchmarks.md`); `chain-core/tests/sin_cos.rs` repeats it on 1e5 points.

use super::Vector;

/// The largest `|x|` reduced in the lanes: `k` stays below `2^24`, where the reduction's error
/// (`|k| 2^-159`) is negligible and the rounding trick (`|x 2/pi| < 2^51`) holds with room.
pub(crate) const LIMIT: f64 = 16_777_216.0; // 2^24

/// Vector operations the polynomial needs beyond [`Vector`]: fused multiply-add and the few
/// bit manipulations on the quadrant.
pub(crate) trait Trig: Vector {
    /// `self * b + c` with one rounding.
    fn mul_add(self, b: Self, c: Self) -> Self;
    /// Applies the quadrant `k mod 4` (low bits of `t = x 2/pi + 1.5 * 2^52`) to the sine and
    /// cosine of the remainder: `(s, c)`, `(c, -s)`, `(-s, -c)` or `(-c, s)`.
    fn quadrant(t: Self, s: Self, c: Self) -> (Self, Self);
    /// `s` with the sign bit of `h` or-ed in.
    fn or_sign(h: Self, s: Self) -> Self;
    /// Whether any lane is NaN, infinite or beyond [`LIMIT`].
    fn any_outside(x: Self) -> bool;
    /// [`with_scalar_lanes`] compiled once for the level (a cold call, not inlined into every
    /// loop).
    fn with_scalar_lanes(x: Self) -> (Self, Self);
}

/// `1.5 * 2^52`: adding it rounds a number below `2^51` to an integer in the low mantissa bits.
const ROUND: f64 = 6_755_399_441_055_744.0;
const FRAC_2_PI: f64 = core::f64::consts::FRAC_2_PI;
/// `pi/2 = P1 + P2 + P3` to 159 bits: `P1` and `P3` the nearest doubles to what the previous ones
/// leave, `P2` the double below that, so that `P3 > 0` (module doc).
const P1: f64 = f64::from_bits(0x3FF9_21FB_5444_2D18);
const P2: f64 = f64::from_bits(0x3C91_A626_3314_5C06);
const P3: f64 = f64::from_bits(0x394C_1CD1_2902_4E09);

const S1: f64 = f64::from_bits(0xBFC5_5555_5555_5549);
const S2: f64 = f64::from_bits(0x3F81_1111_1110_F8A6);
const S3: f64 = f64::from_bits(0xBF2A_01A0_19C1_61D5);
const S4: f64 = f64::from_bits(0x3EC7_1DE3_57B1_FE7D);
const S5: f64 = f64::from_bits(0xBE5A_E5E6_8A2B_9CEB);
const S6: f64 = f64::from_bits(0x3DE5_D93A_5ACF_D57C);
const C1: f64 = f64::from_bits(0x3FA5_5555_5555_554C);
const C2: f64 = f64::from_bits(0xBF56_C16C_16C1_5177);
const C3: f64 = f64::from_bits(0x3EFA_01A0_19CB_1590);
const C4: f64 = f64::from_bits(0xBE92_7E4F_809C_52AD);
const C5: f64 = f64::from_bits(0x3E21_EE9E_BDB4_B1C4);
const C6: f64 = f64::from_bits(0xBDA8_FAE9_BE88_38D4);

/// Sine and cosine of every lane of `x`.
#[inline(always)]
pub(crate) fn sin_cos<V: Trig>(x: V) -> (V, V) {
    let r = reduce(x);
    if V::any_outside(x) {
        return V::with_scalar_lanes(x);
    }
    let [short] = polynomials([r]);
    short
}

/// [`sin_cos`] of two vectors, their polynomials interleaved: two independent chains of fused
/// multiply-adds per step instead of one. The same operations, so the same bits. AVX2 takes its
/// angles two vectors at a time this way ([`Vector::PAIR_TRIG`](super::Vector::PAIR_TRIG)):
/// with four lanes a vector's chain leaves the core idle waiting on its latency (60 angles
/// 87 -> 77 ns, docs/benchmarks.md, sixth round); at eight lanes it does not, and pairs gain
/// nothing there.
#[inline(always)]
pub(crate) fn sin_cos_pair<V: Trig>(x0: V, x1: V) -> ((V, V), (V, V)) {
    let (r0, r1) = (reduce(x0), reduce(x1));
    if V::any_outside(x0) | V::any_outside(x1) {
        return (sin_cos(x0), sin_cos(x1));
    }
    let [first, second] = polynomials([r0, r1]);
    (first, second)
}

/// A vector's angles reduced by `pi/2` (module doc).
#[derive(Clone, Copy)]
struct Reduced<V> {
    /// `x 2/pi + 1.5 * 2^52`: the quadrant `k mod 4` in its low bits.
    t: V,
    /// The remainder `x - k pi/2` in one double (`x` itself where `k = 0`, `-0` included).
    hi: V,
}

/// The reduction: `k = round(x 2/pi)`, `r = ((x - k P1) - k P2) - k P3`, each step one fused
/// multiply-add (the first exact).
#[inline(always)]
fn reduce<V: Trig>(x: V) -> Reduced<V> {
    let sp = V::splat;
    let t = x.mul_add(sp(FRAC_2_PI), sp(ROUND));
    let k = t - sp(ROUND);
    let r1 = (-k).mul_add(sp(P1), x);
    let r2 = (-k).mul_add(sp(P2), r1);
    Reduced { t, hi: (-k).mul_add(sp(P3), r2) }
}

/// The sine and cosine of the remainders, put in their quadrants: `K` vectors, their Horner steps
/// interleaved. Plain loops over `K`, no closures: a closure is a function of its own, compiled
/// without the caller's target features unless inlined.
#[inline(always)]
fn polynomials<V: Trig, const K: usize>(r: [Reduced<V>; K]) -> [(V, V); K] {
    let sp = V::splat;
    let mut z = [r[0].hi; K];
    let (mut ps, mut pc) = (z, z);
    for i in 0..K {
        z[i] = r[i].hi * r[i].hi;
        ps[i] = z[i].mul_add(sp(S6), sp(S5));
        pc[i] = z[i].mul_add(sp(C6), sp(C5));
    }
    for (s, c) in [(S4, C4), (S3, C3), (S2, C2), (S1, C1)] {
        for i in 0..K {
            ps[i] = z[i].mul_add(ps[i], sp(s));
            pc[i] = z[i].mul_add(pc[i], sp(c));
        }
    }
    let mut out = [(z[0], z[0]); K];
    for i in 0..K {
        let (hi, z) = (r[i].hi, z[i]);
        // `hi + hi z S(z)` has the sign of `hi` (|hi| <= pi/4), except that `-0 + 0` is `+0`:
        // the sign bit put back keeps `sin(-0) = -0` (one bitwise operation).
        let sin = V::or_sign(hi, (hi * z).mul_add(ps[i], hi));
        // cos(hi) = 1 + (z^2 C(z) - z/2): the bracket (|.| <= 0.31) rounds to 2^-55, a quarter
        // of an ulp of the result (>= 0.70).
        let cos = sp(1.0) + (z * z).mul_add(pc[i], sp(-0.5) * z);
        out[i] = V::quadrant(r[i].t, sin, cos);
    }
    out
}

/// A vector with a lane beyond [`LIMIT`], NaN or infinite: those lanes by the scalar `sin_cos`
/// (so they give exactly what the scalar path gives), the others by the polynomials, so an angle's
/// sine and cosine never depend on the angles beside it in a vector (a batch of configurations
/// laid back to back gets what each configuration gets alone).
#[inline(always)]
pub(crate) fn with_scalar_lanes<V: Trig>(x: V) -> (V, V) {
    let [(s, c)] = polynomials([reduce(x)]);
    scalar_lanes(x, s, c)
}

/// Replaces the lanes outside the polynomial's range by the scalar `sin_cos` (cold: the dynamics
/// never gets there, but a NaN or a huge angle must give what the scalar path gives).
#[cold]
#[inline(never)]
fn scalar_lanes<V: Trig>(x: V, s: V, c: V) -> (V, V) {
    let (mut xs, mut ss, mut cs) = ([0.0; 8], [0.0; 8], [0.0; 8]);
    x.store(&mut xs);
    s.store(&mut ss);
    c.store(&mut cs);
    for j in 0..V::LANES {
        if !(-LIMIT..=LIMIT).contains(&xs[j]) {
            (ss[j], cs[j]) = crate::math::sin_cos(xs[j]);
        }
    }
    (V::load(&ss), V::load(&cs))
}
