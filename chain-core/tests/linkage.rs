//! The linkage limit (paper Sec. VII-B, Appendix C): kink coordinates of real linkage
//! configurations built with the branch solve, the reduced two-kink model against finite
//! differences and against the discrete linkage, its regimes, and its symplectic dynamics.

use chain_core::branch::{next_angles, previous_angles};
use chain_core::geometry::{ParameterError, spring_length};
use chain_core::statics::continuum::ContinuumChain;
use chain_core::statics::linkage::{
    Equilibrium, KinkMass, LinkageChain, LinkageError, PhaseState, Region, TrajectoryPoint, el_diagram,
    kink_coordinate,
};

const A: f64 = 1.0;
const R: f64 = 0.8;
const TB: f64 = 0.58;
const M: usize = 8;

fn chain(theta_bar: f64) -> ContinuumChain {
    ContinuumChain::new(A, R, theta_bar, 1.0, 1.0).unwrap()
}

fn linkage(l0: f64) -> LinkageChain {
    LinkageChain::new(chain(TB), M, l0).unwrap()
}

/// A sub-chain of `m` rotors with bars at `lbar` (left frame), rotor `k` at angle `at`, built outward
/// on the flipper branch (towards the attracting fixed point in each direction).
fn sub_chain(c: &ContinuumChain, m: usize, k: usize, at: f64) -> Option<Vec<f64>> {
    let (a, r, l) = (c.a(), c.r(), c.rest_length());
    let mut th = vec![0.0; m];
    th[k] = at;
    for j in k..m - 1 {
        th[j + 1] = next_angles(j, a, r, r, l, th[j]).ok()?[0];
    }
    for j in (0..k).rev() {
        th[j] = previous_angles(j, a, r, r, l, th[j + 1]).ok()?[0];
    }
    Some(th)
}

/// The same configuration with the end rotor on the other root of its bar.
fn flip_end(c: &ContinuumChain, th: &[f64]) -> Vec<f64> {
    let mut out = th.to_vec();
    out[0] = previous_angles(0, c.a(), c.r(), c.r(), c.rest_length(), th[1]).unwrap()[1];
    out
}

/// The sub-chain whose end rotor is collinear with its bar: rotor 1 at the edge of the inverse map's
/// domain, `|tip 1 - pivot 0| = lbar - r`.
fn collinear_end(c: &ContinuumChain, m: usize) -> Vec<f64> {
    let (a, r, l) = (c.a(), c.r(), c.rest_length());
    let second = (((l - r).powi(2) - a * a - r * r) / (2.0 * a * r)).asin();
    let mut th = sub_chain(c, m, 1, second).unwrap();
    th[0] = previous_angles(0, a, r, r, l, second).unwrap()[0];
    th
}

#[test]
fn a_vertical_rotor_carries_the_kink_at_its_position() {
    for theta_bar in [0.1, 0.3, TB] {
        let c = chain(theta_bar);
        for k in 0..M {
            let th = sub_chain(&c, M, k, 0.0).unwrap();
            let x = kink_coordinate(&c, &th).unwrap();
            assert!((x - (k + 1) as f64).abs() < 1e-12, "rotor {k}: x = {x}");
            // Flipping the end rotor over its bar negates the coordinate.
            let flipped = kink_coordinate(&c, &flip_end(&c, &th)).unwrap();
            assert!((flipped + x).abs() < 1e-9, "rotor {k}: {flipped} vs {x}");
        }
    }
}

#[test]
fn the_coordinate_is_zero_with_the_end_rotor_collinear() {
    for theta_bar in [0.2, TB] {
        let c = chain(theta_bar);
        let th = collinear_end(&c, M);
        let x = kink_coordinate(&c, &th).unwrap();
        assert!(x.abs() < 1e-6, "x = {x}");
    }
    // The rest of the sub-chain sits at -theta_bar (rotor 1 overshoots it, by an offset that
    // shrinks by F' = 15.2 per site): with both ends collinear, the impurity spring between the
    // heads (the right head mirrored) is l_critical (Appendix C: a state of self-stress; Sec. VII-B:
    // maximally stretched).
    let c = chain(TB);
    let head = collinear_end(&c, M)[M - 1];
    assert!((head + TB).abs() < 1e-7, "head {head}");
    assert!((spring_length(A, R, R, head, -head) - c.l_critical()).abs() < 1e-7);
}

