//! The integrators of `I_i thetadd_i = -dV/dtheta_i - gamma I_i thetadot_i` (paper Secs. V, VI,
//! Appendix B) against known solutions: damped harmonic oscillators in closed form, the exact
//! normal modes of the uniform chain (and Verlet's exactly known discrete frequency), a very
//! accurate reference run, and the conservation or decay of the energy. Then the typed errors,
//! early stops, and (ignored, run in release) the cost per step.

use std::f64::consts::PI;

use chain_core::integrate::{
    AdaptiveOptions, Flow, IntegrateError, Report, State, VerletOptions, adaptive, kinetic_energy,
    total_energy, verlet,
};
use chain_core::statics::continuum::ContinuumChain;
use chain_core::statics::kink::kink;
use chain_core::{ChainGeometry, Potential, RuntimeChain};

const R: f64 = 0.8;
const K: f64 = 1e4;
const TB: f64 = 0.58;

/// Test models with closed-form dynamics.
mod models {
    use chain_core::model::{Potential, Stiffness, StiffnessLayout};

    /// Uncoupled harmonic rotors, `V = sum_i kappa_i theta_i^2 / 2`, `I_i = r_i^2` (`M = 1`); the
    /// gradient turns NaN where `|theta_i| > nan_beyond` (a force law that breaks down).
    pub struct Oscillators {
        pub kappa: Vec<f64>,
        pub r: Vec<f64>,
        pub nan_beyond: f64,
    }

    impl Oscillators {
        pub fn new(kappa: &[f64], r: &[f64]) -> Self {
            Self { kappa: kappa.to_vec(), r: r.to_vec(), nan_beyond: f64::INFINITY }
        }

        /// `omega_0 = sqrt(kappa / I)` of rotor `i`.
        pub fn frequency(&self, i: usize) -> f64 {
            (self.kappa[i] / (self.r[i] * self.r[i])).sqrt()
        }

        /// The exact `(theta, omega)` at `t` from `(theta0, omega0)` with damping `gamma`
        /// (underdamped): `e^{-gamma t/2} (A cos w t + C sin w t)`, `w^2 = omega_0^2 - gamma^2/4`.
        pub fn exact(&self, i: usize, theta0: f64, omega0: f64, gamma: f64, t: f64) -> (f64, f64) {
            let w0 = self.frequency(i);
            let w = (w0 * w0 - 0.25 * gamma * gamma).sqrt();
            let c = (omega0 + 0.5 * gamma * theta0) / w;
            let (s, co) = (w * t).sin_cos();
            let decay = (-0.5 * gamma * t).exp();
            let theta = decay * (theta0 * co + c * s);
            let omega = decay * (-0.5 * gamma * (theta0 * co + c * s) + w * (c * co - theta0 * s));
            (theta, omega)
        }
    }

    /// What the oscillators honestly are: a potential with inertias, and a (diagonal) tangent
    /// stiffness. They have no springs and no chain geometry, so they implement neither rung.
    impl Potential for Oscillators {
        fn dof_count(&self) -> usize {
            self.kappa.len()
        }
        fn inertia(&self, i: usize) -> f64 {
            self.r[i] * self.r[i]
        }
        fn energy(&self, theta: &[f64]) -> f64 {
            theta.iter().zip(&self.kappa).map(|(t, k)| 0.5 * k * t * t).sum()
        }
        fn gradient_into(&self, theta: &[f64], out: &mut [f64]) {
            for ((o, t), k) in out.iter_mut().zip(theta).zip(&self.kappa) {
                *o = if t.abs() > self.nan_beyond { f64::NAN } else { k * t };
            }
        }
    }

    impl Stiffness for Oscillators {
        fn stiffness_layout(&self) -> StiffnessLayout<'_> {
            StiffnessLayout::Tridiagonal
        }
        fn tangent_stiffness_into(&self, _: &[f64], values: &mut [f64]) {
            let (diag, off) = values.split_at_mut(self.kappa.len());
            diag.copy_from_slice(&self.kappa);
            off.fill(0.0);
        }
    }
}

use models::Oscillators;

