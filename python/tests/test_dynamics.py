"""Dynamics through the binding against the Rust library's own runs (rotor-chain-reference):
launch, propagation with Verlet and DOP853, and the paper's five named scattering points, with
identical outcomes and decision times; dynamics errors with their numbers."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

import rotor_chain as rc
from conftest import assert_same_object, close

BASE = dict(n=60, r=0.8, k=1.0e4, theta_bar=0.28)

# The paper's named points (Sec. VI; docs/dynamics.md §5): defect, v0, k_i/k, the paper's outcome.
NAMED = [
    ("kink", 4.0, 0.10, "transmitted"),
    ("kink", 9.6, 0.01, "split"),
    ("antikink", 4.0, 0.80, "transmitted"),
    ("antikink", 4.0, 0.70, "trapped"),
    ("antikink", 4.8, 0.20, "reflected"),
]


def with_impurity(ki):
    spec = dict(BASE, springs=[(29, ki * BASE["k"], None)])
    return spec, rc.Chain(60, 0.8, 1.0e4, 0.28, springs={29: {"k": ki * 1.0e4}})


def test_launch_and_propagate_match_rust(reference):
    c = rc.Chain(60, 0.8, 1.0e4, 0.28)
    launches = [c.launch("kink", 44.0, 4.0), c.launch("antikink", 40.0, 2.5, "right")]
    cases = [
        {"chain": BASE, "op": "launch", "defect": "kink", "position": 44.0, "v0": 4.0, "direction": "left"},
        {"chain": BASE, "op": "launch", "defect": "antikink", "position": 40.0, "v0": 2.5, "direction": "right"},
    ]
    for launch, ref in zip(launches, reference(cases)):
        ref = ref["ok"]
        close(launch.theta, ref["theta"], what="theta")
        close(launch.omega, ref["omega"], what="omega")
        close(launch.mode, ref["mode"], what="mode")
        assert launch.position == pytest.approx(ref["position"], abs=1e-12)
    kink = launches[0]
    runs = [
        c.propagate(kink.theta, kink.omega, t_max=1.5),
        c.propagate(kink.theta, kink.omega, t_max=0.5, method="dop853"),
        c.propagate(kink.theta, kink.omega, t_max=1.0, damping=0.5, absorbing_ends=True),
    ]
    cases = [
        dict(op="propagate", t_max=1.5, method="verlet", damping=0.0, absorbing_ends=False),
        dict(op="propagate", t_max=0.5, method="dop853", damping=0.0, absorbing_ends=False),
        dict(op="propagate", t_max=1.0, method="verlet", damping=0.5, absorbing_ends=True),
    ]
    refs = reference([dict(case, chain=BASE, theta=kink.theta, omega=kink.omega) for case in cases])
    for run, ref in zip(runs, refs):
        ref = ref["ok"]
        assert run.integrator == ref["integrator"] and run.steps == ref["steps"]
        close(run.times, ref["times"], what="times")
        close(run.kinetic, ref["kinetic"], what="kinetic energy")
        close(run.theta, ref["theta"], what="final theta")
        close(run.omega, ref["omega"], what="final omega")
        close(run.energy_final, ref["energy_final"], what="final energy")
        close(run.relative_energy_error, ref["relative_energy_error"], what="energy error")
        assert [[(round(p, 9), q) for p, q in w] for w in run.walls] == [
            [(round(p, 9), q) for p, q in w] for w in ref["walls"]
        ]
        assert run.wall_counts.shape == (len(ref["times"]), 2)
        assert run.wall_counts.dtype == np.int64, "counts are integers"
        assert run.wall_counts.tolist() == [
            [sum(q == "kink" for _, q in w), sum(q == "antikink" for _, q in w)] for w in run.walls
        ]


@pytest.mark.parametrize("defect,v0,ki,paper", NAMED)
def test_the_papers_named_points_scatter_as_in_rust(defect, v0, ki, paper, reference):
    spec, c = with_impurity(ki)
    got = c.scatter(defect, v0, 29)
    (ref,) = reference(
        [{"chain": spec, "op": "scatter", "defect": defect, "v0": v0, "impurity": 29, "method": "verlet", "absorbing_ends": False}]
    )
    ref = ref["ok"]
    assert got.outcome == ref["outcome"] == paper
    assert got.decided_at == ref["decided_at"]
    assert (got.confirmed, got.later, got.later_at) == (ref["confirmed"], ref["later"], ref["later_at"])
    close(got.run.theta, ref["run"]["theta"], what="final state")
    close(got.run.kinetic, ref["run"]["kinetic"], what="kinetic energy")


def test_dynamics_errors_carry_the_numbers():
    c = rc.Chain(60, 0.8, 1.0e4, 0.28)
    with pytest.raises(rc.DynamicsError) as info:
        c.launch("kink", 44.0, -1.0)
    assert (info.value.variant, info.value.v0) == ("BadSpeed", -1.0)
    theta = c.kink(40.0)
    with pytest.raises(rc.IntegrateError) as info:
        c.propagate(theta, np.zeros(60), dt=-1e-3)
    e = info.value
    assert isinstance(e, rc.DynamicsError) and e.variant == "InvalidOption"
    assert (e.name, e.value, e.rule) == ("dt", -1e-3, "positive and finite")
    # A step 30 times the stability limit breaks the energy limit: the numbers say when and how much.
    fast = c.launch("kink", 44.0, 6.0)
    with pytest.raises(rc.IntegrateError) as info:
        c.propagate(fast.theta, fast.omega, t_max=2.0, output_interval=0.1, dt=0.05)
    e = info.value
    assert e.variant in ("EnergyNotConserved", "NotFinite"), e
    if e.variant == "EnergyNotConserved":
        assert e.relative > e.limit == 0.1 and 0 < e.time <= 2.0
    with pytest.raises(ValueError, match="method must be one of 'verlet', 'dop853'"):
        c.propagate(theta, np.zeros(60), method="rk4")
    # An impurity past the last spring is an index out of range, as for every method (test_chain.py).
    with pytest.raises(rc.ParameterError) as info:
        c.scatter("kink", 4.0, 60)
    assert (info.value.variant, info.value.kind, info.value.index, info.value.count) == ("IndexOutOfRange", "spring", 60, 59)


def test_options_of_the_other_method_are_refused():
    c = rc.Chain(30, 0.8, 1.0e4, 0.28)
    theta, omega = c.kink(15.0), np.zeros(30)
    with pytest.raises(ValueError, match="dt = 0.001 applies to method='verlet' only"):
        c.propagate(theta, omega, t_max=0.1, method="dop853", dt=1e-3)
    for name in ("rtol", "atol"):
        with pytest.raises(ValueError, match=f"{name} = -5.0 applies to method='dop853' only"):
            c.propagate(theta, omega, t_max=0.1, **{name: -5.0})
    # Each with its own method runs, and a bad tolerance is DOP853's InvalidOption.
    assert c.propagate(theta, omega, t_max=0.1, method="dop853", rtol=1e-8, atol=1e-9).time >= 0.1
    assert c.propagate(theta, omega, t_max=0.1, dt=1e-3).time >= 0.1
    with pytest.raises(rc.IntegrateError) as info:
        c.propagate(theta, omega, t_max=0.1, method="dop853", atol=-1.0)
    assert (info.value.variant, info.value.options, info.value.name) == ("InvalidOption", "RunOptions", "method.atol")


def test_a_run_ends_at_the_first_output_at_or_past_t_max_with_steps_of_at_most_dt():
    c = rc.Chain(30, 0.8, 1.0e4, 0.28)
    theta, omega = c.kink(15.0), np.zeros(30)
    run = c.propagate(theta, omega, t_max=1.0, output_interval=0.3)
    assert run.times[-1] == pytest.approx(1.2) and run.time == pytest.approx(1.2)
    assert np.allclose(np.diff(run.times), 0.3)
    # dt = 0.03 over intervals of 0.01: one step of 0.01 per output (100 for t = 1); dt = 0.004:
    # three steps of 1/300 per output.
    assert c.propagate(theta, omega, t_max=1.0, dt=0.03).steps == 100
    assert c.propagate(theta, omega, t_max=1.0, dt=0.004).steps == 300


def test_a_space_time_image_beyond_its_budget_is_an_error_before_the_run():
    c = rc.Chain(2000, 0.8, 1.0e4, 0.28)
    with pytest.raises(rc.IntegrateError) as info:
        c.propagate(c.kink(1000.0), np.zeros(2000), t_max=100.0, output_interval=1e-3, space_time=True)
    e = info.value
    assert (e.variant, e.outputs, e.rotors, e.budget) == ("SpaceTimeBudget", 100_001, 2000, 2**27)
    assert e.values == 100_001 * 2000 and "leave space_time off" in str(e)


@pytest.mark.parametrize("call", ["propagate", "scatter"])
def test_ctrl_c_stops_a_run_at_its_next_output(call):
    import os
    import signal
    import threading
    import time

    class Stopped(Exception):
        pass

    def handler(signum, frame):
        raise Stopped()

    c = rc.Chain(20000, 0.8, 1.0e4, 0.28)
    theta, omega = c.kink(10000.0), np.zeros(20000)
    previous = signal.signal(signal.SIGINT, handler)
    try:
        timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
        start = time.monotonic()
        timer.start()
        with pytest.raises(Stopped):
            # About a minute of work at ~1e5 steps per second of 20 000 rotors; the kink at rest
            # meets nothing, so the scattering run is undecided until t_max.
            if call == "propagate":
                c.propagate(theta, omega, t_max=1e3, output_interval=0.01)
            else:
                c.scatter("kink", 0.0, t_max=1e3)
        assert time.monotonic() - start < 10.0
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)


@pytest.mark.parametrize("t_max", [float("nan"), float("inf"), -1.0])
def test_a_bad_t_max_is_named_as_the_user_passed_it(t_max):
    c = rc.Chain(60, 0.8, 1.0e4, 0.28)
    calls = {
        "propagate": lambda: c.propagate(c.kink(40.0), np.zeros(60), t_max=t_max),
        "scatter": lambda: c.scatter("antikink", 4.0, t_max=t_max),
    }
    for name, call in calls.items():
        with pytest.raises(rc.IntegrateError) as info:
            call()
        e = info.value
        assert "[0]" not in str(e), name
        if math.isfinite(t_max):  # before the start, t = 0
            assert (e.variant, e.start, e.end) == ("EndBeforeStart", 0.0, t_max), name
        else:
            assert (e.variant, e.name, e.rule) == ("InvalidOption", "t_max", "finite"), name
            assert str(e).startswith(f"RunOptions.t_max = {'NaN' if math.isnan(t_max) else 'inf'} is invalid"), str(e)
            assert e.value == t_max or (math.isnan(e.value) and math.isnan(t_max))


def test_dynamics_results_pickle_field_by_field():
    spec, c = with_impurity(0.7)
    launch = c.launch("antikink", 44.5, 4.0)
    run = c.propagate(launch.theta, launch.omega, t_max=0.3)
    with_space_time = c.propagate(launch.theta, launch.omega, t_max=0.3, method="dop853", space_time=True)
    scattering = c.scatter("antikink", 4.0, 29)
    assert scattering.outcome == "trapped" and run.space_time is None and with_space_time.space_time.shape[1] == 60
    for result, fields in (
        (launch, {"theta", "omega", "mode", "position", "defect"}),
        (run, {"times", "kinetic", "walls", "wall_counts", "violations", "space_time", "steps", "integrator"}),
        (with_space_time, {"space_time", "rejected", "energy_initial", "energy_final", "max_energy_error"}),
        (scattering, {"outcome", "decided_at", "confirmed", "later", "later_at", "run"}),
    ):
        copy = pickle.loads(pickle.dumps(result))
        names = assert_same_object(copy, result)
        if result is run:
            assert copy.wall_counts.dtype == np.int64
        assert fields <= set(names), fields - set(names)
