//! `sin_cos` over vector lanes: Cody-Waite reduction by `pi/2` into a double-double remainder,
//! then minimax polynomials on `[-pi/4, pi/4]` (fdlibm's coefficients).
//!
//! Written here because no well-kept crate does it on stable Rust with run-time dispatch: the
//! SLEEF port (`sleef`) needs nightly `portable_simd`, `pulp` and `wide` have no trigonometry
//! (and `wide` picks its instructions at compile time), and the f32 SIMD crates do not help.
//!
//! **Reduction.** `k = round(x 2/pi)` (by the `1.5 * 2^52` trick, which also leaves `k mod 4` in
//! the low mantissa bits), then `r = x - k pi/2` with `pi/2 = P1 + P2 + P3` (three doubles, 159
//! bits): `x - k P1` is exact with one fused multiply-add (both terms are multiples of
//! `min(ulp(x), 2^-52)` and the result is below 1), `k P2` is split exactly by a second one, and
//! the difference is carried as `hi + lo` by TwoSum. The error left is about `|k| 2^-159`, far
//! below an ulp of the smallest remainder a double below [`LIMIT`] can have, so the reduction
//! adds nothing measurable. Past `LIMIT` (and for NaN and the infinities) a lane is recomputed by
//! the scalar `crate::math::sin_cos`, so those angles give exactly what the scalar path gives.
//!
//! **The short path** ([`sin_cos`], every lane of ordinary size) keeps the remainder in one
//! double: `r1 = x - k P1` (exact, as above) and `hi = r1 - k P2` by one fused multiply-add,
//! which rounds once (half an ulp of `hi`) and leaves out `k P3` (below `2^24 2^-110 = 2^-86`).
//! Where `|hi| >= 2^-28` that is at most `0.5 + 2^-5` ulp of `hi` in relative terms, and the sine
//! and cosine of `hi` move by no more than their own ulp's worth of that. A vector with a lane
//! nearer a nonzero multiple of `pi/2` takes the double-double reduction ([`careful`]), as does
//! one with a lane beyond `LIMIT`; near 0 (`k = 0`, `hi == x`) the remainder is exact and stays
//! on the short path. Then, on `[-pi/4, pi/4]`:
//! - `sin hi = hi + hi z S(z)` with `z = hi^2`, and the sign bit of `hi` or-ed back in, so that
//!   `sin(-0) = -0` (the sum gives `+0` there, and otherwise already has the sign of `hi`);
//! - `cos hi = 1 + (z^2 C(z) - z/2)`: the bracket lies in `[-0.31, 0]` and rounds to within
//!   `2^-55`, a quarter of an ulp of the result (`>= 0.70`).
//!
//! That is 34 vector operations per group of lanes (AVX-512 build, counted in the disassembly)
//! instead of 46 with the remainder's low part, the rounding error of `1 - z/2` carried
//! (fdlibm's way) and a compare-and-blend for `-0`: 83 -> 62 ns for 60 angles. The largest error
//! measured stays 1 ulp; more points reach it (26 % instead of 6 % on `[-pi, pi]`).
//!
//! **The careful path** ([`careful`]): the remainder as `hi + lo` by TwoSum, and the polynomials
//! of fdlibm's `__kernel_sin` / `__kernel_cos` with the `lo` correction `sin(hi + lo) = sin hi +
//! lo (1 - hi^2/2)`, `cos(hi + lo) = cos hi - lo hi` to first order, and `cos hi = w + ((1 - w) -
//! hi^2/2) + hi^4 C(hi^2)` with `w = 1 - hi^2/2`. fdlibm bounds these below 1 ulp.
//!
//! The polynomials are fdlibm's minimax ones (coefficients as in the `libm` crate), evaluated by
//! Horner's rule with fused multiply-adds.
//!
//! **Measured** against correctly rounded `sin` and `cos` (`dashu-float`, Ziv's method):
//! `cargo run --release -p chain-core --example sin_cos_ulp` (1.02e7 points over three ranges;
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
    /// `x` in the lanes where `x == 0`, `s` elsewhere (so `sin(-0) = -0`).
    fn keep_zero(x: Self, s: Self) -> Self;
    /// `s` with the sign bit of `h` or-ed in.
    fn or_sign(h: Self, s: Self) -> Self;
    /// Whether any lane is NaN, infinite or beyond [`LIMIT`].
    fn any_outside(x: Self) -> bool;
    /// The lanes of `x` that need [`careful`] (bit `i` for lane `i`): NaN, infinite or beyond
    /// [`LIMIT`], or a short-path remainder `hi` with `|hi| < TINY` near a non-zero multiple of
    /// `pi/2` (`hi != x`). Near 0 (`k = 0`, so `hi == x`) the remainder is exact, so zero padding
    /// lanes and small angles stay on the short path.
    fn unusual(x: Self, hi: Self) -> u8;
    /// [`careful`] compiled once for the level (a cold call, not inlined into every loop).
    fn careful(x: Self) -> (Self, Self);
}

