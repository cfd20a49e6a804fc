"""Ctrl-C (SIGINT) stops the long static analyses within half a second (issue 37): the
Maxwell-Calladine count and the modes ask Python's signal handlers between the iterations of their
eigensolvers (QL, bisection, inverse iteration), as the runs do between outputs."""

import os
import signal
import threading
import time

import pytest

import rotor_chain as rc


@pytest.fixture
def python_sigint():
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def _count():
    # 60 000 rotors: the QL iteration on B B^T alone is O(n^2), about a minute in the debug build
    # the tests use (1.4 s in release at n = 8192).
    c = rc.Chain(60000, 0.8, 1.0e4, 0.58)
    theta = c.kink(24000.3)
    return lambda: c.maxwell_calladine(theta)


def _all_modes():
    # Every mode of 3000 rotors: the QL iteration with vectors, O(n^3), tens of seconds in debug.
    c = rc.Chain(3000, 0.8, 1.0e4, 0.58)
    theta = c.kink(1200.3)
    return lambda: c.modes(theta, count=None)


@pytest.mark.parametrize("make", [_count, _all_modes], ids=["maxwell_calladine", "modes"])
def test_ctrl_c_stops_the_count_and_the_modes_within_half_a_second(make, python_sigint):
    call = make()
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.3, send)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
        stopped = time.monotonic()
    finally:
        timer.cancel()
    assert sent, "the call ended before the signal was sent: make it longer"
    assert stopped - sent[0] < 0.5, f"stopped {stopped - sent[0]:.3f} s after SIGINT"
