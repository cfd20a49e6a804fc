"""The exceptions of rotor_chain: one class per error family of the Rust library.

Every exception's message is the Rust error's text. ``variant`` names the Rust variant (for
example ``"OutsideFlipperPhase"``), and every number the variant carries is an attribute and an
entry of ``details``::

    try:
        rotor_chain.Chain(60, 0.8, 1e4, 0.7)
    except rotor_chain.ParameterError as e:
        e.variant            # 'OutsideFlipperPhase'
        e.two_r_sin, e.limit # 1.0306..., 0.6751...

A Rust error that wraps another (a dynamics error caused by a statics error, a phase-diagram point
whose run failed) has the wrapped one as ``details["source"]`` and as ``__cause__``.

=================  ==========================  ===========================================
class              bases                       raised for
=================  ==========================  ===========================================
ParameterError     ValueError                  chain parameters (``Chain(...)``): Rust
                                               ``ParameterError``
BranchError        ValueError                  the branch solve (``next_angles``)
StaticsError       RuntimeError                kink, antikink, modes, counting
DynamicsError      RuntimeError                launch, scattering set-ups
IntegrateError     DynamicsError               integration (``propagate``, ``scatter``)
ConfigError        ValueError                  phase-diagram settings (``sweep``)
PointError         RuntimeError                one phase-diagram point (``sweep.point``)
GridError          ValueError                  an axis ``"FROM:TO:COUNT[:log]"``
SweepError         RuntimeError                a results file (another sweep's, locked, ...)
CellError          ValueError                  a network cell (``Network``): ``key``, ``line``
NetworkError       RuntimeError                a network analysis (``WindingUndefined``, ...)
InvalidOptionError ValueError                  a setting outside its range (``options``,
                                               ``name``, ``value``, ``rule``): raised as
                                               ``StaticsOptionError``, ``DynamicsOptionError``,
                                               ``IntegrateOptionError``, ``ConfigOptionError``,
                                               ``PointOptionError``, ``NetworkOptionError``,
                                               ``GridOptionError`` or ``SweepOptionError``,
                                               each also its family's class
=================  ==========================  ===========================================

All derive from :class:`RotorChainError`. A wrong array length or an unknown option name is a
plain ``ValueError``.
"""

from __future__ import annotations

from typing import Any, Dict, Optional

__all__ = [
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
    "StaticsOptionError",
    "DynamicsOptionError",
    "IntegrateOptionError",
    "ConfigOptionError",
    "PointOptionError",
    "NetworkOptionError",
    "GridOptionError",
    "SweepOptionError",
]


class RotorChainError(Exception):
    """Base of every rotor_chain error: the Rust message, ``variant`` and the numbers."""

    variant: str
    details: Dict[str, Any]

    def __init__(self, message: str, variant: str = "", details: Optional[Dict[str, Any]] = None) -> None:
        super().__init__(message)
        self.message = message
        self.variant = variant
        self.details = dict(details or {})
        for name, value in self.details.items():
            if not hasattr(type(self), name):
                setattr(self, name, value)

    def __reduce__(self):  # picklable, for worker processes
        return (type(self), (self.message, self.variant, self.details))


class ParameterError(RotorChainError, ValueError):
    """A chain parameter outside the model's rules (Rust ``ParameterError``)."""


class BranchError(RotorChainError, ValueError):
    """The branch solve of Appendix A has no root (Rust ``BranchError``)."""


class StaticsError(RotorChainError, RuntimeError):
    """A static analysis could not be carried out (Rust ``StaticsError``)."""


class DynamicsError(RotorChainError, RuntimeError):
    """A dynamics run could not be carried out (Rust ``DynamicsError``)."""


class IntegrateError(DynamicsError):
    """An integration could not start or complete (Rust ``IntegrateError``)."""


class ConfigError(RotorChainError, ValueError):
    """Phase-diagram settings that cannot be computed (Rust ``ConfigError``)."""


class PointError(RotorChainError, RuntimeError):
    """A phase-diagram point without a record (Rust ``PointError``); its message is the text of
    the results file's ``error`` column."""


class GridError(RotorChainError, ValueError):
    """An axis or grid that cannot be built (Rust ``GridError``)."""


class SweepError(RotorChainError, RuntimeError):
    """A results file that cannot be used (Rust ``SweepError``)."""


class CellError(RotorChainError, ValueError):
    """A network cell that cannot be read or is not valid (Rust ``CellError``): ``key`` names the
    key (``bond[2].to``), ``line`` its line in the cell file (None for a cell not read from text)."""


class NetworkError(RotorChainError, RuntimeError):
    """A network analysis that cannot be carried out (Rust ``NetworkError``): ``variant``
    ``WindingUndefined`` or ``WeylPoints`` for a winding that does not exist, ``PatchSize`` for a
    patch that cannot be built, ..."""


class InvalidOptionError(RotorChainError, ValueError):
    """A setting outside its range: a field of a Rust options struct (``RunOptions``,
    ``ScatterSetup``, ``NewtonOptions``, ``PhaseDiagram``, ...) or the keyword argument that set
    it. ``options`` names the struct, ``name`` the field, ``value`` the value given and ``rule``
    what it must be (Rust ``InvalidOption``, checked by ``Validate``). Each family's own class
    below derives from it and from the family's class, so ``except ValueError``,
    ``except InvalidOptionError`` and ``except StaticsError`` (and so on) all catch it."""


class StaticsOptionError(StaticsError, InvalidOptionError):
    """An invalid setting of a static analysis (``NewtonOptions``, ``ModeOptions``, ...)."""


class DynamicsOptionError(DynamicsError, InvalidOptionError):
    """An invalid scattering set-up (``ScatterSetup``, Rust ``InvalidSetup``)."""


class IntegrateOptionError(IntegrateError, InvalidOptionError):
    """An invalid run or integrator setting (``RunOptions``, ``VerletOptions``, ...)."""


class ConfigOptionError(ConfigError, InvalidOptionError):
    """An invalid phase-diagram setting (``PhaseDiagram``)."""


class PointOptionError(PointError, InvalidOptionError):
    """An invalid energy budget of a phase-diagram point (``EnergyBudget``)."""


class NetworkOptionError(NetworkError, InvalidOptionError):
    """An invalid setting of a network analysis (``WindingOptions``, ``Strip``)."""


class GridOptionError(GridError, InvalidOptionError):
    """An invalid grid (``Grid.xs`` or ``Grid.ys``: a count or a value outside its range)."""


class SweepOptionError(SweepError, InvalidOptionError):
    """An invalid sweep setting (``SweepOptions.threads``: 0 or above ``max_threads()``, 4 per
    core); ``max`` and ``cores`` are this machine's bound."""
