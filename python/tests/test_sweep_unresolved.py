"""Unresolved points and the experiment settings in Python's sweeps (issue 34): the records and the
files equal the ``phase-diagram`` command's for the same settings (the command is the reference,
its CSV read with Python's csv module), a pickled diagram keeps every setting."""

from __future__ import annotations

import pickle

import pytest

from cli_results import cli_records, preamble
from rotor_chain import _native, sweep

# The chaotic corner (antikink, k_i/k = 0.01, v0 = 1.1: Verlet and DOP853 decide differently) and
# the paper's reflected point (0.2, 4.8).
CORNER = ("antikink", [0.01, 0.2], [1.1, 4.8])


def test_a_cross_checked_sweep_marks_the_corner_unresolved_as_the_command_does(phase_diagram_cli, tmp_path):
    expected = cli_records(phase_diagram_cli, tmp_path / "cli.csv", "antikink", "0.01:0.2:2", "1.1:4.8:2", "--cross-check")
    records = sweep.phase_diagram("antikink", "0.01:0.2:2", "1.1:4.8:2", cross_check=True, out=tmp_path / "py.csv", threads=2)
    assert records == expected  # every field, floats bit for bit
    assert preamble(tmp_path / "py.csv") == preamble(tmp_path / "cli.csv")
    corner = next(r for r in records if (r["ki"], r["v0"]) == (0.01, 1.1))
    assert corner["unresolved"] == "integrators-disagree"
    assert corner["unresolved_outcome"] in sweep.OUTCOMES and corner["unresolved_outcome"] != corner["outcome"]
    assert corner["t_unresolved"] > 0
    reflected = next(r for r in records if (r["ki"], r["v0"]) == (0.2, 4.8))
    assert (reflected["outcome"], reflected["unresolved"], reflected["t_unresolved"]) == ("reflected", None, None)
    # Without the cross-check the same point is not doubted (no wall from an end came first).
    assert sweep.point("antikink", 0.01, 1.1)["unresolved"] is None


def test_the_experiment_settings_are_the_commands(phase_diagram_cli, tmp_path):
    settings = dict(impurity=20, impurity_rest_length=1.75, start=5.0, direction="right", damping=0.5, t_max=6.0)
    flags = ["--impurity", "20", "--impurity-rest-length", "1.75", "--start", "5", "--direction", "right",
             "--damping", "0.5", "--t-max", "6"]
    expected = cli_records(phase_diagram_cli, tmp_path / "cli.csv", "kink", "1:2:2", "1.5:1.5:1", *flags)
    records = sweep.phase_diagram("kink", "1:2:2", "1.5:1.5:1", out=tmp_path / "py.csv", threads=2, **settings)
    assert records == expected
    assert preamble(tmp_path / "py.csv") == preamble(tmp_path / "cli.csv")
    d = _native.PhaseDiagram("kink", cross_check=True, **settings)
    assert d.run_label.endswith(
        "impurity=20 impurity_rest_length=1.75 direction=right start=5.0 damping=0.5 cross_check=true")
    again = pickle.loads(pickle.dumps(d))
    assert again.run_label == d.run_label


def test_bad_experiment_settings_name_their_rule():
    with pytest.raises(ValueError, match="direction must be one of 'left', 'right', got 'up'"):
        _native.PhaseDiagram("kink", direction="up")
    with pytest.raises(Exception, match="damping"):
        _native.PhaseDiagram("kink", damping=-1.0)
    with pytest.raises(Exception, match="needs n >= 70"):
        _native.PhaseDiagram("kink", impurity=50)
