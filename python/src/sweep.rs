//! Phase-diagram sweeps: chain-sweep's `PhaseDiagram::compute_point` over lists of points (what
//! one Dask task or one local chunk computes), its resumable results files, and the axes of the
//! `phase-diagram` command line. `rotor_chain/sweep.py` drives these.
//!
//! A point's record crosses into Python as a dict with the columns of the results file
//! (`i, j, ki, v0, outcome, t_decided, confirmed, later, t_later, kinks_final, antikinks_final,
//! energy_error, integrator, unresolved, unresolved_outcome, t_unresolved, error`): a failed point
//! has `error` set and `None` elsewhere; a resolved one `None` in the three `unresolved` keys. Floats
//! are Python floats, so a record goes to another process and back bit for bit.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::str::FromStr;

use chain_sweep::scattering::{
    Defect, Direction, Ends, LaterEvent, Outcome, PhaseDiagram as Diagram, PointRecord, Recomputed,
    method_by_name,
};
use chain_sweep::threads::{max_threads, worker_threads};
use chain_sweep::{Axis, Grid, Point, ResultsFile as File, SweepError, SweepOptions};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};
use rayon::prelude::*;
use rotor_chain::validate::InvalidOption;

use crate::args::{self, Real, RotorCount};
use crate::errors::{self, value_error};

/// One phase diagram's settings, checked (chain-sweep's ``PhaseDiagram``): the chain of paper
/// Sec. VI with the impurity on the middle spring, the defect launched from 15 sites to its
/// right, each point held to the energy budget. ``rotor_chain.sweep.phase_diagram`` builds it.
#[pyclass(frozen, module = "rotor_chain._native")]
pub struct PhaseDiagram {
    d: Diagram,
}

/// `(i, j, ki, v0)`: a grid point with its coordinates.
type GridPoint = (usize, usize, f64, f64);

