//! The simplifier's contract (module doc of `graph.rs`), checked against direct `f64` evaluation of
//! the expression as written: every rewrite is exact for every operand, including NaN, the
//! infinities, zeros and subnormal numbers, except the two documented relaxations (the sign of a
//! zero; power-of-two factors moved across an overflowing or subnormal intermediate), which are
//! shown to be what they say.
//!
//! The direct expressions are written exactly as the graph is built (`-1.0 * x`, `x / 1.0`),
//! since the point is to compare the two.
#![allow(clippy::neg_multiply, clippy::identity_op)]

use chain_symbolic::{Graph, Id};

/// Operand values that exercise IEEE special cases: NaN, infinities, zeros, subnormals, numbers
/// near overflow, negatives (for `sqrt` and `ln`), and the overflow threshold of `exp`.
const SPECIAL: [f64; 22] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    5e-324,
    -5e-324,
    1e-310,
    f64::MIN_POSITIVE,
    1e-300,
    0.5,
    1.0,
    -1.0,
    2.0,
    -2.0,
    3.7,
    -0.3,
    700.0,
    710.0,
    -745.5,
    1e300,
    -1e300,
    f64::MAX,
];

/// Same value, or both NaN; zeros of either sign are equal (relaxation 1).
fn same(a: f64, b: f64) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}

type Build = fn(&mut Graph, Id, Id) -> Id;
type Direct = fn(f64, f64) -> f64;

fn check(what: &str, build: Build, direct: Direct, points: &[f64]) {
    let mut g = Graph::new();
    let (x, y) = (g.symbol("x"), g.symbol("y"));
    let e = build(&mut g, x, y);
    for &vx in points {
        for &vy in points {
            let simplified = g.eval(e, &|name| if name == "x" { vx } else { vy });
            let written = direct(vx, vy);
            assert!(
                same(simplified, written),
                "{what} at x = {vx:e}, y = {vy:e}: {simplified:e} != {written:e}"
            );
        }
    }
}

#[test]
fn identities_that_fail_somewhere_are_not_applied() {
    let cases: [(&str, Build, Direct); 10] = [
        (
            "sqrt(x)^2 (NaN for x < 0, not x)",
            |g, x, _| {
                let r = g.sqrt(x);
                g.powi(r, 2)
            },
            |x, _| x.sqrt().powi(2),
        ),
        (
            "0 x",
            |g, x, _| {
                let z = g.zero();
                g.mul(z, x)
            },
            |x, _| 0.0 * x,
        ),
        ("x - x", |g, x, _| g.sub(x, x), |x, _| x - x),
        ("x / x", |g, x, _| g.div(x, x), |x, _| x / x),
        (
            "0 / x",
            |g, x, _| {
                let z = g.zero();
                g.div(z, x)
            },
            |x, _| 0.0 / x,
        ),
        (
            "ln(exp(x))",
            |g, x, _| {
                let e = g.exp(x);
                g.ln(e)
            },
            |x, _| x.exp().ln(),
        ),
        (
            "(x^-1)^-1",
            |g, x, _| {
                let i = g.powi(x, -1);
                g.powi(i, -1)
            },
            |x, _| x.powi(-1).powi(-1),
        ),
        (
            "(x^2)^3",
            |g, x, _| {
                let s = g.powi(x, 2);
                g.powi(s, 3)
            },
            |x, _| x.powi(2).powi(3),
        ),
        (
            "3 x + 5 x",
            |g, x, _| {
                let (three, five) = (g.constant(3.0), g.constant(5.0));
                let (a, b) = (g.mul(three, x), g.mul(five, x));
                g.add(a, b)
            },
            |x, _| 3.0 * x + 5.0 * x,
        ),
        (
            "x y - x y + y",
            |g, x, y| {
                let p = g.mul(x, y);
                let d = g.sub(p, p);
                g.add(d, y)
            },
            |x, y| (x * y - x * y) + y,
        ),
    ];
    for (what, build, direct) in cases {
        check(what, build, direct, &SPECIAL);
    }
}