fn chain(n: usize) -> RuntimeChain {
    RuntimeChain::builder(n, R, K, TB).build().unwrap()
}

/// A reproducible pseudo-random sequence in `[-1, 1)`, for broadband kicks.
fn noise(n: usize, seed: u64) -> Vec<f64> {
    test_support::random::SplitMix(seed).fill(n, -1.0, 1.0)
}

/// The paper's moving kink (Sec. V, Appendix B): the zero-energy kink at `centre`, with a
/// velocity along its translation direction `-dtheta/di` (central differences) scaled so the
/// kinetic energy is `M v0^2 / 2`.
fn moving_kink(model: &RuntimeChain, centre: f64, v0: f64) -> State {
    let theta = kink(model, centre).unwrap();
    let n = theta.len();
    let mut omega: Vec<f64> = (0..n)
        .map(|i| {
            let (lo, hi) = (i.saturating_sub(1), (i + 1).min(n - 1));
            -(theta[hi] - theta[lo]) / (hi - lo) as f64
        })
        .collect();
    let scale = (0.5 * model.mass() * v0 * v0 / kinetic_energy(model, &omega)).sqrt();
    omega.iter_mut().for_each(|w| *w *= scale);
    State { time: 0.0, theta, omega }
}

/// The uniform state `theta_bar` with a broadband kick of amplitude `kick` in the velocities.
fn kicked_uniform(n: usize, kick: f64) -> State {
    let omega = noise(n, 7).into_iter().map(|x| kick * x).collect();
    State { time: 0.0, theta: vec![TB; n], omega }
}

fn tight() -> AdaptiveOptions {
    AdaptiveOptions { rtol: 1e-13, atol: 1e-13, ..AdaptiveOptions::default() }
}

fn continue_always(_: &State) -> Flow {
    Flow::Continue
}

/// Integrates to `t_end` and returns the final state.
fn run_adaptive<M: Potential>(model: &M, start: &State, t_end: f64, options: &AdaptiveOptions) -> State {
    let mut state = start.clone();
    adaptive(model, &mut state, &[t_end], options, &mut continue_always).unwrap();
    state
}

fn run_verlet<M: Potential>(model: &M, start: &State, t_end: f64, options: &VerletOptions) -> State {
    let mut state = start.clone();
    verlet(model, &mut state, t_end, options, usize::MAX, &mut continue_always).unwrap();
    state
}

/// `max_i |a_i - b_i|` over angles and velocities.
fn distance(a: &State, b: &State) -> (f64, f64) {
    let d = |x: &[f64], y: &[f64]| x.iter().zip(y).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    (d(&a.theta, &b.theta), d(&a.omega, &b.omega))
}

// ---------------------------------------------------------------------------------------------
// Known solutions

#[test]
fn damped_oscillators_follow_the_closed_form() {
    let model = Oscillators::new(&[1.0, 40.0, 250.0], &[1.0, 0.8, 1.3]);
    let start = State { time: 0.0, theta: vec![0.3, -0.2, 0.1], omega: vec![0.0, 1.5, -2.0] };
    let t_end = 3.0;
    for gamma in [0.0, 0.7] {
        let exact = |s: &State| {
            (0..3).fold(0.0_f64, |m, i| {
                let (theta, omega) = model.exact(i, start.theta[i], start.omega[i], gamma, t_end);
                m.max((s.theta[i] - theta).abs()).max((s.omega[i] - omega).abs() / model.frequency(i))
            })
        };
        let options = AdaptiveOptions { damping: gamma, ..tight() };
        let error = exact(&run_adaptive(&model, &start, t_end, &options));
        assert!(error < 1e-11, "gamma {gamma}: DOP853 misses the closed form by {error:e}");
        // Verlet: second order, with or without the exact decay.
        let errors: Vec<f64> = [4e-3, 2e-3, 1e-3]
            .iter()
            .map(|&dt| {
                exact(&run_verlet(
                    &model,
                    &start,
                    t_end,
                    &VerletOptions { damping: gamma, ..VerletOptions::new(dt) },
                ))
            })
            .collect();
        for pair in errors.windows(2) {
            let ratio = pair[0] / pair[1];
            assert!((3.8..4.2).contains(&ratio), "gamma {gamma}: errors {errors:?}, ratio {ratio}");
        }
    }
}

