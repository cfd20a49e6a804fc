"""Scattering phase diagrams (paper Sec. VI, Fig. ``fig:phasediagram``), on one machine or a Dask
cluster.

Every point is the Rust ``PhaseDiagram::compute_point`` of chain-sweep, the one implementation the
``phase-diagram`` command and the paper reproduction use: a kink or antikink launched at ``v0``
from 15 sites to the right of an impurity spring of stiffness ``k_i = ki * k`` (the middle
spring), followed until its outcome is decided and confirmed, and held to an energy budget
(recomputed with DOP853 above ``energy_tolerance``, or recorded as failed with the numbers).

>>> from rotor_chain import sweep
>>> records = sweep.phase_diagram("antikink", "0.5:1:2", [4.0], out=None)   # doctest: +SKIP
>>> [(r["ki"], r["outcome"]) for r in records]                              # doctest: +SKIP
[(0.5, 'trapped'), (1.0, 'transmitted')]

A *record* is a dict with the columns of the results file: ``i``, ``j`` (grid indices), ``ki``
(``k_i/k``), ``v0``, ``outcome``, ``t_decided``, ``confirmed``, ``later``, ``t_later``,
``kinks_final``, ``antikinks_final``, ``energy_error``, ``integrator``, ``unresolved``,
``unresolved_outcome``, ``t_unresolved`` (``None``, or why the outcome is not the impurity's alone:
``"end-wall-first"`` or ``"integrators-disagree"`` with DOP853's outcome and time, docs/dynamics.md
§6) and ``error`` (``None``, or the message of a point that failed, whose other fields are then
``None``). Times are in the unit
``t`` of Appendix B, speeds in ``a/t``.

With ``out=...`` every point is appended to that CSV file the moment it is known, in the format of
the ``phase-diagram`` command (same first two lines for the same settings): a sweep that is
interrupted (Ctrl-C, a killed kernel) resumes where it stopped when called again, and the command
and this function resume each other's files.
"""

from __future__ import annotations

import math
import operator
import os
import sys
import uuid
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

from . import _native
from ._progress import Progress, progress_bar
from .errors import ConfigError

__all__ = [
    "OUTCOMES",
    "COLUMNS",
    "phase_diagram",
    "point",
    "read_results",
    "outcome_grid",
    "to_dataset",
    "axis",
]

Record = Dict[str, Any]
AxisSpec = Union[str, Sequence[float]]

#: Every outcome, in the order of the paper's regimes then the others (docs/dynamics.md §5).
OUTCOMES: Tuple[str, ...] = (
    "transmitted",
    "reflected",
    "trapped",
    "split",
    "annihilated",
    "disintegrated",
    "pair-creation",
    "undecided",
)

#: The keys of a record, in the order of the results file's columns.
COLUMNS: Tuple[str, ...] = (
    "i",
    "j",
    "ki",
    "v0",
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
    "error",
)

DEFAULT_ENERGY_TOLERANCE: float = _native.DEFAULT_ENERGY_TOLERANCE
#: The most values an axis may have, and the most points a phase diagram may have: the limits of
#: the ``phase-diagram`` command (chain-sweep's ``grid.rs``). A larger grid is refused with
#: :class:`~rotor_chain.GridError` before anything is allocated per point.
MAX_AXIS_COUNT: int = _native.MAX_AXIS_COUNT
MAX_GRID_POINTS: int = _native.MAX_GRID_POINTS


def axis(spec: AxisSpec) -> List[float]:
    """The values of an axis: ``"FROM:TO:COUNT"`` (evenly spaced, both ends included),
    ``"FROM:TO:COUNT:log"`` (evenly spaced in the logarithm), as on the ``phase-diagram``
    command line, or a sequence of finite floats. Raises :class:`~rotor_chain.GridError`."""
    return _native.axis(spec)


def _check_v0(v0: float) -> None:
    if not (v0 >= 0.0 and math.isfinite(v0)):
        raise ConfigError(
            f"invalid v0: every launch speed must be >= 0, got {v0}",
            "Value",
            {"name": "v0", "value": v0, "rule": ">= 0 and finite"},
        )


