"""Type stubs of the compiled module rotor_chain._native (the Rust half of rotor_chain).

Units: every number is absolute, in the units of the parameters given (nothing is divided by
``a`` or ``k``): angles in radians, lengths in the length unit of ``a`` and ``r``, energies in the
unit of ``k`` times that length unit squared (``Chain(60, 0.8, 1e4, 0.58)``'s Peierls-Nabarro
minimum is 1392.03, that is 0.139 ``k a^2``), time in the unit ``t`` of the paper's Appendix B
(``k`` in ``M / t^2``), speeds in length per ``t``, frequencies in ``1/t``.

Every class but ``ResultsFile`` (an open, locked file) pickles.
"""

from __future__ import annotations

from os import PathLike
from typing import Any, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
ArrayLike = Union[npt.ArrayLike, Sequence[float]]
Defect = Literal["kink", "antikink"]
WallCharge = Literal["kink", "antikink"]
Wall = Tuple[float, WallCharge]
Record = Dict[str, Any]

__version__: str
DEFAULT_ENERGY_TOLERANCE: float
MAX_AXIS_COUNT: int
MAX_GRID_POINTS: int

class Chain:
    """A rotor chain of runtime size (see ``help(rotor_chain.Chain)``): ``n`` rotors (at least 2)
    of length ``r`` on pivots ``a`` apart, tips of mass ``mass`` joined by springs of stiffness
    ``k`` that rest where every rotor stands at ``theta_bar`` or ``-theta_bar``. ``r`` and ``a``
    are lengths in one unit (``r`` is the paper's ``r/a`` only when ``a = 1``, the default);
    ``k`` is an energy per length squared; ``theta_bar`` is in radians, with
    ``2 r sin(theta_bar) < a``."""

    def __init__(
        self,
        n: int,
        r: float,
        k: float,
        theta_bar: float,
        *,
        a: float = 1.0,
        mass: float = 1.0,
        law: Literal["harmonic", "quartic"] = "harmonic",
        springs: Optional[Mapping[int, Mapping[str, float]]] = None,
        rotors: Optional[Mapping[int, float]] = None,
    ) -> None: ...
    @property
    def n_rotors(self) -> int: ...
    @property
    def n_springs(self) -> int: ...
    @property
    def a(self) -> float: ...
    @property
    def theta_bar(self) -> float: ...
    @property
    def mass(self) -> float: ...
    @property
    def law(self) -> str: ...
    @property
    def rotor_lengths(self) -> Array: ...
    @property
    def stiffness(self) -> Array: ...
    @property
    def rest_lengths(self) -> Array: ...
    @property
    def inertia(self) -> Array: ...
    def energy(self, theta: ArrayLike) -> float:
        """Potential energy ``V``: absolute, in the unit of ``k`` times the length unit squared."""
    def gradient(self, theta: ArrayLike) -> Array:
        """``dV/dtheta_i``, length ``n``."""
    def energy_and_gradient(self, theta: ArrayLike) -> Tuple[float, Array]: ...
    def tangent_stiffness(self, theta: ArrayLike) -> Tuple[Array, Array]:
        """``(diag, off)``: lengths ``n`` and ``n - 1``; ``off[p]`` is entry ``(p, p + 1)``."""
    def material_stiffness(self, theta: ArrayLike) -> Tuple[Array, Array]: ...
    def stress_matrix(self, theta: ArrayLike) -> Tuple[Array, Array]: ...
    def hessian(self, theta: ArrayLike) -> Array:
        """The tangent stiffness as a dense ``n x n`` array.

        Raises ``StaticsError`` (``variant == "TooLarge"``, with ``what``, ``value``, ``max``)
        when ``n^2`` passes the bound on dense results, 2**26 values."""
    def spring_lengths(self, theta: ArrayLike) -> Array: ...
    def tensions(self, theta: ArrayLike) -> Array: ...
    def compatibility(self, theta: ArrayLike, *, dense: bool = False) -> Any:
        """``(left, right)`` bands, or with ``dense=True`` the ``(n - 1) x n`` array.

        Raises ``StaticsError`` (``variant == "TooLarge"``) when the dense array's ``n (n - 1)``
        values pass the bound on dense results, 2**26."""
    def next_angles(self, p: int, theta_p: float) -> Tuple[float, float]: ...
    def previous_angles(self, p: int, theta_next: float) -> Tuple[float, float]: ...
    def uniform(self, sign: int = 1) -> Array: ...
    def continuum(self) -> Continuum: ...
    def kink(self, centre: float) -> Array: ...
    def antikink(
        self, centre: Optional[float] = None, *, relaxed: bool = True, ends: Literal["held", "free"] = "held"
    ) -> Antikink: ...
    def peierls_nabarro(self, *, ends: Literal["held", "free"] = "held") -> PeierlsNabarro: ...
    def modes(self, theta: ArrayLike, count: Optional[int] = 12, *, hold_ends: bool = False) -> Modes: ...
    def maxwell_calladine(self, theta: ArrayLike, tolerance: Optional[float] = None) -> Counting: ...
    def launch(
        self, defect: Defect, position: float, v0: float, direction: Literal["left", "right"] = "left"
    ) -> Launch: ...
    def propagate(
        self,
        theta: ArrayLike,
        omega: ArrayLike,
        *,
        t_max: float = 20.0,
        output_interval: float = 0.01,
        method: Literal["verlet", "dop853"] = "verlet",
        dt: Optional[float] = None,
        rtol: Optional[float] = None,
        atol: Optional[float] = None,
        damping: float = 0.0,
        absorbing_ends: bool = False,
        space_time: bool = False,
        energy_limit: float = 0.1,
    ) -> Run: ...
    def scatter(
        self,
        defect: Defect,
        v0: float,
        impurity: Optional[int] = None,
        *,
        start: Optional[float] = None,
        direction: Literal["left", "right"] = "left",
        t_max: float = 20.0,
        method: Literal["verlet", "dop853"] = "verlet",
        dt: Optional[float] = None,
        absorbing_ends: bool = False,
        space_time: bool = False,
        watch: float = 0.0,
    ) -> Scattering: ...

