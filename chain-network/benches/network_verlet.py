"""What benches/network_numba.py and benches/network_jax.py share: the network written by
`examples/verlet_export.rs` (its `.npy` files), the start state of its Verlet run, and the line
each prints (docs/benchmarks.md, "Networks in motion")."""

from __future__ import annotations

import resource
import sys
from pathlib import Path

import numpy as np

NAMES = ("first", "second", "offset", "k", "l0", "x0", "inertia", "steps", "dt")


def load(folder: str) -> dict:
    """The arrays of `verlet_export`'s folder, by name (`steps` and `dt` as numbers)."""
    net = {name: np.load(Path(folder) / f"{name}.npy") for name in NAMES}
    net["steps"] = int(net["steps"][0])
    net["dt"] = float(net["dt"][0])
    return net


def half_kick(net: dict) -> np.ndarray:
    """`dt / (2 I)`: velocity Verlet's half kick per unit force, as chain-core's `Verlet` has it."""
    return net["dt"] / (2.0 * net["inertia"])


def report(name: str, net: dict, energy: float, times: list[float], arrays: int) -> None:
    """One line: the energy after the steps (17 digits), the median time per step and degree of
    freedom, the bytes of the implementation's arrays and the peak resident set per degree of
    freedom."""
    dof = net["x0"].size
    per_dof = sorted(times)[len(times) // 2] / net["steps"] / dof * 1e9
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    print(
        f"{name}: {dof} dof, {net['steps']} steps: energy {energy:.17e}; "
        f"{per_dof:.2f} ns per dof per step (median of {len(times)}); "
        f"arrays {arrays / dof:.1f} B per dof, peak resident {peak / dof:.1f} B per dof"
    )
    sys.stdout.flush()
