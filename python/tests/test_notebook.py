"""The example notebook (python/examples/first_hour.ipynb) runs, cell by cell, in a Jupyter kernel
of this test's own Python (nbclient): a cell that fails fails the test, so the notebook cannot go
stale. It is kept without outputs, so what GitHub shows is never an old run's."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient

import rotor_chain

NOTEBOOK = Path(__file__).resolve().parents[1] / "examples" / "first_hour.ipynb"
KERNEL = "rotor-chain-test"


def test_the_notebook_is_kept_without_outputs():
    nb = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(nb)
    code = [cell for cell in nb.cells if cell.cell_type == "code"]
    assert len(code) >= 6
    for cell in code:
        assert cell.outputs == [] and cell.execution_count is None, cell.source[:60]


def test_the_notebook_runs_from_a_chain_to_a_phase_diagram(tmp_path, monkeypatch):
    # A kernel spec of this interpreter, found first (JUPYTER_PATH comes before the user's and
    # the system's folders): the kernel imports the rotor_chain under test, whatever else is
    # installed on the machine.
    spec = tmp_path / "jupyter" / "kernels" / KERNEL
    spec.mkdir(parents=True)
    argv = [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"]
    (spec / "kernel.json").write_text(json.dumps({"argv": argv, "display_name": KERNEL, "language": "python"}))
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path / "jupyter"))
    monkeypatch.setenv("JUPYTER_RUNTIME_DIR", str(tmp_path / "runtime"))  # its connection file
    monkeypatch.delenv("MPLBACKEND", raising=False)  # the kernel's inline backend, as in Jupyter
    work = tmp_path / "work"
    work.mkdir()

    nb = nbformat.read(NOTEBOOK, as_version=4)
    count = len(nb.cells)
    nb.cells.append(nbformat.v4.new_code_cell("import sys, rotor_chain\nprint(sys.executable)\nprint(rotor_chain.__file__)"))
    client = NotebookClient(nb, timeout=600, kernel_name=KERNEL, resources={"metadata": {"path": str(work)}})
    client.execute()  # CellExecutionError (naming the cell) if any cell raises

    printed = nb.cells[count].outputs[0]["text"].split()
    assert printed == [sys.executable, rotor_chain.__file__]
    code = [cell for cell in nb.cells[:count] if cell.cell_type == "code"]
    errors = [o for cell in code for o in cell.outputs if o.output_type == "error"]
    assert not errors
    # Every drawing cell shows its picture.
    drawing = [cell for cell in code if "plot." in cell.source]
    assert len(drawing) == 5
    for cell in drawing:
        assert any("image/png" in o.get("data", {}) for o in cell.outputs), cell.source
    # The sweep wrote its file beside the notebook, and showed its progress bar as a widget.
    (sweep_cell,) = [cell for cell in code if "sweep.phase_diagram(" in cell.source]
    assert (work / "antikink-12x12.csv").read_text().count("\n") == 2 + 144
    views = [o for o in sweep_cell.outputs if "application/vnd.jupyter.widget-view+json" in o.get("data", {})]
    assert views, [o.output_type for o in sweep_cell.outputs]
    # The last cell's value: the outcome at the grid cell nearest the paper's trapped point
    # (k_i/k = 0.7, v0 = 4; docs/dynamics.md §5).
    last = [o for o in code[-1].outputs if o.output_type == "execute_result"]
    assert last and last[0]["data"]["text/plain"] == "'trapped'"
