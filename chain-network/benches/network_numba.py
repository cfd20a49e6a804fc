"""The Verlet run of `examples/verlet_export.rs` written with numba (one thread, IEEE arithmetic:
no fastmath), for docs/benchmarks.md ("Networks in motion"). In a venv of its own, not CI's:

    python3 -m venv /work/venv-bench && /work/venv-bench/bin/pip install numba jax
    cargo run --release -p rotor-chain-network --example verlet_export -- 256 100 /tmp/kagome256
    NUMBA_NUM_THREADS=1 /work/venv-bench/bin/python chain-network/benches/network_numba.py /tmp/kagome256

The bond loop is the harmonic law's energy and gradient written out by hand (numba has no
derivatives), in the order of the generated kernel, gradient terms scattered bond by bond.
"""

from __future__ import annotations

import sys
import time

import numba
import numpy as np

from network_verlet import half_kick, load, report


@numba.njit(fastmath=False)
def energy_and_gradient(x, first, second, offset, k, l0, g):
    g[:] = 0.0
    energy = 0.0
    for b in range(first.shape[0]):
        i, j = first[b], second[b]
        dx = offset[b, 0] + (x[j] - x[i])
        dy = offset[b, 1] + (x[j + 1] - x[i + 1])
        length = np.sqrt(dx * dx + dy * dy)
        stretch = length - l0[b]
        tension = k[b] * stretch
        energy += 0.5 * (stretch * tension)
        f = tension / length
        g[i] -= dx * f
        g[i + 1] -= dy * f
        g[j] += dx * f
        g[j + 1] += dy * f
    return energy


@numba.njit(fastmath=False)
def verlet(x, w, g, c, dt, steps, first, second, offset, k, l0):
    energy = energy_and_gradient(x, first, second, offset, k, l0, g)
    for _ in range(steps):
        for i in range(x.shape[0]):
            w[i] -= c[i] * g[i]
            x[i] += dt * w[i]
        energy = energy_and_gradient(x, first, second, offset, k, l0, g)
        for i in range(x.shape[0]):
            w[i] -= c[i] * g[i]
    return energy


def main(folder: str) -> None:
    net = load(folder)
    bonds = (net["first"], net["second"], net["offset"], net["k"], net["l0"])
    c = half_kick(net)
    times, energy = [], 0.0
    # The first call compiles; then five timed runs from the same start.
    for run in range(6):
        x, w, g = net["x0"].copy(), np.zeros_like(net["x0"]), np.zeros_like(net["x0"])
        start = time.perf_counter()
        potential = verlet(x, w, g, c, net["dt"], net["steps"], *bonds)
        if run > 0:
            times.append(time.perf_counter() - start)
        energy = potential + 0.5 * np.sum(net["inertia"] * w * w)
    arrays = sum(a.nbytes for a in bonds) + 4 * x.nbytes  # bonds; x, w, g, c
    report(f"numba {numba.__version__}", net, energy, times, arrays)


if __name__ == "__main__":
    main(sys.argv[1])
