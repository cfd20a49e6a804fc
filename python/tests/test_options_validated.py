"""Every keyword argument that sets a field of a Rust options struct is validated by that struct's
``Validate`` (issue 37): an invalid value raises the family's ``...OptionError``, which is an
``InvalidOptionError`` and a ``ValueError``, naming the struct (``options``), the field (``name``)
and the value, with the Rust text (numbers short: ``5e-324``, ``1e300``). Each call below is the
public entry point; each keyword is given its invalid values."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotor_chain as rc
from rotor_chain import _native

NAN, INF = math.nan, math.inf
TINY = 5e-324
POSITIVE = [NAN, INF, -INF, -1.0, -TINY, 0.0]
NON_NEGATIVE = [NAN, INF, -INF, -1.0, -TINY]


def refused(call, options, field, value, family):
    """``call()`` raises ``family``'s option error naming ``options.field = value``."""
    with pytest.raises(ValueError) as info:
        call()
    e = info.value
    assert isinstance(e, rc.InvalidOptionError) and isinstance(e, family), repr(e)
    assert (e.options, e.name) == (options, field), str(e)
    assert e.value == value or (math.isnan(e.value) and math.isnan(value)), str(e)
    assert f"{options}.{field} = " in str(e), str(e)


@pytest.fixture(scope="module")
def chain():
    return rc.Chain(60, 0.8, 1.0e4, 0.28)


@pytest.fixture(scope="module")
def kink_state(chain):
    theta = chain.kink(30.0)
    return theta, np.zeros_like(theta)


PROPAGATE = [
    # keyword, invalid values, the RunOptions field, extra keywords
    ("t_max", [NAN, INF, -INF], "t_max", {}),
    ("output_interval", POSITIVE, "output_interval", {}),
    ("dt", POSITIVE, "dt", {}),
    ("damping", NON_NEGATIVE, "damping", {}),
    ("energy_limit", [NAN, -INF, -1.0, 0.0], "energy_limit", {}),
    ("rtol", NON_NEGATIVE, "method.rtol", {"method": "dop853"}),
    ("atol", POSITIVE, "method.atol", {"method": "dop853"}),
]


@pytest.mark.parametrize("keyword, bad, field, extra", PROPAGATE)
def test_every_run_option_of_propagate_is_validated(chain, kink_state, keyword, bad, field, extra):
    theta, omega = kink_state
    for value in bad:
        call = lambda: chain.propagate(theta, omega, t_max=0.1, **{**extra, keyword: value})  # noqa: E731
        if keyword == "t_max":
            call = lambda: chain.propagate(theta, omega, **{keyword: value})  # noqa: E731
        refused(call, "RunOptions", field, value, rc.IntegrateError)


def test_every_setup_keyword_of_scatter_is_validated(chain):
    for value in NON_NEGATIVE:
        refused(lambda: chain.scatter("kink", value, 29), "ScatterSetup", "v0", value, rc.DynamicsError)
    for value in [NAN, INF, -INF]:
        refused(lambda: chain.scatter("kink", 2.0, 29, start=value), "ScatterSetup", "start", value, rc.DynamicsError)
    # `watch` is a window: non-negative (the chain's time unit is 1 here, so the value is as given).
    for value in NON_NEGATIVE:
        refused(lambda: chain.scatter("kink", 2.0, 29, watch=value), "ScatterSetup", "watch", value, rc.DynamicsError)
    for value in [NAN, INF]:
        refused(lambda: chain.scatter("kink", 2.0, 29, t_max=value), "RunOptions", "t_max", value, rc.IntegrateError)
    for value in POSITIVE:
        refused(lambda: chain.scatter("kink", 2.0, 29, dt=value), "RunOptions", "dt", value, rc.IntegrateError)


def test_the_network_models_keywords_are_validated():
    model = rc.NetworkModel(rc.Network.ready("square"), (3, 3))
    x = model.reference()
    for value in POSITIVE:
        refused(lambda: model.relax(x, tolerance=value), "RelaxOptions", "tolerance", value, rc.StaticsError)
        refused(lambda: model.newton(x, tolerance=value), "NewtonOptions", "tolerance", value, rc.StaticsError)
        refused(
            lambda: model.propagate(x, np.zeros_like(x), t_max=0.1, dt=value),
            "VerletOptions",
            "dt",
            value,
            rc.IntegrateError,
        )
    for value in NON_NEGATIVE:
        call = lambda: model.propagate(x, np.zeros_like(x), t_max=0.1, dt=1e-2, damping=value)  # noqa: E731
        refused(call, "VerletOptions", "damping", value, rc.IntegrateError)
    for value in [NAN, -1.0, 0.0]:
        call = lambda: model.propagate(x, np.zeros_like(x), t_max=0.1, dt=1e-2, energy_limit=value)  # noqa: E731
        refused(call, "VerletOptions", "energy_limit", value, rc.IntegrateError)
    call = lambda: model.propagate(x, np.zeros_like(x), t_max=0.1, dt=1e-2, output_every=0)  # noqa: E731
    refused(call, "verlet", "output_every", 0.0, rc.IntegrateError)