/// Below this `|hi|` (and `k != 0`) the short path's remainder, one double without `k P3`, is no
/// longer within a small fraction of an ulp of the true one: such lanes take [`careful`] (module
/// doc).
pub(crate) const TINY: f64 = 1.0 / 268_435_456.0; // 2^-28

/// `1.5 * 2^52`: adding it rounds a number below `2^51` to an integer in the low mantissa bits.
const ROUND: f64 = 6_755_399_441_055_744.0;
const FRAC_2_PI: f64 = core::f64::consts::FRAC_2_PI;
/// `pi/2 = P1 + P2 + P3` to 159 bits (each the nearest double to what the previous ones leave).
const P1: f64 = f64::from_bits(0x3FF9_21FB_5444_2D18);
const P2: f64 = f64::from_bits(0x3C91_A626_3314_5C07);
const P3: f64 = f64::from_bits(0xB91F_1976_B7ED_8FBC);

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
    let (t, hi) = reduce(x);
    if V::unusual(x, hi) != 0 {
        return V::careful(x);
    }
    let [short] = polynomials([t], [hi]);
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
    let ((t0, h0), (t1, h1)) = (reduce(x0), reduce(x1));
    if V::unusual(x0, h0) | V::unusual(x1, h1) != 0 {
        return (sin_cos(x0), sin_cos(x1));
    }
    let [first, second] = polynomials([t0, t1], [h0, h1]);
    (first, second)
}

/// The short path's reduction: `t = x 2/pi + 1.5 * 2^52` (the quadrant in its low bits) and the
/// remainder `hi` in one double.
#[inline(always)]
fn reduce<V: Trig>(x: V) -> (V, V) {
    let sp = V::splat;
    let t = x.mul_add(sp(FRAC_2_PI), sp(ROUND));
    let k = t - sp(ROUND);
    let r1 = (-k).mul_add(sp(P1), x);
    (t, (-k).mul_add(sp(P2), r1))
}

/// The short path's sine and cosine of the remainders `hi`, put in quadrants `t`: `K` vectors,
/// their Horner steps interleaved. Plain loops over `K`, no closures: a closure is a function of
/// its own, compiled without the caller's target features unless inlined.
#[inline(always)]
fn polynomials<V: Trig, const K: usize>(t: [V; K], hi: [V; K]) -> [(V, V); K] {
    let sp = V::splat;
    let mut z = hi;
    let (mut ps, mut pc) = (hi, hi);
    for i in 0..K {
        z[i] = hi[i] * hi[i];
        ps[i] = z[i].mul_add(sp(S6), sp(S5));
        pc[i] = z[i].mul_add(sp(C6), sp(C5));
    }
    for (s, c) in [(S4, C4), (S3, C3), (S2, C2), (S1, C1)] {
        for i in 0..K {
            ps[i] = z[i].mul_add(ps[i], sp(s));
            pc[i] = z[i].mul_add(pc[i], sp(c));
        }
    }
    let mut out = [(hi[0], hi[0]); K];
    for i in 0..K {
        let (hi, z) = (hi[i], z[i]);
        // `hi + hi z S(z)` has the sign of `hi` (|hi| <= pi/4), except that `-0 + 0` is `+0`:
        // the sign bit of `hi` put back keeps `sin(-0) = -0` (one bitwise operation).
        let sin = V::or_sign(hi, (hi * z).mul_add(ps[i], hi));
        // cos(hi) = 1 + (z^2 C(z) - z/2): the bracket (|.| <= 0.31) rounds to 2^-55, a quarter
        // of an ulp of the result (>= 0.70).
        let cos = sp(1.0) + (z * z).mul_add(pc[i], sp(-0.5) * z);
        out[i] = V::quadrant(t[i], sin, cos);
    }
    out
}

