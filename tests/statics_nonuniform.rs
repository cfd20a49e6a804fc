//! Antikink statics on chains that are not uniform (issue 34): impurity springs (stiffness and
//! rest length, one or two of them), the landscape of equilibria, signed frequencies and the small
//! curvatures at `theta_bar = 0.2`.
//!
//! Every label is checked against an independent computation written here: the Cartesian
//! reference model of tests/common (its own spring lengths, num-dual's exact second derivatives),
//! a Sturm count and a bisection of its Hessian written in this file, and a Newton refinement of
//! the equilibrium with that model.

mod common;

use common::{R, Reference, chains, count_below, lowest, norm, solve};
use rotor_chain::statics::StaticsError;
use rotor_chain::statics::antikink::{
    Antikink, AntikinkOptions, antikink_at, antikink_relaxed, peierls_nabarro,
};
use rotor_chain::statics::landscape::default_centre;
use rotor_chain::statics::modes::{ModeOptions, modes};

/// The reference's tridiagonal Hessian on the moving rotors `1..n-1` (ends held).
fn hessian(reference: &Reference, theta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = theta.len();
    let d = (1..n - 1).map(|i| reference.hessian_entry(theta, i, i)).collect();
    let o = (1..n - 2).map(|i| reference.hessian_entry(theta, i, i + 1)).collect();
    (d, o)
}

/// Eigenvalues of the tridiagonal `(d, o)` below `x` (Sturm count of `LDL^T`).
/// The reference's verdict on `a`: an equilibrium of the moving rotors (`max |dV/dtheta| <=
/// 1e-9 ||K||`) and the Morse index of its Hessian (eigenvalues below `-1e-9 ||K||`).
fn reference_index(reference: &Reference, a: &Antikink) -> usize {
    let n = a.theta.len();
    let (d, o) = hessian(reference, &a.theta);
    let scale = norm(&d, &o);
    let force = reference.gradient(&a.theta)[1..n - 1].iter().fold(0.0f64, |m, g| m.max(g.abs()));
    assert!(force <= 1e-9 * scale, "at {}: max |dV/dtheta| = {force:e}, ||K|| = {scale:e}", a.centre);
    count_below(&d, &o, -1e-9 * scale)
}

/// Every free equilibrium in the landscape carries the reference's index; the minimum is one of
/// index 0 or an error, never a saddle.
fn check_landscape(reference: &Reference, pn: &rotor_chain::statics::antikink::PeierlsNabarro) {
    assert!(!pn.landscape.is_empty());
    for a in pn.landscape.iter().filter(|a| a.is_free()) {
        assert_eq!(a.classification.index, reference_index(reference, a), "index at {}", a.centre);
    }
    if let Ok(m) = pn.minimum() {
        assert_eq!(reference_index(reference, m), 0, "minimum at {}", m.centre);
    }
}

