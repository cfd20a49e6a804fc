//! The linkage limit (paper Sec. VII-B) with a spring law that is not harmonic: the impurity's
//! energy, length and forces come from its model's generated code, so the reduced model follows
//! the law. Checked against finite differences of the potential, against the law evaluated
//! directly at the impurity's length, and against energy conservation along a trajectory.

use rotor_chain::prelude::*;
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::linkage::{LinkageChain, LinkageError, PhaseState};

const K: f64 = 1.0;
const L0: f64 = 2.0;

/// A stiffening impurity spring: harmonic plus a quartic term (not the paper's law).
#[rotor_chain(n = 2, r = 0.8, theta_bar = 0.58, k = 1.0, spring(0, l0 = 2.0),
              law = k * (l - l0).powi(2) / 2.0 + 3.0 * k * (l - l0).powi(4))]
struct Stiffening;

/// A softening one (Morse-like).
#[rotor_chain(n = 2, r = 0.8, theta_bar = 0.58, k = 1.0, spring(0, l0 = 2.0),
              law = k * (1.0 - (l0 - l).exp()).powi(2) / 2.0)]
struct Softening;

fn stiffening_law(l: f64) -> f64 {
    K * (l - L0).powi(2) / 2.0 + 3.0 * K * (l - L0).powi(4)
}

fn softening_law(l: f64) -> f64 {
    K * (1.0 - (L0 - l).exp()).powi(2) / 2.0
}

fn continuum() -> ContinuumChain {
    ContinuumChain::new(1.0, 0.8, 0.58, K, 1.0).unwrap()
}

const POINTS: [(f64, f64); 6] = [(0.7, 0.0), (3.2, 1.5), (5.9, 7.3), (-2.4, 4.4), (8.0, -6.5), (1.1, 2.2)];

fn check_law<M: ChainModel>(model: &LinkageChain<M>, law: fn(f64) -> f64) {
    let h = 1e-6;
    for (x1, x2) in POINTS {
        // The potential is the law at the impurity's length, evaluated directly here.
        let v = model.potential(x1, x2);
        let direct = law(model.impurity_length(x1, x2));
        assert!(
            (v - direct).abs() <= 1e-13 * (1.0 + direct.abs()),
            "V({x1}, {x2}) = {v}, law gives {direct}"
        );
        // Forces: the generated gradient times the head slopes, against central differences.
        let [g1, g2] = model.potential_gradient(x1, x2);
        let fd1 = (model.potential(x1 + h, x2) - model.potential(x1 - h, x2)) / (2.0 * h);
        let fd2 = (model.potential(x1, x2 + h) - model.potential(x1, x2 - h)) / (2.0 * h);
        let scale = 1e-6 * (1.0 + v.abs() + g1.abs() + g2.abs());
        assert!(
            (g1 - fd1).abs() <= scale && (g2 - fd2).abs() <= scale,
            "({x1}, {x2}): {g1} {g2} vs {fd1} {fd2}"
        );
    }
}

#[test]
fn a_custom_law_sets_the_potential_and_its_forces() {
    let stiffening = LinkageChain::with_impurity(continuum(), 8, Stiffening).unwrap();
    check_law(&stiffening, stiffening_law);
    let softening = LinkageChain::with_impurity(continuum(), 8, Softening).unwrap();
    check_law(&softening, softening_law);
    // Not the harmonic answer: the law is not ignored.
    let harmonic = LinkageChain::new(continuum(), 8, L0).unwrap();
    let (x1, x2) = (0.7, 0.0);
    assert_eq!(stiffening.impurity_length(x1, x2), harmonic.impurity_length(x1, x2));
    let stretch = harmonic.impurity_length(x1, x2) - L0;
    assert!(stretch.abs() > 0.05, "{stretch}");
    assert!((stiffening.potential(x1, x2) - harmonic.potential(x1, x2)).abs() > 1e-3);
    assert!((stiffening.critical_energy() - stiffening_law(continuum().l_critical())).abs() < 1e-12);
}

#[test]
fn the_harmonic_model_is_the_papers_closed_form() {
    let model = LinkageChain::new(continuum(), 8, 2.15).unwrap();
    for (x1, x2) in POINTS {
        let d = model.impurity_length(x1, x2) - 2.15;
        let v = model.potential(x1, x2);
        assert!((v - 0.5 * K * d * d).abs() <= 1e-14 * (1.0 + v), "{v}");
    }
    let e_c = continuum().critical_energy(2.15);
    assert!((model.critical_energy() - e_c).abs() <= 1e-12 * e_c);
}

#[test]
fn trajectories_conserve_the_custom_laws_energy_to_second_order() {
    let model = LinkageChain::with_impurity(continuum(), 8, Stiffening).unwrap();
    let start = PhaseState { x1: 4.0, x2: 0.5, p1: 0.05, p2: -0.02 };
    // Over the same time span, halving the step divides the energy error by about 4 (Stormer-
    // Verlet is second order): the forces are the exact gradient of the law's potential.
    let drift = |dt: f64, steps: usize| {
        let path = model.trajectory(start, dt, steps, 10).unwrap();
        assert!(path.iter().any(|p| (p.x1 - start.x1).abs() > 0.1), "the kink moved");
        let e0 = path[0].energy;
        path.iter().map(|p| (p.energy - e0).abs()).fold(0.0, f64::max) / e0.abs()
    };
    let (coarse, fine) = (drift(0.02, 10_000), drift(0.01, 20_000));
    assert!(coarse < 1e-3, "{coarse}");
    let ratio = fine / coarse;
    assert!((0.15..0.35).contains(&ratio), "drift {coarse} at dt = 0.02, {fine} at 0.01: ratio {ratio}");
}

#[test]
fn an_impurity_model_of_another_shape_is_an_error() {
    let three = RuntimeChain::builder(3, 0.8, 1.0, 0.58).build().unwrap();
    assert!(matches!(
        LinkageChain::with_impurity(continuum(), 8, three),
        Err(LinkageError::ImpurityNotOneSpring { rotors: 3 })
    ));
    let other_rotor = RuntimeChain::builder(2, 0.7, 1.0, 0.58).build().unwrap();
    assert!(matches!(
        LinkageChain::with_impurity(continuum(), 8, other_rotor),
        Err(LinkageError::ImpurityGeometry { what: "first rotor length", .. })
    ));
}