/// Every lane of `x` exactly, however near a multiple of `pi/2`: the double-double reduction,
/// and the scalar `sin_cos` for lanes beyond [`LIMIT`], NaN and the infinities. The lanes that
/// did not need it keep the short path's values, so an angle's sine and cosine never depend on
/// the angles beside it in a vector (a batch of configurations laid back to back gets what each
/// configuration gets alone).
#[inline(always)]
pub(crate) fn careful<V: Trig>(x: V) -> (V, V) {
    let (s, c) = reduced(x);
    let careful = if V::any_outside(x) { scalar_lanes(x, s, c) } else { (s, c) };
    let (t, hi) = reduce(x);
    let [short] = polynomials([t], [hi]);
    usual_lanes(V::unusual(x, hi), careful, short)
}

/// `careful` in the lanes set in `unusual`, `short` in the others (cold: a vector gets here only
/// with an unusual lane).
#[cold]
#[inline(never)]
fn usual_lanes<V: Trig>(unusual: u8, careful: (V, V), short: (V, V)) -> (V, V) {
    let mut lanes = [[0.0; 8]; 4];
    for (l, v) in lanes.iter_mut().zip([careful.0, careful.1, short.0, short.1]) {
        v.store(l);
    }
    let [mut ss, mut cs, short_s, short_c] = lanes;
    for j in (0..V::LANES).filter(|j| unusual & (1 << j) == 0) {
        (ss[j], cs[j]) = (short_s[j], short_c[j]);
    }
    (V::load(&ss), V::load(&cs))
}

/// The double-double reduction and fdlibm's kernels, for lanes inside the limit (assuming every
/// lane is).
#[inline(always)]
fn reduced<V: Trig>(x: V) -> (V, V) {
    let sp = V::splat;
    let t = x.mul_add(sp(FRAC_2_PI), sp(ROUND));
    let k = t - sp(ROUND);
    // r = x - k (P1 + P2 + P3) as hi + lo.
    let r1 = (-k).mul_add(sp(P1), x);
    let p2 = k * sp(P2);
    let p2_err = k.mul_add(sp(P2), -p2);
    let s = r1 - p2;
    let b = s - r1;
    let s_err = (r1 - (s - b)) - (p2 + b);
    let lo = (-k).mul_add(sp(P3), s_err - p2_err);
    let hi = s + lo;
    let lo = lo - (hi - s);

    let z = hi * hi;
    let w = z * z;
    // sin(hi + lo)
    let r = z.mul_add(z.mul_add(sp(S4), sp(S3)), sp(S2)) + z * w * z.mul_add(sp(S6), sp(S5));
    let v = z * hi;
    let sin = hi - ((z * (sp(0.5) * lo - v * r) - lo) - v * sp(S1));
    // cos(hi + lo)
    let r = z * z.mul_add(z.mul_add(sp(C3), sp(C2)), sp(C1))
        + w * w * z.mul_add(z.mul_add(sp(C6), sp(C5)), sp(C4));
    let hz = sp(0.5) * z;
    let one_hz = sp(1.0) - hz;
    let cos = one_hz + (((sp(1.0) - one_hz) - hz) + (z * r - hi * lo));

    let (sin, cos) = V::quadrant(t, sin, cos);
    (V::keep_zero(x, sin), cos)
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
