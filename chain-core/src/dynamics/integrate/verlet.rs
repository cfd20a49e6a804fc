//! Velocity Verlet (kick-drift-kick) for `I_i thetadd_i = -dV/dtheta_i - gamma I_i thetadot_i`.
//!
//! The vector field splits into three exactly solvable flows: the drift `thetadot = omega`, the
//! kick `omegadot = -I^-1 dV/dtheta`, and the decay `omegadot = -gamma omega`, solved by
//! `omega -> e^{-gamma t} omega`. One step of length `dt` composes them symmetrically (Strang):
//!
//! ```text
//! decay(dt/2) kick(dt/2) drift(dt) kick(dt/2) decay(dt/2)
//! ```
//!
//! so it is second order and time-reversible (Hairer, Lubich and Wanner, *Geometric Numerical
//! Integration*, Secs. I.1.4 and II.5). Without damping the decay is the identity (the factor is
//! exactly 1.0), and what is left is the Stormer-Verlet map: symplectic, so it conserves a
//! modified energy `E + O(dt^2)` and the energy error oscillates with bounded amplitude instead
//! of drifting, over exponentially long times (GNI Sec. IX.8). With damping, applying the decay
//! exactly makes each step contract the symplectic form by exactly `e^{-gamma dt}`, as the true
//! flow does (a conformally symplectic integrator), and the phonon damping rate is exact at any
//! `dt`.
//!
//! The gradient at the end of a step is the one the next step starts with, so a step costs one
//! evaluation of the energy and gradient together ([`ChainModel::energy_and_gradient_into`]: one
//! pass, each angle's `sin_cos` once; the outputs' energies come with it) and two O(n) sweeps. Stability needs `omega_max dt < 2` for the fastest
//! mode; [`VerletOptions::stable_for`] picks `dt` from a bound on `omega_max`.

use alloc::vec;
use alloc::vec::Vec;

use super::{
    DEFAULT_ENERGY_LIMIT, Flow, IntegrateError, Integrator, Monitor, Report, Schedule, Sponge, State,
    check_option, check_positive, damping_rates, inverse_inertia, not_finite, step_count,
};
use crate::model::ChainModel;
use crate::statics::equilibrium;

/// Settings of [`verlet`]. There is no sensible default step: it depends on the stiffness
/// (the fastest phonon, `omega_max ~ sqrt(k / M)`); use [`VerletOptions::stable_for`] or
/// [`VerletOptions::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VerletOptions {
    /// Time step, in the time unit `t` of paper Appendix B. [`verlet`] shortens it slightly if
    /// needed so that a whole number of equal steps ends exactly at `t_end`.
    pub dt: f64,
    /// Damping rate `gamma >= 0` of every rotor, in `1 / t` (0: Newtonian dynamics).
    pub damping: f64,
    /// Absorbing ends: extra damping on the last rotors at each end. Default `None`.
    pub sponge: Option<Sponge>,
    /// The most steps a run may take; a run that would need more is refused before the first
    /// step ([`IntegrateError::StepBudget`]). Default [`VerletOptions::DEFAULT_MAX_STEPS`].
    pub max_steps: u64,
    /// The largest relative energy change before the run stops with
    /// [`IntegrateError::EnergyNotConserved`] (checked at every output). Default
    /// [`DEFAULT_ENERGY_LIMIT`]; infinite switches it off.
    pub energy_limit: f64,
}

impl VerletOptions {
    /// The default of `safety` in [`stable_for`](Self::stable_for): `omega_max dt <= 0.2`. Verlet
    /// is stable up to 2, but a mode of frequency `omega` comes out with a relative frequency
    /// error `(omega dt)^2 / 24` and an energy that oscillates by a fraction `(omega dt)^2 / 4`
    /// about the conserved modified energy: 0.2 keeps both within 1 % for the fastest phonons
    /// (and far within for the slow motion of a kink), and leaves room for the stiffness to grow
    /// along a nonlinear trajectory.
    pub const DEFAULT_SAFETY: f64 = 0.1;

    /// The default step budget: 1e8 steps, about 100 s for the paper's 60 rotors (1 µs per step).
    /// A run asking for more is almost always a step far shorter than intended.
    pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

    /// Step `dt`, no damping, the default budgets.
    pub fn new(dt: f64) -> Self {
        Self {
            dt,
            damping: 0.0,
            sponge: None,
            max_steps: Self::DEFAULT_MAX_STEPS,
            energy_limit: DEFAULT_ENERGY_LIMIT,
        }
    }