/// The case: n = 40, theta_bar = 0.4, the middle spring at 2k. The stiff spring repels
/// the antikink: both middle centrings slide onto the impurity's saddle (index 1), so there is no
/// minimum there, and the impurity's energy is a repulsion.
#[test]
fn a_stiff_impurity_repels_the_antikink_and_no_saddle_is_called_a_minimum() {
    let (model, reference) = chains(40, 0.4, &[(19, 2.0, 1.0)]);
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    assert!(!pn.resolved);
    match pn.minimum() {
        Err(StaticsError::NoMinimum { index, .. }) => assert!(index >= 1),
        other => panic!("{:?}", other.map(|a| (a.centre, a.classification.index))),
    }
    check_landscape(&reference, &pn);
    // The impurity's own centring is a saddle of index 1 (the translation), by the reference.
    let on = pn.landscape.iter().find(|a| a.requested == 19.5).unwrap();
    assert!(on.is_free() && reference_index(&reference, on) == 1);
    // Repulsion: positive, and the reference's own energies of the two configurations.
    let e = pn.impurities[0];
    assert_eq!(e.spring, 19);
    let far = antikink_at(&model, e.reference, &AntikinkOptions::default()).unwrap();
    let expected = reference.energy(&on.theta) - reference.energy(&far.theta);
    assert!(expected > 1.0 && (e.energy - expected).abs() < 1e-9 * expected, "{} vs {expected}", e.energy);
    // The energy along the constrained path (reference energies of the centrings that stayed
    // where they were asked for, leftwards) falls from the saddle for at least two sites before
    // the first Peierls-Nabarro well; the first free minimum to the left is one by the reference.
    let stayed: Vec<&Antikink> = (3..=39)
        .rev()
        .filter_map(|twice| pn.landscape.iter().find(|a| a.requested == twice as f64 / 2.0 && !a.moved()))
        .collect();
    let path: Vec<f64> = stayed.iter().map(|a| reference.energy(&a.theta)).collect();
    let falling = path.windows(2).take_while(|w| w[1] < w[0]).count();
    assert!(falling >= 4 && stayed[falling].requested <= 17.5, "{path:?}");
    // The first free minimum to the left lies between the centrings (the landscape's zero of the
    // path's slope), below where the path stops falling, a minimum by the reference.
    let minimum = pn.minima().filter(|a| a.centre < 19.5).max_by(|a, b| a.centre.total_cmp(&b.centre));
    let minimum = minimum.expect("a minimum left of the impurity");
    assert!(minimum.centre <= stayed[falling].requested + 0.5, "{}", minimum.centre);
    assert_eq!(reference_index(&reference, minimum), 0);
    // A centring with no equilibrium says where the solution went.
    for c in [17.0, 18.5] {
        match antikink_at(&model, c, &AntikinkOptions::default()) {
            Err(StaticsError::NotAnEquilibrium { requested, found, .. }) => {
                assert_eq!(requested, c);
                assert!((found - c).abs() > 0.25, "{c} -> {found}");
            }
            other => panic!("{c}: {:?}", other.map(|a| a.centre)),
        }
    }
    // The relaxed construction ends at a minimum (by the reference) or says what it found: here
    // the well next to the impurity's slope is off the centrings (its centring holds the
    // translation), never a saddle called a minimum.
    match antikink_relaxed(&model, 15.0, &AntikinkOptions::default()) {
        Ok(a) => assert!(a.is_free_minimum() && reference_index(&reference, &a) == 0, "{}", a.centre),
        Err(StaticsError::NoMinimum { found, index, held, .. }) => {
            assert!(held > 0 || index > 0, "{found}");
            assert!((found - 15.0).abs() < 3.0, "{found}");
        }
        Err(e) => panic!("{e}"),
    }
    // The default placement keeps clear of the ends and of the impurity.
    let c = default_centre(&model);
    assert!((9.0..=30.0).contains(&c) && (c - 19.5).abs() >= 9.0, "{c}");
}

/// Soft impurities (a spring at 0.1 k; a longer rest length) pin the antikink: the minimum sits on
/// the impurity with a negative energy. Two impurities: every free equilibrium's index agrees.
#[test]
fn soft_and_rest_length_impurities_pin_the_antikink_and_labels_agree_with_the_reference() {
    for overrides in [vec![(19, 0.1, 1.0)], vec![(19, 1.0, 1.01)], vec![(16, 2.0, 1.0), (22, 0.3, 1.0)]] {
        let (model, reference) = chains(40, 0.4, &overrides);
        let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
        check_landscape(&reference, &pn);
        assert_eq!(pn.impurities.len(), overrides.len(), "{overrides:?}");
        for (e, &(_, k, _)) in pn.impurities.iter().zip(&overrides) {
            let on = pn.landscape.iter().find(|a| a.requested == e.spring as f64 + 0.5).unwrap();
            let far = antikink_at(&model, e.reference, &AntikinkOptions::default()).unwrap();
            let expected = reference.energy(&on.theta) - reference.energy(&far.theta);
            assert!((e.energy - expected).abs() < 1e-9 * expected.abs().max(1.0), "{overrides:?}");
            assert_eq!(e.energy > 0.0, k > 1.0, "{overrides:?}: {}", e.energy);
        }
        let relaxed = antikink_relaxed(&model, default_centre(&model), &AntikinkOptions::default()).unwrap();
        assert_eq!(reference_index(&reference, &relaxed), 0, "{overrides:?}");
    }
    // The soft spring's own centring is a minimum.
    let (model, reference) = chains(40, 0.4, &[(19, 0.1, 1.0)]);
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    let m = pn.minimum().unwrap();
    assert_eq!(m.requested, 19.5);
    assert_eq!(reference_index(&reference, m), 0);
}

