//! Fused and vectorised evaluation against the scalar generated code, at every dispatch level
//! this machine supports (forced with `simd::with_level`).
//!
//! The reference is the macro's unrolled straight-line code: scalar `sin_cos` of the platform's
//! libm, one expression graph per chain. Compared with it, on random configurations (proptest):
//! `RuntimeChain` (harmonic and quartic laws) and the macro's looped kernel (harmonic and a custom
//! law using `exp`, `ln` and `powi(5)`), through every method of `ChainModel`, the fused ones
//! included. Chains of 70 rotors cross a driver chunk (64 springs) and leave a short last vector
//! at every lane width.
//!
//! Tolerance: 1e-13 of the largest entry of the same output. The levels' `sin_cos` differ by up
//! to 2 ulp, and a rotor's gradient entry is the near-cancelling sum of its two springs' terms,
//! so an entry near zero cannot be held to its own size; the kernel arithmetic itself is
//! bit-identical at every lane width.

mod common;

use common::Reference;
use proptest::prelude::*;
use rotor_chain::prelude::*;
use rotor_chain::simd::{self, Level};

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(29, k = 100.0), rotor(12, r = 0.7))]
struct HarmonicUnrolled;

#[rotor_chain(
    n = 70,
    r = 0.8,
    theta_bar = 0.58,
    k = 1.0e4,
    spring(29, k = 100.0),
    rotor(12, r = 0.7),
    unroll = 0
)]
struct HarmonicLooped;

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4, law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2))]
struct QuarticUnrolled;

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4,
              law = k * ((l - l0).powi(2) / 2.0 + 0.05 * (l - l0).powi(5) + 0.01 * ((l - l0).exp() - 1.0)
                         + 0.01 * (l / l0).ln().powi(2)))]
struct CustomUnrolled;

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0,
              law = k * ((l - l0).powi(2) / 2.0 + 0.05 * (l - l0).powi(5) + 0.01 * ((l - l0).exp() - 1.0)
                         + 0.01 * (l / l0).ln().powi(2)))]
struct CustomLooped;

fn harmonic_runtime() -> RuntimeChain {
    RuntimeChain::builder(70, 0.8, 1.0e4, 0.58).spring(29, Some(100.0), None).rotor(12, 0.7).build().unwrap()
}

fn quartic_runtime() -> RuntimeChain {
    RuntimeChain::builder(70, 0.8, 1.0e4, 0.58).law(Law::Quartic).build().unwrap()
}

fn levels() -> impl Iterator<Item = Level> {
    Level::ALL.into_iter().filter(|l| l.is_supported())
}

/// Every output of `ChainModel`, grouped by quantity (the fused ones as their parts).
fn outputs(m: &impl ChainModel, theta: &[f64]) -> Vec<(&'static str, Vec<f64>)> {
    let n = m.rotor_count();
    let (mut g, mut d, mut o) = (vec![0.0; n], vec![0.0; n], vec![0.0; n - 1]);
    let mut out = vec![("energy", vec![m.energy(theta)])];
    m.gradient_into(theta, &mut g);
    out.push(("gradient", g.clone()));
    m.tangent_stiffness_into(theta, &mut d, &mut o);
    out.extend([("stiffness.diag", d.clone()), ("stiffness.off", o.clone())]);
    m.material_stiffness_into(theta, &mut d, &mut o);
    out.extend([("material.diag", d.clone()), ("material.off", o.clone())]);
    m.stress_matrix_into(theta, &mut d, &mut o);
    out.extend([("stress.diag", d.clone()), ("stress.off", o.clone())]);
    m.spring_lengths_into(theta, &mut o);
    out.push(("lengths", o.clone()));
    m.tensions_into(theta, &mut o);
    out.push(("tensions", o.clone()));
    let mut right = vec![0.0; n - 1];
    m.compatibility_into(theta, &mut o, &mut right);
    out.extend([("compatibility.left", o.clone()), ("compatibility.right", right)]);
    let e = m.energy_and_gradient_into(theta, &mut g);
    out.extend([("fused E+g: energy", vec![e]), ("fused E+g: gradient", g.clone())]);
    let e = m.energy_gradient_stiffness_into(theta, &mut g, &mut d, &mut o);
    out.extend([
        ("fused E+g+K: energy", vec![e]),
        ("fused E+g+K: gradient", g),
        ("fused E+g+K: diag", d),
        ("fused E+g+K: off", o),
    ]);
    out
}

