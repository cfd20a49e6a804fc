//! The dynamics of a `Chain` (paper Secs. V, VI, Appendix B): launch, propagate, scatter. Each
//! runs with the GIL released.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rotor_chain::dynamics::integrate::{AdaptiveOptions, Sponge, State};
use rotor_chain::dynamics::launch::{self as ln, Direction};
use rotor_chain::dynamics::run::{self as rn, ABSORBING_ENDS, Method, RunOptions};
use rotor_chain::dynamics::scatter::{self as sc, ScatterSetup};

use crate::args::{array, charge, choice, matrix, try_rows};
use crate::chain::Chain;
use crate::errors::{self, value_error};
use crate::pickle::{self, pickle_fields};

fn direction(name: &str) -> PyResult<Direction> {
    choice("direction", name, &[("left", Direction::Left), ("right", Direction::Right)])
}

/// The run options of `Chain.propagate` and `Chain.scatter`; the Rust run checks each by name
/// (a non-finite `t_max` is `InvalidOption`, a negative one `EndBeforeStart`). An option of the
/// other method (`dt` with `"dop853"`, `rtol` or `atol` with `"verlet"`) is a `ValueError`: it
/// would go unused.
#[allow(clippy::too_many_arguments)]
pub fn run_options(
    t_max: f64,
    output_interval: f64,
    method: &str,
    dt: Option<f64>,
    (rtol, atol): (Option<f64>, Option<f64>),
    damping: f64,
    absorbing_ends: bool,
    space_time: bool,
    energy_limit: f64,
    time_unit: f64,
) -> PyResult<RunOptions> {
    let adaptive = choice("method", method, &[("verlet", false), ("dop853", true)])?;
    let method = if adaptive {
        if let Some(dt) = dt {
            return Err(value_error(format!(
                "dt = {dt:?} applies to method='verlet' only (dop853 chooses its steps by rtol and atol)"
            )));
        }
        // The Rust defaults (`Method::dop853()`'s), for a tolerance not given.
        let d = AdaptiveOptions::default();
        Method::Dop853 { rtol: rtol.unwrap_or(d.rtol), atol: atol.unwrap_or(d.atol) }
    } else {
        if let Some((name, value)) =
            [("rtol", rtol), ("atol", atol)].into_iter().find_map(|(n, v)| Some((n, v?)))
        {
            return Err(value_error(format!(
                "{name} = {value:?} applies to method='dop853' only (verlet takes steps of at most dt)"
            )));
        }
        Method::Verlet
    };
    Ok(RunOptions {
        t_max,
        output_interval,
        method,
        dt,
        damping,
        // The sponge's rate is the paper's in the chain's time unit (30/t at k = 1e4, M = 1).
        absorbing_ends: absorbing_ends
            .then_some(Sponge { strength: ABSORBING_ENDS.strength / time_unit, ..ABSORBING_ENDS }),
        space_time,
        energy_limit,
        ..RunOptions::default()
    })
}

/// A defect set in motion (``Chain.launch``).
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct Launch {
    /// Angles at time 0 (radians).
    theta: Py<PyArray1<f64>>,
    /// Angular velocities at time 0 (``1/t``).
    omega: Py<PyArray1<f64>>,
    /// The normalised launch vector in tip displacements (``sum e_i^2 = 1``).
    mode: Py<PyArray1<f64>>,
    /// Where the defect starts (Appendix C wall position).
    position: f64,
    /// ``"kink"`` or ``"antikink"``.
    defect: String,
}

