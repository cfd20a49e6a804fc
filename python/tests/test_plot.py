"""rotor_chain.plot draws what it is given: the data of each artist (cells, segments, arrows,
image, markers) checked against the input through numpy formulas written here, independent of
the module (the tip positions and spring lengths of docs/theory.md §1, finite differences for a
mode's tip displacements)."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402

import rotor_chain as rc  # noqa: E402
from rotor_chain import plot, sweep  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def theory_tips(a, r, theta):
    """docs/theory.md §1: x_i = (i a + r_i sin theta_i, (-1)^i r_i cos theta_i)."""
    i = np.arange(len(theta))
    return np.column_stack([i * a + r * np.sin(theta), (-1.0) ** i * r * np.cos(theta)])


def theory_strain(a, r, theta_bar, theta):
    """(l_p - lbar) / lbar with l_p^2 from docs/theory.md §1 and lbar^2 = a^2 + 4 r^2 cos^2 theta_bar."""
    tp, tq = theta[:-1], theta[1:]
    l = np.sqrt((a + r * np.sin(tq) - r * np.sin(tp)) ** 2 + (r * np.cos(tp) + r * np.cos(tq)) ** 2)
    lbar = math.sqrt(a * a + 4 * r * r * math.cos(theta_bar) ** 2)
    return l / lbar - 1.0


# --- phase diagrams ---------------------------------------------------------------------------

KI = [0.01, 0.1, 1.0, 3.0]  # not evenly spaced in the logarithm, but over two decades: log
V0 = [1.0, 2.0, 4.0]
# One outcome per cell, (ki, v0) -> outcome; None: the point failed; absent: no record.
CELLS = {
    (0.01, 1.0): "trapped",
    (0.01, 2.0): "reflected",
    (0.01, 4.0): "reflected",
    (0.1, 1.0): "trapped",
    (0.1, 2.0): None,
    (0.1, 4.0): "unresolved",  # an outcome sweep.OUTCOMES does not list yet
    (1.0, 1.0): "transmitted",
    (1.0, 2.0): "transmitted",
    (3.0, 1.0): "reflected",
    (3.0, 2.0): "pair-creation",
    (3.0, 4.0): "reflected",
}  # (1.0, 4.0) is missing


def record(ki, v0, outcome):
    r = {key: None for key in sweep.COLUMNS}
    r.update(i=KI.index(ki) if ki in KI else 0, j=V0.index(v0) if v0 in V0 else 0, ki=ki, v0=v0)
    if outcome is None:
        r["error"] = "energy budget: 0.02 > 0.005"
    else:
        r.update(outcome=outcome, t_decided=3.5, confirmed=True, kinks_final=0, antikinks_final=1)
        r.update(energy_error=1e-4, integrator="verlet")
    return r


def records():
    return [record(ki, v0, o) for (ki, v0), o in CELLS.items()]


def test_the_phase_diagram_colours_each_cell_by_its_records_outcome():
    ax = plot.phase_diagram(records())
    (mesh,) = [c for c in ax.collections if c.get_gid() == "outcomes"]
    colours = mesh.to_rgba(mesh.get_array()).reshape(len(V0), len(KI), 4)
    mask = np.ma.getmaskarray(mesh.get_array()).reshape(len(V0), len(KI))
    for j, v0 in enumerate(V0):
        for i, ki in enumerate(KI):
            if (ki, v0) not in CELLS:
                assert mask[j, i], (ki, v0)  # not drawn
                continue
            outcome = CELLS[(ki, v0)] or "failed"
            assert not mask[j, i]
            assert np.allclose(colours[j, i], to_rgba(plot.OUTCOME_COLOURS[outcome])), (ki, v0, outcome)
    # Cell edges midway between the grid values, in the logarithm across and linearly up; the
    # outer cells as wide as their neighbours.
    edges = mesh.get_coordinates()  # (ny + 1, nx + 1, 2)
    x, y = edges[0, :, 0], edges[:, 0, 1]
    assert np.allclose(x[1:-1], np.sqrt(np.multiply(KI[1:], KI[:-1])), rtol=1e-12)
    assert np.allclose([x[1] / x[0], x[-1] / x[-2]], [KI[1] / KI[0], KI[-1] / KI[-2]], rtol=1e-12)
    assert np.allclose(y, [0.5, 1.5, 3.0, 5.0], rtol=1e-12)
    assert ax.get_xlim() == pytest.approx((x[0], x[-1])) and ax.get_ylim() == pytest.approx((0.5, 5.0))
    # The legend: only what is present, in sweep.OUTCOMES' order, then the others, failed, missing.
    legend = ax.get_legend()
    names = [t.get_text() for t in legend.get_texts()]
    assert names == ["transmitted", "reflected", "trapped", "pair-creation", "unresolved", "failed", "not computed"]
    for patch, name in zip(legend.get_patches()[:-1], names[:-1]):
        assert np.allclose(patch.get_facecolor(), to_rgba(plot.OUTCOME_COLOURS[name])), name


def test_the_log_axis_is_labelled_with_k_i_over_k_values():
    ax = plot.phase_diagram(records())
    ax.figure.canvas.draw()
    assert ax.get_xscale() == "log"
    shown = [t.get_text() for t in ax.get_xticklabels() if t.get_text()]
    assert {"0.01", "0.1", "1"} <= set(shown), shown
    assert not [t for t in shown if "e" in t or "$" in t or "10^" in t], shown
    assert not [t.get_text() for t in ax.get_xticklabels(minor=True) if t.get_text()]  # over two decades
    assert ax.get_xlabel() == r"$k_i/k$" and "v_0" in ax.get_ylabel()
    # Inside one decade the ticks between the powers of ten carry the values.
    narrow = [record(ki, 4.0, "trapped") for ki in (0.5, 0.6, 0.7, 0.8, 0.9)]
    ax = plot.phase_diagram(narrow, log_ki=True)
    ax.figure.canvas.draw()
    minor = [t.get_text() for t in ax.get_xticklabels(minor=True) if t.get_text()]
    assert {"0.5", "0.6", "0.7", "0.8", "0.9"} <= set(minor), minor


def test_a_linearly_spaced_axis_stays_linear_and_the_legend_lists_only_whats_there():
    few = [record(ki, v0, "transmitted" if ki > 0.5 else "trapped") for ki in (0.1, 1.0) for v0 in (1.0, 2.0)]
    ax = plot.phase_diagram(few, log_ki=False)
    assert ax.get_xscale() == "linear"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["transmitted", "trapped"]


def test_the_phase_diagram_of_a_sweep(tmp_path):
    recs = sweep.phase_diagram("antikink", "0.2:1:3:log", "3:5:3", progress=False)
    ax = plot.phase_diagram(recs, title="antikink")
    mesh = ax.collections[0]
    colours = mesh.to_rgba(mesh.get_array()).reshape(3, 3, 4)
    ki, v0 = sorted({r["ki"] for r in recs}), sorted({r["v0"] for r in recs})
    for r in recs:
        expected = to_rgba(plot.OUTCOME_COLOURS[r["outcome"]])
        assert np.allclose(colours[v0.index(r["v0"]), ki.index(r["ki"])], expected)
    assert ax.get_title() == "antikink"
    ax.figure.savefig(tmp_path / "pd.png")
    assert (tmp_path / "pd.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --- chains -----------------------------------------------------------------------------------

PAPER = (60, 0.8, 1.0e4, 0.58)  # n, r (a length: a = 1), k, theta_bar


def springs_of(ax):
    (springs,) = [c for c in ax.collections if c.get_gid() == "springs"]
    return springs


def test_a_kink_is_drawn_at_rest_on_the_chains_fixed_scale():
    c = rc.Chain(*PAPER)
    theta = c.kink(29.5)
    ax = plot.chain(c, theta)
    springs = springs_of(ax)
    strain = np.asarray(springs.get_array())
    assert np.max(np.abs(strain)) < 1e-12  # the kink costs no energy: every spring at rest
    # The scale is the chain's, not the configuration's rounding: an antikink one spring wide,
    # l^2 = a^2 + 4 a r sin(theta_bar) + 4 r^2, over lbar.
    a, r, tb = 1.0, 0.8, 0.58
    sharp = math.sqrt(a * a + 4 * a * r * math.sin(tb) + 4 * r * r) / math.sqrt(a * a + 4 * r * r * math.cos(tb) ** 2) - 1
    assert springs.norm.vmin == pytest.approx(-sharp, rel=1e-12) and springs.norm.vmax == pytest.approx(sharp, rel=1e-12)
    assert sharp == pytest.approx(0.3798, abs=1e-4)
    # ... so every spring has the colour of zero strain: grey.
    rest = springs.to_rgba(np.zeros(59))
    assert np.array_equal(springs.to_rgba(strain), rest)
    assert rest[0][0] == rest[0][1] == rest[0][2] == pytest.approx(0xA8 / 255, abs=1 / 255)
    # The segments join the tips, the rotors run from the pivots to the tips.
    tips = theory_tips(a, r, theta)
    assert np.allclose(np.array(springs.get_segments()), np.stack([tips[:-1], tips[1:]], axis=1), atol=1e-14)
    (rotors,) = [col for col in ax.collections if col.get_gid() == "rotors"]
    pivots = np.column_stack([np.arange(60.0), np.zeros(60)])
    assert np.allclose(np.array(rotors.get_segments()), np.stack([pivots, tips], axis=1), atol=1e-14)


def test_an_antikinks_springs_carry_their_strain():
    c = rc.Chain(*PAPER)
    theta = c.antikink().theta
    springs = springs_of(plot.chain(c, theta))
    strain = np.asarray(springs.get_array())
    assert np.allclose(strain, theory_strain(1.0, 0.8, 0.58, theta), atol=1e-13)
    assert 0.2 < strain.max() < springs.norm.vmax  # the middle springs, within the scale
    # Stretched springs are drawn redder than those at rest.
    colours = springs.to_rgba(strain)
    middle, end = int(np.argmax(strain)), 0
    assert colours[middle][0] > colours[end][0] and colours[middle][2] < colours[end][2]


def test_the_chain_drawings_scale_and_errors():
    c = rc.Chain(*PAPER)
    springs = springs_of(plot.chain(c, c.uniform(), strain_scale=0.1, colorbar=False))
    assert (springs.norm.vmin, springs.norm.vmax) == (-0.1, 0.1)
    with pytest.raises(ValueError, match="strain_scale"):
        plot.chain(c, c.uniform(), strain_scale=0.0)
    with pytest.raises(ValueError):
        plot.chain(c, np.zeros(59))  # the chain's own check of theta's length


def test_a_modes_arrows_are_its_tip_displacements():
    c = rc.Chain(*PAPER)
    theta = c.antikink().theta
    modes = c.modes(theta, 4)
    m = modes.kinds.index("translation")
    ax = plot.mode(c, theta, modes, m)
    (arrows,) = [col for col in ax.collections if col.get_gid() == "mode"]
    tips = theory_tips(1.0, 0.8, theta)
    assert np.allclose(arrows.get_offsets(), tips, atol=1e-14)
    # The tip displacement of the angular pattern v, by central differences of the tip positions.
    v = modes.vectors[m]
    h = 1e-6
    moved = (theory_tips(1.0, 0.8, theta + h * v) - theory_tips(1.0, 0.8, theta - h * v)) / (2 * h)
    drawn = np.column_stack([arrows.U, arrows.V])
    assert np.allclose(drawn, moved, atol=1e-8 * np.max(np.abs(moved)))
    # The longest arrow is 0.8 a long on the axes.
    assert np.max(np.hypot(arrows.U, arrows.V)) / arrows.scale == pytest.approx(0.8, rel=1e-12)
    # Zoomed on where the mode lives: the antikink in the middle.
    left, right = ax.get_xlim()
    assert left < 29.0 < right and right - left < 30
    assert "translation" in ax.get_title()
    with pytest.raises(IndexError):
        plot.mode(c, theta, modes, 4)


# --- runs -------------------------------------------------------------------------------------


def test_the_space_time_image_is_the_runs_angles_with_its_walls():
    c = rc.Chain(40, 0.8, 1.0e4, 0.28)
    launch = c.launch("kink", 25.5, 4.0)
    run = c.propagate(launch.theta, launch.omega, t_max=1.0, output_interval=0.05, space_time=True)
    ax = plot.space_time(run)
    (image,) = ax.images
    assert np.array_equal(image.get_array(), run.space_time)
    left, right, bottom, top = image.get_extent()
    assert (left, right) == (-0.5, 39.5)
    assert bottom == pytest.approx(-0.025, abs=1e-12) and top == pytest.approx(run.times[-1] + 0.025, abs=1e-12)
    assert image.norm.vmax == -image.norm.vmin == np.max(np.abs(run.space_time))
    (kinks,) = [col for col in ax.collections if col.get_gid() == "kink"]
    expected = [(x, t) for t, walls in zip(run.times, run.walls) for x, charge in walls if charge == "kink"]
    assert len(expected) == len(run.times)  # one kink, tracked at every output
    assert np.array_equal(kinks.get_offsets(), np.array(expected))
    (antikinks,) = [col for col in ax.collections if col.get_gid() == "antikink"]
    assert len(antikinks.get_offsets()) == 0
    # The kink moves left: its marker at the end is left of the start.
    assert expected[-1][0] < expected[0][0] - 2


def test_a_scattering_draws_its_run_and_a_run_without_angles_is_refused():
    c = rc.Chain(60, 0.8, 1.0e4, 0.28, springs={29: {"k": 7.0e3}})
    s = c.scatter("antikink", 4.0, space_time=True)
    ax = plot.space_time(s, limit=0.28, walls=False)
    assert np.array_equal(ax.images[0].get_array(), s.run.space_time)
    assert (ax.images[0].norm.vmin, ax.images[0].norm.vmax) == (-0.28, 0.28)
    assert not [col for col in ax.collections if col.get_gid() in ("kink", "antikink")]
    with pytest.raises(ValueError, match="space_time=True"):
        plot.space_time(c.scatter("antikink", 4.0))


def test_each_helper_draws_into_the_axes_it_is_given():
    fig, axes = plt.subplots(1, 2)
    c = rc.Chain(*PAPER)
    assert plot.chain(c, c.kink(29.5), ax=axes[0], colorbar=False) is axes[0]
    assert plot.phase_diagram(records(), ax=axes[1], legend=False) is axes[1]
    assert axes[1].get_legend() is None


def test_the_package_works_without_matplotlib_and_the_helpers_say_what_to_install():
    import subprocess
    import sys

    code = (
        "import sys; sys.modules['matplotlib'] = None\n"
        "import rotor_chain as rc\n"
        "c = rc.Chain(20, 0.8, 1e4, 0.58)\n"
        "assert c.energy(c.kink(9.5)) < 1e-20\n"
        "try:\n"
        "    rc.plot.chain(c, c.kink(9.5))\n"
        "except ImportError as e:\n"
        "    print(e)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "rotor_chain.plot needs matplotlib: pip install matplotlib"