def _count(name: str, value: Any, minimum: int) -> int:
    """``value`` as an int >= ``minimum``: a ``TypeError`` naming ``name`` for what is not an int
    (a float, a string, a bool), a ``ValueError`` below ``minimum``."""
    if isinstance(value, bool) or not hasattr(type(value), "__index__"):
        raise TypeError(f"{name} must be an int, got {value!r} ({type(value).__name__})")
    value = operator.index(value)
    if value < minimum:
        raise ValueError(f"{name} must be at least {minimum}, got {value}")
    return value


def point(
    defect: str,
    ki: float,
    v0: float,
    *,
    theta_bar: float = 0.28,
    n: int = 60,
    r: float = 0.8,
    k: float = 1.0e4,
    mass: float = 1.0,
    ends: str = "free",
    integrator: str = "verlet",
    dt: Optional[float] = None,
    energy_tolerance: float = DEFAULT_ENERGY_TOLERANCE,
    recompute: bool = True,
    t_max: float = 20.0,
    impurity: Optional[int] = None,
    impurity_rest_length: Optional[float] = None,
    start: Optional[float] = None,
    direction: str = "left",
    damping: float = 0.0,
    cross_check: bool = False,
) -> Record:
    """One point of a phase diagram, as a record (``i = j = 0``). The settings are those of
    :func:`phase_diagram`.

    Raises:
        PointError: the point failed (energy budget, a failed run, rotors spun through pi), with
            the numbers (``variant``, ``error``, ``tolerance``, ``time``, ...).
        ConfigError: invalid settings, ``ki`` or ``v0`` (as :func:`phase_diagram` raises them).
    """
    d = _native.PhaseDiagram(
        defect,
        n=n,
        r=r,
        k=k,
        theta_bar=theta_bar,
        mass=mass,
        ends=ends,
        integrator=integrator,
        dt=dt,
        energy_tolerance=energy_tolerance,
        recompute=recompute,
        t_max=t_max,
        impurity=impurity,
        impurity_rest_length=impurity_rest_length,
        start=start,
        direction=direction,
        damping=damping,
        cross_check=cross_check,
    )
    d.check_ki(ki)
    _check_v0(v0)
    return d.compute_point(ki, v0)


