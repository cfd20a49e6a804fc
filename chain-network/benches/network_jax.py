"""The Verlet run of `examples/verlet_export.rs` written with JAX on the CPU (float64, one
thread), for docs/benchmarks.md ("Networks in motion"). In a venv of its own, not CI's:

    python3 -m venv /work/venv-bench && /work/venv-bench/bin/pip install numba jax
    cargo run --release -p rotor-chain-network --example verlet_export -- 256 100 /tmp/kagome256
    /work/venv-bench/bin/python chain-network/benches/network_jax.py /tmp/kagome256

As a JAX user writes it: the energy of the bond list (gathered endpoints), its gradient by
`jax.value_and_grad` (XLA's scatter-add), the steps in one jitted `lax.fori_loop`.
"""

from __future__ import annotations

import os
import sys
import time

# One thread for XLA's CPU backend, as for the others (set before JAX starts).
os.environ["XLA_FLAGS"] = "--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1"

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import numpy as np  # noqa: E402

from network_verlet import half_kick, load, report  # noqa: E402

jax.config.update("jax_enable_x64", True)
jax.config.update("jax_platforms", "cpu")


def main(folder: str) -> None:
    net = load(folder)
    first, second = jnp.asarray(net["first"]), jnp.asarray(net["second"])
    offset, k, l0 = jnp.asarray(net["offset"]), jnp.asarray(net["k"]), jnp.asarray(net["l0"])
    c, dt, steps = jnp.asarray(half_kick(net)), net["dt"], net["steps"]

    def energy(x):
        dx = offset[:, 0] + (x[second] - x[first])
        dy = offset[:, 1] + (x[second + 1] - x[first + 1])
        stretch = jnp.sqrt(dx * dx + dy * dy) - l0
        return jnp.sum(0.5 * (stretch * (k * stretch)))

    energy_and_gradient = jax.value_and_grad(energy)

    @jax.jit
    def verlet(x, w):
        def step(_, state):
            x, w, g, _ = state
            w = w - c * g
            x = x + dt * w
            e, g = energy_and_gradient(x)
            return x, w - c * g, g, e

        e, g = energy_and_gradient(x)
        return jax.lax.fori_loop(0, steps, step, (x, w, g, e))

    x0 = jnp.asarray(net["x0"])
    times, total = [], 0.0
    # The first call compiles; then five timed runs from the same start.
    for run in range(6):
        start = time.perf_counter()
        x, w, g, e = jax.block_until_ready(verlet(x0, jnp.zeros_like(x0)))
        if run > 0:
            times.append(time.perf_counter() - start)
        total = float(e) + 0.5 * float(jnp.sum(jnp.asarray(net["inertia"]) * w * w))
    arrays = sum(a.nbytes for a in (first, second, offset, k, l0)) + 4 * x0.nbytes
    report(f"jax {jax.__version__}", net, total, times, arrays)


if __name__ == "__main__":
    main(sys.argv[1])
