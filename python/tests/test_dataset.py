"""rotor_chain.sweep.to_dataset: every variable at every cell is the record's value (a sweep with
a point removed and one failed point), the fill of cells without a record, the coordinates and
their order; the errors."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
import xarray  # noqa: F401  (the test requirements have it)

import rotor_chain as rc
from rotor_chain import sweep

FIELDS = ("t_decided", "confirmed", "later", "t_later", "kinks_final", "antikinks_final", "energy_error", "integrator")


@pytest.fixture(scope="module")
def records():
    # Over the trapped/transmitted border near k_i/k = 0.75 (docs/dynamics.md §5).
    recs = sweep.phase_diagram("antikink", "0.6:0.9:4", "3:4.5:4", progress=False)
    assert {r["outcome"] for r in recs} >= {"trapped", "transmitted"}
    # A sweep stops at the confirmed outcome, so its records have no later event; give one a
    # later event as Chain.scatter(..., watch=...) finds it (the README's (4.0, 0.7) point).
    assert all(r["later"] is None for r in recs)
    recs[2] = dict(recs[2], later="annihilated", t_later=8.1875)
    return recs


def test_every_variable_is_the_records_value(records):
    missing = records[5]
    failed = dict(records[9])
    failed.update({key: None for key in FIELDS + ("outcome",)}, error="energy budget: 0.02 > 0.005 (a test's)")
    given = [r for k, r in enumerate(records) if k not in (5, 9)] + [failed]
    ds = sweep.to_dataset(given)
    assert ds.outcome.dims == ("v0", "ki") and ds.sizes == {"v0": 4, "ki": 4}
    assert ds.ki.values.tolist() == sorted({r["ki"] for r in records})
    assert ds.v0.values.tolist() == sorted({r["v0"] for r in records})
    assert ds.ki.attrs["long_name"] == "k_i/k" and ds.v0.attrs["units"] == "a/t"
    assert ds.t_decided.attrs["units"] == "t"
    checked = 0
    for r in given:
        cell = ds.sel(ki=r["ki"], v0=r["v0"])  # exact coordinates: floats bit for bit
        if r["error"] is not None:
            assert cell.outcome.item() == "failed" and cell.error.item() == r["error"]
            assert math.isnan(cell.t_decided.item()) and math.isnan(cell.energy_error.item())
            assert cell.kinks_final.item() == -1 and cell.confirmed.item() is False and cell.integrator.item() == ""
            continue
        assert cell.outcome.item() == r["outcome"] and cell.error.item() == ""
        for name in FIELDS:
            value = cell[name].item()
            if r[name] is None:  # later and t_later of a point without a later event
                assert value == "" if name == "later" else math.isnan(value), (name, value)
            else:
                assert value == r[name] and type(value) is type(r[name]), (name, value, r[name])
        checked += 1
    assert checked == 14
    hole = ds.sel(ki=missing["ki"], v0=missing["v0"])
    assert hole.outcome.item() == "" and math.isnan(hole.t_decided.item()) and hole.antikinks_final.item() == -1
    # The variables are numpy types, ready for xarray's arithmetic and files.
    assert ds.t_decided.dtype == np.float64 and ds.kinks_final.dtype == np.int64 and ds.confirmed.dtype == bool
    assert (ds.outcome == "trapped").sum().item() == sum(r["outcome"] == "trapped" for r in given)


def test_a_dataset_agrees_with_outcome_grid(records):
    ki, v0, outcomes = sweep.outcome_grid(records)
    ds = sweep.to_dataset(records)
    assert np.array_equal(ds.ki.values, ki) and np.array_equal(ds.v0.values, v0)
    assert ds.outcome.values.tolist() == outcomes.tolist()


def test_two_records_of_one_cell_are_refused(records):
    with pytest.raises(ValueError, match="two records at ki = "):
        sweep.to_dataset(records + [records[0]])


def test_without_xarray_the_error_says_what_to_install(records, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(ImportError, match="pip install xarray"):
        sweep.to_dataset(records)
    assert rc.sweep.outcome_grid(records)[2].shape == (4, 4)  # the rest works without it
