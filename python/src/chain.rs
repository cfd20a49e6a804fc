//! `Chain`: a `RuntimeChain`, its evaluation methods, and the entry points of its statics and
//! dynamics; `Continuum`: the continuum theory of the same chain.

use chain_core::geometry::IndexKind;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::{Law, RuntimeChain};

use crate::args::{self, AtMost, Real, RotorCount, array, choice, matrix, memory_error, vector};
use crate::errors::{self, value_error};
use crate::pickle::{self, Pickle};
use rotor_chain::ChainGeometry;
use rotor_chain::Potential;
use rotor_chain::SpringNetwork;
use rotor_chain::Stiffness;
use rotor_chain::allocation::try_filled;

/// How the chain was asked for: kept for `repr`, pickling and the continuum theory.
#[derive(Clone, Debug)]
struct Spec {
    n: usize,
    r: f64,
    k: f64,
    theta_bar: f64,
    a: f64,
    mass: f64,
    law: &'static str,
    springs: Vec<(usize, Option<f64>, Option<f64>)>,
    rotors: Vec<(usize, f64)>,
}

/// A rotor chain of runtime size (paper Sec. II): ``n`` rotors of length ``r`` on pivots a
/// distance ``a`` apart, their tips (mass ``mass`` each) joined by ``n - 1`` springs of stiffness
/// ``k`` whose rest length makes ``theta_i = +theta_bar`` and ``-theta_bar`` the uniform states.
///
/// Units: every number is absolute, in the units of the parameters given; nothing is divided by
/// ``a`` or ``k``. Angles are in radians (from the vertical, alternately measured as in the
/// paper); lengths in the length unit ``a`` and ``r`` are given in; ``k`` is an energy per length
/// squared, so energies are in the unit of ``k`` times that length unit squared (the paper's
/// figures plot ``V / (k a^2)`` instead: ``peierls_nabarro().minimum_energy`` is 1392.03 for
/// ``k = 1e4``, ``a = 1``, that is ``0.139 k a^2``). Time is the unit ``t`` of Appendix B, in
/// which ``k`` is given (``M / t^2``), so with ``a = M = 1`` energies are in ``M a^2 / t^2``.
///
/// Args:
///     n: number of rotors, an int, at least 2.
///     r: rotor length, a length in the unit of ``a`` (the paper's ``r/a`` only when ``a = 1``,
///         the default).
///     k: spring stiffness, an energy per length squared, > 0.
///     theta_bar: equilibrium angle in radians, with ``2 r sin(theta_bar) < a`` (the flipper
///         phase).
///     a: lattice spacing, the distance between pivots (default 1).
///     mass: tip mass ``M`` (default 1); time is in the unit ``t`` with ``k`` in ``M / t^2``.
///     law: ``"harmonic"`` (``k (l - l0)^2 / 2``, the default) or ``"quartic"``
///         (``k (l^2 - l0^2)^2 / (8 l0^2)``).
///     springs: per-spring overrides ``{p: {"k": k_p, "l0": l0_p}}`` (either key may be left out),
///         for example an impurity ``{29: {"k": 0.7e4}}``.
///     rotors: per-rotor lengths ``{i: r_i}``.
///
/// Raises:
///     ParameterError: a parameter outside the model's rules, with the same message and numbers as
///         the Rust ``ParameterError`` (``variant``, and ``n``, ``key``, ``value``, ``theta_bar``, ...).
#[pyclass(frozen, module = "rotor_chain._native")]
pub struct Chain {
    pub(crate) chain: RuntimeChain,
    spec: Spec,
}

impl Chain {
    pub fn n(&self) -> usize {
        self.chain.rotor_count()
    }

    pub fn theta(&self, theta: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
        vector(theta, "theta", self.n())
    }

    /// The chain's time unit relative to the paper's (`k = 1e4`, `M = 1`): `sqrt(1e4 M / k)`.
    pub fn time_unit(&self) -> f64 {
        rotor_chain::dynamics::scatter::paper_time_unit(self.spec.k, self.spec.mass)
    }

    fn springs_of(spec: &Spec) -> Vec<(usize, Option<f64>, Option<f64>)> {
        spec.springs.clone()
    }
}