#[test]
fn the_coordinate_moves_continuously_along_the_linkage() {
    // Sweep the head angle from the far end's collinear point to the head: x grows from 0 to m.
    let c = chain(TB);
    let start = collinear_end(&c, M)[M - 1];
    let mut last = -1.0;
    let mut swept = 0;
    for s in 0..=400 {
        let head = start + (0.0 - start) * f64::from(s) / 400.0;
        let Some(th) = sub_chain(&c, M, M - 1, head) else { continue };
        let x = kink_coordinate(&c, &th).unwrap();
        assert!(x > last, "head {head}: {x} after {last}");
        assert!(x <= M as f64 + 1e-12);
        last = x;
        swept += 1;
    }
    assert!(swept > 390 && (last - M as f64).abs() < 1e-12, "{swept} {last}");
    // Past the head: the head rotor leans forward, x in (m, m + 1].
    let th = sub_chain(&c, M, M - 1, 0.3).unwrap();
    let x = kink_coordinate(&c, &th).unwrap();
    assert!(x > M as f64 && x < M as f64 + 1.0, "{x}");
}

#[test]
fn kink_coordinate_rejects_what_is_not_one_kink() {
    let c = chain(TB);
    assert!(matches!(
        kink_coordinate(&c, &[-0.5, -0.4, 0.3, 0.5]),
        Err(LinkageError::NotAKink { rotor: 2, .. })
    ));
    assert!(matches!(kink_coordinate(&c, &[0.5, 0.5, 1.4]), Err(LinkageError::HeadFlipped { .. })));
    assert!(matches!(kink_coordinate(&c, &[0.5, f64::NAN]), Err(LinkageError::NotFinite { .. })));
    assert!(matches!(
        kink_coordinate(&c, &[0.5]),
        Err(LinkageError::Parameter(ParameterError::TooFewRotors { n: 1 }))
    ));
}

#[test]
fn the_head_follows_the_continuum_width_not_the_printed_one() {
    // At small theta_bar the discrete linkage's head angle, at the Appendix C coordinate of the
    // configuration, is the continuum profile with width w = a^2/(2 ubar); the printed Sec. VII-B
    // equation (width 2w) is far off. (Between the collinear point and the vertical end rotor,
    // x < 1, Appendix C interpolates the end rotor's angle, which swings much further than the
    // head: the coordinate is not the continuum's there.)
    for theta_bar in [0.1, 0.2] {
        let c = chain(theta_bar);
        let model = LinkageChain::new(c, M, 2.0).unwrap();
        let printed = model.with_profile_width(model.printed_profile_width()).unwrap();
        let (mut ours, mut theirs) = (0.0f64, 0.0f64);
        for k in 0..M - 1 {
            for at in [0.0, -0.3 * theta_bar] {
                let th = sub_chain(&c, M, k, at).unwrap();
                let x = kink_coordinate(&c, &th).unwrap();
                if x < 1.0 {
                    continue;
                }
                ours = ours.max((model.head_angle(x) - th[M - 1]).abs());
                theirs = theirs.max((printed.head_angle(x) - th[M - 1]).abs());
            }
        }
        assert!(ours < 0.01 * theta_bar, "theta_bar {theta_bar}: {ours}");
        assert!(theirs > 0.2 * theta_bar, "theta_bar {theta_bar}: {theirs}");
    }
}

#[test]
fn the_chain_profile_puts_the_impurity_between_the_heads() {
    let model = linkage(2.1);
    for (x1, x2) in [(0.0, 0.0), (3.2, -5.0), (7.5, 9.0)] {
        let theta = model.chain_profile(x1, x2);
        assert_eq!(theta.len(), 2 * M);
        assert_eq!(theta[M - 1], model.head_angle(x1));
        assert_eq!(theta[M], -model.head_angle(x2));
        // The impurity's length from the tips in Cartesian coordinates (pivot i at (i a, 0), tip
        // at (i a + r sin theta_i, (-1)^i r cos theta_i)), not from the library's formula.
        let tip = |i: usize| {
            let sign = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
            (i as f64 * A + R * theta[i].sin(), sign * R * theta[i].cos())
        };
        let ((xa, ya), (xb, yb)) = (tip(M - 1), tip(M));
        let l = ((xb - xa).powi(2) + (yb - ya).powi(2)).sqrt();
        assert!((l - model.impurity_length(x1, x2)).abs() < 1e-14, "({x1}, {x2}): {l}");
        let left = model.sub_chain_profile(x1);
        assert_eq!(&theta[..M], &left[..]);
    }
    // x1 = x2 = 0: left head near -theta_bar, right head near +theta_bar.
    // With the heads at -theta_bar and +theta_bar the impurity spans tips 2 r cos theta_bar apart
    // across and a + 2 r sin theta_bar along: the critical length of Sec. VII-A.
    let theta = model.chain_profile(0.0, 0.0);
    assert!((theta[M - 1] + TB).abs() < 1e-5 && (theta[M] - TB).abs() < 1e-5);
    let l_critical = ((A + 2.0 * R * TB.sin()).powi(2) + (2.0 * R * TB.cos()).powi(2)).sqrt();
    assert!(
        (model.impurity_length(0.0, 0.0) - l_critical).abs() < 1e-4,
        "{}",
        model.impurity_length(0.0, 0.0)
    );
    // A mirror-symmetric pair of kinks gives an antisymmetric profile.
    let theta = model.chain_profile(4.5, 4.5);
    for j in 0..M {
        assert_eq!(theta[2 * M - 1 - j], -theta[j]);
    }
}

