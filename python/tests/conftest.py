"""Shared fixtures: the Rust side of every comparison comes from Rust programs, never from the
binding under test.

- ``reference(cases)`` runs ``rotor-chain-reference`` (python/reference/), which computes each case
  with the ``rotor_chain`` Rust library directly and prints JSON (floats that read back exactly).
- ``phase_diagram_cli`` is the path of the ``phase-diagram`` command (chain-sweep).

``cargo xtask test`` builds both and passes their paths in ``ROTOR_CHAIN_REFERENCE`` and
``PHASE_DIAGRAM``; without those, ``target/debug`` of the repository is used.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any, Dict, List

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]


def _binary(env: str, name: str) -> Path:
    path = Path(os.environ.get(env, REPO / "target" / "debug" / name))
    if not path.is_file():
        pytest.fail(
            f"{path} does not exist: build it with `cargo build -p rotor-chain-reference -p rotor-chain-sweep --bins` "
            f"(or run the whole suite with `cargo xtask test`), or set {env}"
        )
    return path


@pytest.fixture(scope="session")
def reference():
    binary = _binary("ROTOR_CHAIN_REFERENCE", "rotor-chain-reference")

    def run(cases: List[Dict[str, Any]]) -> List[Dict[str, Any]]:
        cases = [_plain(c) for c in cases]
        done = subprocess.run(
            [str(binary)], input=json.dumps(cases), capture_output=True, text=True, timeout=600, check=False
        )
        assert done.returncode == 0, done.stderr
        results = json.loads(done.stdout)
        assert len(results) == len(cases)
        return results

    return run


@pytest.fixture(scope="session")
def phase_diagram_cli() -> Path:
    return _binary("PHASE_DIAGRAM", "phase-diagram")


def _plain(value: Any) -> Any:
    """numpy arrays and scalars as JSON-able lists and floats."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return _plain(value.item())
    if isinstance(value, float) and not np.isfinite(value):
        return str(value)  # "nan", "inf", "-inf": read by the reference program
    return value


def close(actual: Any, expected: Any, rtol: float = 1e-12, what: str = "") -> None:
    """``actual`` equals ``expected`` to ``rtol`` relative to the largest magnitude of ``expected``
    (so entries that are zero up to rounding compare on the scale of the whole array)."""
    a = np.asarray(actual, dtype=float)
    e = np.asarray(expected, dtype=float)
    assert a.shape == e.shape, f"{what}: shape {a.shape} != {e.shape}"
    scale = max(float(np.max(np.abs(e))) if e.size else 0.0, 1e-300)
    err = float(np.max(np.abs(a - e))) if e.size else 0.0
    assert err <= rtol * scale, f"{what}: max |difference| {err:.3e} > {rtol:.0e} x {scale:.3e}"


def assert_same_object(got: Any, expected: Any, what: str = "") -> List[str]:
    """``got`` is of ``expected``'s class, has its ``repr``, and every public attribute of it
    equal: numpy arrays of the same dtype, shape and bytes, floats bit for bit, nested results
    (``rotor_chain._native`` objects) compared the same way. Returns the names compared."""
    what = what or type(expected).__name__
    assert type(got) is type(expected), f"{what}: {type(got)} is not {type(expected)}"
    assert repr(got) == repr(expected), what
    names = [n for n in dir(expected) if not n.startswith("_") and not callable(getattr(expected, n))]
    assert names, f"{what}: no attributes to compare"
    for name in names:
        _assert_same_value(getattr(got, name), getattr(expected, name), f"{what}.{name}")
    return names


def _assert_same_value(got: Any, expected: Any, what: str) -> None:
    if isinstance(expected, np.ndarray):
        assert isinstance(got, np.ndarray), what
        assert (got.dtype, got.shape) == (expected.dtype, expected.shape), what
        assert got.tobytes() == expected.tobytes(), what
    elif type(expected).__module__ == "rotor_chain._native":
        assert_same_object(got, expected, what)
    elif isinstance(expected, float):
        assert type(got) is float and got.hex() == expected.hex(), f"{what}: {got!r} != {expected!r}"
    else:
        assert type(got) is type(expected) and got == expected, f"{what}: {got!r} != {expected!r}"
