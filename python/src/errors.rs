//! Rust errors as Python exceptions. Each Rust error family has its class in
//! `rotor_chain/errors.py` (a subclass of `RotorChainError` and of `ValueError` or
//! `RuntimeError`); the exception's message is the Rust error's `Display`, `variant` names the
//! Rust variant, and every number the variant carries is an attribute (and an entry of
//! `details`). A wrapped error is `details["source"]` and the exception's `__cause__`.

use chain_sweep::scattering::{BudgetError, ConfigError, PointError, VerletBreach};
use chain_sweep::{GridError, SweepError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyModule};
use rotor_chain::dynamics::DynamicsError;
use rotor_chain::dynamics::integrate::IntegrateError;
use rotor_chain::geometry::CountText;
use rotor_chain::linalg::LinalgError;
use rotor_chain::network::{CellError, NetworkError};
use rotor_chain::statics::StaticsError;
use rotor_chain::{BranchError, ParameterError};

/// The variant name and the numbers of one Rust error.
pub struct Details<'py> {
    py: Python<'py>,
    variant: &'static str,
    fields: Bound<'py, PyDict>,
    cause: Option<PyErr>,
}

impl<'py> Details<'py> {
    fn new(py: Python<'py>, variant: &'static str) -> Self {
        Self { py, variant, fields: PyDict::new(py), cause: None }
    }

    /// Add a field. Setting a field cannot fail for these plain values; a failure would only
    /// lose the attribute, never the exception.
    fn f<T: IntoPyObject<'py>>(self, name: &str, value: T) -> Self {
        let _ = self.fields.set_item(name, value);
        self
    }

    /// The wrapped error, as `details["source"]` and `__cause__`.
    fn source(mut self, cause: PyErr) -> Self {
        let _ = self.fields.set_item("source", cause.value(self.py));
        self.cause = Some(cause);
        self
    }

    /// The exception of class `class` (a name in `rotor_chain.errors`) with `message`.
    fn raise(self, class: &str, message: String) -> PyErr {
        let py = self.py;
        let build = || -> PyResult<PyErr> {
            let class = errors_module(py)?.getattr(class)?;
            let value = class.call1((message.clone(), self.variant, self.fields))?;
            let err = PyErr::from_value(value);
            if let Some(cause) = self.cause {
                err.set_cause(py, Some(cause));
            }
            Ok(err)
        };
        // If the errors module cannot be imported (a broken install), still raise, plainly.
        build().unwrap_or_else(|e| e)
    }
}

/// A field of an options struct outside its range (the `InvalidOption` of every family, and
/// the dynamics' `InvalidSetup`): `options` names the struct (or the function whose argument it
/// is), `name` the field (also the keyword argument that set it), `value` and `rule`. Raised as
/// the family's `...OptionError`, which is also `InvalidOptionError` and a `ValueError`.
fn option<'py>(
    d: Details<'py>,
    variant: &'static str,
    options: &'static str,
    name: &'static str,
    value: f64,
    rule: &'static str,
) -> Details<'py> {
    Details { variant, ..d }.f("options", options).f("name", name).f("value", value).f("rule", rule)
}

