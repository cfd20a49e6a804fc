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
//! gradient evaluation and two O(n) sweeps. Stability needs `omega_max dt < 2` for the fastest
//! mode; [`VerletOptions::stable_for`] picks `dt` from a bound on `omega_max`.

use alloc::vec;
use alloc::vec::Vec;

use super::{
    Flow, IntegrateError, Monitor, Report, State, check_non_negative, check_option, check_positive,
    inverse_inertia, not_finite,
};
use crate::model::ChainModel;
use crate::statics::equilibrium;

/// Settings of [`verlet`]. There is no sensible default step: it depends on the stiffness
/// (the fastest phonon, `omega_max ~ sqrt(k / M)`); use [`VerletOptions::stable_for`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VerletOptions {
    /// Time step, in the time unit `t` of paper Appendix B. [`verlet`] shortens it slightly if
    /// needed so that a whole number of equal steps ends exactly at `t_end`.
    pub dt: f64,
    /// Damping rate `gamma >= 0` in `1 / t` (0: Newtonian dynamics).
    pub damping: f64,
}

impl VerletOptions {
    /// The default of `safety` in [`stable_for`](Self::stable_for): `omega_max dt <= 0.2`. Verlet
    /// is stable up to 2, but a mode of frequency `omega` comes out with a relative frequency
    /// error `(omega dt)^2 / 24` and an energy that oscillates by a fraction `(omega dt)^2 / 4`
    /// about the conserved modified energy: 0.2 keeps both within 1 % for the fastest phonons
    /// (and far within for the slow motion of a kink), and leaves room for the stiffness to grow
    /// along a nonlinear trajectory.
    pub const DEFAULT_SAFETY: f64 = 0.1;

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
        let omega_max = crate::math::sqrt(norm * max_inverse_inertia);
        Ok(Self { dt: safety * 2.0 / omega_max, damping: 0.0 })
    }
}

/// The number of equal steps of at most `dt` that cover `span`: a span that is a whole number of
/// steps up to rounding takes exactly that many.
fn step_count(span: f64, dt: f64) -> usize {
    let ratio = span / dt;
    let nearest = libm::round(ratio);
    // `as` saturates: an absurd ratio gives a long run, never a panic.
    if (ratio - nearest).abs() <= 1e-9 * nearest.max(1.0) {
        nearest as usize
    } else {
        libm::ceil(ratio) as usize
    }
}

/// Integrates `state` to `t_end` with velocity Verlet (module doc), calling `observer` on the
/// initial state, after every `output_every` steps and after the last step.
///
/// The steps are equal, `dt' = (t_end - t0) / ceil((t_end - t0) / dt) <= dt`, and the last one
/// ends exactly at `t_end`. On return `state` holds the last state the observer saw (the final
/// one unless it stopped the run). On [`IntegrateError::NotFinite`] during the run `state` holds
/// the step that went non-finite.
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
    check_non_negative("damping", options.damping)?;
    check_option("output_every", output_every as f64, output_every > 0, "at least 1")?;
    if !t_end.is_finite() {
        return Err(IntegrateError::NotFinite { what: "t_end", time: state.time, index: 0, value: t_end });
    }
    if t_end < state.time {
        return Err(IntegrateError::EndBeforeStart { start: state.time, end: t_end });
    }
    let inverse = inverse_inertia(model)?;
    let n = inverse.len();
    let t0 = state.time;
    let steps = step_count(t_end - t0, options.dt);
    let dt = if steps == 0 { 0.0 } else { (t_end - t0) / steps as f64 };
    // The kick `omega -= dt/2 * dV/dtheta / I` with the factor folded in once.
    let half_kick: Vec<f64> = inverse.iter().map(|x| 0.5 * dt * x).collect();
    let decay = crate::math::exp(-0.5 * options.damping * dt);

    let mut monitor = Monitor::new(model, state);
    if monitor.output(model, state, observer) {
        return Ok(monitor.report);
    }
    let mut g = vec![0.0; n];
    model.gradient_into(&state.theta, &mut g);
    not_finite("gradient", t0, &g)?;
    for step in 1..=steps {
        let (theta, omega) = (&mut state.theta[..n], &mut state.omega[..n]);
        for (((t, w), gi), c) in theta.iter_mut().zip(omega.iter_mut()).zip(&g).zip(&half_kick) {
            *w = *w * decay - c * gi;
            *t += dt * *w;
        }
        model.gradient_into(theta, &mut g);
        let mut finite = true;
        for ((w, gi), c) in omega.iter_mut().zip(&g).zip(&half_kick) {
            *w = (*w - c * gi) * decay;
            finite &= w.is_finite();
        }
        // Times from the step count, not a running sum, so they carry no accumulated rounding.
        state.time = if step == steps { t_end } else { t0 + step as f64 * dt };
        if !finite {
            // A NaN force gives a NaN velocity; an unstable step grows both until they overflow.
            not_finite("theta", state.time, &state.theta)?;
            not_finite("omega", state.time, &state.omega)?;
        }
        monitor.report.steps = step;
        if (step % output_every == 0 || step == steps) && monitor.output(model, state, observer) {
            break;
        }
    }
    Ok(monitor.report)
}
