"""Verification of the reliability campaign (issue 34 items 3, 4, 6): the estimators recover a
closed-form probability through the campaign path (Zarr store, task identity, seed as an
input); a rerun reads every storm back; Dask gives the serial answer; a campaign killed at any
time resumes to the uninterrupted result; Monte Carlo and subset simulation agree on an
affordable dynamic (storm) case."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("openturns")
pytest.importorskip("zarr")

from onbottom.reliability import UncertainParameter
from onbottom.reliability.campaign import Campaign, ResultStore
from onbottom.reliability.closed_form import FrictionModel
from onbottom.reliability.dynamic import estimate_exceedance, seeds_from_uniform

pytestmark = pytest.mark.verification

MU = (0.6, 0.06)
LOAD = (480.0, 75.0)


def _params():
    return [
        UncertainParameter("friction_coefficient", "normal", {"mean": MU[0], "std": MU[1]}),
        UncertainParameter("load", "normal", {"mean": LOAD[0], "std": LOAD[1]}),
    ]


@pytest.mark.parametrize("scatter", [0.0])  # 0.1: the coverage test (its estimates skew low)
def test_importance_sampling_recovers_the_closed_form_through_the_campaign(tmp_path, scatter):
    model = FrictionModel(scatter=scatter)
    exact = model.exact_probability(MU, LOAD)
    est = []
    for seed in range(4):  # one run misses its 95 % interval 1 time in 13 (coverage test)
        with Campaign(model, tmp_path / "s.zarr", n_workers=0, task_size=100) as c:
            r = estimate_exceedance(
                c, _params(), 1.0, method="importance", target_cv=0.1, block_size=500, seed=seed
            )
        assert r.cv <= 0.1
        est.append((r.probability, r.cv * r.probability))
    p, se = np.mean([e[0] for e in est]), np.sqrt(sum(e[1] ** 2 for e in est)) / 4
    assert abs(p - exact) <= 3.0 * se
    assert {"friction_coefficient", "load"} <= set(r.importance)  # SRRC², the pilot's 1st block
    assert r.failure_mean["friction_coefficient"] < 0.0 < r.failure_mean["load"]
    assert r.storms == c.stats.requested  # the pilot's runs and the sampling, all in the store


def test_subset_recovers_the_seed_scattered_probability_and_a_rerun_reads_it_back(tmp_path):
    model = FrictionModel(scatter=0.1)
    exact = model.exact_probability(MU, LOAD)  # 7.35e-4: the seed's scatter integrated
    ests = []
    for seed in range(4):
        with Campaign(model, tmp_path / "s.zarr", n_workers=0, task_size=100) as c:
            ests.append(
                estimate_exceedance(c, _params(), 1.0, method="subset", block_size=1000, seed=seed)
            )
    p = np.array([e.probability for e in ests])
    # the CV neglects the levels' correlation (docs/theory/reliability.md): the mean of 4
    # within 3 x 2 x stated CV / 2
    cv = float(np.mean([e.cv for e in ests]))
    assert abs(p.mean() - exact) <= 3.0 * 2.0 * cv * exact / 2.0
    with Campaign(model, tmp_path / "s.zarr", n_workers=0, task_size=100) as c:
        again = estimate_exceedance(c, _params(), 1.0, method="subset", block_size=1000, seed=0)
        assert c.stats.computed == 0 and c.stats.reused == again.storms
    assert again.probability == ests[0].probability
    # SRRC²: load and friction explain most of Y; the seed's share is the residual
    imp = ests[0].importance
    assert imp["load"] > imp["friction_coefficient"] > 0.0
    assert 0.0 < imp["storm_seed and interactions"] < 0.5


def test_a_store_of_another_model_is_refused(tmp_path):
    with Campaign(FrictionModel(), tmp_path / "s.zarr", n_workers=0) as c:
        c.evaluate(np.array([[0.6, 400.0]]), np.array([1]))
    with pytest.raises(Exception, match="another model"):
        Campaign(FrictionModel(weight=1000.0), tmp_path / "s.zarr", n_workers=0)


def test_dask_gives_the_serial_result(tmp_path):
    model = FrictionModel(scatter=0.1)
    rng = np.random.default_rng(0)
    x = np.column_stack([rng.normal(*MU, 64), rng.normal(*LOAD, 64)])
    seeds = seeds_from_uniform(rng.uniform(size=64))
    with Campaign(model, tmp_path / "a.zarr", n_workers=0, task_size=5) as c:
        serial, _ = c.evaluate(x, seeds)
    with Campaign(model, tmp_path / "b.zarr", n_workers=2, task_size=5) as c:
        dask, _ = c.evaluate(x, seeds)
    np.testing.assert_array_equal(serial, dask)
    assert len(ResultStore(tmp_path / "b.zarr", model.identity(), ("a", "b"), ("y",))) == 64


_SCRIPT = textwrap.dedent(
    """
    import json, sys
    from onbottom.reliability import UncertainParameter as U
    from onbottom.reliability.campaign import Campaign
    from onbottom.reliability.closed_form import FrictionModel
    from onbottom.reliability.dynamic import estimate_exceedance
    ps = [U("friction_coefficient", "normal", {"mean": 0.6, "std": 0.06}),
          U("load", "normal", {"mean": 700.0, "std": 75.0})]
    with Campaign(FrictionModel(scatter=0.1, delay=0.002), sys.argv[1], n_workers=0,
                  task_size=10) as c:
        r = estimate_exceedance(c, ps, 1.0, method="monte_carlo", target_cv=0.01,
                                max_storms=1500, block_size=300, seed=5)
    print(json.dumps([r.probability, r.cv, r.storms, c.stats.computed]))
    """
)


def _committed(store: Path) -> int:
    """Rows the store's metadata says are committed (0 while absent or being written)."""
    import json

    try:
        return int(json.loads((store / "zarr.json").read_text())["attributes"]["n_rows"])
    except (OSError, ValueError, KeyError, TypeError):
        return 0


