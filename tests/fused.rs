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

#[rotor_chain(
    n = 70,
    r = 0.8,
    theta_bar = 0.58,
    k = 1.0e4,
    unroll = 128,
    spring(29, k = 100.0),
    rotor(12, r = 0.7)
)]
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

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 128, law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2))]
struct QuarticUnrolled;

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 128,
              law = k * ((l - l0).powi(2) / 2.0 + 0.05 * (l - l0).powi(5) + 0.01 * ((l - l0).exp() - 1.0)
                         + 0.01 * (l / l0).ln().powi(2)))]
struct CustomUnrolled;

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0,
              law = k * ((l - l0).powi(2) / 2.0 + 0.05 * (l - l0).powi(5) + 0.01 * ((l - l0).exp() - 1.0)
                         + 0.01 * (l / l0).ln().powi(2)))]
struct CustomLooped;

fn harmonic_runtime() -> RuntimeChain {
    RuntimeChain::builder(70, 0.8, 1.0e4, 0.58).spring_constant(29, 100.0).rotor(12, 0.7).build().unwrap()
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
    let (mut g, mut k, mut o) = (vec![0.0; n], vec![0.0; 2 * n - 1], vec![0.0; n - 1]);
    let mut out = vec![("energy", vec![m.energy(theta)])];
    m.gradient_into(theta, &mut g);
    out.push(("gradient", g.clone()));
    m.tangent_stiffness_into(theta, &mut k);
    out.push(("stiffness (diag, off)", k.clone()));
    m.material_stiffness_into(theta, &mut k);
    out.push(("material (diag, off)", k.clone()));
    m.stress_matrix_into(theta, &mut k);
    out.push(("stress (diag, off)", k.clone()));
    m.spring_lengths_into(theta, &mut o);
    out.push(("lengths", o.clone()));
    m.tensions_into(theta, &mut o);
    out.push(("tensions", o.clone()));
    let mut c = vec![0.0; 2 * (n - 1)];
    m.compatibility_into(theta, &mut c);
    out.push(("compatibility (left, right)", c));
    let e = m.energy_and_gradient_into(theta, &mut g);
    out.extend([("fused E+g: energy", vec![e]), ("fused E+g: gradient", g.clone())]);
    let e = m.energy_gradient_stiffness_into(theta, &mut g, &mut k);
    out.extend([
        ("fused E+g+K: energy", vec![e]),
        ("fused E+g+K: gradient", g),
        ("fused E+g+K: (diag, off)", k),
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

/// Chains of every short length (all vector tails), across several chunks (64 springs, whose
/// angles reach 4 or 8 past the chunk, the next chunk's first ones), and the smallest: every
/// level against the scalar level, which against num-dual autodiff of the independent Cartesian
/// reference.
#[test]
fn every_length_agrees_across_levels_and_with_autodiff() {
    for n in (2..=20).chain([63, 64, 65, 66, 68, 69, 72, 73, 129, 132, 136, 137, 200]) {
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

#[rotor_chain(n = 70, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0,
              law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2))]
struct QuarticLooped;

/// `got` equals `expected` to 1e-13 of the largest entry of `expected`.
#[track_caller]
fn assert_close_to_scale(expected: &[f64], got: &[f64], what: &str) {
    assert_eq!(expected.len(), got.len(), "{what}: lengths");
    let scale = expected.iter().fold(f64::MIN_POSITIVE, |s, x| s.max(x.abs()));
    for (i, (x, y)) in expected.iter().zip(got).enumerate() {
        assert!((x - y).abs() <= 1e-13 * scale, "{what}[{i}]: {x} vs {y} (scale {scale:e})");
    }
}

/// A macro chain's inherent fused methods against its own separate inherent methods (`energy`,
/// `gradient`, `tangent_stiffness`), and its `ChainModel` fused overrides against the same, at
/// every level (the unrolled code is scalar at all of them; the looped kernel dispatches).
macro_rules! check_macro_fused {
    ($chain:expr, $theta:expr, $what:expr) => {{
        let chain = $chain;
        let theta: [f64; 70] = $theta.as_slice().try_into().unwrap();
        let (e, g) = (chain.energy(&theta), chain.gradient(&theta));
        let k = chain.tangent_stiffness(&theta);
        for level in levels() {
            let what = format!("{} at {}", $what, level.name());
            simd::with_level(level, || {
                let (e1, g1) = chain.energy_and_gradient(&theta);
                assert_close_to_scale(&[e], &[e1], &format!("{what}: energy_and_gradient energy"));
                assert_close_to_scale(&g, &g1, &format!("{what}: energy_and_gradient gradient"));
                let (e2, g2, k2) = chain.energy_gradient_stiffness(&theta);
                assert_close_to_scale(&[e], &[e2], &format!("{what}: energy_gradient_stiffness energy"));
                assert_close_to_scale(&g, &g2, &format!("{what}: energy_gradient_stiffness gradient"));
                assert_close_to_scale(&k.diag, &k2.diag, &format!("{what}: stiffness diag"));
                assert_close_to_scale(&k.off, &k2.off, &format!("{what}: stiffness off"));
                let mut out = [0.0; 70];
                let e3 = Potential::energy_and_gradient_into(&chain, &theta, &mut out);
                assert_close_to_scale(&[e], &[e3], &format!("{what}: energy_and_gradient_into energy"));
                assert_close_to_scale(&g, &out, &format!("{what}: energy_and_gradient_into gradient"));
                let mut values = [0.0; 139];
                let e4 = Stiffness::energy_gradient_stiffness_into(&chain, &theta, &mut out, &mut values);
                let (d, o) = values.split_at(70);
                assert_close_to_scale(&[e], &[e4], &format!("{what}: energy_gradient_stiffness_into energy"));
                assert_close_to_scale(&g, &out, &format!("{what}: energy_gradient_stiffness_into gradient"));
                assert_close_to_scale(&k.diag, d, &format!("{what}: energy_gradient_stiffness_into diag"));
                assert_close_to_scale(&k.off, o, &format!("{what}: energy_gradient_stiffness_into off"));
            })
            .unwrap();
        }
    }};
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 24,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x0f05_ed01),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Harmonic, quartic and a custom law; unrolled and looped: the macro's fused methods equal
    /// its separate ones.
    #[test]
    fn macro_fused_methods_equal_the_separate_methods(theta in angles()) {
        check_macro_fused!(HarmonicUnrolled, theta, "harmonic unrolled");
        check_macro_fused!(HarmonicLooped, theta, "harmonic looped");
        check_macro_fused!(QuarticUnrolled, theta, "quartic unrolled");
        check_macro_fused!(QuarticLooped, theta, "quartic looped");
        check_macro_fused!(CustomUnrolled, theta, "custom unrolled");
        check_macro_fused!(CustomLooped, theta, "custom looped");
    }
}

/// The runtime chains' fused overrides against their own separate methods at every level.
#[test]
fn runtime_fused_methods_equal_the_separate_methods() {
    for (chain, what) in [(harmonic_runtime(), "runtime harmonic"), (quartic_runtime(), "runtime quartic")] {
        for seed in 0..8 {
            let theta: Vec<f64> = (0..70)
                .map(|i| 1.1 * (0.37 * (i + 13 * seed) as f64).sin() * (0.05 * i as f64).cos())
                .collect();
            for level in levels() {
                let what = format!("{what}, seed {seed}, at {}", level.name());
                simd::with_level(level, || {
                    let (mut g, mut k) = (vec![0.0; 70], vec![0.0; 139]);
                    let e = chain.energy(&theta);
                    chain.gradient_into(&theta, &mut g);
                    chain.tangent_stiffness_into(&theta, &mut k);
                    let (mut g1, mut k1) = (vec![0.0; 70], vec![0.0; 139]);
                    let e1 = chain.energy_and_gradient_into(&theta, &mut g1);
                    assert_close_to_scale(&[e], &[e1], &format!("{what}: E+g energy"));
                    assert_close_to_scale(&g, &g1, &format!("{what}: E+g gradient"));
                    let e2 = chain.energy_gradient_stiffness_into(&theta, &mut g1, &mut k1);
                    assert_close_to_scale(&[e], &[e2], &format!("{what}: E+g+K energy"));
                    assert_close_to_scale(&g, &g1, &format!("{what}: E+g+K gradient"));
                    assert_close_to_scale(&k, &k1, &format!("{what}: E+g+K (diag, off)"));
                })
                .unwrap();
            }
        }
    }
}