/// The `j`-th normal mode of the uniform free chain (`docs/theory.md` §7): `H = k C^T C` with `C`
/// bidiagonal (`alpha` on the diagonal, `beta` above), so `v = C^T u` with `u_p = sin(j pi (p+1)/n)`
/// the eigenvectors of `C C^T` (tridiagonal Toeplitz), eigenvalue `k (alpha^2 + beta^2 + 2 alpha
/// beta cos(j pi / n))`. Returns `(omega_j, v / max|v|)`.
fn normal_mode(n: usize, j: usize) -> (f64, Vec<f64>) {
    let c = ContinuumChain::new(1.0, R, TB, K, 1.0).unwrap();
    let (alpha, beta) = c.spring_length_derivatives();
    let u: Vec<f64> = (0..n - 1).map(|p| (j as f64 * PI * (p + 1) as f64 / n as f64).sin()).collect();
    let v: Vec<f64> = (0..n)
        .map(|i| alpha * u.get(i).copied().unwrap_or(0.0) + if i > 0 { beta * u[i - 1] } else { 0.0 })
        .collect();
    let max = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let omega = c.phonon_frequency(j as f64 * PI / n as f64);
    let spectrum = c.finite_chain_frequencies(n).unwrap();
    assert!(spectrum.iter().any(|w| (w - omega).abs() < 1e-12 * omega), "omega_{j} is in the spectrum");
    (omega, v.into_iter().map(|x| x / max).collect())
}

#[test]
fn small_oscillations_are_the_exact_normal_modes() {
    let (n, eps) = (20, 1e-6);
    let model = chain(n);
    for j in [1, 7, 19] {
        let (omega, v) = normal_mode(n, j);
        let start = State::at_rest(v.iter().map(|x| TB + eps * x).collect());
        let t_end = 3.0 * 2.0 * PI / omega;
        // theta - theta_bar = eps v cos(omega t), up to O(eps^2) anharmonic terms.
        let deviation = |s: &State, w: f64| {
            s.theta
                .iter()
                .zip(&v)
                .fold(0.0_f64, |m, (t, x)| m.max((t - TB - eps * x * (w * t_end).cos()).abs()))
                / eps
        };
        let options = AdaptiveOptions { rtol: 1e-13, atol: 1e-15, ..AdaptiveOptions::default() };
        let d = deviation(&run_adaptive(&model, &start, t_end, &options), omega);
        assert!(d < 1e-4, "mode {j}: DOP853 deviates by {d:e} eps");
        // Verlet's discrete oscillation is known exactly: cos(w dt) = 1 - (omega dt)^2 / 2.
        let dt = t_end / 600.0;
        let discrete = (1.0 - 0.5 * (omega * dt).powi(2)).acos() / dt;
        let d = deviation(&run_verlet(&model, &start, t_end, &VerletOptions::new(dt)), discrete);
        assert!(d < 1e-4, "mode {j}: Verlet deviates by {d:e} eps from its discrete mode");
    }
}

#[test]
fn verlet_converges_at_second_order_on_the_nonlinear_chain() {
    let n = 12;
    let model = chain(n);
    let theta =
        noise(n, 3).iter().enumerate().map(|(i, x)| TB + 0.05 * (0.4 * i as f64).sin() + 0.01 * x).collect();
    let start = State::at_rest(theta);
    let t_end = 0.5;
    let reference = run_adaptive(&model, &start, t_end, &tight());
    let errors: Vec<f64> = [2e-3, 1e-3, 5e-4]
        .iter()
        .map(|&dt| distance(&run_verlet(&model, &start, t_end, &VerletOptions::new(dt)), &reference).0)
        .collect();
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((3.8..4.2).contains(&ratio), "errors {errors:?}: ratio {ratio}");
    }
}

// ---------------------------------------------------------------------------------------------
// Energy

