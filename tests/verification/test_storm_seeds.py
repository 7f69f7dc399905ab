"""Seeds on Dask: the same seed gives bitwise the same result on 1 and on 2 workers."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.soil.verley_sotberg import VerleySotberg
from onbottom.study.storm_seeds import STATUS_ERROR, run_storm_seeds, seed_list

pytestmark = pytest.mark.verification


@pytest.fixture(scope="module")
def case():
    pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm(stages=(SeaState(hs=4.68, tp=10.8, duration_s=300.0),), build_up_s=30.0)
    kw = {"depth": 13.0, "current": Current(velocity=0.91, z0=5.2e-6)}
    return pipe, soil, storm, kw


@pytest.mark.slow
@pytest.mark.dask
def test_same_seed_bitwise_same_on_one_and_two_workers(case):
    pipe, soil, storm, kw = case
    ref = run_storm_seeds(pipe, soil, storm, seeds=4, n_workers=0, **kw)
    one = run_storm_seeds(pipe, soil, storm, seeds=4, n_workers=1, **kw)
    two = run_storm_seeds(pipe, soil, storm, seeds=4, n_workers=2, **kw)
    assert ref.success and one.success and two.success
    for name in ("max_displacement", "final_displacement", "time_of_max", "n_steps"):
        a = ref.data[name].values
        assert np.array_equal(a, one.data[name].values)
        assert np.array_equal(a, two.data[name].values)
    # and the seeds differ from each other
    assert np.unique(ref.data["max_displacement"].values).size == 4


def test_statistics_and_failures_are_recorded(case):
    pipe, soil, storm, kw = case
    st = run_storm_seeds(pipe, soil, storm, seeds=[3, 1, 2], n_workers=0, fractile=0.5, **kw)
    y = st.data["max_displacement"].values
    assert list(st.data["seed"].values) == [3, 1, 2]
    assert st.statistics["mean"] == pytest.approx(np.mean(y))
    assert st.statistics["max"] == np.max(y) and st.statistics["fractile"] == np.median(y)
    assert st.criteria["10D"]
    summary = st.to_dict()  # the payload of `onbottom storm --seeds N --json`
    assert summary["seeds"] == 3 and summary["diameter_m"] == 0.3951 and summary["success"]
    assert summary["max_displacement_m"] == np.max(y) and summary["status"] == 1
    assert summary["final_displacement_m"] == pytest.approx(
        np.mean(np.abs(st.data["final_displacement"].values))
    )
    assert summary["message"].startswith(
        f"3 seeds: seed-averaged maximum displacement {np.mean(y) / 0.3951:.3g}D"
    )
    # a seed that raises is recorded, not dropped
    bad = run_storm_seeds(pipe, soil, storm, seeds=2, n_workers=0, depth=None)
    assert not bad.success and len(bad.failures) == 2
    assert all(f["status"] == STATUS_ERROR and "depth" in f["message"] for f in bad.failures)
    assert np.all(np.isnan(bad.data["max_displacement"].values))
    assert bad.to_dict()["final_displacement_m"] is None and bad.to_dict()["status"] == -9
    assert bad.to_dict()["message"].endswith("; 2 seed(s) failed")
    assert seed_list(5, 3) == [5, 6, 7]
