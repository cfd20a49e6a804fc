"""``NetworkModel.maxwell_calladine`` beyond the dense SVD's bound of 512 coordinates (issue 37):
the sparse path's counts against the literature's exact counts of square and kagome patches, its
null vectors against a compatibility matrix written here in numpy from the reference positions,
and Ctrl-C (SIGINT) stops it within half a second."""

from __future__ import annotations

import os
import signal
import threading
import time

import numpy as np
import pytest

import rotor_chain as rc


def square_compatibility(model: rc.NetworkModel, n1: int, n2: int) -> np.ndarray:
    """``C`` of a periodic ``n1 x n2`` square patch at its reference: the row of bond ``(i, j)`` is
    the bond's unit vector on ``u_j`` and minus it on ``u_i``; nodes found by their positions. The
    bonds' order does not matter for the null spaces of ``C`` and the count of ``C^T``'s."""
    ref = model.reference().reshape(-1, 2)
    index = {(round(x), round(y)): k for k, (x, y) in enumerate(ref)}
    assert len(index) == n1 * n2
    rows = []
    for (x, y), i in index.items():
        for dx, dy in ((1, 0), (0, 1)):
            j = index[((x + dx) % n1, (y + dy) % n2)]
            row = np.zeros(2 * n1 * n2)
            row[2 * j : 2 * j + 2] += (dx, dy)
            row[2 * i : 2 * i + 2] -= (dx, dy)
            rows.append(row)
    return np.array(rows)


def test_a_square_patch_above_the_bound_has_one_zero_mode_and_stress_per_line():
    # Periodic N1 x N2 square: N1 + N2 straight lines, each a zero mode and a self-stress
    # (Lubensky et al., Rep. Prog. Phys. 78 (2015), section 5.1).
    n1, n2 = 17, 18
    model = rc.NetworkModel(rc.Network.ready("square"), (n1, n2), boundary="periodic")
    assert model.dof > 512
    counting = model.maxwell_calladine(model.reference())
    assert (counting.n_zero_modes, counting.n_self_stresses) == (n1 + n2, n1 + n2)
    c = square_compatibility(model, n1, n2)
    z = np.asarray(counting.zero_modes)
    assert z.shape == (n1 + n2, model.dof)
    assert np.abs(c @ z.T).max() < 1e-10
    assert np.abs(z @ z.T - np.eye(n1 + n2)).max() < 1e-10
    # numpy's rank of the same C, by its singular values (a dense SVD of 612 x 612).
    assert model.dof - np.linalg.matrix_rank(c) == n1 + n2


def test_a_kagome_patch_above_the_bound_has_its_lines_counts():
    # Periodic kagome N1 x N2: N1 + N2 + gcd(N1, N2) lines (section 5.2).
    model = rc.NetworkModel(rc.Network.ready("kagome"), (10, 12), boundary="periodic")
    assert model.dof > 512
    counting = model.maxwell_calladine(model.reference())
    assert (counting.n_zero_modes, counting.n_self_stresses) == (24, 24)


@pytest.fixture
def python_sigint():
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_ctrl_c_stops_a_network_count_above_the_bound_within_half_a_second(python_sigint):
    model = rc.NetworkModel(rc.Network.ready("kagome"), (40, 40), boundary="periodic")
    x = model.reference()
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.3, send)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            model.maxwell_calladine(x)
        stopped = time.monotonic()
    finally:
        timer.cancel()
    assert sent, "the count ended before the signal was sent: make it larger"
    assert stopped - sent[0] < 0.5, f"stopped {stopped - sent[0]:.3f} s after SIGINT"