fn errors_module(py: Python<'_>) -> PyResult<&Bound<'_, PyModule>> {
    static MODULE: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
    MODULE.get_or_try_init(py, || py.import("rotor_chain.errors").map(Bound::unbind)).map(|m| m.bind(py))
}

/// `ParameterError` for a rotor count or an index that no `usize` holds (Python's ints are
/// unbounded: `-1`, `10**20`), so the Rust error cannot carry it: chain-geometry's text of the
/// same variant with Python's own int, which is also the `n` or `index` field.
pub fn unbounded(py: Python<'_>, text: CountText<&Bound<'_, PyAny>>) -> PyErr {
    let d = Details::new(py, "");
    let d = match text {
        CountText::TooFew(n) => Details { variant: "TooFewRotors", ..d }.f("n", n),
        CountText::TooMany { n, max } => Details { variant: "TooManyRotors", ..d }.f("n", n).f("max", max),
        CountText::OutOfRange { kind, index, count } => Details { variant: "IndexOutOfRange", ..d }
            .f("kind", kind.to_string())
            .f("index", index)
            .f("count", count),
    };
    d.raise("ParameterError", text.to_string())
}

pub fn parameter(py: Python<'_>, e: &ParameterError) -> PyErr {
    let d = Details::new(py, "");
    let d = match *e {
        ParameterError::TooFewRotors { n } => Details { variant: "TooFewRotors", ..d }.f("n", n),
        ParameterError::NotPositive { key, value } => {
            Details { variant: "NotPositive", ..d }.f("key", key.to_string()).f("value", value)
        }
        ParameterError::OutsideFlipperPhase { theta_bar, a, r, two_r_sin, limit } => {
            Details { variant: "OutsideFlipperPhase", ..d }
                .f("theta_bar", theta_bar)
                .f("a", a)
                .f("r", r)
                .f("two_r_sin", two_r_sin)
                .f("limit", limit)
        }
        ParameterError::RestLengthOutOfRange { rest_length, a, r, max } => {
            Details { variant: "RestLengthOutOfRange", ..d }
                .f("rest_length", rest_length)
                .f("a", a)
                .f("r", r)
                .f("max", max)
        }
        ParameterError::IndexOutOfRange { kind, index, count } => Details { variant: "IndexOutOfRange", ..d }
            .f("kind", kind.to_string())
            .f("index", index)
            .f("count", count),
        ParameterError::TooManyRotors { n, max } => {
            Details { variant: "TooManyRotors", ..d }.f("n", n).f("max", max)
        }
        ParameterError::EmptyOverride { kind, index } => {
            Details { variant: "EmptyOverride", ..d }.f("kind", kind.to_string()).f("index", index)
        }
        ParameterError::OverriddenTwice { kind, index } => {
            Details { variant: "OverriddenTwice", ..d }.f("kind", kind.to_string()).f("index", index)
        }
        ParameterError::ScaleUnderflow { quantity, value } => {
            Details { variant: "ScaleUnderflow", ..d }.f("quantity", quantity).f("value", value)
        }
        ParameterError::AllocationFailed { n, bytes } => {
            Details { variant: "AllocationFailed", ..d }.f("n", n).f("bytes", bytes)
        }
        _ => Details { variant: "Other", ..d },
    };
    d.raise("ParameterError", e.to_string())
}

pub fn branch(py: Python<'_>, e: &BranchError) -> PyErr {
    let d = Details::new(py, "");
    let d = match *e {
        BranchError::NoRealRoot { spring, theta, distance, rotor_length, rest_length, min, max } => {
            Details { variant: "NoRealRoot", ..d }
                .f("spring", spring)
                .f("theta", theta)
                .f("distance", distance)
                .f("rotor_length", rotor_length)
                .f("rest_length", rest_length)
                .f("min", min)
                .f("max", max)
        }
        BranchError::NotFinite { spring, theta } => {
            Details { variant: "NotFinite", ..d }.f("spring", spring).f("theta", theta)
        }
        BranchError::NoSuchSpring { spring, springs } => {
            Details { variant: "NoSuchSpring", ..d }.f("spring", spring).f("springs", springs)
        }
        BranchError::Degenerate { spring, theta } => {
            Details { variant: "Degenerate", ..d }.f("spring", spring).f("theta", theta)
        }
        _ => Details { variant: "Other", ..d },
    };
    d.raise("BranchError", e.to_string())
}

fn linalg<'py>(d: Details<'py>, e: &LinalgError) -> Details<'py> {
    match *e {
        LinalgError::DimensionMismatch { diag, off } => d.f("diag", diag).f("off", off),
        LinalgError::RhsMismatch { n, rhs } => d.f("n", n).f("rhs", rhs),
        LinalgError::NotFinite { input, index, value } => {
            d.f("input", input.to_string()).f("index", index).f("value", value)
        }
        LinalgError::IndexOutOfRange { lo, hi, n } => d.f("lo", lo).f("hi", hi).f("n", n),
        LinalgError::Singular { row, pivot } => d.f("row", row).f("pivot", pivot),
        LinalgError::NoConvergence { iterations, index, residual } => {
            d.f("iterations", iterations).f("index", index).f("residual", residual)
        }
        _ => d,
    }
}

