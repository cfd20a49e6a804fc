"""rotor_chain.sweep on one machine against the `phase-diagram` command (Rust): identical records,
the same resumable CSV file (each resumes the other's), the same point errors; settings errors
with their numbers; the GIL released during long computations."""

from __future__ import annotations

import os
import pickle
import re
import threading
import time
import tracemalloc

import numpy as np
import pytest

import rotor_chain as rc
from rotor_chain import _native, sweep
from cli_results import cli_records, line_count, preamble, read_csv, run_cli

ANTIKINK = ("antikink", "0.05:3:4:log", "0.5:12:4")
KINK = ("kink", "0.01:1:3:log", "4:10:3")


@pytest.mark.parametrize("grid", [ANTIKINK, KINK], ids=["antikink", "kink"])
def test_records_equal_the_clis(grid, phase_diagram_cli, tmp_path):
    expected = cli_records(phase_diagram_cli, tmp_path / "cli.csv", *grid)
    records = sweep.phase_diagram(*grid, threads=2)
    assert records == expected  # every field, floats bit for bit
    assert len(records) == 16 if grid is ANTIKINK else 9
    assert {r["outcome"] for r in records} <= set(sweep.OUTCOMES)
    ki, v0, outcomes = sweep.outcome_grid(records)
    assert outcomes.shape == (len(v0), len(ki)) and "" not in outcomes


def test_the_file_is_the_clis_and_each_resumes_the_other(phase_diagram_cli, tmp_path, capsys):
    whole = cli_records(phase_diagram_cli, tmp_path / "cli.csv", *ANTIKINK)
    out = tmp_path / "pd.csv"
    seen = []

    def stop_after_first_chunk(done, total):
        seen.append((done, total))
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        sweep.phase_diagram(*ANTIKINK, out=out, chunk_size=5, progress=stop_after_first_chunk)
    assert seen == [(5, 16)] and line_count(out) == 2 + 5
    # Before the traceback, a line says what was kept and how to go on.
    message = f"antikink phase diagram interrupted: 5 of the 16 points are in {out}; call phase_diagram again"
    assert message in capsys.readouterr().err
    assert preamble(out) == preamble(tmp_path / "cli.csv")
    # The command resumes the file Python started...
    done = run_cli(phase_diagram_cli, out, *ANTIKINK)
    assert done.returncode == 0, done.stderr
    assert "16 points: 11 computed now (0 failed), 5 already done" in done.stderr
    assert read_csv(out) == whole
    # ...and Python finds it complete: nothing computed, every record returned.
    calls = []
    assert sweep.phase_diagram(*ANTIKINK, out=out, progress=lambda d, t: calls.append(d)) == whole
    assert calls == []
    # Python resumes a file the command started (a shard file would be refused: another part).
    out2 = tmp_path / "pd2.csv"
    partial = run_cli(phase_diagram_cli, out2, "antikink", "0.05:3:4:log", "0.5:12:4", "--shard", "0/1")
    assert partial.returncode == 0
    assert sweep.read_results(tmp_path / "pd2.shard-0-of-1.csv") == whole


def test_point_errors_are_the_clis(phase_diagram_cli, tmp_path):
    # A stiff chain (k = 1e5) and a Verlet step of a whole output interval (0.01 sqrt(1e4 / k) =
    # 0.00316, 5 times the default step) against a tolerance of 1e-3: the energy budget breaks.
    settings = dict(k=1.0e5, dt=0.0032, energy_tolerance=1e-3, recompute=False)
    options = ["--k", "1e5", "--dt", "0.0032", "--energy-tolerance", "1e-3", "--no-recompute"]
    cli = cli_records(phase_diagram_cli, tmp_path / "bad.csv", "antikink", "0.7:0.7:1", "4:4:1", *options)
    assert cli[0]["error"] is not None
    with pytest.raises(rc.PointError) as info:
        sweep.point("antikink", 0.7, 4.0, **settings)
    e = info.value
    assert str(e) == cli[0]["error"]
    assert e.variant in ("EnergyBudget", "Run"), e
    if e.variant == "EnergyBudget":
        assert e.error > e.tolerance == 1e-3 and e.integrator == "verlet"
    else:
        assert isinstance(e.__cause__, rc.DynamicsError)
    # In a sweep the failure is recorded, not raised, with the same text.
    (record,) = sweep.phase_diagram("antikink", [0.7], [4.0], **settings)
    assert record == cli[0]