#[pymethods]
impl Chain {
    #[new]
    #[pyo3(signature = (n, r, k, theta_bar, *, a = Real::of(1.0), mass = Real::of(1.0), law = "harmonic",
                        springs = None, rotors = None),
           text_signature = "(n, r, k, theta_bar, *, a=1.0, mass=1.0, law='harmonic', springs=None, rotors=None)")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        n: RotorCount,
        r: Real,
        k: Real,
        theta_bar: Real,
        a: Real,
        mass: Real,
        law: &str,
        springs: Option<&Bound<'_, PyDict>>,
        rotors: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let n = n.0?;
        let (r, k, theta_bar) = (r.get("r")?, k.get("k")?, theta_bar.get("theta_bar")?);
        let (a, mass) = (a.get("a")?, mass.get("mass")?);
        let (law_name, law) = choice(
            "law",
            law,
            &[("harmonic", ("harmonic", Law::Harmonic)), ("quartic", ("quartic", Law::Quartic))],
        )?;
        let mut spring_list = Vec::new();
        if let Some(springs) = springs {
            for (p, spec) in springs.iter() {
                let p = args::unsigned_index(&p, IndexKind::Spring, n.saturating_sub(1))?;
                let spec = spec.cast_into::<PyDict>().map_err(|_| {
                    value_error(format!("springs[{p}] must be a dict with the keys 'k' and/or 'l0'"))
                })?;
                let (mut kp, mut l0) = (None, None);
                for (key, value) in spec.iter() {
                    let key = key.extract::<String>().map_err(|_| {
                        pyo3::exceptions::PyTypeError::new_err(format!(
                            "springs[{p}]: a key must be 'k' or 'l0', got {}",
                            args::described(&key)
                        ))
                    })?;
                    match key.as_str() {
                        "k" => kp = Some(value.extract::<Real>()?.get(&format!("springs[{p}]['k']"))?),
                        "l0" => l0 = Some(value.extract::<Real>()?.get(&format!("springs[{p}]['l0']"))?),
                        other => {
                            return Err(value_error(format!(
                                "springs[{p}]: unknown key '{other}' (a spring takes 'k' and 'l0')"
                            )));
                        }
                    }
                }
                spring_list.push((p, kp, l0));
            }
        }
        let mut rotor_list = Vec::new();
        if let Some(rotors) = rotors {
            for (i, ri) in rotors.iter() {
                let i = args::unsigned_index(&i, IndexKind::Rotor, n)?;
                rotor_list.push((i, ri.extract::<Real>()?.get(&format!("rotors[{i}]"))?));
            }
        }
        let mut builder = RuntimeChain::builder(n, r, k, theta_bar).lattice_spacing(a).mass(mass).law(law);
        for &(p, kp, l0) in &spring_list {
            builder = builder.spring(p, kp, l0);
        }
        for &(i, ri) in &rotor_list {
            builder = builder.rotor(i, ri);
        }
        let chain = builder.build().map_err(|e| errors::parameter(py, &e))?;
        let spec =
            Spec { n, r, k, theta_bar, a, mass, law: law_name, springs: spring_list, rotors: rotor_list };
        Ok(Self { chain, spec })
    }

    /// Number of rotors ``n``.
    #[getter]
    fn n_rotors(&self) -> usize {
        self.n()
    }

    /// Number of springs ``n - 1``.
    #[getter]
    fn n_springs(&self) -> usize {
        self.chain.spring_count()
    }

    /// Lattice spacing ``a``.
    #[getter]
    fn a(&self) -> f64 {
        self.chain.lattice_spacing()
    }

    /// Equilibrium angle ``theta_bar`` (radians).
    #[getter]
    fn theta_bar(&self) -> f64 {
        self.chain.theta_bar()
    }

    /// Tip mass ``M``.
    #[getter]
    fn mass(&self) -> f64 {
        self.chain.mass()
    }

    /// The spring law: ``"harmonic"`` or ``"quartic"``.
    #[getter]
    fn law(&self) -> &'static str {
        self.spec.law
    }

    /// Rotor lengths ``r_i`` (length ``n``), in the length unit of ``a``.
    #[getter]
    fn rotor_lengths(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array(py, (0..self.n()).map(|i| self.chain.rotor_length(i)).collect())
    }

    /// Spring stiffnesses ``k_p`` (length ``n - 1``).
    #[getter]
    fn stiffness(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array(py, (0..self.chain.spring_count()).map(|p| self.chain.spring_constant(p)).collect())
    }

    /// Spring rest lengths ``l0_p`` (length ``n - 1``), in the length unit of ``a``.
    #[getter]
    fn rest_lengths(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array(py, (0..self.chain.spring_count()).map(|p| self.chain.rest_length(p)).collect())
    }

    /// Moments of inertia ``M r_i^2`` (length ``n``).
    #[getter]
    fn inertia(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array(py, (0..self.n()).map(|i| self.chain.inertia(i)).collect())
    }

    /// Potential energy ``V(theta) = sum_p law(l_p)``: absolute, in the unit of ``k`` times the
    /// length unit squared (not divided by ``k a^2``).
    fn energy(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<f64> {
        let theta = self.theta(theta)?;
        Ok(py.detach(|| self.chain.energy(&theta)))
    }

    /// Gradient ``dV/dtheta_i`` (length ``n``; the torques are its negative): energy per radian,
    /// absolute as ``energy``.
    fn gradient(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<Py<PyArray1<f64>>> {
        let theta = self.theta(theta)?;
        let out = py.detach(|| {
            let mut out = vec![0.0; theta.len()];
            self.chain.gradient_into(&theta, &mut out);
            out
        });
        Ok(array(py, out))
    }

    /// Energy and gradient in one pass: ``(V, dV/dtheta)``.
    fn energy_and_gradient(
        &self,
        py: Python<'_>,
        theta: &Bound<'_, PyAny>,
    ) -> PyResult<(f64, Py<PyArray1<f64>>)> {
        let theta = self.theta(theta)?;
        let (e, out) = py.detach(|| {
            let mut out = vec![0.0; theta.len()];
            let e = self.chain.energy_and_gradient_into(&theta, &mut out);
            (e, out)
        });
        Ok((e, array(py, out)))
    }

    /// The tangent stiffness ``d2V/dtheta_i dtheta_j`` (paper Appendix D), tridiagonal:
    /// ``(diag, off)`` with ``diag`` of length ``n`` and ``off[p]`` the entry ``(p, p + 1)``
    /// (length ``n - 1``); energy per radian squared, absolute as ``energy``.
    fn tangent_stiffness(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<Banded> {
        self.banded(py, theta, |c, t, k| c.tangent_stiffness_into(t, k))
    }

    /// The material part ``sum_p g_p a_p a_p^T`` of the tangent stiffness (Appendix D), as ``(diag, off)``.
    fn material_stiffness(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<Banded> {
        self.banded(py, theta, |c, t, k| c.material_stiffness_into(t, k))
    }

    /// The stress matrix ``sum_p S_p`` (Appendix D), as ``(diag, off)``; material part + stress
    /// matrix = tangent stiffness.
    fn stress_matrix(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<Banded> {
        self.banded(py, theta, |c, t, k| c.stress_matrix_into(t, k))
    }

    /// The tangent stiffness as a dense symmetric ``n x n`` array.
    ///
    /// Raises:
    ///     StaticsError: ``n^2`` past the statics' bound on dense results, 2**26 values
    ///         (``variant == "TooLarge"``, with ``what``, ``value`` and ``max``).
    fn hessian(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<Py<PyArray2<f64>>> {
        let theta = self.theta(theta)?;
        let n = theta.len();
        dense_size(py, "hessian: rotors x rotors", n, n)?;
        // n^2 values (up to 2^26): allocated fallibly, a MemoryError rather than an abort.
        let mut dense = try_filled(n * n, 0.0, "hessian: rotors x rotors").map_err(memory_error)?;
        py.detach(|| {
            let mut values = vec![0.0; 2 * n - 1];
            self.chain.tangent_stiffness_into(&theta, &mut values);
            let (diag, off) = values.split_at(n);
            for i in 0..n {
                dense[i * n + i] = diag[i];
            }
            for p in 0..n - 1 {
                dense[p * n + p + 1] = off[p];
                dense[(p + 1) * n + p] = off[p];
            }
        });
        Ok(matrix(py, n, n, dense))
    }

    /// Spring lengths ``l_p`` (length ``n - 1``), in the length unit of ``a``.
    fn spring_lengths(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<Py<PyArray1<f64>>> {
        self.per_spring(py, theta, |c, t, o| c.spring_lengths_into(t, o))
    }

    /// Spring tensions ``t_p = dlaw/dl`` at the current lengths (length ``n - 1``): the unit of
    /// ``k`` times the length unit (absolute, not divided by ``k a``).
    fn tensions(&self, py: Python<'_>, theta: &Bound<'_, PyAny>) -> PyResult<Py<PyArray1<f64>>> {
        self.per_spring(py, theta, |c, t, o| c.tensions_into(t, o))
    }

    /// The compatibility matrix ``C[p][i] = dl_p / d(r_i theta_i)`` (paper Sec. VII-A): its two
    /// bands ``(left, right)`` with ``left[p] = C[p][p]``, ``right[p] = C[p][p + 1]``, or with
    /// ``dense=True`` the ``(n - 1) x n`` array. Dimensionless.
    ///
    /// Raises:
    ///     StaticsError: with ``dense=True``, ``n (n - 1)`` past the statics' bound on dense
    ///         results, 2**26 values (``variant == "TooLarge"``).
    #[pyo3(signature = (theta, *, dense = false))]
    fn compatibility<'py>(
        &self,
        py: Python<'py>,
        theta: &Bound<'py, PyAny>,
        dense: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let theta = self.theta(theta)?;
        let (n, m) = (self.n(), self.chain.spring_count());
        let (left, right) = py.detach(|| {
            let mut values = vec![0.0; 2 * m];
            self.chain.compatibility_into(&theta, &mut values);
            let right = values.split_off(m);
            (values, right)
        });
        if dense {
            dense_size(py, "compatibility: springs x rotors", m, n)?;
            let mut c = try_filled(m * n, 0.0, "compatibility: springs x rotors").map_err(memory_error)?;
            for p in 0..m {
                c[p * n + p] = left[p];
                c[p * n + p + 1] = right[p];
            }
            Ok(matrix(py, m, n, c).into_bound(py).into_any())
        } else {
            Ok(PyTuple::new(py, [array(py, left), array(py, right)])?.into_any())
        }
    }

    /// Both ``theta_{p+1}`` that put spring ``p`` at its rest length given ``theta_p`` (the branch
    /// solve of Appendix A), flipper branch first.
    ///
    /// Raises:
    ///     ParameterError: no spring ``p`` (``variant == "IndexOutOfRange"``, with ``index`` and
    ///         ``count``).
    ///     BranchError: no real root (``variant == "NoRealRoot"``, with ``distance``, ``min``,
    ///         ``max``, ...), or a non-finite ``theta_p``.
    fn next_angles(&self, py: Python<'_>, p: &Bound<'_, PyAny>, theta_p: Real) -> PyResult<(f64, f64)> {
        let p = args::index(p, IndexKind::Spring, self.chain.spring_count())?;
        let theta_p = theta_p.get("theta_p")?;
        let [a, b] = self.chain.next_angles(p, theta_p).map_err(|e| errors::branch(py, &e))?;
        Ok((a, b))
    }

    /// Both ``theta_p`` that put spring ``p`` at its rest length given ``theta_{p+1}``: the inverse
    /// map. Raises as ``next_angles``.
    fn previous_angles(
        &self,
        py: Python<'_>,
        p: &Bound<'_, PyAny>,
        theta_next: Real,
    ) -> PyResult<(f64, f64)> {
        let p = args::index(p, IndexKind::Spring, self.chain.spring_count())?;
        let theta_next = theta_next.get("theta_next")?;
        let [a, b] = self.chain.previous_angles(p, theta_next).map_err(|e| errors::branch(py, &e))?;
        Ok((a, b))
    }

    /// A uniform state: every rotor at ``sign * theta_bar``.
    #[pyo3(signature = (sign = 1))]
    fn uniform(&self, py: Python<'_>, sign: i32) -> PyResult<Py<PyArray1<f64>>> {
        let s = match sign {
            1 => 1.0,
            -1 => -1.0,
            _ => return Err(value_error(format!("sign must be +1 or -1, got {sign}"))),
        };
        Ok(array(py, vec![s * self.chain.theta_bar(); self.n()]))
    }

    /// The continuum theory of this chain (paper Secs. III-V, App. E) with its uniform ``a``,
    /// ``r``, ``theta_bar``, ``k`` and ``M`` (per-spring and per-rotor overrides are not part of it).
    fn continuum(&self, py: Python<'_>) -> PyResult<Continuum> {
        let s = &self.spec;
        Continuum::new(py, [s.a, s.r, s.theta_bar, s.k, s.mass])
    }

    // --- statics (paper Secs. II-V, VII) -------------------------------------------------------

    /// The zero-energy kink centred at ``centre`` (a rotor index, fractional allowed, in
    /// ``[0, n - 1]``), built outward from its centre by the branch solve: ``+theta_bar`` on the
    /// left, ``-theta_bar`` on the right. Returns the angles (radians). At ``centre = 0`` or
    /// ``n - 1`` the end rotor stands vertical and the chain is one domain (no wall left inside).
    fn kink(&self, py: Python<'_>, centre: Real) -> PyResult<Py<PyArray1<f64>>> {
        crate::statics::kink(self, py, centre.get("centre")?)
    }

    /// An antikink equilibrium (``-theta_bar`` on the left, ``+theta_bar`` on the right).
    ///
    /// With ``relaxed=True`` (default), the paper's construction: the reflected kink near
    /// ``centre`` relaxed by dissipative dynamics and polished by Newton's method: a
    /// Peierls-Nabarro **minimum** in the middle of a chain. Near an end the ends' pull on a wide
    /// antikink (``theta_bar`` about 0.3 and below at ``n = 60``) can beat the barrier; the result
    /// is then a saddle or a fixed-centring point, as ``kind`` and ``held`` say. With
    /// ``relaxed=False``, the equilibrium centred exactly at ``centre`` (an integer: on a rotor; a
    /// half-integer: on a spring; any other centre is a ``StaticsError``), minimum or saddle, or
    /// with ``held > 0`` the equilibrium at that fixed centring.
    /// ``centre`` defaults to the rotor farthest from both ends and from every impurity spring
    /// (the middle rotor of a uniform chain; Rust ``statics::landscape::default_centre``); ``ends`` is ``"held"`` (end rotors held at
    /// ``-theta_bar``, ``+theta_bar``, the default) or ``"free"``.
    ///
    /// Raises:
    ///     StaticsError: no convergence, or the defect was lost (with the numbers).
    #[pyo3(signature = (centre = None, *, relaxed = true, ends = "held"))]
    fn antikink(
        &self,
        py: Python<'_>,
        centre: Option<f64>,
        relaxed: bool,
        ends: &str,
    ) -> PyResult<crate::statics::Antikink> {
        crate::statics::antikink(self, py, centre, relaxed, ends)
    }

    /// The Peierls-Nabarro barrier (paper Sec. V): the antikink centred on the middle rotor and
    /// on the neighbouring spring, which is the minimum and which the saddle, and the barrier
    /// ``V_saddle - V_minimum`` (absolute energies, as ``energy``).
    #[pyo3(signature = (*, ends = "held"))]
    fn peierls_nabarro(&self, py: Python<'_>, ends: &str) -> PyResult<crate::statics::PeierlsNabarro> {
        crate::statics::peierls_nabarro(self, py, ends)
    }

    /// The lowest ``count`` vibrational modes about ``theta`` (``K v = omega^2 I v``, paper
    /// Sec. IV), ascending; ``count=None`` gives all ``n``. Frequencies in ``1/t``.
    #[pyo3(signature = (theta, count = Some(AtMost(12)), *, hold_ends = false),
           text_signature = "($self, theta, count=12, *, hold_ends=False)")]
    fn modes(
        &self,
        py: Python<'_>,
        theta: &Bound<'_, PyAny>,
        count: Option<AtMost>,
        hold_ends: bool,
    ) -> PyResult<crate::statics::Modes> {
        crate::statics::modes(self, py, theta, count, hold_ends)
    }

    /// Maxwell-Calladine counting at ``theta`` (paper Sec. VII-A): the rank of the compatibility
    /// matrix, the zero modes and the states of self-stress; ``N_zero - N_selfstress = 1``.
    /// ``tolerance`` overrides the numerical-rank rule for singular values.
    #[pyo3(signature = (theta, tolerance = None))]
    fn maxwell_calladine(
        &self,
        py: Python<'_>,
        theta: &Bound<'_, PyAny>,
        tolerance: Option<f64>,
    ) -> PyResult<crate::statics::Counting> {
        crate::statics::maxwell_calladine(self, py, theta, tolerance)
    }

    // --- dynamics (paper Secs. V, VI, Appendix B) ----------------------------------------------

    /// A ``defect`` (``"kink"`` or ``"antikink"``) at ``position`` set in motion along its
    /// translation mode with speed amplitude ``v0`` (length per ``t``) towards ``direction``
    /// (``"left"``: rotor 0, or ``"right"``); Appendix B: ``r_i thetadot_i = v0 e_i``, kinetic
    /// energy ``M v0^2 / 2``. An antikink is relaxed from ``position`` (``antikink()``): near an
    /// end the ends push a wide one inward, possibly far (at ``theta_bar = 0.58``, ``n = 60``, a
    /// start at 59 ends at 36), so ``Launch.position`` is the centre actually used.
    #[pyo3(signature = (defect, position, v0, direction = "left"))]
    fn launch(
        &self,
        py: Python<'_>,
        defect: &str,
        position: Real,
        v0: Real,
        direction: &str,
    ) -> PyResult<crate::dynamics::Launch> {
        let (position, v0) = (position.get("position")?, v0.get("v0")?);
        crate::dynamics::launch(self, py, defect, position, v0, direction)
    }

    /// Integrate ``M r_i^2 thetadd_i = -dV/dtheta_i - gamma M r_i^2 thetadot_i`` from ``(theta,
    /// omega)`` at time 0 to ``t_max``, recording at every ``output_interval`` the time, the
    /// kinetic energy and the domain walls (Appendix C). The outputs are evenly spaced, so the
    /// run ends at the first output at or past ``t_max`` (``t_max = 1``, ``output_interval =
    /// 0.3`` ends at 1.2; ``Run.time`` says where). Ctrl-C stops the run at its next output and
    /// raises ``KeyboardInterrupt``.
    ///
    /// Args:
    ///     method: ``"verlet"`` (velocity Verlet) or ``"dop853"`` (adaptive, tolerances ``rtol``
    ///         (default 1e-10) and ``atol`` (1e-11)). Options of the other method are refused
    ///         (``ValueError``), so a setting never goes unused unnoticed.
    ///     dt: Verlet's largest step (default a tenth of the stability limit). Each output
    ///         interval is cut into a whole number of equal steps, each at most ``dt``:
    ///         ``dt = 0.03`` with ``output_interval = 0.01`` steps at 0.01.
    ///     damping: viscous rate ``gamma`` (``1/t``), >= 0.
    ///     absorbing_ends: a damping sponge on the last 10 rotors at each end (rate ``30/t`` at the
    ///         end rotor for ``k = 1e4``, ``mass = 1``; ``30 sqrt(k / (1e4 mass))`` in general, so
    ///         that it absorbs the same in any units).
    ///     space_time: keep the angles at every output (``Run.space_time``; at most 2**27 angles,
    ///         outputs times rotors).
    ///     energy_limit: the run stops with ``IntegrateError`` if the energy changes by more than
    ///         this fraction.
    ///
    /// Raises:
    ///     IntegrateError: a bad option, a non-finite state, a broken energy limit or budget
    ///         (``OutputBudget``, ``StepBudget``, ``SpaceTimeBudget``).
    #[pyo3(signature = (theta, omega, *, t_max = Real::of(20.0), output_interval = Real::of(0.01),
                        method = "verlet", dt = None, rtol = None, atol = None, damping = Real::of(0.0),
                        absorbing_ends = false, space_time = false, energy_limit = Real::of(0.1)),
           text_signature = "($self, theta, omega, *, t_max=20.0, output_interval=0.01, method='verlet', \
                             dt=None, rtol=None, atol=None, damping=0.0, absorbing_ends=False, \
                             space_time=False, energy_limit=0.1)")]
    #[allow(clippy::too_many_arguments)]
    fn propagate(
        &self,
        py: Python<'_>,
        theta: &Bound<'_, PyAny>,
        omega: &Bound<'_, PyAny>,
        t_max: Real,
        output_interval: Real,
        method: &str,
        dt: Option<Real>,
        rtol: Option<Real>,
        atol: Option<Real>,
        damping: Real,
        absorbing_ends: bool,
        space_time: bool,
        energy_limit: Real,
    ) -> PyResult<crate::dynamics::Run> {
        let (t_max, output_interval) = (t_max.get("t_max")?, output_interval.get("output_interval")?);
        let (damping, energy_limit) = (damping.get("damping")?, energy_limit.get("energy_limit")?);
        let dt = Real::optional(dt, "dt")?;
        let (rtol, atol) = (Real::optional(rtol, "rtol")?, Real::optional(atol, "atol")?);
        let theta = self.theta(theta)?;
        let omega = vector(omega, "omega", self.n())?;
        let options = crate::dynamics::run_options(
            t_max,
            output_interval,
            method,
            dt,
            (rtol, atol),
            damping,
            absorbing_ends,
            space_time,
            energy_limit,
            self.time_unit(),
        )?;
        crate::dynamics::propagate(self, py, theta, omega, options)
    }

    /// Scattering of a ``defect`` on the stiffness impurity at spring ``impurity`` (paper
    /// Sec. VI; the chain carries the impurity's stiffness, e.g. ``springs={29: {"k": 7e3}}``):
    /// launched at ``v0`` from 15 sites away (``start`` overrides), run until the outcome is
    /// decided and confirmed, or ``t_max``. Ctrl-C stops the run at its next output and raises
    /// ``KeyboardInterrupt``.
    ///
    /// Units: the outcome rules' windows, the output interval (0.01) and the absorbing ends are
    /// the paper's (``k = 1e4``, ``mass = 1``) in this chain's time unit ``sqrt(1e4 mass / k)``,
    /// so a chain with other ``k`` and ``mass`` gives the paper's outcome at ``v0`` times
    /// ``sqrt(k / (1e4 mass))`` (``v0`` is a tip speed in length per ``t``). ``t_max``, ``dt``
    /// and ``watch`` are in ``t`` as given.
    ///
    /// ``impurity`` defaults to the middle spring ``(n - 1) // 2``; ``direction="left"`` (the
    /// paper's, from the right) or ``"right"``.
    #[pyo3(signature = (defect, v0, impurity = None, *, start = None, direction = "left", t_max = Real::of(20.0),
                        method = "verlet", dt = None, absorbing_ends = false, space_time = false,
                        watch = Real::of(0.0)),
           text_signature = "($self, defect, v0, impurity=None, *, start=None, direction='left', t_max=20.0, \
                             method='verlet', dt=None, absorbing_ends=False, space_time=False, watch=0.0)")]
    #[allow(clippy::too_many_arguments)]
    fn scatter(
        &self,
        py: Python<'_>,
        defect: &str,
        v0: Real,
        impurity: Option<&Bound<'_, PyAny>>,
        start: Option<Real>,
        direction: &str,
        t_max: Real,
        method: &str,
        dt: Option<Real>,
        absorbing_ends: bool,
        space_time: bool,
        watch: Real,
    ) -> PyResult<crate::dynamics::Scattering> {
        let (v0, t_max, watch) = (v0.get("v0")?, t_max.get("t_max")?, watch.get("watch")?);
        let start = Real::optional(start, "start")?;
        let dt = Real::optional(dt, "dt")?;
        let springs = self.chain.spring_count();
        let impurity = match impurity {
            Some(p) => args::index(p, IndexKind::Spring, springs)?,
            None => (self.n() - 1) / 2,
        };
        // The paper's output interval and rules in this chain's time unit; t_max, dt, watch as given.
        let time_unit = self.time_unit();
        let options = crate::dynamics::run_options(
            t_max,
            0.01 * time_unit,
            method,
            dt,
            (None, None),
            0.0,
            absorbing_ends,
            space_time,
            0.1,
            time_unit,
        )?;
        let setup = crate::dynamics::ScatterArgs {
            defect,
            v0,
            impurity,
            start,
            direction,
            watch,
            options,
            time_unit,
        };
        crate::dynamics::scatter(self, py, setup)
    }

    fn __repr__(&self) -> String {
        let s = &self.spec;
        let mut text = format!("Chain(n={}, r={:?}, k={:?}, theta_bar={:?}", s.n, s.r, s.k, s.theta_bar);
        if s.a != 1.0 {
            text += &format!(", a={:?}", s.a);
        }
        if s.mass != 1.0 {
            text += &format!(", mass={:?}", s.mass);
        }
        if s.law != "harmonic" {
            text += &format!(", law={:?}", s.law);
        }
        if !s.springs.is_empty() {
            let items: Vec<String> = Self::springs_of(s)
                .iter()
                .map(|(p, k, l0)| {
                    let mut parts = Vec::new();
                    if let Some(k) = k {
                        parts.push(format!("'k': {k:?}"));
                    }
                    if let Some(l0) = l0 {
                        parts.push(format!("'l0': {l0:?}"));
                    }
                    format!("{p}: {{{}}}", parts.join(", "))
                })
                .collect();
            text += &format!(", springs={{{}}}", items.join(", "));
        }
        if !s.rotors.is_empty() {
            let items: Vec<String> = s.rotors.iter().map(|(i, r)| format!("{i}: {r:?}")).collect();
            text += &format!(", rotors={{{}}}", items.join(", "));
        }
        text + ")"
    }

    /// Pickling (for multiprocessing and Dask): the constructor's arguments.
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let s = &self.spec;
        let args = (s.n, s.r, s.k, s.theta_bar).into_pyobject(py)?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("a", s.a)?;
        kwargs.set_item("mass", s.mass)?;
        kwargs.set_item("law", s.law)?;
        let springs = PyDict::new(py);
        for &(p, k, l0) in &s.springs {
            let d = PyDict::new(py);
            if let Some(k) = k {
                d.set_item("k", k)?;
            }
            if let Some(l0) = l0 {
                d.set_item("l0", l0)?;
            }
            springs.set_item(p, d)?;
        }
        kwargs.set_item("springs", springs)?;
        let rotors = PyDict::new(py);
        for &(i, r) in &s.rotors {
            rotors.set_item(i, r)?;
        }
        kwargs.set_item("rotors", rotors)?;
        Ok((args, kwargs))
    }
}

