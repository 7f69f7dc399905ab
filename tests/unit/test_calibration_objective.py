"""Unit tests: misfit terms computed by hand on tiny records."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from onbottom import InputError
from onbottom.calibration.objective import (
    MisfitWeights,
    evaluate_misfit,
    residual_labels,
    residuals,
    time_to_limit,
)
from onbottom.calibration.records import TestRecord


@pytest.fixture
def record() -> TestRecord:
    ds = xr.Dataset(
        {"y": ("time", [0.0, 0.5, 1.0, 2.0]), "z": ("time", [0.10, 0.12, 0.14, 0.14])},
        coords={"time": [0.0, 1.0, 2.0, 3.0]},
    )
    return TestRecord(name="tiny", data=ds, diameter=1.0, displacement_limit=2.0, cycle_period=1.5)


@pytest.fixture
def simulated() -> xr.Dataset:
    return xr.Dataset(
        {"y": ("time", [0.0, 1.0, 2.2]), "z": ("time", [0.11, 0.13, 0.15])},
        coords={"time": [0.0, 2.0, 4.0]},
    )


def test_terms_by_hand(record, simulated):
    m = evaluate_misfit(record, simulated)
    # u resampled at t = 0,1,2,3: [0, 0.5, 1.0, 1.6]; error at t=3 is -0.4; scale = limit 2
    assert m.terms["u_history"] == pytest.approx(0.4 / (2.0 * 2.0))
    # w resampled: [0.11, 0.12, 0.13, 0.14]; errors ±0.01 twice; scale = max w = 0.14
    assert m.terms["w_history"] == pytest.approx(math.sqrt(2 * 0.01**2) / (0.14 * 2.0))
    assert m.terms["initial_penetration"] == pytest.approx(0.01 / 0.10)
    # features of the simulation resampled onto the record: max w 0.14 (the 0.15 at t = 4 is
    # after the record ends), max |u| 1.6 against 2.0 measured
    assert m.terms["max_penetration"] == pytest.approx(0.0)
    assert m.terms["max_displacement"] == pytest.approx(0.4 / 2.0)
    # limit reached: measured at t = 3; simulated at 2 + (2 - 1)/(2.2 - 1)·2 = 3.6667
    assert m.measured["time_to_limit"] == pytest.approx(3.0)
    assert m.simulated["time_to_limit"] == pytest.approx(2.0 + 2.0 / 1.2)
    assert m.simulated["cycles_to_limit"] == pytest.approx((2.0 + 2.0 / 1.2) / 1.5)
    assert m.terms["time_to_limit"] == pytest.approx((2.0 / 1.2 - 1.0) / 3.0)
    assert m.total == pytest.approx(sum(t**2 for t in m.terms.values()))


def test_weights_scale_contributions_and_residual_vector(record, simulated):
    w = MisfitWeights(u_history=4.0, w_history=0.0, time_to_limit=0.0)
    m = evaluate_misfit(record, simulated, w)
    assert "w_history" not in m.terms and "time_to_limit" not in m.terms
    assert m.contributions["u_history"] == pytest.approx(4.0 * 0.1**2)
    r = residuals(record, simulated, w)
    labels = residual_labels(record, w)
    assert len(r) == len(labels) == 3 + 4
    assert float(np.sum(r**2)) == pytest.approx(m.total)
    assert labels[2:6] == [f"u_history[{i}]" for i in range(4)]


def test_identical_simulation_has_zero_misfit(record):
    assert evaluate_misfit(record, record.data).total == 0.0


def test_time_to_limit_surrogate_when_never_reached():
    # max |u| = 1 of limit 2 over 10 s → 10·(1 + 0.5)
    assert time_to_limit(np.array([0.0, 10.0]), np.array([0.0, 1.0]), 2.0) == 15.0
    assert time_to_limit(np.array([0.0, 10.0]), np.array([0.0, -4.0]), 2.0, 0.0) == 5.0


def test_invalid_weights_and_simulation(record):
    with pytest.raises(InputError, match="MisfitWeights.u_history"):
        MisfitWeights(u_history=-1.0)
    with pytest.raises(InputError, match="at least one"):
        MisfitWeights(**dict.fromkeys(MisfitWeights.__slots__, 0.0))
    bad = xr.Dataset({"y": ("time", [0.0, np.nan])}, coords={"time": [0.0, 1.0]})
    with pytest.raises(InputError):
        evaluate_misfit(record, bad)
