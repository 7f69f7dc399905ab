"""The pipeline storm API on built objects: the run's cost model, the seed files, the seed
count rule, the summary over seeds, and the built run travelling to a worker (pickle)."""

from __future__ import annotations

import math
import pickle
from pathlib import Path

import numpy as np
import pytest

from onbottom.cases.pipeline import load_pipeline_run
from onbottom.dynamics.pipeline.storm_run import PipelineStormRun, run_cost
from onbottom.errors import InputError
from onbottom.study.pipeline_seeds import (
    PipelineSeeds,
    estimate_pipeline_seeds,
    pipeline_seed_count,
    seed_output,
)
from storm_cases import PIPELINE, REGULAR, write_case

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "pipeline_case.toml"


class _Storm:
    duration_s = 7200.0  # a 2 h spectral storm


def test_run_cost_by_hand():
    """51 nodes, 2 h storm, 1 h simulated at 0.1 s: 36 000 steps, 1 µs per node-step,
    0.5 MB per node-hour of storm."""
    c = run_cost(51, _Storm(), 3600.0, 0.1)
    assert (c.nodes, c.storm_s, c.run_s) == (51, 7200.0, 3600.0)
    assert c.steps == pytest.approx(36000.0)
    assert c.cpu_s == pytest.approx(51 * 36000.0 * 1e-6)
    assert c.memory_bytes == pytest.approx(0.5e6 * 51 * 2.0)
    assert run_cost(51, _Storm(), None, 0.1).run_s == 7200.0  # None: the whole storm
    assert run_cost(51, _Storm(), 9000.0, 0.1).run_s == 7200.0  # never past its end


def test_seed_files():
    assert seed_output("out/p.nc", 7, 1) == Path("out/p.nc")
    assert seed_output("out/p.nc", 7, 3) == Path("out/p.seed7.nc")


def test_built_run_of_the_example_and_its_estimate():
    run = load_pipeline_run(EXAMPLE)
    assert isinstance(run, PipelineStormRun)
    assert run.attrs == {"case_file": str(EXAMPLE)}
    assert run.identity == {"case": EXAMPLE.read_text(encoding="utf-8")}
    assert run.settings.dt_max == run.setup.settings.dt_max  # [storm] time_step, read once
    assert pipeline_seed_count(run, None) == run.setup.seeds
    est = estimate_pipeline_seeds(run, 4, 2)
    cost = run.cost()
    assert (est.runs, est.workers) == (4, 2) and est.wall_s == pytest.approx(2 * cost.cpu_s)
    # the Dask seed job sends the built run to its workers
    back = pickle.loads(pickle.dumps(run))
    assert back.cost() == cost and np.array_equal(back.model.x, run.model.x)
    assert back.identity == run.identity


def test_a_deterministic_flow_runs_one_seed(tmp_path):
    run = load_pipeline_run(write_case(tmp_path, REGULAR, PIPELINE))
    assert pipeline_seed_count(run, None) == 1
    with pytest.raises(InputError, match="deterministic, run one seed"):
        pipeline_seed_count(run, 2)


def _row(seed, ymax, strain, ok=True, status=1):
    if not ok:
        return {"seed": seed, "status": -9, "success": False, "message": "ValueError: x"}
    return {
        "seed": seed,
        "max_displacement_m": ymax,
        "max_displacement_over_D": ymax / 0.4,
        "max_strain": strain,
        "worst_node_x_m": 20.0 + seed,
        "criteria": {"0.5D": ymax <= 0.2, "10D": True, "strain": strain <= 1e-3},
        "status": status,
        "success": True,
        "message": f"seed {seed} ended",
    }


def test_summary_over_seeds_by_hand():
    rows = [_row(1, 0.1, 4e-4), _row(2, 0.3, 6e-4), _row(3, 0.0, 0.0, ok=False)]
    outs = [Path(f"p.seed{s}.nc") for s in (1, 2, 3)]
    s = PipelineSeeds(rows=rows, outputs=outs, diameter=0.4, n_nodes=51, strain_limit=1e-3)
    d = s.to_dict()
    assert d["max_displacement_m"] == 0.3 and d["worst_node_x_m"] == 22.0  # seed 2
    assert d["mean_max_displacement_m"] == pytest.approx(0.2)
    assert d["max_strain"] == 6e-4 and d["strain_check"] is True
    assert d["criteria"] == {"0.5D": False, "10D": True}
    assert d["success"] is False and d["status"] == -9  # the worst status of any seed
    assert d["failures"] == [{"seed": 3, "status": -9, "message": "ValueError: x"}]
    assert d["netcdf"] == [str(o) for o in outs] and d["seeds"] == 3
    assert d["message"] == (
        "3 seeds: seed-averaged maximum displacement 0.5D (max 0.75D); 1 seed(s) failed;"
        " worst node x = 22.0 m; max strain 0.06 % (limit 0.1 %: PASS)"
    )
    # one seed: its own message and file; no strain limit: no verdict
    one = PipelineSeeds(
        rows=rows[:1], outputs=outs[:1], diameter=0.4, n_nodes=51, strain_limit=None
    ).to_dict(plot="f.png")
    assert one["message"] == "seed 1 ended; worst node x = 21.0 m; max strain 0.04 %"
    assert one["netcdf"] == "p.seed1.nc" and one["plot"] == "f.png" and one["success"]
    assert one["strain_check"] is None and one["status"] == 1
    # every seed failed: no numbers, NaN mean
    bad = PipelineSeeds(
        rows=rows[2:], outputs=outs[2:], diameter=0.4, n_nodes=51, strain_limit=1e-3
    ).to_dict()
    assert bad["max_displacement_m"] is None and math.isnan(bad["mean_max_displacement_m"])
    assert bad["criteria"] == {"0.5D": False, "10D": False} and bad["strain_check"] is None
