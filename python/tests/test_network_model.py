"""``rotor_chain.NetworkModel`` (issue 36) against a numpy statement of the same square patch written
here from the reference positions (periodic and free, harmonic and quartic), finite differences,
``numpy.linalg.eigh`` of the numpy Hessian, and the closed-form spectrum of a stressed square
lattice; relaxation, Newton, Verlet's energy and Ctrl-C."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotor_chain as rc


def square_bonds(model: rc.NetworkModel, n: int, periodic: bool):
    """Each bond of the square patch as ``(i, j, shift)``: node ``j`` seen from node ``i`` is at
    ``x_j + shift``; nodes are found by their reference positions (integers ``0 <= X, Y < n``)."""
    ref = model.reference().reshape(-1, 2)
    index = {(round(x), round(y)): k for k, (x, y) in enumerate(ref)}
    assert len(index) == n * n
    bonds = []
    for (x, y), i in index.items():
        for dx, dy in ((1, 0), (0, 1)):
            tx, ty = x + dx, y + dy
            if (tx >= n or ty >= n) and not periodic:
                continue
            j = index[(tx % n, ty % n)]
            bonds.append((i, j, np.array([tx - tx % n, ty - ty % n], dtype=float)))
    return bonds


def law(name: str, k: float, l0: float, l: np.ndarray):
    """Energy and tension ``dV/dl`` of each bond."""
    if name == "quartic":
        return k * (l * l - l0 * l0) ** 2 / (8 * l0 * l0), k * l * (l * l - l0 * l0) / (2 * l0 * l0)
    return 0.5 * k * (l - l0) ** 2, k * (l - l0)


def numpy_energy_gradient(x: np.ndarray, bonds, name: str, k: float, l0: float):
    p = x.reshape(-1, 2)
    i = np.array([b[0] for b in bonds])
    j = np.array([b[1] for b in bonds])
    shift = np.array([b[2] for b in bonds])
    d = p[j] + shift - p[i]
    l = np.hypot(d[:, 0], d[:, 1])
    e, t = law(name, k, l0, l)
    f = (t / l)[:, None] * d  # dV/dp_j
    g = np.zeros_like(p)
    np.add.at(g, j, f)
    np.add.at(g, i, -f)
    return e.sum(), g.ravel()


def numpy_hessian(x: np.ndarray, bonds, k: float, l0: float) -> np.ndarray:
    """Harmonic: each bond's block ``k n n^T + (t / l)(I - n n^T)``."""
    p = x.reshape(-1, 2)
    h = np.zeros((x.size, x.size))
    for i, j, shift in bonds:
        d = p[j] + shift - p[i]
        l = math.hypot(*d)
        u = d / l
        block = k * np.outer(u, u) + (k * (l - l0) / l) * (np.eye(2) - np.outer(u, u))
        for a, b, s in ((i, i, 1), (j, j, 1), (i, j, -1), (j, i, -1)):
            h[2 * a : 2 * a + 2, 2 * b : 2 * b + 2] += s * block
    return h


def stressed(n: int, l0: float, *, boundary: str = "periodic", law_name: str = "harmonic", k: float = 1.0):
    square = rc.Network.ready("square")
    plain = rc.NetworkModel(square, (n, n), boundary=boundary)
    springs = {p: {"k": k, "rest_length": l0} for p in range(plain.spring_count)}
    return rc.NetworkModel(square, (n, n), boundary=boundary, law=law_name, springs=springs)


@pytest.mark.parametrize("boundary", ["periodic", "free"])
@pytest.mark.parametrize("law_name", ["harmonic", "quartic"])
def test_energy_and_gradient_match_numpy_and_finite_differences(boundary, law_name):
    n, k, l0 = 5, 1.7, 0.93
    model = stressed(n, l0, boundary=boundary, law_name=law_name, k=k)
    bonds = square_bonds(model, n, boundary == "periodic")
    assert len(bonds) == model.spring_count
    rng = np.random.default_rng(3)
    x = model.reference() + 0.05 * rng.standard_normal(model.dof)
    e, g = numpy_energy_gradient(x, bonds, law_name, k, l0)
    assert model.energy(x) == pytest.approx(e, rel=1e-13)
    np.testing.assert_allclose(model.gradient(x), g, rtol=0, atol=1e-13 * np.abs(g).max())
    h = 1e-6
    for i in rng.choice(model.dof, 8, replace=False):
        step = np.zeros(model.dof)
        step[i] = h
        fd = (model.energy(x + step) - model.energy(x - step)) / (2 * h)
        assert fd == pytest.approx(model.gradient(x)[i], abs=1e-8)


