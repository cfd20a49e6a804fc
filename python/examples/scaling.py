"""What each way of computing a phase diagram costs, measured side by side (docs/scaling.md):
the same 40 x 40 antikink diagram on this machine's threads, on a Dask LocalCluster of worker
processes (default chunks, and one point per task to show the per-task overhead), and whether the
records agree. Install the package in release first (pip install './python[dask]').

    python python/examples/scaling.py [--workers 2] [--grid 40]
"""

import argparse
import os
import time

from distributed import Client, LocalCluster

from rotor_chain import sweep


def timed(label, f):
    t0, c0 = time.perf_counter(), time.process_time()
    result = f()
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"{label:<58} {wall:7.2f} s wall  {cpu:6.2f} s CPU here", flush=True)
    return result, wall


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--grid", type=int, default=40)
    args = parser.parse_args()
    ki, v0 = f"0.01:3:{args.grid}:log", f"0.5:12:{args.grid}"
    points = args.grid * args.grid
    print(f"antikink phase diagram, {points} points, {args.workers} workers / threads")
    local, t_local = timed("one process, threads", lambda: sweep.phase_diagram("antikink", ki, v0, threads=args.workers))
    cluster, _ = timed(
        f"LocalCluster start ({args.workers} worker processes, 1 thread each)",
        lambda: LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=":0"),
    )
    with cluster, Client(cluster) as client:
        timed("first task on each worker (imports rotor_chain)", lambda: client.run(lambda: __import__("rotor_chain")))
        dask, t_dask = timed("Dask, default chunks", lambda: sweep.phase_diagram("antikink", ki, v0, client=client))
        single, t_single = timed(
            "Dask, 1 point per task", lambda: sweep.phase_diagram("antikink", ki, v0, client=client, chunk_size=1)
        )
    assert dask == local and single == local, "the records differ"
    print(f"records identical; per point: {1e3 * t_local / points:.2f} ms (threads), "
          f"{1e3 * t_dask / points:.2f} ms (Dask chunks), {1e3 * t_single / points:.2f} ms (Dask, 1 per task)")


if __name__ == "__main__":
    main()