/// `candidate`'s outputs equal `reference`'s to 1e-13 of each output's largest entry.
#[track_caller]
fn assert_agree(reference: &[(&str, Vec<f64>)], candidate: &[(&str, Vec<f64>)], what: &str) {
    assert_eq!(reference.len(), candidate.len());
    for ((name, a), (_, b)) in reference.iter().zip(candidate) {
        let scale = a.iter().fold(f64::MIN_POSITIVE, |s, x| s.max(x.abs()));
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(
                (x - y).abs() <= 1e-13 * scale,
                "{what}: {name}[{i}]: {x} vs {y} (difference {:e}, scale {scale:e})",
                (x - y).abs()
            );
        }
    }
}

/// The fused outputs of the reference itself equal its separate outputs (the defaults or the
/// unrolled overrides), and every level of `candidate` agrees with the reference.
fn check(reference: &impl ChainModel, candidate: &impl ChainModel, theta: &[f64], what: &str) {
    let expected = outputs(reference, theta);
    for (name, fused) in [("fused E+g: energy", "energy"), ("fused E+g+K: energy", "energy")] {
        let get = |n: &str| expected.iter().find(|(m, _)| *m == n).unwrap().1[0];
        let (a, b) = (get(name), get(fused));
        assert!((a - b).abs() <= 1e-13 * b.abs(), "{what}: reference {name} {a} vs {b}");
    }
    for level in levels() {
        let got = simd::with_level(level, || outputs(candidate, theta)).unwrap();
        assert_agree(&expected, &got, &format!("{what} at {}", level.name()));
    }
}

fn angles() -> impl Strategy<Value = Vec<f64>> {
    // |theta| <= 1.2 keeps every spring longer than 0.5 a (no coincident tips).
    proptest::collection::vec(-1.2f64..1.2, 70)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 24,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xf05e_d5d1),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn runtime_harmonic_matches_the_unrolled_code(theta in angles()) {
        check(&HarmonicUnrolled, &harmonic_runtime(), &theta, "runtime harmonic");
    }

    #[test]
    fn looped_harmonic_matches_the_unrolled_code(theta in angles()) {
        check(&HarmonicUnrolled, &HarmonicLooped, &theta, "looped harmonic");
    }

    #[test]
    fn runtime_quartic_matches_the_unrolled_code(theta in angles()) {
        check(&QuarticUnrolled, &quartic_runtime(), &theta, "runtime quartic");
    }

    #[test]
    fn looped_custom_law_matches_the_unrolled_code(theta in angles()) {
        check(&CustomUnrolled, &CustomLooped, &theta, "looped custom law");
    }
}

/// Chains of every short length (all vector tails), across several chunks, and the smallest:
/// every level against the scalar level, which against num-dual autodiff of the independent
/// Cartesian reference.
#[test]
fn every_length_agrees_across_levels_and_with_autodiff() {
    for n in (2..=20).chain([63, 64, 65, 66, 129, 200]) {
        let chain = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().unwrap();
        let theta: Vec<f64> =
            (0..n).map(|i| 0.58 * (0.7 * i as f64).cos() + 0.1 * (1.3 * i as f64).sin()).collect();
        let scalar = simd::with_level(Level::Scalar, || outputs(&chain, &theta)).unwrap();
        for level in levels() {
            let got = simd::with_level(level, || outputs(&chain, &theta)).unwrap();
            assert_agree(&scalar, &got, &format!("n = {n} at {}", level.name()));
            let reference = Reference::uniform(n, 0.58);
            let exact = reference.gradient(&theta);
            let mut e_and_g = vec![0.0; n];
            let energy =
                simd::with_level(level, || chain.energy_and_gradient_into(&theta, &mut e_and_g)).unwrap();
            common::assert_close(
                energy,
                reference.energy(&theta),
                1e-11,
                &format!("n = {n}: energy vs reference"),
            );
            // Entries are near-cancelling sums of two springs' terms: measured against the largest.
            let scale = exact.iter().fold(1.0f64, |s, x| s.max(x.abs()));
            for i in 0..n {
                let (x, y) = (e_and_g[i], exact[i]);
                assert!(
                    (x - y).abs() <= 1e-11 * scale,
                    "n = {n}: dV/dtheta_{i}: {x} vs num-dual {y} (scale {scale})"
                );
            }
        }
    }
}
