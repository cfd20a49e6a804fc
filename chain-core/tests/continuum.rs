//! The continuum closed forms (paper Sec. III-V, `app:AppendixPN`) and the uniform chain's phonons,
//! each against a reference computed here independently: quadrature, lattice sums, finite
//! differences, a dense eigensolver, and the generated-code stiffness of a runtime chain.

use std::f64::consts::PI;

use chain_core::RuntimeChain;
use chain_core::geometry::{ParameterError, spring_length};
use chain_core::linalg::SymmetricMatrix;
use chain_core::statics::continuum::{
    ContinuumChain, ContinuumError, PN_ASYMPTOTIC_LOG_SLOPE, sech4_fourier_transform,
};
use chain_core::statics::walls::Charge;
use nalgebra::{DMatrix, SymmetricEigen};

const A: f64 = 1.0;
const R: f64 = 0.8;
const TB: f64 = 0.58;

fn paper() -> ContinuumChain {
    ContinuumChain::new(A, R, TB, 1.0, 1.0).unwrap()
}

fn chain(theta_bar: f64, k: f64) -> ContinuumChain {
    ContinuumChain::new(A, R, theta_bar, k, 1.3).unwrap()
}

/// The angle that gives wall width `w` at `r = R`: `w = a^2 / (2 r sin theta_bar)`.
fn theta_for_width(w: f64) -> f64 {
    (A * A / (2.0 * R * w)).asin()
}

/// Composite Simpson rule on `[lo, hi]` with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, lo: f64, hi: f64, n: usize) -> f64 {
    let h = (hi - lo) / n as f64;
    let inner: f64 = (1..n).map(|i| f(lo + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 }).sum();
    (f(lo) + f(hi) + inner) * h / 3.0
}

#[test]
fn antikink_energy_is_the_integral_of_the_continuum_density() {
    for (theta_bar, k) in [(0.1, 1.0), (0.3, 7.0), (TB, 1.0), (0.65, 1e4)] {
        let c = chain(theta_bar, k);
        // Independent of the crate: ubar, w, lbar from their definitions.
        let ub = R * theta_bar.sin();
        let w = A * A / (2.0 * ub);
        let l2 = A * A + 4.0 * R * R * theta_bar.cos().powi(2);
        // Energy per unit length: one spring of energy (2k/lbar^2)(a^2/2 u' + ubar^2 - u^2)^2 per a.
        let density = |x: f64, sign: f64| {
            let u = sign * ub * (x / w).tanh();
            let du = sign * ub / w / (x / w).cosh().powi(2);
            let bracket = 0.5 * A * A * du + ub * ub - u * u;
            2.0 * k / (A * l2) * bracket * bracket
        };
        let antikink = simpson(|x| density(x, 1.0), -40.0 * w, 40.0 * w, 40_000);
        let kink = simpson(|x| density(x, -1.0), -40.0 * w, 40.0 * w, 40_000);
        let closed = c.antikink_energy();
        assert!((antikink - closed).abs() < 1e-10 * closed, "theta_bar {theta_bar}: {antikink} vs {closed}");
        assert!(kink.abs() < 1e-20 * k, "the kink costs nothing: {kink}");
        // The crate's own density agrees with the one written here.
        let x = 0.37 * w;
        let u = ub * (x / w).tanh();
        let du = ub / w / (x / w).cosh().powi(2);
        assert!((c.potential_density(u, du) - density(x, 1.0)).abs() < 1e-13 * k);
    }
}

