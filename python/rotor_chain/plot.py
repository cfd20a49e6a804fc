"""Pictures of chains and their results with matplotlib (``pip install matplotlib``; the rest of
``rotor_chain`` works without it, and this module imports it only when a function is called).

- :func:`phase_diagram`: the outcomes of a sweep over ``k_i/k`` and ``v0`` (paper Fig.
  ``fig:phasediagram``), one colour per outcome whatever the sweep;
- :func:`chain`: the rotors and springs of a configuration, the springs coloured by their strain
  ``(l - l0)/l0`` on a fixed scale of the chain's own (paper Fig. ``fig:kcobweb``'s drawing);
- :func:`space_time`: the angles of a run at every output, rotor against time, with its walls;
- :func:`mode`: a vibrational mode as arrows at the rotor tips.

Each draws into ``ax`` (a new figure when ``ax`` is ``None``) and returns the ``Axes``, so
titles, limits and colours can be changed after (``ax.figure.savefig(...)`` saves it). Lengths
are in the unit of ``a``, times in ``t`` (as everywhere in ``rotor_chain``).
"""

from __future__ import annotations

import math
from typing import Any, Dict, Iterable, List, Optional, Sequence

import numpy as np

__all__ = ["OUTCOME_COLOURS", "phase_diagram", "chain", "space_time", "mode", "tips"]

#: The colour of each outcome, fixed so that two diagrams compare (matplotlib's ``tab10``).
#: ``"unresolved"`` is kept for the label of cells whose outcome a finer run would change;
#: ``"failed"`` marks a point without a record. An outcome not listed here gets a colour of
#: ``tab20``'s light half, the same for the same set of names.
OUTCOME_COLOURS: Dict[str, str] = {
    "transmitted": "#1f77b4",
    "reflected": "#ff7f0e",
    "trapped": "#2ca02c",
    "split": "#d62728",
    "annihilated": "#9467bd",
    "disintegrated": "#8c564b",
    "pair-creation": "#e377c2",
    "undecided": "#7f7f7f",
    "unresolved": "#bcbd22",
    "failed": "#000000",
}
_SPARE_COLOURS = ("#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5", "#c49c94", "#f7b6d2", "#dbdb8d")


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError("rotor_chain.plot needs matplotlib: pip install matplotlib") from e
    return plt


def _axes(ax: Any, figsize: Sequence[float]) -> Any:
    if ax is not None:
        return ax
    _, ax = _pyplot().subplots(figsize=figsize, layout="constrained")
    return ax


# --- phase diagrams ---------------------------------------------------------------------------


def _edges(values: np.ndarray, log: bool) -> np.ndarray:
    """Cell edges around sorted grid values: midway between neighbours (in the logarithm on a log
    axis), the outer cells as wide as their neighbours."""
    x = np.log(values) if log else np.asarray(values, dtype=float)
    if len(x) == 1:
        half = 0.05 if log else 0.05 * max(abs(x[0]), 1.0)
        edges = np.array([x[0] - half, x[0] + half])
    else:
        mid = (x[1:] + x[:-1]) / 2
        edges = np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])
    return np.exp(edges) if log else edges


def _log_spaced(ki: np.ndarray) -> bool:
    """Whether a ``k_i/k`` axis reads best on a log scale: evenly spaced in the logarithm (as
    ``"FROM:TO:COUNT:log"`` gives), or spanning a decade or more."""
    if len(ki) < 2 or ki[0] <= 0:
        return False
    steps = np.diff(np.log(ki))
    return bool(np.ptp(steps) <= 1e-6 * np.max(np.abs(steps)) and len(ki) > 2) or ki[-1] / ki[0] >= 10


def _decimal_log_formatter(minor: bool) -> Any:
    """Tick labels of a log axis as the values they mark (0.01, 0.1, 1, not 10^-2): every
    decade; between decades only when the axis spans a decade or less (then at 2, 3, 4, 6 times
    a power of ten, or at every tick below 0.4 decades, matplotlib's own rule for minor labels)."""
    from matplotlib.ticker import Formatter

    class DecimalLogFormatter(Formatter):
        def __call__(self, x: float, pos: Optional[int] = None) -> str:
            if not x > 0:
                return ""
            if minor:
                lo, hi = sorted(self.axis.get_view_interval())
                decades = math.log10(hi / lo) if lo > 0 else math.inf
                mantissa = round(x / 10 ** math.floor(math.log10(x) + 1e-9))
                if decades > 1 or (decades > 0.4 and mantissa not in (2, 3, 4, 6)):
                    return ""
            return f"{x:g}"

    return DecimalLogFormatter()


def _colours(names: Iterable[str]) -> Dict[str, str]:
    spare = iter(_SPARE_COLOURS * (1 + len(OUTCOME_COLOURS)))
    return {name: OUTCOME_COLOURS.get(name) or next(spare) for name in names}


