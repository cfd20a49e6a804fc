//! The statics of a `Chain` (paper Secs. II-V, VII-A): kink, antikink, Peierls-Nabarro barrier,
//! modes, Maxwell-Calladine counting, domain walls. Each runs with the GIL released.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rotor_chain::statics::antikink::{self as ak, AntikinkOptions, Ends};
use rotor_chain::statics::classify::EquilibriumKind;
use rotor_chain::statics::counting;
use rotor_chain::statics::modes::{self as md, ModeKind, ModeOptions};
use rotor_chain::statics::walls;

use crate::args::{AtMost, array, choice, try_rows};
use crate::chain::Chain;
use crate::dynamics::Interrupt;
use crate::errors;
use crate::pickle::{self, pickle_fields};

fn ends(name: &str) -> PyResult<Ends> {
    choice("ends", name, &[("held", Ends::Held), ("free", Ends::Free)])
}

pub fn kink(chain: &Chain, py: Python<'_>, centre: f64) -> PyResult<Py<PyArray1<f64>>> {
    let theta = py.detach(|| rotor_chain::statics::kink::kink(&chain.chain, centre));
    Ok(array(py, theta.map_err(|e| errors::statics(py, &e))?))
}

/// An antikink equilibrium (see ``Chain.antikink``). Energies are absolute, as ``Chain.energy``
/// (the unit of ``k`` times the length unit squared, not divided by ``k a^2``).
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct Antikink {
    /// The angles (radians).
    theta: Py<PyArray1<f64>>,
    /// Potential energy ``V``.
    energy: f64,
    /// Position of the antikink (Appendix C wall coordinate, in rotor indices).
    centre: f64,
    /// Morse index: eigenvalues of the tangent stiffness below ``-tolerance`` (1 at a saddle).
    index: usize,
    /// Eigenvalues within the tolerance of zero.
    nullity: usize,
    /// ``"minimum"``, ``"degenerate-minimum"`` or ``"saddle"``: the tangent stiffness's
    /// classification (with ``held > 0`` that of a fixed-centring point).
    kind: String,
    /// ``max |dV/dtheta| / ||K||`` at the end (near-null directions held).
    residual: f64,
    /// ``max |dV/dtheta| / ||K||`` over every rotor, held directions and end rotors included: the
    /// force they carry (rounding level when nothing was held; equal to ``residual`` when nothing
    /// held carries more).
    edge_force: f64,
    /// How many soft directions Newton's method held. ``0``: a free equilibrium. Above 0 the
    /// translation was held: the equilibrium at fixed centring (a point of the adiabatic
    /// trajectory), not a free one, ``edge_force`` the force that takes.
    held: usize,
    /// Newton steps of the polish.
    newton_iterations: usize,
    /// Dissipative-relaxation steps (0 when not relaxed).
    relax_steps: usize,
}

#[pymethods]
impl Antikink {
    /// Whether the tangent stiffness shows a saddle.
    #[getter]
    fn is_saddle(&self) -> bool {
        self.kind == "saddle"
    }