#[test]
fn exact_rewrites_agree_everywhere() {
    let cases: [(&str, Build, Direct); 15] = [
        (
            "x + 0",
            |g, x, _| {
                let z = g.zero();
                g.add(x, z)
            },
            |x, _| x + 0.0,
        ),
        (
            "0 - x",
            |g, x, _| {
                let z = g.zero();
                g.sub(z, x)
            },
            |x, _| 0.0 - x,
        ),
        (
            "1 x / 1",
            |g, x, _| {
                let one = g.one();
                let p = g.mul(one, x);
                g.div(p, one)
            },
            |x, _| 1.0 * x / 1.0,
        ),
        (
            "-1 x",
            |g, x, _| {
                let m = g.constant(-1.0);
                g.mul(m, x)
            },
            |x, _| -1.0 * x,
        ),
        (
            "-(-x) - (-y)",
            |g, x, y| {
                let (nx, ny) = (g.neg(x), g.neg(y));
                let nnx = g.neg(nx);
                g.sub(nnx, ny)
            },
            |x, y| -(-x) - (-y),
        ),
        (
            "-(x - y)",
            |g, x, y| {
                let d = g.sub(x, y);
                g.neg(d)
            },
            |x, y| -(x - y),
        ),
        (
            "(-x) y / (-y)",
            |g, x, y| {
                let nx = g.neg(x);
                let ny = g.neg(y);
                let p = g.mul(nx, y);
                g.div(p, ny)
            },
            |x, y| (-x) * y / (-y),
        ),
        (
            "(-x)^2 + (-x)^3",
            |g, x, _| {
                let nx = g.neg(x);
                let (a, b) = (g.powi(nx, 2), g.powi(nx, 3));
                g.add(a, b)
            },
            |x, _| (-x).powi(2) + (-x).powi(3),
        ),
        ("x x", |g, x, _| g.mul(x, x), |x, _| x * x),
        ("x + x", |g, x, _| g.add(x, x), |x, _| x + x),
        (
            "x / 4",
            |g, x, _| {
                let four = g.constant(4.0);
                g.div(x, four)
            },
            |x, _| x / 4.0,
        ),
        (
            "x / 3",
            |g, x, _| {
                let three = g.constant(3.0);
                g.div(x, three)
            },
            |x, _| x / 3.0,
        ),
        ("x^0 (1 also for NaN, as IEEE pown)", |g, x, _| g.powi(x, 0), |x, _| x.powi(0)),
        ("x^1", |g, x, _| g.powi(x, 1), |x, _| x.powi(1)),
        (
            "sqrt(x) - ln(y) + exp(x) sin(y) / cos(x)",
            |g, x, y| {
                let (r, l) = (g.sqrt(x), g.ln(y));
                let (e, s, c) = (g.exp(x), g.sin(y), g.cos(x));
                let d = g.sub(r, l);
                let p = g.mul(e, s);
                let q = g.div(p, c);
                g.add(d, q)
            },
            |x, y| x.sqrt() - y.ln() + x.exp() * y.sin() / x.cos(),
        ),
    ];
    for (what, build, direct) in cases {
        check(what, build, direct, &SPECIAL);
    }
}

