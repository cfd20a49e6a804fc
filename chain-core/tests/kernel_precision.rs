//! The rendered spring kernels against a 256-bit evaluation of the same springs (dashu-float):
//! energy, gradient and Hessian block of the harmonic and the quartic law, on random springs
//! near and far from their rest lengths.
//!
//! The reference takes the kernel's nine inputs `[s1, c1, s2, c2, a, r1, r2, k, l0]` as exact
//! numbers (with `ds/dtheta = c`, `dc/dtheta = -s`, as the engine differentiates) and writes
//! the energy through `q = l^2` (paper Eq. `eq:discretelagrangian` for the harmonic law, Eq.
//! `eq:discretepotential` for the quartic one):
//! `g1 = -2 u1 E_q`, `g2 = 2 u2 E_q`, `H_ij = E_q q_ij + E_qq q_i q_j`, with
//! `u1 = dx r1 c1 + dy r1 s1`, `u2 = dx r2 c2 - dy r2 s2`, `q_1 = -2 u1`, `q_2 = 2 u2` and
//! the second derivatives of `q` written out below. That is an independent derivation (by
//! hand, in a test), not the engine's graph.
//!
//! Each output must lie within `K` roundings of a first-order bound of what rounding the
//! inputs' own magnitudes allows ([`error_scales`]): for instance the energy's error scale is
//! `k |l - l0| (|dx| + |dy| + l0)` because `l - l0` cancels. A kernel that lost digits to a
//! poorly chosen formula (a cancellation the problem does not have) would exceed it.

use chain_core::kernel::{SpringFn, harmonic, quartic};
use test_support::dashu_float::FBig;
use test_support::dashu_float::round::mode::HalfEven;
use test_support::random::SplitMix;

type Big = FBig<HalfEven, 2>;

/// Bits of the reference.
const PRECISION: usize = 256;
/// The unit roundoff of `f64`.
const EPS: f64 = f64::EPSILON / 2.0;
/// Roundings allowed per unit of the bound's scale. The kernels' worst over 320 000 springs
/// per law (40 seeds of this test) was 2.23 (harmonic dE/dtheta1) and 1.67 (quartic H12).
const K: f64 = 4.0;

fn big(x: f64) -> Big {
    Big::try_from(x).expect("finite").with_precision(PRECISION).value()
}

fn float(x: &Big) -> f64 {
    x.to_f64().value()
}

/// The two laws as functions of `q = l^2`: `E`, `dE/dq`, `d2E/dq2` in high precision.
#[derive(Clone, Copy, Debug)]
enum Law {
    Harmonic,
    Quartic,
}

impl Law {
    fn of_q(self, q: &Big, k: &Big, l0: &Big) -> [Big; 3] {
        let (two, four, eight) = (big(2.0), big(4.0), big(8.0));
        match self {
            Law::Harmonic => {
                // E = k (l - l0)^2 / 2, E_q = k (l - l0) / (2 l), E_qq = k l0 / (4 l^3).
                let l = q.sqrt();
                let d = &l - l0;
                let e = k * &d * &d / &two;
                let eq = k * &d / (&two * &l);
                let eqq = k * l0 / (&four * &l * q);
                [e, eq, eqq]
            }
            Law::Quartic => {
                // E = k (q - l0^2)^2 / (8 l0^2), E_q = k (q - l0^2) / (4 l0^2), E_qq = k / (4 l0^2).
                let l02 = l0 * l0;
                let w = q - &l02;
                let e = k * &w * &w / (&eight * &l02);
                let eq = k * &w / (&four * &l02);
                let eqq = k / (&four * &l02);
                [e, eq, eqq]
            }
        }
    }

    /// `[E, g1, g2, H11, H12, H22]` of the kernel.
    fn kernel(self, x: [f64; 9]) -> [f64; 6] {
        match self {
            Law::Harmonic => harmonic::EnergyGradientHessian::eval::<f64>(x),
            Law::Quartic => quartic::EnergyGradientHessian::eval::<f64>(x),
        }
    }

    /// `[E, g1, g2]` of the fused energy + gradient kernel.
    fn kernel_eg(self, x: [f64; 9]) -> [f64; 3] {
        match self {
            Law::Harmonic => harmonic::EnergyGradient::eval::<f64>(x),
            Law::Quartic => quartic::EnergyGradient::eval::<f64>(x),
        }
    }
}

