//! Time integration of the equations of motion of any [`Potential`] (paper Secs. V, VI and
//! Appendix B):
//!
//! `I_i thetadd_i = -dV/dtheta_i - gamma I_i thetadot_i`, with `I_i = M r_i^2` for a rotor chain,
//!
//! the Newtonian dynamics of the free chain, and with `gamma > 0` the paper's dissipative
//! dynamics. Units as in `docs/theory.md` §3: `a = 1`, `M = 1`, time in the unit `t` of paper
//! Appendix B, `k` in `M / t^2`, so `gamma` is a rate in `1 / t`. The state is the degrees of
//! freedom (a chain's angles) and their rates `omega = dtheta/dt`; the energy is
//! `E = sum_i I_i omega_i^2 / 2 + V`.
//!
//! This module sits between the model traits and the analyses (model -> integrate -> statics ->
//! dynamics): the statics' relaxation and the dynamics' runs both step with its [`Verlet`].
//!
//! One algorithm per file:
//!
//! - [`verlet`](mod@verlet): velocity Verlet (kick-drift-kick) with a fixed step, second order
//!   and symplectic, so the energy error stays bounded over arbitrarily long runs instead of
//!   drifting; with damping the decay is applied exactly and the map stays conformally
//!   symplectic. One gradient evaluation per step: the workhorse for long runs and big chains.
//!   Its stepper [`Verlet`] is generic over the float type and the storage (no heap needed).
//! - [`bound`]: the one bound on the fastest mode that steps are chosen from.
//! - [`method`]: [`Method`], the one way to choose an integrator (runs, scattering, sweeps, the
//!   command line and Python).
//! - [`dop853`]: the Dormand-Prince 8(5,3) Runge-Kutta pair of Hairer, Norsett and Wanner,
//!   *Solving Ordinary Differential Equations I* (2nd ed.), Secs. II.4-II.6, with step-size
//!   control and 7th-order dense output: errors controlled to a tolerance, for scattering runs
//!   that must be accurate (paper Sec. VI) and for references.
//!
//! Both run generic over [`Potential`], reuse their buffers (no allocation per step), check
//! their input (wrong lengths and non-finite numbers are [`IntegrateError`]s, never a panic), and
//! stop with an error instead of carrying a NaN. After each output they hand the [`State`] to an
//! observer, which answers [`Flow::Continue`] or [`Flow::Stop`] (a scattering outcome decided),
//! and they return a [`Report`] with the energy seen at the outputs.
//!
//! ```
//! use chain_core::RuntimeChain;
//! use chain_core::integrate::{self, AdaptiveOptions, Flow, State, VerletOptions};
//!
//! // The paper's chain (Sec. V): 60 rotors, r/a = 0.8, k = 1e4, theta_bar = 0.58; a smooth
//! // disturbance of the uniform state, released at rest.
//! let chain = RuntimeChain::builder(60, 0.8, 1e4, 0.58).build()?;
//! let start = State::at_rest((0..60).map(|i| 0.58 + 0.01 * (0.3 * i as f64).sin()).collect());
//!
//! // Verlet at the default stable step, the kinetic energy recorded every 10 steps.
//! let options = VerletOptions::stable_for(&chain, &start.theta, VerletOptions::DEFAULT_SAFETY)?;
//! let mut kinetic = Vec::new();
//! let mut state = start.clone();
//! let report = integrate::verlet(&chain, &mut state, 1.0, &options, 10, &mut |s: &State| {
//!     kinetic.push((s.time, integrate::kinetic_energy(&chain, &s.omega)));
//!     Flow::Continue
//! })?;
//! assert_eq!(state.time, 1.0);
//! // All phonons of this chain lie near omega_max, where the energy of Verlet states oscillates
//! // by a fraction (omega dt)^2 / 4 around a conserved value: under 1 % at the default step.
//! assert!(report.max_energy_error < 1e-2 * report.energy_initial);
//!
//! // DOP853 to the default tolerances, observed at t = 0.5 and 1, stopping at the first.
//! let mut state = start.clone();
//! let options = AdaptiveOptions::default();
//! let report = integrate::adaptive(&chain, &mut state, &[0.5, 1.0], &options, &mut |_| Flow::Stop)?;
//! assert!(report.stopped_early && state.time == 0.5);
//! assert!(report.max_energy_error < 1e-9 * report.energy_initial);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#[cfg(feature = "alloc")]
pub mod bound;
#[cfg(feature = "alloc")]
pub mod dop853;
pub mod error;
pub mod method;
mod state;
#[cfg(feature = "alloc")]
mod tableau;
pub mod verlet;

