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
    assert (tmp_path / "antikink-8x8.csv").read_text().count("\n") == 2 + 64


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
    assert public == set(stubbed) - {"Array", "IntArray", "ArrayLike", "Defect", "WallCharge", "Wall", "Record"}
    for name, members in stubbed.items():
        if members is None or not hasattr(_native, name):
            continue
        runtime = {m for m in dir(getattr(_native, name)) if not m.startswith("_")}
        stub = {m for m in members if not m.startswith("_") or m in ("__len__",)} - {"__len__"}
        assert runtime == stub, f"{name}: only at run time {runtime - stub}, only in the stub {stub - runtime}"


def _stub_defaults():
    """``{(class or None, function): {parameter: default}}`` for every function of the stubs
    whose defaults are literals (``__init__`` stands for the class)."""
    tree = ast.parse((Path(rotor_chain.__file__).parent / "_native.pyi").read_text())
    found = {}

    def defaults(function):
        args = function.args
        positional = args.posonlyargs + args.args
        pairs = list(zip(positional[len(positional) - len(args.defaults) :], args.defaults))
        pairs += [(a, d) for a, d in zip(args.kwonlyargs, args.kw_defaults) if d is not None]
        return {a.arg: ast.literal_eval(d) for a, d in pairs}

    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and not any(
                    isinstance(d, ast.Name) and d.id in ("property", "staticmethod", "classmethod")
                    for d in item.decorator_list
                ):
                    found[(node.name, item.name)] = defaults(item)
        elif isinstance(node, ast.FunctionDef):
            found[(None, node.name)] = defaults(node)
    return found


def test_help_shows_the_stubs_defaults_never_an_ellipsis():
    """``help`` and ``inspect.signature`` read ``__text_signature__``: a default pyo3 cannot
    spell (``Some(AtMost(12))``) would show as ``...``."""
    import inspect

    checked = 0
    for (owner, name), stub in _stub_defaults().items():
        if owner is None:
            target = getattr(_native, name)
        elif name == "__init__":
            target = getattr(_native, owner)
        else:
            target = getattr(getattr(_native, owner), name, None)
        if target is None or not callable(target) or name.startswith("__") and name != "__init__":
            continue
        try:
            signature = inspect.signature(target)
        except (ValueError, TypeError):
            continue
        runtime = {
            p.name: p.default for p in signature.parameters.values() if p.default is not inspect.Parameter.empty
        }
        where = f"{owner}.{name}" if owner else name
        assert Ellipsis not in runtime.values(), f"{where}{signature}"
        # A stub's ``...`` (a default it leaves to the docstring, e.g. DEFAULT_ENERGY_TOLERANCE)
        # matches any value that help can show.
        stub = {p: runtime.get(p, d) if d is Ellipsis else d for p, d in stub.items()}
        assert runtime == stub, f"{where}: help says {signature}, the stub's defaults are {stub}"
        checked += 1
    assert checked >= 15
    assert str(inspect.signature(_native.Chain.modes)) == "(self, /, theta, count=12, *, hold_ends=False)"
