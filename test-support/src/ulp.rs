//! Shared by `tests/sin_cos.rs` (1e5 points) and `examples/sin_cos_ulp.rs` (1e7 points): the
//! correctly rounded reference, the ulp distance, and reproducible sample angles.

use std::cell::RefCell;

use dashu_float::round::mode::HalfEven;
use dashu_float::{ConstCache, Context, FBig};

use crate::random::SplitMix;

std::thread_local! {
    /// pi at the working precisions, kept between calls (recomputing it dominated the time).
    static CACHE: RefCell<ConstCache> = RefCell::new(ConstCache::default());
}

/// Correctly rounded `(sin x, cos x)` of a finite `x`: dashu-float evaluates them with Ziv's
/// method at the 53 bits of an `f64`, rounding to nearest, and the conversion back is exact.
pub fn reference(x: f64) -> (f64, f64) {
    let big = FBig::<HalfEven, 2>::try_from(x).expect("finite angle");
    let (s, c) =
        CACHE.with(|cache| Context::<HalfEven>::new(53).sin_cos(big.repr(), Some(&mut cache.borrow_mut())));
    let value = |r: Result<dashu_float::round::Rounded<FBig<HalfEven, 2>>, _>| {
        r.expect("finite").value().to_f64().value()
    };
    (value(s), value(c))
}

/// How many doubles lie between `a` and `b` (0 if equal; both finite).
pub fn ulps(a: f64, b: f64) -> u64 {
    fn ordered(x: f64) -> i64 {
        let bits = x.to_bits() as i64;
        if bits < 0 { i64::MIN - bits } else { bits }
    }
    ordered(a).abs_diff(ordered(b))
}

/// The ranges the error is measured on: the dynamics' angles, angles of rotors that turned many
/// times, and every magnitude up to the vector reduction's limit.
pub const RANGES: [(&str, Range); 3] = [
    ("[-pi, pi]", Range::Uniform(core::f64::consts::PI)),
    ("[-100, 100]", Range::Uniform(100.0)),
    ("|x| log-uniform in [2^-30, 2^24]", Range::LogUniform(-30.0, 24.0)),
];

#[derive(Clone, Copy)]
pub enum Range {
    /// Uniform in `[-h, h]`.
    Uniform(f64),
    /// `+-2^u` with `u` uniform in `[lo, hi]`.
    LogUniform(f64, f64),
}

/// `count` reproducible angles of `range` (splitmix64 from `seed`).
pub fn angles(range: Range, count: usize, seed: u64) -> Vec<f64> {
    let mut random = SplitMix(seed);
    (0..count)
        .map(|_| {
            let bits = random.bits();
            let u = SplitMix::unit(bits); // [0, 1)
            match range {
                Range::Uniform(h) => (2.0 * u - 1.0) * h,
                Range::LogUniform(lo, hi) => {
                    let sign = if bits & 1 == 0 { 1.0 } else { -1.0 };
                    sign * (lo + (hi - lo) * u).exp2()
                }
            }
        })
        .collect()
}

/// The largest ulp distance of `sin` and `cos` from the reference values, and where.
pub struct Worst {
    pub ulps: u64,
    pub angle: f64,
    /// Points at 1 ulp and at 2 or more.
    pub at_one: usize,
    pub at_two_or_more: usize,
}

pub fn worst(theta: &[f64], sin: &[f64], cos: &[f64], reference: &[(f64, f64)]) -> Worst {
    let mut w = Worst { ulps: 0, angle: 0.0, at_one: 0, at_two_or_more: 0 };
    for (i, &(rs, rc)) in reference.iter().enumerate() {
        let d = ulps(sin[i], rs).max(ulps(cos[i], rc));
        match d {
            0 => {}
            1 => w.at_one += 1,
            _ => w.at_two_or_more += 1,
        }
        if d > w.ulps {
            (w.ulps, w.angle) = (d, theta[i]);
        }
    }
    w
}
