"""The binding's Chain against the Rust library's own numbers (rotor-chain-reference): energies,
gradients, stiffness, lengths, tensions, compatibility and the branch solve to 1e-12; every
builder error with the Rust message and its numbers."""

from __future__ import annotations

import numpy as np
import pytest

import rotor_chain as rc
from rotor_chain import _native
from conftest import close

CHAINS = [
    dict(n=60, r=0.8, k=1.0e4, theta_bar=0.58),
    dict(n=60, r=0.8, k=1.0e4, theta_bar=0.28, springs=[(29, 7.0e3, None)]),
    dict(n=23, r=0.6, k=3.5, theta_bar=0.4, a=1.3, mass=2.5, law="quartic"),
    dict(n=17, r=0.7, k=12.0, theta_bar=0.2, springs=[(3, None, 1.9), (8, 40.0, 1.75)], rotors=[(5, 0.55)]),
    dict(n=2, r=0.45, k=1.0, theta_bar=0.5),
]


def make(spec):
    springs = {p: {key: v for key, v in (("k", k), ("l0", l0)) if v is not None} for p, k, l0 in spec.get("springs", [])}
    rotors = dict(spec.get("rotors", []))
    kwargs = {key: spec[key] for key in ("a", "mass", "law") if key in spec}
    return rc.Chain(spec["n"], spec["r"], spec["k"], spec["theta_bar"], springs=springs, rotors=rotors, **kwargs)


def angles(spec, seed):
    rng = np.random.default_rng(seed)
    n, tb = spec["n"], spec["theta_bar"]
    signs = np.where(np.arange(n) < n // 2, 1.0, -1.0)
    return signs * tb + rng.normal(0.0, 0.15, n)


@pytest.mark.parametrize("spec", CHAINS, ids=lambda s: f"n{s['n']}-{s.get('law', 'harmonic')}")
def test_evaluation_matches_rust(spec, reference):
    chain = make(spec)
    thetas = [angles(spec, seed) for seed in range(4)]
    try:
        thetas.append(chain.kink(0.5 * (spec["n"] - 1)))
    except rc.StaticsError as e:  # a rest-length impurity with no kink through it
        assert e.variant == "Branch" and isinstance(e.__cause__, rc.BranchError)
    results = reference([{"chain": spec, "op": "evaluate", "theta": t} for t in thetas])
    for theta, result in zip(thetas, results):
        ref = result["ok"]
        close(chain.energy(theta), ref["energy"], what="energy")
        close(chain.gradient(theta), ref["gradient"], what="gradient")
        e, g = chain.energy_and_gradient(theta)
        close(e, ref["energy_fused"], what="fused energy")
        close(g, ref["gradient_fused"], what="fused gradient")
        diag, off = chain.tangent_stiffness(theta)
        close(diag, ref["stiffness"]["diag"], what="stiffness diag")
        close(off, ref["stiffness"]["off"], what="stiffness off")
        for name, method in (("material", chain.material_stiffness), ("stress", chain.stress_matrix)):
            d, o = method(theta)
            close(d, ref[name]["diag"], what=name)
            close(o, ref[name]["off"], what=name)
        h = chain.hessian(theta)
        n = spec["n"]
        dense = np.diag(ref["stiffness"]["diag"]) + np.diag(ref["stiffness"]["off"], 1) + np.diag(ref["stiffness"]["off"], -1)
        close(h, dense, what="hessian")
        assert h.shape == (n, n) and np.array_equal(h, h.T)
        close(chain.spring_lengths(theta), ref["spring_lengths"], what="lengths")
        close(chain.tensions(theta), ref["tensions"], what="tensions")
        left, right = chain.compatibility(theta)
        close(left, ref["compatibility"]["left"], what="C left")
        close(right, ref["compatibility"]["right"], what="C right")
        c = chain.compatibility(theta, dense=True)
        assert c.shape == (n - 1, n)
        close(np.diag(c), ref["compatibility"]["left"], what="dense C")
        close(np.diag(c, 1), ref["compatibility"]["right"], what="dense C")
        # Lists and integer-typed arrays are accepted as angles too.
        assert chain.energy(list(theta)) == chain.energy(theta)


def test_properties_and_the_constructor_round_trip():
    spec = CHAINS[3]
    chain = make(spec)
    assert (chain.n_rotors, chain.n_springs, chain.theta_bar, chain.law) == (17, 16, 0.2, "harmonic")
    assert chain.stiffness[8] == 40.0 and chain.stiffness[0] == 12.0
    assert chain.rest_lengths[3] == 1.9 and chain.rotor_lengths[5] == 0.55
    assert np.allclose(chain.inertia, chain.mass * chain.rotor_lengths**2)
    again = eval(repr(chain), {"Chain": rc.Chain})
    theta = angles(spec, 7)
    assert again.energy(theta) == chain.energy(theta)
    import pickle

    assert pickle.loads(pickle.dumps(chain)).energy(theta) == chain.energy(theta)
    assert np.array_equal(chain.uniform(-1), -0.2 * np.ones(17))


@pytest.mark.parametrize("p,theta_p", [(0, 0.3), (10, 0.58), (30, -0.2), (58, 0.1), (20, 1.4)])
def test_branch_solve_matches_rust(p, theta_p, reference):
    spec = CHAINS[0]
    chain = make(spec)
    (result,) = reference([{"chain": spec, "op": "next_angles", "p": p, "theta_p": theta_p}])
    if "ok" in result:
        close(chain.next_angles(p, theta_p), result["ok"]["next"], what="next")
        close(chain.previous_angles(p, theta_p), result["ok"]["previous"], what="previous")
    else:
        with pytest.raises(rc.BranchError) as info:
            chain.next_angles(p, theta_p)
        assert str(info.value) == result["error"]
        assert isinstance(info.value, ValueError)


def test_no_real_root_carries_its_numbers():
    chain = make(CHAINS[0])
    with pytest.raises(rc.BranchError) as info:
        chain.next_angles(3, 1.5)
    e = info.value
    assert e.variant == "NoRealRoot" and e.spring == 3 and e.theta == 1.5
    assert not (e.min <= e.distance <= e.max)
    assert f"distances in [{e.min!r}, {e.max!r}]" in str(e)


BAD = [
    (dict(n=1, r=0.8, k=1e4, theta_bar=0.3), "TooFewRotors", {"n": 1}),
    (dict(n=10, r=-0.8, k=1e4, theta_bar=0.3), "NotPositive", {"key": "r", "value": -0.8}),
    (dict(n=10, r=0.8, k=float("nan"), theta_bar=0.3), "NotPositive", {"key": "k"}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=0.7), "OutsideFlipperPhase", {"theta_bar": 0.7, "r": 0.8}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=-0.1), "OutsideFlipperPhase", {"theta_bar": -0.1}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=0.3, mass=0.0), "NotPositive", {"key": "mass", "value": 0.0}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=0.3, a=0.0), "NotPositive", {"key": "a"}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=0.3, springs=[(9, 1.0, None)]), "IndexOutOfRange", {"index": 9, "count": 9, "kind": "spring"}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=0.3, springs=[(2, None, -1.0)]), "NotPositive", {"key": "l0"}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=0.3, rotors=[(10, 0.5)]), "IndexOutOfRange", {"kind": "rotor", "index": 10}),
    (dict(n=200_000_000, r=0.8, k=1e4, theta_bar=0.3), "TooManyRotors", {"n": 200_000_000, "max": 100_000_000}),
    (dict(n=10, r=0.8, k=1e4, theta_bar=0.3, springs=[(4, None, None)]), "EmptyOverride", {"kind": "spring", "index": 4}),
]