/// `[E, g1, g2, H11, H12, H22]` at 256 bits.
fn reference(law: Law, x: [f64; 9]) -> [f64; 6] {
    let [s1, c1, s2, c2, a, r1, r2, k, l0] = x.map(big);
    let two = big(2.0);
    let dx = &a + &r2 * &s2 - &r1 * &s1;
    let dy = &r1 * &c1 + &r2 * &c2;
    let q = &dx * &dx + &dy * &dy;
    let u1 = &dx * &r1 * &c1 + &dy * &r1 * &s1;
    let u2 = &dx * &r2 * &c2 - &dy * &r2 * &s2;
    let (q1, q2) = (-(&two * &u1), &two * &u2);
    // Second derivatives of q = dx^2 + dy^2 (dx' = -r1 c1, dx'' = r1 s1, dy' = -r1 s1,
    // dy'' = -r1 c1 in theta1; dx' = r2 c2, dx'' = -r2 s2, dy' = -r2 s2, dy'' = -r2 c2 in theta2).
    let q11 = &two * (&r1 * &r1 * (&c1 * &c1 + &s1 * &s1) + &dx * &r1 * &s1 - &dy * &r1 * &c1);
    let q12 = &two * &r1 * &r2 * (&s1 * &s2 - &c1 * &c2);
    let q22 = &two * (&r2 * &r2 * (&c2 * &c2 + &s2 * &s2) - &dx * &r2 * &s2 - &dy * &r2 * &c2);
    let [e, eq, eqq] = law.of_q(&q, &k, &l0);
    [
        float(&e),
        float(&(&q1 * &eq)),
        float(&(&q2 * &eq)),
        float(&(&eq * &q11 + &eqq * &q1 * &q1)),
        float(&(&eq * &q12 + &eqq * &q1 * &q2)),
        float(&(&eq * &q22 + &eqq * &q2 * &q2)),
    ]
}

/// First-order error scales of `[E, g1, g2, H11, H12, H22]` (in units of one rounding, `EPS`):
/// each input of an operation carries the rounding of its own magnitude, and the magnitudes
/// are those of the terms (`dx` is a sum of `a`, `r2 s2`, `r1 s1`: its scale is their absolute
/// sum). Constants (`c`) are left out: `K` covers them. The scales are the problem's, not the
/// kernel's formula's: a formula that rounds where the problem does not cancel exceeds them.
fn error_scales(law: Law, x: [f64; 9]) -> [f64; 6] {
    let [s1, c1, s2, c2, a, r1, r2, k, l0] = x;
    let dx = a + r2 * s2 - r1 * s1;
    let dy = r1 * c1 + r2 * c2;
    let (dxm, dym) = (a.abs() + (r2 * s2).abs() + (r1 * s1).abs(), (r1 * c1).abs() + (r2 * c2).abs());
    let q = dx * dx + dy * dy;
    let l = q.sqrt();
    // Scale of q's rounding, and of l's (half q's relative one, plus its own).
    let qm = 2.0 * (dx.abs() * dxm + dy.abs() * dym) + q;
    let lm = qm / (2.0 * l) + l;
    let (eq, eqq, de, deq, deqq) = match law {
        Law::Harmonic => {
            let d = l - l0;
            let f = k * d / l;
            let dd = lm + l0.abs(); // l - l0 cancels: its error scale is that of l and l0
            let e = 0.5 * k * d * d;
            let eqq = k * l0 / (4.0 * l * q);
            (f / 2.0, eqq, k * d.abs() * dd + e, k * dd / l + f.abs(), eqq * lm / l)
        }
        Law::Quartic => {
            let l02 = l0 * l0;
            let w = q - l02;
            let wm = qm + l02;
            let c = k / (4.0 * l02);
            (c * w, c, c * w.abs() * wm + c * w * w / 2.0, c * wm + (c * w).abs(), c)
        }
    };
    let (u1, u2) = (dx * r1 * c1 + dy * r1 * s1, dx * r2 * c2 - dy * r2 * s2);
    // u's error: its products' magnitudes, with dx and dy carrying theirs.
    let um1 = (r1 * c1).abs() * dxm + (r1 * s1).abs() * dym + (dx * r1 * c1).abs() + (dy * r1 * s1).abs();
    let um2 = (r2 * c2).abs() * dxm + (r2 * s2).abs() * dym + (dx * r2 * c2).abs() + (dy * r2 * s2).abs();
    let q11 = 2.0 * (r1 * r1 + dx * r1 * s1 - dy * r1 * c1);
    let q12 = 2.0 * r1 * r2 * (s1 * s2 - c1 * c2);
    let q22 = 2.0 * (r2 * r2 - dx * r2 * s2 - dy * r2 * c2);
    let qm11 = 2.0
        * (r1 * r1
            + dxm * (r1 * s1).abs()
            + (dx * r1 * s1).abs()
            + dym * (r1 * c1).abs()
            + (dy * r1 * c1).abs());
    let qm12 = 2.0 * (r1 * r2).abs() * ((s1 * s2).abs() + (c1 * c2).abs());
    let qm22 = 2.0
        * (r2 * r2
            + dxm * (r2 * s2).abs()
            + (dx * r2 * s2).abs()
            + dym * (r2 * c2).abs()
            + (dy * r2 * c2).abs());
    let g = |u: f64, um: f64| 2.0 * (u.abs() * deq + eq.abs() * um);
    let h = |qij: f64, qmij: f64, ui: f64, umi: f64, uj: f64, umj: f64| {
        deq * qij.abs()
            + eq.abs() * qmij
            + 4.0 * deqq * (ui * uj).abs()
            + 4.0 * eqq.abs() * (ui.abs() * umj + uj.abs() * umi)
    };
    [
        de,
        g(u1, um1),
        g(u2, um2),
        h(q11, qm11, u1, um1, u1, um1),
        h(q12, qm12, u1, um1, u2, um2),
        h(q22, qm22, u2, um2, u2, um2),
    ]
}

