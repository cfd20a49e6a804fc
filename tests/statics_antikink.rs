//! Statics acceptance (paper Secs. III-V, VII-A; r/a = 0.8, k = 1e4, M = 1, n = 60 unless said):
//! antikink energies and the Peierls-Nabarro barrier, modes, Maxwell-Calladine counting.
//!
//! References are the paper's numbers and the continuum closed forms (docs/statics.md), never
//! values computed by the code under test.

mod common;

use common::{Reference, assert_close};
use rotor_chain::Potential;
use rotor_chain::RuntimeChain;
use rotor_chain::statics::antikink::{AntikinkOptions, antikink_at, antikink_relaxed, peierls_nabarro};
use rotor_chain::statics::classify::EquilibriumKind;
use rotor_chain::statics::counting::maxwell_calladine;
use rotor_chain::statics::impurity::{critical_length, impurity_analysis};
use rotor_chain::statics::kink::kink;
use rotor_chain::statics::modes::{ModeKind, ModeOptions, modes};

const K: f64 = 1.0e4;

fn chain(n: usize, theta_bar: f64) -> RuntimeChain {
    RuntimeChain::builder(n, 0.8, K, theta_bar).build().unwrap()
}

/// Paper Eq. (eq:akenergy), in units of k a^2.
fn continuum_antikink_energy(theta_bar: f64) -> f64 {
    let (s, c) = theta_bar.sin_cos();
    16.0 / 3.0 * 0.8f64.powi(3) * s.powi(3) / (1.0 + 4.0 * 0.64 * c * c)
}

/// Paper Eq. (eq:continuumtheoryfrequency2).
fn continuum_shape_frequency(theta_bar: f64) -> f64 {
    let (s, c) = theta_bar.sin_cos();
    0.8 * (12.0 * K).sqrt() * s / (1.0 + 4.0 * 0.64 * c * c).sqrt()
}

/// Checks `theta` against the independent reference model (tests/common: Cartesian tips,
/// num-dual derivatives): an equilibrium (`max |dV/dtheta| <= 1e-9 ||K||`) with `index` negative
/// eigenvalues of its hyper-dual Hessian (a Sturm count, below `-1e-7 ||K||`, written here), and
/// returns its energy in the reference model.
fn reference_equilibrium(theta_bar: f64, theta: &[f64], index: usize, what: &str) -> f64 {
    let reference = Reference::uniform(theta.len(), theta_bar);
    let n = theta.len();
    let diagonal: Vec<f64> = (0..n).map(|i| reference.hessian_entry(theta, i, i)).collect();
    let off: Vec<f64> = (0..n - 1).map(|i| reference.hessian_entry(theta, i, i + 1)).collect();
    // ||K||_inf of the tridiagonal Hessian.
    let norm = (0..n)
        .map(|i| {
            diagonal[i].abs()
                + if i > 0 { off[i - 1].abs() } else { 0.0 }
                + if i + 1 < n { off[i].abs() } else { 0.0 }
        })
        .fold(0.0, f64::max);
    let force = reference.gradient(theta).iter().fold(0.0f64, |m, g| m.max(g.abs()));
    assert!(force <= 1e-9 * norm, "{what}: max |dV/dtheta| = {force:e}, ||K|| = {norm:e}");
    // Sturm count: the negative pivots of K + tol I (LDL^T) are its eigenvalues below -tol.
    let shift = 1e-7 * norm;
    let mut negative = 0;
    let mut pivot = diagonal[0] + shift;
    for i in 0..n {
        if i > 0 {
            pivot = diagonal[i] + shift - off[i - 1] * off[i - 1] / pivot;
        }
        negative += usize::from(pivot < 0.0);
    }
    assert_eq!(negative, index, "{what}: negative eigenvalues of the reference Hessian");
    reference.energy(theta)
}

