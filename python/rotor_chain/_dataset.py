"""Phase-diagram records as an ``xarray.Dataset`` (``rotor_chain.sweep.to_dataset``)."""

from __future__ import annotations

from typing import Any, Dict, Iterable, List

import numpy as np

# Each record column but the grid's own (i, j, ki, v0): its type in the dataset, the value of a
# cell without one (a failed point, or a point the records lack), and its attributes.
_VARIABLES = {
    "t_decided": (np.float64, np.nan, {"long_name": "time the outcome was decided", "units": "t"}),
    "confirmed": (np.bool_, False, {"long_name": "outcome confirmed before the run ended"}),
    "later": (np.str_, "", {"long_name": "event after the outcome was settled ('annihilated', 'escaped')"}),
    "t_later": (np.float64, np.nan, {"long_name": "time of the later event", "units": "t"}),
    "kinks_final": (np.int64, -1, {"long_name": "kinks at the end of the run"}),
    "antikinks_final": (np.int64, -1, {"long_name": "antikinks at the end of the run"}),
    "energy_error": (np.float64, np.nan, {"long_name": "largest relative energy error", "units": "1"}),
    "integrator": (np.str_, "", {"long_name": "integrator of the record ('verlet', 'dop853', ...)"}),
    "unresolved": (np.str_, "", {"long_name": "why the outcome is not the impurity's alone ('' if it is)"}),
    "unresolved_outcome": (np.str_, "", {"long_name": "DOP853's outcome where the integrators disagree"}),
    "t_unresolved": (np.float64, np.nan, {"long_name": "DOP853's decision, or when an end-born wall reached the impurity", "units": "t"}),
}


def to_dataset(records: Iterable[Dict[str, Any]]):
    """See ``rotor_chain.sweep.to_dataset``."""
    try:
        import xarray as xr
    except ImportError as e:
        raise ImportError("to_dataset needs xarray: pip install xarray (or use sweep.outcome_grid)") from e
    from .sweep import outcome_grid

    records = list(records)
    ki, v0, outcomes = outcome_grid(records)  # GridError past MAX_GRID_POINTS cells
    col = {x: i for i, x in enumerate(ki.tolist())}
    row = {y: j for j, y in enumerate(v0.tolist())}
    shape = (len(v0), len(ki))
    columns: Dict[str, List[Any]] = {name: [fill] * (shape[0] * shape[1]) for name, (_, fill, _) in _VARIABLES.items()}
    error: List[str] = [""] * (shape[0] * shape[1])
    seen = set()
    for r in records:
        cell = row[r["v0"]] * shape[1] + col[r["ki"]]
        if cell in seen:
            raise ValueError(f"two records at ki = {r['ki']!r}, v0 = {r['v0']!r}: records of one sweep have one each")
        seen.add(cell)
        if r["error"] is not None:
            error[cell] = r["error"]
            continue
        for name in _VARIABLES:
            if r[name] is not None:
                columns[name][cell] = r[name]
    dims = ("v0", "ki")
    data = {
        "outcome": (
            dims,
            np.asarray(outcomes, dtype=str).reshape(shape),
            {"long_name": "outcome ('failed': the point failed; '': no record)"},
        ),
        "error": (dims, np.array(error, dtype=str).reshape(shape), {"long_name": "why the point failed"}),
    }
    for name, (kind, _, attrs) in _VARIABLES.items():
        data[name] = (dims, np.array(columns[name], dtype=kind).reshape(shape), attrs)
    return xr.Dataset(
        data,
        coords={
            "ki": ("ki", ki.astype(np.float64), {"long_name": "k_i/k", "units": "1"}),
            "v0": ("v0", v0.astype(np.float64), {"long_name": "v0", "units": "a/t"}),
        },
        attrs={
            "description": "scattering phase diagram (rotor_chain.sweep); a cell without a record "
            "(failed, or not computed) holds NaN, -1, False or '' and its outcome says which",
        },
    )