type Banded = (Py<PyArray1<f64>>, Py<PyArray1<f64>>);

impl Chain {
    fn banded(
        &self,
        py: Python<'_>,
        theta: &Bound<'_, PyAny>,
        f: impl Fn(&RuntimeChain, &[f64], &mut [f64]) + Sync,
    ) -> PyResult<Banded> {
        let theta = self.theta(theta)?;
        let n = theta.len();
        let (diag, off) = py.detach(|| {
            let mut diag = vec![0.0; 2 * n - 1];
            f(&self.chain, &theta, &mut diag);
            let off = diag.split_off(n);
            (diag, off)
        });
        Ok((array(py, diag), array(py, off)))
    }

    fn per_spring(
        &self,
        py: Python<'_>,
        theta: &Bound<'_, PyAny>,
        f: impl Fn(&RuntimeChain, &[f64], &mut [f64]) + Sync,
    ) -> PyResult<Py<PyArray1<f64>>> {
        let theta = self.theta(theta)?;
        let m = self.chain.spring_count();
        let out = py.detach(|| {
            let mut out = vec![0.0; m];
            f(&self.chain, &theta, &mut out);
            out
        });
        Ok(array(py, out))
    }
}

/// The continuum theory of a chain (paper Secs. III-V, Appendix E): closed forms with the chain's
/// ``a``, ``r``, ``theta_bar``, ``k``, ``M``. Get it from ``Chain.continuum()``.
#[pyclass(frozen, module = "rotor_chain._native")]
pub struct Continuum {
    c: ContinuumChain,
    /// `[a, r, theta_bar, k, mass]`, for pickling.
    parameters: [f64; 5],
}