#[test]
fn the_paper_numbers() {
    let c = paper();
    // Sec. VII-B and Fig. fig:longbar: l_critical / a = 2.31; Sec. III: V_antikink = 0.161 k a^2.
    assert!((c.l_critical() - 2.3051).abs() < 1e-4, "{}", c.l_critical());
    assert!((c.l_critical() - 2.31).abs() < 0.005);
    assert!((c.antikink_energy() - 0.161).abs() < 5e-4, "{}", c.antikink_energy());
    // docs/theory.md §6: F' = 15.24, decay length 0.367 a; §4: w = 1.14 a.
    assert!((c.cobweb_slope() - 15.24).abs() < 0.01, "{}", c.cobweb_slope());
    assert!((c.decay_length() - 0.367).abs() < 1e-3, "{}", c.decay_length());
    assert!((c.width() - 1.14).abs() < 5e-3, "{}", c.width());
    assert!((c.rest_length() - 1.670675).abs() < 1e-6);
}

#[test]
fn l_critical_is_the_spring_from_minus_to_plus_theta_bar() {
    for theta_bar in [0.1, 0.3, TB] {
        let c = chain(theta_bar, 1.0);
        let direct = spring_length(A, R, R, -theta_bar, theta_bar);
        assert!((c.l_critical() - direct).abs() < 1e-14);
        // ... the longest spring between two rotors in [-theta_bar, theta_bar] (Sec. VII-B: the
        // impurity is maximally stretched at x1 = x2 = 0).
        let mut longest: f64 = 0.0;
        for i in 0..=60 {
            for j in 0..=60 {
                let t1 = -theta_bar + 2.0 * theta_bar * i as f64 / 60.0;
                let t2 = -theta_bar + 2.0 * theta_bar * j as f64 / 60.0;
                longest = longest.max(spring_length(A, R, R, t1, t2));
            }
        }
        assert_eq!(longest, direct);
        let l0 = 2.0;
        assert!((c.critical_energy(l0) - 0.5 * (l0 - direct).powi(2)).abs() < 1e-15);
    }
}

#[test]
fn static_walls_run_between_the_uniform_states() {
    let c = paper();
    let far = 40.0;
    assert!((c.angle(Charge::Kink, -far, 0.0) - TB).abs() < 1e-12);
    assert!((c.angle(Charge::Kink, far, 0.0) + TB).abs() < 1e-12);
    assert!((c.angle(Charge::Antikink, -far, 3.0) + TB).abs() < 1e-12);
    assert_eq!(c.angle(Charge::Kink, 2.5, 2.5), 0.0);
    // The kink is a zero of the bracket of Eq. eq:continuouspotential: a^2/2 u' = u^2 - ubar^2.
    let h = 1e-5;
    for x in [-2.0, -0.3, 0.0, 0.8, 3.0] {
        let u = c.field(Charge::Kink, x, 0.1);
        let du = (c.field(Charge::Kink, x + h, 0.1) - c.field(Charge::Kink, x - h, 0.1)) / (2.0 * h);
        assert!(c.potential_density(u, du) < 1e-18, "{x}");
    }
    let profile = c.angle_profile(Charge::Kink, 9, 4.0).unwrap();
    assert_eq!(profile.len(), 9);
    assert_eq!(profile[4], 0.0);
    assert!(profile.windows(2).all(|p| p[1] < p[0]));
    // A profile is a chain's: its rotor count is checked before anything is allocated.
    let too_many = c.angle_profile(Charge::Kink, chain_core::geometry::MAX_ROTORS + 1, 0.0);
    assert!(matches!(too_many, Err(chain_core::ParameterError::TooManyRotors { .. })), "{too_many:?}");
    assert!(matches!(
        c.angle_profile(Charge::Kink, 1, 0.0),
        Err(chain_core::ParameterError::TooFewRotors { n: 1 })
    ));
}

