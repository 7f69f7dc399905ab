"""Unit test: a campaign task records each run's status in the one enumeration (Status)."""

from __future__ import annotations

import numpy as np

from onbottom.reliability.campaign import STATUS_RAISED, run_task
from onbottom.status import Status


class _Model:
    input_names = ("a",)
    output_names = ("y",)

    def identity(self) -> str:
        return "hand"

    def __call__(self, x: np.ndarray, seed: int) -> dict:
        if seed == 1:
            raise RuntimeError("boom")
        if seed == 2:
            return {"y": 2.0 * x[0], "status": Status.OUTSIDE_VALIDITY, "message": "z > D/2"}
        return {"y": 2.0 * x[0]}  # no status: ran to the end


def test_run_task_statuses_are_the_enumeration():
    res = run_task(_Model(), np.array([[1.0], [2.0], [3.0]]), np.array([0, 1, 2]))
    assert STATUS_RAISED == Status.RAISED == -9
    assert res["status"].tolist() == [Status.END, Status.RAISED, Status.OUTSIDE_VALIDITY]
    assert res["outputs"][0, 0] == 2.0 and np.isnan(res["outputs"][1, 0])
    assert res["outputs"][2, 0] == 6.0
    assert [i for i, _ in res["messages"]] == [1, 2] and "boom" in res["messages"][0][1]