#[pymethods]
impl Launch {
    fn __repr__(&self) -> String {
        format!("Launch(defect='{}', position={:?})", self.defect, self.position)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

pickle_fields!(Launch { theta, omega, mode, position, defect });

pub fn launch(
    chain: &Chain,
    py: Python<'_>,
    defect: &str,
    position: f64,
    v0: f64,
    direction_name: &str,
) -> PyResult<Launch> {
    let (charge, direction) = (charge(defect)?, direction(direction_name)?);
    let l = py
        .detach(|| ln::launch(&chain.chain, charge, position, v0, direction))
        .map_err(|e| errors::dynamics(py, &e))?;
    Ok(Launch {
        theta: array(py, l.state.theta),
        omega: array(py, l.state.omega),
        mode: array(py, l.mode),
        position: l.position,
        defect: l.charge.name().to_owned(),
    })
}

/// What a run recorded (``Chain.propagate``, ``Scattering.run``): one entry per output.
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct Run {
    /// Output times (``t``).
    times: Py<PyArray1<f64>>,
    /// Kinetic energy ``sum_i M r_i^2 thetadot_i^2 / 2`` at each output, absolute as
    /// ``Chain.energy``.
    kinetic: Py<PyArray1<f64>>,
    /// The walls at each output: ``[(position, "kink" | "antikink"), ...]``, interior walls left
    /// to right, then walls that left through an end (kept at ``0`` or ``n - 1``, Appendix C).
    walls: Vec<Vec<(f64, String)>>,
    /// ``(kinks, antikinks)`` at each output (``T x 2``, int64: they are counts).
    wall_counts: Py<PyArray2<i64>>,
    /// Output times at which the conserved ``N_kink - N_antikink`` was violated (rotors spun
    /// through ``|theta| = pi``).
    violations: Vec<f64>,
    /// The angles at every output (``T x n``) if ``space_time=True``, else ``None``.
    space_time: Option<Py<PyArray2<f64>>>,
    /// Final time, angles and angular velocities.
    time: f64,
    theta: Py<PyArray1<f64>>,
    omega: Py<PyArray1<f64>>,
    /// ``E = T + V`` at the start and at the end, and the largest ``|E - E0|`` at the outputs.
    energy_initial: f64,
    energy_final: f64,
    max_energy_error: f64,
    /// The largest relative energy error (the rise, with damping).
    relative_energy_error: f64,
    /// Accepted and rejected steps.
    steps: usize,
    rejected: usize,
    /// ``"verlet"`` or ``"dop853"``.
    integrator: String,
}

#[pymethods]
impl Run {
    fn __repr__(&self) -> String {
        format!(
            "Run(integrator='{}', time={:?}, steps={}, relative_energy_error={:e})",
            self.integrator, self.time, self.steps, self.relative_energy_error
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

pickle_fields!(Run {
    times,
    kinetic,
    walls,
    wall_counts,
    violations,
    space_time,
    time,
    theta,
    omega,
    energy_initial,
    energy_final,
    max_energy_error,
    relative_energy_error,
    steps,
    rejected,
    integrator
});

fn run_of(py: Python<'_>, run: rn::Run) -> PyResult<Run> {
    let snapshots = &run.tracker.snapshots;
    // A count past i64::MAX is no chain's (MAX_ROTORS is far below it); saturate rather than wrap.
    let counts: Vec<i64> = snapshots
        .iter()
        .flat_map(|s| {
            let (k, a) = s.counts();
            [k, a].map(|c| i64::try_from(c).unwrap_or(i64::MAX))
        })
        .collect();
    let walls = snapshots
        .iter()
        .map(|s| s.walls.iter().map(|w| (w.position, w.charge.name().to_owned())).collect())
        .collect();
    let n = run.final_state.theta.len();
    let space_time = match run.space_time.times.is_empty() {
        true => None,
        false => Some(try_rows(py, &run.space_time.theta, n, "the space-time image")?),
    };
    Ok(Run {
        times: array(py, run.kinetic.iter().map(|k| k.0).collect()),
        kinetic: array(py, run.kinetic.iter().map(|k| k.1).collect()),
        walls,
        wall_counts: matrix(py, snapshots.len(), 2, counts),
        violations: run.tracker.violations.clone(),
        space_time,
        time: run.final_state.time,
        theta: array(py, run.final_state.theta),
        omega: array(py, run.final_state.omega),
        energy_initial: run.report.energy_initial,
        energy_final: run.report.energy_final,
        max_energy_error: run.report.max_energy_error,
        relative_energy_error: run.report.relative_energy_error(),
        steps: run.report.steps,
        rejected: run.report.rejected,
        integrator: run.integrator.to_owned(),
    })
}

pub fn propagate(
    chain: &Chain,
    py: Python<'_>,
    theta: Vec<f64>,
    omega: Vec<f64>,
    options: RunOptions,
) -> PyResult<Run> {
    let state = State { time: 0.0, theta, omega };
    let mut interrupt = Interrupt::default();
    let run = py
        .detach(|| rn::propagate(&chain.chain, state, &options, &mut |_| interrupt.pending()))
        .map_err(|e| errors::dynamics(py, &e))?;
    interrupt.raise()?;
    run_of(py, run)
}

/// Python's signals (Ctrl-C) seen from a run without the GIL: at an output, at most every
/// 50 ms, the GIL is taken to run the signal handlers; a `KeyboardInterrupt` (or any error they
/// raise) stops the run and is raised when it returns.
#[derive(Default)]
pub(crate) struct Interrupt {
    last: Option<std::time::Instant>,
    error: Option<PyErr>,
}

impl Interrupt {
    /// Whether a signal handler raised: the run's stop question.
    pub(crate) fn pending(&mut self) -> bool {
        let now = std::time::Instant::now();
        if self.last.is_some_and(|t| now.duration_since(t) < std::time::Duration::from_millis(50)) {
            return false;
        }
        self.last = Some(now);
        self.error = Python::attach(|py| py.check_signals()).err();
        self.error.is_some()
    }

    /// The signal handler's error, if one stopped the run.
    pub(crate) fn raise(self) -> PyResult<()> {
        self.error.map_or(Ok(()), Err)
    }
}

/// The outcome of ``Chain.scatter`` (paper Sec. VI).
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct Scattering {
    /// ``"transmitted"``, ``"reflected"``, ``"trapped"``, ``"split"``, ``"annihilated"``,
    /// ``"disintegrated"``, ``"pair-creation"`` or ``"undecided"`` (docs/dynamics.md §5).
    outcome: String,
    /// When the outcome was decided (``t``; the run's end if undecided).
    decided_at: f64,
    /// Whether the confirmation window closed before the run ended.
    confirmed: bool,
    /// An event after the outcome was settled (``"annihilated"`` or ``"escaped"``), or ``None``.
    later: Option<String>,
    /// Its time, or ``None``.
    later_at: Option<f64>,
    /// The run (walls, energies, final state).
    run: Py<Run>,
}

#[pymethods]
impl Scattering {
    fn __repr__(&self) -> String {
        format!(
            "Scattering(outcome='{}', decided_at={:?}, confirmed={}, later={}, later_at={})",
            self.outcome,
            self.decided_at,
            if self.confirmed { "True" } else { "False" },
            self.later.as_ref().map_or("None".to_owned(), |l| format!("'{l}'")),
            self.later_at.map_or("None".to_owned(), |t| format!("{t:?}"))
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

pickle_fields!(Scattering { outcome, decided_at, confirmed, later, later_at, run });

pub struct ScatterArgs<'a> {
    pub defect: &'a str,
    pub v0: f64,
    pub impurity: usize,
    pub start: Option<f64>,
    pub direction: &'a str,
    pub watch: f64,
    pub options: RunOptions,
    /// The chain's time unit relative to the paper's (`paper_time_unit`), for the rules' windows.
    pub time_unit: f64,
}

pub fn scatter(chain: &Chain, py: Python<'_>, a: ScatterArgs<'_>) -> PyResult<Scattering> {
    let (charge, direction) = (charge(a.defect)?, direction(a.direction)?);
    let mut setup = ScatterSetup::from_the_right(charge, a.v0, a.impurity).in_time_unit(a.time_unit);
    setup.direction = direction;
    setup.start = match (a.start, direction) {
        (Some(start), _) => start,
        (None, Direction::Left) => setup.start,
        (None, Direction::Right) => a.impurity as f64 + 0.5 - 15.0,
    };
    // Checked with every other field by `ScatterSetup`'s validation, in `scatter_with`.
    setup.watch = a.watch;
    setup.run = a.options;
    let mut interrupt = Interrupt::default();
    let s = py
        .detach(|| sc::scatter_with(&chain.chain, &setup, &mut |_| interrupt.pending()))
        .map_err(|e| errors::dynamics(py, &e))?;
    interrupt.raise()?;
    Ok(Scattering {
        outcome: s.outcome.name().to_owned(),
        decided_at: s.decided_at,
        confirmed: s.confirmed,
        later: s.later.map(|(e, _)| e.name().to_owned()),
        later_at: s.later.map(|(_, t)| t),
        run: Py::new(py, run_of(py, s.run)?)?,
    })
}
