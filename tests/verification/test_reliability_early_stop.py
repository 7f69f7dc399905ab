"""Verification of the reliability campaign's early stop: storms stopped just above the largest
limit asked give the verdicts of the whole storms, storm by storm and in the estimates (subset
simulation and Monte Carlo), and the estimates say how many storms stopped early."""

from __future__ import annotations

import tomllib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("openturns")
pytest.importorskip("zarr")

from onbottom._casefile import parse_case
from onbottom.cases.storm import StormCase, build_setup
from onbottom.reliability import UncertainParameter
from onbottom.reliability.campaign import Campaign
from onbottom.reliability.dynamic import estimate_exceedance, seeds_from_uniform
from onbottom.reliability.run import EARLY_STOP_MARGIN, stop_displacement
from onbottom.reliability.setup import ReliabilitySetup
from onbottom.reliability.storm_model import StormModel

pytestmark = pytest.mark.verification

ROOT = Path(__file__).resolve().parents[2]
PARAMS = [
    UncertainParameter("hs", "normal", {"mean": 3.5, "std": 0.5}),
    UncertainParameter("tp", "uniform", {"low": 9.0, "high": 12.0}),
]


def _models() -> tuple[StormModel, StormModel, float]:
    """(whole storms, storms stopped above the limit, the limit [m]): a 0.05-h storm of
    examples/storm_case.toml, limit 0.2D (about a third of the storms exceed it)."""
    doc = tomllib.loads((ROOT / "examples" / "storm_case.toml").read_text())
    doc["storm"].update(build_up_hours=0.0, peak_hours=0.05)
    full = StormModel(build_setup(parse_case(StormCase, doc)), inputs=("hs", "tp"))
    limit = 0.2 * full.diameter
    return full, replace(full, stop_at=limit * (1.0 + EARLY_STOP_MARGIN)), limit


def test_stopped_storms_keep_the_whole_storms_verdicts_storm_by_storm(tmp_path):
    full, early, limit = _models()
    rng = np.random.default_rng(5)
    n = 24
    x = np.column_stack([rng.normal(3.5, 0.5, n), rng.uniform(9.0, 12.0, n)])
    seeds = seeds_from_uniform(rng.uniform(size=n))
    k = full.output_names.index("max_displacement")
    ks = full.output_names.index("stopped_early")
    with Campaign(full, tmp_path / "a.zarr", n_workers=0) as c:
        yf, sf = c.evaluate(x, seeds)
    with Campaign(early, tmp_path / "b.zarr", n_workers=0) as c:
        ye, se = c.evaluate(x, seeds)
    exceed = yf[:, k] > limit
    assert 0 < exceed.sum() < n  # both verdicts occur
    assert np.array_equal(ye[:, k] > limit, exceed)
    stopped = ye[:, ks] == 1.0
    assert stopped.any() and not (yf[:, ks] == 1.0).any()
    assert np.all(exceed[stopped])
    # a storm that never reaches the stop runs exactly as the whole storm
    assert np.array_equal(ye[~stopped], yf[~stopped])
    assert np.array_equal(se[~stopped], sf[~stopped])
    # a stopped storm's displacement is a lower bound of the whole storm's, and beyond the stop
    assert np.all(ye[stopped, k] <= yf[stopped, k])
    assert np.all(ye[stopped, k] >= early.stop_at)


@pytest.mark.parametrize("method", ["subset", "monte_carlo", "importance"])
def test_an_early_stopped_estimate_equals_the_whole_storms_estimate(tmp_path, method):
    full, early, limit = _models()
    kw = {"method": method, "block_size": 40, "max_storms": 80, "target_cv": 0.01, "seed": 3}
    with Campaign(full, tmp_path / "a.zarr", n_workers=0, task_size=8) as c:
        a = estimate_exceedance(c, PARAMS, limit, **kw)
    with Campaign(early, tmp_path / "b.zarr", n_workers=0, task_size=8) as c:
        b = estimate_exceedance(c, PARAMS, limit, **kw)
    assert 0.0 < a.probability < 1.0
    assert b.probability == a.probability
    assert b.cv == a.cv or (np.isnan(a.cv) and np.isnan(b.cv))
    assert b.storms == a.storms
    assert b.history == a.history
    assert b.curve == a.curve
    assert a.stopped_early == 0 and b.stopped_early > 0
    assert b.to_dict()["stopped_early"] == b.stopped_early


def test_the_stop_is_just_above_the_largest_limit_for_every_estimator():
    full, _, _ = _models()
    s = ReliabilitySetup(
        storm=full.setup,
        limits=(("0.5D", 0.2), ("1D", 0.4)),
        seabed_model="sand",
        storms_per_year=3.0,
    )
    assert stop_displacement(s) == pytest.approx(0.4 * (1.0 + EARLY_STOP_MARGIN), rel=1e-15)
    assert stop_displacement(s) > 0.4
    for method in ("importance", "subset", "monte_carlo"):
        assert stop_displacement(replace(s, method=method)) == stop_displacement(s)