    /// `dt = safety * 2 / omega_max`, no damping, with `omega_max^2 <= ||K||_inf / I_min` for the
    /// tangent stiffness `K` at `theta` (Gershgorin: every eigenvalue of the generalized problem
    /// `K v = omega^2 I v` is at most `||K||_inf / I_min`), as in
    /// [`relax`](crate::statics::equilibrium::relax). `safety` must lie in `(0, 1]`; `1` is the
    /// stability limit for the bound, which lies above the true `omega_max`.
    pub fn stable_for<M: ChainModel + ?Sized>(
        model: &M,
        theta: &[f64],
        safety: f64,
    ) -> Result<Self, IntegrateError> {
        Ok(Self::new(safety * 2.0 / omega_bound(model, theta, safety)?))
    }
}

/// The Gershgorin bound on `omega_max` at `theta` (see [`VerletOptions::stable_for`]), after
/// checking the inputs.
pub fn omega_bound<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    safety: f64,
) -> Result<f64, IntegrateError> {
    check_option("safety", safety, safety > 0.0 && safety <= 1.0, "in (0, 1]")?;
    let n = model.rotor_count();
    if theta.len() != n {
        return Err(IntegrateError::WrongLength { what: "theta", len: theta.len(), expected: n });
    }
    not_finite("theta", 0.0, theta)?;
    let max_inverse_inertia = inverse_inertia(model)?.into_iter().fold(0.0, f64::max);
    if n == 0 {
        return Err(IntegrateError::NoTimeScale { norm: 0.0 });
    }
    let (diag, off) = equilibrium::stiffness(model, theta);
    let norm = equilibrium::norm(&diag, &off);
    if !(norm > 0.0 && norm.is_finite()) {
        return Err(IntegrateError::NoTimeScale { norm });
    }
    let omega = crate::math::sqrt(norm * max_inverse_inertia);
    if !omega.is_finite() {
        return Err(IntegrateError::NoStableStep { norm, inverse_inertia: max_inverse_inertia });
    }
    Ok(omega)
}

/// One velocity-Verlet step after another on a state: the one implementation of the damped
/// Verlet map (module doc), used by [`verlet`] and by the statics' dissipative relaxation
/// ([`relax`](crate::statics::equilibrium::relax)). Rotors can be held still.
pub struct Stepper<'a, M: ?Sized> {
    model: &'a M,
    state: &'a mut State,
    dt: f64,
    /// `dt / (2 I_i)`, 0 for a held rotor.
    half_kick: Vec<f64>,
    /// `exp(-gamma_i dt / 2)`.
    decay: Vec<f64>,
    /// `dV/dtheta` at the current angles.
    gradient: Vec<f64>,
    /// `V` at the current angles (from the same fused evaluation as the gradient).
    potential: f64,
}

impl<'a, M: ChainModel + ?Sized> Stepper<'a, M> {
    /// Prepares steps of `dt` from `state` (checked) with damping `rates` (one per rotor, each
    /// `>= 0`); evaluates the gradient once.
    pub fn new(model: &'a M, state: &'a mut State, dt: f64, rates: &[f64]) -> Result<Self, IntegrateError> {
        state.check(model)?;
        check_positive("dt", dt)?;
        let inverse = inverse_inertia(model)?;
        let n = inverse.len();
        if rates.len() != n {
            return Err(IntegrateError::WrongLength { what: "damping rates", len: rates.len(), expected: n });
        }
        if let Some(&bad) = rates.iter().find(|r| !(**r >= 0.0 && r.is_finite())) {
            return Err(IntegrateError::InvalidOption {
                name: "damping",
                value: bad,
                rule: "non-negative and finite",
            });
        }
        // The kick `omega -= dt/2 * dV/dtheta / I` with the factor folded in once.
        let half_kick = inverse.iter().map(|x| 0.5 * dt * x).collect();
        let decay = rates.iter().map(|g| crate::math::exp(-0.5 * g * dt)).collect();
        let mut gradient = vec![0.0; n];
        let potential = model.energy_and_gradient_into(&state.theta, &mut gradient);
        not_finite("gradient", state.time, &gradient)?;
        Ok(Self { model, state, dt, half_kick, decay, gradient, potential })
    }

    /// Holds rotor `i` still: its velocity becomes 0 and no force moves it (a Dirichlet end).
    pub fn hold(&mut self, i: usize) {
        self.half_kick[i] = 0.0;
        self.state.omega[i] = 0.0;
    }

    /// The state after the steps taken so far.
    pub fn state(&self) -> &State {
        self.state
    }

    /// `dV/dtheta` at the current angles.
    pub fn gradient(&self) -> &[f64] {
        &self.gradient
    }

    /// The potential energy `V` at the current angles, evaluated with the gradient in one pass
    /// ([`ChainModel::energy_and_gradient_into`]).
    pub fn potential(&self) -> f64 {
        self.potential
    }