def test_settings_errors_carry_the_numbers(phase_diagram_cli, tmp_path):
    with pytest.raises(rc.ConfigError) as info:
        sweep.phase_diagram("antikink", "0.1:1:2", "1:2:2", theta_bar=0.7)
    assert info.value.variant == "Chain" and isinstance(info.value.__cause__, rc.ParameterError)
    assert info.value.__cause__.variant == "OutsideFlipperPhase"
    # A chain too short for the experiment (the defect starts 15.5 sites right of the middle
    # spring): refused up front, the setup's reason as the cause.
    with pytest.raises(rc.ConfigError) as info:
        sweep.phase_diagram("antikink", "0.1:1:2", "1:2:2", n=12)
    e = info.value
    assert (e.variant, e.n) == ("Experiment", 12) and str(e).startswith("a chain of 12 rotors cannot hold the experiment")
    assert isinstance(e.__cause__, rc.DynamicsError) and e.__cause__ is e.details["source"]
    assert (e.__cause__.variant, e.__cause__.name, e.__cause__.value) == ("InvalidSetup", "start", 20.5)
    cli = run_cli(phase_diagram_cli, tmp_path / "short.csv", "antikink", "0.1:1:2", "1:2:2", "--n", "12")
    assert cli.returncode == 2 and str(e) in cli.stderr
    with pytest.raises(rc.ConfigError, match="must be > 0") as info:
        sweep.phase_diagram("kink", "0:1:3", "1:2:2")
    assert (info.value.name, info.value.value) == ("k_i/k", 0.0)
    with pytest.raises(rc.ConfigError, match="every launch speed must be >= 0, got -1.0"):
        sweep.phase_diagram("kink", "0.1:1:3", [-1.0, 2.0])
    with pytest.raises(rc.GridError) as info:
        sweep.phase_diagram("kink", "0.1:1:0", "1:2:2")
    assert (info.value.variant, info.value.count) == ("EmptyAxis", 0)
    with pytest.raises(ValueError, match="defect must be one of 'kink', 'antikink', got 'soliton'"):
        sweep.phase_diagram("soliton", "0.1:1:3", "1:2:2")
    # A file of another run is refused, untouched, with both labels.
    other = tmp_path / "other.csv"
    assert run_cli(phase_diagram_cli, other, "kink", "0.1:1:2", "1:2:2", "--theta-bar", "0.3").returncode == 0
    before = other.read_bytes()
    with pytest.raises(rc.SweepError) as info:
        sweep.phase_diagram("kink", "0.1:1:2", "1:2:2", out=other)
    e = info.value
    assert e.variant == "RunMismatch" and e.path == str(other)
    assert "theta_bar=0.3" in e.found and "theta_bar=0.28" in e.expected
    assert other.read_bytes() == before


class _Untouchable:
    """A Dask client stand-in that fails the test if anything of it is used."""

    def __getattr__(self, name):
        raise AssertionError(f"client.{name} was used before the grid was refused")


def test_a_grid_past_the_clis_limit_is_refused_before_any_point_is_listed(tmp_path):
    # 10^10 points: the list of points alone would be hundreds of GB. Refused from the two axes
    # (1e5 values each), with the command's message and numbers, and nothing written.
    out = tmp_path / "huge.csv"
    for kwargs in ({}, {"out": out}, {"client": _Untouchable()}):
        tracemalloc.start()
        try:
            with pytest.raises(rc.GridError) as info:
                sweep.phase_diagram("antikink", "0.1:1:100000", "1:2:100000", **kwargs)
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        e = info.value
        assert str(e) == "the grid has 100000 x 100000 points, more than the limit of 10000000", kwargs
        assert (e.variant, e.nx, e.ny) == ("TooLarge", 100_000, 100_000)
        assert peak < 32 * 2**20, f"{kwargs}: {peak / 2**20:.0f} MiB allocated before the refusal"
    assert not out.exists()
    # The limit is chain-sweep's, exactly: a grid at it passes the check, one more row does not.
    assert (sweep.MAX_AXIS_COUNT, sweep.MAX_GRID_POINTS) == (100_000, 10_000_000)
    xs = sweep.axis(f"0.1:1:{sweep.MAX_AXIS_COUNT}")
    rows = sweep.MAX_GRID_POINTS // sweep.MAX_AXIS_COUNT
    assert _native.check_grid(xs, [1.0] * rows) is None
    with pytest.raises(rc.GridError) as info:
        _native.check_grid(xs, [1.0] * (rows + 1))
    assert (info.value.nx, info.value.ny) == (sweep.MAX_AXIS_COUNT, rows + 1)
    with pytest.raises(rc.GridError) as info:  # a results file checks the same grid
        _native.ResultsFile(xs, [1.0] * (rows + 1), str(out), "run")
    assert info.value.variant == "TooLarge" and not out.exists()
    with pytest.raises(rc.GridError) as info:  # and an axis has its own limit
        sweep.axis(f"0.1:1:{sweep.MAX_AXIS_COUNT + 1}")
    assert (info.value.variant, info.value.count) == ("TooManyPoints", sweep.MAX_AXIS_COUNT + 1)
    # outcome_grid makes a cell per (ki, v0) pair of the records: records off any grid could ask
    # for more cells than a grid may have points.
    side = 3163  # 3163^2 > 10^7
    scattered = [dict(ki=0.1 + i, v0=float(i), outcome=None, error="x") for i in range(side)]
    with pytest.raises(rc.GridError) as info:
        sweep.outcome_grid(scattered)
    assert (info.value.nx, info.value.ny) == (side, side)