/// The names of `Continuum::parameters`, in order.
const CONTINUUM_PARAMETERS: [&str; 5] = ["a", "r", "theta_bar", "k", "mass"];

impl Continuum {
    fn new(py: Python<'_>, parameters: [f64; 5]) -> PyResult<Self> {
        let [a, r, theta_bar, k, mass] = parameters;
        let c = ContinuumChain::new(a, r, theta_bar, k, mass).map_err(|e| errors::parameter(py, &e))?;
        Ok(Self { c, parameters })
    }
}

/// A continuum pickles as its chain's parameters, checked again when unpickled.
impl Pickle for Continuum {
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let state = PyDict::new(py);
        for (name, value) in CONTINUUM_PARAMETERS.iter().zip(self.parameters) {
            state.set_item(name, value)?;
        }
        Ok(state)
    }

    fn from_state(state: &Bound<'_, PyDict>) -> PyResult<Self> {
        let mut parameters = [0.0; 5];
        for (name, value) in CONTINUUM_PARAMETERS.iter().zip(&mut parameters) {
            *value = args::item(state, "pickled Continuum state", name)?;
        }
        Self::new(state.py(), parameters)
    }
}

#[pymethods]
impl Continuum {
    /// Energy of the static continuum antikink, Eq. (akenergy), absolute as ``Chain.energy``:
    /// ``V = k a^2 (16/3)(r/a)^3 sin^3(theta_bar) / (1 + 4 (r/a)^2 cos^2(theta_bar))`` (1610.2 for
    /// ``k = 1e4``, ``a = 1``, ``r = 0.8``, ``theta_bar = 0.58``; divide by ``k a^2`` for the
    /// paper's Fig. ``fig:akenergy``).
    #[getter]
    fn antikink_energy(&self) -> f64 {
        self.c.antikink_energy()
    }

