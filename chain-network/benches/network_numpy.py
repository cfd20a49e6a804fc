"""The counts of benches/network.rs by a separate numpy/scipy implementation (dense SVD, and
numpy's batched SVD of the Bloch blocks), and by PyRigi (numerical rank of the rigidity matrix of
free patches; PyRigi has no periodic frameworks), printed with their times. Run in the venv of
`cargo xtask test` (numpy; `pip install scipy pyrigi`):

    target/python/venv/bin/python chain-network/benches/network_numpy.py

The numbers are in docs/benchmarks.md, "Networks", beside the divan run.
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np

A1 = np.array([1.0, 0.0])
A2 = np.array([-0.5, math.sqrt(3) / 2])
SITES = [A1 / 2, A2 / 2, -(A1 + A2) / 2]
# Kane and Lubensky's standard kagome cell: (from, to, cell offset).
BONDS = [(0, 2, (1, 1)), (1, 2, (1, 1)), (1, 0, (-1, 0)), (2, 0, (-1, 0)), (2, 1, (0, -1)), (0, 1, (0, -1))]


def unit(f, t, c):
    v = SITES[t] + c[0] * A1 + c[1] * A2 - SITES[f]
    return v / np.linalg.norm(v)


def patch(n1, n2, periodic):
    rows = []
    for c2 in range(n2):
        for c1 in range(n1):
            for f, t, c in BONDS:
                t1, t2 = c1 + c[0], c2 + c[1]
                if periodic:
                    t1, t2 = t1 % n1, t2 % n2
                elif not (0 <= t1 < n1 and 0 <= t2 < n2):
                    continue
                e = unit(f, t, c)
                row = np.zeros(6 * n1 * n2)
                i, j = 6 * (c1 + n1 * c2) + 2 * f, 6 * (t1 + n1 * t2) + 2 * t
                row[i : i + 2] -= e
                row[j : j + 2] += e
                rows.append(row)
    return np.array(rows)


def dense_counts(c, svd):
    s = svd(c)
    r = int(np.sum(s > 1e-9 * s[0]))
    return c.shape[1] - r, c.shape[0] - r


def bloch_counts(n):
    m = np.arange(n)
    t1, t2 = np.meshgrid(2 * np.pi * m / n, 2 * np.pi * m / n, indexing="ij")
    t1, t2 = t1.ravel(), t2.ravel()
    q = np.zeros((t1.size, 6, 6), complex)
    for row, (f, t, c) in enumerate(BONDS):
        e = unit(f, t, c)
        q[:, row, 2 * f : 2 * f + 2] -= e
        q[:, row, 2 * t : 2 * t + 2] += np.exp(1j * (c[0] * t1 + c[1] * t2))[:, None] * e
    s = np.linalg.svd(q, compute_uv=False)
    r = int(np.sum(s > 1e-9 * s.max()))
    return 6 * n * n - r, 6 * n * n - r


def timed(f, repeat=3):
    best, out = math.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t)
    return best, out


def main():
    import scipy.linalg

    print(f"numpy {np.__version__}; {np.show_config.__module__}")
    for n in (20, 50, 100):
        dt, c = timed(lambda: bloch_counts(n))
        print(f"periodic kagome {n}x{n}, numpy batched Bloch SVD: {dt * 1e3:.1f} ms  counts {c}")
    for n in (10, 20) + ((40,) if "--big" in sys.argv else ()):
        c = patch(n, n, False)
        rep = 1 if n >= 40 else 3
        dt, k = timed(lambda: dense_counts(c, lambda m: np.linalg.svd(m, compute_uv=False)), rep)
        print(f"free kagome {n}x{n} ({c.shape[1]} dof), numpy dense SVD: {dt:.3f} s  counts {k}")
        dt, k = timed(lambda: dense_counts(c, lambda m: scipy.linalg.svdvals(m, check_finite=False)), rep)
        print(f"free kagome {n}x{n}, scipy svdvals (gesdd): {dt:.3f} s  counts {k}")
    for n in (10, 20):
        c = patch(n, n, True)
        dt, k = timed(lambda: dense_counts(c, lambda m: np.linalg.svd(m, compute_uv=False)))
        print(f"periodic kagome {n}x{n}, numpy dense SVD of the whole matrix: {dt:.3f} s  counts {k}")
    try:
        from pyrigi import Framework, Graph
    except ImportError:
        print("pyrigi not installed")
        return
    for n in (5, 10):
        points, edges = {}, []
        for c2 in range(n):
            for c1 in range(n):
                for s in range(3):
                    points[(c1, c2, s)] = list(SITES[s] + c1 * A1 + c2 * A2)
                for f, t, c in BONDS:
                    t1, t2 = c1 + c[0], c2 + c[1]
                    if 0 <= t1 < n and 0 <= t2 < n:
                        edges.append(((c1, c2, f), (t1, t2, t)))
        g = Graph(edges)
        g.add_vertices([v for v in points if v not in g.nodes])
        fw = Framework(g, {v: points[v] for v in g.nodes})
        dt, r = timed(lambda: fw.rigidity_matrix_rank(numerical=True), 1)
        dof = 2 * len(points)
        print(f"free kagome {n}x{n} ({dof} dof), PyRigi numerical rank: {dt:.3f} s  counts {(dof - r, len(edges) - r)}")


if __name__ == "__main__":
    main()