class Continuum:
    @property
    def antikink_energy(self) -> float: ...
    @property
    def width(self) -> float: ...
    @property
    def sound_speed(self) -> float: ...
    @property
    def rest_length(self) -> float: ...
    @property
    def pn_barrier(self) -> float: ...
    @property
    def l_critical(self) -> float: ...
    @property
    def phonon_band_edges(self) -> Tuple[float, float]: ...
    def angle_profile(self, defect: Defect, n: int, x0: float) -> Array: ...

class Antikink:
    theta: Array
    energy: float
    centre: float
    index: int
    nullity: int
    kind: Literal["minimum", "degenerate-minimum", "saddle"]
    residual: float
    edge_force: float
    held: int
    newton_iterations: int
    relax_steps: int
    @property
    def is_saddle(self) -> bool: ...

class PeierlsNabarro:
    minimum: Optional[Antikink]
    saddle: Optional[Antikink]
    rotor_centred: Antikink
    spring_centred: Antikink
    barrier: float
    resolved: bool
    @property
    def minimum_energy(self) -> Optional[float]: ...
    @property
    def saddle_energy(self) -> Optional[float]: ...

class Modes:
    frequencies: Array
    omega_squared: Array
    vectors: Array
    positions: Array
    participation: Array
    kinds: List[Literal["translation", "shape", "edge-left", "edge-right", "extended"]]
    def __len__(self) -> int: ...

class Network:
    """A periodic network's unit cell (``rotor_chain::network``); the file format of issue 33."""
    def __init__(
        self,
        *,
        dimension: int,
        lattice: Sequence[Sequence[float]],
        nodes: Sequence[Mapping[str, Any]],
        bonds: Optional[Sequence[Mapping[str, Any]]] = None,
    ) -> None: ...
    @staticmethod
    def from_string(text: str) -> Network: ...
    @staticmethod
    def from_file(path: Union[str, PathLike[str]]) -> Network: ...
    @staticmethod
    def ready(name: str, *parameters: float) -> Network: ...
    def to_toml(self) -> str: ...
    @property
    def dimension(self) -> int: ...
    @property
    def dof(self) -> int: ...
    @property
    def bond_count(self) -> int: ...
    @property
    def lattice(self) -> Array: ...
    def counts(self, cells: Union[int, Sequence[int]], boundary: Literal["periodic", "free"] = "periodic") -> Dict[str, Any]: ...
    def null_spaces(
        self, cells: Union[int, Sequence[int]], boundary: Literal["periodic", "free"] = "periodic"
    ) -> Tuple[Array, Array]: ...
    def compatibility(self, cells: Union[int, Sequence[int]], boundary: Literal["periodic", "free"] = "free") -> Array: ...
    def bloch(self, theta: Sequence[float]) -> npt.NDArray[np.complex128]: ...
    def frequencies(self, theta: Sequence[float]) -> Array: ...
    def bands(self, path: str = "G-X-M-G", samples: int = 60) -> Tuple[Array, Array]: ...
    def winding(self) -> Dict[str, Any]: ...
    def strip(self, along: int, cells: int, q: float = 2.0) -> Dict[str, Any]: ...
    def guest_modes(self) -> Tuple[int, Array]: ...