pub fn statics(py: Python<'_>, e: &StaticsError) -> PyErr {
    if let &StaticsError::Linalg(LinalgError::OutOfMemory { bytes, what }) = e {
        return crate::args::memory_error(rotor_chain::allocation::AllocationError { bytes, what });
    }
    let d = Details::new(py, "");
    let d = match e {
        StaticsError::Branch(b) => Details { variant: "Branch", ..d }.source(branch(py, b)),
        StaticsError::Parameter(p) => Details { variant: "Parameter", ..d }.source(parameter(py, p)),
        StaticsError::Linalg(l) => linalg(Details { variant: "Linalg", ..d }, l),
        &StaticsError::CentreOutOfRange { centre, n, max } => {
            Details { variant: "CentreOutOfRange", ..d }.f("centre", centre).f("n", n).f("max", max)
        }
        &StaticsError::NoConvergence { method, iterations, residual, tolerance } => {
            Details { variant: "NoConvergence", ..d }
                .f("method", method)
                .f("iterations", iterations)
                .f("residual", residual)
                .f("tolerance", tolerance)
        }
        &StaticsError::DefectLost { expected, kinks, antikinks } => Details { variant: "DefectLost", ..d }
            .f("expected", expected)
            .f("kinks", kinks)
            .f("antikinks", antikinks),
        &StaticsError::NoWall { expected, centre, theta_bar, kinks, antikinks } => {
            Details { variant: "NoWall", ..d }
                .f("expected", expected)
                .f("centre", centre)
                .f("theta_bar", theta_bar)
                .f("kinks", kinks)
                .f("antikinks", antikinks)
        }
        &StaticsError::NoZeroEnergyState { spring, rest_length, min, max } => {
            Details { variant: "NoZeroEnergyState", ..d }
                .f("spring", spring)
                .f("rest_length", rest_length)
                .f("min", min)
                .f("max", max)
        }
        &StaticsError::WrongLength { what, len, expected } => {
            Details { variant: "WrongLength", ..d }.f("what", what).f("len", len).f("expected", expected)
        }
        &StaticsError::NotFinite { what, index, value } => {
            Details { variant: "NotFinite", ..d }.f("what", what).f("index", index).f("value", value)
        }
        &StaticsError::InvalidValue { what, value, expected } => {
            Details { variant: "InvalidValue", ..d }.f("what", what).f("value", value).f("expected", expected)
        }
        &StaticsError::InvalidOption { options, name, value, rule } => {
            option(d, "InvalidOption", options, name, value, rule)
        }
        &StaticsError::TooLarge { what, value, max } => {
            Details { variant: "TooLarge", ..d }.f("what", what).f("value", value).f("max", max)
        }
        &StaticsError::NotAnEquilibrium { requested, found, index, held } => {
            Details { variant: "NotAnEquilibrium", ..d }
                .f("requested", requested)
                .f("found", found)
                .f("index", index)
                .f("held", held)
        }
        &StaticsError::NoMinimum { near, found, index, held } => Details { variant: "NoMinimum", ..d }
            .f("near", near)
            .f("found", found)
            .f("index", index)
            .f("held", held),
        &StaticsError::DescentLeftRegion { start, lo, hi, reached, energy, slope } => {
            Details { variant: "DescentLeftRegion", ..d }
                .f("start", start)
                .f("lo", lo)
                .f("hi", hi)
                .f("reached", reached)
                .f("energy", energy)
                .f("slope", slope)
        }
        _ => Details { variant: "Other", ..d },
    };
    let class =
        if matches!(e, StaticsError::InvalidOption { .. }) { "StaticsOptionError" } else { "StaticsError" };
    d.raise(class, e.to_string())
}