@pytest.mark.parametrize("spec,variant,numbers", BAD, ids=[b[1] + str(k) for k, b in enumerate(BAD)])
def test_builder_errors_are_the_rust_errors(spec, variant, numbers, reference):
    (result,) = reference([{"chain": spec, "op": "build"}])
    with pytest.raises(rc.ParameterError) as info:
        make(spec)
    e = info.value
    assert isinstance(e, ValueError) and isinstance(e, rc.RotorChainError)
    assert str(e) == result["error"]
    assert e.variant == variant
    for name, value in numbers.items():
        assert getattr(e, name) == value, name
        assert e.details[name] == value


def test_python_side_misuse_is_a_clear_value_error():
    chain = make(CHAINS[0])
    with pytest.raises(ValueError, match="theta has 59 values, the chain has 60 rotors"):
        chain.energy(np.zeros(59))
    with pytest.raises(ValueError, match=r"theta\[4\] = NaN is not finite"):
        chain.gradient(np.where(np.arange(60) == 4, np.nan, 0.3))
    with pytest.raises(ValueError, match="law must be one of 'harmonic', 'quartic', got 'cubic'"):
        rc.Chain(10, 0.8, 1e4, 0.3, law="cubic")
    with pytest.raises(ValueError, match="unknown key 'K'"):
        rc.Chain(10, 0.8, 1e4, 0.3, springs={2: {"K": 1.0}})
    with pytest.raises(rc.ParameterError, match="got -3") as info:
        rc.Chain(-3, 0.8, 1e4, 0.3)
    assert info.value.n == -3
    with pytest.raises(rc.ParameterError, match="spring index -1 is out of range"):
        rc.Chain(10, 0.8, 1e4, 0.3, springs={-1: {"k": 1.0}})
    with pytest.raises(rc.ParameterError, match="rotor index 100000000000000000000 is out of range"):
        rc.Chain(10, 0.8, 1e4, 0.3, rotors={10**20: 0.7})
    # A two-rotor chain has one spring, said in the singular.
    with pytest.raises(rc.ParameterError, match="the chain has 1 spring, numbered 0 to 0"):
        rc.Chain(2, 0.8, 1e4, 0.3).next_angles(1, 0.3)
    # An array of another dimension is a ValueError with its shape, as a wrong length is; what is
    # not numbers at all is a TypeError naming the argument.
    with pytest.raises(ValueError, match=r"theta must be a one-dimensional array, got one of shape \(2, 60\)"):
        chain.energy(np.zeros((2, 60)))
    with pytest.raises(ValueError, match=r"omega must be a one-dimensional array, got one of shape \(\)"):
        chain.propagate(np.zeros(60), 0.0, t_max=0.1)
    with pytest.raises(ValueError, match=r"got one of shape \(1, 60\)"):
        rc.domain_walls([[0.3] * 60])
    with pytest.raises(TypeError, match="theta must be an array of real numbers, got str"):
        chain.gradient("sixty angles")