#[pymethods]
impl PhaseDiagram {
    #[new]
    #[pyo3(signature = (defect, *, n = RotorCount(Ok(60)), r = Real::of(0.8), k = Real::of(1.0e4), theta_bar = Real::of(0.28),
                        mass = Real::of(1.0), ends = "free", integrator = "verlet", dt = None,
                        energy_tolerance = Real::of(chain_sweep::scattering::DEFAULT_ENERGY_TOLERANCE),
                        recompute = true, t_max = Real::of(20.0), impurity = None, impurity_rest_length = None,
                        start = None, direction = "left", damping = Real::of(0.0), cross_check = false),
           text_signature = "(defect, *, n=60, r=0.8, k=1e4, theta_bar=0.28, mass=1.0, ends='free', \
                             integrator='verlet', dt=None, energy_tolerance=DEFAULT_ENERGY_TOLERANCE, recompute=True, \
                             t_max=20.0, impurity=None, impurity_rest_length=None, start=None, direction='left', \
                             damping=0.0, cross_check=False)")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        defect: &str,
        n: RotorCount,
        r: Real,
        k: Real,
        theta_bar: Real,
        mass: Real,
        ends: &str,
        integrator: &str,
        dt: Option<Real>,
        energy_tolerance: Real,
        recompute: bool,
        t_max: Real,
        impurity: Option<usize>,
        impurity_rest_length: Option<Real>,
        start: Option<Real>,
        direction: &str,
        damping: Real,
        cross_check: bool,
    ) -> PyResult<Self> {
        let (r, k, theta_bar, mass) =
            (r.get("r")?, k.get("k")?, theta_bar.get("theta_bar")?, mass.get("mass")?);
        let dt = Real::optional(dt, "dt")?;
        let (energy_tolerance, t_max) = (energy_tolerance.get("energy_tolerance")?, t_max.get("t_max")?);
        // chain-sweep's own names (its `FromStr`), as the command line and the results file
        // spell them.
        let unknown = |e: chain_sweep::scattering::UnknownName| value_error(e.to_string());
        let defect: Defect = defect.parse().map_err(unknown)?;
        let ends: Ends = ends.parse().map_err(unknown)?;
        let integrator = method_by_name(integrator).map_err(unknown)?;
        // A wrong type stays the TypeError that names `n`; a wrong count is a setting's error.
        let n = n.0.map_err(|cause| {
            if cause.is_instance_of::<pyo3::exceptions::PyTypeError>(py) {
                cause
            } else {
                errors::config_chain(py, cause)
            }
        })?;
        let mut d = Diagram::new(n, r, k, theta_bar, defect).map_err(|e| errors::config(py, &e))?;
        d.mass = mass;
        d.ends = ends;
        d.integrator = integrator;
        d.dt = dt;
        d.energy_tolerance = energy_tolerance;
        d.recompute = recompute;
        d.t_max = t_max;
        // The `phase-diagram` command's experiment settings, with its names.
        d.impurity_spring = impurity;
        d.impurity_rest_length = Real::optional(impurity_rest_length, "impurity_rest_length")?;
        d.start = Real::optional(start, "start")?;
        d.direction = match direction {
            "left" => Direction::Left,
            "right" => Direction::Right,
            other => {
                return Err(value_error(format!("direction must be one of 'left', 'right', got '{other}'")));
            }
        };
        d.damping = damping.get("damping")?;
        d.cross_check = cross_check;
        d.check().map_err(|e| errors::config(py, &e))?;
        Ok(Self { d })
    }

    /// The run label of the results file: the same as the ``phase-diagram`` command's for the
    /// same settings, so either resumes the other's file.
    #[getter]
    fn run_label(&self) -> String {
        self.d.run_label()
    }

    /// Checks an impurity stiffness ratio ``k_i/k`` (ConfigError if it is not > 0 with a finite
    /// ``k_i``).
    fn check_ki(&self, py: Python<'_>, ki: f64) -> PyResult<()> {
        self.d.check_ki(ki).map_err(|e| errors::config(py, &e))
    }

    /// One point: the scattering run at ``(ki, v0)`` with its energy budget, as a record dict.
    ///
    /// Raises:
    ///     PointError: the point failed, with the numbers (``variant``: ``EnergyBudget``,
    ///         ``Recomputed``, ``Run``, ``SpunThroughPi``, ...).
    fn compute_point<'py>(&self, py: Python<'py>, ki: f64, v0: f64) -> PyResult<Bound<'py, PyDict>> {
        let record = py.detach(|| self.d.compute_point(ki, v0)).map_err(|e| errors::point(py, &e))?;
        record_dict(py, (0, 0, ki, v0), &Ok(record))
    }

    /// The records of ``points`` (``(i, j, ki, v0)`` tuples), computed on ``threads`` threads
    /// (default: every core) with the GIL released, in the order given. A point that fails (or
    /// panics) has its message in ``error``; nothing is raised for it. Never more threads start
    /// than there are points; ``threads`` above ``max_threads()`` (4 per core) or 0 is a
    /// ``SweepOptionError`` (a ``ValueError`` naming ``SweepOptions.threads``) before any point.
    #[pyo3(signature = (points, threads = None))]
    fn compute_points<'py>(
        &self,
        py: Python<'py>,
        points: Vec<GridPoint>,
        threads: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let threads = threads.map(thread_count).transpose()?;
        let threads = worker_threads(threads, points.len()).map_err(|e| errors::sweep(py, &e))?;
        // Every point's record has its place before any is computed: MemoryError at once.
        let mut results: Vec<Result<PointRecord, String>> =
            rotor_chain::allocation::try_vec(points.len(), "the points' records")
                .map_err(crate::args::memory_error)?;
        let results = py
            .detach(|| -> Result<(), rayon::ThreadPoolBuildError> {
                let one = |&(_, _, ki, v0): &GridPoint| compute_one(&self.d, ki, v0);
                if threads == 1 {
                    results.extend(points.iter().map(one));
                    return Ok(());
                }
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build()?;
                pool.install(|| points.par_iter().map(one).collect_into_vec(&mut results));
                Ok(())
            })
            .map(|()| results);
        let results = results
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("cannot start threads: {e}")))?;
        points.iter().zip(&results).map(|(p, r)| record_dict(py, *p, r)).collect()
    }

    fn __repr__(&self) -> String {
        format!("PhaseDiagram({})", self.d.run_label())
    }

    /// Pickling (for multiprocessing and Dask): the constructor's arguments, checked again.
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let d = &self.d;
        let args = PyTuple::new(py, [d.defect.name()])?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("n", d.n)?;
        kwargs.set_item("r", d.r)?;
        kwargs.set_item("k", d.k)?;
        kwargs.set_item("theta_bar", d.theta_bar)?;
        kwargs.set_item("mass", d.mass)?;
        kwargs.set_item("ends", d.ends.name())?;
        kwargs.set_item("integrator", d.integrator.name())?;
        kwargs.set_item("dt", d.dt)?;
        kwargs.set_item("energy_tolerance", d.energy_tolerance)?;
        kwargs.set_item("recompute", d.recompute)?;
        kwargs.set_item("t_max", d.t_max)?;
        kwargs.set_item("impurity", d.impurity_spring)?;
        kwargs.set_item("impurity_rest_length", d.impurity_rest_length)?;
        kwargs.set_item("start", d.start)?;
        kwargs.set_item("direction", if d.direction == Direction::Right { "right" } else { "left" })?;
        kwargs.set_item("damping", d.damping)?;
        kwargs.set_item("cross_check", d.cross_check)?;
        Ok((args, kwargs))
    }
}