pub fn integrate(py: Python<'_>, e: &IntegrateError) -> PyErr {
    let d = Details::new(py, "");
    let d = match *e {
        IntegrateError::WrongLength { what, len, expected } => {
            Details { variant: "WrongLength", ..d }.f("what", what).f("len", len).f("expected", expected)
        }
        IntegrateError::NotFinite { what, time, index, value } => Details { variant: "NotFinite", ..d }
            .f("what", what)
            .f("time", time)
            .f("index", index)
            .f("value", value),
        IntegrateError::StepSizeTooSmall { time, step } => {
            Details { variant: "StepSizeTooSmall", ..d }.f("time", time).f("step", step)
        }
        IntegrateError::TooManySteps { time, steps } => {
            Details { variant: "TooManySteps", ..d }.f("time", time).f("steps", steps)
        }
        IntegrateError::StepBudget { steps, dt, span, budget } => Details { variant: "StepBudget", ..d }
            .f("steps", steps)
            .f("dt", dt)
            .f("span", span)
            .f("budget", budget),
        IntegrateError::OutputBudget { outputs, budget } => {
            Details { variant: "OutputBudget", ..d }.f("outputs", outputs).f("budget", budget)
        }
        IntegrateError::SpaceTimeBudget { outputs, rotors, values, budget } => {
            Details { variant: "SpaceTimeBudget", ..d }
                .f("outputs", outputs)
                .f("rotors", rotors)
                .f("values", values)
                .f("budget", budget)
        }
        IntegrateError::EnergyNotConserved { time, energy, initial, relative, limit } => {
            Details { variant: "EnergyNotConserved", ..d }
                .f("time", time)
                .f("energy", energy)
                .f("initial", initial)
                .f("relative", relative)
                .f("limit", limit)
        }
        IntegrateError::InvalidOption { options, name, value, rule } => {
            option(d, "InvalidOption", options, name, value, rule)
        }
        IntegrateError::EndBeforeStart { start, end } => {
            Details { variant: "EndBeforeStart", ..d }.f("start", start).f("end", end)
        }
        IntegrateError::OutputsOutOfOrder { index, time, previous } => {
            Details { variant: "OutputsOutOfOrder", ..d }
                .f("index", index)
                .f("time", time)
                .f("previous", previous)
        }
        IntegrateError::BadInertia { index, inertia } => {
            Details { variant: "BadInertia", ..d }.f("index", index).f("inertia", inertia)
        }
        IntegrateError::NoTimeScale { norm } => Details { variant: "NoTimeScale", ..d }.f("norm", norm),
        IntegrateError::NoStableStep { norm, inverse_inertia } => {
            Details { variant: "NoStableStep", ..d }.f("norm", norm).f("inverse_inertia", inverse_inertia)
        }
        _ => Details { variant: "Other", ..d },
    };
    let class = if matches!(e, IntegrateError::InvalidOption { .. }) {
        "IntegrateOptionError"
    } else {
        "IntegrateError"
    };
    d.raise(class, e.to_string())
}

pub fn dynamics(py: Python<'_>, e: &DynamicsError) -> PyErr {
    // An integration error is raised as IntegrateError, a subclass of DynamicsError.
    if let DynamicsError::Integrate(i) = e {
        return integrate(py, i);
    }
    if let &DynamicsError::OutOfMemory(a) = e {
        return crate::args::memory_error(a);
    }
    if let DynamicsError::Statics(s) = e
        && let StaticsError::Linalg(LinalgError::OutOfMemory { .. }) = s
    {
        return statics(py, s);
    }
    let d = Details::new(py, "");
    let d = match e {
        DynamicsError::Statics(s) => Details { variant: "Statics", ..d }.source(statics(py, s)),
        &DynamicsError::NoTranslationMode { position } => {
            Details { variant: "NoTranslationMode", ..d }.f("position", position)
        }
        &DynamicsError::BadSpeed { v0 } => Details { variant: "BadSpeed", ..d }.f("v0", v0),
        &DynamicsError::NoSuchSpring { spring, springs } => {
            Details { variant: "NoSuchSpring", ..d }.f("spring", spring).f("springs", springs)
        }
        &DynamicsError::InvalidSetup { options, name, value, rule } => {
            option(d, "InvalidSetup", options, name, value, rule)
        }
        _ => Details { variant: "Other", ..d },
    };
    let class =
        if matches!(e, DynamicsError::InvalidSetup { .. }) { "DynamicsOptionError" } else { "DynamicsError" };
    d.raise(class, e.to_string())
}