#[test]
fn gradient_matches_finite_differences() {
    for l0 in [1.9, 2.2, 2.5] {
        let model = linkage(l0);
        let h = 1e-6;
        for (x1, x2) in [(0.7, 3.0), (-2.5, 6.1), (7.9, -8.3), (11.0, 0.4), (-0.2, -4.0)] {
            let g = model.potential_gradient(x1, x2);
            let d1 = (model.potential(x1 + h, x2) - model.potential(x1 - h, x2)) / (2.0 * h);
            let d2 = (model.potential(x1, x2 + h) - model.potential(x1, x2 - h)) / (2.0 * h);
            let scale = 1e-8 * (1.0 + d1.abs() + d2.abs());
            assert!((g[0] - d1).abs() < scale && (g[1] - d2).abs() < scale, "{g:?} vs {d1} {d2}");
            // Exchange and far-end flips are symmetries.
            let v = model.potential(x1, x2);
            assert!((model.potential(x2, x1) - v).abs() < 1e-15);
            assert_eq!(model.potential(-x1, x2), v);
        }
        assert_eq!(model.potential_gradient(0.0, 0.0), [0.0, 0.0]);
        let h = 1e-6;
        let x = 2.3;
        let fd = (model.head_angle(x + h) - model.head_angle(x - h)) / (2.0 * h);
        assert!((model.head_angle_slope(x) - fd).abs() < 1e-8);
    }
}

#[test]
fn the_impurity_is_most_stretched_with_both_kinks_at_the_far_ends() {
    for l0 in [1.8, 2.0, 2.2] {
        let model = linkage(l0);
        let top = model.potential(0.0, 0.0);
        assert_eq!(model.separatrix_energy(), top);
        // l12 is largest at x1 = x2 = 0, so V is largest there among stretched states (the
        // plateau of the Mexican hat). Compressed states can cost more: with both kinks at the heads
        // l12 = sqrt(a^2 + 4 r^2), the corner the paper trims in Fig. fig:KLphaseportrait.
        let mut longest: f64 = 0.0;
        let mut stretched: f64 = 0.0;
        for i in -60i32..=60 {
            for j in -60i32..=60 {
                let (x1, x2) = (f64::from(i) * 0.2, f64::from(j) * 0.2);
                let l = model.impurity_length(x1, x2);
                longest = longest.max(l);
                if l >= l0 {
                    stretched = stretched.max(model.potential(x1, x2));
                }
                // ... and (0, 0) is a local maximum.
                if i.abs() <= 10 && j.abs() <= 10 {
                    assert!(model.potential(x1, x2) <= top);
                }
            }
        }
        assert_eq!(longest, model.impurity_length(0.0, 0.0));
        assert_eq!(stretched, top);
        // l12(0, 0) = l_critical up to the tanh tail at the far end, exp(-2 x_head / w): V(0, 0) = E_c.
        let c = model.chain();
        let tail = (-2.0 * M as f64 / c.width()).exp();
        assert!((model.impurity_length(0.0, 0.0) - c.l_critical()).abs() < 4.0 * R * tail);
        assert!((top - model.critical_energy()).abs() < 1e-4 * top);
    }
    // Long sub-chains: V(0, 0) = E_c to rounding.
    let long = LinkageChain::new(chain(TB), 30, 2.0).unwrap();
    assert!((long.separatrix_energy() - long.critical_energy()).abs() < 1e-12 * long.critical_energy());
}