def test_point_refuses_settings_as_phase_diagram_does():
    with pytest.raises(rc.ConfigError) as info:
        sweep.point("antikink", 0.5, float("nan"))
    assert info.value.name == "v0" and str(info.value) == "invalid v0: every launch speed must be >= 0, got nan"
    with pytest.raises(rc.ConfigError) as info:
        sweep.point("antikink", -0.5, 4.0)
    assert (info.value.name, info.value.value) == ("k_i/k", -0.5)


def test_phase_diagram_settings_pickle_and_a_results_file_does_not(tmp_path):
    d = _native.PhaseDiagram("kink", n=40, ends="absorbing", integrator="dop853", dt=1e-3, recompute=False, t_max=3.5)
    again = pickle.loads(pickle.dumps(d))
    assert type(again) is _native.PhaseDiagram and again.run_label == d.run_label
    assert "integrator=dop853" in d.run_label and "t_max=3.5" in d.run_label
    assert again.compute_point(0.5, 2.0) == d.compute_point(0.5, 2.0)
    # A results file is an open, locked file: like a Python file object it does not pickle.
    with _native.ResultsFile([0.5], [2.0], str(tmp_path / "f.csv"), d.run_label) as f:
        with pytest.raises(TypeError, match="ResultsFile"):
            pickle.dumps(f)


def _main_thread_progress(call) -> tuple:
    """Run ``call`` in a thread; count the main thread's loop iterations while it runs. With the
    GIL held by ``call`` the main thread could not run at all."""
    started, finished = threading.Event(), threading.Event()

    def worker():
        started.set()
        call()
        finished.set()

    thread = threading.Thread(target=worker)
    thread.start()
    started.wait()
    t0, count = time.perf_counter(), 0
    while not finished.is_set():
        count += 1
    elapsed = time.perf_counter() - t0
    thread.join()
    return count, elapsed


def _call_of(what: str, scale: int):
    """The computation ``what`` at a size that grows with ``scale``."""
    if what == "sweep points":
        d = rc._native.PhaseDiagram("antikink")
        pts = [(0, j, 0.7, 4.0 + 0.1 * (j % 20)) for j in range(6 * scale)]
        return lambda: d.compute_points(pts, 1)
    if what == "propagate":
        c = rc.Chain(2000, 0.8, 1.0e4, 0.28)
        theta = c.kink(1000.0)
        return lambda: c.propagate(theta, np.zeros(2000), t_max=1.0 * scale)
    c = rc.Chain(12000 * scale, 0.8, 1.0e4, 0.2)
    return lambda: c.peierls_nabarro()


@pytest.mark.parametrize("what", ["sweep points", "propagate", "peierls_nabarro"])
def test_long_computations_release_the_gil(what):
    # One call long enough to tell (> 0.05 s) whatever the build's speed: the size doubles until
    # a call alone takes 0.1 s (at most 2^6 times the smallest).
    scale = 1
    call = _call_of(what, scale)
    while scale < 64:
        t0 = time.perf_counter()
        call()
        if time.perf_counter() - t0 >= 0.1:
            break
        scale *= 2
        call = _call_of(what, scale)
    count, elapsed = _main_thread_progress(call)
    assert elapsed > 0.05, f"{what} took only {elapsed:.3f} s: too short to tell"
    # The main thread ran its loop throughout (millions of iterations per second when free).
    assert count > 10_000 * elapsed, f"{what}: {count} iterations in {elapsed:.2f} s"