#[test]
fn verlet_energy_error_is_bounded_over_a_long_run() {
    let n = 60;
    let model = chain(n);
    let mut state = kicked_uniform(n, 1.0);
    let options = VerletOptions::stable_for(&model, &state.theta, VerletOptions::DEFAULT_SAFETY).unwrap();
    let e0 = total_energy(&model, &state);
    let steps = 100_000;
    let mut errors = Vec::with_capacity(steps + 1);
    let t_end = steps as f64 * options.dt;
    let report = verlet(&model, &mut state, t_end, &options, 1, &mut |s: &State| {
        errors.push((total_energy(&model, s) - e0).abs());
        Flow::Continue
    })
    .unwrap();
    assert_eq!((report.steps, errors.len()), (steps, steps + 1));
    // Largest and mean error over a window of 1e4 steps.
    let window =
        |w: &[f64]| (w.iter().fold(0.0_f64, |m, &x| m.max(x)), w.iter().sum::<f64>() / w.len() as f64);
    let (first, first_mean) = window(&errors[..10_000]);
    let (last, last_mean) = window(&errors[steps - 10_000..]);
    // A broadband kick puts energy in the fastest phonons, where Verlet's energy error is a
    // fraction ~ (omega dt)^2 / 4 <= 1 % at the default safety.
    assert!(report.max_energy_error < 1e-2 * e0, "{report:?}, E0 = {e0}");
    assert!(
        last < 1.5 * first,
        "the energy error drifts: {first:e} in the first 1e4 steps, {last:e} in the last"
    );
    assert!(
        last_mean < 1.5 * first_mean,
        "the energy error drifts: on average {first_mean:e} in the first 1e4 steps, {last_mean:e} in the last"
    );
    assert!((report.max_energy_error - errors.iter().fold(0.0_f64, |m, &x| m.max(x))).abs() < 1e-12 * e0);
}

#[test]
fn adaptive_conserves_the_energy_of_a_moving_kink() {
    let model = chain(60);
    let mut state = moving_kink(&model, 20.0, 2.4);
    let e0 = total_energy(&model, &state);
    assert!((e0 - 0.5 * 2.4 * 2.4).abs() < 1e-10, "the kink costs no energy: E0 = {e0}");
    let outputs: Vec<f64> = (0..=40).map(|i| 0.5 * i as f64).collect();
    let report =
        adaptive(&model, &mut state, &outputs, &AdaptiveOptions::default(), &mut continue_always).unwrap();
    let relative = report.max_energy_error / e0;
    assert!(relative < 1e-9, "relative energy error {relative:e}: {report:?}");
    assert_eq!(state.time, 20.0);
    assert!(!report.stopped_early);
}

#[test]
fn dense_output_agrees_with_direct_integration() {
    let model = chain(60);
    let start = moving_kink(&model, 20.0, 2.4);
    let options = AdaptiveOptions { rtol: 1e-9, atol: 1e-9, ..AdaptiveOptions::default() };
    let outputs = [0.0, 0.37, 1.234, 1.2341, 2.5, 3.99];
    let mut seen = Vec::new();
    let mut state = start.clone();
    adaptive(&model, &mut state, &outputs, &options, &mut |s: &State| {
        seen.push(s.clone());
        Flow::Continue
    })
    .unwrap();
    assert_eq!(seen.len(), outputs.len());
    assert_eq!(seen[0], start);
    for (s, &t) in seen.iter().zip(&outputs).skip(1) {
        assert_eq!(s.time, t);
        let direct = run_adaptive(&model, &start, t, &options);
        let (dtheta, domega) = distance(s, &direct);
        // Both are global solutions at rtol = atol = 1e-9 along different step sequences.
        assert!(dtheta < 2e-8 && domega < 2e-8, "t = {t}: dense output off by {dtheta:e}, {domega:e}");
    }
}

#[test]
fn adaptive_error_decreases_with_rtol() {
    let model = chain(60);
    let start = moving_kink(&model, 20.0, 2.4);
    let t_end = 2.0;
    let reference = run_adaptive(&model, &start, t_end, &tight());
    let mut previous = f64::INFINITY;
    for rtol in [1e-5, 1e-7, 1e-9, 1e-11] {
        let options = AdaptiveOptions { rtol, atol: rtol, ..AdaptiveOptions::default() };
        let (dtheta, domega) = distance(&run_adaptive(&model, &start, t_end, &options), &reference);
        let error = dtheta.max(domega);
        assert!(error < previous, "rtol {rtol:e}: error {error:e} after {previous:e}");
        assert!(error < 100.0 * rtol, "rtol {rtol:e}: error {error:e}");
        previous = error;
    }
}