    fn __repr__(&self) -> String {
        format!(
            "Antikink(energy={:?}, centre={:?}, kind='{}', index={}{})",
            self.energy,
            self.centre,
            self.kind,
            self.index,
            if self.held > 0 { format!(", held={}", self.held) } else { String::new() }
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

pickle_fields!(Antikink {
    theta,
    energy,
    centre,
    index,
    nullity,
    kind,
    residual,
    edge_force,
    held,
    newton_iterations,
    relax_steps
});

fn antikink_of(py: Python<'_>, a: &ak::Antikink) -> Antikink {
    let kind = match a.classification.kind {
        EquilibriumKind::Minimum => "minimum",
        EquilibriumKind::DegenerateMinimum { .. } => "degenerate-minimum",
        EquilibriumKind::Saddle { .. } => "saddle",
    };
    Antikink {
        theta: array(py, a.theta.clone()),
        energy: a.energy,
        centre: a.centre,
        index: a.classification.index,
        nullity: a.classification.nullity,
        kind: kind.to_owned(),
        residual: a.residual,
        edge_force: a.edge_force,
        held: a.held,
        newton_iterations: a.newton_iterations,
        relax_steps: a.relax_steps,
    }
}

pub fn antikink(
    chain: &Chain,
    py: Python<'_>,
    centre: Option<f64>,
    relaxed: bool,
    ends_name: &str,
) -> PyResult<Antikink> {
    let options = AntikinkOptions { ends: ends(ends_name)?, ..AntikinkOptions::default() };
    let centre = centre.unwrap_or_else(|| rotor_chain::statics::landscape::default_centre(&chain.chain));
    let result = py.detach(|| {
        if relaxed {
            ak::antikink_relaxed(&chain.chain, centre, &options)
        } else {
            ak::antikink_at(&chain.chain, centre, &options)
        }
    });
    Ok(antikink_of(py, &result.map_err(|e| errors::statics(py, &e))?))
}

/// Both antikink equilibria in the middle of the chain and the Peierls-Nabarro barrier
/// between them (paper Sec. V). Energies are absolute, as ``Chain.energy`` (not divided by
/// ``k a^2``).
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct PeierlsNabarro {
    /// The lower-energy centring if it is a minimum (Morse index 0, stayed at its centring);
    /// ``None`` when it is not (a saddle, or an antikink that slid away, as next to a stiff
    /// impurity): there is no minimum at the middle.
    minimum: Option<Py<Antikink>>,
    /// The higher-energy centring if it is a saddle (index at least 1, stayed at its centring),
    /// else ``None``.
    saddle: Option<Py<Antikink>>,
    /// The antikink centred on the middle rotor ``(n - 1) // 2``.
    rotor_centred: Py<Antikink>,
    /// The antikink centred on the spring to its right.
    spring_centred: Py<Antikink>,
    /// ``V_saddle - V_minimum``.
    barrier: f64,
    /// Whether the spectra show exactly one minimum and one saddle of index 1 (for very wide
    /// antikinks the barrier is below what double precision resolves; it is then an upper estimate).
    resolved: bool,
}

#[pymethods]
impl PeierlsNabarro {
    /// ``minimum.energy`` (``None`` without a minimum).
    #[getter]
    fn minimum_energy(&self) -> Option<f64> {
        self.minimum.as_ref().map(|a| a.get().energy)
    }

    /// ``saddle.energy`` (``None`` without a saddle).
    #[getter]
    fn saddle_energy(&self) -> Option<f64> {
        self.saddle.as_ref().map(|a| a.get().energy)
    }

    fn __repr__(&self) -> String {
        format!(
            "PeierlsNabarro(minimum_energy={:?}, saddle_energy={:?}, barrier={:?}, resolved={})",
            PyOption(self.minimum_energy()),
            PyOption(self.saddle_energy()),
            self.barrier,
            if self.resolved { "True" } else { "False" }
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

pickle_fields!(PeierlsNabarro { minimum, saddle, rotor_centred, spring_centred, barrier, resolved });

pub fn peierls_nabarro(chain: &Chain, py: Python<'_>, ends_name: &str) -> PyResult<PeierlsNabarro> {
    let options = AntikinkOptions { ends: ends(ends_name)?, ..AntikinkOptions::default() };
    let pn =
        py.detach(|| ak::peierls_nabarro(&chain.chain, &options)).map_err(|e| errors::statics(py, &e))?;
    let rotor = Py::new(py, antikink_of(py, &pn.rotor_centred))?;
    let spring = Py::new(py, antikink_of(py, &pn.spring_centred))?;
    let pick = |a: Result<&ak::Antikink, _>| {
        a.ok().map(|a| {
            if core::ptr::eq(a, &pn.rotor_centred) { rotor.clone_ref(py) } else { spring.clone_ref(py) }
        })
    };
    let (minimum, saddle) = (pick(pn.minimum()), pick(pn.saddle()));
    Ok(PeierlsNabarro {
        minimum,
        saddle,
        rotor_centred: rotor,
        spring_centred: spring,
        barrier: pn.barrier,
        resolved: pn.resolved,
    })
}

/// An optional number as Python prints it: the number, or `None`.
struct PyOption(Option<f64>);

impl core::fmt::Debug for PyOption {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.0 {
            Some(x) => write!(f, "{x:?}"),
            None => f.write_str("None"),
        }
    }
}

/// Vibrational modes about an equilibrium, ascending in ``omega^2`` (paper Sec. IV):
/// ``K v = omega^2 I v`` with ``I = diag(M r_i^2)``.
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct Modes {
    /// Signed frequencies ``sign(omega^2) sqrt(|omega^2|)`` (``1/t``): negative for a negative
    /// ``omega^2``, an unstable direction (its imaginary frequency ``i sqrt(-omega^2)`` written
    /// with a minus sign), never 0 for one.
    frequencies: Py<PyArray1<f64>>,
    /// The eigenvalues ``omega^2`` (``1/t^2``).
    omega_squared: Py<PyArray1<f64>>,
    /// ``vectors[m]`` is mode ``m``'s angular pattern ``v`` (``count x n``), normalised so
    /// ``sum_i I_i v_i^2 = 1``.
    vectors: Py<PyArray2<f64>>,
    /// Mean position of each mode's weights ``I_i v_i^2`` (rotor index).
    positions: Py<PyArray1<f64>>,
    /// Participation number of each mode: how many rotors take part.
    participation: Py<PyArray1<f64>>,
    /// Where each mode lives: ``"translation"``, ``"shape"``, ``"edge-left"``, ``"edge-right"``
    /// or ``"extended"``.
    kinds: Vec<String>,
}

#[pymethods]
impl Modes {
    fn __len__(&self) -> usize {
        self.kinds.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Modes(count={}, kinds=[{}])",
            self.kinds.len(),
            self.kinds.iter().map(|k| format!("'{k}'")).collect::<Vec<_>>().join(", ")
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

pickle_fields!(Modes { frequencies, omega_squared, vectors, positions, participation, kinds });

pub fn modes(
    chain: &Chain,
    py: Python<'_>,
    theta: &Bound<'_, PyAny>,
    count: Option<AtMost>,
    hold_ends: bool,
) -> PyResult<Modes> {
    let theta = chain.theta(theta)?;
    // `count` is "at most": past the chain's modes it means all of them, so it is clamped to `n`
    // before `ModeOptions.count`'s bound (MAX_DENSE_VALUES) could refuse a large int.
    let n = chain.n();
    let options = ModeOptions { count: count.map(|c| c.0.min(n)), hold_ends, ..ModeOptions::default() };
    // Ctrl-C: the eigensolver asks the interrupt between its iterations and stops.
    let mut interrupt = Interrupt::default();
    let found = py.detach(|| md::modes_with(&chain.chain, &theta, &options, &mut || interrupt.pending()));
    interrupt.raise()?;
    let found = found.map_err(|e| errors::statics(py, &e))?;
    let shapes: Vec<Vec<f64>> = found.iter().map(|m| m.shape.clone()).collect();
    Ok(Modes {
        frequencies: array(py, found.iter().map(|m| m.frequency).collect()),
        omega_squared: array(py, found.iter().map(|m| m.omega_squared).collect()),
        vectors: try_rows(py, &shapes, n, "the modes' vectors")?,
        positions: array(py, found.iter().map(|m| m.position).collect()),
        participation: array(py, found.iter().map(|m| m.participation).collect()),
        kinds: found
            .iter()
            .map(|m| match m.kind {
                ModeKind::Translation => "translation",
                ModeKind::Shape => "shape",
                ModeKind::Edge { left: true } => "edge-left",
                ModeKind::Edge { left: false } => "edge-right",
                ModeKind::Extended => "extended",
                _ => "unlabelled",
            })
            .map(str::to_owned)
            .collect(),
    })
}

/// Maxwell-Calladine counting at one configuration (paper Sec. VII-A).
#[pyclass(frozen, get_all, module = "rotor_chain._native")]
pub struct Counting {
    rotors: usize,
    springs: usize,
    /// Singular values of the compatibility matrix, descending.
    singular_values: Py<PyArray1<f64>>,
    /// Singular values at or below this count as zero.
    tolerance: f64,
    /// Rank of the compatibility matrix.
    rank: usize,
    /// Orthonormal zero modes, one per row (rotor displacements ``r_i dtheta_i``; ``N_zero x n``).
    zero_modes: Py<PyArray2<f64>>,
    /// Orthonormal states of self-stress, one per row (spring tensions; ``N_ss x (n - 1)``).
    self_stresses: Py<PyArray2<f64>>,
    /// ``N_zero - N_selfstress`` (always ``n - (n - 1) = 1``).
    index: isize,
}

#[pymethods]
impl Counting {
    /// Number of zero modes ``N_zero = n - rank``.
    #[getter]
    fn n_zero_modes(&self) -> usize {
        self.rotors - self.rank
    }

    /// Number of states of self-stress ``N_ss = (n - 1) - rank``.
    #[getter]
    fn n_self_stresses(&self) -> usize {
        self.springs - self.rank
    }

    fn __repr__(&self) -> String {
        format!(
            "Counting(rotors={}, springs={}, rank={}, zero_modes={}, self_stresses={})",
            self.rotors,
            self.springs,
            self.rank,
            self.rotors - self.rank,
            self.springs - self.rank
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

pickle_fields!(Counting {
    rotors,
    springs,
    singular_values,
    tolerance,
    rank,
    zero_modes,
    self_stresses,
    index
});

pub fn maxwell_calladine(
    chain: &Chain,
    py: Python<'_>,
    theta: &Bound<'_, PyAny>,
    tolerance: Option<f64>,
) -> PyResult<Counting> {
    let theta = chain.theta(theta)?;
    count(py, &chain.chain, &theta, tolerance)
}

/// The Maxwell-Calladine count of any spring network (a chain, a network patch) at `x`, Ctrl-C
/// answered between the iterations of its eigensolvers.
pub fn count<M: rotor_chain::SpringNetwork + Sync + ?Sized>(
    py: Python<'_>,
    model: &M,
    x: &[f64],
    tolerance: Option<f64>,
) -> PyResult<Counting> {
    let mut interrupt = Interrupt::default();
    let c = py.detach(|| counting::maxwell_calladine_with(model, x, tolerance, &mut || interrupt.pending()));
    interrupt.raise()?;
    let c = c.map_err(|e| errors::statics(py, &e))?;
    Ok(Counting {
        rotors: c.rotors,
        springs: c.springs,
        singular_values: array(py, c.singular_values.clone()),
        tolerance: c.tolerance,
        rank: c.rank,
        zero_modes: try_rows(py, &c.zero_modes, c.rotors, "the zero modes")?,
        self_stresses: try_rows(py, &c.self_stresses, c.springs, "the states of self-stress")?,
        index: c.index(),
    })
}

/// The domain walls of a profile (paper Appendix C): ``[(position, "kink" | "antikink"), ...]``
/// from left to right, positions in rotor indices (the interpolated sign changes of the angles).
#[pyfunction]
pub fn domain_walls(theta: &Bound<'_, PyAny>) -> PyResult<Vec<(f64, &'static str)>> {
    let theta = crate::args::finite_floats(theta, "theta")?;
    Ok(walls::domain_walls(&theta).into_iter().map(|w| (w.position, w.charge.name())).collect())
}