#[test]
fn power_of_two_factors_move_exactly_where_nothing_overflows_or_is_subnormal() {
    // Relaxation 2: exact unless an intermediate overflows or is subnormal in one of the orders.
    let moderate = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, 1e-200, -0.3, 1.0, 3.7, -2.0, 1e200];
    let cases: [(&str, Build, Direct); 7] = [
        (
            "0.3 x + 0.3 x = 2 (0.3 x) = 0.6 x",
            |g, x, _| {
                let c = g.constant(0.3);
                let a = g.mul(c, x);
                g.add(a, a)
            },
            |x, _| 0.3 * x + 0.3 * x,
        ),
        (
            "2 (3 x)",
            |g, x, _| {
                let (two, three) = (g.constant(2.0), g.constant(3.0));
                let t = g.mul(three, x);
                g.mul(two, t)
            },
            |x, _| 2.0 * (3.0 * x),
        ),
        (
            "(0.5 x) y",
            |g, x, y| {
                let half = g.constant(0.5);
                let h = g.mul(half, x);
                g.mul(h, y)
            },
            |x, y| (0.5 * x) * y,
        ),
        (
            "(0.5 x) / y",
            |g, x, y| {
                let half = g.constant(0.5);
                let h = g.mul(half, x);
                g.div(h, y)
            },
            |x, y| (0.5 * x) / y,
        ),
        (
            "0.5 / x",
            |g, x, _| {
                let half = g.constant(0.5);
                g.div(half, x)
            },
            |x, _| 0.5 / x,
        ),
        (
            "2 x + 2 y",
            |g, x, y| {
                let two = g.constant(2.0);
                let (a, b) = (g.mul(two, x), g.mul(two, y));
                g.add(a, b)
            },
            |x, y| 2.0 * x + 2.0 * y,
        ),
        (
            "0.25 x - (-0.25) y",
            |g, x, y| {
                let (q, mq) = (g.constant(0.25), g.constant(-0.25));
                let (a, b) = (g.mul(q, x), g.mul(mq, y));
                g.sub(a, b)
            },
            |x, y| 0.25 * x - (-0.25) * y,
        ),
    ];
    for (what, build, direct) in cases {
        check(what, build, direct, &moderate);
    }
    // And where an intermediate of the written order overflows, the moved factor gives the
    // finite result: (2 x) y with x = 1e308, y = 0.25 is inf as written, 5e307 simplified.
    let mut g = Graph::new();
    let (x, y) = (g.symbol("x"), g.symbol("y"));
    let two = g.constant(2.0);
    let tx = g.mul(two, x);
    let e = g.mul(tx, y);
    let simplified = g.eval(e, &|n| if n == "x" { 1e308 } else { 0.25 });
    assert_eq!((2.0 * 1e308) * 0.25, f64::INFINITY);
    assert_eq!(simplified, 5e307);
}

#[test]
fn the_sign_of_zero_is_the_one_relaxation_for_zeros() {
    // Relaxation 1: 1 / (x + 0) at x = -0 is +inf as written (-0 + 0 = +0), -inf simplified.
    let mut g = Graph::new();
    let x = g.symbol("x");
    let (zero, one) = (g.zero(), g.one());
    let s = g.add(x, zero);
    let e = g.div(one, s);
    assert_eq!(1.0 / (-0.0f64 + 0.0), f64::INFINITY);
    assert_eq!(g.eval(e, &|_| -0.0), f64::NEG_INFINITY);
    // Any other x agrees.
    for v in SPECIAL {
        assert!(same(g.eval(e, &|_| v), 1.0 / (v + 0.0)), "{v}");
    }
}

#[test]
fn a_compressed_spring_under_a_root_stays_nan() {
    // The case: energy sqrt(l - l0)^2 of a compressed spring (l < l0) is NaN, not l - l0.
    let mut g = Graph::new();
    let (l, l0) = (g.symbol("l"), g.symbol("l0"));
    let d = g.sub(l, l0);
    let r = g.sqrt(d);
    let e = g.powi(r, 2);
    let energy = g.eval(e, &|n| if n == "l" { 1.2 } else { 1.67 });
    assert!(energy.is_nan(), "{energy}");
}

#[test]
fn every_i32_exponent_builds_exactly_and_differentiates() {
    let mut g = Graph::new();
    let x = g.symbol("x");
    let cos_710 = 710f64.cos();
    for n in [i32::MIN, i32::MIN + 1, -1025, -3, 2, 1024, i32::MAX] {
        let p = g.powi(x, n);
        let d = chain_symbolic::diff::diff(&mut g, p, x);
        for v in [1.0, -1.0, 1.0 + 1e-12, 1.0 - 1e-15, cos_710, -cos_710, 2.0, 0.5, 0.0, f64::NAN] {
            // Bit for bit what `powi` gives, i32::MIN included (built as 1 / (x^(2^30))^2).
            assert!(same(g.eval(p, &|_| v), v.powi(n)), "x^{n} at {v}");
        }
        assert_eq!(g.eval(d, &|_| 1.0), f64::from(n), "d x^{n} / dx at 1");
    }
}
