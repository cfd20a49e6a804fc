"""Results sized by the input that cannot be allocated are a ``MemoryError`` with the bytes asked
for, and the interpreter goes on (issue 37; an abort would be exit status 134): the eigenvectors of
``Chain.modes(count=...)``, the space-time image of a long ``propagate`` and the outputs of a long
``NetworkModel.propagate``, under an address-space
limit in a subprocess (as ``test_statics.py`` does for the copy of an argument)."""

import math
import subprocess
import sys
import textwrap


def test_modes_and_frames_that_cannot_be_allocated_are_memory_errors_not_an_abort():
    n_modes, count = 500_000, 24
    n_run, t_max, interval = 1000, 20.0, 0.001
    script = textwrap.dedent(
        f"""
        import resource
        import numpy as np
        import rotor_chain as rc
        big = rc.Chain({n_modes}, 0.8, 1.0e4, 0.58)
        theta = np.full({n_modes}, 0.58)
        small = rc.Chain({n_run}, 0.8, 1.0e4, 0.58)
        kink = small.kink(400.3)
        with open("/proc/self/status") as f:
            vm = next(int(l.split()[1]) * 1024 for l in f if l.startswith("VmSize:"))
        # Room for what is mapped and 64 MiB more: the work of each call fits, its result does not.
        resource.setrlimit(resource.RLIMIT_AS, (vm + 2**26, resource.RLIM_INFINITY))
        try:
            big.modes(theta, count={count})
        except MemoryError as e:
            print("MemoryError:", e)
        try:
            small.propagate(kink, np.zeros({n_run}), t_max={t_max}, output_interval={interval}, space_time=True)
        except MemoryError as e:
            print("MemoryError:", e)
        print("still running")
        """
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    # The bytes of the whole result: count vectors of n, and one frame of n angles per output
    # (t = 0, 0.001, ..., 20: 20 001 outputs).
    vectors = count * n_modes * 8
    frames = (round(t_max / interval) + 1) * n_run * 8
    assert done.stdout.splitlines() == [
        f"MemoryError: cannot allocate {vectors} bytes for the eigenvectors",
        f"MemoryError: cannot allocate {frames} bytes for the space-time image",
        "still running",
    ], done.stdout + done.stderr


def test_a_network_run_whose_outputs_cannot_be_allocated_is_a_memory_error():
    # NetworkModel.propagate keeps a time and an energy per output, t_max / dt / output_every + 2
    # of them (reserved before the first step): 10^8 outputs, 800 MB each, do not fit.
    t_max, dt = 1.0e5, 1.0e-3
    script = textwrap.dedent(
        f"""
        import resource
        import numpy as np
        import rotor_chain as rc
        model = rc.NetworkModel(rc.Network.ready("square"), (4, 4), boundary="periodic")
        x = np.asarray(model.reference())
        with open("/proc/self/status") as f:
            vm = next(int(l.split()[1]) * 1024 for l in f if l.startswith("VmSize:"))
        resource.setrlimit(resource.RLIMIT_AS, (vm + 2**26, resource.RLIM_INFINITY))
        try:
            model.propagate(x, np.zeros_like(x), t_max={t_max}, dt={dt}, output_every=1)
        except MemoryError as e:
            print("MemoryError:", e)
        print("still running")
        """
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    outputs = math.ceil(t_max / dt / 1) + 2
    assert done.stdout.splitlines() == [
        f"MemoryError: cannot allocate {outputs * 8} bytes for the run's output times and energies",
        "still running",
    ], done.stdout + done.stderr
