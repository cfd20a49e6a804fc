"""Mirror symmetry of the Python-only surfaces (tests/mirror_symmetry.rs checks the Rust API).

Reflecting the chain ``x -> -x`` maps ``theta_i -> -theta_{n-1-i}``, spring ``p`` to
``n - 2 - p`` and rotor ``i`` to ``n - 1 - i``; a defect launched or scattered towards one side
is the mirror image of the one launched towards the other from the mirrored position, with the
same charge (a kink stays a kink). What Python adds to the Rust API is the choice of side by name:
``Chain.launch(..., direction)`` and ``Chain.scatter(..., direction=, start=)``, whose default
start for ``direction="right"`` must be the mirror image of the default for ``"left"`` (15 sites
from the impurity on the far side). Each expected value is the unmirrored run's result mapped by
the symmetry. The phase diagrams (``sweep``, ``PhaseDiagram``) always launch from the right and
take no side, so there is nothing of theirs to mirror. ``Chain.antikink()`` without a centre
takes rotor ``(n - 1) // 2`` and ``Chain.scatter`` without an impurity spring ``(n - 1) // 2``:
for an even ``n`` (resp. an odd one) that is not its own mirror image, so those defaults are
left out and every call below names its centre and impurity."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotor_chain as rc

# n = 61 with the impurity on spring 29: the mirrored impurity is spring 30 (n - 2 - 29).
N, P = 61, 29
LAST = N - 1


def chain(impurity, ki, k=1.0e4, mass=1.0):
    """The paper's Sec. VI chain (theta_bar = 0.28, r = 0.8) with ``k_i = ki k`` on ``impurity``."""
    return rc.Chain(N, 0.8, k, 0.28, mass=mass, springs={impurity: {"k": ki * k}}, rotors={12: 0.78})


def mirrored_chain(ki, k=1.0e4, mass=1.0):
    return rc.Chain(N, 0.8, k, 0.28, mass=mass, springs={N - 2 - P: {"k": ki * k}}, rotors={LAST - 12: 0.78})


def mirror(theta):
    return -np.asarray(theta, dtype=float)[::-1]


def close(got, expected, rtol, what):
    g, e = np.asarray(got, dtype=float), np.asarray(expected, dtype=float)
    assert g.shape == e.shape, f"{what}: shape {g.shape} != {e.shape}"
    size = float(np.max(np.abs(e)))
    assert size > 0.0 and math.isfinite(size), f"{what}: nothing to compare"
    err = float(np.max(np.abs(g - e)))
    assert err <= rtol * size, f"{what}: off by {err / size:.2e}"


def mirrored_walls(walls):
    """A snapshot's walls at ``n - 1 - x``, same charges, sorted by position."""
    return sorted((LAST - x, q) for x, q in walls)


def assert_runs_mirrored(got, base, rtol, what):
    assert got.integrator == base.integrator
    assert (got.steps, got.rejected) == (base.steps, base.rejected), what
    np.testing.assert_array_equal(got.times, base.times)
    close(got.theta, mirror(base.theta), rtol, f"{what}: angles")
    close(got.omega, mirror(base.omega), rtol, f"{what}: velocities")
    close(got.kinetic, base.kinetic, rtol, f"{what}: kinetic energy")
    assert got.violations == base.violations, what
    np.testing.assert_array_equal(got.wall_counts, base.wall_counts)
    compared = 0
    for w, w0 in zip(got.walls, base.walls):
        w, e = sorted(w), mirrored_walls(w0)
        assert [q for _, q in w] == [q for _, q in e], f"{what}: {w} against {e}"
        if w:
            err = max(abs(x - y) for (x, _), (y, _) in zip(w, e))
            assert err <= rtol * LAST, f"{what}: walls off by {err:.2e}"
            compared += 1
    assert compared > 0, f"{what}: no wall compared"


@pytest.mark.parametrize("defect, v0, ki", [("kink", 4.0, 0.10), ("antikink", 4.8, 0.20)])
def test_scatter_from_the_left_mirrors_the_paper_setup(defect, v0, ki):
    base = chain(P, ki).scatter(defect, v0, P, absorbing_ends=True, space_time=True)
    # The default start of direction="right": the mirror image of the default from the right.
    got = mirrored_chain(ki).scatter(defect, v0, N - 2 - P, direction="right", absorbing_ends=True, space_time=True)
    what = f"{defect} v0 = {v0}, k_i/k = {ki}"
    assert (got.outcome, got.confirmed, got.decided_at) == (base.outcome, base.confirmed, base.decided_at), what
    assert (got.later, got.later_at) == (base.later, base.later_at), what
    # The antikink's start comes from Newton's method (to ~1e-11), and the run amplifies that
    # about tenfold per t (tests/mirror_symmetry.rs): 1e-8 by the end of this one, t = 2.8.
    assert_runs_mirrored(got.run, base.run, 1e-6, what)
    for a, b in zip(got.run.space_time, base.run.space_time):
        close(a, mirror(b), 1e-6, f"{what}: space-time")


def test_scatter_with_a_start_of_its_own_and_free_ends():
    # An explicit start on either side, in a chain with another time unit (k = 4e4, M = 2).
    k, mass = 4.0e4, 2.0
    v0 = 4.0 * math.sqrt(k / (1.0e4 * mass))
    start = P + 0.5 + 11.25
    base = chain(P, 0.1, k, mass).scatter("kink", v0, P, start=start, direction="left", watch=1.0)
    got = mirrored_chain(0.1, k, mass).scatter("kink", v0, N - 2 - P, start=LAST - start, direction="right", watch=1.0)
    assert (got.outcome, got.confirmed, got.decided_at) == (base.outcome, base.confirmed, base.decided_at)
    assert (got.later, got.later_at) == (base.later, base.later_at)
    assert base.run.walls[0] == [(start, "kink")] and got.run.walls[0] == [(LAST - start, "kink")]
    assert_runs_mirrored(got.run, base.run, 1e-10, "kink from an own start")


@pytest.mark.parametrize("defect, position", [("kink", 40.25), ("antikink", 22.0)])
def test_launch_by_name_and_propagate(defect, position):
    c, m = chain(P, 0.5), mirrored_chain(0.5)
    left = c.launch(defect, position, 3.0)  # direction defaults to "left"
    right = m.launch(defect, LAST - position, 3.0, "right")
    assert left.defect == right.defect == defect
    assert abs(right.position - (LAST - left.position)) <= 1e-9 * LAST
    for name in ("theta", "omega", "mode"):
        close(getattr(right, name), mirror(getattr(left, name)), 1e-9, f"{defect} launch {name}")
    for method in ("verlet", "dop853"):
        options = dict(t_max=0.2, method=method, damping=0.3, absorbing_ends=True)
        base = c.propagate(left.theta, left.omega, **options)
        got = m.propagate(right.theta, right.omega, **options)
        assert_runs_mirrored(got, base, 1e-9, f"{defect} {method}")
    walls, walls_m = mirrored_walls(rc.domain_walls(left.theta)), sorted(rc.domain_walls(right.theta))
    assert [q for _, q in walls_m] == [q for _, q in walls] == [defect]
    assert abs(walls_m[0][0] - walls[0][0]) <= 1e-9 * LAST
