"""docs/network.md §10.6: the Python script of the networks-in-motion guide runs and prints what
the page says it does (force balance, the stressed square lattice's closed-form modes, Verlet's
energy)."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_the_network_guides_script_runs(tmp_path):
    text = (ROOT / "docs" / "network.md").read_text()
    (block,) = [b for b in re.findall(r"```python\n(.*?)```", text, flags=re.S) if "NetworkModel" in b]
    assert 'if __name__ == "__main__":' in block
    done = subprocess.run([sys.executable, "-c", block], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    force, modes, energy = done.stdout.splitlines()
    assert float(force.removeprefix("largest force ")) < 1e-13
    values = [float(w) for w in modes.removeprefix("omega^2 ").split()]
    shear = 0.1 * (2 - 2 * math.cos(2 * math.pi / 20))  # t (2 - 2 cos(2 pi / N)), N = 20
    assert all(abs(v) < 5e-7 for v in values[:2])  # the two translations
    assert all(abs(v - shear) < 5e-7 for v in values[2:])  # printed to 6 decimals
    assert float(energy.removeprefix("energy kept to ")) < 1e-2