def _run(store: Path, kill_after: float | None = None, kill_at_rows: int | None = None):
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[2] / "src"))
    p = subprocess.Popen(
        [sys.executable, "-c", _SCRIPT, str(store)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
        text=True,
    )
    if kill_at_rows is not None:  # SIGKILL as soon as the store holds that many rows
        deadline = time.monotonic() + 600.0
        while p.poll() is None and time.monotonic() < deadline:
            if _committed(store) >= kill_at_rows:
                break
            time.sleep(0.01)
        kill_after = 0.0
    if kill_after is not None:
        time.sleep(kill_after)
        p.send_signal(signal.SIGKILL)
        p.communicate()
        return None
    out, err = p.communicate()
    assert p.returncode == 0, err
    import json

    return json.loads(out.strip().splitlines()[-1])


def _store(store: Path) -> ResultStore:
    return ResultStore(store, FrictionModel(scatter=0.1).identity(), ("a", "b"), ("y",))


def _rows(store: Path):
    s = _store(store)
    rows = [
        np.column_stack([b["inputs"], b["seed"], b["outputs"], b["status"]]) for b in s.iter_rows()
    ]
    a = np.concatenate(rows)
    return a[np.lexsort(a.T[::-1])]


@pytest.mark.slow
@pytest.mark.long
def test_resume_after_kill_equals_an_uninterrupted_run(tmp_path):
    ref = _run(tmp_path / "ref.zarr")
    assert ref[2] == 1500 and ref[3] == 1500
    partial = []
    # kills at fixed delays land before the store exists on a loaded machine (imports take
    # longer): the first kill waits for a committed row, the others land after 0.5 s and 3 s
    for i, (delay, rows) in enumerate(((None, 1), (0.5, None), (3.0, None))):
        store = tmp_path / f"k{i}.zarr"
        _run(store, kill_after=delay, kill_at_rows=rows)
        if (store / "zarr.json").exists():
            partial.append(len(_store(store)))
        res = _run(store)
        assert res[:3] == ref[:3]  # the same estimate from the same storms
        assert res[3] <= 1500  # what the kill had committed was not rerun
        np.testing.assert_array_equal(_rows(store), _rows(tmp_path / "ref.zarr"))
    assert any(0 < n < 1500 for n in partial), partial  # at least one kill landed mid-campaign


@pytest.mark.slow
@pytest.mark.long
def test_resume_after_a_kill_at_a_random_time_equals_an_uninterrupted_run(tmp_path):
    """SIGKILL at a time drawn uniformly over the uninterrupted run's wall time (its seed in the
    failure message; ONBOTTOM_KILL_SEED replays one), twice on the same store, then a rerun:
    the same estimate, the same stored rows, and nothing committed recomputed."""
    seed = int(os.environ.get("ONBOTTOM_KILL_SEED", time.time_ns() % 2**32))
    rng = np.random.default_rng(seed)
    t0 = time.perf_counter()
    ref = _run(tmp_path / "ref.zarr")
    wall = time.perf_counter() - t0
    store = tmp_path / "killed.zarr"
    done = []
    for _ in range(2):
        _run(store, kill_after=float(rng.uniform(0.0, wall)))
        done.append(len(_store(store)) if (store / "zarr.json").exists() else 0)
    res = _run(store)
    why = f"ONBOTTOM_KILL_SEED={seed}, wall {wall:.1f} s, rows after the kills {done}"
    assert res[:3] == ref[:3], why
    assert res[3] == 1500 - done[-1], why  # exactly the rows the kills had not committed
    np.testing.assert_array_equal(_rows(store), _rows(tmp_path / "ref.zarr"), err_msg=why)


@pytest.mark.slow
@pytest.mark.long
def test_monte_carlo_and_subset_agree_on_a_dynamic_storm_case(tmp_path):
    """A short storm (0.05 h build-up, 0.15 h peak) of examples/storm_case.toml with
    H_s ~ N(3.5, 0.5) m, T_p ~ U(9, 12) s, μ ~ N(0.6, 0.06) and the seed: P[Y > 2D] ≈ 0.2
    per storm with the load-reversal reading of V&S (≈ 0.04 with the former, whose pipe dug
    itself in), affordable by Monte Carlo (1000 storms) and by subset simulation (200 a level)."""
    import tomllib

    from onbottom._casefile import parse_case
    from onbottom.cases.storm import StormCase, build_setup
    from onbottom.reliability.storm_model import StormModel

    root = Path(__file__).resolve().parents[2]
    doc = tomllib.loads((root / "examples" / "storm_case.toml").read_text())
    doc["storm"].update(build_up_hours=0.05, peak_hours=0.15)
    model = StormModel(
        build_setup(parse_case(StormCase, doc)),
        inputs=("hs", "tp", "friction_coefficient"),
        soil_kind="sand",
    )
    params = [
        UncertainParameter("hs", "normal", {"mean": 3.5, "std": 0.5}),
        UncertainParameter("tp", "uniform", {"low": 9.0, "high": 12.0}),
        UncertainParameter("friction_coefficient", "normal", {"mean": 0.6, "std": 0.06}),
    ]
    limit = 2.0 * model.diameter
    with Campaign(model, tmp_path / "s.zarr", n_workers=0, task_size=20) as c:
        mc = estimate_exceedance(
            c,
            params,
            limit,
            method="monte_carlo",
            target_cv=0.01,
            max_storms=1000,
            block_size=200,
            seed=1,
        )
        ss = estimate_exceedance(c, params, limit, method="subset", block_size=200, seed=2)
    assert mc.storms == 1000 and mc.failed_runs == 0
    assert 0.01 < mc.probability < 0.4
    # subset's stated CV is about half its real one (docs/theory/reliability.md): doubled here
    sigma = np.hypot(mc.cv * mc.probability, 2.0 * ss.cv * ss.probability)
    assert abs(mc.probability - ss.probability) <= 3.0 * sigma
    assert ss.storms < mc.storms
    # H_s drives the response more than μ; the seed's share is substantial
    assert mc.importance["hs"] > mc.importance["friction_coefficient"]
    assert mc.importance["storm_seed and interactions"] > 0.05


def test_a_store_killed_while_being_created_starts_afresh_and_a_foreign_group_is_kept(tmp_path):
    import zarr

    half = tmp_path / "half.zarr"
    zarr.open_group(str(half), mode="w").create_array("inputs", shape=(0, 2), dtype="float64")
    with Campaign(FrictionModel(), half, n_workers=0) as c:  # no attributes yet: recreated
        c.evaluate(np.array([[0.6, 400.0]]), np.array([1]))
    assert len(ResultStore(half, FrictionModel().identity(), ("a", "b"), ("y",))) == 1
    other = tmp_path / "other.zarr"
    zarr.open_group(str(other), mode="w").create_array("data", shape=(3,), dtype="float64")
    with pytest.raises(Exception, match="not an onbottom campaign store"):
        Campaign(FrictionModel(), other, n_workers=0)
    assert "data" in zarr.open_group(str(other), mode="r")