/// A thread count as Python gives it: an int (not a bool or a float: `TypeError`); one that no
/// machine integer holds is outside any bound, so it is the same `SweepOptionError` as
/// chain-sweep's `SweepError::Threads`, with the number as given (as a float).
fn thread_count(x: &Bound<'_, PyAny>) -> PyResult<usize> {
    if x.is_instance_of::<pyo3::types::PyBool>() {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "threads must be an int, got {}",
            args::described(x)
        )));
    }
    let beyond = || {
        let value = x.extract::<f64>().unwrap_or(f64::INFINITY);
        let option = InvalidOption {
            options: "SweepOptions",
            field: "threads",
            value,
            rule: chain_sweep::threads::THREADS_RULE,
        };
        let cores = chain_sweep::threads::cores();
        errors::sweep(x.py(), &SweepError::Threads { option, max: max_threads(), cores })
    };
    match args::int(x)? {
        args::Int::Fits(n) => usize::try_from(n).map_err(|_| beyond()),
        args::Int::Above | args::Int::Below => Err(beyond()),
    }
}

/// Checks a thread count as ``compute_points`` would (a ``SweepOptionError``, a ValueError,
/// above ``max_threads()`` or below 1, a TypeError for what is not an int):
/// ``rotor_chain.sweep.phase_diagram`` calls it before any point.
#[pyfunction]
pub fn check_threads(threads: &Bound<'_, PyAny>) -> PyResult<()> {
    let count = thread_count(threads)?;
    worker_threads(Some(count), 1).map(|_| ()).map_err(|e| errors::sweep(threads.py(), &e))
}

/// The most worker threads a sweep starts on this machine (4 per core).
#[pyfunction(name = "max_threads")]
pub fn max_threads_py() -> usize {
    max_threads()
}

/// One point; a panic becomes its error, as in chain-sweep's sweeps.
fn compute_one(d: &Diagram, ki: f64, v0: f64) -> Result<PointRecord, String> {
    match catch_unwind(AssertUnwindSafe(|| d.compute_point(ki, v0))) {
        Ok(result) => result.map_err(|e| e.to_string()),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown payload".to_owned());
            Err(format!("panicked: {message}"))
        }
    }
}

fn record_dict<'py>(
    py: Python<'py>,
    (i, j, ki, v0): GridPoint,
    outcome: &Result<PointRecord, String>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("i", i)?;
    d.set_item("j", j)?;
    d.set_item("ki", ki)?;
    d.set_item("v0", v0)?;
    let none = py.None();
    match outcome {
        Ok(r) => {
            d.set_item("outcome", r.outcome.name())?;
            d.set_item("t_decided", r.t_decided)?;
            d.set_item("confirmed", r.confirmed)?;
            d.set_item("later", r.later.map(|(e, _)| e.name()))?;
            d.set_item("t_later", r.later.map(|(_, t)| t))?;
            d.set_item("kinks_final", r.kinks_final)?;
            d.set_item("antikinks_final", r.antikinks_final)?;
            d.set_item("energy_error", r.energy_error)?;
            d.set_item("integrator", r.integrator.to_string())?;
            let (reason, other, time) = r.unresolved_columns();
            d.set_item("unresolved", reason)?;
            d.set_item("unresolved_outcome", other.map(Outcome::name))?;
            d.set_item("t_unresolved", time)?;
            d.set_item("error", &none)?;
        }
        Err(message) => {
            for key in [
                "outcome",
                "t_decided",
                "confirmed",
                "later",
                "t_later",
                "kinks_final",
                "antikinks_final",
                "energy_error",
                "integrator",
                "unresolved",
                "unresolved_outcome",
                "t_unresolved",
            ] {
                d.set_item(key, &none)?;
            }
            d.set_item("error", message)?;
        }
    }
    Ok(d)
}