// ---------------------------------------------------------------------------------------------
// Damping

/// Runs `run` with an observer that checks that the energy never rises between outputs, and
/// returns the report and the final state.
fn check_relaxation(
    model: &RuntimeChain,
    run: impl FnOnce(&mut State, &mut dyn FnMut(&State) -> Flow) -> Report,
) {
    let n = model.rotor_count();
    let mut state = State { time: 0.0, theta: vec![TB; n], omega: vec![0.0; n] };
    for (i, x) in noise(n, 11).into_iter().enumerate() {
        state.theta[i] += 0.02 * x;
        state.omega[i] = 2.0 * x;
    }
    let mut previous = f64::INFINITY;
    let mut rises = 0;
    let report = run(&mut state, &mut |s: &State| {
        let e = total_energy(model, s);
        rises += usize::from(e > previous * (1.0 + 1e-12));
        previous = e;
        Flow::Continue
    });
    assert_eq!(rises, 0, "the energy rose at {rises} outputs: {report:?}");
    assert!(report.energy_final < 1e-8 * report.energy_initial, "{report:?}");
    let mut g = vec![0.0; n];
    model.gradient_into(&state.theta, &mut g);
    let force = g.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(force < 1e-7 * K, "relaxed toward an equilibrium: largest force {force:e}");
}

#[test]
fn damping_relaxes_toward_an_equilibrium() {
    let model = chain(30);
    let gamma = 10.0;
    check_relaxation(&model, |state, observer| {
        let outputs: Vec<f64> = (0..=60).map(|i| 0.05 * i as f64).collect();
        let options = AdaptiveOptions { damping: gamma, ..AdaptiveOptions::default() };
        adaptive(&model, state, &outputs, &options, observer).unwrap()
    });
    check_relaxation(&model, |state, observer| {
        let options = VerletOptions {
            damping: gamma,
            ..VerletOptions::stable_for(&model, &state.theta, VerletOptions::DEFAULT_SAFETY).unwrap()
        };
        verlet(&model, state, 3.0, &options, 50, observer).unwrap()
    });
}

// ---------------------------------------------------------------------------------------------
// Early stop

#[test]
fn observer_stop_ends_the_run() {
    let model = chain(30);
    let start = kicked_uniform(30, 1.0);
    let stop_at_third = || {
        let mut calls = 0;
        move |_: &State| {
            calls += 1;
            if calls == 3 { Flow::Stop } else { Flow::Continue }
        }
    };
    let mut state = start.clone();
    let outputs = [0.1, 0.2, 0.3, 0.4, 5.0];
    let report =
        adaptive(&model, &mut state, &outputs, &AdaptiveOptions::default(), &mut stop_at_third()).unwrap();
    assert!(report.stopped_early);
    assert_eq!(state.time, 0.3);

    let mut state = start.clone();
    let options = VerletOptions::new(1e-3);
    let report = verlet(&model, &mut state, 5.0, &options, 10, &mut stop_at_third()).unwrap();
    // Outputs at steps 0, 10, 20: it stops after 20 of 5000 steps.
    assert!(report.stopped_early);
    assert_eq!(report.steps, 20);
    assert!((state.time - 0.02).abs() < 1e-15);

    let report = verlet(&model, &mut start.clone(), 0.1, &options, 10, &mut continue_always).unwrap();
    assert!(!report.stopped_early);
    assert_eq!(report.steps, 100);
}

// ---------------------------------------------------------------------------------------------
// Errors

