"""rotor_chain: topological mechanical rotor chains, from Python.

The paper *Kink-antikink asymmetry and impurity interactions in topological mechanical chains*
(Zhou, Chen, Upadhyaya, Vitelli), computed by the Rust library ``rotor-chain`` through PyO3:

>>> import numpy as np, rotor_chain as rc
>>> chain = rc.Chain(60, 0.8, 1e4, 0.58)          # n, r, k, theta_bar (r = 0.8 a; a = 1)
>>> theta = chain.kink(29.5)                       # the zero-energy kink (radians)
>>> bool(chain.energy(theta) < 1e-20)
True
>>> pn = chain.peierls_nabarro()                   # antikink minimum, saddle, barrier
>>> round(pn.barrier, 3)
0.668

- :class:`Chain`: energy, gradient, tangent stiffness, Hessian, spring lengths, tensions,
  compatibility, branch solve; statics (``kink``, ``antikink``, ``peierls_nabarro``, ``modes``,
  ``maxwell_calladine``) and dynamics (``launch``, ``propagate``, ``scatter``) as methods.
- :mod:`rotor_chain.sweep`: scattering phase diagrams (Fig. ``fig:phasediagram``) on one machine
  or a Dask cluster, resumable CSV files shared with the ``phase-diagram`` command.
- :mod:`rotor_chain.plot`: pictures with matplotlib (a phase diagram, a chain, a run's space-time
  image, a mode).
- :class:`Network`: periodic spring and rotor networks (issue 33) from a cell file, TOML text,
  keyword arguments or a ready lattice: Maxwell-Calladine counts, zero modes, Bloch matrices,
  bands, winding numbers and the polarization, strips with edge modes, Guest modes.
- :class:`NetworkModel`: a finite patch of a network in motion (issue 36): energy, gradient,
  relaxation, Newton, the lowest modes (sparse stiffness for large patches), Verlet.
- :mod:`rotor_chain.errors`: the exceptions, one class per Rust error family.

Units: every number is absolute, in the units of the parameters given; nothing is divided by
``a`` or ``k``. Angles are in radians, lengths in the length unit of ``a`` and ``r``, energies in
the unit of ``k`` times that length unit squared (the barrier above is 0.668 for ``k = 1e4``,
``a = 1``: ``6.7e-5 k a^2``), time in the unit ``t`` of the paper's Appendix B (``M = 1``, ``k`` in
``M/t^2``). Arrays are numpy ``float64``. Long computations release the GIL, so threads run them
in parallel. Results pickle (multiprocessing, Dask).
"""

from . import errors, plot, sweep
from ._native import (
    Antikink,
    Chain,
    Continuum,
    Counting,
    Launch,
    Modes,
    Network,
    NetworkModel,
    NetworkModes,
    NetworkRun,
    PeierlsNabarro,
    Run,
    Scattering,
    __version__,
    domain_walls,
)
from .errors import (
    BranchError,
    CellError,
    ConfigError,
    DynamicsError,
    GridError,
    IntegrateError,
    InvalidOptionError,
    NetworkError,
    ParameterError,
    PointError,
    RotorChainError,
    StaticsError,
    SweepError,
)

__all__ = [
    "Chain",
    "Continuum",
    "Network",
    "NetworkModel",
    "NetworkModes",
    "NetworkRun",
    "Antikink",
    "PeierlsNabarro",
    "Modes",
    "Counting",
    "Launch",
    "Run",
    "Scattering",
    "domain_walls",
    "sweep",
    "plot",
    "errors",
    "RotorChainError",
    "ParameterError",
    "BranchError",
    "StaticsError",
    "DynamicsError",
    "IntegrateError",
    "ConfigError",
    "PointError",
    "GridError",
    "SweepError",
    "CellError",
    "NetworkError",
    "InvalidOptionError",
    "__version__",
]
