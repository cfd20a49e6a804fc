//! Propagating a launched defect: the integrator, the wall tracker, the kinetic-energy series and
//! the space-time image, with an early stop once the caller has seen enough.
//!
//! Every run is bounded by its inputs: the number of outputs by [`RunOptions::max_outputs`], the
//! number of steps by [`RunOptions::max_steps`] (Verlet) or [`AdaptiveOptions::max_steps`]
//! (DOP853), a space-time image by [`MAX_SPACE_TIME_VALUES`], and a run whose energy leaves
//! [`RunOptions::energy_limit`] stops with an error.

use alloc::vec::Vec;

use super::DynamicsError;
use super::track::{Snapshot, SpaceTime, Tracker};
/// The one way to choose an integrator ([`crate::integrate::Method`]), re-exported where runs are
/// configured.
pub use crate::integrate::Method;
use crate::integrate::{
    AdaptiveOptions, DEFAULT_ENERGY_LIMIT, Flow, IntegrateError, Integrator, Report, Schedule, Sponge, State,
    VerletOptions, check_step_budget, kinetic_energy,
};
use crate::model::{ChainModel, Potential, Stiffness};
use crate::validate::{Fields, Validate};

/// The most angles a space-time image ([`RunOptions::space_time`]) may hold: 2^27, 1 GiB of
/// `f64`. Checked before the run starts ([`IntegrateError::SpaceTimeBudget`]), so a run of a long
/// chain with many outputs fails at once instead of exhausting the memory after hours.
pub const MAX_SPACE_TIME_VALUES: usize = 1 << 27;

/// Settings of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// Stop at this time if nothing stopped the run before. Default 20 (the paper's runs).
    pub t_max: f64,
    /// Time between outputs (tracking, energies). Default 0.01.
    pub output_interval: f64,
    /// The integrator. Default [`Method::Verlet`].
    pub method: Method,
    /// Verlet step, positive and finite; `None` picks a tenth of the stability limit from the
    /// tangent stiffness ([`VerletOptions::DEFAULT_SAFETY`]). It is shortened to divide the
    /// output interval. Ignored by DOP853.
    pub dt: Option<f64>,
    /// Viscous damping `gamma` of every rotor, `>= 0` (0: conservative). Default 0.
    pub damping: f64,
    /// Absorbing ends: a damping sponge on the last rotors at each end ([`Sponge`]). Default
    /// `None` (the paper's free ends).
    pub absorbing_ends: Option<Sponge>,
    /// Keep the angles at every output for a space-time image. Default `false`.
    pub space_time: bool,
    /// The most outputs a run may have (its span divided by the output interval). Default
    /// 1 000 000 (the paper's runs have 2000). Between 1 and [`MAX_SPACE_TIME_VALUES`] (2^27):
    /// every output records at least one value (its kinetic energy), so the space-time image's
    /// bound on the values a run keeps bounds the outputs too.
    pub max_outputs: usize,
    /// The most Verlet steps a run may take. Default [`VerletOptions::DEFAULT_MAX_STEPS`];
    /// between 1 and [`MAX_STEP_BUDGET`](crate::integrate::MAX_STEP_BUDGET) (10^10), every
    /// integrator's bound.
    pub max_steps: u64,
    /// The largest relative energy change before the run stops with an error. Default
    /// [`DEFAULT_ENERGY_LIMIT`] (10 %).
    pub energy_limit: f64,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self {
            t_max: 20.0,
            output_interval: 0.01,
            method: Method::Verlet,
            dt: None,
            damping: 0.0,
            absorbing_ends: None,
            space_time: false,
            max_outputs: 1_000_000,
            max_steps: VerletOptions::DEFAULT_MAX_STEPS,
            energy_limit: DEFAULT_ENERGY_LIMIT,
        }
    }
}

impl Validate for RunOptions {
    type Error = IntegrateError;

