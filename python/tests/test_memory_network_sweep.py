"""A network patch and a phase diagram's records that cannot be allocated are a ``MemoryError``
with the bytes asked for, and the interpreter goes on (issue 37; an abort would be exit status
134), under an address-space limit in a subprocess (as ``test_memory_results.py`` does)."""

import re
import subprocess
import sys
import textwrap


def _run(body: str) -> subprocess.CompletedProcess:
    script = textwrap.dedent(
        """
        import resource
        import rotor_chain as rc

        def limit(headroom):
            with open("/proc/self/status") as f:
                vm = next(int(l.split()[1]) * 1024 for l in f if l.startswith("VmSize:"))
            resource.setrlimit(resource.RLIMIT_AS, (vm + headroom, resource.RLIM_INFINITY))
        """
    ) + textwrap.dedent(body)
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)


def test_a_network_patch_too_large_for_the_limit_is_a_memory_error():
    # 4000 x 4000 square cells of 2 bonds: 32 000 000 bonds of 40 bytes (under the patch rule's
    # 2^25 bonds), 1.28 GB against 64 MiB of room.
    done = _run(
        """
        limit(2**26)
        try:
            rc.NetworkModel(rc.Network.ready("square"), (4000, 4000), boundary="periodic")
        except MemoryError as e:
            print("MemoryError:", e)
        print("still running")
        """
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        f"MemoryError: cannot allocate {4000 * 4000 * 2 * 40} bytes for the patch's bonds",
        "still running",
    ], done.stdout + done.stderr


def test_a_phase_diagrams_records_that_cannot_be_held_are_a_memory_error_before_any_point():
    # 10^6 copies of one point (the list holds 8 MB of references; its Rust copy 32 MB): their
    # records, each more than 64 bytes, do not fit in the 48 MiB left, and are refused before any
    # point is computed (computing one takes seconds).
    points = 1_000_000
    done = _run(
        f"""
        import time
        from rotor_chain import _native
        diagram = _native.PhaseDiagram("antikink")
        points = [(0, 0, 0.5, 1.0)] * {points}
        limit(48 * 2**20)
        start = time.monotonic()
        try:
            diagram.compute_points(points, 1)
        except MemoryError as e:
            print("MemoryError:", e)
        print("seconds", time.monotonic() - start)
        """
    )
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    found = re.fullmatch(r"MemoryError: cannot allocate (\d+) bytes for the points' records", lines[0])
    assert found, done.stdout + done.stderr
    size, rest = divmod(int(found.group(1)), points)
    assert rest == 0 and size > 64, found.group(1)
    assert float(lines[1].split()[1]) < 1.0, "a point was computed"