/// The reference's lowest curvature at `theta` refined by its own Newton steps (the soft mode,
/// found by inverse iteration, projected out of each step so rounding along it is not amplified).
fn refined_lowest(reference: &Reference, theta: &[f64]) -> f64 {
    let n = theta.len();
    let mut theta = theta.to_vec();
    for _ in 0..3 {
        let (d, o) = hessian(reference, &theta);
        let mut v = vec![1.0; n - 2];
        for _ in 0..4 {
            v = solve(&d, &o, &v);
            let s = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            v.iter_mut().for_each(|x| *x /= s);
        }
        let project = |x: &mut Vec<f64>| {
            let dot: f64 = x.iter().zip(&v).map(|(a, b)| a * b).sum();
            x.iter_mut().zip(&v).for_each(|(a, b)| *a -= dot * b);
        };
        let mut g: Vec<f64> = reference.gradient(&theta)[1..n - 1].iter().map(|x| -x).collect();
        project(&mut g);
        let mut step = solve(&d, &o, &g);
        project(&mut step);
        theta[1..n - 1].iter_mut().zip(&step).for_each(|(t, s)| *t += s);
    }
    let (d, o) = hessian(reference, &theta);
    lowest(&d, &o)
}

/// theta_bar = 0.2, n = 60, ends held: the antikink's translation curvature is resolved (4e-7,
/// far above rounding) and agrees with the reference's to 1e-3, with the right sign at the
/// minimum and the saddle; the saddle's frequency is negative (signed), never 0.
#[test]
fn small_curvatures_at_theta_bar_0_2_agree_with_the_reference_and_frequencies_are_signed() {
    let (model, reference) = chains(60, 0.2, &[]);
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    assert!(pn.resolved, "a soft mode called null");
    let held = ModeOptions { count: Some(2), hold_ends: true, ..ModeOptions::default() };
    let inertia = R * R; // M r^2, M = 1
    for (a, sign) in [(pn.minimum().unwrap(), 1.0), (pn.saddle().unwrap(), -1.0)] {
        let expected = refined_lowest(&reference, &a.theta);
        let ours = modes(&model, &a.theta, &held).unwrap()[0].clone();
        assert!(expected * sign > 3e-7, "{expected:e}");
        assert!(
            (ours.omega_squared * inertia / expected - 1.0).abs() < 1e-3,
            "{:e} vs {expected:e}",
            ours.omega_squared * inertia
        );
        assert_eq!(ours.frequency.signum(), sign);
        assert!(
            (ours.frequency.abs() - (expected.abs() / inertia).sqrt()).abs() < 1e-3 * ours.frequency.abs()
        );
    }
}

/// The Peierls-Nabarro saddle of the paper's chain (theta_bar = 0.58): its unstable translation
/// has a negative frequency equal to minus the square root of the reference's lowest eigenvalue.
#[test]
fn the_saddles_unstable_direction_has_a_negative_frequency() {
    let (model, reference) = chains(60, 0.58, &[]);
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    let saddle = pn.saddle().unwrap();
    let (d, o) = hessian(&reference, &saddle.theta);
    let expected = lowest(&d, &o) / (R * R);
    assert!(expected < -1.0);
    let held = ModeOptions { count: Some(1), hold_ends: true, ..ModeOptions::default() };
    let ours = &modes(&model, &saddle.theta, &held).unwrap()[0];
    assert!(
        (ours.frequency + (-expected).sqrt()).abs() < 1e-6 * (-expected).sqrt(),
        "{} vs {expected}",
        ours.frequency
    );
}