pub fn config(py: Python<'_>, e: &ConfigError) -> PyErr {
    let d = Details::new(py, "");
    let d = match e {
        ConfigError::Chain(p) => Details { variant: "Chain", ..d }.source(parameter(py, p)),
        &ConfigError::InvalidOption(o) => option(d, "InvalidOption", o.options, o.field, o.value, o.rule),
        &ConfigError::Value { name, value, rule } => {
            Details { variant: "Value", ..d }.f("name", name).f("value", value).f("rule", rule)
        }
        &ConfigError::OutputBudget { t_max, output_interval, outputs, budget } => {
            Details { variant: "OutputBudget", ..d }
                .f("t_max", t_max)
                .f("output_interval", output_interval)
                .f("outputs", outputs)
                .f("budget", budget)
        }
        &ConfigError::StepBudget { dt, t_max, steps, budget } => Details { variant: "StepBudget", ..d }
            .f("dt", dt)
            .f("t_max", t_max)
            .f("steps", steps)
            .f("budget", budget),
        ConfigError::Experiment { n, shortest, source } => Details { variant: "Experiment", ..d }
            .f("n", *n)
            .f("shortest", shortest.map(std::num::NonZeroUsize::get))
            .source(dynamics(py, source)),
        _ => Details { variant: "Other", ..d },
    };
    let class = if matches!(e, ConfigError::InvalidOption(_)) { "ConfigOptionError" } else { "ConfigError" };
    d.raise(class, e.to_string())
}

/// chain-sweep's `ConfigError::Chain` (worded as its `Display`, "invalid chain: ...") around a
/// `ParameterError` raised here, for a rotor count that no `usize` holds ([`unbounded`]).
pub fn config_chain(py: Python<'_>, cause: PyErr) -> PyErr {
    let message = format!("invalid chain: {}", cause.value(py));
    Details { variant: "Chain", ..Details::new(py, "") }.source(cause).raise("ConfigError", message)
}

pub fn point(py: Python<'_>, e: &PointError) -> PyErr {
    let d = Details::new(py, "");
    let d = match e {
        PointError::Config(c) => Details { variant: "Config", ..d }.source(config(py, c)),
        PointError::Chain(p) => Details { variant: "Chain", ..d }.source(parameter(py, p)),
        PointError::Scatter(b) => budget(py, b, d),
        _ => Details { variant: "Other", ..d },
    };
    let class = match e {
        PointError::Scatter(
            BudgetError::InvalidOption(_) | BudgetError::Setup(DynamicsError::InvalidSetup { .. }),
        )
        | PointError::Config(ConfigError::InvalidOption(_)) => "PointOptionError",
        _ => "PointError",
    };
    d.raise(class, e.to_string())
}

/// The details of a point that broke its energy budget (the dynamics' `BudgetError`), under the
/// variant names Python has always seen (`Run`, `EnergyBudget`, `Recomputed`, ...).
fn budget<'py>(py: Python<'py>, e: &BudgetError, d: Details<'py>) -> Details<'py> {
    match e {
        BudgetError::Run { integrator, source } => {
            Details { variant: "Run", ..d }.f("integrator", integrator.name()).source(dynamics(py, source))
        }
        &BudgetError::EnergyBudget { error, tolerance, integrator } => {
            Details { variant: "EnergyBudget", ..d }
                .f("error", error)
                .f("tolerance", tolerance)
                .f("integrator", integrator.name())
        }
        BudgetError::Recomputed { verlet, dop853 } => {
            let d = Details { variant: "Recomputed", ..d }.f("verlet", verlet.to_string());
            let d = match verlet {
                VerletBreach::EnergyError { error } => d.f("verlet_energy_error", *error),
                VerletBreach::Failed { source } => d.f("verlet_error", dynamics(py, source).value(py)),
                _ => d,
            };
            let inner = budget(py, dop853, Details::new(py, "")).raise("PointError", dop853.to_string());
            d.source(inner)
        }
        &BudgetError::SpunThroughPi { time, outputs } => {
            Details { variant: "SpunThroughPi", ..d }.f("time", time).f("outputs", outputs)
        }
        BudgetError::NothingRecorded => Details { variant: "NothingRecorded", ..d },
        &BudgetError::InvalidOption(o) => option(d, "InvalidOption", o.options, o.field, o.value, o.rule),
        BudgetError::Setup(source) => Details { variant: "Setup", ..d }.source(dynamics(py, source)),
        _ => Details { variant: "Other", ..d },
    }
}