#[cfg(feature = "alloc")]
use alloc::vec::Vec;

#[cfg(feature = "alloc")]
pub use bound::{OmegaBound, omega_bound};
#[cfg(feature = "alloc")]
pub use dop853::{AdaptiveOptions, adaptive};
pub use error::IntegrateError;
pub use method::Method;
#[cfg(feature = "alloc")]
pub use state::State;
pub use state::{Phase, Storage};
pub use verlet::{Verlet, kinetic_energy};
#[cfg(feature = "alloc")]
pub use verlet::{VerletOptions, verlet};

#[cfg(feature = "alloc")]
use crate::model::Potential;
use crate::validate::{Fields, Validate};

/// What an observer returns after each output: keep going or stop (e.g. once a scattering
/// outcome is decided).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on integrating.
    Continue,
    /// End the run after this output.
    Stop,
}

/// What a run did, with an energy monitor: `E = T + V` at the start, at the end, and the largest
/// change seen at the outputs (a conservation check when the run has no damping; with damping
/// the energy falls, and only a rise is an error).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Report {
    /// Accepted steps.
    pub steps: usize,
    /// Steps rejected by the error control (always 0 for fixed-step methods).
    pub rejected: usize,
    /// Total energy `E0` at the start, in `M a^2 / t^2`.
    pub energy_initial: f64,
    /// Total energy at the end, in `M a^2 / t^2`.
    pub energy_final: f64,
    /// The largest `|E - E0|` seen at the outputs.
    pub max_energy_error: f64,
    /// The largest `E - E0` seen at the outputs: the energy error of a damped run, whose energy
    /// may only fall.
    pub max_energy_rise: f64,
    /// The observer returned [`Flow::Stop`].
    pub stopped_early: bool,
    /// Whether the equations of motion had any damping.
    pub damped: bool,
    /// The smallest energy scale of the model ([`Potential::energy_floor`]: `1e-12 k_max a^2`
    /// for a chain, the energy of a spring stretched by a millionth of the lattice spacing). A
    /// state whose energy `E0` is below it (a zero-energy kink at rest has `E0 ~ 1e-27`,
    /// rounding) measures errors against it instead.
    pub energy_floor: f64,
}

impl Report {
    /// What relative energy errors are measured against: `max(|E0|, energy_floor)`, or 1 (the
    /// model's energy unit) if both are 0.
    pub fn energy_scale(&self) -> f64 {
        energy_scale(self.energy_initial, self.energy_floor)
    }

    /// The largest relative energy error of the run: `max |E - E0| / scale` without damping,
    /// `max (E - E0) / scale` (the rise; 0 if the energy only fell) with damping.
    pub fn relative_energy_error(&self) -> f64 {
        let error = if self.damped { self.max_energy_rise.max(0.0) } else { self.max_energy_error };
        error / self.energy_scale()
    }
}

fn energy_scale(e0: f64, floor: f64) -> f64 {
    let scale = e0.abs().max(floor);
    if scale > 0.0 { scale } else { 1.0 }
}

/// The model's [`Potential::energy_floor`], 0 if it is not finite and positive.
#[cfg(feature = "alloc")]
fn energy_floor<M: Potential + ?Sized>(model: &M) -> f64 {
    let floor = model.energy_floor();
    if floor.is_finite() && floor > 0.0 { floor } else { 0.0 }
}