#[test]
fn antikink_energy_and_barrier_reproduce_the_paper() {
    // Paper Sec. V, Fig. fig:akconfigpn: V_min = 1359.15, V_saddle = 1359.75, barrier
    // "1359.75 - 1359.15 = 0.60". Our chain gives these at theta_bar = 0.575132, not at the
    // printed 0.58 (docs/statics.md §3): that angle is fitted to V_min alone, so the saddle and the
    // barrier are predictions. Tolerances: 1e-5 relative on the energies (the paper's last digit
    // is 7e-6 of them; the issue asked 1e-4), and the barrier within the two roundings of the
    // paper's last digit (0.005 each).
    let theta_bar = 0.575132;
    let pn = peierls_nabarro(&chain(60, theta_bar), &AntikinkOptions::default()).unwrap();
    assert!(pn.resolved, "{:?} / {:?}", pn.rotor_centred.classification, pn.spring_centred.classification);
    let (min, saddle) = (pn.minimum().unwrap(), pn.saddle().unwrap());
    eprintln!(
        "theta_bar = {theta_bar}: V_min = {:.4}, V_saddle = {:.4}, barrier = {:.4}",
        min.energy, saddle.energy, pn.barrier
    );
    assert_close(min.energy, 1359.15, 1e-5, "V_min");
    assert_close(saddle.energy, 1359.75, 1e-5, "V_saddle");
    assert!((pn.barrier - 0.60).abs() <= 0.01, "barrier {}", pn.barrier);
    // And both are what an independent model says they are.
    let v_min = reference_equilibrium(theta_bar, &min.theta, 0, "minimum");
    let v_saddle = reference_equilibrium(theta_bar, &saddle.theta, 1, "saddle");
    assert_close(min.energy, v_min, 1e-12, "V_min against the reference");
    assert_close(saddle.energy, v_saddle, 1e-12, "V_saddle against the reference");
    assert_close(pn.barrier, v_saddle - v_min, 1e-9, "barrier against the reference");
}

#[test]
fn antikink_at_the_printed_angle_is_a_minimum_and_a_saddle_of_the_reference() {
    // At the printed theta_bar = 0.58 (docs/statics.md §3: 1392.03 and a barrier of 0.668), the
    // two centrings are still exact equilibria of the independent model, of index 0 and 1.
    let pn = peierls_nabarro(&chain(60, 0.58), &AntikinkOptions::default()).unwrap();
    assert!(pn.resolved);
    let (min, saddle) = (pn.minimum().unwrap(), pn.saddle().unwrap());
    assert_eq!(min.classification.index, 0, "the lower centring is a minimum");
    assert!(matches!(saddle.classification.kind, EquilibriumKind::Saddle { index: 1 }));
    let v_min = reference_equilibrium(0.58, &min.theta, 0, "minimum");
    let v_saddle = reference_equilibrium(0.58, &saddle.theta, 1, "saddle");
    assert_close(min.energy, v_min, 1e-12, "V_min");
    assert_close(pn.barrier, v_saddle - v_min, 1e-9, "barrier");
    // The numbers docs/statics.md §3 and the paper figures' test (chain-paper/tests/statics_a.rs)
    // quote, rounded to 1e-6: the reference model's own energies.
    assert!((v_min - 1392.029215).abs() <= 5e-7, "V_min = {v_min}");
    assert!((v_saddle - v_min - 0.668267).abs() <= 5e-7, "barrier = {}", v_saddle - v_min);
    // Below the continuum's Eq. (eq:akenergy), 1.61e3: discreteness lowers it.
    let continuum = K * continuum_antikink_energy(0.58);
    assert!(v_min < continuum, "{v_min} vs {continuum}");
}

#[test]
fn the_papers_relaxation_lands_in_the_minimum() {
    let model = chain(60, 0.58);
    let relaxed = antikink_relaxed(&model, 29.0, &AntikinkOptions::default()).unwrap();
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    assert!(
        (relaxed.energy - pn.minimum().unwrap().energy).abs() < 1e-6 * relaxed.energy,
        "{} vs {}",
        relaxed.energy,
        pn.minimum().unwrap().energy
    );
    assert_eq!(relaxed.classification.index, 0);
}

