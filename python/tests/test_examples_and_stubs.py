"""The example script runs and draws its two figures; the type stubs name every class, method and
function of the compiled module, and nothing it lacks."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import rotor_chain
from rotor_chain import _native

HERE = Path(__file__).resolve().parent


def test_the_example_draws_fig_akenergy_and_a_phase_diagram(tmp_path):
    script = HERE.parent / "examples" / "paper_figures.py"
    done = subprocess.run(
        [sys.executable, str(script), "--out", str(tmp_path), "--quick"], capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stderr
    for name in ("akenergy.png", "phasediagram.png"):
        png = (tmp_path / name).read_bytes()
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000, name
    assert (tmp_path / "antikink.csv").read_text().count("\n") == 2 + 64


def _stubbed():
    tree = ast.parse((Path(rotor_chain.__file__).parent / "_native.pyi").read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            members = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members.add(item.name)
                elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                    members.add(item.target.id)
            names[node.name] = members
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names[node.target.id] = None
    return names


def test_the_stubs_match_the_compiled_module():
    stubbed = _stubbed()
    public = {n for n in dir(_native) if not n.startswith("_")} | {"__version__"}
    assert public == set(stubbed) - {"Array", "ArrayLike", "Defect", "WallCharge", "Wall", "Record"}
    for name, members in stubbed.items():
        if members is None or not hasattr(_native, name):
            continue
        runtime = {m for m in dir(getattr(_native, name)) if not m.startswith("_")}
        stub = {m for m in members if not m.startswith("_") or m in ("__len__",)} - {"__len__"}
        assert runtime == stub, f"{name}: only at run time {runtime - stub}, only in the stub {stub - runtime}"