/// `E = T + V` of a state.
///
/// # Panics
/// As [`kinetic_energy`], and as [`Potential::energy`] if `theta` has the wrong length.
#[cfg(feature = "alloc")]
pub fn total_energy<M: Potential + ?Sized>(model: &M, state: &State) -> f64 {
    kinetic_energy(model, &state.omega) + model.energy(&state.theta)
}

/// A damping sponge on the last `width` rotors at each end: absorbing ends (the standard device
/// of soliton-scattering studies for a finite chain that should behave like an infinite one).
///
/// Rotor `i` at distance `d_i` from the nearer end (`d = 0` for the end rotor) gets the damping
/// rate `strength * ((width - d_i) / width)^2` for `d_i < width`, 0 inside. The quadratic ramp
/// reflects little of what enters it: a wave meets a rate that grows smoothly from 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sponge {
    /// Rotors in each end's sponge, between 0 (no sponge) and `MAX_ROTORS` = 100000000 (no
    /// chain has more rotors; wider than half the chain, the two overlap).
    pub width: usize,
    /// The damping rate at the end rotor, in `1 / t`.
    pub strength: f64,
}

impl Validate for Sponge {
    type Error = IntegrateError;

    /// `width` between 0 (no sponge) and `MAX_ROTORS` (no chain has more rotors; wider than
    /// half the chain, the two overlap); `strength` finite and `>= 0`.
    fn validate(&self) -> Result<(), IntegrateError> {
        let Self { width, strength } = *self;
        let fields = Fields("Sponge");
        fields.count_in(
            "width",
            width as u64,
            0,
            chain_geometry::MAX_ROTORS as u64,
            "between 0 and MAX_ROTORS = 100000000 rotors (no chain has more)",
        )?;
        Ok(fields.non_negative("strength", strength)?)
    }
}

impl Sponge {
    /// The rate of rotor `i` of `n`.
    pub fn rate(&self, i: usize, n: usize) -> f64 {
        let d = i.min(n.saturating_sub(1).saturating_sub(i));
        if self.width == 0 || d >= self.width {
            return 0.0;
        }
        let x = (self.width - d) as f64 / self.width as f64;
        self.strength * x * x
    }
}

/// The damping rate of each of `n` degrees of freedom: `uniform` everywhere plus the sponge's,
/// checked.
#[cfg(feature = "alloc")]
pub fn damping_rates(n: usize, uniform: f64, sponge: Option<Sponge>) -> Result<Vec<f64>, IntegrateError> {
    Fields("damping_rates").non_negative("uniform", uniform)?;
    if let Some(s) = sponge {
        s.validate()?;
    }
    Ok((0..n).map(|i| uniform + sponge.map_or(0.0, |s| s.rate(i, n))).collect())
}

/// The largest relative energy change a run may show before it is stopped with
/// [`IntegrateError::EnergyNotConserved`]: 10 %. A run that far off is wrong whatever it is used
/// for (the step is past the stability limit, or the forces are not the energy's gradient);
/// the much smaller tolerances that decide whether a result is accurate enough belong to the
/// caller (the sweep's energy budget, for example).
pub const DEFAULT_ENERGY_LIMIT: f64 = 0.1;

/// The largest step budget of any integrator or relaxation (`max_steps` of [`VerletOptions`],
/// [`AdaptiveOptions`], `RunOptions` and `RelaxOptions`): 10^10 steps, a hundred times the
/// default budget ([`VerletOptions::DEFAULT_MAX_STEPS`]), about 3 hours of the paper's 60 rotors
/// at 1 µs per Verlet step and more for DOP853's twelve evaluations per step. A budget above it
/// bounds nothing a run would finish: a run that long is a step far shorter than intended, or a
/// tolerance that cannot be met.
pub const MAX_STEP_BUDGET: u64 = 10_000_000_000;