pub fn grid(py: Python<'_>, e: &GridError) -> PyErr {
    let d = Details::new(py, "");
    let d = match e {
        &GridError::EmptyAxis { count } => Details { variant: "EmptyAxis", ..d }.f("count", count),
        &GridError::TooManyPoints { count } => Details { variant: "TooManyPoints", ..d }.f("count", count),
        &GridError::TooLarge { nx, ny } => Details { variant: "TooLarge", ..d }.f("nx", nx).f("ny", ny),
        &GridError::NotFinite { value } => Details { variant: "NotFinite", ..d }.f("value", value),
        &GridError::AmbiguousSinglePoint { from, to } => {
            Details { variant: "AmbiguousSinglePoint", ..d }.f("from_", from).f("to", to)
        }
        GridError::BadRange { text, reason } => {
            Details { variant: "BadRange", ..d }.f("text", text.as_str()).f("reason", reason.as_str())
        }
        &GridError::NotPositive { from, to } => {
            Details { variant: "NotPositive", ..d }.f("from_", from).f("to", to)
        }
        &GridError::InvalidOption(o) => option(d, "InvalidOption", o.options, o.field, o.value, o.rule),
        _ => Details { variant: "Other", ..d },
    };
    let class = if matches!(e, GridError::InvalidOption(_)) { "GridOptionError" } else { "GridError" };
    d.raise(class, e.to_string())
}