fn item<'py, T: FromPyObjectOwned<'py>>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<T> {
    args::item(d, "record", key)
}

/// A record dict's grid index, the coordinates it was computed at, and its outcome.
type RecordOf = ((usize, usize), (f64, f64), Result<PointRecord, String>);

/// A record dict back into the point, its coordinates and its outcome.
fn record_of(d: &Bound<'_, PyDict>) -> PyResult<RecordOf> {
    let index = (item(d, "i")?, item(d, "j")?);
    let coords = (item(d, "ki")?, item(d, "v0")?);
    if let Some(error) = item::<Option<String>>(d, "error")? {
        return Ok((index, coords, Err(error)));
    }
    let outcome: String = item(d, "outcome")?;
    let outcome = Outcome::from_str(&outcome).map_err(|e| value_error(e.to_string()))?;
    let later = match (item::<Option<String>>(d, "later")?, item::<Option<f64>>(d, "t_later")?) {
        (Some(e), Some(t)) => Some((LaterEvent::from_str(&e).map_err(|e| value_error(e.to_string()))?, t)),
        (None, None) => None,
        _ => return Err(value_error("a record has `later` and `t_later` both or neither")),
    };
    let integrator = Recomputed::from_str(&item::<String>(d, "integrator")?).map_err(value_error)?;
    let mut record = PointRecord {
        outcome,
        t_decided: item(d, "t_decided")?,
        confirmed: item(d, "confirmed")?,
        later,
        kinks_final: item(d, "kinks_final")?,
        antikinks_final: item(d, "antikinks_final")?,
        energy_error: item(d, "energy_error")?,
        integrator,
        unresolved: None,
    };
    // Records made before the `unresolved` keys existed have none of them: resolved.
    let optional = |key: &str| -> PyResult<Option<Bound<'_, PyAny>>> {
        d.get_item(key)?.filter(|v| !v.is_none()).map(Ok).transpose()
    };
    let reason: Option<String> = optional("unresolved")?.map(|v| v.extract()).transpose()?;
    let other = match optional("unresolved_outcome")? {
        Some(v) => Some(Outcome::from_str(&v.extract::<String>()?).map_err(|e| value_error(e.to_string()))?),
        None => None,
    };
    let time: Option<f64> = optional("t_unresolved")?.map(|v| v.extract()).transpose()?;
    record.unresolved = record.unresolved_of((reason.as_deref(), other, time)).map_err(value_error)?;
    Ok((index, coords, Ok(record)))
}

/// The values of an axis: ``"FROM:TO:COUNT"`` or ``"FROM:TO:COUNT:log"`` as on the
/// ``phase-diagram`` command line, or a sequence of finite floats.
///
/// Raises:
///     GridError: a malformed range or a value that is not finite.
#[pyfunction]
pub fn axis(py: Python<'_>, spec: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    let axis = if spec.is_instance_of::<PyString>() {
        Axis::from_str(&spec.extract::<String>()?)
    } else {
        Axis::from_values(spec.extract::<Vec<f64>>()?)
    };
    Ok(axis.map_err(|e| errors::grid(py, &e))?.values().to_vec())
}

/// Checks that ``xs`` x ``ys`` is a grid a sweep may have: both axes non-empty, finite and of at
/// most ``MAX_AXIS_COUNT`` values, and at most ``MAX_GRID_POINTS`` points in all (the
/// ``phase-diagram`` command's limits). ``rotor_chain.sweep.phase_diagram`` calls it before it
/// allocates anything per point.
///
/// Raises:
///     GridError: ``variant == "TooLarge"`` (with ``nx``, ``ny``) for too many points;
///         ``"EmptyAxis"``, ``"TooManyPoints"``, ``"NotFinite"`` for a bad axis.
#[pyfunction]
pub fn check_grid(py: Python<'_>, xs: Vec<f64>, ys: Vec<f64>) -> PyResult<()> {
    grid(py, xs, ys).map(|_| ())
}