def phase_diagram(
    records: Iterable[Dict[str, Any]],
    *,
    ax: Any = None,
    log_ki: Optional[bool] = None,
    legend: bool = True,
    title: Optional[str] = None,
) -> Any:
    """The outcome of each point of a sweep (``rotor_chain.sweep`` records, or
    ``sweep.read_results(path)``): one cell per point, ``k_i/k`` across, ``v0`` up, coloured by
    outcome (:data:`OUTCOME_COLOURS`), with a legend of the outcomes present only, in the order
    of ``sweep.OUTCOMES``. A point the records lack stays white (``"not computed"`` in the
    legend).

    Args:
        log_ki: a log ``k_i/k`` axis, its ticks labelled with ``k_i/k`` values (0.01, 0.1, 1);
            ``None`` decides from the values (log for an axis evenly spaced in the logarithm,
            or one spanning a decade).
        legend: draw the legend, right of the axes.
        title: the axes' title.

    Returns:
        The ``Axes``; the cells are ``ax.collections[0]`` (a ``QuadMesh``).
    """
    _pyplot()  # ImportError with what to install, before any other import of matplotlib
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    from .sweep import OUTCOMES, outcome_grid

    ki, v0, outcomes = outcome_grid(records)
    if not len(ki):
        raise ValueError("no records to draw")
    order = list(OUTCOMES) + sorted({str(o) for o in outcomes.flat} - set(OUTCOMES) - {"failed", ""}) + ["failed"]
    present = [name for name in order if (outcomes == name).any()]
    colours = _colours(order)
    codes = np.full(outcomes.shape, -1, dtype=int)
    for c, name in enumerate(present):
        codes[outcomes == name] = c
    log = _log_spaced(ki) if log_ki is None else log_ki
    ax = _axes(ax, (6.4, 4.4))
    cmap = ListedColormap([colours[name] for name in present])
    mesh = ax.pcolormesh(
        _edges(ki, log),
        _edges(v0, False),
        np.ma.masked_less(codes, 0),  # a point without a record is not drawn: white
        cmap=cmap,
        norm=BoundaryNorm(np.arange(-0.5, len(present) + 0.5), cmap.N),
        shading="flat",
    )
    mesh.set_gid("outcomes")
    if log:
        ax.set_xscale("log")
        ax.xaxis.set_major_formatter(_decimal_log_formatter(minor=False))
        ax.xaxis.set_minor_formatter(_decimal_log_formatter(minor=True))
    ax.set_xlim(*_edges(ki, log)[[0, -1]])
    ax.set_ylim(*_edges(v0, False)[[0, -1]])
    ax.set_xlabel(r"$k_i/k$")
    ax.set_ylabel(r"$v_0$ ($a/t$)")
    if title is not None:
        ax.set_title(title)
    if legend:
        handles = [Patch(facecolor=colours[name], edgecolor="none", label=name) for name in present]
        if (codes < 0).any():
            handles.append(Patch(facecolor="white", edgecolor="0.5", label="not computed"))
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, frameon=False)
    return ax


# --- chains -----------------------------------------------------------------------------------


def tips(chain: Any, theta: Any) -> np.ndarray:
    """The tip positions ``(n, 2)`` of ``chain``'s rotors at ``theta`` (docs/theory.md §1):
    ``x_i = (i a + r_i sin theta_i, (-1)^i r_i cos theta_i)``, pivots at ``(i a, 0)``."""
    theta = np.asarray(theta, dtype=float)
    r = chain.rotor_lengths
    i = np.arange(len(r))
    return np.column_stack([i * chain.a + r * np.sin(theta), np.where(i % 2 == 0, 1.0, -1.0) * r * np.cos(theta)])


def _sharp_antikink_strain(chain: Any) -> float:
    """The strain of a spring whose rotors stand at ``-theta_bar`` (rotor ``p``) and
    ``+theta_bar`` (``p + 1``), an antikink one spring wide, the largest over the springs: the
    stretch scale of the chain's own antikinks, whose wider walls stretch their middle springs
    less (``Chain(60, 0.8, 1e4, theta_bar)``: 0.156 against 0.054 at ``theta_bar = 0.28``, 0.380
    against 0.212 at 0.58). From docs/theory.md §1 with ``theta_p = -theta_bar``,
    ``theta_{p+1} = theta_bar``."""
    r, a, t = chain.rotor_lengths, chain.a, chain.theta_bar
    l2 = (a + (r[1:] + r[:-1]) * math.sin(t)) ** 2 + ((r[:-1] + r[1:]) * math.cos(t)) ** 2
    return float(np.max(np.sqrt(l2) / chain.rest_lengths - 1.0))