/// Errors of results files. The path, when the variant has one, is the `path` attribute.
pub fn sweep(py: Python<'_>, e: &SweepError) -> PyErr {
    // A result buffer the allocator cannot hold: MemoryError with the bytes.
    if let &SweepError::OutOfMemory(a) = e {
        return crate::args::memory_error(a);
    }
    let d = Details::new(py, "");
    let path = |p: &std::path::Path| p.display().to_string();
    let d = match e {
        SweepError::Io { action, path: p, source } => Details { variant: "Io", ..d }
            .f("action", *action)
            .f("path", path(p))
            .f("errno", source.raw_os_error()),
        SweepError::NotAResultsFile { path: p, found } => {
            Details { variant: "NotAResultsFile", ..d }.f("path", path(p)).f("found", found.as_str())
        }
        SweepError::HeaderMismatch { path: p, expected, found } => Details { variant: "HeaderMismatch", ..d }
            .f("path", path(p))
            .f("expected", expected.as_str())
            .f("found", found.as_str()),
        SweepError::GridMismatch { path: p, expected, found } => Details { variant: "GridMismatch", ..d }
            .f("path", path(p))
            .f("expected", expected.as_str())
            .f("found", found.as_str()),
        SweepError::RunMismatch { path: p, expected, found } => Details { variant: "RunMismatch", ..d }
            .f("path", path(p))
            .f("expected", expected.as_str())
            .f("found", found.as_str()),
        SweepError::ShardMismatch { path: p, expected, found } => Details { variant: "ShardMismatch", ..d }
            .f("path", path(p))
            .f("expected", expected.as_str())
            .f("found", found.as_str()),
        SweepError::Parse { path: p, line, reason } => {
            Details { variant: "Parse", ..d }.f("path", path(p)).f("line", *line).f("reason", reason.as_str())
        }
        SweepError::Locked { path: p } => Details { variant: "Locked", ..d }.f("path", path(p)),
        SweepError::NotAFile { path: p, kind } => {
            Details { variant: "NotAFile", ..d }.f("path", path(p)).f("kind", *kind)
        }
        SweepError::NotInSweep { path: p, index, .. } => {
            Details { variant: "NotInSweep", ..d }.f("path", path(p)).f("index", *index)
        }
        SweepError::WrongCoordinates { index, given, grid } => Details { variant: "WrongCoordinates", ..d }
            .f("index", *index)
            .f("given", *given)
            .f("grid", *grid),
        SweepError::AlreadyDone { path: p, index } => {
            Details { variant: "AlreadyDone", ..d }.f("path", path(p)).f("index", *index)
        }
        SweepError::Grid(g) => Details { variant: "Grid", ..d }.source(grid(py, g)),
        SweepError::NoShards { reason } => Details { variant: "NoShards", ..d }.f("reason", reason.as_str()),
        SweepError::NotAShard { path: p } => Details { variant: "NotAShard", ..d }.f("path", path(p)),
        SweepError::ShardSet { reason } => Details { variant: "ShardSet", ..d }.f("reason", reason.as_str()),
        SweepError::DuplicatePoint { index, first, second } => Details { variant: "DuplicatePoint", ..d }
            .f("index", *index)
            .f("first", path(first))
            .f("second", path(second)),
        SweepError::MissingPoints { missing, total, first, unfinished } => {
            Details { variant: "MissingPoints", ..d }
                .f("missing", *missing)
                .f("total", *total)
                .f("first", *first)
                .f("unfinished", unfinished.as_str())
        }
        SweepError::WouldOverwrite { path: p, reason } => {
            Details { variant: "WouldOverwrite", ..d }.f("path", path(p)).f("reason", reason.as_str())
        }
        SweepError::InvalidRecord { reason } => {
            Details { variant: "InvalidRecord", ..d }.f("reason", reason.as_str())
        }
        SweepError::ThreadPool { threads, .. } => {
            Details { variant: "ThreadPool", ..d }.f("threads", *threads)
        }
        &SweepError::Threads { option: o, max, cores } => {
            option(d, "Threads", o.options, o.field, o.value, o.rule).f("max", max).f("cores", cores)
        }
        _ => Details { variant: "Other", ..d },
    };
    let class = if matches!(e, SweepError::Threads { .. }) { "SweepOptionError" } else { "SweepError" };
    d.raise(class, e.to_string())
}

/// A plain `ValueError` (a wrong array length, an unknown name): programming errors of the
/// caller, which the Rust API treats as panics.
pub fn value_error(message: impl Into<String>) -> PyErr {
    pyo3::exceptions::PyValueError::new_err(message.into())
}

/// A cell that cannot be read or is not valid: `CellError` with `key` and `line` (None when the
/// cell did not come from text) and the variant's numbers.
pub fn cell(py: Python<'_>, e: &CellError) -> PyErr {
    let d = Details::new(py, "");
    let at = e.location();
    let d = d.f("key", at.map(|a| a.key.clone())).f("line", e.line());
    let d = match e {
        CellError::Syntax { column, message, .. } => {
            Details { variant: "Syntax", ..d }.f("column", *column).f("reason", message.clone())
        }
        CellError::Missing { .. } => Details { variant: "Missing", ..d },
        CellError::NotForKind { kind, .. } => Details { variant: "NotForKind", ..d }.f("kind", *kind),
        CellError::NotFinite { value, .. } => Details { variant: "NotFinite", ..d }.f("value", *value),
        CellError::OutOfRange { value, rule, .. } => {
            Details { variant: "OutOfRange", ..d }.f("value", *value).f("rule", *rule)
        }
        CellError::Length { expected, found, .. } => {
            Details { variant: "Length", ..d }.f("expected", *expected).f("found", *found)
        }
        CellError::Dimension { found, .. } => Details { variant: "Dimension", ..d }.f("found", *found),
        CellError::DegenerateLattice { det, relative, .. } => {
            Details { variant: "DegenerateLattice", ..d }.f("det", *det).f("relative", *relative)
        }
        CellError::Empty { .. } => Details { variant: "Empty", ..d },
        CellError::TooLarge { what, found, max, .. } => {
            Details { variant: "TooLarge", ..d }.f("what", *what).f("found", *found).f("max", *max)
        }
        CellError::UnknownKind { found, .. } => {
            Details { variant: "UnknownKind", ..d }.f("found", found.clone())
        }
        CellError::BadName { name, .. } => Details { variant: "BadName", ..d }.f("name", name.clone()),
        CellError::UnknownNode { name, suggestion, .. } => Details { variant: "UnknownNode", ..d }
            .f("name", name.clone())
            .f("suggestion", suggestion.clone()),
        CellError::ZeroLengthBond { bond, length, scale, .. } => Details { variant: "ZeroLengthBond", ..d }
            .f("bond", *bond)
            .f("length", *length)
            .f("scale", *scale),
        CellError::DuplicateBond { first, second, .. } => {
            Details { variant: "DuplicateBond", ..d }.f("first", *first).f("second", *second)
        }
        _ => Details { variant: "Other", ..d },
    };
    d.raise("CellError", e.to_string())
}