class NetworkModel:
    """A finite patch of a network with masses, a spring law and overrides (issue 36)."""
    def __init__(
        self,
        network: Network,
        cells: Union[int, Sequence[int]],
        *,
        boundary: Literal["periodic", "free"] = "periodic",
        mass: float = 1.0,
        law: Literal["harmonic", "quartic"] = "harmonic",
        springs: Optional[Mapping[int, Mapping[str, float]]] = None,
        masses: Optional[Mapping[Tuple[Tuple[int, int], int], float]] = None,
    ) -> None: ...
    @property
    def dof(self) -> int: ...
    @property
    def spring_count(self) -> int: ...
    def reference(self) -> Array: ...
    def inertia(self) -> Array: ...
    def energy(self, x: ArrayLike) -> float: ...
    def gradient(self, x: ArrayLike) -> Array: ...
    def relax(self, x: ArrayLike, *, tolerance: float = 1e-8, max_steps: int = 20000) -> Tuple[Array, int]: ...
    def newton(self, x: ArrayLike, *, tolerance: float = 1e-11, max_iterations: int = 60) -> Array: ...
    def modes(self, x: ArrayLike, count: int = 12) -> NetworkModes: ...
    def maxwell_calladine(self, x: ArrayLike, tolerance: Optional[float] = None) -> Counting: ...
    def propagate(
        self,
        x: ArrayLike,
        v: ArrayLike,
        *,
        t_max: float,
        dt: Optional[float] = None,
        output_every: int = 100,
        damping: float = 0.0,
        energy_limit: float = 0.1,
    ) -> NetworkRun: ...

class NetworkModes:
    """The lowest modes of a patch, ascending in ``omega^2``."""
    frequencies: Array
    omega_squared: Array
    vectors: Array
    participation: Array

class NetworkRun:
    """A Verlet run of a patch."""
    times: Array
    energies: Array
    x: Array
    v: Array
    time: float
    steps: int
    max_energy_error: float

class Counting:
    rotors: int
    springs: int
    singular_values: Array
    tolerance: float
    rank: int
    zero_modes: Array
    self_stresses: Array
    index: int
    @property
    def n_zero_modes(self) -> int: ...
    @property
    def n_self_stresses(self) -> int: ...

class Launch:
    theta: Array
    omega: Array
    mode: Array
    position: float
    defect: Defect

class Run:
    times: Array
    kinetic: Array
    walls: List[List[Wall]]
    wall_counts: IntArray  # (kinks, antikinks) per output, int64
    violations: List[float]
    space_time: Optional[Array]
    time: float
    theta: Array
    omega: Array
    energy_initial: float
    energy_final: float
    max_energy_error: float
    relative_energy_error: float
    steps: int
    rejected: int
    integrator: Literal["verlet", "dop853"]

class Scattering:
    outcome: str
    decided_at: float
    confirmed: bool
    later: Optional[Literal["annihilated", "escaped"]]
    later_at: Optional[float]
    run: Run

def domain_walls(theta: ArrayLike) -> List[Wall]: ...

class PhaseDiagram:
    def __init__(
        self,
        defect: Defect,
        *,
        n: int = 60,
        r: float = 0.8,
        k: float = 1.0e4,
        theta_bar: float = 0.28,
        mass: float = 1.0,
        ends: Literal["free", "absorbing"] = "free",
        integrator: Literal["verlet", "dop853"] = "verlet",
        dt: Optional[float] = None,
        energy_tolerance: float = ...,
        recompute: bool = True,
        t_max: float = 20.0,
        impurity: Optional[int] = None,
        impurity_rest_length: Optional[float] = None,
        start: Optional[float] = None,
        direction: Literal["left", "right"] = "left",
        damping: float = 0.0,
        cross_check: bool = False,
    ) -> None: ...
    @property
    def run_label(self) -> str: ...
    def check_ki(self, ki: float) -> None: ...
    def compute_point(self, ki: float, v0: float) -> Record: ...
    def compute_points(
        self, points: Sequence[Tuple[int, int, float, float]], threads: Optional[int] = None
    ) -> List[Record]: ...

class ResultsFile:
    def __init__(
        self,
        xs: Sequence[float],
        ys: Sequence[float],
        path: Union[str, PathLike[str]],
        run: str,
        *,
        retry_failed: bool = False,
    ) -> None: ...
    def missing(self) -> List[Tuple[int, int]]: ...
    def summary(self) -> Dict[str, Any]: ...
    def append(self, record: Record) -> None: ...
    def close(self) -> None: ...
    def __enter__(self) -> ResultsFile: ...
    def __exit__(self, *args: Any) -> bool: ...

def axis(spec: Union[str, Sequence[float]]) -> List[float]: ...
def check_grid(xs: Sequence[float], ys: Sequence[float]) -> None:
    """GridError unless ``xs`` x ``ys`` is within the limits (``MAX_GRID_POINTS``, ...)."""
def check_threads(threads: int) -> None:
    """ValueError unless ``1 <= threads <= max_threads()``."""
def max_threads() -> int:
    """The most worker threads a sweep starts here: 4 per core."""
def read_points(path: Union[str, PathLike[str]]) -> List[Record]: ...