@pytest.mark.parametrize("n", [-1, np.int64(-5), -(10**20), 2**63, 10**20])
def test_a_rotor_count_no_machine_integer_holds_is_the_builders_error_wherever_a_count_is_taken(n):
    # The words Rust gives the same variant for a count it can hold, with n in place of its number.
    small, word = (1, "got {}") if n < 0 else (10**9, "`n` = {} is")
    with pytest.raises(rc.ParameterError) as rust:
        rc.Chain(small, 0.8, 1e4, 0.3)
    expected = str(rust.value).replace(word.format(small), word.format(n))
    assert expected != str(rust.value)
    continuum = rc.Chain(10, 0.8, 1e4, 0.3).continuum()
    for call in (lambda: rc.Chain(n, 0.8, 1e4, 0.3), lambda: continuum.angle_profile("kink", n, 0.0)):
        with pytest.raises(rc.ParameterError) as info:  # not OverflowError
            call()
        assert str(info.value) == expected
        assert (info.value.variant, info.value.n) == (rust.value.variant, n)
    # A phase diagram's settings: chain-sweep's ConfigError around it, worded as Rust words it.
    with pytest.raises(rc.ConfigError) as config:
        _native.PhaseDiagram("kink", n=small)
    with pytest.raises(rc.ConfigError) as info:
        _native.PhaseDiagram("kink", n=n)
    assert str(info.value) == str(config.value).replace(word.format(small), word.format(n))
    assert info.value.variant == "Chain" and str(info.value.__cause__) == expected


def test_a_count_of_modes_is_any_int_that_is_not_negative():
    chain = rc.Chain(10, 0.8, 1e4, 0.3)
    uniform = chain.uniform()
    every = chain.modes(uniform, count=None).frequencies
    assert len(every) == 10
    for count in (10, 10**9, 2**63, 10**20):
        assert np.array_equal(chain.modes(uniform, count=count).frequencies, every)
    assert np.allclose(chain.modes(uniform, count=np.int64(3)).frequencies, every[:3], rtol=1e-9, atol=1e-5)
    for count in (-1, -(10**20)):
        with pytest.raises(ValueError, match=f"a count must be >= 0, got {count}"):
            chain.modes(uniform, count=count)


def test_an_index_out_of_range_is_a_parameter_error_in_every_method(reference):
    spec = CHAINS[0]
    chain = make(spec)
    # The message is the Rust builder's for the same index (a spring override past the end).
    (past_end,) = reference([{"chain": dict(spec, springs=[(59, 1.0, None)]), "op": "build"}])
    calls = {
        "next_angles": lambda p: chain.next_angles(p, 0.3),
        "previous_angles": lambda p: chain.previous_angles(p, 0.3),
        "scatter": lambda p: chain.scatter("antikink", 4.0, p),
    }
    beyond = "spring index {} is out of range: the chain has 59 springs, numbered 0 to 58"
    for name, call in calls.items():
        # Past the end, negative, and beyond every machine integer (no OverflowError); numpy's
        # integers are indices too.
        cases = [(59, past_end["error"])] + [(p, beyond.format(p)) for p in (-1, 10**20, -(10**30), 2**63)]
        cases.append((np.int64(59), past_end["error"]))
        for p, message in cases:
            with pytest.raises(rc.ParameterError) as info:
                call(p)
            e = info.value
            assert not isinstance(e, (rc.BranchError, rc.DynamicsError)), name
            assert str(e) == message, name
            assert (e.variant, e.kind, e.index, e.count) == ("IndexOutOfRange", "spring", p, 59), name
    # The last spring is in range; a branch solve there without a root is still a BranchError.
    assert len(chain.next_angles(58, 0.1)) == len(chain.previous_angles(58, 0.1)) == 2
    with pytest.raises(rc.BranchError):
        chain.next_angles(58, 1.5)