#[test]
fn the_relaxed_construction_returns_the_minimum_from_any_start() {
    // At theta_bar = 0.40 the Peierls-Nabarro force is too weak for the relaxation to slide an
    // off-centre antikink; the construction must still return the minimum, never a saddle or a
    // fixed-centring point.
    for (theta_bar, start) in [(0.40, 29.25), (0.40, 29.5), (0.58, 29.5), (0.58, 28.8)] {
        let model = chain(60, theta_bar);
        let relaxed = antikink_relaxed(&model, start, &AntikinkOptions::default()).unwrap();
        let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
        assert_eq!(relaxed.classification.index, 0, "theta_bar {theta_bar}, start {start}");
        assert_eq!(relaxed.held, 0);
        assert!(
            (relaxed.energy - pn.minimum().unwrap().energy).abs() < 1e-9 * relaxed.energy,
            "{} vs {}",
            relaxed.energy,
            pn.minimum().unwrap().energy
        );
    }
}

#[test]
fn antikink_energy_approaches_the_continuum_at_small_theta_bar() {
    let mut previous = f64::INFINITY;
    for theta_bar in [0.1, 0.2, 0.3, 0.4, 0.5, 0.58, 0.65] {
        let pn = peierls_nabarro(&chain(60, theta_bar), &AntikinkOptions::default()).unwrap();
        let ratio = pn.minimum().unwrap().energy / (K * continuum_antikink_energy(theta_bar));
        eprintln!("theta_bar = {theta_bar}: V / V_continuum = {ratio:.5}");
        if theta_bar == 0.1 {
            assert!((0.98..=1.0).contains(&ratio), "ratio {ratio} at 0.1");
        }
        assert!(ratio < previous, "the ratio falls as theta_bar grows: {ratio} after {previous}");
        previous = ratio;
    }
}

#[test]
fn peierls_nabarro_barrier_falls_exponentially_with_the_width() {
    // ln(V_PNB / k a^2) against w / a, w = a^2 / (2 r sin theta_bar) (paper Fig. fig:logvpn-theta).
    let mut points = Vec::new();
    for theta_bar in [0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65] {
        let pn = peierls_nabarro(&chain(60, theta_bar), &AntikinkOptions::default()).unwrap();
        assert!(pn.resolved, "theta_bar = {theta_bar}");
        // Each barrier is the energy difference of a minimum and a saddle of the independent model.
        let what = format!("theta_bar = {theta_bar}");
        let v_min = reference_equilibrium(theta_bar, &pn.minimum().unwrap().theta, 0, &what);
        let v_saddle = reference_equilibrium(theta_bar, &pn.saddle().unwrap().theta, 1, &what);
        assert_close(pn.barrier, v_saddle - v_min, 1e-7, &what);
        let w = 1.0 / (2.0 * 0.8 * f64::sin(theta_bar));
        points.push((w, (pn.barrier / K).ln()));
    }
    let n = points.len() as f64;
    let (mx, my) = (points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n);
    let slope = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
        / points.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
    eprintln!("slope of ln V_PNB vs w/a: {slope:.3} (paper fit -10.6, continuum -pi^2)");
    // The paper's fit (Fig. fig:logvpn-theta) is -10.6 over a theta_bar range it does not print;
    // ours is -11.39 over 0.35-0.65. Its two digits and the unknown range allow 10 %.
    assert!((slope / -10.6 - 1.0).abs() <= 0.10, "slope {slope} against the paper's -10.6");
}