#[test]
fn bad_input_is_a_typed_error() {
    let model = chain(10);
    let good = State::at_rest(vec![TB; 10]);
    let verlet_options = VerletOptions::new(1e-3);
    let run_both = |state: &State| {
        let v = verlet(&model, &mut state.clone(), 1.0, &verlet_options, 1, &mut continue_always);
        let a =
            adaptive(&model, &mut state.clone(), &[1.0], &AdaptiveOptions::default(), &mut continue_always);
        (v.unwrap_err(), a.unwrap_err())
    };

    let mut nan = good.clone();
    nan.theta[4] = f64::NAN;
    for e in <[_; 2]>::from(run_both(&nan)) {
        assert!(matches!(e, IntegrateError::NotFinite { what: "theta", index: 4, .. }), "{e}");
    }
    let mut inf = good.clone();
    inf.omega[9] = f64::INFINITY;
    for e in <[_; 2]>::from(run_both(&inf)) {
        assert!(matches!(e, IntegrateError::NotFinite { what: "omega", index: 9, .. }), "{e}");
    }
    let mut short = good.clone();
    short.omega.pop();
    for e in <[_; 2]>::from(run_both(&short)) {
        assert_eq!(e, IntegrateError::WrongLength { what: "omega", len: 9, expected: 10 });
    }

    let mut state = good.clone();
    let mut run_verlet = |dt: f64, damping: f64, t_end: f64, every: usize| {
        verlet(
            &model,
            &mut state,
            t_end,
            &VerletOptions { damping, ..VerletOptions::new(dt) },
            every,
            &mut continue_always,
        )
        .unwrap_err()
    };
    assert!(matches!(run_verlet(0.0, 0.0, 1.0, 1), IntegrateError::InvalidOption { name: "dt", .. }));
    assert!(matches!(run_verlet(1e-3, -1.0, 1.0, 1), IntegrateError::InvalidOption { name: "damping", .. }));
    assert!(matches!(
        run_verlet(1e-3, 0.0, 1.0, 0),
        IntegrateError::InvalidOption { name: "output_every", .. }
    ));
    assert!(matches!(
        run_verlet(1e-3, 0.0, f64::NAN, 1),
        IntegrateError::InvalidOption { name: "t_end", .. }
    ));
    assert_eq!(run_verlet(1e-3, 0.0, -1.0, 1), IntegrateError::EndBeforeStart { start: 0.0, end: -1.0 });

    let mut state = good.clone();
    let mut run_adaptive = |outputs: &[f64], options: AdaptiveOptions| {
        adaptive(&model, &mut state, outputs, &options, &mut continue_always).unwrap_err()
    };
    let defaults = AdaptiveOptions::default();
    assert_eq!(
        run_adaptive(&[1.0, 0.5], defaults),
        IntegrateError::OutputsOutOfOrder { index: 1, time: 0.5, previous: 1.0 }
    );
    assert!(matches!(run_adaptive(&[-1.0], defaults), IntegrateError::OutputsOutOfOrder { index: 0, .. }));
    assert!(matches!(run_adaptive(&[f64::NAN], defaults), IntegrateError::NotFinite { what: "outputs", .. }));
    for (options, name) in [
        (AdaptiveOptions { rtol: -1.0, ..defaults }, "rtol"),
        (AdaptiveOptions { atol: 0.0, ..defaults }, "atol"),
        (AdaptiveOptions { initial_step: Some(0.0), ..defaults }, "initial_step"),
        (AdaptiveOptions { max_step: f64::NAN, ..defaults }, "max_step"),
        (AdaptiveOptions { min_step: 2.0, max_step: 1.0, ..defaults }, "min_step"),
        (AdaptiveOptions { max_steps: 0, ..defaults }, "max_steps"),
        (AdaptiveOptions { damping: f64::INFINITY, ..defaults }, "damping"),
    ] {
        let e = run_adaptive(&[1.0], options);
        assert!(matches!(e, IntegrateError::InvalidOption { name: n, .. } if n == name), "{name}: {e}");
    }

    assert!(matches!(
        VerletOptions::stable_for(&model, &good.theta, 0.0),
        Err(IntegrateError::InvalidOption { name: "safety", .. })
    ));
    assert!(matches!(
        VerletOptions::stable_for(&model, &good.theta[..3], 0.1),
        Err(IntegrateError::WrongLength { what: "theta", len: 3, expected: 10 })
    ));
    let free = Oscillators::new(&[0.0, 0.0], &[1.0, 1.0]);
    assert_eq!(
        VerletOptions::stable_for(&free, &[0.0, 0.0], 0.1),
        Err(IntegrateError::NoTimeScale { norm: 0.0 })
    );
    let massless = Oscillators::new(&[1.0, 1.0], &[1.0, 0.0]);
    let e =
        verlet(&massless, &mut State::at_rest(vec![0.0; 2]), 1.0, &verlet_options, 1, &mut continue_always);
    assert_eq!(e.unwrap_err(), IntegrateError::BadInertia { index: 1, inertia: 0.0 });
}