    /// Wall width ``w = a^2 / (2 r sin theta_bar)`` (Sec. III), in the length unit of ``a``.
    #[getter]
    fn width(&self) -> f64 {
        self.c.width()
    }

    /// Sound speed ``c`` of the continuum: the length unit of ``a`` per ``t``.
    #[getter]
    fn sound_speed(&self) -> f64 {
        self.c.sound_speed()
    }

    /// Rest length ``lbar`` of the springs, in the length unit of ``a``.
    #[getter]
    fn rest_length(&self) -> f64 {
        self.c.rest_length()
    }

    /// Peierls-Nabarro barrier of the continuum estimate (Sec. V), an absolute energy as
    /// ``antikink_energy``.
    #[getter]
    fn pn_barrier(&self) -> f64 {
        self.c.pn_barrier()
    }

    /// ``l_critical`` of a spring-length impurity (Sec. VII-A), in the length unit of ``a``.
    #[getter]
    fn l_critical(&self) -> f64 {
        self.c.l_critical()
    }

    /// Edges ``[omega_min, omega_max]`` of the phonon band about the uniform state (``1/t``).
    #[getter]
    fn phonon_band_edges(&self) -> (f64, f64) {
        let [lo, hi] = self.c.phonon_band_edges();
        (lo, hi)
    }