def test_a_dense_result_past_the_dense_bound_is_an_error_before_any_allocation():
    # The statics' bound on dense results, 2**26 values (512 MiB): 8 192 rotors' Hessian is the
    # largest; 8 193 rotors' (or 100 001 rotors', 80 GB) is refused before anything is allocated.
    assert rc.Chain(2000, 0.8, 1.0e4, 0.58).hessian(np.full(2000, 0.58)).shape == (2000, 2000)
    for n in (8193, 100_001):
        chain = rc.Chain(n, 0.8, 1.0e4, 0.58)
        theta = chain.uniform()
        with pytest.raises(rc.StaticsError) as info:
            chain.hessian(theta)
        e = info.value
        assert (e.variant, e.what, e.value, e.max) == ("TooLarge", "hessian: rotors x rotors", n * n, 2**26)
        with pytest.raises(rc.StaticsError) as info:
            chain.compatibility(theta, dense=True)
        assert (info.value.value, info.value.max) == ((n - 1) * n, 2**26)
        # The banded form of the same chain still works.
        left, right = chain.compatibility(theta)
        assert left.shape == right.shape == (n - 1,)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: rc.Chain(60, 0.8, 1e4, "0.58"), "`theta_bar` must be a real number, got '0.58' (str)"),
        (lambda: rc.Chain(60, 0.8, 1e4, 0.58, mass=None), "`mass` must be a real number, got None (NoneType)"),
        (lambda: rc.Chain(60.0, 0.8, 1e4, 0.58), "`n` must be an int (a number of rotors), got 60.0 (float)"),
        (lambda: rc.Chain(True, 0.8, 1e4, 0.58), "`n` must be an int (a number of rotors), got True (bool)"),
        (lambda: rc.Chain(60, 0.8, 1e4, 0.58).launch("kink", "45", 1.0), "`position` must be a real number, got '45' (str)"),
        (lambda: rc.Chain(60, 0.8, 1e4, 0.58).energy(None), "theta must be an array of real numbers, got None"),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58).energy(np.full(60, 0.58) + 1j),
            "theta must be an array of real numbers, got ndarray of dtype complex128",
        ),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58).gradient([0.58 + 0j] * 60),
            "theta must be an array of real numbers, got list of dtype complex128",
        ),
        (lambda: rc.Chain(60, 0.8, 1e4, 0.58).next_angles(3, "0.5"), "`theta_p` must be a real number, got '0.5' (str)"),
        (lambda: rc.Chain(60, 0.8, 1e4, 0.58).previous_angles(3, None), "`theta_next` must be a real number, got None (NoneType)"),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58).propagate(np.full(60, 0.58), np.zeros(60), t_max="1"),
            "`t_max` must be a real number, got '1' (str)",
        ),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58).propagate(np.full(60, 0.58), np.zeros(60), dt=[0.01]),
            "`dt` must be a real number, got [0.01] (list)",
        ),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58, springs={29: {"k": "7e3"}}),
            "`springs[29]['k']` must be a real number, got '7e3' (str)",
        ),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58, springs={3: {"k": 7e3, "l0": None}}),
            "`springs[3]['l0']` must be a real number, got None (NoneType)",
        ),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58, springs={3: {1: 7e3}}),
            "springs[3]: a key must be 'k' or 'l0', got 1 (int)",
        ),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58, rotors={7: [0.7]}),
            "`rotors[7]` must be a real number, got [0.7] (list)",
        ),
        (lambda: rc.Chain(60, 0.8, 1e4, 0.58).scatter("kink", "4"), "`v0` must be a real number, got '4' (str)"),
        (
            lambda: rc.Chain(60, 0.8, 1e4, 0.58).scatter("kink", 4.0, start="44.5"),
            "`start` must be a real number, got '44.5' (str)",
        ),
    ],
)
def test_an_argument_of_the_wrong_type_is_a_type_error_that_names_it(call, message):
    with pytest.raises(TypeError) as info:
        call()
    assert str(info.value) == message
    assert not isinstance(info.value, rc.RotorChainError)


def test_a_complex_array_is_refused_not_cast_to_its_real_part():
    import warnings

    chain = rc.Chain(60, 0.8, 1e4, 0.58)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's ComplexWarning of a silent cast would fail here
        with pytest.raises(TypeError, match="theta must be an array of real numbers"):
            chain.energy(chain.kink(29.5) + 0j)
    # Integer arrays are still read as numbers.
    assert chain.energy(np.zeros(60, dtype=np.int64)) == chain.energy(np.zeros(60))
