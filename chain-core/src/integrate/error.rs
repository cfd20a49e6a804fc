//! Errors of the integrators. Each carries the numbers that explain it, printed short and exact
//! ([`Short`]).

use chain_geometry::Short;

/// A run that could not be started or completed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IntegrateError {
    /// A slice with the wrong length for the chain.
    #[error("{what} has {}, the model has {expected} degrees of freedom", chain_geometry::Counted(*len, "value"))]
    WrongLength {
        /// Which input.
        what: &'static str,
        /// Its length.
        len: usize,
        /// The length it must have.
        expected: usize,
    },
    /// A non-finite number: in the input, or in the state or the accelerations during the run
    /// (a force law that returned NaN, or a fixed step beyond the stability limit). `time` is the
    /// time of the state concerned (0 for [`VerletOptions::stable_for`](super::VerletOptions::stable_for)).
    #[error("{what}[{index}] is not finite ({}) at t = {}", Short(*value), Short(*time))]
    NotFinite {
        /// Which input.
        what: &'static str,
        /// Time of the event, in the unit `t` of Appendix B.
        time: f64,
        /// Which entry.
        index: usize,
        /// The value found.
        value: f64,
    },
    /// The error control asked for a step too short to be taken: below `min_step`, or so short
    /// that `t + step` rounds to `t`.
    #[error("the step size fell to {step:e} at t = {}, below what can be taken there", Short(*time))]
    StepSizeTooSmall {
        /// Time of the event, in the unit `t` of Appendix B.
        time: f64,
        /// The step size the error control asked for, in `t`.
        step: f64,
    },
    /// The step budget ran out before the last output time.
    #[error("gave up at t = {} after {steps} steps (accepted and rejected): raise max_steps", Short(*time))]
    TooManySteps {
        /// Time of the event, in the unit `t` of Appendix B.
        time: f64,
        /// The steps taken.
        steps: usize,
    },
    /// A fixed-step run would need more steps than its budget (`max_steps`): the step is far
    /// shorter than the span (a very stiff chain, or an output interval far below the step).
    /// Refused before the first step.
    #[error(
        "the run needs {steps:e} steps of {dt:e} to cover {span:e}, more than the budget of {budget}: raise max_steps, \
         or shorten the run"
    )]
    StepBudget {
        /// The steps the run would need (`span / dt`).
        steps: f64,
        /// The time step, in `t`.
        dt: f64,
        /// The time span of the run, in `t`.
        span: f64,
        /// The most steps allowed (`max_steps`).
        budget: u64,
    },
    /// A run would report at more output times than its budget (`max_outputs`).
    #[error(
        "the run needs {outputs:e} outputs, more than the budget of {budget}: lengthen the output interval"
    )]
    OutputBudget {
        /// The outputs the run would need (`span / interval`).
        outputs: f64,
        /// The most outputs allowed (`max_outputs`).
        budget: usize,
    },
    /// A run asked for a space-time image (the angles at every output) larger than
    /// [`crate::dynamics::run::MAX_SPACE_TIME_VALUES`].
    #[error(
        "the space-time image needs {outputs} outputs x {rotors} rotors = {values:e} angles, more than \
         the budget of {budget}: lengthen the output interval, shorten the run or leave space_time off"
    )]
    SpaceTimeBudget {
        /// The outputs of the run, its start included.
        outputs: usize,
        /// The rotors of the chain.
        rotors: usize,
        /// `outputs * rotors`.
        values: f64,
        /// The most angles allowed.
        budget: usize,
    },
    /// The energy left its limit: `|E - E0|` (or, with damping, the rise `E - E0`) exceeded
    /// `limit * |E0|`. A fixed step past the stability limit, or forces that are not the
    /// energy's gradient; the state is the one that broke the limit.
    #[error(
        "the energy changed from {} to {} at t = {}: {relative:e} of |E0|, beyond the \
         limit {limit:e} (a step past the stability limit, or forces that are not the energy's gradient)",
        Short(*initial), Short(*energy), Short(*time)
    )]
    EnergyNotConserved {
        /// Time of the event, in the unit `t` of Appendix B.
        time: f64,
        /// The total energy then, in `M a^2 / t^2`.
        energy: f64,
        /// The total energy at the start.
        initial: f64,
        /// The relative change `|E - E0| / max(|E0|, floor)` (the rise only with damping).
        relative: f64,
        /// The largest relative change allowed.
        limit: f64,
    },
    /// An option outside its range: a field of an options struct ([`crate::validate::Validate`])
    /// or an argument of an integrator's function.
    #[error("{options}.{name} = {} is invalid: it must be {rule}", Short(*value))]
    InvalidOption {
        /// The options struct (`VerletOptions`, `AdaptiveOptions`, `RunOptions`, `Sponge`), or
        /// the function whose argument it is.
        options: &'static str,
        /// The name of the setting.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The rule it breaks, in words.
        rule: &'static str,
    },
    /// The end time lies before the start: the integrators run forward in time.
    #[error("the end time {end} lies before the start time {start}: integration runs forward", end = Short(*end), start = Short(*start))]
    EndBeforeStart {
        /// The start time, in `t`.
        start: f64,
        /// The end time, before the start.
        end: f64,
    },
    /// Output times must not decrease, nor lie before the start time.
    #[error("output time {time} (index {index}) lies before {previous}: outputs must not decrease", previous = Short(*previous), time = Short(*time))]
    OutputsOutOfOrder {
        /// The output that comes too early.
        index: usize,
        /// Its time.
        time: f64,
        /// The time of the output before it.
        previous: f64,
    },
    /// A rotor whose inertia `M r_i^2` is not positive and finite, or so small that its inverse
    /// overflows.
    #[error(
        "degree of freedom {index} has inertia {inertia}: it must be positive and finite, with a finite inverse", inertia = Short(*inertia)
    )]
    BadInertia {
        /// The rotor.
        index: usize,
        /// Its moment of inertia `M r_i^2`.
        inertia: f64,
    },
    /// The tangent stiffness vanishes or is not finite, so it sets no time scale to pick a step
    /// from.
    #[error("the tangent stiffness has norm {norm}: no time scale to choose a step from", norm = Short(*norm))]
    NoTimeScale {
        /// The norm of the tangent stiffness, which gives no finite stability limit.
        norm: f64,
    },
    /// The bound on the fastest mode's angular frequency, `sqrt(||K||_inf / I_min)`, overflows
    /// (a stiffness far too large for the inertia), so the stable step would be 0: no default
    /// step exists.
    #[error(
        "the fastest mode's frequency bound sqrt({norm:e} x {inverse_inertia:e}) overflows: the stable step \
         would be 0 (stiffness far too large for the inertia M r^2)"
    )]
    NoStableStep {
        /// The norm of the tangent stiffness.
        norm: f64,
        /// The largest inverse inertia `1 / (M r^2)`.
        inverse_inertia: f64,
    },
    /// The energy of a stepper left the tolerance around its reference
    /// ([`Verlet::check_energy`](super::Verlet::check_energy)): a step past the stability limit
    /// grows the energy while every number stays finite.
    #[error(
        "energy {energy} after step {step} is {} from the reference {reference}, more than the \
         tolerance {tolerance}: is dt = {dt} within the stability limit omega_max dt < 2?",
        (energy - reference).abs(), dt = Short(*dt), energy = Short(*energy), reference = Short(*reference), tolerance = Short(*tolerance)
    )]
    EnergyDrift {
        /// Steps taken.
        step: u64,
        /// The energy now.
        energy: f64,
        /// The reference energy.
        reference: f64,
        /// The tolerance.
        tolerance: f64,
        /// The step.
        dt: f64,
    },
}

impl From<crate::validate::InvalidOption> for IntegrateError {
    fn from(e: crate::validate::InvalidOption) -> Self {
        IntegrateError::InvalidOption { options: e.options, name: e.field, value: e.value, rule: e.rule }
    }
}
