//! Known answers of the discrete model (paper Sec. II): the zero-energy kink built by the branch
//! solve, the uniform states, and what a spring impurity touches.
//!
//! Convention (docs/theory.md): the kink runs from `+theta_bar` on the left to `-theta_bar` on the
//! right and costs no energy; the antikink (`-theta_bar` to `+theta_bar`) stretches springs.

mod common;

use common::{Reference, assert_close};
use rotor_chain::prelude::*;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Paper;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.28, k = 1.0e4)]
struct Wide;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(29, k = k_imp))]
struct Impure {
    k_imp: f64,
}

#[rotor_chain(n = 8, r = rr, theta_bar = tb, k = 1.0e4)]
struct FieldDriven {
    rr: f64,
    tb: f64,
}

/// The kink by forward iteration of the flipper branch from just below `+theta_bar` at the left
/// end (paper Sec. II, steps 1-4 of the cobweb construction).
fn kink<const N: usize>(model: &impl ChainModel, offset: f64) -> [f64; N] {
    let mut theta = [0.0; N];
    theta[0] = model.theta_bar() - offset;
    for p in 0..N - 1 {
        theta[p + 1] = model.next_angles(p, theta[p]).expect("the flipper branch has a real root")[0];
    }
    theta
}

#[test]
fn the_kink_costs_no_energy_at_every_position() {
    // Smaller offsets put the kink further right: the mechanism (paper Sec. II).
    for offset in [1e-3, 1e-6, 1e-9, 1e-12] {
        let theta: [f64; 60] = kink(&Paper, offset);
        let tb = Paper.theta_bar();
        assert!((theta[59] + tb).abs() < 1e-9, "the kink ends at -theta_bar: {}", theta[59]);
        let e = Paper.energy(&theta);
        assert!(e <= 1e-20 * 1.0e4, "kink energy {e:e} (offset {offset:e})");
        let g = Paper.gradient(&theta);
        assert!(g.iter().all(|x| x.abs() < 1e-8), "the kink is an equilibrium: {g:?}");
    }
    let theta: [f64; 60] = kink(&Wide, 1e-8);
    assert!(Wide.energy(&theta) <= 1e-20 * 1.0e4);
}

#[test]
fn the_antikink_costs_energy() {
    // Reflecting the kink (theta -> -theta) gives a wall from -theta_bar to +theta_bar.
    let kink: [f64; 60] = kink(&Paper, 1e-9);
    let antikink = kink.map(|t| -t);
    let e = Paper.energy(&antikink);
    // The independent model's energy of the same angles (Cartesian tips, tests/common).
    let reference = Reference::uniform(60, 0.58).energy(&antikink);
    assert_close(e, reference, 1e-12, "energy of the reflected kink");
    // The continuum (paper Eq. eq:akenergy), 16/3 (r/a)^3 sin^3 / (1 + 4 (r/a)^2 cos^2) k a^2 =
    // 1.61e3, is an upper estimate: the discrete wall, three sites wide, costs less.
    let (s, c) = 0.58f64.sin_cos();
    let continuum = 1.0e4 * 16.0 / 3.0 * 0.8f64.powi(3) * s.powi(3) / (1.0 + 4.0 * 0.64 * c * c);
    assert!(e > 0.0 && e < continuum, "antikink energy {e} vs continuum {continuum}");
    assert!(Paper.energy(&kink) < 1e-12 * e);
}

#[test]
fn uniform_states_are_stress_free_equilibria() {
    let reference = Reference::uniform(60, 0.58);
    for sign in [1.0, -1.0] {
        let theta = [sign * 0.58; 60];
        let lengths = Paper.spring_lengths(&theta);
        for (p, l) in lengths.iter().enumerate() {
            assert_close(*l, reference.l0[p], 1e-14, &format!("l_{p} at {sign} theta_bar"));
        }
        assert!(Paper.energy(&theta) < 1e-20);
        assert!(Paper.gradient(&theta).iter().all(|g| g.abs() < 1e-9));
        assert!(Paper.tensions(&theta).iter().all(|t| t.abs() < 1e-9));
    }
}

#[test]
fn a_spring_impurity_changes_only_its_own_spring() {
    let (soft, stiff) = (Impure { k_imp: 100.0 }, Impure { k_imp: 5000.0 });
    let theta: [f64; 60] = common::wavy(60, 0.58, 5).try_into().unwrap();
    let (ts, tt) = (soft.tensions(&theta), stiff.tensions(&theta));
    let (gs, gt) = (soft.gradient(&theta), stiff.gradient(&theta));
    let (ks, kt) = (soft.tangent_stiffness(&theta), stiff.tangent_stiffness(&theta));
    for p in 0..59 {
        assert_eq!(ts[p] == tt[p], p != 29, "tension {p}");
        assert_eq!(ks.off[p] == kt.off[p], p != 29, "K[{p}][{}]", p + 1);
    }
    for i in 0..60 {
        let touched = i == 29 || i == 30;
        assert_eq!(gs[i] == gt[i], !touched, "gradient {i}");
        assert_eq!(ks.diag[i] == kt.diag[i], !touched, "K[{i}][{i}]");
    }
    // The energy difference is exactly that of spring 29: (k1 - k2) (l - l0)^2 / 2.
    let l = soft.spring_lengths(&theta)[29];
    let stretch = l - soft.rest_length(29);
    let de = soft.energy(&theta) - stiff.energy(&theta);
    assert_close(de, 0.5 * (100.0 - 5000.0) * stretch * stretch, 1e-9, "energy difference");
    assert_eq!(soft.spring_constant(29), 100.0);
    assert_eq!(soft.spring_constant(28), 1.0e4);
}

#[test]
fn branch_solve_errors_carry_the_numbers() {
    // At theta = 1.5 the tip is 0.2 a from the next pivot, closer than l0 - r = 0.87 a: the two
    // circles do not meet, so there is no real root (an error, never NaN).
    match Paper.next_angles(3, 1.5) {
        Err(BranchError::NoRealRoot { spring, distance, min, max, .. }) => {
            assert_eq!(spring, 3);
            assert!(distance < min || distance > max);
        }
        other => panic!("expected NoRealRoot, got {other:?}"),
    }
    assert!(matches!(Paper.next_angles(59, 0.1), Err(BranchError::NoSuchSpring { spring: 59, springs: 59 })));
    let [back, _] = Paper.previous_angles(10, Paper.next_angles(10, 0.3).unwrap()[0]).unwrap();
    assert_close(back, 0.3, 1e-12, "inverse map");
}

#[test]
fn field_values_are_checked_at_run_time() {
    assert!(FieldDriven { rr: 0.8, tb: 0.58 }.check().is_ok());
    match (FieldDriven { rr: 0.8, tb: 0.7 }).check() {
        Err(ParameterError::OutsideFlipperPhase { theta_bar, .. }) => assert_eq!(theta_bar, 0.7),
        other => panic!("expected OutsideFlipperPhase, got {other:?}"),
    }
    assert!(matches!((FieldDriven { rr: -1.0, tb: 0.5 }).check(), Err(ParameterError::NotPositive { .. })));
    // Field values flow into the generated code: the uniform state of the field's theta_bar.
    let c = FieldDriven { rr: 0.7, tb: 0.4 };
    assert!(c.gradient(&[0.4; 8]).iter().all(|g| g.abs() < 1e-9));
    assert_close(
        c.rest_length(0),
        (1.0f64 + 4.0 * 0.49 * 0.4f64.cos().powi(2)).sqrt(),
        1e-15,
        "lbar from fields",
    );
}
