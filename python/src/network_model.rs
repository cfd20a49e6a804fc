//! `NetworkModel`: the nonlinear mechanics of a finite patch of a `Network` (issue 36;
//! `rotor_chain::network::NetworkModel`): energy and forces, relaxation and Newton, the lowest
//! modes (sparse beyond a few hundred degrees of freedom) and Verlet dynamics, numpy arrays in and
//! out. Coordinates are the patch's: each joint's `x, y` and each rotor's angle, cell after cell.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rotor_chain::Law;
use rotor_chain::Potential;
use rotor_chain::integrate::{Flow, State, VerletOptions, verlet};
use rotor_chain::network::NetworkModel as Model;
use rotor_chain::network::patch::Patch;
use rotor_chain::statics::equilibrium::{NewtonOptions, RelaxOptions, newton, polish, relax};
use rotor_chain::statics::modes::{ModeOptions, normal_modes};

use crate::args::{self, array, choice, matrix, memory_error};
use crate::dynamics::Interrupt;
use crate::errors::{self, value_error};
use crate::network::{Network, boundary_of, cells_of};
use rotor_chain::allocation::{try_grow, try_vec};

/// A finite patch of a network with masses, a spring law and overrides (impurities).
#[pyclass(module = "rotor_chain._native", frozen)]
pub struct NetworkModel {
    model: Model,
}

/// The lowest vibrational modes of a patch, ascending in ``omega^2`` (``K v = omega^2 M v``).
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct NetworkModes {
    /// Signed frequencies ``sign(omega^2) sqrt(|omega^2|)``, as ``Chain.modes``: negative for an
    /// unstable direction.
    frequencies: Py<PyArray1<f64>>,
    /// The eigenvalues ``omega^2``.
    omega_squared: Py<PyArray1<f64>>,
    /// ``vectors[m]``: mode ``m`` over the coordinates, normalised so ``sum_i M_i v_i^2 = 1``.
    vectors: Py<numpy::PyArray2<f64>>,
    /// How many coordinates take part in each mode (``1 / sum_i w_i^2``, ``w_i = M_i v_i^2``).
    participation: Py<PyArray1<f64>>,
}

/// A Verlet run of a patch.
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct NetworkRun {
    /// The output times.
    times: Py<PyArray1<f64>>,
    /// The total energy ``T + V`` at each output.
    energies: Py<PyArray1<f64>>,
    /// The coordinates at the end.
    x: Py<PyArray1<f64>>,
    /// The velocities at the end.
    v: Py<PyArray1<f64>>,
    /// The time reached.
    time: f64,
    /// Steps taken.
    steps: usize,
    /// The largest relative energy change seen at an output.
    max_energy_error: f64,
}

impl NetworkModel {
    fn coordinates(&self, x: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
        let values = args::finite_floats(x, what)?;
        let n = self.model.dof_count();
        if values.len() != n {
            return Err(value_error(format!(
                "{what} has {} values, the patch has {n} coordinates",
                values.len()
            )));
        }
        Ok(values)
    }
}

/// `springs={p: {"k": ..., "rest_length": ...}}` and `masses={((i, j), node): mass}` applied to
/// the builder (their checks are the builder's).
fn overrides<'p, 'c>(
    mut builder: rotor_chain::network::NetworkModelBuilder<'p, 'c>,
    springs: Option<&Bound<'_, PyDict>>,
    masses: Option<&Bound<'_, PyDict>>,
) -> PyResult<rotor_chain::network::NetworkModelBuilder<'p, 'c>> {
    for (key, value) in springs.into_iter().flat_map(|d| d.iter()) {
        let p: usize =
            key.extract().map_err(|_| value_error("springs: keys are bond indices (ints >= 0)"))?;
        let what = format!("springs[{p}]");
        let d = value.cast::<PyDict>().map_err(|_| value_error(format!("{what} must be a dict")))?;
        for (name, v) in d.iter() {
            let name: String =
                name.extract().map_err(|_| value_error(format!("{what}: keys are strings")))?;
            let v: f64 =
                v.extract().map_err(|_| value_error(format!("{what}['{name}'] must be a number")))?;
            builder = match name.as_str() {
                "k" => builder.spring_constant(p, v),
                "rest_length" => builder.rest_length(p, v),
                other => return Err(value_error(format!("{what}: unknown key '{other}' (k, rest_length)"))),
            };
        }
    }
    for (key, value) in masses.into_iter().flat_map(|d| d.iter()) {
        let ((i, j), node): ((usize, usize), usize) =
            key.extract().map_err(|_| value_error("masses: keys are ((i, j), node) with ints >= 0"))?;
        let mass: f64 = value.extract().map_err(|_| value_error("masses: values are numbers"))?;
        builder = builder.node_mass([i, j], node, mass);
    }
    Ok(builder)
}