def chain(
    chain: Any,
    theta: Any,
    *,
    ax: Any = None,
    strain_scale: Optional[float] = None,
    cmap: Any = None,
    colorbar: bool = True,
) -> Any:
    """The rotors (black, from pivot to tip) and springs of ``chain`` at ``theta``, each spring
    coloured by its strain ``(l_p - l0_p) / l0_p``: grey at rest, red stretched, blue compressed
    (``cmap`` replaces that colour map).

    The colour scale is fixed by the chain, not by the configuration, so a chain at rest looks
    at rest (a kink's springs, at rest to rounding, are all grey) and two pictures of one chain
    compare: ``strain_scale`` (default: the strain of an antikink one spring wide, rotors at
    ``-theta_bar`` and ``+theta_bar``, 0.156 for ``Chain(60, 0.8, 1e4, 0.28)`` and 0.380 at
    ``theta_bar = 0.58``) is full colour, and strains beyond it saturate.

    Returns:
        The ``Axes``; its collections are the rotors (gid ``"rotors"``), the springs
        (``"springs"``, a ``LineCollection`` whose array is the strains) and the pivots.
    """
    return _draw_chain(chain, theta, ax, strain_scale, cmap, colorbar)


def _draw_chain(
    chain: Any,
    theta: Any,
    ax: Any,
    strain_scale: Optional[float],
    cmap: Any,
    colorbar: bool,
    window: Optional[Sequence[float]] = None,
) -> Any:
    _pyplot()  # ImportError with what to install, before any other import of matplotlib
    from matplotlib.collections import LineCollection
    from matplotlib.colors import LinearSegmentedColormap, Normalize

    if cmap is None:
        # Diverging through a grey that shows on white: a spring at rest is drawn, not hidden.
        # An odd number of colours puts the grey itself at zero, and rounding either side on it.
        cmap = LinearSegmentedColormap.from_list("strain", ["#2166ac", "#a8a8a8", "#b2182b"], N=255)

    strain = chain.spring_lengths(theta) / chain.rest_lengths - 1.0  # checks theta first
    theta = np.asarray(theta, dtype=float)
    x = tips(chain, theta)
    n = len(x)
    pivots = np.column_stack([np.arange(n) * chain.a, np.zeros(n)])
    scale = _sharp_antikink_strain(chain) if strain_scale is None else float(strain_scale)
    if not (scale > 0 and math.isfinite(scale)):
        raise ValueError(f"strain_scale must be > 0 and finite, got {strain_scale!r}")
    if ax is None:
        # A figure of the drawing's own shape (equal scales): a chain is long and flat.
        left, right = window if window is not None else (x[:, 0].min() - 0.5 * chain.a, x[:, 0].max() + 0.5 * chain.a)
        high = 1.3 * (max(x[:, 1].max(), 0.0) - min(x[:, 1].min(), 0.0))
        wide = min(max(4.0, 0.22 * (right - left) / chain.a), 14.0)
        ax = _axes(None, (wide, wide * high / (right - left) + (1.7 if colorbar else 1.0)))
    rotors = LineCollection(np.stack([pivots, x], axis=1), colors="black", linewidths=1.0, zorder=2)
    rotors.set_gid("rotors")
    ax.add_collection(rotors)
    springs = LineCollection(
        np.stack([x[:-1], x[1:]], axis=1), cmap=cmap, norm=Normalize(-scale, scale), linewidths=2.5, zorder=1
    )
    springs.set_array(strain)
    springs.set_gid("springs")
    ax.add_collection(springs)
    dots = ax.scatter(pivots[:, 0], pivots[:, 1], s=8, color="black", zorder=3)
    dots.set_gid("pivots")
    ax.set_aspect("equal")
    ax.margins(x=0.01, y=0.15)
    ax.autoscale_view()
    ax.set_xlabel("x ($a$)")
    ax.set_yticks([])
    if colorbar:
        shrink = min(1.0, 3.5 / ax.figure.get_figwidth())
        bar = ax.figure.colorbar(springs, ax=ax, location="bottom", extend="both", shrink=shrink, aspect=25)
        bar.set_label(r"spring strain $(l - l_0)/l_0$")
    return ax