def phase_diagram(
    defect: str,
    ki: AxisSpec,
    v0: AxisSpec,
    *,
    theta_bar: float = 0.28,
    n: int = 60,
    r: float = 0.8,
    k: float = 1.0e4,
    mass: float = 1.0,
    ends: str = "free",
    integrator: str = "verlet",
    dt: Optional[float] = None,
    energy_tolerance: float = DEFAULT_ENERGY_TOLERANCE,
    recompute: bool = True,
    t_max: float = 20.0,
    impurity: Optional[int] = None,
    impurity_rest_length: Optional[float] = None,
    start: Optional[float] = None,
    direction: str = "left",
    damping: float = 0.0,
    cross_check: bool = False,
    out: Union[None, str, "os.PathLike[str]"] = None,
    client: Any = None,
    threads: Optional[int] = None,
    chunk_size: Optional[int] = None,
    retry_failed: bool = False,
    progress: Progress = None,
    max_resubmits: int = 3,
) -> List[Record]:
    """The scattering phase diagram of ``defect`` over ``ki`` (``k_i/k``) x ``v0``, as records in
    grid order (``ki`` outer, ``v0`` inner).

    Args:
        defect: ``"kink"`` or ``"antikink"``.
        ki: impurity stiffness ratios ``k_i/k`` (every value > 0): ``"0.01:3:40:log"``,
            ``"0.1:1:10"`` or a sequence of floats.
        v0: launch speeds (``a/t``, every value >= 0), likewise.
        theta_bar, n, r, k, mass: the chain (paper Sec. VI: 0.28, 60, 0.8, 1e4, 1), as
            ``rotor_chain.Chain`` takes them with the lattice spacing ``a = 1`` (so ``r`` is the
            paper's ``r/a``); ``n`` must hold the experiment, the defect starting 15.5 sites
            right of the middle spring (``n >= 38``; shorter: ``ConfigError`` with
            ``variant == "Experiment"``).
        ends: ``"free"`` (the paper's) or ``"absorbing"`` (a damping sponge at each end).
        integrator: ``"verlet"`` (default; recomputed with DOP853 over the energy budget) or
            ``"dop853"``.
        dt: Verlet's largest step (default a tenth of its stability limit): each output interval
            is cut into equal steps of at most ``dt``.
        energy_tolerance: the largest relative energy error of a point (default 5e-3).
        recompute: recompute a point over budget with DOP853 (else it is recorded as failed).
        t_max: the end of each run (``t``, as given). The outcome rules' windows, the output
            interval and the absorbing ends are the paper's in the chain's time unit
            ``sqrt(1e4 mass / k)``: with other ``k`` and ``mass`` the same diagram shows at
            ``v0`` and ``t_max`` scaled by ``sqrt(k / (1e4 mass))`` and its inverse.
        impurity, impurity_rest_length, start, direction, damping: the experiment, as the
            ``phase-diagram`` command's ``--impurity`` (the impurity spring; default the middle
            one), ``--impurity-rest-length`` (its rest length ``l0`` in ``a``; default the
            chain's), ``--start`` (the defect's start site; default 15 sites from the impurity),
            ``--direction`` (``"left"``, the paper's, or ``"right"``) and ``--damping`` (every
            rotor's damping rate in ``1/t``; default 0) take them.
        cross_check: run every point with DOP853 as well and mark it unresolved
            (``"integrators-disagree"``) where the integrators decide differently; 6 times the
            cost of a point (``--cross-check``). Points where a wall from a free end reached the
            impurity before the decision are marked ``"end-wall-first"`` either way.
        out: a results file (CSV): created, or resumed if it holds part of this sweep (then only
            the missing points are computed, and the records returned are all of the file's).
        client: a ``dask.distributed.Client``: the points are computed in chunks on its workers
            and gathered here (and appended to ``out`` here). A chunk whose worker dies is computed
            again; the others are kept.
        threads: without ``client``, the threads computing points (an int >= 1, default: every
            core; never more are started than a chunk has points).
        chunk_size: points per chunk (an int >= 1; default: about 8 chunks per worker thread with
            ``client``, ``8 x threads`` without).
        retry_failed: compute again the points ``out`` records as failed.
        progress: a progress bar (``tqdm.auto``: a widget in Jupyter, text in a terminal)
            where someone watches (``None``, the default: stderr is a terminal or a Jupyter
            kernel's), always (``True``) or never (``False``); a callable is called as
            ``progress(done, total)`` after each chunk instead. Without tqdm installed there is
            no bar, only a ``done/total`` line on stderr where the bar would be.
        max_resubmits: how often a chunk is submitted again after Dask gave up on it
            (``KilledWorker``: it killed its worker each time it ran); after that its points are
            recorded as failed with the reason (an int >= 0).

    Raises:
        ConfigError, GridError: invalid settings or axes, or a grid of more than
            ``MAX_GRID_POINTS`` points (``GridError`` with ``variant == "TooLarge"``, ``nx``,
            ``ny``), the ``phase-diagram`` command's limit: refused before anything is
            allocated per point, computed or written. A ``t_max`` whose runs would need more
            outputs than a run allows (``t_max=1e9``: 1e11 outputs every 0.01 against 1e6) is
            ``ConfigError`` with ``variant == "OutputBudget"``, ``t_max``, ``output_interval``,
            ``outputs`` and ``budget``.
        SweepError: ``out`` belongs to another sweep (another grid or settings), is locked by a
            running sweep, or cannot be written.
        TypeError, ValueError: ``threads``, ``chunk_size`` or ``max_resubmits`` not an int (a
            bool, a float, a string) or below its minimum; ``client`` not a Dask client; a
            setting of the wrong type (``n`` a float or a bool, ``"0.28"`` for a number). Each
            names the argument.
    """
    settings: Dict[str, Any] = dict(
        defect=defect,
        n=n,
        r=r,
        k=k,
        theta_bar=theta_bar,
        mass=mass,
        ends=ends,
        integrator=integrator,
        dt=dt,
        energy_tolerance=energy_tolerance,
        recompute=recompute,
        t_max=t_max,
        impurity=impurity,
        impurity_rest_length=impurity_rest_length,
        start=start,
        direction=direction,
        damping=damping,
        cross_check=cross_check,
    )
    d = _native.PhaseDiagram(**settings)  # checks them all: ConfigError or ValueError
    xs, ys = _native.axis(ki), _native.axis(v0)  # at most MAX_AXIS_COUNT values each
    _native.check_grid(xs, ys)  # before any list of points: GridError past MAX_GRID_POINTS
    for x in xs:
        d.check_ki(x)
    for y in ys:
        _check_v0(y)
    threads = None if threads is None else _count("threads", threads, 1)
    if threads is not None:
        _native.check_threads(threads)  # ValueError above max_threads(): 4 per core
    chunk_size = None if chunk_size is None else _count("chunk_size", chunk_size, 1)
    max_resubmits = _count("max_resubmits", max_resubmits, 0)
    if client is not None and not all(callable(getattr(client, m, None)) for m in ("submit", "nthreads")):
        raise TypeError(f"client must be a dask.distributed.Client (or None), got {type(client).__name__}")

    file = None
    if out is not None:
        file = _native.ResultsFile(xs, ys, os.fspath(out), d.run_label, retry_failed=retry_failed)
        points = [(i, j, xs[i], ys[j]) for i, j in file.missing()]
    else:
        points = [(i, j, x, y) for i, x in enumerate(xs) for j, y in enumerate(ys)]
    records: List[Record] = []
    written = 0

    def sink(record: Record) -> None:
        nonlocal written
        if file is not None:
            file.append(record)
        else:
            records.append(record)
        written += 1

    try:
        # The bar is closed (where it stopped) before a Ctrl-C's message below.
        with progress_bar(progress, len(points), f"{defect} phase diagram") as report:
            if client is None:
                _run_local(d, points, threads, chunk_size, sink, report)
            else:
                _run_dask(client, settings, points, chunk_size, sink, report, max_resubmits)
    except KeyboardInterrupt:
        # Say what was kept before Python's traceback.
        total = len(xs) * len(ys)
        if file is not None:
            saved = total - len(points) + written
            sys.stderr.write(
                f"\n{defect} phase diagram interrupted: {saved} of the {total} points are in {os.fspath(out)}; "
                f"call phase_diagram again with the same arguments to compute the other {total - saved}\n"
            )
        else:
            sys.stderr.write(
                f"\n{defect} phase diagram interrupted: the {written} points computed are not kept "
                "(give out=... to keep every point as it is computed, and resume from it)\n"
            )
        raise
    finally:
        if file is not None:
            file.close()
    if out is not None:
        return read_results(out)
    return sorted(records, key=lambda r: (r["i"], r["j"]))