/// Random springs: angles anywhere, rotor lengths 0.3 – 1.5, spacing 0.5 – 2, stiffness
/// 0.1 – 1e4 (log-uniform); half of them within 1e-12 – 1e-2 of their rest length (where
/// `l - l0` cancels), half with a rest length anywhere in 0.1 – 3.
fn springs(count: usize, seed: u64) -> Vec<[f64; 9]> {
    let mut u = SplitMix(seed);
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let (t1, t2) = (u.range(-3.2, 3.2), u.range(-3.2, 3.2));
        let ((s1, c1), (s2, c2)) = (t1.sin_cos(), t2.sin_cos());
        let (a, r1, r2) = (u.range(0.5, 2.0), u.range(0.3, 1.5), u.range(0.3, 1.5));
        let k = 10f64.powf(u.range(-1.0, 4.0));
        let dx = a + r2 * s2 - r1 * s1;
        let dy = r1 * c1 + r2 * c2;
        let l = (dx * dx + dy * dy).sqrt();
        if l < 1e-3 {
            continue; // a spring of no length has no direction: outside every law's domain
        }
        let l0 = if out.len() % 2 == 0 {
            let sign = if u.uniform() < 0.5 { -1.0 } else { 1.0 };
            l * (1.0 + sign * 10f64.powf(u.range(-12.0, -2.0)))
        } else {
            u.range(0.1, 3.0)
        };
        out.push([s1, c1, s2, c2, a, r1, r2, k, l0]);
    }
    out
}

const NAMES: [&str; 6] = ["E", "dE/dtheta1", "dE/dtheta2", "H11", "H12", "H22"];

/// The largest error of each output over `springs`, in roundings of its bound's scale.
fn worst(law: Law, springs: &[[f64; 9]]) -> [(f64, [f64; 9]); 6] {
    let mut worst = [(0.0, [0.0; 9]); 6];
    for &x in springs {
        let (got, fused, exact, scale) =
            (law.kernel(x), law.kernel_eg(x), reference(law, x), error_scales(law, x));
        // The fused energy + gradient kernel gives the same bits as the first three outputs.
        assert_eq!(fused.map(f64::to_bits), [got[0], got[1], got[2]].map(f64::to_bits), "{law:?} at {x:?}");
        for i in 0..6 {
            let ratio = (got[i] - exact[i]).abs() / (EPS * scale[i]);
            assert!(ratio.is_finite(), "{law:?} {}: {} against {} at {x:?}", NAMES[i], got[i], exact[i]);
            if ratio > worst[i].0 {
                worst[i] = (ratio, x);
            }
        }
    }
    worst
}

fn check(law: Law, seed: u64) {
    let springs = springs(8_000, seed);
    let worst = worst(law, &springs);
    for (i, (ratio, x)) in worst.iter().enumerate() {
        println!("{law:?} {}: worst {ratio:.2} roundings of its scale", NAMES[i]);
        assert!(*ratio <= K, "{law:?} {}: {ratio:.1} roundings of its scale (bound {K}) at {x:?}", NAMES[i]);
    }
}

#[test]
fn harmonic_kernels_are_as_accurate_as_their_inputs_allow() {
    check(Law::Harmonic, 0x4A52_0001);
}

#[test]
fn quartic_kernels_are_as_accurate_as_their_inputs_allow() {
    check(Law::Quartic, 0x4A52_0002);
}

/// The bound is not so loose that anything passes: the harmonic energy written as the quartic
/// expansion `k (q - 2 l l0 + l0^2) / 2` (the same function, a cancellation the problem does not
/// have near rest length) exceeds it.
#[test]
fn a_formula_that_loses_digits_exceeds_the_bound() {
    let springs = springs(2_000, 0x4A52_0003);
    let mut worst: f64 = 0.0;
    for &x in &springs {
        let [s1, c1, s2, c2, a, r1, r2, k, l0] = x;
        let dx = a + r2 * s2 - r1 * s1;
        let dy = r1 * c1 + r2 * c2;
        let q = dx * dx + dy * dy;
        let careless = 0.5 * k * (q - 2.0 * q.sqrt() * l0 + l0 * l0);
        let exact = reference(Law::Harmonic, x)[0];
        worst = worst.max((careless - exact).abs() / (EPS * error_scales(Law::Harmonic, x)[0]));
    }
    assert!(
        worst > 100.0 * K,
        "the expanded energy stays within {worst:.1} roundings: the bound cannot tell"
    );
}