def mode(
    chain: Any,
    theta: Any,
    modes: Any,
    index: int = 0,
    *,
    ax: Any = None,
    length: float = 0.8,
    zoom: bool = True,
    colorbar: bool = False,
) -> Any:
    """Mode ``index`` of ``modes`` (``chain.modes(theta)``) as arrows at the rotor tips of the
    chain drawn at ``theta`` (:func:`chain`): the tip displacement ``r_i v_i (cos theta_i,
    -(-1)^i sin theta_i)`` of the angular pattern ``v`` (purple), the longest arrow ``length``
    (in ``a``). With ``zoom``, the x axis shows only where the mode lives: from 4 ``a`` left of
    the first rotor whose arrow is 2 % of the longest to 4 ``a`` right of the last.

    Returns:
        The ``Axes``; the arrows are a ``Quiver`` with gid ``"mode"``.
    """
    theta = np.asarray(theta, dtype=float)
    count = len(modes.frequencies)
    if not -count <= index < count:
        raise IndexError(f"mode {index} of {count}")
    v = modes.vectors[index]
    r = chain.rotor_lengths
    sign = np.where(np.arange(len(r)) % 2 == 0, 1.0, -1.0)
    d = np.column_stack([r * v * np.cos(theta), -sign * r * v * np.sin(theta)])
    size = np.hypot(d[:, 0], d[:, 1])
    biggest = float(np.max(size))
    scale = biggest / length if biggest > 0 else 1.0
    x = tips(chain, theta)
    window = None
    if zoom and biggest > 0:
        moving = np.flatnonzero(size >= 0.02 * biggest)
        window = (x[moving[0], 0] - 4 * chain.a, x[moving[-1], 0] + 4 * chain.a)
    ax = _draw_chain(chain, theta, ax, None, None, colorbar, window)
    # Widths in units of a, so that arrows read the same in a chain of any length.
    arrows = ax.quiver(
        x[:, 0], x[:, 1], d[:, 0], d[:, 1], angles="xy", scale_units="xy", scale=scale, units="xy", width=0.04,
        headwidth=3, headlength=3.5, headaxislength=3, minlength=0, color="#7b3294", zorder=4,
    )
    arrows.set_gid("mode")
    kind = modes.kinds[index]
    ax.set_title(rf"mode {index % count}: $\omega$ = {modes.frequencies[index]:.4g} / $t$ ({kind})")
    ax.update_datalim(x + d / scale)
    ax.autoscale_view()
    if window is not None:
        ax.set_xlim(*window)
    return ax


# --- runs -------------------------------------------------------------------------------------


def space_time(
    run: Any,
    *,
    ax: Any = None,
    limit: Optional[float] = None,
    cmap: str = "coolwarm",
    walls: bool = True,
) -> Any:
    """The angles ``theta_i(t)`` of a run (``Chain.propagate(..., space_time=True)``, or a
    ``Scattering`` of ``Chain.scatter(..., space_time=True)``): rotor across, time up, the
    colour from ``-limit`` (blue) to ``+limit`` (red), ``limit`` by default the largest
    ``|theta|`` of the run; with ``walls``, the kinks (``x``) and antikinks (``o``) the run
    tracked at every output.

    Returns:
        The ``Axes``; the image is ``ax.images[0]``, the walls the collections with gid
        ``"kink"`` and ``"antikink"``.

    Raises:
        ValueError: the run kept no angles (it ran without ``space_time=True``).
    """
    _pyplot()  # ImportError with what to install, before any other import of matplotlib
    from matplotlib.colors import Normalize

    run = getattr(run, "run", run)  # a Scattering's run
    if run.space_time is None:
        raise ValueError("the run kept no angles: run it with space_time=True")
    image = run.space_time
    times = run.times
    steps, n = image.shape
    dt = float(times[1] - times[0]) if steps > 1 else 1.0
    top = float(np.max(np.abs(image))) if limit is None else float(limit)
    if not (top > 0 and math.isfinite(top)):
        raise ValueError(f"limit must be > 0 and finite, got {limit!r}")
    ax = _axes(ax, (6.4, 4.4))
    shown = ax.imshow(
        image,
        origin="lower",
        aspect="auto",
        interpolation="nearest",
        extent=(-0.5, n - 0.5, times[0] - dt / 2, times[-1] + dt / 2),
        cmap=cmap,
        norm=Normalize(-top, top),
    )
    bar = ax.figure.colorbar(shown, ax=ax)
    bar.set_label(r"$\theta_i$ (rad)")
    if walls:
        for charge, marker in (("kink", "x"), ("antikink", "o")):
            points = _walls(run, charge)
            colour = {"facecolors": "none", "edgecolors": "black"} if marker == "o" else {"color": "black"}
            dots = ax.scatter(points[:, 0], points[:, 1], s=4, marker=marker, linewidths=0.5, label=charge, **colour)
            dots.set_gid(charge)
        if any(len(w) for w in run.walls):
            ax.legend(loc="upper right", fontsize="small", markerscale=2)
    ax.set_xlim(-0.5, n - 0.5)
    ax.set_xlabel("rotor $i$")
    ax.set_ylabel("time ($t$)")
    return ax


def _walls(run: Any, charge: str) -> np.ndarray:
    """``(position, time)`` of every wall of ``charge`` at every output."""
    found: List[List[float]] = [
        [position, t] for t, walls in zip(run.times, run.walls) for position, c in walls if c == charge
    ]
    return np.array(found, dtype=float).reshape(-1, 2)