#[test]
fn kink_mass_is_the_kinetic_energy_of_the_profile() {
    let model = linkage(2.0);
    let h = 1e-6;
    for x in [0.3, -1.7, 4.0, 7.2, 9.5] {
        // T = sum_j M r^2 thetadot_j^2 / 2 = m(x) xdot^2 / 2, by finite differences of the profile.
        let (plus, minus) = (model.sub_chain_profile(x + h), model.sub_chain_profile(x - h));
        let direct: f64 = plus.iter().zip(&minus).map(|(p, m)| R * R * ((p - m) / (2.0 * h)).powi(2)).sum();
        assert!((model.kink_mass(x) - direct).abs() < 1e-7 * direct, "x {x}");
        let fd = (model.kink_mass(x + h) - model.kink_mass(x - h)) / (2.0 * h);
        assert!((model.kink_mass_slope(x) - fd).abs() < 1e-7, "x {x}");
    }
    // Deep in a long sub-chain at small theta_bar: the continuum kink's 4 M ubar^2 / (3 w a).
    let c = chain(0.05);
    let long = LinkageChain::new(c, 400, 2.0).unwrap();
    let bulk = 4.0 * c.u_bar().powi(2) / (3.0 * c.width() * A);
    assert!((long.kink_mass(200.3) / bulk - 1.0).abs() < 2e-3, "{}", long.kink_mass(200.3) / bulk);
    // The Hamiltonian of one kink is the two-kink one with the other at rest at 0.
    let s = PhaseState { x1: 3.0, x2: 0.0, p1: 0.2, p2: 0.0 };
    assert_eq!(model.one_kink_hamiltonian(3.0, 0.2), model.hamiltonian(&s));
    let fixed = model.with_kink_mass(KinkMass::Constant(0.5)).unwrap();
    assert_eq!(fixed.kink_mass(-4.0), 0.5);
    assert_eq!(fixed.kink_mass_slope(-4.0), 0.0);
}

fn minima(eq: &[Equilibrium]) -> Vec<f64> {
    eq.iter().filter(|e| e.stable).map(|e| e.x).collect()
}

#[test]
fn equilibria_form_a_supercritical_pitchfork() {
    // Below l_critical: minima at +-x_eq near the heads (V = 0) and the maximum E_c at 0.
    let model = linkage(2.2);
    let eq = model.equilibria();
    assert_eq!(eq.len(), 3);
    assert!(!eq[1].stable && eq[1].x == 0.0 && eq[1].energy == model.separatrix_energy());
    let x_eq = eq[2].x;
    assert!(eq[0].x == -x_eq && (6.0..9.0).contains(&x_eq), "{x_eq}");
    assert!(model.potential(x_eq, 0.0) < 1e-20);
    assert!(model.potential_gradient(x_eq, 0.0)[0].abs() < 1e-9);
    // The minima walk in to 0 as l0 -> l12(0, 0) and merge there.
    let top = model.impurity_length(0.0, 0.0);
    let mut last = f64::INFINITY;
    for gap in [1e-1, 1e-2, 1e-4, 1e-6, 1e-8] {
        let x = minima(&linkage(top - gap).equilibria())[1];
        assert!(x < last && x > 0.0, "l0 = l12(0, 0) - {gap}: {x}");
        last = x;
    }
    assert!(last < 0.1, "{last}");
    for l0 in [top + 1e-9, 2.31, 2.5] {
        let eq = linkage(l0).equilibria();
        assert_eq!(eq.len(), 1);
        assert!(eq[0].stable && eq[0].x == 0.0);
    }
    // ... where V = E_min = k (l0 - l_critical)^2 / 2, up to the tanh tail of the heads.
    let c = chain(TB);
    let tail = 4.0 * R * (-2.0 * M as f64 / c.width()).exp();
    for l0 in [2.31, 2.5] {
        let energy = linkage(l0).equilibria()[0].energy;
        assert!(((2.0 * energy).sqrt() - (l0 - c.l_critical())).abs() < tail, "l0 {l0}: {energy}");
    }
    // Below lbar the impurity pushes the kink out through the head: no finite minimum.
    let eq = linkage(1.6).equilibria();
    assert_eq!(eq.len(), 1);
    assert!(!eq[0].stable);
}