#[test]
fn shape_modes_match_the_continuum_at_small_theta_bar() {
    let model = chain(60, 0.1);
    let expected = continuum_shape_frequency(0.1);
    let opts = ModeOptions { count: Some(8), ..ModeOptions::default() };
    let kink_theta = kink(&model, 29.5).unwrap();
    let kink_modes = modes(&model, &kink_theta, &opts).unwrap();
    let shape = kink_modes.iter().find(|m| m.kind == ModeKind::Shape).expect("a kink shape mode");
    assert!((shape.frequency / expected - 1.0).abs() < 0.02, "kink shape {} vs {expected}", shape.frequency);
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    let ak_modes = modes(&model, &pn.minimum().unwrap().theta, &opts).unwrap();
    let shape = ak_modes.iter().find(|m| m.kind == ModeKind::Shape).expect("an antikink shape mode");
    assert!(
        (shape.frequency / expected - 1.0).abs() < 0.02,
        "antikink shape {} vs {expected}",
        shape.frequency
    );
}

#[test]
fn antikink_translation_is_soft_but_not_zero_and_separate_from_edge_modes() {
    let model = chain(60, 0.58);
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    let all = modes(
        &model,
        &pn.minimum().unwrap().theta,
        &ModeOptions { count: Some(8), ..ModeOptions::default() },
    )
    .unwrap();
    let t = all.iter().find(|m| m.kind == ModeKind::Translation).expect("a translation mode");
    let s = all.iter().find(|m| m.kind == ModeKind::Shape).expect("a shape mode");
    assert!(
        t.frequency > 0.0 && t.frequency < s.frequency,
        "translation {} vs shape {}",
        t.frequency,
        s.frequency
    );
    assert!(
        (t.position - pn.minimum().unwrap().centre).abs() < 3.0,
        "translation mode at {} vs antikink at {}",
        t.position,
        pn.minimum().unwrap().centre
    );
    let edges = all.iter().filter(|m| matches!(m.kind, ModeKind::Edge { .. })).count();
    assert!(edges >= 1, "edge modes found: {all:#?}");
}

#[test]
fn kink_translation_is_a_zero_mode_at_every_position() {
    let model = chain(60, 0.58);
    for centre in [10.0, 20.5, 29.5, 33.25, 45.0] {
        let theta = kink(&model, centre).unwrap();
        let all = modes(&model, &theta, &ModeOptions { count: Some(6), ..ModeOptions::default() }).unwrap();
        let t = all.iter().find(|m| m.kind == ModeKind::Translation).expect("translation");
        let s = all.iter().find(|m| m.kind == ModeKind::Shape).expect("shape");
        assert!(
            t.omega_squared.abs() <= 1e-8 * s.omega_squared,
            "centre {centre}: {} vs {}",
            t.omega_squared,
            s.omega_squared
        );
    }
}

#[test]
fn maxwell_calladine_index_is_one_everywhere_and_l_critical_has_a_self_stress() {
    let model = chain(60, 0.58);
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    for theta in [
        kink(&model, 20.3).unwrap(),
        pn.minimum().unwrap().theta.clone(),
        pn.saddle().unwrap().theta.clone(),
        vec![0.58; 60],
    ] {
        let c = maxwell_calladine(&model, &theta, None).unwrap();
        assert_eq!(
            c.index(),
            1,
            "zero modes {} - self-stresses {}",
            c.zero_modes.len(),
            c.self_stresses.len()
        );
    }
    // Spring-length impurity at l_critical (paper Sec. VII-A): closed form sqrt((2 r sin + a)^2 + (2 r cos)^2).
    let (s, c) = 0.58f64.sin_cos();
    let l_critical = ((2.0 * 0.8 * s + 1.0).powi(2) + (2.0 * 0.8 * c).powi(2)).sqrt();
    assert!((critical_length(&model, 29).unwrap() - l_critical).abs() < 1e-12);
    assert!((l_critical - 2.31).abs() < 0.01, "paper: l_critical / a = 2.31");
    let at_critical =
        RuntimeChain::builder(60, 0.8, K, 0.58).spring_rest_length(29, l_critical).build().unwrap();
    let analysis = impurity_analysis(&at_critical, 29).unwrap();
    assert_eq!(analysis.counting.self_stresses.len(), 1, "one state of self-stress at l_critical");
    assert_eq!(analysis.counting.zero_modes.len(), 2);
}