fn grid(py: Python<'_>, xs: Vec<f64>, ys: Vec<f64>) -> PyResult<Grid> {
    let axes = Axis::from_values(xs).and_then(|x| Ok((x, Axis::from_values(ys)?)));
    let (x, y) = axes.map_err(|e| errors::grid(py, &e))?;
    Grid::new(x, y).map_err(|e| errors::grid(py, &e))
}

/// A phase diagram's results file, opened and locked for one sweep (chain-sweep's
/// ``ResultsFile``): created with its two-line preamble, or resumed if it holds part of the same
/// sweep (the same grid ``xs`` x ``ys`` and ``run`` label), its unfinished last line cut off.
#[pyclass(module = "rotor_chain._native")]
pub struct ResultsFile {
    file: Option<File<PointRecord>>,
}

impl ResultsFile {
    fn open(&mut self) -> PyResult<&mut File<PointRecord>> {
        self.file.as_mut().ok_or_else(|| value_error("the results file is closed"))
    }
}

#[pymethods]
impl ResultsFile {
    #[new]
    #[pyo3(signature = (xs, ys, path, run, *, retry_failed = false))]
    fn new(
        py: Python<'_>,
        xs: Vec<f64>,
        ys: Vec<f64>,
        path: PathBuf,
        run: String,
        retry_failed: bool,
    ) -> PyResult<Self> {
        let grid = grid(py, xs, ys)?;
        let mut options = SweepOptions::new("phase diagram", run);
        options.retry_failed = retry_failed;
        let file = py.detach(|| File::open(&grid, &path, &options)).map_err(|e| errors::sweep(py, &e))?;
        Ok(Self { file: Some(file) })
    }

    /// The ``(i, j)`` the file lacks, in grid order.
    fn missing(&mut self) -> PyResult<Vec<(usize, usize)>> {
        Ok(self.open()?.missing())
    }

    /// What the file held when opened: ``total``, ``skipped`` (points already there),
    /// ``failed_before``, ``retried``, ``repaired_bytes``, ``duplicates``.
    fn summary<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.open()?.summary().clone();
        let d = PyDict::new(py);
        d.set_item("total", s.total)?;
        d.set_item("skipped", s.skipped)?;
        d.set_item("failed_before", s.failed_before)?;
        d.set_item("retried", s.retried)?;
        d.set_item("repaired_bytes", s.repaired_bytes)?;
        d.set_item("duplicates", s.duplicates)?;
        Ok(d)
    }

    /// Append one record dict as one whole line. A point outside the grid, already in the file,
    /// or whose ``ki`` and ``v0`` are not bit for bit the grid's coordinates of its ``(i, j)``
    /// (``variant == "WrongCoordinates"``, with ``given`` and ``grid``) raises SweepError and
    /// writes nothing.
    fn append(&mut self, py: Python<'_>, record: &Bound<'_, PyDict>) -> PyResult<()> {
        let (index, coords, outcome) = record_of(record)?;
        self.open()?.append(index, coords, &outcome).map_err(|e| errors::sweep(py, &e))
    }

    /// Sync the file to disk and release its lock.
    fn close(&mut self, py: Python<'_>) -> PyResult<()> {
        match self.file.take() {
            Some(f) => f.finish().map(|_| ()).map_err(|e| errors::sweep(py, &e)),
            None => Ok(()),
        }
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    fn __exit__(
        &mut self,
        py: Python<'_>,
        _kind: Option<Bound<'_, PyAny>>,
        _value: Option<Bound<'_, PyAny>>,
        _traceback: Option<Bound<'_, PyAny>>,
    ) -> PyResult<bool> {
        self.close(py)?;
        Ok(false)
    }
}

/// Every point of a results file (of ``phase-diagram``, ``rotor_chain.sweep.phase_diagram`` or
/// ``phase-diagram merge``) as record dicts, failed points included, in file order.
#[pyfunction]
pub fn read_points<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let points: Vec<Point<PointRecord>> =
        py.detach(|| chain_sweep::read_points(&path)).map_err(|e| errors::sweep(py, &e))?;
    points
        .iter()
        .map(|p| record_dict(py, (p.index.0, p.index.1, p.coords.0, p.coords.1), &p.outcome))
        .collect()
}