/// An analysis of a network that cannot be carried out: `NetworkError` (`WindingUndefined` and
/// `WeylPoints` for a winding that does not exist), with the variant's numbers.
pub fn network(py: Python<'_>, e: &NetworkError) -> PyErr {
    // A patch or model the allocator cannot hold: MemoryError with the bytes.
    if let &NetworkError::OutOfMemory(a) = e {
        return crate::args::memory_error(a);
    }
    // A large free patch's count on the sparse path: the statics' exception, with its numbers.
    if let NetworkError::Statics(s) = e {
        return statics(py, s);
    }
    let d = Details::new(py, "");
    let d = match e {
        NetworkError::PatchSize { what, direction, found, rule } => Details { variant: "PatchSize", ..d }
            .f("what", *what)
            .f("direction", *direction)
            .f("found", *found)
            .f("rule", rule.clone()),
        NetworkError::PeriodicImage { cells, bond, problem } => Details { variant: "PeriodicImage", ..d }
            .f("cells", cells.to_vec())
            .f("bond", *bond)
            .f("problem", problem.clone()),
        NetworkError::TooLarge { what, rows, cols, limit } => Details { variant: "TooLarge", ..d }
            .f("what", *what)
            .f("rows", *rows)
            .f("cols", *cols)
            .f("limit", *limit),
        NetworkError::NoConvergence { what, decomposition, rows, cols } => {
            Details { variant: "NoConvergence", ..d }
                .f("what", *what)
                .f("decomposition", *decomposition)
                .f("rows", *rows)
                .f("cols", *cols)
        }
        NetworkError::IndexTheorem { zero_modes, self_stresses, dof, bonds } => {
            Details { variant: "IndexTheorem", ..d }
                .f("zero_modes", *zero_modes)
                .f("self_stresses", *self_stresses)
                .f("dof", *dof)
                .f("bonds", *bonds)
        }
        NetworkError::NotSquare { bonds, dof } => {
            Details { variant: "NotSquare", ..d }.f("bonds", *bonds).f("dof", *dof)
        }
        NetworkError::WindingUndefined { direction, reason } => Details { variant: "WindingUndefined", ..d }
            .f("direction", *direction)
            .f("reason", reason.clone()),
        NetworkError::WeylPoints { direction, transverse, windings } => {
            Details { variant: "WeylPoints", ..d }
                .f("direction", *direction)
                .f("transverse", transverse.clone())
                .f("windings", windings.clone())
        }
        NetworkError::Argument { what, problem } => {
            Details { variant: "Argument", ..d }.f("what", *what).f("problem", problem.clone())
        }
        &NetworkError::InvalidOption(o) => option(d, "InvalidOption", o.options, o.field, o.value, o.rule),
        _ => Details { variant: "Other", ..d },
    };
    let class =
        if matches!(e, NetworkError::InvalidOption(_)) { "NetworkOptionError" } else { "NetworkError" };
    d.raise(class, e.to_string())
}