/// The rule of every integrator's step budget: between 1 and [`MAX_STEP_BUDGET`].
#[cfg(feature = "alloc")]
pub(crate) fn check_step_budget(
    fields: Fields,
    field: &'static str,
    steps: u64,
) -> Result<(), crate::validate::InvalidOption> {
    fields.count_in(
        field,
        steps,
        1,
        MAX_STEP_BUDGET,
        "between 1 and MAX_STEP_BUDGET = 10000000000 steps (a hundred times the default budget)",
    )
}

/// When an integrator reports: the initial state and every `interval` after it, `count` times
/// (the last output at `start + count * interval`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schedule {
    /// Time between outputs, in `t`.
    pub interval: f64,
    /// Number of outputs after the start.
    pub count: usize,
}

impl Schedule {
    /// The outputs every `interval` from `start` that cover `[start, t_max]` (the last one at or
    /// just past `t_max`), refusing more than `max_outputs` of them.
    pub fn covering(
        start: f64,
        t_max: f64,
        interval: f64,
        max_outputs: usize,
    ) -> Result<Self, IntegrateError> {
        Fields("Schedule::covering").finite("t_max", t_max)?;
        if t_max < start {
            return Err(IntegrateError::EndBeforeStart { start, end: t_max });
        }
        check_positive("Schedule::covering", "output_interval", interval)?;
        // An interval longer than the run still takes one output, at `start + interval`.
        let needed = step_count(t_max - start, interval);
        if needed > max_outputs as f64 {
            return Err(IntegrateError::OutputBudget { outputs: needed, budget: max_outputs });
        }
        Ok(Self { interval, count: needed as usize })
    }

    /// The time of output `k` (0: the start).
    pub fn time(&self, start: f64, k: usize) -> f64 {
        start + k as f64 * self.interval
    }
}

/// A time integrator of the equations of motion: [`VerletOptions`] (fixed step, symplectic) and
/// [`AdaptiveOptions`] (DOP853) implement it, so a run, a scattering experiment or a sweep takes
/// either alike. [`Method`] chooses one by name.
#[cfg(feature = "alloc")]
pub trait Integrator {
    /// A short name for reports: `verlet`, `dop853`.
    fn name(&self) -> &'static str;

    /// Integrates `state` over `schedule`, calling `observer` with the state at its start and at
    /// every output time, and stopping early when it answers [`Flow::Stop`]. On return `state`
    /// holds the last state the observer saw.
    fn integrate<M: Potential + ?Sized>(
        &self,
        model: &M,
        state: &mut State,
        schedule: &Schedule,
        observer: &mut dyn FnMut(&State) -> Flow,
    ) -> Result<Report, IntegrateError>;
}

/// `Err(NotFinite)` naming the first non-finite entry of `v`.
fn not_finite<T: crate::real::Real>(what: &'static str, time: f64, v: &[T]) -> Result<(), IntegrateError> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(IntegrateError::NotFinite { what, time, index, value: v[index].widen() }),
        None => Ok(()),
    }
}

/// `1 / I_i`, checked: a zero, negative or non-finite inertia has no dynamics.
#[cfg(feature = "alloc")]
fn inverse_inertia<M: Potential + ?Sized>(model: &M) -> Result<Vec<f64>, IntegrateError> {
    (0..model.dof_count())
        .map(|i| {
            let inertia = model.inertia(i);
            // A subnormal inertia is positive and finite, but its inverse overflows.
            if inertia > 0.0 && inertia.is_finite() && (1.0 / inertia).is_finite() {
                Ok(1.0 / inertia)
            } else {
                Err(IntegrateError::BadInertia { index: i, inertia })
            }
        })
        .collect()
}