#[test]
fn level_curves_lie_on_the_energy_surface() {
    let model = linkage(2.15);
    let e_c = model.separatrix_energy();
    let xs: Vec<f64> = (0..=1200).map(|i| -12.0 + 0.02 * f64::from(i)).collect();
    // Inside the separatrix: one loop around each minimum; outside: one loop around both.
    let inside = model.level_curves(0.5 * e_c, &xs);
    let outside = model.level_curves(1.5 * e_c, &xs);
    assert_eq!(inside.len(), 2);
    assert_eq!(outside.len(), 1);
    for curve in inside.iter().chain(&outside) {
        let e = if curve[0][0] < -10.0 || outside.contains(curve) { 1.5 * e_c } else { 0.5 * e_c };
        for &[x, p] in curve {
            assert!((model.one_kink_hamiltonian(x, p) - e).abs() < 1e-12);
        }
    }
    assert!(inside[0].iter().all(|&[x, _]| x < 0.0) && inside[1].iter().all(|&[x, _]| x > 0.0));
    let profile = model.potential_profile(&xs);
    assert_eq!(profile[600], [0.0, e_c]);
}

/// Largest deviation of the energy from its start over `points`.
fn energy_error(points: &[TrajectoryPoint]) -> f64 {
    points.iter().map(|p| (p.energy - points[0].energy).abs()).fold(0.0, f64::max)
}

/// A state at `(x1, x2)` with `p2 = 0` and `p1 > 0` chosen so that `H = energy`.
fn state_with_energy(model: &LinkageChain, x1: f64, x2: f64, energy: f64) -> PhaseState {
    let kinetic = energy - model.potential(x1, x2);
    assert!(kinetic > 0.0);
    PhaseState { x1, x2, p1: (2.0 * model.kink_mass(x1) * kinetic).sqrt(), p2: 0.0 }
}

/// The mean of `H - H(0)` over `points`.
fn mean_energy_offset(points: &[TrajectoryPoint], e0: f64) -> f64 {
    points.iter().map(|p| p.energy - e0).sum::<f64>() / points.len() as f64
}

#[test]
fn leapfrog_conserves_energy_without_drift() {
    for mass in [KinkMass::Profile, KinkMass::Constant(0.2)] {
        let model = linkage(2.15).with_kink_mass(mass).unwrap();
        // Both kinks go over their far ends (x = 0, the cusp of |x|) several times.
        let x_eq = model.equilibria()[2].x;
        let start = state_with_energy(&model, x_eq - 1.0, 4.0, 0.7 * model.separatrix_energy());
        let steps = 100_000;
        let run = model.trajectory(start, 0.01, steps, 10).unwrap();
        assert_eq!(run.len(), steps / 10 + 1);
        assert!((run[run.len() - 1].t - 1000.0).abs() < 1e-9);
        let crossings = run.windows(2).filter(|w| w[0].x1 * w[1].x1 < 0.0 || w[0].x2 * w[1].x2 < 0.0);
        assert!(crossings.count() >= 4);
        // Bounded error ...
        let e0 = run[0].energy;
        let all = energy_error(&run);
        assert!(all < 1e-4 * e0, "{mass:?}: {all} of {e0}");
        // ... that oscillates about a fixed offset: no drift between the first and last tenths.
        let tenth = run.len() / 10;
        let early = mean_energy_offset(&run[..tenth], e0);
        let late = mean_energy_offset(&run[run.len() - tenth..], e0);
        assert!((late - early).abs() < 0.1 * all, "{mass:?}: mean offset {early} -> {late}, error {all}");
        // Halving the step quarters the offset (second order).
        let fine = model.trajectory(start, 0.005, 2 * steps, 20).unwrap();
        let ratio = mean_energy_offset(&run, e0) / mean_energy_offset(&fine, e0);
        assert!(ratio > 3.5 && ratio < 4.5, "{mass:?}: {ratio}");
    }
}

#[test]
fn below_e_c_the_kinks_never_leave_together() {
    let model = linkage(2.15);
    let e_c = model.separatrix_energy();
    let energy = 0.7 * e_c;
    // The square where V > energy: both kinks within delta of the far ends.
    let delta = 1.0;
    for i in -20..=20 {
        for j in -20..=20 {
            let (x1, x2) = (f64::from(i) * delta / 20.0, f64::from(j) * delta / 20.0);
            assert!(model.potential(x1, x2) > energy);
        }
    }
    let x_eq = model.equilibria()[2].x;
    let start = state_with_energy(&model, x_eq - 1.0, 4.0, energy);
    let run = model.trajectory(start, 0.01, 100_000, 1).unwrap();
    assert!(run.iter().all(|p| p.x1.abs() > delta || p.x2.abs() > delta));
    // The annulus is explored: each kink goes over its far end (x changes sign) while the other
    // waits near the impurity.
    let crossings =
        |x: fn(&TrajectoryPoint) -> f64| run.windows(2).filter(|w| x(&w[0]) * x(&w[1]) < 0.0).count();
    assert!(crossings(|p| p.x1) >= 2 && crossings(|p| p.x2) >= 2);
    assert_eq!(model.region(energy).unwrap(), Region::Annulus);
}