#[test]
fn moving_walls_are_lorentz_contracted() {
    let c = chain(0.3, 4.0);
    let speed = 0.6 * c.sound_speed();
    // At t = 2 the centre has moved by 2 v and the width has shrunk by sqrt(1 - 0.36) = 0.8.
    for x in [-1.0, 0.4, 2.0] {
        let moving = c.moving_field(Charge::Antikink, 2.0 * speed + 0.8 * x, 2.0, 0.0, speed).unwrap();
        assert!((moving - c.field(Charge::Antikink, x, 0.0)).abs() < 1e-14);
    }
    let static_angle = c.angle(Charge::Kink, 0.7, 0.2);
    assert!((c.moving_angle(Charge::Kink, 0.7, 5.0, 0.2, 0.0).unwrap() - static_angle).abs() < 1e-15);
    assert!(matches!(
        c.moving_field(Charge::Kink, 0.0, 0.0, 0.0, -c.sound_speed()),
        Err(ContinuumError::NotSubsonic { .. })
    ));
    assert!(c.moving_field(Charge::Kink, 0.0, 0.0, 0.0, f64::NAN).is_err());
    // c = (a^2 / lbar) sqrt(k / M).
    let lbar = (A * A + 4.0 * R * R * 0.3f64.cos().powi(2)).sqrt();
    assert!((c.sound_speed() - A * A / lbar * (4.0f64 / 1.3).sqrt()).abs() < 1e-14);
}

#[test]
fn shape_mode_is_the_phi4_fraction_of_the_gap() {
    for theta_bar in [0.05, 0.3, TB] {
        let (k, m) = (1e4, 1.0);
        let c = ContinuumChain::new(A, R, theta_bar, k, m).unwrap();
        let rho = R / A;
        let printed = rho * (12.0 * k / m).sqrt() * theta_bar.sin()
            / (1.0 + 4.0 * rho * rho * theta_bar.cos().powi(2)).sqrt();
        assert!((c.shape_mode_frequency() - printed).abs() < 1e-12 * printed);
        assert!(
            (c.shape_mode_frequency() - 0.75f64.sqrt() * c.continuum_phonon_gap()).abs() < 1e-12 * printed
        );
        assert_eq!(c.translation_mode_frequency(), 0.0);
        // The lattice band bottom is the continuum gap times cos(theta_bar).
        let [bottom, top] = c.phonon_band_edges();
        assert!((bottom - c.continuum_phonon_gap() * theta_bar.cos()).abs() < 1e-12 * bottom);
        let lbar = c.rest_length();
        assert!((top - 2.0 * A * theta_bar.cos() * (k / m).sqrt() / lbar).abs() < 1e-12 * top);
    }
}

#[test]
fn sech4_transform_matches_quadrature() {
    for s in [0.0, 1e-6, 0.5, 2.0, 2.0 * PI * 1.14, 12.0, -3.0] {
        let numeric = simpson(|t| (s * t).cos() / t.cosh().powi(4), -30.0, 30.0, 60_000);
        let closed = sech4_fourier_transform(s);
        assert!((numeric - closed).abs() < 1e-12, "s = {s}: {numeric} vs {closed}");
    }
    assert_eq!(sech4_fourier_transform(1e4), 0.0);
}

/// `sum_n f(n, X)`, `f = (8 k ubar^4 / lbar^2) sech^4((n a - X)/w)`: the discretised continuum energy
/// of Eqs. eq:PNsum and eq:PNoneterm2, summed directly.
fn lattice_sum(theta_bar: f64, k: f64, x: f64) -> f64 {
    let ub = R * theta_bar.sin();
    let w = A * A / (2.0 * ub);
    let l2 = A * A + 4.0 * R * R * theta_bar.cos().powi(2);
    let pref = 8.0 * k * ub.powi(4) / l2;
    (-4000..=4000).map(|n| pref / ((n as f64 * A - x) / w).cosh().powi(4)).sum()
}

#[test]
fn pn_potential_is_the_lattice_sum() {
    for w in [1.02, 1.14, 1.6, 3.0] {
        let tb = theta_for_width(w);
        let c = chain(tb, 3.0);
        for x in [0.0, 0.1, 0.25, 0.5, 0.77, 1.3] {
            let direct = lattice_sum(tb, 3.0, x);
            assert!((c.pn_potential(x) - direct).abs() < 1e-13 * direct, "w {w}, X {x}");
        }
    }
}

