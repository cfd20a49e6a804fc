//! Errors of the integrators. Each carries the numbers that explain it.

/// A run that could not be started or completed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IntegrateError {
    /// A slice with the wrong length for the chain.
    #[error("{what} has {len} entries, the chain has {expected} rotors")]
    WrongLength { what: &'static str, len: usize, expected: usize },
    /// A non-finite number: in the input, or in the state or the accelerations during the run
    /// (a force law that returned NaN, or a fixed step beyond the stability limit). `time` is the
    /// time of the state concerned (0 for [`VerletOptions::stable_for`](super::VerletOptions::stable_for)).
    #[error("{what}[{index}] is not finite ({value}) at t = {time}")]
    NotFinite { what: &'static str, time: f64, index: usize, value: f64 },
    /// The error control asked for a step too short to be taken: below `min_step`, or so short
    /// that `t + step` rounds to `t`.
    #[error("the step size fell to {step:e} at t = {time}, below what can be taken there")]
    StepSizeTooSmall { time: f64, step: f64 },
    /// The step budget ran out before the last output time.
    #[error("gave up at t = {time} after {steps} steps (accepted and rejected): raise max_steps")]
    TooManySteps { time: f64, steps: usize },
    /// A fixed-step run would need more steps than its budget (`max_steps`): the step is far
    /// shorter than the span (a very stiff chain, or an output interval far below the step).
    /// Refused before the first step.
    #[error(
        "the run needs {steps:e} steps of {dt:e} to cover {span:e}, more than the budget of {budget}: raise max_steps, \
         or shorten the run"
    )]
    StepBudget { steps: f64, dt: f64, span: f64, budget: u64 },
    /// A run would report at more output times than its budget (`max_outputs`).
    #[error(
        "the run needs {outputs:e} outputs, more than the budget of {budget}: lengthen the output interval"
    )]
    OutputBudget { outputs: f64, budget: usize },
    /// The energy left its limit: `|E - E0|` (or, with damping, the rise `E - E0`) exceeded
    /// `limit * |E0|`. A fixed step past the stability limit, or forces that are not the
    /// energy's gradient; the state is the one that broke the limit.
    #[error(
        "the energy changed from {initial} to {energy} at t = {time}: {relative:e} of |E0|, beyond the \
         limit {limit:e} (a step past the stability limit, or forces that are not the energy's gradient)"
    )]
    EnergyNotConserved { time: f64, energy: f64, initial: f64, relative: f64, limit: f64 },
    /// An option outside its range.
    #[error("{name} = {value} is invalid: it must be {rule}")]
    InvalidOption { name: &'static str, value: f64, rule: &'static str },
    /// The end time lies before the start: the integrators run forward in time.
    #[error("the end time {end} lies before the start time {start}: integration runs forward")]
    EndBeforeStart { start: f64, end: f64 },
    /// Output times must not decrease, nor lie before the start time.
    #[error("output time {time} (index {index}) lies before {previous}: outputs must not decrease")]
    OutputsOutOfOrder { index: usize, time: f64, previous: f64 },
    /// A rotor whose inertia `M r_i^2` is not positive and finite.
    #[error("rotor {index} has inertia {inertia}: it must be positive and finite")]
    BadInertia { index: usize, inertia: f64 },
    /// The tangent stiffness vanishes or is not finite, so it sets no time scale to pick a step
    /// from.
    #[error("the tangent stiffness has norm {norm}: no time scale to choose a step from")]
    NoTimeScale { norm: f64 },
}
