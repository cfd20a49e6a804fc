"""Progress and Ctrl-C in the long calls Python drives in chunks (the phase-diagram sweeps): a
tqdm bar where someone watches (a terminal, a Jupyter kernel's stream), none when asked or
unwatched, a plain line without tqdm; a real SIGINT stops a sweep, local or on Dask, within a
chunk, closes the bar and keeps the finished points."""

from __future__ import annotations

import os
import signal
import sys
import threading
import time

import distributed
import pytest
import tqdm  # noqa: F401  (the test requirements have it: a bar is what is tested)

from rotor_chain import sweep
from cli_results import line_count

GRID = ("antikink", "0.05:3:4:log", "0.5:12:4")  # 16 points


def test_a_bar_on_stderr_when_asked(capsys):
    sweep.phase_diagram(*GRID, progress=True)
    err = capsys.readouterr().err
    assert "antikink phase diagram" in err and "16/16" in err and "100%" in err, err


@pytest.mark.parametrize("progress", [False, None], ids=["off", "unwatched"])
def test_no_bar_when_off_or_nobody_watches(progress, capsys):
    sweep.phase_diagram(*GRID, progress=progress)  # under pytest stderr is no terminal
    assert capsys.readouterr().err == ""


class KernelStream:
    """What ipykernel puts in sys.stderr: no terminal, but shown in the notebook."""

    def __init__(self):
        self.text = []

    def write(self, s):
        self.text.append(s)
        return len(s)

    def flush(self):
        pass

    def isatty(self):
        return False


KernelStream.__module__ = "ipykernel.iostream"


def test_a_jupyter_kernels_stream_gets_a_bar_by_default(monkeypatch):
    stream = KernelStream()
    monkeypatch.setattr(sys, "stderr", stream)
    sweep.phase_diagram(*GRID)
    text = "".join(stream.text)
    assert "antikink phase diagram" in text and "16/16" in text, text


def test_without_tqdm_a_plain_line_and_no_error(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    with pytest.raises(ImportError):
        import tqdm.auto  # noqa: F401  (the situation: tqdm cannot be imported)
    records = sweep.phase_diagram(*GRID, progress=True, chunk_size=8)
    assert len(records) == 16
    err = capsys.readouterr().err
    assert err == "\rantikink phase diagram: 8/16 points\rantikink phase diagram: 16/16 points\n", err
    sweep.phase_diagram(*GRID)
    assert capsys.readouterr().err == ""


def _interrupt_after(seconds):
    """Python's own Ctrl-C (SIGINT, the handler raising KeyboardInterrupt) sent to this process
    after ``seconds``; returns the timer and a list that gets the time it was sent."""
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(seconds, send)
    return timer, sent


@pytest.fixture
def python_sigint():
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_ctrl_c_stops_a_local_sweep_within_a_chunk(tmp_path, capsys, python_sigint):
    out = tmp_path / "big.csv"
    # 40 000 points: seconds of work even in a release build (0.35 ms a point on one core), so the
    # signal comes during the call.
    grid = ("antikink", "0.01:3:200:log", "0.5:12:200")
    timer, sent = _interrupt_after(0.5)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sweep.phase_diagram(*grid, out=out, threads=2, chunk_size=8, progress=True)
        stopped = time.monotonic()
    finally:
        timer.cancel()
    assert sent and stopped - sent[0] < 2.0, "Ctrl-C took more than a chunk"
    kept = line_count(out) - 2
    assert 0 < kept < 40_000
    err = capsys.readouterr().err
    # The bar was closed where it stopped, then the line that says what was kept.
    message = f"antikink phase diagram interrupted: {kept} of the 40000 points are in {out}"
    assert message in err and err.rindex(f"{kept}/40000") < err.index(message), err[-400:]


def test_ctrl_c_stops_a_dask_sweep(tmp_path, capsys, python_sigint):
    out = tmp_path / "dask.csv"
    grid = ("antikink", "0.01:3:60:log", "0.5:12:60")  # 3600 points in 900 tasks: seconds in any build
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0"
    ) as cluster, distributed.Client(cluster) as client:
        timer, sent = _interrupt_after(1.0)
        timer.start()
        try:
            with pytest.raises(KeyboardInterrupt):
                sweep.phase_diagram(*grid, out=out, client=client, chunk_size=4, progress=False)
            stopped = time.monotonic()
        finally:
            timer.cancel()
        assert sent and stopped - sent[0] < 2.0, "Ctrl-C took more than a wait of as_completed"
        # The tasks not gathered were cancelled, not left to run on the cluster.
        deadline = time.monotonic() + 10
        while client.processing() and any(client.processing().values()) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(client.processing().values())
    kept = line_count(out) - 2
    assert 0 < kept < 3600
    assert f"interrupted: {kept} of the 3600 points are in {out}" in capsys.readouterr().err