#[test]
fn soft_mode_and_tensional_mode_soften_towards_l_critical() {
    let (s, c) = 0.58f64.sin_cos();
    let l_critical = ((2.0 * 0.8 * s + 1.0).powi(2) + (2.0 * 0.8 * c).powi(2)).sqrt();
    let mut previous = (f64::INFINITY, f64::INFINITY);
    for l0 in [1.9, 2.1, 2.25, 2.30] {
        let model = RuntimeChain::builder(60, 0.8, K, 0.58).spring_rest_length(29, l0).build().unwrap();
        let a = impurity_analysis(&model, 29).unwrap();
        let soft = a.modes[1].frequency;
        let tension = a.tensional.eigenvalue;
        eprintln!("l0 = {l0}: soft mode omega = {soft:.3e}, softest tensional eigenvalue = {tension:.3e}");
        assert!(soft < previous.0 && tension < previous.1, "both soften as l0 -> l_critical = {l_critical}");
        previous = (soft, tension);
        // The tensional mode lives on the impurity spring.
        let peak =
            a.tensional.tensions.iter().enumerate().max_by(|x, y| x.1.abs().total_cmp(&y.1.abs())).unwrap().0;
        assert!((peak as isize - 29).abs() <= 1, "tensional mode peaks at spring {peak}");
    }
}

#[test]
fn failures_are_typed_errors() {
    let model = chain(60, 0.58);
    assert!(kink(&model, 60.5).is_err());
    assert!(kink(&model, f64::NAN).is_err());
    let too_long = RuntimeChain::builder(60, 0.8, K, 0.58).spring_rest_length(29, 2.5).build().unwrap();
    assert!(impurity_analysis(&too_long, 29).is_err(), "no zero-energy state beyond l_critical");
}

/// A wall far wider than the chain (theta_bar = 1e-8: every angle rounds to zero) is an error
/// naming it, not a wall-less configuration handed back as a kink; a wide wall that still shows
/// (theta_bar = 0.05, some 20 sites wide) is built as before.
#[test]
fn a_kink_too_wide_to_show_is_an_error() {
    use rotor_chain::statics::StaticsError;
    use rotor_chain::statics::kink::reflected_kink;
    use rotor_chain::statics::walls::{Charge, domain_walls};
    for theta_bar in [1e-8, 1e-300] {
        let model = chain(60, theta_bar);
        match kink(&model, 29.5) {
            Err(StaticsError::NoWall { expected: "kink", centre, theta_bar: tb, .. }) => {
                assert_eq!((centre, tb), (29.5, theta_bar));
            }
            other => panic!("{theta_bar}: {:?}", other.map(|t| t[0])),
        }
        assert!(matches!(
            reflected_kink(&model, 30.0),
            Err(StaticsError::NoWall { expected: "antikink", .. })
        ));
        // The no-alloc builder both share says so itself (firmware builds its kinks with it).
        let mut theta = [0.0; 60];
        let e = rotor_chain::embedded::kink_into(&model, 29.5, &mut theta);
        assert!(matches!(e, Err(StaticsError::NoWall { expected: "kink", .. })), "{e:?}");
    }
    let wide = chain(60, 0.05);
    let theta = kink(&wide, 29.5).unwrap();
    let walls = domain_walls(&theta);
    assert_eq!(walls.len(), 1);
    assert!(walls[0].charge == Charge::Kink && (walls[0].position - 29.5).abs() < 1e-6);
}