def test_modes_match_numpy_eigh_on_a_small_stressed_patch():
    n, l0 = 4, 0.9
    model = stressed(n, l0)
    x = model.reference()
    bonds = square_bonds(model, n, True)
    values = np.linalg.eigh(numpy_hessian(x, bonds, 1.0, l0))[0]
    modes = model.modes(x, 10)
    np.testing.assert_allclose(modes.omega_squared, values[:10], atol=1e-12)
    assert np.all(modes.frequencies == np.sign(modes.omega_squared) * np.sqrt(np.abs(modes.omega_squared)))
    assert modes.vectors.shape == (10, model.dof)


def test_large_patch_modes_take_the_sparse_path_and_match_the_closed_form():
    # 20 x 20 cells, 800 coordinates: beyond DENSE_LIMIT (384), so shift-invert subspace iteration.
    n, l0 = 20, 0.9
    model = stressed(n, l0)
    t = 1.0 - l0
    s = 2 - 2 * np.cos(2 * np.pi * np.arange(n) / n)
    exact = np.sort(np.concatenate([(s[:, None] + t * s[None, :]).ravel(), (t * s[:, None] + s[None, :]).ravel()]))
    modes = model.modes(model.reference(), 14)
    np.testing.assert_allclose(modes.omega_squared, exact[:14], atol=1e-10)
    # And against numpy's dense eigensolver on the numpy Hessian.
    values = np.linalg.eigh(numpy_hessian(model.reference(), square_bonds(model, n, True), 1.0, l0))[0]
    np.testing.assert_allclose(modes.omega_squared, values[:14], atol=1e-10)


def test_relax_and_newton_reach_force_balance():
    model = stressed(12, 0.9)
    rng = np.random.default_rng(5)
    start = model.reference() + 1e-2 * rng.standard_normal(model.dof)
    relaxed, steps = model.relax(start, tolerance=1e-6)
    assert steps > 0 and np.abs(model.gradient(relaxed)).max() < 1e-5
    x = model.newton(start)
    assert np.abs(model.gradient(x)).max() < 1e-13
    # The patch came back to the regular lattice up to a rigid translation.
    d = (x - model.reference()).reshape(-1, 2)
    np.testing.assert_allclose(d - d.mean(axis=0), 0.0, atol=1e-10)


def test_verlet_conserves_energy_and_overrides_show():
    model = stressed(6, 0.9)
    rng = np.random.default_rng(9)
    x = model.reference() + 1e-2 * rng.standard_normal(model.dof)
    run = model.propagate(x, np.zeros(model.dof), t_max=5.0, output_every=10)
    assert run.time == pytest.approx(5.0)
    assert np.ptp(run.energies) < 2e-2 * run.energies[0]
    heavy = rc.NetworkModel(rc.Network.ready("square"), (3, 3), masses={((1, 2), 0): 4.0})
    inertia = heavy.inertia()
    assert sorted(inertia)[-2:] == [4.0, 4.0] and np.count_nonzero(inertia == 1.0) == 16


def test_bad_input_is_refused():
    model = rc.NetworkModel(rc.Network.ready("square"), (3, 3))
    with pytest.raises(ValueError, match="18 coordinates"):
        model.energy(np.zeros(5))
    with pytest.raises(ValueError, match="not finite"):
        model.gradient(np.full(18, np.nan))
    with pytest.raises(ValueError, match="law"):
        rc.NetworkModel(rc.Network.ready("square"), (3, 3), law="cubic")
    with pytest.raises(rc.NetworkError):
        rc.NetworkModel(rc.Network.ready("square"), (3, 3), springs={999: {"k": 1.0}})


def test_ctrl_c_stops_a_network_run():
    import os
    import signal
    import threading
    import time

    class Stopped(Exception):
        pass

    def handler(signum, frame):
        raise Stopped()

    model = rc.NetworkModel(rc.Network.ready("kagome"), (60, 60))
    x = model.reference() + 1e-3
    previous = signal.signal(signal.SIGINT, handler)
    try:
        timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
        start = time.monotonic()
        timer.start()
        with pytest.raises(Stopped):
            model.propagate(x, np.zeros(model.dof), t_max=1e4, output_every=10)
        assert time.monotonic() - start < 10.0
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