def read_results(path: Union[str, "os.PathLike[str]"]) -> List[Record]:
    """Every point of a results file (of :func:`phase_diagram`, the ``phase-diagram`` command or
    ``phase-diagram merge``) as records in grid order, failed points included."""
    return sorted(_native.read_points(os.fspath(path)), key=lambda r: (r["i"], r["j"]))


def outcome_grid(records: Iterable[Record]):
    """``(ki, v0, outcomes)`` for plotting: the sorted axis values and a 2-D numpy array of
    outcome names, ``outcomes[j, i]`` at ``v0[j]``, ``ki[i]`` (``"failed"`` for a failed point,
    ``""`` for a point not in ``records``).

    Raises:
        GridError: the records span more than ``MAX_GRID_POINTS`` cells (records that are not
            one grid's: each distinct ``ki`` and ``v0`` is a column and a row)."""
    import numpy as np

    records = list(records)
    ki = sorted({r["ki"] for r in records})
    v0 = sorted({r["v0"] for r in records})
    if ki and v0:
        _native.check_grid(ki, v0)
    col = {x: i for i, x in enumerate(ki)}
    row = {y: j for j, y in enumerate(v0)}
    grid = np.full((len(v0), len(ki)), "", dtype=object)
    for r in records:
        grid[row[r["v0"]], col[r["ki"]]] = r["outcome"] if r["error"] is None else "failed"
    return np.array(ki), np.array(v0), grid