/// The zero modes and self-stresses of the counting are null vectors of `C` and `C^T` to
/// rounding, `|C z| <= 4 n eps sigma_max`, on every configuration, also where a singular value
/// lies just above the rank tolerance (an antikink at 15 of 41 rotors, r = 0.7, theta_bar = 0.6:
/// sigma = 3.3e-14 against a tolerance of 1.0e-14, where eigenvectors of `C^T C` returned a
/// "zero mode" with `|C z| = 3.3e-14`, found by a mirror-symmetry audit). `C` is applied here
/// from its bands, not through the counting.
#[test]
fn counting_returns_null_vectors_to_rounding() {
    use rotor_chain::statics::counting::{compatibility, tensional_modes};
    let model = RuntimeChain::builder(41, 0.7, K, 0.6).build().unwrap();
    let options = AntikinkOptions::default();
    let mut checked = 0;
    for centre in (4..=36).map(|c| c as f64) {
        let Ok(antikink) = antikink_at(&model, centre, &options) else { continue };
        let theta = antikink.theta;
        let (left, right) = compatibility(&model, &theta);
        let counting = maxwell_calladine(&model, &theta, None).unwrap();
        let sigma_max = counting.singular_values[0];
        let bound = 4.0 * 41.0 * f64::EPSILON * sigma_max;
        assert_eq!(counting.index(), 1, "centre {centre}");
        // The singular values against an independent route: sigma^2 are the eigenvalues of the
        // tridiagonal C C^T (Sturm bisection), to a few eps sigma_max^2. (nalgebra's SVD of a
        // non-square matrix with vectors was 1e-5 off; the counting does not use it.)
        let mut squares: Vec<f64> =
            tensional_modes(&model, &theta, 40).unwrap().iter().map(|t| t.eigenvalue).collect();
        squares.sort_by(|a, b| b.total_cmp(a));
        for (s, e) in counting.singular_values.iter().zip(&squares) {
            assert!((s * s - e).abs() <= 1e-13 * sigma_max * sigma_max, "centre {centre}: {s}^2 vs {e}");
        }
        for z in &counting.zero_modes {
            let norm = z.iter().map(|x| x * x).sum::<f64>().sqrt();
            let residual =
                (0..40).map(|p| (left[p] * z[p] + right[p] * z[p + 1]).powi(2)).sum::<f64>().sqrt();
            assert!(
                (norm - 1.0).abs() < 1e-12 && residual <= bound,
                "centre {centre}: |C z| = {residual:.2e}"
            );
        }
        for t in &counting.self_stresses {
            let residual = (0..41)
                .map(|i| {
                    let from_left = if i < 40 { left[i] * t[i] } else { 0.0 };
                    let from_right = if i > 0 { right[i - 1] * t[i - 1] } else { 0.0 };
                    (from_left + from_right).powi(2)
                })
                .sum::<f64>()
                .sqrt();
            assert!(residual <= bound, "centre {centre}: |C^T s| = {residual:.2e}");
        }
        checked += 1;
    }
    assert!(checked >= 30, "{checked} centres");
}

/// A wide kink's wall sits at the asked centre to its conditioning: the branch solve's angles
/// carry an absolute rounding of about `eps`, and near the core of a wall `1 / theta_bar` sites
/// wide neighbours differ by about `2 r theta_bar^2 / a`, so the interpolated sign change is good
/// to about `eps a / (r theta_bar^2)` sites (the bound `kink`'s documentation states). Checked
/// with the walls' own interpolation, over rotor lengths, widths down to `theta_bar = 1e-6` and
/// fractional centres; the profile has zero energy to rounding throughout.
#[test]
fn a_wide_kink_sits_at_its_centre_to_the_documented_bound() {
    use rotor_chain::statics::walls::domain_walls;
    let eps = f64::EPSILON;
    for r in [0.3, 0.8, 1.5] {
        for theta_bar in [1e-6, 1e-4, 1e-2, 0.3] {
            let model = RuntimeChain::builder(120, r, K, theta_bar).build().unwrap();
            let bound = 4.0 * eps / (r * theta_bar * theta_bar) + 1e-13;
            let mut worst = 0.0f64;
            for step in 0..40 {
                let centre = 10.0 + 2.47 * step as f64;
                let theta = kink(&model, centre).unwrap();
                let walls = domain_walls(&theta);
                assert_eq!(walls.len(), 1, "r {r}, theta_bar {theta_bar}, centre {centre}");
                worst = worst.max((walls[0].position - centre).abs());
                let energy = model.energy(&theta);
                assert!(energy < 1e-16 * K, "r {r}, theta_bar {theta_bar}, centre {centre}: {energy}");
            }
            assert!(worst <= bound, "r {r}, theta_bar {theta_bar}: off by {worst:.3e} > {bound:.3e} sites");
        }
    }
}