#[pymethods]
impl NetworkModel {
    /// A patch of ``cells`` (an int for a 1D cell, a pair for 2D) of ``network`` with
    /// ``boundary`` ``"periodic"`` or ``"free"``; every node of mass ``mass`` (a rotor's inertia
    /// ``mass r^2``), springs of ``law`` ``"harmonic"`` or ``"quartic"``; overrides
    /// ``springs={p: {"k": ..., "rest_length": ...}}`` (``p`` the patch's bond index) and
    /// ``masses={((i, j), node): m}``.
    #[new]
    #[pyo3(signature = (network, cells, *, boundary = "periodic", mass = 1.0, law = "harmonic",
                        springs = None, masses = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        network: &Network,
        cells: &Bound<'_, PyAny>,
        boundary: &str,
        mass: f64,
        law: &str,
        springs: Option<&Bound<'_, PyDict>>,
        masses: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let cell = network.cell();
        let cells = cells_of(cell, cells)?;
        let boundary = boundary_of(boundary)?;
        let law = choice("law", law, &[("harmonic", Law::Harmonic), ("quartic", Law::Quartic)])?;
        let patch = Patch::new(cell, cells, boundary).map_err(|e| errors::network(py, &e))?;
        let builder = overrides(Model::builder(&patch).law(law).mass(mass), springs, masses)?;
        let model = builder.build().map_err(|e| errors::network(py, &e))?;
        Ok(Self { model })
    }

    /// The number of coordinates.
    #[getter]
    fn dof(&self) -> usize {
        self.model.dof_count()
    }

    /// The number of springs (the patch's bonds).
    #[getter]
    fn spring_count(&self) -> usize {
        rotor_chain::SpringNetwork::spring_count(&self.model)
    }

    /// The patch as drawn by the cell: its stress-free reference coordinates.
    fn reference(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array(py, self.model.reference())
    }

    /// The inertia of each coordinate (a joint's mass for its ``x`` and ``y``, ``M r^2`` a
    /// rotor's).
    fn inertia(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array(py, (0..self.model.dof_count()).map(|i| self.model.inertia(i)).collect())
    }

    /// The elastic energy at ``x``.
    fn energy(&self, x: &Bound<'_, PyAny>) -> PyResult<f64> {
        Ok(self.model.energy(&self.coordinates(x, "x")?))
    }

    /// The gradient ``dV/dx`` (minus the forces) at ``x``.
    fn gradient(&self, py: Python<'_>, x: &Bound<'_, PyAny>) -> PyResult<Py<PyArray1<f64>>> {
        let x = self.coordinates(x, "x")?;
        Ok(array(py, py.detach(|| self.model.gradient(&x))))
    }

    /// Dissipative dynamics from rest at ``x`` until every force is below ``tolerance ||K||``:
    /// ``(x, steps)``.
    #[pyo3(signature = (x, *, tolerance = 1e-8, max_steps = 20000))]
    fn relax<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        tolerance: f64,
        max_steps: usize,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let x = self.coordinates(x, "x")?;
        let options = RelaxOptions { tolerance, max_steps, ..RelaxOptions::default() };
        let (x, steps) =
            py.detach(|| relax(&self.model, &x, &options)).map_err(|e| errors::statics(py, &e))?;
        PyTuple::new(py, [array(py, x).into_any(), steps.into_pyobject(py)?.into_any().unbind()])
    }

    /// Newton's method from ``x`` to the nearest equilibrium (of any index), its near-null
    /// directions (rigid motions, floppy modes) left alone, then polished to the rounding of
    /// the forces; the sparse stiffness beyond a few hundred coordinates.
    #[pyo3(signature = (x, *, tolerance = 1e-11, max_iterations = 60))]
    fn newton(
        &self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        tolerance: f64,
        max_iterations: usize,
    ) -> PyResult<Py<PyArray1<f64>>> {
        let x = self.coordinates(x, "x")?;
        let options = NewtonOptions { tolerance, max_iterations, ..NewtonOptions::default() };
        let solution = py
            .detach(|| newton(&self.model, &x, &options).and_then(|s| polish(&self.model, s, &options)))
            .map_err(|e| errors::statics(py, &e))?;
        Ok(array(py, solution.theta))
    }

    /// The lowest ``count`` modes about ``x`` (``K v = omega^2 M v``), ascending.
    #[pyo3(signature = (x, count = 12))]
    fn modes(&self, py: Python<'_>, x: &Bound<'_, PyAny>, count: usize) -> PyResult<NetworkModes> {
        let x = self.coordinates(x, "x")?;
        let options = ModeOptions { count: Some(count), ..ModeOptions::default() };
        let modes =
            py.detach(|| normal_modes(&self.model, &x, &options)).map_err(|e| errors::statics(py, &e))?;
        let n = self.model.dof_count();
        // The vectors' copy for numpy is sized by `count` x dof: allocated fallibly.
        let mut vectors =
            try_vec(modes.len().saturating_mul(n), "the network modes' vectors").map_err(memory_error)?;
        for m in &modes {
            vectors.extend_from_slice(&m.shape);
        }
        Ok(NetworkModes {
            frequencies: array(py, modes.iter().map(|m| m.frequency).collect()),
            omega_squared: array(py, modes.iter().map(|m| m.omega_squared).collect()),
            vectors: matrix(py, modes.len(), n, vectors),
            participation: array(py, modes.iter().map(|m| m.participation).collect()),
        })
    }

    /// The Maxwell-Calladine count at ``x`` (a ``Counting``; ``rotors`` are the coordinates):
    /// zero modes and states of self-stress with their orthonormal bases. Up to 512 coordinates
    /// and bonds by a dense SVD, beyond by inertia counts of the sparse Gram matrices and
    /// subspace iteration (docs/guarantees.md); Ctrl-C stops it and raises ``KeyboardInterrupt``.
    #[pyo3(signature = (x, tolerance = None))]
    fn maxwell_calladine(
        &self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        tolerance: Option<f64>,
    ) -> PyResult<crate::statics::Counting> {
        let x = self.coordinates(x, "x")?;
        crate::statics::count(py, &self.model, &x, tolerance)
    }

    /// Velocity Verlet from ``(x, v)`` at time 0 to ``t_max``, an output every ``output_every``
    /// steps; ``dt`` defaults to a tenth of the stability bound at ``x``, ``damping`` is the
    /// viscous rate. Ctrl-C stops the run at its next output and raises ``KeyboardInterrupt``.
    #[pyo3(signature = (x, v, *, t_max, dt = None, output_every = 100, damping = 0.0, energy_limit = 0.1))]
    #[allow(clippy::too_many_arguments)]
    fn propagate(
        &self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        v: &Bound<'_, PyAny>,
        t_max: f64,
        dt: Option<f64>,
        output_every: usize,
        damping: f64,
        energy_limit: f64,
    ) -> PyResult<NetworkRun> {
        let (x, v) = (self.coordinates(x, "x")?, self.coordinates(v, "v")?);
        let mut options = match dt {
            Some(dt) => VerletOptions::new(dt),
            None => VerletOptions::stable_for(&self.model, &x, VerletOptions::DEFAULT_SAFETY)
                .map_err(|e| errors::integrate(py, &e))?,
        };
        options.damping = damping;
        options.energy_limit = energy_limit;
        let mut state = State { time: 0.0, theta: x, omega: v };
        // The outputs' count is sized by the caller (t_max, dt, output_every): their arrays are
        // reserved fallibly up front (a MemoryError with the bytes, not an abort), and grown
        // fallibly should the run give more outputs than t_max / dt / output_every + 2.
        const WHAT: &str = "the run's output times and energies";
        let outputs = (t_max / options.dt / output_every.max(1) as f64).ceil();
        let outputs =
            if outputs.is_finite() && outputs >= 0.0 { outputs.min(usize::MAX as f64) as usize } else { 0 };
        let outputs = outputs.saturating_add(2);
        let mut times = try_vec(outputs, WHAT).map_err(memory_error)?;
        let mut energies = try_vec(outputs, WHAT).map_err(memory_error)?;
        let mut out_of_memory = None;
        let mut interrupt = Interrupt::default();
        let report = py
            .detach(|| {
                verlet(&self.model, &mut state, t_max, &options, output_every, &mut |s: &State| {
                    if times.len() == times.capacity() {
                        let more = times.len().max(16);
                        let grown = try_grow(&mut times, more, WHAT)
                            .and_then(|()| try_grow(&mut energies, more, WHAT));
                        if let Err(e) = grown {
                            out_of_memory = Some(e);
                            return Flow::Stop;
                        }
                    }
                    times.push(s.time);
                    energies.push(
                        self.model.energy(&s.theta)
                            + rotor_chain::integrate::kinetic_energy(&self.model, &s.omega),
                    );
                    if interrupt.pending() { Flow::Stop } else { Flow::Continue }
                })
            })
            .map_err(|e| errors::integrate(py, &e))?;
        if let Some(e) = out_of_memory {
            return Err(memory_error(e));
        }
        interrupt.raise()?;
        Ok(NetworkRun {
            times: array(py, times),
            energies: array(py, energies),
            time: state.time,
            x: array(py, state.theta),
            v: array(py, state.omega),
            steps: report.steps,
            max_energy_error: report.max_energy_error,
        })
    }

    fn __repr__(&self) -> String {
        format!("NetworkModel(dof={})", self.model.dof_count())
    }
}