    /// Every field in its range: `t_max` finite (a `t_max` before the state's time is
    /// [`IntegrateError::EndBeforeStart`] at the run), `output_interval > 0` and finite, the
    /// method's tolerances (`rtol >= 0`, `atol > 0`, finite), `dt > 0` and finite, `damping >= 0`
    /// and finite, the sponge's, `max_outputs` between 1 and [`MAX_SPACE_TIME_VALUES`],
    /// `max_steps` between 1 and [`MAX_STEP_BUDGET`](crate::integrate::MAX_STEP_BUDGET),
    /// `energy_limit > 0` (infinite: no check). The errors are the integrator's, as the run would
    /// report them.
    fn validate(&self) -> Result<(), IntegrateError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self {
            t_max,
            output_interval,
            method,
            dt,
            damping,
            absorbing_ends,
            space_time: _,
            max_outputs,
            max_steps,
            energy_limit,
        } = *self;
        let fields = Fields("RunOptions");
        fields.finite("t_max", t_max)?;
        fields.positive("output_interval", output_interval)?;
        if let Method::Dop853 { rtol, atol } = method {
            fields.non_negative("method.rtol", rtol)?;
            fields.positive("method.atol", atol)?;
        }
        if let Some(dt) = dt {
            fields.positive("dt", dt)?;
        }
        fields.non_negative("damping", damping)?;
        if let Some(sponge) = absorbing_ends {
            sponge.validate()?;
        }
        fields.count_in(
            "max_outputs",
            max_outputs as u64,
            1,
            MAX_SPACE_TIME_VALUES as u64,
            "between 1 and MAX_SPACE_TIME_VALUES = 134217728 (an output records at least one value)",
        )?;
        check_step_budget(fields, "max_steps", max_steps)?;
        fields.rule("energy_limit", energy_limit, energy_limit > 0.0, "positive (infinite: no check)")?;
        Ok(())
    }
}

/// The sponge of [`RunOptions::absorbing_ends`] that the docs measure: 10 rotors at each end, a
/// rate of 30 / t at the end rotor. It absorbs the phonons that would otherwise flip a free end
/// of an antikink's domain (docs/dynamics.md §5).
pub const ABSORBING_ENDS: Sponge = Sponge { width: 10, strength: 30.0 };

/// The integrator [`RunOptions`] asks for, with its step and damping: either kind, behind
/// [`Integrator`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RunIntegrator {
    /// Velocity Verlet with these options.
    Verlet(VerletOptions),
    /// DOP853 with these options.
    Dop853(AdaptiveOptions),
}

impl Integrator for RunIntegrator {
    fn name(&self) -> &'static str {
        match self {
            RunIntegrator::Verlet(v) => v.name(),
            RunIntegrator::Dop853(a) => a.name(),
        }
    }

    fn integrate<M: Potential + ?Sized>(
        &self,
        model: &M,
        state: &mut State,
        schedule: &Schedule,
        observer: &mut dyn FnMut(&State) -> Flow,
    ) -> Result<Report, IntegrateError> {
        match self {
            RunIntegrator::Verlet(v) => v.integrate(model, state, schedule, observer),
            RunIntegrator::Dop853(a) => a.integrate(model, state, schedule, observer),
        }
    }
}

impl RunOptions {
    /// The integrator of these options for `model` starting from `theta` (Verlet's default step
    /// comes from the tangent stiffness there).
    pub fn integrator<M: Stiffness + ?Sized>(
        &self,
        model: &M,
        theta: &[f64],
    ) -> Result<RunIntegrator, DynamicsError> {
        self.validate()?;
        Ok(match self.method {
            Method::Verlet => {
                // A given `dt` is checked where every Verlet run checks it (`VerletOptions::integrate`).
                let dt = match self.dt {
                    Some(dt) => dt,
                    None => VerletOptions::stable_for(model, theta, VerletOptions::DEFAULT_SAFETY)?.dt,
                };
                RunIntegrator::Verlet(VerletOptions {
                    dt,
                    damping: self.damping,
                    sponge: self.absorbing_ends,
                    max_steps: self.max_steps,
                    energy_limit: self.energy_limit,
                })
            }
            Method::Dop853 { rtol, atol } => RunIntegrator::Dop853(AdaptiveOptions {
                rtol,
                atol,
                damping: self.damping,
                sponge: self.absorbing_ends,
                energy_limit: self.energy_limit,
                omega_max: crate::integrate::omega_bound(model, theta).ok().map(|b| b.omega),
                ..AdaptiveOptions::default()
            }),
        })
    }
}

/// What a run recorded.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// The walls at every output (Appendix C).
    pub tracker: Tracker,
    /// `(t, kinetic energy)` at every output (paper Fig. `fig:ketimeplot`).
    pub kinetic: Vec<(f64, f64)>,
    /// The angles at every output, if [`RunOptions::space_time`] was set.
    pub space_time: SpaceTime,
    /// Steps taken and the energy record.
    pub report: Report,
    /// The state at the end of the run.
    pub final_state: State,
    /// Which integrator ran: `verlet` or `dop853`.
    pub integrator: &'static str,
}