    /// One step of `dt`, after which the state's time is `time` (the caller counts steps, so
    /// times carry no accumulated rounding). A non-finite velocity (a NaN force, or a step so
    /// far past the stability limit that the motion overflowed) is an error, and the state
    /// shows the step that went wrong.
    pub fn step(&mut self, time: f64) -> Result<(), IntegrateError> {
        let n = self.half_kick.len();
        let (theta, omega) = (&mut self.state.theta[..n], &mut self.state.omega[..n]);
        let dt = self.dt;
        for (((t, w), (g, c)), d) in theta
            .iter_mut()
            .zip(omega.iter_mut())
            .zip(self.gradient.iter().zip(&self.half_kick))
            .zip(&self.decay)
        {
            *w = *w * d - c * g;
            *t += dt * *w;
        }
        self.potential = self.model.energy_and_gradient_into(theta, &mut self.gradient);
        let mut finite = true;
        for ((w, (g, c)), d) in
            omega.iter_mut().zip(self.gradient.iter().zip(&self.half_kick)).zip(&self.decay)
        {
            *w = (*w - c * g) * d;
            finite &= w.is_finite();
        }
        self.state.time = time;
        if !finite {
            not_finite("theta", time, &self.state.theta)?;
            not_finite("omega", time, &self.state.omega)?;
        }
        Ok(())
    }
}

/// Integrates `state` to `t_end` with velocity Verlet (module doc), calling `observer` on the
/// initial state, after every `output_every` steps and after the last step.
///
/// The steps are equal, `dt' = (t_end - t0) / ceil((t_end - t0) / dt) <= dt`, and the last one
/// ends exactly at `t_end` (a positive span takes at least one step). The energy is checked at
/// every output against [`VerletOptions::energy_limit`], and a run needing more than
/// [`VerletOptions::max_steps`] steps is refused before it starts. On return `state` holds the
/// last state the observer saw (the final one unless it stopped the run). On an error during the
/// run `state` holds the step that broke.
pub fn verlet<M: ChainModel + ?Sized>(
    model: &M,
    state: &mut State,
    t_end: f64,
    options: &VerletOptions,
    output_every: usize,
    observer: &mut dyn FnMut(&State) -> Flow,
) -> Result<Report, IntegrateError> {
    state.check(model)?;
    check_positive("dt", options.dt)?;
    check_option("output_every", output_every as f64, output_every > 0, "at least 1")?;
    let rates = damping_rates(model.rotor_count(), options.damping, options.sponge)?;
    if !t_end.is_finite() {
        return Err(IntegrateError::InvalidOption { name: "t_end", value: t_end, rule: "finite" });
    }
    if t_end < state.time {
        return Err(IntegrateError::EndBeforeStart { start: state.time, end: t_end });
    }
    let t0 = state.time;
    let span = t_end - t0;
    let count = step_count(span, options.dt);
    if count > options.max_steps as f64 {
        return Err(IntegrateError::StepBudget {
            steps: count,
            dt: options.dt,
            span,
            budget: options.max_steps,
        });
    }
    let steps = count as u64;
    let dt = if steps == 0 { options.dt } else { span / steps as f64 };
    let damped = rates.iter().any(|&r| r > 0.0);
    let mut monitor = Monitor::new(model, state, damped, options.energy_limit)?;
    if monitor.output(model, state, observer)? {
        return Ok(monitor.report);
    }
    let mut stepper = Stepper::new(model, state, dt, &rates)?;
    for step in 1..=steps {
        // Times from the step count, not a running sum, so they carry no accumulated rounding.
        let time = if step == steps { t_end } else { t0 + step as f64 * dt };
        stepper.step(time)?;
        monitor.report.steps = step as usize;
        if (step % output_every as u64 == 0 || step == steps)
            && monitor.output_with(model, stepper.state(), stepper.potential(), observer)?
        {
            break;
        }
    }
    Ok(monitor.report)
}

impl Integrator for VerletOptions {
    fn name(&self) -> &'static str {
        "verlet"
    }

    /// A whole number of equal steps per output interval, each at most `dt`.
    fn integrate<M: ChainModel + ?Sized>(
        &self,
        model: &M,
        state: &mut State,
        schedule: &Schedule,
        observer: &mut dyn FnMut(&State) -> Flow,
    ) -> Result<Report, IntegrateError> {
        check_positive("dt", self.dt)?;
        check_positive("output_interval", schedule.interval)?;
        let per_output = libm::ceil(schedule.interval / self.dt - 1e-9).max(1.0);
        let total = per_output * schedule.count as f64;
        if per_output > self.max_steps as f64 || total > self.max_steps as f64 {
            let span = schedule.interval * schedule.count as f64;
            return Err(IntegrateError::StepBudget {
                steps: total.max(per_output),
                dt: self.dt,
                span,
                budget: self.max_steps,
            });
        }
        let t_end = schedule.time(state.time, schedule.count);
        let options = VerletOptions { dt: schedule.interval / per_output, ..*self };
        verlet(model, state, t_end, &options, per_output as usize, observer)
    }
}