@pytest.mark.parametrize(
    "kwargs, error, message",
    [
        (dict(threads="2"), TypeError, "threads must be an int, got '2' (str)"),
        (dict(threads=True), TypeError, "threads must be an int, got True (bool)"),
        (dict(threads=0), ValueError, "threads must be at least 1, got 0"),
        (dict(chunk_size="3"), TypeError, "chunk_size must be an int, got '3' (str)"),
        (dict(chunk_size=2.0), TypeError, "chunk_size must be an int, got 2.0 (float)"),
        (dict(max_resubmits=-1), ValueError, "max_resubmits must be at least 0, got -1"),
        (dict(client="x"), TypeError, "client must be a dask.distributed.Client (or None), got str"),
        (dict(n=60.0), TypeError, "`n` must be an int (a number of rotors), got 60.0 (float)"),
        (dict(n=True), TypeError, "`n` must be an int (a number of rotors), got True (bool)"),
        (dict(theta_bar="0.28"), TypeError, "`theta_bar` must be a real number, got '0.28' (str)"),
    ],
)
def test_a_setting_of_the_wrong_type_or_range_is_refused_by_name_before_any_point(kwargs, error, message, tmp_path):
    out = tmp_path / "never.csv"
    with pytest.raises(error) as info:
        sweep.phase_diagram("antikink", [0.5], [1.0], out=out, **kwargs)
    assert str(info.value) == message
    assert not isinstance(info.value, rc.RotorChainError)
    assert not out.exists()


def test_a_thread_count_past_four_per_core_is_refused_before_any_point(tmp_path):
    most, cores = _native.max_threads(), os.cpu_count()
    assert most >= 4 and most % 4 == 0 and cores >= 1
    out = tmp_path / "never.csv"
    d = _native.PhaseDiagram("antikink")
    for threads in (most + 1, 20_000, 10**20):
        bound = f"; at most {most} on this machine"
        with pytest.raises(ValueError, match=r"^SweepOptions\.threads = .*" + re.escape(bound)):
            sweep.phase_diagram("antikink", [0.5], [1.0], threads=threads, out=out)
        assert not out.exists()
        start = time.monotonic()
        with pytest.raises(ValueError, match=r"^SweepOptions\.threads = .*" + re.escape(bound)):
            d.compute_points([(0, 0, 0.5, 1.0)], threads)
        assert time.monotonic() - start < 1.0
    with pytest.raises(ValueError, match=r"SweepOptions\.threads = 0 is invalid"):
        d.compute_points([(0, 0, 0.5, 1.0)], 0)
    with pytest.raises(TypeError, match="threads must be an int, got True"):
        d.compute_points([(0, 0, 0.5, 1.0)], True)
    # The most allowed, on one point: one thread computes it.
    [record] = d.compute_points([(0, 0, 0.5, 1.0)], most)
    assert record["error"] is None


def test_a_t_max_past_the_output_budget_is_a_config_error_before_any_point(tmp_path):
    out = tmp_path / "never.csv"
    with pytest.raises(rc.ConfigError) as info:
        sweep.phase_diagram("antikink", [0.5], [1.0], t_max=1e9, out=out)
    e = info.value
    assert e.variant == "OutputBudget"
    # 1e9 / 0.01 = 1e11 outputs, against a run's budget of 1 000 000.
    assert (e.t_max, e.output_interval, e.budget) == (1e9, 0.01, 1_000_000)
    assert e.outputs == pytest.approx(1e11)
    assert not out.exists()


def test_a_record_is_appended_only_under_its_own_coordinates(tmp_path):
    out = tmp_path / "r.csv"
    xs, ys = [0.25, 1.0], [2.0]
    d = _native.PhaseDiagram("antikink")
    record = dict(i=1, j=0, ki=1.0, v0=2.0, outcome=None, t_decided=None, confirmed=None, later=None,
                  t_later=None, kinks_final=None, antikinks_final=None, energy_error=None,
                  integrator=None, error="computed elsewhere")
    with _native.ResultsFile(xs, ys, str(out), d.run_label) as f:
        # Computed at k_i/k = 0.5 (or NaN, or one ulp off 1.0), filed as point (1, 0) at 1.0.
        for ki in (0.5, float("nan"), np.nextafter(1.0, 2.0), 0.25):
            with pytest.raises(rc.SweepError) as info:
                f.append({**record, "ki": float(ki)})
            e = info.value
            assert e.variant == "WrongCoordinates" and e.index == (1, 0) and e.grid == (1.0, 2.0)
            assert np.array_equal(e.given, (ki, 2.0), equal_nan=True)
            assert "but the grid has it at (1, 2)" in str(e)
        with pytest.raises(rc.SweepError, match=r"computed at \(1, 3\)"):
            f.append({**record, "v0": 3.0})
        assert f.missing() == [(0, 0), (1, 0)]
        f.append(record)
    [point] = _native.read_points(str(out))
    assert (point["i"], point["j"], point["ki"], point["v0"], point["error"]) == (1, 0, 1.0, 2.0,
                                                                                  "computed elsewhere")