#[test]
fn pn_barrier_is_the_height_of_the_first_harmonic() {
    for w in [1.02, 1.14, 1.4, 1.8, 2.2] {
        let tb = theta_for_width(w);
        let c = chain(tb, 1.0);
        assert!((c.width() - w).abs() < 1e-12);
        // The lattice sum is largest with the centre on a site, smallest half-way.
        let (top, bottom) = (lattice_sum(tb, 1.0, 0.0), lattice_sum(tb, 1.0, 0.5 * A));
        let height = top - bottom;
        assert!(height > 0.0);
        // Harmonics 3, 5, ... are down by 27 exp(-2 pi^2 w/a) < 1e-7; the difference of two sums
        // of size ~1 loses ~1e-16 / height.
        let tol = 1e-7 + 1e-14 / height;
        assert!((c.pn_barrier() - height).abs() < tol * height, "w {w}: {} vs {height}", c.pn_barrier());
        // The printed Eq. eq:PNB2 is the amplitude: half the height.
        assert!((2.0 * c.pn_barrier_as_printed() - c.pn_barrier()).abs() < 1e-14 * c.pn_barrier());
        // ... and is written with 1 + 4 (r/a)^2 - (a/w)^2 = lbar^2 / a^2.
        let y = w / A;
        let printed = 4.0 * PI * PI * (PI * PI + 1.0 / (y * y))
            / (3.0 * (1.0 + 4.0 * (R / A).powi(2) - 1.0 / (y * y)) * (PI * PI * y).sinh());
        assert!((c.pn_barrier_as_printed() - printed).abs() < 1e-12 * printed);
    }
}

#[test]
fn pn_barrier_decays_with_slope_minus_pi_squared() {
    // d ln V / d(w/a) by finite differences along theta_bar (fixed r/a).
    for w in [1.2, 2.0, 4.0, 8.0] {
        let h = 1e-5;
        let ln_v = |w: f64| chain(theta_for_width(w), 1.0).pn_barrier().ln();
        let numeric = (ln_v(w + h) - ln_v(w - h)) / (2.0 * h);
        let closed = chain(theta_for_width(w), 1.0).pn_log_slope();
        assert!((numeric - closed).abs() < 1e-6 * closed.abs(), "w {w}: {numeric} vs {closed}");
    }
    let wide = chain(theta_for_width(20.0), 1.0).pn_log_slope();
    assert!((wide - PN_ASYMPTOTIC_LOG_SLOPE).abs() < 1e-3, "{wide}");
    assert_eq!(PN_ASYMPTOTIC_LOG_SLOPE, -PI * PI);
}

#[test]
fn spring_length_derivatives_match_finite_differences() {
    for theta_bar in [0.1, 0.4, TB] {
        let c = chain(theta_bar, 1.0);
        let (alpha, beta) = c.spring_length_derivatives();
        let h = 1e-6;
        let fd_alpha = (spring_length(A, R, R, theta_bar + h, theta_bar)
            - spring_length(A, R, R, theta_bar - h, theta_bar))
            / (2.0 * h);
        let fd_beta = (spring_length(A, R, R, theta_bar, theta_bar + h)
            - spring_length(A, R, R, theta_bar, theta_bar - h))
            / (2.0 * h);
        assert!((alpha - fd_alpha).abs() < 1e-9, "{alpha} vs {fd_alpha}");
        assert!((beta - fd_beta).abs() < 1e-9, "{beta} vs {fd_beta}");
        assert!((c.cobweb_slope() + alpha / beta).abs() < 1e-12 * c.cobweb_slope());
    }
}

/// `dl/dtheta_p` and `dl/dtheta_{p+1}` of one spring, from the geometry, at any angles.
fn length_gradient(t1: f64, t2: f64) -> (f64, f64) {
    let dx = A + R * t2.sin() - R * t1.sin();
    let dy = R * t1.cos() + R * t2.cos();
    let l = (dx * dx + dy * dy).sqrt();
    ((-dx * R * t1.cos() - dy * R * t1.sin()) / l, (dx * R * t2.cos() - dy * R * t2.sin()) / l)
}

