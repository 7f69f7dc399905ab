"""The storms an estimator needs for a target CV (``reliability.run.storm_plan``, hand
calculations) and the campaign's grouped store commits (every finished task committed by the
end of a block, also when the block is interrupted)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from onbottom.reliability.campaign import CampaignStats

pytest.importorskip("zarr")


def _estimate(**kw):
    base = dict(
        label="0.5D", probability=0.01, upper_bound=False, failures=30, method="monte_carlo",
        cv=0.18, storms=3000, pilot_storms=0,
    )  # fmt: skip
    base.update(kw)
    return SimpleNamespace(**base)


def test_monte_carlo_needs_the_binomial_count():
    from onbottom.reliability.run import storm_plan

    stats = CampaignStats(computed=100, compute_cpu_seconds=2.0)
    stats.task_rates.extend([0.5, 0.02, 0.02, 0.019, 0.021])  # the first task compiled
    plan = storm_plan(_estimate(), 0.1, stats)
    # n = (1 - p)/(p CV^2) = 0.99/(0.01 * 0.01) = 9900 storms at 0.02 CPU-s each
    assert plan["storms"] == 9900.0
    assert plan["cpu_seconds_per_storm"] == pytest.approx(0.02)
    assert plan["cpu_seconds"] == pytest.approx(198.0)
    assert not plan["lower_bound"]


def test_importance_sampling_scales_its_sampled_storms_by_the_cv_ratio():
    from onbottom.reliability.run import storm_plan

    e = _estimate(method="importance", cv=0.2, storms=1200, pilot_storms=200)
    stats = CampaignStats(computed=10, compute_cpu_seconds=0.5)
    stats.task_rates.append(0.05)
    plan = storm_plan(e, 0.1, stats)
    # (1200 - 200) * (0.2/0.1)^2 + 200 = 4200
    assert plan["storms"] == 4200.0
    assert plan["cpu_seconds"] == pytest.approx(4200 * 0.05)


def test_without_a_failure_or_a_computed_storm_the_plan_says_so():
    from onbottom.reliability.run import storm_plan

    plan = storm_plan(_estimate(probability=0.0, failures=0), 0.1, CampaignStats())
    assert math.isnan(plan["storms"]) and math.isnan(plan["cpu_seconds"])
    assert plan["lower_bound"]
    # an upper bound p <= 0.095 and no failing storm: Monte Carlo at the bound,
    # 0.905/(0.095 * 0.01) = 952.6 -> at least 953 storms, whatever the method
    e = _estimate(method="importance", probability=0.095, failures=0, upper_bound=True)
    plan = storm_plan(e, 0.1, CampaignStats())
    assert plan["storms"] == 953.0 and plan["lower_bound"] and plan["method"] == "monte_carlo"


class _Model:
    input_names = ("a",)
    output_names = ("y",)

    def __init__(self, stop_at: int | None = None) -> None:
        self.stop_at = stop_at
        self.calls = 0

    def identity(self) -> str:
        return "test model y = 2a"

    def __call__(self, x, seed):
        self.calls += 1
        if self.stop_at is not None and self.calls > self.stop_at:
            raise KeyboardInterrupt
        return {"y": 2.0 * float(x[0])}


def test_grouped_commits_keep_every_finished_task(tmp_path):
    from onbottom.reliability.campaign import Campaign, ResultStore

    x = np.arange(40.0).reshape(-1, 1)
    seeds = np.arange(40)
    with Campaign(_Model(), tmp_path / "s.zarr", n_workers=0, task_size=4,
                  commit_interval=1e9) as c:  # fmt: skip
        out, _ = c.evaluate(x, seeds)
    np.testing.assert_array_equal(out[:, 0], 2.0 * x[:, 0])
    assert len(ResultStore(tmp_path / "s.zarr", "test model y = 2a", ("a",), ("y",))) == 40
    # interrupted after 10 runs: the two finished tasks (8 rows) are committed, not lost
    with Campaign(_Model(stop_at=10), tmp_path / "i.zarr", n_workers=0, task_size=4,
                  commit_interval=1e9) as c:  # fmt: skip
        with pytest.raises(KeyboardInterrupt):
            c.evaluate(x, seeds)
    assert len(ResultStore(tmp_path / "i.zarr", "test model y = 2a", ("a",), ("y",))) == 8


def test_commit_interval_is_checked(tmp_path):
    from onbottom.errors import InputError
    from onbottom.reliability.campaign import Campaign

    with pytest.raises(InputError, match="commit_interval"):
        Campaign(_Model(), tmp_path / "s.zarr", n_workers=0, commit_interval=-1.0)