#[test]
fn above_e_c_both_kinks_reach_the_far_ends() {
    let model = linkage(2.15);
    let e_c = model.separatrix_energy();
    for (energy, reaches) in [(1.2 * e_c, true), (0.9 * e_c, false)] {
        // On the diagonal x1 = x2, heading for the far ends together.
        let x = 6.0;
        let kinetic = energy - model.potential(x, x);
        let p = -(model.kink_mass(x) * kinetic).sqrt();
        let start = PhaseState { x1: x, x2: x, p1: p, p2: p };
        let run = model.trajectory(start, 0.01, 20_000, 1).unwrap();
        let together = run.iter().any(|q| q.x1.abs() < 0.3 && q.x2.abs() < 0.3);
        assert_eq!(together, reaches, "E = {energy}");
    }
    assert_eq!(model.region(1.2 * e_c).unwrap(), Region::Disk);
}

#[test]
fn the_energy_rest_length_diagram() {
    let c = chain(TB);
    let (lbar, lc) = (c.rest_length(), c.l_critical());
    let l0s: Vec<f64> = (1..=50).map(|i| lbar + f64::from(i) * 0.02).collect();
    let curve = el_diagram(&c, &l0s).unwrap();
    for &[l0, e] in &curve {
        assert_eq!(e, 0.5 * (l0 - lc).powi(2));
    }
    // The parabola's vertex is at l_critical.
    let lowest = curve.iter().min_by(|p, q| p[1].total_cmp(&q[1])).unwrap();
    assert!((lowest[0] - lc).abs() <= 0.01);
    let e_c = |l0: f64| c.critical_energy(l0);
    assert_eq!(Region::classify(&c, 2.0, 0.5 * e_c(2.0)).unwrap(), Region::Annulus);
    assert_eq!(Region::classify(&c, 2.0, e_c(2.0)).unwrap(), Region::Disk);
    assert_eq!(Region::classify(&c, lc, 0.0).unwrap(), Region::Disk);
    assert_eq!(Region::classify(&c, 2.5, 0.5 * e_c(2.5)).unwrap(), Region::Forbidden);
    assert_eq!(Region::classify(&c, 2.5, 2.0 * e_c(2.5)).unwrap(), Region::Disk);
    assert_eq!(Region::classify(&c, 2.0, -1e-9).unwrap(), Region::Forbidden);
    assert!(matches!(Region::classify(&c, lbar, 0.1), Err(LinkageError::RestLengthNotAboveBar { .. })));
    assert!(el_diagram(&c, &[2.0, 1.5]).is_err());
    // Above l_critical the least energy of the model is at x1 = x2 = 0 and is E_min.
    let model = linkage(2.5);
    let e_min = model.potential(0.0, 0.0);
    assert!((e_min - e_c(2.5)).abs() < 1e-4 * e_min);
    assert!(model.potential(3.0, -5.0) > e_min);
}

#[test]
fn bad_input_is_an_error() {
    let c = chain(TB);
    assert!(matches!(LinkageChain::new(c, 1, 2.0), Err(LinkageError::Parameter(_))));
    assert!(matches!(LinkageChain::new(c, M, -2.0), Err(LinkageError::Parameter(_))));
    let model = linkage(2.0);
    assert!(model.with_profile_width(0.0).is_err());
    assert!(model.with_kink_mass(KinkMass::Constant(f64::NAN)).is_err());
    let s = PhaseState { x1: 1.0, x2: 2.0, p1: 0.0, p2: 0.0 };
    assert!(matches!(model.trajectory(s, 0.0, 10, 1), Err(LinkageError::NotPositive { .. })));
    assert!(model.trajectory(s, 0.01, 10, 0).is_err());
    let bad = PhaseState { p2: f64::INFINITY, ..s };
    assert!(matches!(model.trajectory(bad, 0.01, 10, 1), Err(LinkageError::NotFinite { what: "p2", .. })));
}