def to_dataset(records: Iterable[Record]):
    """The records as an ``xarray.Dataset`` (xarray must be installed): dimensions ``v0`` and
    ``ki`` (``k_i/k``), their sorted values as coordinates, and one variable per column of the
    records: ``outcome`` (``"failed"`` for a failed point, ``""`` for a point not in
    ``records``), ``t_decided``, ``confirmed``, ``later``, ``t_later``, ``kinks_final``,
    ``antikinks_final``, ``energy_error``, ``integrator`` and ``error`` (the message of a failed
    point, else ``""``), with ``long_name`` and ``units`` attributes. A cell without a record
    holds ``NaN`` (times, ``energy_error``), ``-1`` (the counts), ``False`` (``confirmed``) or
    ``""``.

    >>> ds = sweep.to_dataset(records)                                  # doctest: +SKIP
    >>> ds.outcome.sel(ki=0.7, v0=4.0, method="nearest").item()         # doctest: +SKIP
    'trapped'

    Raises:
        ImportError: xarray is not installed.
        GridError: the records span more than ``MAX_GRID_POINTS`` cells (as ``outcome_grid``).
        ValueError: two records at the same ``(ki, v0)``.
    """
    from ._dataset import to_dataset as build

    return build(records)


# --- running the points -----------------------------------------------------------------------


def _run_local(
    d: "_native.PhaseDiagram",
    points: List[Tuple[int, int, float, float]],
    threads: Optional[int],
    chunk_size: Optional[int],
    sink: Callable[[Record], None],
    report: Callable[[int], None],
) -> None:
    # Chunks of points, each computed in parallel with the GIL released; between chunks the
    # records are written and Ctrl-C is seen, so an interrupted sweep keeps every finished chunk.
    width = threads or os.cpu_count() or 1
    size = chunk_size or 8 * width
    done = 0
    for start in range(0, len(points), size):
        chunk = points[start : start + size]
        # compute_points starts no more threads than the chunk has points.
        for record in d.compute_points(chunk, threads):
            sink(record)
        done += len(chunk)
        report(done)


def _compute_chunk(settings: Dict[str, Any], chunk: List[Tuple[int, int, float, float]]) -> List[Record]:
    """One Dask task: the records of ``chunk`` on one thread of the worker."""
    return _native.PhaseDiagram(**settings).compute_points(chunk, 1)


def _run_dask(
    client: Any,
    settings: Dict[str, Any],
    points: List[Tuple[int, int, float, float]],
    chunk_size: Optional[int],
    sink: Callable[[Record], None],
    report: Callable[[int], None],
    max_resubmits: int,
) -> None:
    try:
        from distributed import KilledWorker, as_completed
    except ImportError as e:  # pragma: no cover - only without dask installed
        raise ImportError("client=... needs dask.distributed: pip install 'dask[distributed]'") from e
    if not points:
        return
    slots = max(1, sum(client.nthreads().values()))
    size = chunk_size or max(1, min(256, math.ceil(len(points) / (8 * slots))))
    chunks = [points[k : k + size] for k in range(0, len(points), size)]
    tag = uuid.uuid4().hex[:12]

    def submit(c: int, attempt: int):
        key = f"phase-diagram-{tag}-chunk-{c}-try-{attempt}"
        return client.submit(_compute_chunk, settings, chunks[c], key=key, pure=False)

    futures = {submit(c, 0): c for c in range(len(chunks))}
    attempts = [0] * len(chunks)
    done = 0
    pending = as_completed(list(futures))
    try:
        for future in pending:
            c = futures.pop(future)
            if future.status == "finished":
                for record in future.result():
                    sink(record)
            else:
                error = future.exception()
                # None: the chunk had finished, but its result was lost with its worker between
                # as_completed's report and this look (seen with a release build, whose chunks
                # finish sooner): it is submitted again like a chunk whose worker died.
                if error is not None and not isinstance(error, KilledWorker):
                    raise error
                if attempts[c] < max_resubmits:
                    attempts[c] += 1
                    again = submit(c, attempts[c])
                    futures[again] = c
                    pending.add(again)
                    future.release()
                    continue
                message = (
                    f"dask: the worker computing this point's chunk died each time it ran "
                    f"({max_resubmits + 1} submissions): "
                    + (f"{type(error).__name__}: {error}" if error is not None else "its result was lost with it")
                )
                for i, j, x, y in chunks[c]:
                    sink(_failed(i, j, x, y, message))
            future.release()
            done += len(chunks[c])
            report(done)
    finally:
        for future in futures:
            future.cancel()


def _failed(i: int, j: int, ki: float, v0: float, message: str) -> Record:
    record: Record = {key: None for key in COLUMNS}
    record.update(i=i, j=j, ki=ki, v0=v0, error=message)
    return record