    /// The continuum angle profile of a wall of ``defect`` at ``x0`` (a length, in the unit of
    /// ``a``) on ``n`` rotors at ``x = i a`` (radians).
    ///
    /// Raises:
    ///     ParameterError: ``n`` not a chain's rotor count (``variant == "TooFewRotors"`` below 2,
    ///         ``"TooManyRotors"`` past ``MAX_ROTORS``).
    ///     ValueError: ``x0`` is not finite.
    fn angle_profile(
        &self,
        py: Python<'_>,
        defect: &str,
        n: RotorCount,
        x0: f64,
    ) -> PyResult<Py<PyArray1<f64>>> {
        let charge = args::charge(defect)?;
        let n = n.0?;
        if !x0.is_finite() {
            return Err(value_error(format!("x0 = {x0} is not finite")));
        }
        let profile =
            py.detach(|| self.c.angle_profile(charge, n, x0)).map_err(|e| errors::parameter(py, &e))?;
        Ok(array(py, profile))
    }

    fn __repr__(&self) -> String {
        let [a, r, theta_bar, k, mass] = self.parameters;
        format!("Continuum(a={a:?}, r={r:?}, theta_bar={theta_bar:?}, k={k:?}, mass={mass:?})")
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<pickle::Reduced<'py>> {
        pickle::reduce(slf)
    }
}

/// A dense ``rows x cols`` result of Python's own (``hessian``, ``compatibility(dense=True)``)
/// within the statics' bound on dense results, [`MAX_DENSE_VALUES`](rotor_chain::statics::MAX_DENSE_VALUES)
/// (2^26 values, 512 MiB): beyond it a ``StaticsError`` (``TooLarge``) before anything is allocated,
/// the same rule as the dense SVD of the counting and the vectors of ``modes``, and the same on
/// every machine (an allocation that merely succeeds can still exhaust the memory when filled).
fn dense_size(py: Python<'_>, what: &'static str, rows: usize, cols: usize) -> PyResult<()> {
    let (value, max) = (rows.saturating_mul(cols), rotor_chain::statics::MAX_DENSE_VALUES);
    if value > max {
        return Err(errors::statics(py, &rotor_chain::statics::StaticsError::TooLarge { what, value, max }));
    }
    Ok(())
}
