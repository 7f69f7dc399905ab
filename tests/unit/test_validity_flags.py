"""Runs that leave the soil model's range are flagged, never silent (issue 30 item 5).

A storm with a sustained strong current on a Verley & Sotberg sand whose penetration growth is
made fast (B = 10, Youssef & Cassidy's factor on Eqs 13–14) buries the pipe beyond D/2 within a
minute: the storm section and the pipeline report status −3 (the section solver's "outside
the model's validity"), the time, and (pipeline) the node and its position. The Verley &
Sotberg cap of Eq 8 about the as-laid z_i stops the ratchet over repeated breakouts.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from onbottom.dynamics.pipeline import (
    PipelineModel,
    PipelineSettings,
    SoilSection,
    simulate_pipeline,
)
from onbottom.dynamics.section import STATUS_OUTSIDE_VALIDITY
from onbottom.dynamics.storm_section import (
    StormSolverSettings,
    penetration_limit,
    simulate_storm_section,
)
from onbottom.hydro.short_crested import long_crested_node_kinematics
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current
from onbottom.soil._path import drive_path, drive_path_py
from onbottom.soil.base import OUT_SIZE, OUT_Z
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.verley_sotberg import VerleySotberg, max_cyclic_penetration

D = 0.5
SAND = Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6)
PIPE = Pipe(outer_diameter=D, submerged_weight=1000.0, bending_stiffness=1e8, axial_stiffness=1e10)
CURRENT = Current(velocity=1.2, reference_height=0.25, z0=1.0e-5)


def _flow(duration=60.0):
    return StormKinematics.regular(
        2.5, 10.0, 15.0, duration=duration, diameter=D, build_up_s=10.0, current=CURRENT
    )


def _fast_sand():
    return VerleySotberg.silica(PIPE, SAND, B=10.0)


def test_storm_section_flags_burial_with_time_and_place():
    kin = _flow()
    res = simulate_storm_section(
        PIPE, _fast_sand(), kin, settings=StormSolverSettings(dt_max=0.1, record_interval=0.5)
    )
    assert res.status == STATUS_OUTSIDE_VALIDITY and not res.success
    t_out = res.summary["out_of_range_time"]
    assert 0.0 < t_out < kin.duration
    assert res.summary["max_penetration"] > 0.5 * D
    assert res.summary["penetration_limit"] == pytest.approx(0.5 * D)
    assert f"t = {t_out:.1f} s" in res.message and "D/2" in res.message
    # the run went on to the end of the flow (flagged, not stopped)
    assert res.summary["final_time"] == pytest.approx(kin.duration)
    # the records agree: z first exceeds D/2 at the flagged time
    z = res.data["z"].values
    t = res.data["time"].values
    assert t[np.argmax(z > 0.5 * D)] >= t_out - 1e-9
    assert res.data.attrs["out_of_range"] == 1
    assert res.data.attrs["status"] == STATUS_OUTSIDE_VALIDITY
    assert res.data.attrs["out_of_range_time"] == pytest.approx(t_out)


def test_storm_section_in_range_is_not_flagged_and_coulomb_has_no_limit():
    kin = _flow(30.0)
    silica = VerleySotberg.silica(PIPE, SAND)
    res = simulate_storm_section(
        PIPE, silica, kin, settings=StormSolverSettings(record_interval=None)
    )
    assert res.success and res.summary["out_of_range_time"] == -1.0
    assert res.summary["max_penetration"] < 0.5 * D
    assert penetration_limit(CoulombFriction(friction_coefficient=0.6)) == np.inf


def test_pipeline_flags_burial_with_time_node_and_x():
    sections = (
        SoilSection(start=0.0, end=20.0, model=CoulombFriction(friction_coefficient=0.6)),
        SoilSection(start=20.0, end=40.0, model=_fast_sand()),
    )
    m = PipelineModel(
        pipe=PIPE,
        length=40.0,
        element_length=5.0,
        soil=sections,
        current=_flow().current,
        end_conditions="free",
    )
    kin = long_crested_node_kinematics(_flow(40.0), m.x.size)
    r = simulate_pipeline(m, kin, settings=PipelineSettings(dt_max=0.1, record_interval=2.0))
    assert r.status == STATUS_OUTSIDE_VALIDITY and not r.success
    node = int(r.summary["out_of_range_node"])
    x_out = r.summary["out_of_range_x"]
    assert x_out == pytest.approx(m.x[node]) and x_out >= 20.0  # on the sand, not the rock
    assert 0.0 < r.summary["out_of_range_time"] < 40.0
    assert f"node {node}" in r.message and "x = " in r.message
    assert r.data.attrs["out_of_range"] == 1
    assert json.loads(r.data.attrs["summary"])["out_of_range_node"] == node
    assert float(r.envelopes["max_z"].max()) > 0.5 * D
    assert float(r.envelopes["max_z"].sel(node=m.x < 20.0).max()) == 0.0  # Coulomb: z = 0


# ---- Verley & Sotberg: Eq 8's cap about the as-laid z_i (no ratchet over troughs) ---------------
def _drive(model, u, v):
    h = np.zeros((u.size, OUT_SIZE))
    drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h


def _ratchet_path(model, n_troughs=8):
    """Oscillate in region 2 about a trough, slide beyond y3, reverse; repeat."""
    y2, y3 = model.y2, model.y3
    pieces, origin = [], 0.0
    for _ in range(n_troughs):
        s = np.linspace(0.0, 40.0, 4001)[1:]
        pieces.append(origin + 0.9 * y2 * np.sin(2 * np.pi * s))  # cyclic, region 2
        slide = np.linspace(origin, origin + 1.2 * y3, 400)[1:]
        pieces.append(slide)  # breakout beyond y3
        back = np.linspace(slide[-1], slide[-1] - 0.01 * D, 20)[1:]
        pieces.append(back)  # reversal: a new trough starts here
        origin = back[-1]
    return np.concatenate(pieces)


def test_sustained_sliding_does_not_ratchet_penetration_past_the_eq8_cap():
    v = PIPE.submerged_weight
    as_laid = VerleySotberg.silica(PIPE, SAND)
    trough = dataclasses.replace(as_laid, max_penetration_base="trough")
    u = _ratchet_path(as_laid)
    vv = np.full(u.size, v)
    z_new = _drive(as_laid, u, vv)[:, OUT_Z]
    z_old = _drive(trough, u, vv)[:, OUT_Z]
    # Eq 8 with the as-laid z_i (Eq 7) and the largest amplitude of region 2 bounds z
    cap = max_cyclic_penetration(as_laid.initial_penetration, SAND.submerged_unit_weight, D, v,
                                 as_laid.y2)  # fmt: skip
    assert z_new.max() <= cap * (1.0 + 1e-9)
    assert z_new.max() == pytest.approx(cap, rel=0.02)  # the first trough reaches it
    # the earlier rule restarted the cap from z3 in every trough and climbed past it
    assert z_old.max() > 1.3 * cap
    # both rules agree in the first trough
    first = u.size // 8 // 2
    np.testing.assert_array_equal(z_new[:first], z_old[:first])


def test_max_penetration_base_kernel_equals_python_twin():
    m = VerleySotberg.silica(PIPE, SAND, max_penetration_base="trough")
    for model in (m, dataclasses.replace(m, max_penetration_base="as_laid")):
        u = _ratchet_path(model, 3)
        v = np.full(u.size, PIPE.submerged_weight)
        h1 = _drive(model, u, v)
        h2 = np.zeros_like(h1)
        drive_path_py(model.python_kernel, model.packed_parameters(), model.initial_state(), u,
                      v, h2)  # fmt: skip
        np.testing.assert_allclose(h1, h2, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match="max_penetration_base"):
        VerleySotberg.silica(PIPE, SAND, max_penetration_base="deepest")


def test_seeds_count_flagged_runs_and_say_so():
    from onbottom.dynamics.storm_section import StormSolverSettings as Settings
    from onbottom.inputs.storm import SeaState, Storm
    from onbottom.study.storm_seeds import run_storm_seeds

    storm = Storm.standard(SeaState(hs=2.5, tp=10.0), build_up_hours=0.003, peak_hours=0.02)
    # a soil that buries fast under this current: every region-2 increment counting in Eq 6
    # (the default counts none under a load that does not reverse)
    study = run_storm_seeds(
        PIPE,
        dataclasses.replace(_fast_sand(), work_counting="any_region2"),
        storm,
        seeds=2,
        n_workers=0,
        depth=15.0,
        current=CURRENT,
        settings=Settings(record_interval=None),
    )
    flags = study.data["out_of_range"].values
    assert flags.tolist() == [1, 1]
    assert (study.data["status"].values == STATUS_OUTSIDE_VALIDITY).all()
    assert (study.data["out_of_range_time"].values > 0.0).all()
    # the flagged seeds count in the statistics (their numbers are kept) ...
    assert study.statistics["n_out_of_range"] == 2 and study.statistics["n_failed"] == 0
    assert study.statistics["mean"] == pytest.approx(
        float(np.mean(study.data["max_displacement"].values))
    )
    # ... and the study is not a clean success (exit code 3 from the CLI)
    assert not study.success and len(study.failures) == 2