#[test]
fn a_nan_force_during_the_run_is_a_typed_error() {
    let mut model = Oscillators::new(&[1.0, 1.0], &[1.0, 1.0]);
    model.nan_beyond = 0.5;
    // Moving out of the region where the force is defined.
    let start = State { time: 0.0, theta: vec![0.0, 0.4], omega: vec![0.0, 1.0] };
    let mut state = start.clone();
    let options = VerletOptions::new(1e-2);
    let e = verlet(&model, &mut state, 1.0, &options, 1, &mut continue_always).unwrap_err();
    assert!(
        matches!(e, IntegrateError::NotFinite { what: "omega", index: 1, time, .. } if time > 0.05),
        "{e}"
    );
    assert!(state.omega[1].is_nan(), "the state shows the step that went wrong");
    // Already outside: the first force evaluation fails.
    let mut state = State { theta: vec![0.0, 0.6], ..start.clone() };
    let e =
        adaptive(&model, &mut state, &[1.0], &AdaptiveOptions::default(), &mut continue_always).unwrap_err();
    assert!(matches!(e, IntegrateError::NotFinite { what: "acceleration", index: 1, .. }), "{e}");
    // Running into the boundary: the error control cannot step across, and says so.
    let mut state = start;
    let e =
        adaptive(&model, &mut state, &[1.0], &AdaptiveOptions::default(), &mut continue_always).unwrap_err();
    assert!(
        matches!(e, IntegrateError::StepSizeTooSmall { .. } | IntegrateError::TooManySteps { .. }),
        "{e}"
    );
    assert!(state.theta.iter().chain(&state.omega).all(|x| x.is_finite()) && state.theta[1] <= 0.5);
}

#[test]
fn an_unstable_step_ends_in_a_typed_error() {
    // omega dt = 4, twice Verlet's stability limit: the oscillation grows ~14-fold per step. The
    // energy check stops it at the first output, long before it overflows.
    let model = Oscillators::new(&[100.0], &[1.0]);
    let mut state = State::at_rest(vec![0.1]);
    let options = VerletOptions::new(0.4);
    let e = verlet(&model, &mut state, 1e4, &options, 1, &mut continue_always).unwrap_err();
    assert!(
        matches!(e, IntegrateError::EnergyNotConserved { time, limit, .. } if time <= 0.4 && limit == 0.1),
        "{e}"
    );
    // With the check switched off it still ends in an error once the motion overflows.
    let options = VerletOptions { energy_limit: f64::INFINITY, ..options };
    let e =
        verlet(&model, &mut State::at_rest(vec![0.1]), 1e4, &options, 1, &mut continue_always).unwrap_err();
    assert!(matches!(e, IntegrateError::NotFinite { index: 0, time, .. } if time < 400.0), "{e}");
}

