"""Windowed storm kinematics (a temporary file read in time windows as the pipeline run
advances) give the values and the run of the kinematics held whole, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.dynamics.pipeline import solver as pipeline_solver
from onbottom.hydro.short_crested import (
    NodeKinematics,
    WindowedNodeKinematics,
    pipeline_kinematics,
)
from onbottom.inputs.pipe import Layer
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import SeaState, Storm
from onbottom.soil.verley_sotberg import VerleySotberg

pytestmark = pytest.mark.verification


def _case(n_el: int = 20):
    pipe = PipeBuildUp(
        steel_outer_diameter=0.2191,
        wall_thickness=0.0127,
        layers=(
            Layer(name="fbe", thickness=0.0055, density=1335.0),
            Layer(name="concrete", thickness=0.03, density=3043.5),
        ),
        contents=Contents.uniform(1025.0),
    ).pipe("operation")
    model = PipelineModel(
        pipe=pipe,
        length=200.0,
        element_length=200.0 / n_el,
        soil=VerleySotberg.silica(pipe, Sand(submerged_unit_weight=1.0e4)),
        end_conditions="fixed",
        current=0.3,
    )
    sea = SeaState(hs=4.5, tp=10.0, direction_deg=80.0, spreading_s=8.0)
    storm = Storm.standard(sea, build_up_hours=0.0, peak_hours=0.03, seed=3)
    return model, storm


def test_windows_hold_the_whole_arrays_values_and_the_file_goes():
    model, storm = _case()
    whole = pipeline_kinematics(storm, 13.0, model.x)
    win = pipeline_kinematics(storm, 13.0, model.x, memory_limit=0)
    assert isinstance(whole, NodeKinematics) and isinstance(win, WindowedNodeKinematics)
    assert win.shape == whole.shape and win.dt == whole.dt and win.t_end == whole.t_end
    np.testing.assert_array_equal(win.weights, whole.weights)
    n_t = whole.shape[0]
    for k0, k1 in ((0, n_t), (0, 7), (n_t // 3, n_t // 3 + 50), (n_t - 2, n_t)):
        u, a = win.window(k0, k1)
        assert u.dtype == np.float32 and u.flags.c_contiguous
        np.testing.assert_array_equal(u, whole.velocity[k0:k1])
        np.testing.assert_array_equal(a, whole.acceleration[k0:k1])
    # a limit above the size keeps them whole
    assert isinstance(pipeline_kinematics(storm, 13.0, model.x, memory_limit=10**9), NodeKinematics)
    path = win.path
    assert path.exists()
    win.close()
    assert not path.exists()


def test_a_run_on_windowed_kinematics_equals_the_run_on_whole_ones(monkeypatch):
    model, storm = _case()
    whole = pipeline_kinematics(storm, 13.0, model.x)
    st = PipelineSettings(dt_max=0.1, record_interval=2.0, chunk_duration=15.0)
    a = simulate_pipeline(model, whole, settings=st)
    # windows of a few samples: many reloads, windows that end inside a call's span
    monkeypatch.setattr(pipeline_solver._KinematicsWindow, "WINDOW_BYTES", 1)
    with pipeline_kinematics(storm, 13.0, model.x, memory_limit=0) as win:
        b = simulate_pipeline(model, win, settings=st)
    assert a.status == b.status == 1
    for k in a.summary:
        assert np.array_equal(a.summary[k], b.summary[k], equal_nan=True), k
    for v in a.envelopes.data_vars:
        np.testing.assert_array_equal(a.envelopes[v].values, b.envelopes[v].values)
    for v in a.data.data_vars:
        np.testing.assert_array_equal(a.data[v].values, b.data[v].values)