/// `antikink_at` solves the centrings, rotor or spring: a centre between them has no equilibrium
/// (an audit found 29.25 labelled a minimum with an interior force of 0.65), so it is refused.
/// Where the translation is held, `held` says so and the force shows in the gradient, checked
/// here with the chain's gradient rather than the solver's own numbers.
#[test]
fn antikink_at_solves_centrings_only_and_says_when_it_held_the_translation() {
    use rotor_chain::statics::StaticsError;
    let model = chain(60, 0.58);
    let options = AntikinkOptions::default();
    for centre in [29.25, 29.4, 30.1, 0.3] {
        match antikink_at(&model, centre, &options) {
            Err(StaticsError::InvalidValue { what: "centre", value, .. }) => assert_eq!(value, centre),
            other => panic!("{centre}: {:?}", other.map(|a| a.centre)),
        }
    }
    let interior_force = |theta: &[f64]| {
        let mut g = vec![0.0; theta.len()];
        model.gradient_into(theta, &mut g);
        g[1..59].iter().fold(0.0f64, |m, x| m.max(x.abs()))
    };
    // In the middle: free equilibria, the interior force at rounding level (|g| ~ k = 1e4).
    for centre in [29.0, 29.5] {
        let a = antikink_at(&model, centre, &options).unwrap();
        assert_eq!(a.held, 0, "{centre}");
        assert!(interior_force(&a.theta) < 1e-6, "{centre}: {}", interior_force(&a.theta));
    }
    // At the last spring the ends' pull wins: the antikink slides inward (the translation held
    // on the way), and antikink_at reports where it went instead of an equilibrium at 58.5.
    match antikink_at(&model, 58.5, &options) {
        Err(StaticsError::NotAnEquilibrium { requested, found, held, .. }) => {
            assert_eq!(requested, 58.5);
            assert!(found < 58.25 && held > 0, "{found}, held {held}");
        }
        other => panic!("{:?}", other.map(|a| a.centre)),
    }
}

#[test]
fn phonon_band_edges_of_the_uniform_chain_match_the_exact_dispersion() {
    use rotor_chain::linalg::SymmetricMatrix;
    use rotor_chain::linalg::eigenvalues;
    use rotor_chain::statics::continuum::ContinuumChain;
    for (n, theta_bar) in [(60, 0.58), (200, 0.3)] {
        let model = chain(n, theta_bar);
        let k = SymmetricMatrix::tangent_stiffness(&model, &vec![theta_bar; n]).unwrap();
        let (diag, off) = k.bands().unwrap();
        let ours = eigenvalues(diag, off).unwrap();
        let exact =
            ContinuumChain::new(1.0, 0.8, theta_bar, K, 1.0).unwrap().finite_chain_spectrum(n).unwrap();
        let top = exact[n - 1];
        for (j, (a, b)) in ours.iter().zip(&exact).enumerate() {
            assert!((a - b).abs() <= 1e-8 * top, "n = {n}, eigenvalue {j}: {a} vs exact {b}");
        }
        // The band edges (the lowest and highest phonons) in particular.
        assert!((ours[1] / exact[1] - 1.0).abs() < 1e-8 && (ours[n - 1] / exact[n - 1] - 1.0).abs() < 1e-8);
    }
}

#[test]
fn finite_size_effects_on_the_barrier_decay_with_the_chain_length() {
    use rotor_chain::statics::antikink::barrier_vs_size;
    // Paper Fig. fig:logvpn-size: theta_bar = 0.40, Delta V_PNB = V_PNB(L) - V_PNB(60).
    let sizes = [16, 20, 24, 28, 60];
    let barriers = barrier_vs_size(
        &sizes,
        |n| RuntimeChain::builder(n, 0.8, K, 0.40).build(),
        &AntikinkOptions::default(),
    )
    .unwrap();
    let reference = barriers.last().unwrap().1;
    let deltas: Vec<f64> = barriers[..4].iter().map(|(_, b)| (b - reference).abs()).collect();
    eprintln!("Delta V_PNB for n = 16, 20, 24, 28: {deltas:?}");
    for w in deltas.windows(2) {
        assert!(w[1] < w[0], "finite-size corrections shrink with n: {deltas:?}");
    }
}