/// Runs `state` with the integrator of `options`, recording at every output and asking `stop`
/// after each snapshot whether to end the run.
/// # Example
///
/// ```
/// use rotor_chain::RuntimeChain;
/// use rotor_chain::dynamics::integrate::State;
/// use rotor_chain::dynamics::run::{RunOptions, propagate};
/// use rotor_chain::statics::kink::kink;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let chain = RuntimeChain::builder(30, 0.8, 1.0e4, 0.58).build()?;
/// let state = State::at_rest(kink(&chain, 15.0)?);          // a static kink stays put
/// let options = RunOptions { t_max: 1.0, ..RunOptions::default() };
/// let run = propagate(&chain, state, &options, &mut |_| false)?;
/// assert_eq!(run.tracker.snapshots.len(), 101);             // t = 0, 0.01, ..., 1
/// let x = run.tracker.snapshots[100].walls[0].position;
/// assert!((x - 15.0).abs() < 1e-6);
/// # Ok(())
/// # }
/// ```
pub fn propagate<M: ChainModel + ?Sized>(
    model: &M,
    state: State,
    options: &RunOptions,
    stop: &mut dyn FnMut(&Snapshot) -> bool,
) -> Result<Run, DynamicsError> {
    state.check(model)?;
    let integrator = options.integrator(model, &state.theta)?;
    propagate_with(model, state, &integrator, options, stop)
}

/// [`propagate`] with any [`Integrator`]: it carries its own step, damping and budgets, and
/// `options` gives the span, the output interval, the output budget and the space-time image.
pub fn propagate_with<M: ChainModel + ?Sized, I: Integrator + ?Sized>(
    model: &M,
    mut state: State,
    integrator: &I,
    options: &RunOptions,
    stop: &mut dyn FnMut(&Snapshot) -> bool,
) -> Result<Run, DynamicsError> {
    state.check(model)?;
    options.validate()?;
    let schedule =
        Schedule::covering(state.time, options.t_max, options.output_interval, options.max_outputs)?;
    if options.space_time {
        let (outputs, rotors) = (schedule.count + 1, state.theta.len());
        let values = outputs as f64 * rotors as f64;
        if values > MAX_SPACE_TIME_VALUES as f64 {
            return Err(IntegrateError::SpaceTimeBudget {
                outputs,
                rotors,
                values,
                budget: MAX_SPACE_TIME_VALUES,
            }
            .into());
        }
    }
    let mut tracker = Tracker::new(&state.theta);
    let mut kinetic = Vec::with_capacity(schedule.count.min(1 << 16) + 1);
    let mut space_time = SpaceTime::default();
    let mut failed = None;
    let report = integrator.integrate(model, &mut state, &schedule, &mut |s| {
        // The per-output records (kinetic energies, wall snapshots) are sized by the schedule's
        // output count, the caller's: grown fallibly (doubling), the bytes in the error.
        if kinetic.len() == kinetic.capacity() {
            let more = kinetic.len().max(16);
            if let Err(e) = crate::allocation::try_grow(&mut kinetic, more, "a run's kinetic energies") {
                failed = Some(e);
                return Flow::Stop;
            }
        }
        if tracker.snapshots.len() == tracker.snapshots.capacity() {
            let more = tracker.snapshots.len().max(16);
            if let Err(e) =
                crate::allocation::try_grow(&mut tracker.snapshots, more, "a run's wall snapshots")
            {
                failed = Some(e);
                return Flow::Stop;
            }
        }
        kinetic.push((s.time, kinetic_energy(model, &s.omega)));
        if options.space_time {
            // The image is the run's one output sized by outputs x rotors: its allocation failing
            // ends the run with the bytes, never an abort.
            if let Err(e) = space_time.try_push(s.time, &s.theta, schedule.count + 1) {
                failed = Some(e);
                return Flow::Stop;
            }
        }
        if stop(tracker.record(s.time, &s.theta)) { Flow::Stop } else { Flow::Continue }
    })?;
    if let Some(e) = failed {
        return Err(e.into());
    }
    Ok(Run { tracker, kinetic, space_time, report, final_state: state, integrator: integrator.name() })
}
