//! Verlet runs of the dynamics (with `alloc`): [`VerletOptions`] and [`verlet`], integrating a
//! [`State`] to an end time through an output schedule, with damping, absorbing ends and the
//! energy monitor of the module [`integrate`](crate::integrate).

use alloc::vec::Vec;

use super::Verlet;
use crate::integrate::bound::omega_bound;
use crate::integrate::{
    DEFAULT_ENERGY_LIMIT, Flow, IntegrateError, Integrator, Monitor, Report, Schedule, Sponge, State,
    check_energy_limit, check_option, check_positive, check_step_budget, damping_rates, step_count,
};
use crate::model::{Potential, Stiffness};
use crate::validate::{Fields, Validate};

/// Settings of [`verlet`]. There is no sensible default step: it depends on the stiffness
/// (the fastest phonon, `omega_max ~ sqrt(k / M)`); use [`VerletOptions::stable_for`] or
/// [`VerletOptions::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VerletOptions {
    /// Time step, in the time unit `t` of paper Appendix B. [`verlet`] shortens it slightly if
    /// needed so that a whole number of equal steps ends exactly at `t_end`.
    pub dt: f64,
    /// Damping rate `gamma >= 0` of every degree of freedom, in `1 / t` (0: Newtonian dynamics).
    pub damping: f64,
    /// Absorbing ends: extra damping on the last degrees of freedom at each end. Default `None`.
    pub sponge: Option<Sponge>,
    /// The most steps a run may take; a run that would need more is refused before the first
    /// step ([`IntegrateError::StepBudget`]). Default [`VerletOptions::DEFAULT_MAX_STEPS`];
    /// between 1 and [`MAX_STEP_BUDGET`](crate::integrate::MAX_STEP_BUDGET) (10^10).
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

    /// `dt = safety * 2 / omega_max`, no damping, with `omega_max` bounded from the tangent
    /// stiffness at `x` ([`omega_bound`]). `safety` must lie in `(0, 1]`; `1` is the stability
    /// limit for the bound, which lies above the true `omega_max`.
    pub fn stable_for<M: Stiffness + ?Sized>(
        model: &M,
        x: &[f64],
        safety: f64,
    ) -> Result<Self, IntegrateError> {
        check_option(
            "VerletOptions::stable_for",
            "safety",
            safety,
            safety > 0.0 && safety <= 1.0,
            "in (0, 1]",
        )?;
        Ok(Self::new(safety * 2.0 / omega_bound(model, x)?.omega))
    }
}

/// Integrates `state` to `t_end` with velocity Verlet ([`Verlet`]), calling `observer` on the
/// initial state, after every `output_every` steps and after the last step.
///
/// The steps are equal, `dt' = (t_end - t0) / ceil((t_end - t0) / dt) <= dt`, and the last one
/// ends exactly at `t_end` (a positive span takes at least one step). The energy is checked at
/// every output against [`VerletOptions::energy_limit`], and a run needing more than
/// [`VerletOptions::max_steps`] steps is refused before it starts. On return `state` holds the
/// last state the observer saw (the final one unless it stopped the run). On an error during the
/// run `state` holds the step that broke.
pub fn verlet<M: Potential + ?Sized>(
    model: &M,
    state: &mut State,
    t_end: f64,
    options: &VerletOptions,
    output_every: usize,
    observer: &mut dyn FnMut(&State) -> Flow,
) -> Result<Report, IntegrateError> {
    state.check(model)?;
    options.validate()?;
    Fields("verlet").at_least_one("output_every", output_every as u64)?;
    let rates = damping_rates(model.dof_count(), options.damping, options.sponge)?;
    Fields("verlet").finite("t_end", t_end)?;
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
    // The stepper owns the state while it runs; it goes back to the caller however the run ends.
    let start = core::mem::replace(state, State { time: t0, theta: Vec::new(), omega: Vec::new() });
    let mut stepper = match Verlet::damped(model, start.clone(), dt, &rates) {
        Ok(s) => s,
        Err(e) => {
            *state = start;
            return Err(e);
        }
    };
    let mut outcome = Ok(());
    for step in 1..=steps {
        // Times from the step count, not a running sum, so they carry no accumulated rounding.
        let time = if step == steps { t_end } else { t0 + step as f64 * dt };
        if let Err(e) = stepper.step_to(model, time) {
            outcome = Err(e);
            break;
        }
        monitor.report.steps = step as usize;
        if step % output_every as u64 == 0 || step == steps {
            let potential = stepper.potential_energy(model);
            match monitor.output_with(model, stepper.state(), potential, observer) {
                Ok(false) => {}
                Ok(true) => break,
                Err(e) => {
                    outcome = Err(e);
                    break;
                }
            }
        }
    }
    *state = stepper.into_state();
    outcome.map(|()| monitor.report)
}

impl VerletOptions {
    /// The steps per output interval of a run through `schedule`: a whole number of equal steps,
    /// each at most `dt`. A run that needs more than [`VerletOptions::max_steps`] in all is
    /// [`IntegrateError::StepBudget`] before its first step; callers that check settings before
    /// any run (a phase diagram) ask the same question here.
    pub fn steps_per_output(&self, schedule: &Schedule) -> Result<f64, IntegrateError> {
        self.validate()?;
        check_positive("Schedule", "interval", schedule.interval)?;
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
        Ok(per_output)
    }
}

impl Validate for VerletOptions {
    type Error = IntegrateError;

    /// Every field in its range: `dt > 0` and finite, `damping >= 0` and finite, the sponge's,
    /// `max_steps` between 1 and [`MAX_STEP_BUDGET`](crate::integrate::MAX_STEP_BUDGET),
    /// `energy_limit > 0` (infinite: no check).
    fn validate(&self) -> Result<(), IntegrateError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { dt, damping, sponge, max_steps, energy_limit } = *self;
        let fields = Fields("VerletOptions");
        fields.positive("dt", dt)?;
        fields.non_negative("damping", damping)?;
        if let Some(sponge) = sponge {
            sponge.validate()?;
        }
        check_step_budget(fields, "max_steps", max_steps)?;
        check_energy_limit(fields, energy_limit)
    }
}

impl Integrator for VerletOptions {
    fn name(&self) -> &'static str {
        "verlet"
    }

    /// A whole number of equal steps per output interval, each at most `dt`.
    fn integrate<M: Potential + ?Sized>(
        &self,
        model: &M,
        state: &mut State,
        schedule: &Schedule,
        observer: &mut dyn FnMut(&State) -> Flow,
    ) -> Result<Report, IntegrateError> {
        let per_output = self.steps_per_output(schedule)?;
        let t_end = schedule.time(state.time, schedule.count);
        let options = VerletOptions { dt: schedule.interval / per_output, ..*self };
        verlet(model, state, t_end, &options, per_output as usize, observer)
    }
}