#[test]
fn antikinks_are_found_across_the_required_range() {
    use rotor_chain::statics::StaticsError;
    // The range: theta_bar in [0.1, 0.65], n in [16, 2000]; both centrings converge and hold
    // exactly one antikink (walls are counted inside the analysis).
    for n in [16, 2000] {
        for theta_bar in [0.1, 0.3, 0.65] {
            let pn = peierls_nabarro(&chain(n, theta_bar), &AntikinkOptions::default())
                .unwrap_or_else(|e| panic!("n = {n}, theta_bar = {theta_bar}: {e}"));
            assert!(pn.minimum().unwrap().residual <= 1e-11);
            // At n = 16 the held ends confine a wide antikink: at theta_bar = 0.1 the rotor centring
            // slides onto the middle spring, at 0.3 both centrings are minima. No saddle there, and
            // `saddle()` says so instead of naming one.
            match pn.saddle() {
                Ok(saddle) => assert!(saddle.residual <= 1e-11 && pn.resolved),
                Err(StaticsError::NotAnEquilibrium { index, found, requested, .. }) => {
                    assert!(
                        !pn.resolved && (index == 0 || (found - requested).abs() > 0.25),
                        "n = {n}, {theta_bar}"
                    )
                }
                Err(e) => panic!("n = {n}, theta_bar = {theta_bar}: {e}"),
            }
            assert!(pn.minimum().unwrap().energy > 0.0 && pn.barrier >= 0.0);
        }
    }
}

/// A guard on the precision of the generated energy and gradient, and on the rounding floor that
/// Fig. fig:logvpn-size assumes (`chain-paper`, `barrier.rs`: differences below 20 eps V_min are
/// drawn as rounding and left out of the fit). Past n ~ 28 at theta_bar = 0.40 the finite-size
/// part of Delta V_PNB (falling as exp(-1.46 n)) is below eps V_min, so what the barriers of
/// n = 30 ... 38 differ from that of n = 60 by is the rounding of the two energies each barrier
/// subtracts. Measured (docs/benchmarks.md, ninth round): at most 10 eps V_min now, 13.5 before
/// the ninth round, and 20.5 with the lowering of 1 / sqrt(x) dropped in the eighth, whose extra
/// rounding made the paper's fit take that noise for signal while every other test passed.
#[test]
fn long_chains_barriers_agree_to_the_rounding_floor_the_paper_assumes() {
    use rotor_chain::statics::antikink::barrier_vs_size;
    let sizes: Vec<usize> = (30..=38).chain([60]).collect();
    let mut scaled = Vec::new();
    for k in [1.0, 3.7, K] {
        let build = |n: usize| RuntimeChain::builder(n, 0.8, k, 0.40).build();
        let barriers = barrier_vs_size(&sizes, build, &AntikinkOptions::default()).unwrap();
        let v_min = peierls_nabarro(&build(60).unwrap(), &AntikinkOptions::default())
            .unwrap()
            .minimum()
            .unwrap()
            .energy;
        let (_, reference) = barriers[barriers.len() - 1];
        scaled.extend(
            barriers[..barriers.len() - 1].iter().map(|(_, b)| (b - reference) / (f64::EPSILON * v_min)),
        );
    }
    let worst = scaled.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    eprintln!("Delta V_PNB / (eps V_min), n = 30 ... 38, k = 1, 3.7, 1e4: {scaled:.2?}");
    assert!(worst < 20.0, "a barrier differs by {worst:.2} eps V_min from n = 60's: {scaled:.2?}");
}
