"""The dynamic-design search of `onbottom assess` (assess.dynamic.search_dynamic) on step
functions with a known answer: no storms, hand-checkable."""

from __future__ import annotations

import json

import numpy as np
import pytest

from onbottom.assess.dynamic import bisect_dynamic, search_dynamic
from onbottom.status import Status


def _step(threshold: float):
    """g(x) = 0.5 (passes) for x >= threshold, 1.5 (fails) below; one storm a trial."""

    def evaluate(x: float) -> tuple[float, int]:
        return (0.5 if x >= threshold else 1.5), 1

    return evaluate


def test_a_bracket_wider_than_tol_by_round_off_only_is_closed():
    """a = 0.009 fails, b = 0.01 passes: b − a = 0.0010000000000000009 > tol = 0.001 by
    round-off. The search used to spin here for ever (one step onto b, no progress: found by
    the gallery's ex11 hanging); it now returns b with no new trial but the confirmation."""
    s = search_dynamic(
        _step(0.0095), 0.0, 0.02, 0.001, known=[(0.009, 1.5), (0.01, 0.5)], confirm=1
    )
    assert s["status"] is Status.CONVERGED and s["value"] == 0.01
    assert [x for x, _ in s["trials"]] == [pytest.approx(0.011)]  # the confirmation only


@pytest.mark.parametrize("tol", [0.001, 0.002, 0.005])
def test_the_design_found_is_within_tol_above_the_threshold(tol):
    rng = np.random.default_rng(3)
    for threshold in np.concatenate([rng.uniform(0.0005, 0.19, 40), np.arange(1, 40) * 0.005]):
        known = [(round(k * 0.001, 3), 1.5 if k * 0.001 < threshold else 0.5) for k in (3, 40)]
        s = search_dynamic(_step(float(threshold)), 0.0, 0.2, tol, known=known)
        assert s["status"] is Status.CONVERGED, threshold
        assert threshold <= s["value"] <= threshold + tol * (1 + 1e-9), (threshold, s["value"])
        assert s["bracket"][1] - s["bracket"][0] <= tol * (1 + 1e-9)


@pytest.mark.parametrize("search", [search_dynamic, bisect_dynamic])
def test_the_three_outcomes_are_solver_statuses(search):
    """One status convention (docs/conventions.md, "Solver status"): a design found is
    CONVERGED (6), a passing lower bound AT_BOUND (7), no passing value NO_SOLUTION (-6);
    results.json writes the number."""
    found = search(_step(0.05), 0.0, 0.2, 0.01)
    assert found["status"] is Status.CONVERGED and found["status"].success
    assert 0.05 <= found["value"] <= 0.06
    at_lo = search(_step(0.0), 0.01, 0.2, 0.01)
    assert at_lo["status"] is Status.AT_BOUND and at_lo["value"] == 0.01
    none = search(_step(0.5), 0.0, 0.2, 0.01)
    assert none["status"] is Status.NO_SOLUTION and not none["status"].success
    assert none["value"] is None
    assert json.loads(json.dumps({"status": found["status"]})) == {"status": 6}