/// The number of equal steps of at most `dt` that cover `span` (Verlet's steps, a schedule's
/// outputs): a span that is a whole number of
/// steps up to rounding takes exactly that many, and a positive span takes at least one (so the
/// time always reaches the end). As a float: the caller checks it against its budget.
#[cfg_attr(not(feature = "alloc"), allow(dead_code))]
pub(crate) fn step_count(span: f64, dt: f64) -> f64 {
    if span <= 0.0 {
        return 0.0;
    }
    let ratio = span / dt;
    let nearest = libm::round(ratio);
    let count = if (ratio - nearest).abs() <= 1e-9 * nearest.max(1.0) { nearest } else { libm::ceil(ratio) };
    count.max(1.0)
}

/// `Ok` if `ok`, else `InvalidOption` naming the argument `name` of the function `options`.
fn check_option(
    options: &'static str,
    name: &'static str,
    value: f64,
    ok: bool,
    rule: &'static str,
) -> Result<(), IntegrateError> {
    Ok(Fields(options).rule(name, value, ok, rule)?)
}

/// `value > 0`, finite: an argument `name` of the function `options`.
#[cfg_attr(not(feature = "alloc"), allow(dead_code))]
fn check_positive(options: &'static str, name: &'static str, value: f64) -> Result<(), IntegrateError> {
    Ok(Fields(options).positive(name, value)?)
}

/// The energy limit: positive (infinite switches the check off).
#[cfg_attr(not(feature = "alloc"), allow(dead_code))]
fn check_energy_limit(fields: Fields, limit: f64) -> Result<(), IntegrateError> {
    Ok(fields.rule("energy_limit", limit, limit > 0.0, "positive (infinite: no check)")?)
}

/// Hands a state to the observer after recording its energy in the report, and stops a run
/// whose energy left the limit.
#[cfg(feature = "alloc")]
struct Monitor {
    report: Report,
    limit: f64,
}

#[cfg(feature = "alloc")]
impl Monitor {
    /// Starts the report from `state`; its energy must be finite.
    fn new<M: Potential + ?Sized>(
        model: &M,
        state: &State,
        damped: bool,
        limit: f64,
    ) -> Result<Self, IntegrateError> {
        check_energy_limit(Fields("Monitor::new"), limit)?;
        let e = total_energy(model, state);
        if !e.is_finite() {
            return Err(IntegrateError::NotFinite { what: "energy", time: state.time, index: 0, value: e });
        }
        let report = Report {
            steps: 0,
            rejected: 0,
            energy_initial: e,
            energy_final: e,
            max_energy_error: 0.0,
            max_energy_rise: 0.0,
            stopped_early: false,
            damped,
            energy_floor: energy_floor(model),
        };
        Ok(Self { report, limit })
    }

    /// Records the energy of `state`, checks it, and asks the observer; `Ok(true)` if it said
    /// stop.
    fn output<M: Potential + ?Sized>(
        &mut self,
        model: &M,
        state: &State,
        observer: &mut dyn FnMut(&State) -> Flow,
    ) -> Result<bool, IntegrateError> {
        self.output_with(model, state, model.energy(&state.theta), observer)
    }

    /// [`Monitor::output`] with the potential energy of `state` already known.
    fn output_with<M: Potential + ?Sized>(
        &mut self,
        model: &M,
        state: &State,
        potential: f64,
        observer: &mut dyn FnMut(&State) -> Flow,
    ) -> Result<bool, IntegrateError> {
        let e = kinetic_energy(model, &state.omega) + potential;
        if !e.is_finite() {
            return Err(IntegrateError::NotFinite { what: "energy", time: state.time, index: 0, value: e });
        }
        let r = &mut self.report;
        r.energy_final = e;
        let change = e - r.energy_initial;
        r.max_energy_error = r.max_energy_error.max(change.abs());
        r.max_energy_rise = r.max_energy_rise.max(change);
        let relative = if r.damped { change } else { change.abs() } / r.energy_scale();
        if relative > self.limit {
            return Err(IntegrateError::EnergyNotConserved {
                time: state.time,
                energy: e,
                initial: r.energy_initial,
                relative,
                limit: self.limit,
            });
        }
        let stop = observer(state) == Flow::Stop;
        r.stopped_early = stop;
        Ok(stop)
    }
}