fn sorted_eigenvalues(m: DMatrix<f64>) -> Vec<f64> {
    let mut ev: Vec<f64> = SymmetricEigen::new(m).eigenvalues.iter().copied().collect();
    ev.sort_by(f64::total_cmp);
    ev
}

#[test]
fn finite_chain_spectrum_matches_the_dense_eigensolver() {
    let k = 2.5;
    for (theta_bar, n) in [(TB, 2), (TB, 3), (TB, 17), (0.2, 40), (0.45, 61)] {
        let c = chain(theta_bar, k);
        let (alpha, beta) = length_gradient(theta_bar, theta_bar);
        let mut compat = DMatrix::<f64>::zeros(n - 1, n);
        for p in 0..n - 1 {
            compat[(p, p)] = alpha;
            compat[(p, p + 1)] = beta;
        }
        let dense = sorted_eigenvalues(compat.transpose() * &compat * k);
        let closed = c.finite_chain_spectrum(n).unwrap();
        assert_eq!(closed.len(), n);
        for (x, y) in closed.iter().zip(&dense) {
            assert!((x - y).abs() < 1e-10, "n {n}: {x} vs {y}");
        }
        let omegas = c.finite_chain_frequencies(n).unwrap();
        assert!((omegas[n - 1] - (closed[n - 1] / (1.3 * R * R)).sqrt()).abs() < 1e-14);
    }
    assert!(matches!(paper().finite_chain_spectrum(1), Err(ParameterError::TooFewRotors { n: 1 })));
}

#[test]
fn finite_chain_spectrum_matches_the_generated_tangent_stiffness() {
    // The harmonic RuntimeChain's tangent stiffness at theta_i = theta_bar is k C^T C.
    let (n, k) = (24, 3.0);
    let model = RuntimeChain::builder(n, R, k, TB).build().unwrap();
    let k_matrix = SymmetricMatrix::tangent_stiffness(&model, &vec![TB; n]).unwrap();
    let (diag, off) = k_matrix.bands().unwrap();
    let dense = DMatrix::from_fn(n, n, |i, j| match i.abs_diff(j) {
        0 => diag[i],
        1 => off[i.min(j)],
        _ => 0.0,
    });
    let closed = chain(TB, k).finite_chain_spectrum(n).unwrap();
    for (x, y) in closed.iter().zip(sorted_eigenvalues(dense)) {
        assert!((x - y).abs() < 1e-10, "{x} vs {y}");
    }
}

#[test]
fn decay_length_tends_to_half_the_width() {
    // ln F' = ln((1 + a/w)/(1 - a/w)) ~ 2a/w: the lattice tail decays like the tanh's exp(-2x/w).
    for theta_bar in [0.02, 0.005] {
        let c = chain(theta_bar, 1.0);
        let ratio = c.decay_length() / (0.5 * c.width());
        assert!((ratio - 1.0).abs() < 2.0 * (A / c.width()).powi(2), "{ratio}");
    }
}

#[test]
fn bad_parameters_are_rejected_with_the_numbers() {
    assert!(matches!(
        ContinuumChain::new(A, R, 0.7, 1.0, 1.0),
        Err(ParameterError::OutsideFlipperPhase { theta_bar, .. }) if theta_bar == 0.7
    ));
    assert!(matches!(ContinuumChain::new(A, R, TB, -1.0, 1.0), Err(ParameterError::NotPositive { .. })));
    assert!(matches!(ContinuumChain::new(A, R, TB, 1.0, f64::NAN), Err(ParameterError::NotPositive { .. })));
    assert!(ContinuumChain::new(0.0, R, TB, 1.0, 1.0).is_err());
}
