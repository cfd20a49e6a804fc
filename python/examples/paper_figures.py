"""Two of the paper's figures from Python, in a few lines each:

- ``fig:akenergy``: the antikink's energy (the Peierls-Nabarro minimum) against theta_bar, the
  lattice (n = 60, r/a = 0.8) beside the continuum's Eq. (akenergy);
- ``fig:phasediagram``: the antikink's scattering phase diagram over k_i/k and v0, computed in
  parallel (``--dask`` computes it on a local Dask cluster instead) and saved as a resumable CSV.

    python python/examples/paper_figures.py --out figures/          # ~10 s on 2 cores
    python python/examples/paper_figures.py --out figures/ --quick  # a coarse version, ~2 s
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rotor_chain as rc  # noqa: E402
from rotor_chain import plot, sweep  # noqa: E402


def akenergy(out: Path, quick: bool) -> Path:
    thetas = np.linspace(0.05, 0.65, 7 if quick else 25)
    lattice = [rc.Chain(60, 0.8, 1e4, t).peierls_nabarro().minimum_energy / 1e4 for t in thetas]
    fine = np.linspace(0.05, 0.65, 121)
    continuum = [rc.Chain(60, 0.8, 1e4, t).continuum().antikink_energy / 1e4 for t in fine]
    fig, ax = plt.subplots(figsize=(5, 3.6))
    ax.plot(fine, continuum, "-", label="continuum, Eq. (akenergy)")
    ax.plot(thetas, lattice, "o", label="lattice, n = 60 (PN minimum)")
    ax.set(xlabel=r"$\bar\theta$ (rad)", ylabel=r"$V / (k a^2)$", title="Antikink energy (fig:akenergy)")
    ax.legend()
    path = out / "akenergy.png"
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    return path


def phasediagram(out: Path, quick: bool, client=None) -> Path:
    count = 8 if quick else 30
    records = sweep.phase_diagram(
        "antikink",
        f"0.01:3:{count}:log",
        f"0.5:12:{count}",
        # One file per grid: --quick and the full run in the same folder must not share one.
        out=out / f"antikink-{count}x{count}.csv",
        client=client,
    )
    ax = plot.phase_diagram(records, title="Antikink scattering (fig:phasediagram)")
    path = out / "phasediagram.png"
    ax.figure.savefig(path, dpi=150)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", type=Path, default=Path("python-figures"), help="output folder")
    parser.add_argument("--quick", action="store_true", help="coarse grids, for a first look (and the tests)")
    parser.add_argument("--dask", action="store_true", help="compute the phase diagram on a local Dask cluster")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    print(akenergy(args.out, args.quick))
    if args.dask:
        from distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
            print(phasediagram(args.out, args.quick, client))
    else:
        print(phasediagram(args.out, args.quick))


if __name__ == "__main__":
    main()
