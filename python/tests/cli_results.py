"""The `phase-diagram` command (Rust) as the reference of the sweep tests: run it, and read its CSV
with Python's csv module (not with the binding under test)."""

from __future__ import annotations

import csv
import subprocess
from pathlib import Path
from typing import Any, Dict, List, Optional

INTS = {"i", "j", "kinks_final", "antikinks_final"}
FLOATS = {"ki", "v0", "t_decided", "t_later", "energy_error", "t_unresolved"}


def run_cli(cli: Path, out: Path, defect: str, ki: str, v0: str, *extra: str) -> subprocess.CompletedProcess:
    args = [str(cli), "--defect", defect, "--ki", ki, "--v0", v0, "--out", str(out), *extra]
    return subprocess.run(args, capture_output=True, text=True, timeout=600, check=False)


def parse(value: str, column: str) -> Any:
    if value == "":
        return None
    if column in INTS:
        return int(value)
    if column in FLOATS:
        return float(value)
    if column == "confirmed":
        return {"true": True, "false": False}[value]
    return value


def read_csv(path: Path) -> List[Dict[str, Any]]:
    """The records of a results file, in grid order, as the binding returns them."""
    with open(path, newline="") as f:
        preamble = f.readline()
        assert preamble.startswith("# chain-sweep v1; grid "), preamble
        rows = list(csv.DictReader(f))
    records = []
    for row in rows:
        record = {("ki" if k == "x" else "v0" if k == "y" else k): v for k, v in row.items()}
        records.append({k: parse(v, k) for k, v in record.items()})
    return sorted(records, key=lambda r: (r["i"], r["j"]))


def cli_records(cli: Path, out: Path, defect: str, ki: str, v0: str, *extra: str) -> List[Dict[str, Any]]:
    done = run_cli(cli, out, defect, ki, v0, *extra)
    assert done.returncode in (0, 3), done.stderr
    return read_csv(out)


def preamble(path: Path) -> str:
    return Path(path).read_text().splitlines()[0]


def line_count(path: Optional[Path]) -> int:
    return len(Path(path).read_text().splitlines()) if path and Path(path).exists() else 0