#[test]
fn steps_far_past_the_stability_limit_never_return_ok() {
    // The paper's chain with a moving kink: bounded forces (sines and cosines) never overflow,
    // so only the energy shows that the run went wrong. Every step from twice to 500 times the
    // stability limit must end in a typed error carrying the numbers, never in `Ok`.
    let model = chain(60);
    let start = moving_kink(&model, 30.0, 2.4);
    let limit = VerletOptions::stable_for(&model, &start.theta, 1.0).unwrap().dt;
    for factor in [2.0, 10.0, 50.0, 200.0, 500.0] {
        for every in [1, 7, 1000] {
            let mut state = start.clone();
            let options = VerletOptions::new(factor * limit);
            let e = verlet(&model, &mut state, 2.0, &options, every, &mut continue_always).unwrap_err();
            match e {
                IntegrateError::EnergyNotConserved { relative, limit, energy, initial, .. } => {
                    assert!(relative > limit && limit == 0.1 && energy != initial, "{factor}x: {e}");
                }
                IntegrateError::NotFinite { .. } => {}
                other => panic!("{factor}x, every {every}: {other}"),
            }
        }
    }
    // At the default step the same run is fine.
    let options = VerletOptions::stable_for(&model, &start.theta, VerletOptions::DEFAULT_SAFETY).unwrap();
    let report = verlet(&model, &mut start.clone(), 2.0, &options, 7, &mut continue_always).unwrap();
    assert!(report.relative_energy_error() < 1e-3);
}

#[test]
fn steps_that_underflow_or_run_out_are_typed_errors() {
    let model = Oscillators::new(&[100.0, 1.0], &[1.0, 1.0]);
    // At t = 1e17 a step of the oscillation's size is lost to rounding.
    let mut state = State { time: 1e17, theta: vec![0.1, 0.2], omega: vec![0.0, 0.0] };
    let e = adaptive(&model, &mut state, &[1e17 + 64.0], &AdaptiveOptions::default(), &mut continue_always);
    assert!(
        matches!(e, Err(IntegrateError::StepSizeTooSmall { time, step }) if time == 1e17 && step < 22.0),
        "{e:?}"
    );
    // A floor the error control must go below.
    let mut state = State::at_rest(vec![0.1, 0.2]);
    let options = AdaptiveOptions { min_step: 0.5, ..AdaptiveOptions::default() };
    let e = adaptive(&model, &mut state, &[10.0], &options, &mut continue_always);
    assert!(matches!(e, Err(IntegrateError::StepSizeTooSmall { time: 0.0, .. })), "{e:?}");
    // A budget that cannot cover the run even at the largest stable step: refused before the
    // first step, the state untouched, when the options carry the bound on the fastest mode
    // (from the tangent stiffness; the runs of `dynamics` fill it in).
    let omega_max = Some(chain_core::integrate::omega_bound(&model, &state.theta).unwrap().omega);
    let options = AdaptiveOptions { max_steps: 5, omega_max, ..AdaptiveOptions::default() };
    let e = adaptive(&model, &mut state, &[10.0], &options, &mut continue_always).unwrap_err();
    assert!(matches!(e, IntegrateError::StepBudget { budget: 5, .. }), "{e}");
    assert_eq!(state.time, 0.0);
    // Without the bound (a model with only a potential has none) the budget still ends the run.
    let options = AdaptiveOptions { max_steps: 5, ..AdaptiveOptions::default() };
    let e = adaptive(&model, &mut state.clone(), &[10.0], &options, &mut continue_always).unwrap_err();
    assert!(matches!(e, IntegrateError::TooManySteps { steps: 5, .. }), "{e}");
    // A budget the error control runs out of; the state is left at the last accepted step.
    let options = AdaptiveOptions { max_steps: 20, ..AdaptiveOptions::default() };
    let e = adaptive(&model, &mut state, &[10.0], &options, &mut continue_always).unwrap_err();
    let IntegrateError::TooManySteps { time, steps: 20 } = e else { panic!("{e}") };
    assert!(time > 0.0 && state.time == time);
}

#[test]
fn stable_step_respects_the_true_spectrum() {
    let n = 60;
    let model = chain(n);
    let options = VerletOptions::stable_for(&model, &vec![TB; n], VerletOptions::DEFAULT_SAFETY).unwrap();
    let c = ContinuumChain::new(1.0, R, TB, K, 1.0).unwrap();
    let omega_max = c.finite_chain_frequencies(n).unwrap().into_iter().fold(0.0, f64::max);
    let product = omega_max * options.dt;
    // Gershgorin bounds omega_max from above, by less than a factor 2 here.
    assert!(product <= 2.0 * VerletOptions::DEFAULT_SAFETY && product > 0.1, "omega_max dt = {product}");
    assert_eq!(options.damping, 0.0);
}
