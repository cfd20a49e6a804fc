"""docs/network.md §10.6 and §10.7: the Python scripts of the networks-in-motion guide run and
print what the page says they do (§10.6: force balance, the stressed square lattice's closed-form
modes, Verlet's energy; §10.7: a domain wall moving through coupled chains, the counts and
windings of its two sides)."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def script(tmp_path, marker):
    """Run the guide's Python block that contains `marker`; its printed lines."""
    text = (ROOT / "docs" / "network.md").read_text()
    (block,) = [b for b in re.findall(r"```python\n(.*?)```", text, flags=re.S) if marker in b]
    assert 'if __name__ == "__main__":' in block
    done = subprocess.run([sys.executable, "-c", block], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def test_the_network_guides_script_runs(tmp_path):
    force, modes, energy = script(tmp_path, 'Network.ready("square")')
    assert float(force.removeprefix("largest force ")) < 1e-13
    values = [float(w) for w in modes.removeprefix("omega^2 ").split()]
    shear = 0.1 * (2 - 2 * math.cos(2 * math.pi / 20))  # t (2 - 2 cos(2 pi / N)), N = 20
    assert all(abs(v) < 5e-7 for v in values[:2])  # the two translations
    assert all(abs(v - shear) < 5e-7 for v in values[2:])  # printed to 6 decimals
    assert float(energy.removeprefix("energy kept to ")) < 1e-2


def test_the_moving_wall_script_runs(tmp_path):
    moved, apart, energy, minus, plus = script(tmp_path, "def wall(theta)")
    start, end = (float(w) for w in re.fullmatch(r"wall from (\S+) to (\S+)", moved).groups())
    assert abs(start - 6.0) < 0.1 and end - start > 10.0  # launched at rotor 6, moved right
    # No stagger: the chains move as one (inter-chain springs at rest).
    assert float(apart.removeprefix("chains apart by at most ")) < 1e-6
    assert float(energy.removeprefix("energy kept to ")) < 1e-2
    # 4 chains of 32 rotors: 128 dof, 4 * 31 + 3 * 32 = 220 springs; N0 = 1, S = 220 - 128 + 1.
    # The kink's right side (-theta_bar) has winding 1, its left side (+theta_bar) 0.
    assert minus == "tilt -0.58: N0 1 S 93 winding 1"
    assert plus == "tilt +0.58: N0 1 S 93 winding 0"
