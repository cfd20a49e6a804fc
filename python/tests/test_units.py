"""Units of the Python surface: ``Chain``'s keyword parameters (``a``, ``mass``, ``springs``,
``rotors``, ``law``) and the arguments that carry a unit (``v0`` in length per ``t``; ``t_max``,
``output_interval``, ``dt`` in ``t``; ``damping`` in ``1/t``; ``x0`` of ``angle_profile`` a
length) must make every result covariant under lengths x L, stiffnesses x K and mass x m:
angles unchanged, lengths x L, tensions x K L, energies, gradients and stiffnesses x K L^2,
inertia x m L^2, times x T = sqrt(m/K), frequencies x 1/T, speeds x L/T. Each expected value is
the unscaled chain's result times its factor (tests/units_covariance.rs checks the Rust API).

The audit that added this file found ``Chain.scatter`` and the phase diagrams not covariant under
K or m (their rules' windows, output interval and sponge were fixed in t); they now take the
chain's time unit ``sqrt(1e4 mass / k)`` and are checked here."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotor_chain as rc
from rotor_chain import sweep

N, A, R, K, MASS, THETA_BAR = 48, 1.7, 1.36, 3.3e3, 2.5, 0.5
LBAR = math.sqrt(A * A + 4.0 * (R * math.cos(THETA_BAR)) ** 2)
# (L, K, m): each scaling alone, then all three.
UNITS = [(2.3, 1.0, 1.0), (1.0, 7.1, 1.0), (1.0, 1.0, 0.37), (0.6, 43.0, 3.1)]
NONE = (1.0, 1.0, 1.0)


def make(units, law="harmonic"):
    l, k, m = units
    return rc.Chain(
        N,
        R * l,
        K * k,
        THETA_BAR,
        a=A * l,
        mass=MASS * m,
        law=law,
        springs={8: {"k": 0.3 * K * k}, 38: {"l0": 1.02 * LBAR * l}},
        rotors={30: 1.2 * l},
    )


def scaled(got, unscaled, factor, rtol=1e-10, what=""):
    """``got == factor * unscaled`` to ``rtol`` of the largest expected entry, which must not be 0."""
    g, e = np.asarray(got, dtype=float), factor * np.asarray(unscaled, dtype=float)
    assert g.shape == e.shape, f"{what}: shape {g.shape} != {e.shape}"
    size = float(np.max(np.abs(e)))
    assert size > 0.0 and math.isfinite(size), f"{what}: nothing to compare"
    err = float(np.max(np.abs(g - e)))
    assert err <= rtol * size, f"{what}: off by {err / size:.2e}"


def factors(units):
    l, k, m = units
    t = math.sqrt(m / k)
    return dict(length=l, tension=k * l, energy=k * l * l, inertia=m * l * l, time=t, rate=1.0 / t, speed=l / t)


@pytest.mark.parametrize("law", ["harmonic", "quartic"])
@pytest.mark.parametrize("units", UNITS)
def test_evaluations_follow_the_constructors_units(units, law):
    c0, c = make(NONE, law), make(units, law)
    f = factors(units)
    theta = c0.kink(19.3) + 0.07 * np.sin(0.9 * np.arange(N))
    e = f["energy"]
    cases = [
        ("energy", c.energy(theta), c0.energy(theta), e),
        ("gradient", c.gradient(theta), c0.gradient(theta), e),
        ("hessian", c.hessian(theta), c0.hessian(theta), e),
        ("fused gradient", c.energy_and_gradient(theta)[1], c0.energy_and_gradient(theta)[1], e),
        ("spring lengths", c.spring_lengths(theta), c0.spring_lengths(theta), f["length"]),
        ("tensions", c.tensions(theta), c0.tensions(theta), f["tension"]),
        ("compatibility", c.compatibility(theta, dense=True), c0.compatibility(theta, dense=True), 1.0),
        ("inertia", c.inertia, c0.inertia, f["inertia"]),
        ("rotor lengths", c.rotor_lengths, c0.rotor_lengths, f["length"]),
        ("rest lengths", c.rest_lengths, c0.rest_lengths, f["length"]),
        ("stiffness", c.stiffness, c0.stiffness, units[1]),
        ("a", c.a, c0.a, f["length"]),
        ("mass", c.mass, c0.mass, units[2]),
        ("next angles", c.next_angles(5, 0.3), c0.next_angles(5, 0.3), 1.0),
        ("kink", c.kink(31.25), c0.kink(31.25), 1.0),
    ]
    for name in ["tangent_stiffness", "material_stiffness", "stress_matrix"]:
        for band, band0 in zip(getattr(c, name)(theta), getattr(c0, name)(theta)):
            cases.append((name, band, band0, e))
    for what, got, base, factor in cases:
        scaled(got, base, factor, what=f"{what}, {units}")


@pytest.mark.parametrize("units", UNITS)
def test_continuum_getters_and_statics(units):
    c0, c = make(NONE), make(units)
    f = factors(units)
    k0, k1 = c0.continuum(), c.continuum()
    for what, factor in [
        ("antikink_energy", f["energy"]),
        ("pn_barrier", f["energy"]),
        ("width", f["length"]),
        ("rest_length", f["length"]),
        ("l_critical", f["length"]),
        ("sound_speed", f["speed"]),
        ("phonon_band_edges", f["rate"]),
    ]:
        scaled(getattr(k1, what), getattr(k0, what), factor, what=f"{what}, {units}")
    profile = k1.angle_profile("antikink", 30, 14.3 * c.a)
    scaled(profile, k0.angle_profile("antikink", 30, 14.3 * c0.a), 1.0, what=f"angle_profile, {units}")

    theta = c0.kink(23.5)
    m0, m1 = c0.modes(theta, 6), c.modes(theta, 6)
    scaled(m1.frequencies[1:], m0.frequencies[1:], f["rate"], what=f"frequencies, {units}")
    scaled(m1.omega_squared[1:], m0.omega_squared[1:], f["rate"] ** 2, what=f"omega^2, {units}")
    scaled(m1.positions, m0.positions, 1.0, rtol=1e-8, what=f"positions, {units}")
    assert m1.kinds == m0.kinds, f"kinds, {units}"
    pn0, pn = c0.peierls_nabarro(), c.peierls_nabarro()
    assert pn0.resolved and pn.resolved
    scaled(pn.barrier, pn0.barrier, f["energy"], rtol=1e-9, what=f"barrier, {units}")
    scaled(pn.minimum.theta, pn0.minimum.theta, 1.0, rtol=1e-9, what=f"antikink, {units}")
    counting0, counting = c0.maxwell_calladine(theta), c.maxwell_calladine(theta)
    assert counting.rank == counting0.rank
    scaled(counting.singular_values, counting0.singular_values, 1.0, what=f"singular values, {units}")


@pytest.mark.parametrize("units", UNITS)
@pytest.mark.parametrize("defect", ["kink", "antikink"])
def test_launch_and_propagate_take_speeds_and_times_in_their_units(units, defect):
    c0, c = make(NONE), make(units)
    f = factors(units)
    t = f["time"]
    v0 = 0.2 * c0.continuum().sound_speed
    l0, l1 = c0.launch(defect, 27.0, v0), c.launch(defect, 27.0, v0 * f["speed"])
    scaled(l1.theta, l0.theta, 1.0, rtol=1e-9, what=f"launch angles, {units}")
    scaled(l1.omega, l0.omega, f["rate"], rtol=1e-9, what=f"launch velocities, {units}")
    assert abs(l1.position - l0.position) < 1e-9
    for dt in [None, 1e-3]:
        options = dict(t_max=0.3, output_interval=0.02, damping=0.4, dt=dt)
        r0 = c0.propagate(l0.theta, l0.omega, **options)
        options = dict(t_max=0.3 * t, output_interval=0.02 * t, damping=0.4 / t, dt=dt and dt * t)
        r1 = c.propagate(l1.theta, l1.omega, **options)
        assert r1.steps == r0.steps
        scaled(r1.times, r0.times, t, what=f"times, {units}")
        scaled(r1.theta, r0.theta, 1.0, rtol=1e-9, what=f"angles, {units}")
        scaled(r1.omega, r0.omega, f["rate"], rtol=1e-9, what=f"velocities, {units}")
        scaled(r1.kinetic, r0.kinetic, f["energy"], rtol=1e-9, what=f"kinetic energy, {units}")
        scaled(r1.energy_initial, r0.energy_initial, f["energy"], rtol=1e-9, what=f"energy, {units}")
        walls = [x for snapshot in r1.walls for x, _ in snapshot]
        scaled(walls, [x for snapshot in r0.walls for x, _ in snapshot], 1.0, rtol=1e-9, what="walls")


@pytest.mark.parametrize("point", [("kink", 9.6, 0.01), ("antikink", 4.0, 0.8), ("antikink", 4.8, 0.2)])
@pytest.mark.parametrize("absorbing_ends", [False, True])
def test_scattering_outcome_is_invariant_under_a_change_of_units(point, absorbing_ends):
    # The paper's chain of Sec. VI; v0 is a tip speed, length per t (Appendix B); t_max is as
    # given, so it is scaled here; the rules' windows follow the chain's time unit by themselves.
    defect, v0, ki = point
    results = []
    for units in [NONE] + UNITS:
        l, k, m = units
        f = factors(units)
        chain = rc.Chain(60, 0.8 * l, 1e4 * k, 0.28, a=l, mass=m, springs={29: {"k": ki * 1e4 * k}})
        s = chain.scatter(defect, v0 * f["speed"], t_max=20.0 * f["time"], absorbing_ends=absorbing_ends)
        if l == 1.0:  # the phase diagrams' chains have a = 1
            ends = "absorbing" if absorbing_ends else "free"
            record = sweep.point(defect, ki, v0 * f["speed"], k=1e4 * k, mass=m, t_max=20.0 * f["time"], ends=ends)
            assert (record["outcome"], record["t_decided"]) == (s.outcome, s.decided_at), units
        results.append((units, s, f["time"]))
    _, base, _ = results[0]
    for units, s, t in results[1:]:
        assert (s.outcome, s.confirmed) == (base.outcome, base.confirmed), units
        assert abs(s.decided_at / t - base.decided_at) <= 0.0101, units