def test_the_network_models_counts_are_bounded():
    """The counts' documented ranges (chain-core's ``Fields::count_in``): a relaxation's steps at
    most ``MAX_STEP_BUDGET`` = 10**10, Newton's iterations at most 1000, the modes at most
    ``MAX_DENSE_VALUES`` = 2**26; the bound itself is not refused by the validation."""
    model = rc.NetworkModel(rc.Network.ready("square"), (3, 3))
    x = model.reference()
    refused(lambda: model.relax(x, max_steps=10**10 + 1), "RelaxOptions", "max_steps", 1e10 + 1, rc.StaticsError)
    refused(lambda: model.newton(x, max_iterations=1001), "NewtonOptions", "max_iterations", 1001.0, rc.StaticsError)
    refused(lambda: model.modes(x, count=2**26 + 1), "ModeOptions", "count", 2.0**26 + 1, rc.StaticsError)
    # At the bounds: the reference is already relaxed and balanced, so these return at once.
    assert model.relax(x, max_steps=10**10)[0].shape == x.shape
    assert model.newton(x, max_iterations=1000).shape == x.shape
    assert model.newton(x, max_iterations=0).shape == x.shape
    with pytest.raises(rc.errors.StaticsOptionError, match=r"NewtonOptions\.max_iterations = 1001 is invalid: it must be between 0"):
        model.newton(x, max_iterations=1001)


def test_a_chains_mode_count_means_at_most():
    """``Chain.modes(count=...)`` is "at most": a count past the chain's modes gives them all,
    however large (it is clamped to n before ModeOptions' bound)."""
    chain = rc.Chain(8, 0.8, 1.0e4, 0.28)
    theta = chain.kink(4.0)
    assert len(chain.modes(theta, count=10**30).frequencies) == 8


def test_a_thread_count_is_an_invalid_sweep_option():
    """``SweepOptions.threads`` between 1 and ``max_threads()`` (4 per core): 0 and the bound + 1
    raise ``SweepOptionError`` (a ``SweepError`` and an ``InvalidOptionError``) with this
    machine's ``max`` and ``cores``, before any point."""
    d = _native.PhaseDiagram("antikink")
    most = _native.max_threads()
    for threads in (0, most + 1, 10**20):
        with pytest.raises(rc.InvalidOptionError) as info:
            d.compute_points([(0, 0, 0.5, 1.0)], threads)
        e = info.value
        assert isinstance(e, rc.SweepError) and isinstance(e, ValueError), repr(e)
        assert isinstance(e, rc.errors.SweepOptionError), repr(e)
        assert (e.options, e.name, e.value) == ("SweepOptions", "threads", float(threads)), str(e)
        assert e.details["max"] == most and e.details["cores"] >= 1, e.details
        assert str(e).startswith("SweepOptions.threads = "), str(e)
        assert f"; at most {most} on this machine" in str(e), str(e)


def test_a_strips_keywords_are_validated():
    net = rc.Network.ready("deformed-kagome", 0.1, 0.1, -0.1, 0.0)
    for value in [NAN, INF, -INF]:
        refused(lambda: net.strip(1, 20, value), "Strip", "q", value, rc.NetworkError)
    refused(lambda: net.strip(1, 0), "Strip", "cells", 0.0, rc.NetworkError)
    # At most MAX_STRIP_DOF = 4000 cells.
    refused(lambda: net.strip(1, 4001), "Strip", "cells", 4001.0, rc.NetworkError)


PHASE_DIAGRAM = [
    ("mass", POSITIVE),
    ("energy_tolerance", POSITIVE),
    ("t_max", POSITIVE),
    ("dt", POSITIVE),
    ("impurity_rest_length", POSITIVE),
    ("start", [NAN, INF, -INF]),
    ("damping", NON_NEGATIVE),
]


@pytest.mark.parametrize("keyword, bad", PHASE_DIAGRAM)
def test_every_phase_diagram_keyword_is_validated(keyword, bad):
    for value in bad:
        refused(lambda: _native.PhaseDiagram("kink", **{keyword: value}), "PhaseDiagram", keyword, value, rc.ConfigError)


def test_numbers_print_short(chain, kink_state):
    theta, omega = kink_state
    with pytest.raises(rc.InvalidOptionError, match=r"RunOptions\.dt = -5e-324 is invalid") as info:
        chain.propagate(theta, omega, dt=-TINY)
    assert "000000" not in str(info.value)
    with pytest.raises(rc.InvalidOptionError, match=r"ScatterSetup\.start = 1e300 is invalid"):
        chain.scatter("kink", 2.0, 29, start=1e300)
