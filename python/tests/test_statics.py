"""Statics through the binding against the Rust library's own results (rotor-chain-reference):
kink, antikink, Peierls-Nabarro minimum and saddle energies (1e-12), modes, Maxwell-Calladine
counts, the continuum; statics errors with their numbers."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import rotor_chain as rc
from conftest import assert_same_object, close

PAPER = dict(n=60, r=0.8, k=1.0e4, theta_bar=0.58)


def chain(spec):
    return rc.Chain(spec["n"], spec["r"], spec["k"], spec["theta_bar"])


@pytest.mark.parametrize("theta_bar", [0.2, 0.45, 0.58])
def test_peierls_nabarro_matches_rust(theta_bar, reference):
    spec = dict(PAPER, theta_bar=theta_bar)
    (ref,) = reference([{"chain": spec, "op": "peierls_nabarro"}])
    ref = ref["ok"]
    pn = chain(spec).peierls_nabarro()
    close(pn.minimum_energy, ref["minimum_energy"], what="minimum")
    close(pn.saddle_energy, ref["saddle_energy"], what="saddle")
    close(pn.barrier, ref["barrier"], rtol=1e-9, what="barrier")  # a difference of two 1e3 numbers
    assert pn.resolved == ref["resolved"]
    close(pn.minimum.theta, ref["minimum_theta"], what="minimum profile")
    close(pn.saddle.theta, ref["saddle_theta"], what="saddle profile")
    if ref["resolved"]:  # wide antikinks (small theta_bar) have a barrier below rounding
        assert (pn.minimum.kind, pn.saddle.kind, pn.saddle.is_saddle) == ("minimum", "saddle", True)
        assert pn.minimum.index == 0 and pn.saddle.index == 1
    # One of the two is the rotor-centred antikink, the other the spring-centred one.
    centres = sorted([pn.rotor_centred.centre, pn.spring_centred.centre])
    assert abs(centres[0] - 29) < 1e-6 and abs(centres[1] - 29.5) < 1e-6


def test_kink_antikink_modes_and_counting_match_rust(reference):
    c = chain(PAPER)
    kink = c.kink(31.25)
    antikink = c.antikink(33.0)
    at_spring = c.antikink(29.5, relaxed=False)
    cases = [
        {"chain": PAPER, "op": "kink", "centre": 31.25},
        {"chain": PAPER, "op": "antikink", "centre": 33.0, "relaxed": True},
        {"chain": PAPER, "op": "antikink", "centre": 29.5, "relaxed": False},
        {"chain": PAPER, "op": "modes", "theta": antikink.theta, "count": 6},
        {"chain": PAPER, "op": "maxwell_calladine", "theta": kink},
        {"chain": PAPER, "op": "maxwell_calladine", "theta": antikink.theta},
        {"chain": PAPER, "op": "continuum"},
    ]
    k, a, s, m, mc_kink, mc_antikink, cont = [r["ok"] for r in reference(cases)]
    close(kink, k["theta"], what="kink")
    assert c.energy(kink) < 1e-20 * 1e4
    assert rc.domain_walls(kink) == [(pytest.approx(31.25, abs=1e-9), "kink")]
    close(antikink.theta, a["theta"], what="antikink")
    close(antikink.energy, a["energy"], what="antikink energy")
    assert antikink.centre == pytest.approx(a["centre"], abs=1e-12)
    close(at_spring.theta, s["theta"], what="antikink at 29.5")
    assert at_spring.index == s["index"] == 1
    modes = c.modes(antikink.theta, 6)
    close(modes.omega_squared, m["omega_squared"], what="omega^2")
    close(modes.frequencies, m["frequencies"], what="frequencies")
    close(np.abs(modes.vectors), np.abs(np.array(m["vectors"])), what="mode shapes")
    assert len(modes) == 6 and "translation" in modes.kinds
    for got, ref in ((c.maxwell_calladine(kink), mc_kink), (c.maxwell_calladine(antikink.theta), mc_antikink)):
        assert (got.rank, got.n_zero_modes, got.n_self_stresses) == (ref["rank"], ref["zero_modes"], ref["self_stresses"])
        assert got.index == 1 == ref["zero_modes"] - ref["self_stresses"]
        close(got.singular_values, ref["singular_values"], what="singular values")
        assert got.zero_modes.shape == (got.n_zero_modes, 60)
        assert got.self_stresses.shape == (got.n_self_stresses, 59)
    continuum = c.continuum()
    close(continuum.antikink_energy, cont["antikink_energy"], what="continuum antikink energy")
    close(continuum.width, cont["width"], what="width")
    close(continuum.sound_speed, cont["sound_speed"], what="sound speed")


def test_statics_errors_carry_the_numbers():
    c = chain(PAPER)
    with pytest.raises(rc.StaticsError) as info:
        c.kink(75.0)
    e = info.value
    assert (e.variant, e.centre, e.n) == ("CentreOutOfRange", 75.0, 60)
    assert isinstance(e, RuntimeError)
    assert str(e) == "centre 75 is outside the chain: it must lie in [0, 59] for 60 rotors"
    with pytest.raises(ValueError, match="ends must be one of 'held', 'free'"):
        c.peierls_nabarro(ends="fixed")


def test_a_kink_wider_than_the_chain_is_an_error_not_a_wall_less_state():
    c = rc.Chain(60, 0.8, 1.0e4, 1e-8)
    with pytest.raises(rc.StaticsError) as info:
        c.kink(29.5)
    e = info.value
    assert (e.variant, e.expected, e.centre, e.theta_bar) == ("NoWall", "kink", 29.5, 1e-8)
    assert "wider than the chain" in str(e)
    assert rc.domain_walls(rc.Chain(60, 0.8, 1.0e4, 0.05).kink(29.5)) == [(pytest.approx(29.5), "kink")]


def test_an_antikink_at_a_fixed_centre_says_what_it_is():
    c = rc.Chain(60, 0.8, 1.0e4, 0.58)
    # Between two centrings there is no equilibrium: refused, with the value.
    with pytest.raises(rc.StaticsError) as info:
        c.antikink(29.25, relaxed=False)
    assert (info.value.variant, info.value.what, info.value.value) == ("InvalidValue", "centre", 29.25)
    # A centring in the middle is a free equilibrium: nothing held, no interior force.
    free = c.antikink(29.5, relaxed=False)
    assert free.held == 0 and np.max(np.abs(c.gradient(free.theta)[1:-1])) < 1e-6
    # At the last spring the ends' pull wins: no equilibrium there, and the error says where the
    # antikink went (inward) instead of returning it as if it were at 58.5.
    with pytest.raises(rc.StaticsError) as info:
        c.antikink(58.5, relaxed=False)
    e = info.value
    assert (e.variant, e.requested) == ("NotAnEquilibrium", 58.5)
    assert e.found < 58.25 and e.held > 0
    assert "held" not in repr(free)


def test_statics_results_pickle_field_by_field():
    c = chain(PAPER)
    pn = c.peierls_nabarro()
    antikink = c.antikink(33.0)
    results = [
        antikink,
        c.antikink(29.5, relaxed=False),
        pn,
        c.modes(antikink.theta, 6),
        c.maxwell_calladine(antikink.theta),
        c.continuum(),
    ]
    for result in results:
        again = pickle.loads(pickle.dumps(result))
        names = assert_same_object(again, result)
        assert len(names) >= 5, names
    again = pickle.loads(pickle.dumps(pn))
    assert {"minimum", "saddle", "rotor_centred", "spring_centred", "barrier", "resolved"} <= set(dir(again))
    # The minimum is one of the two centrings, the same object after unpickling as before.
    assert again.minimum is (again.rotor_centred if pn.minimum is pn.rotor_centred else again.spring_centred)
    modes = pickle.loads(pickle.dumps(results[3]))
    assert len(modes) == 6 and modes.kinds == results[3].kinds
    continuum = pickle.loads(pickle.dumps(c.continuum()))
    assert np.array_equal(continuum.angle_profile("kink", 60, 29.5), c.continuum().angle_profile("kink", 60, 29.5))


def test_a_bad_pickled_state_is_a_value_error():
    with pytest.raises(ValueError, match="the pickled Antikink state has no field `theta`"):
        rc._native._restore("Antikink", {})
    state = pickle.loads(pickle.dumps(chain(PAPER).continuum())).__reduce__()[1][1]
    with pytest.raises(rc.ParameterError) as info:  # the parameters are checked again
        rc._native._restore("Continuum", dict(state, k=-1.0))
    assert (info.value.variant, info.value.key, info.value.value) == ("NotPositive", "k", -1.0)
    with pytest.raises(ValueError, match="has no result class `Chain`"):
        rc._native._restore("Chain", {})


def test_continuum_profile_refuses_what_it_cannot_compute():
    continuum = chain(PAPER).continuum()
    with pytest.raises(rc.ParameterError) as info:  # not an allocation of 8 TB
        continuum.angle_profile("antikink", 10**12, 0.0)
    assert (info.value.variant, info.value.n, info.value.max) == ("TooManyRotors", 10**12, 100_000_000)
    with pytest.raises(ValueError, match="x0 = NaN is not finite"):
        continuum.angle_profile("antikink", 60, float("nan"))


def test_a_copy_that_cannot_be_allocated_is_a_memory_error_not_an_abort():
    """Under an address-space limit, a 1.2 GB argument whose copy does not fit: ``MemoryError``
    with the bytes requested, and the interpreter goes on (an abort would be exit status 134)."""
    import subprocess
    import sys
    import textwrap

    script = textwrap.dedent(
        """
        import resource
        import numpy as np
        import rotor_chain as rc
        from rotor_chain import _native
        theta = np.zeros(150_000_000)                        # 1.2 GB, mapped
        with open("/proc/self/status") as f:
            vm = next(int(l.split()[1]) * 1024 for l in f if l.startswith("VmSize:"))
        # Room for everything already mapped and 0.5 GB more, not for a second copy of theta.
        resource.setrlimit(resource.RLIMIT_AS, (vm + 2**29, resource.RLIM_INFINITY))
        try:
            _native.domain_walls(theta)
        except MemoryError as e:
            print("MemoryError:", e)
        print("still running")
        """
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["MemoryError: cannot allocate 1200000000 bytes to copy theta",
                                        "still running"], done.stdout + done.stderr
