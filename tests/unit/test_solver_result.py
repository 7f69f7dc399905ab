"""Unit test: what the three time-domain solvers share at the end of a run (dynamics.result):
the outcome and its message, the D/2 penetration rule, the F109 dynamic criteria."""

from __future__ import annotations

import logging
import math

import numpy as np

from onbottom.dynamics.result import (
    CRITERIA_OVER_D,
    dynamic_criteria,
    penetration_limit,
    penetration_reason,
    records_dataset,
    run_outcome,
)
from onbottom.dynamics.status import Status
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.verley_sotberg import VerleySotberg

LOG = logging.getLogger("onbottom.test")


def test_a_normal_end_keeps_its_status_and_detail(caplog):
    with caplog.at_level(logging.WARNING):
        ok, st, msg = run_outcome(
            LOG, Status.LIMIT, run="storm", t=5.0, dt_min=1e-4, detail="10D at t = 5 s"
        )
    assert (ok, st) == (
        True,
        2,
    ) and msg == "runaway: stopped at the displacement limit (10D at t = 5 s)"
    assert not caplog.records  # a normal end is not a warning


def test_a_failed_run_says_when_and_is_logged(caplog):
    with caplog.at_level(logging.WARNING):
        ok, st, msg = run_outcome(
            LOG, Status.STEP_FAILED, run="storm", t=12.5, dt_min=1e-5, outside="x"
        )
    # a failure is not flagged as outside the validity: its own status is kept
    assert (ok, st) == (False, -1) and "t = 12.5 s, dt_min = 1e-05 s" in msg
    assert caplog.records[0].getMessage() == msg and caplog.records[0].name == "onbottom.test"


def test_a_run_outside_its_model_is_flagged_with_its_end():
    reason = penetration_reason(0.2, 31.0, "y = 0.1 m", 0.25, 0.4, "the vs model")
    ok, st, msg = run_outcome(LOG, Status.END, run="storm", t=60.0, dt_min=1e-4, outside=reason)
    assert (ok, st) == (False, int(Status.OUTSIDE_VALIDITY))
    assert msg == (
        "outside the model's validity: penetration exceeded D/2 = 0.2 m at t = 31.0 s"
        " (y = 0.1 m); largest 0.25 m = 0.625D; the vs model valid for z <= D/2"
        " (the run went on: reached the end of the storm)"
    )


def test_penetration_limit_and_criteria():
    pipe = Pipe(outer_diameter=0.4, submerged_weight=800.0)
    assert penetration_limit(VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))) == 0.2
    assert penetration_limit(CoulombFriction(friction_coefficient=0.6)) == math.inf
    assert CRITERIA_OVER_D == {"0.5D": 0.5, "10D": 10.0}
    assert dynamic_criteria(0.1, 0.4, 10.0, stopped=False) == {"0.5D": True, "10D": True}
    assert dynamic_criteria(1.0, 0.4, 10.0, stopped=False) == {"0.5D": False, "10D": True}
    # stopped at a limit at or below a criterion: that criterion is not met (it would grow on)
    assert dynamic_criteria(0.19, 0.4, 0.5, stopped=True) == {"0.5D": False, "10D": False}
    assert dynamic_criteria(0.19, 0.4, None, stopped=True) == {"0.5D": True, "10D": True}


def test_records_dataset():
    rows = np.array([[0.0, 1.0], [0.5, 2.0]])
    ds = records_dataset(rows, {"y": 1}, 0, {"model": "m"})
    np.testing.assert_array_equal(ds["time"].values, [0.0, 0.5])
    np.testing.assert_array_equal(ds["y"].values, [1.0, 2.0])
    assert ds.attrs["model"] == "m" and ds["y"].attrs["units"] == "m"
