"""Verification of the pipeline's user-load path q(x, t): a uniform, slowly ramped load on a
pinned and on a fixed beam against the closed-form static deflection (lateral: 5qL⁴/384EI and
qL⁴/384EI; axial: q_xL²/8EA), the kernel's load against the NumPy evaluation, input checks."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics.pipeline import (
    PipelineModel,
    PipelineSettings,
    SoilSection,
    simulate_pipeline,
)
from onbottom.dynamics.pipeline import _pipeline_kernel as K
from onbottom.dynamics.pipeline.user_load import (
    TableLoad,
    TravellingSineLoad,
    kernel_settings,
    still_water,
)
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.soil.coulomb import CoulombFriction

pytestmark = pytest.mark.verification

PIPE = Pipe(outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9)
L = 50.0
EI = 5e7
EA = 5e9


def _ramped_uniform(n_nodes, q_y, q_x, ramp, dt=0.5, hold=20.0):
    """Half-cosine ramp 0 → q sampled every dt, then held."""
    t = np.arange(0.0, ramp + hold + dt / 2, dt)
    r = 0.5 * (1.0 - np.cos(np.pi * np.clip(t / ramp, 0.0, 1.0)))
    one = np.ones(n_nodes)
    return TableLoad(dt=dt, lateral=np.outer(r * q_y, one), axial=np.outer(r * q_x, one))


def _static_run(ends, q_y, q_x):
    # μ = 1e-7: the friction μW_s = 6e-5 N/m is 6e-5 of the lateral load (1 N/m); the first
    # lateral period (pinned, 50 m) is ≈ 4 s against a 100-s ramp: the response is static
    # within 1e-3. The lateral load is small (y ≈ 1.6 mm pinned) so that the membrane tension
    # of the axially held ends stiffens by < 1e-4 (6e-3 at 10 N/m)
    soil = (
        SoilSection(
            start=0.0,
            end=L,
            model=CoulombFriction(friction_coefficient=1e-7),
            axial_friction_coefficient=1e-7,
        ),
    )
    n = round(L / 2.5) + 1  # 20 elements: a node at midspan
    m = PipelineModel(
        pipe=PIPE, length=L, element_length=2.5, soil=soil, end_conditions=ends,
        relative_velocity=False, user_load=_ramped_uniform(n, q_y, q_x, ramp=100.0),
    )  # fmt: skip
    res = simulate_pipeline(
        m, still_water(n, 120.0), settings=PipelineSettings(alpha=-0.1, record_interval=1.0)
    )
    assert res.success, res.message
    # the user load's work is in the external work: the energy residual is small
    assert abs(res.summary["energy_residual"]) < 1e-2 * abs(res.summary["work_hydro"])
    return m.x, res.data


@pytest.mark.parametrize("ends", ["pinned", "fixed"])
def test_slowly_ramped_uniform_lateral_load_gives_the_static_beam_deflection(ends):
    q = 1.0
    x, data = _static_run(ends, q, 0.0)
    y = data["y"].values
    mid = x.size // 2
    xi = x / L
    if ends == "pinned":  # 5qL⁴/384EI at midspan
        shape = q * L**4 / (24.0 * EI) * (xi - 2.0 * xi**3 + xi**4)
    else:  # qL⁴/384EI
        shape = q * L**4 / (24.0 * EI) * xi**2 * (1.0 - xi) ** 2
    y_mid = (5.0 if ends == "pinned" else 1.0) * q * L**4 / (384.0 * EI)
    assert shape[mid] == pytest.approx(y_mid)
    # the mean over the last 10 s of the hold: the static deflection
    assert np.mean(y[-10:, mid]) == pytest.approx(y_mid, rel=1e-2)
    # the whole deflected shape, not only the midpoint
    np.testing.assert_allclose(np.mean(y[-10:], axis=0), shape, rtol=0.0, atol=1e-2 * y_mid)


def test_slowly_ramped_uniform_axial_load_gives_the_static_bar_displacement():
    q = 1000.0
    x, data = _static_run("fixed", 0.0, q)
    u = np.mean(data["u_axial"].values[-10:], axis=0)
    exact = q * x * (L - x) / (2.0 * EA)  # q_xL²/8EA at midspan
    np.testing.assert_allclose(u, exact, rtol=0.0, atol=1e-2 * exact.max())
    np.testing.assert_allclose(data["y"].values, 0.0, atol=1e-12)


def test_kernel_user_load_equals_the_numpy_evaluation():
    x = np.linspace(0.0, 120.0, 13)
    nodes = np.zeros((x.size, K.N_NODE_COLS))
    nodes[:, K.ND_X0] = x
    nodes[:, K.ND_TRIB] = 10.0
    nodes[[0, -1], K.ND_TRIB] = 5.0
    rng = np.random.default_rng(4)
    sine = TravellingSineLoad(
        amplitude=250.0, wavelength=70.0, period=9.0, ramp=15.0, axial_amplitude=-40.0, start=2.0
    )
    table = TableLoad(
        dt=0.7, t0=1.0, lateral=rng.normal(size=(6, x.size)), axial=rng.normal(size=(6, x.size))
    )
    for load in (sine, table):
        st = np.zeros(K.N_SETTINGS)
        st[K.ST_UL_KIND :] = kernel_settings(load)
        tab = load.table(x.size)
        for t in (0.0, 1.0, 2.0, 3.3, 9.99, 16.9, 17.0, 40.0):
            p = np.zeros(3 * x.size)
            fext = np.zeros(3 * x.size)
            K.add_user_load(st, tab, nodes, t, p, fext)
            qy, qx = load.at(x, t)
            np.testing.assert_allclose(p[1::3], qy * nodes[:, K.ND_TRIB], rtol=1e-12, atol=1e-12)
            np.testing.assert_allclose(p[0::3], qx * nodes[:, K.ND_TRIB], rtol=1e-12, atol=1e-12)
            np.testing.assert_array_equal(p[2::3], 0.0)
            np.testing.assert_array_equal(p, fext)
    # the ramp: nothing before the start, half at mid-ramp, full after
    assert sine.ramp_factor(2.0) == 0.0
    assert sine.ramp_factor(9.5) == pytest.approx(0.5)
    assert sine.ramp_factor(17.0) == 1.0
    # none: nothing added
    p = np.zeros(3 * x.size)
    K.add_user_load(np.zeros(K.N_SETTINGS), np.zeros((1, 2, 1)), nodes, 3.0, p, p.copy())
    assert not p.any()


def test_user_load_inputs_are_validated():
    with pytest.raises(InputError, match="TravellingSineLoad.wavelength"):
        TravellingSineLoad(amplitude=1.0, wavelength=0.0, period=5.0)
    with pytest.raises(InputError, match="TravellingSineLoad.period"):
        TravellingSineLoad(amplitude=1.0, wavelength=10.0, period=-1.0)
    with pytest.raises(InputError, match="TravellingSineLoad.ramp"):
        TravellingSineLoad(amplitude=1.0, wavelength=10.0, period=5.0, ramp=-1.0)
    with pytest.raises(InputError, match="TravellingSineLoad.amplitude"):
        TravellingSineLoad(amplitude=math.nan, wavelength=10.0, period=5.0)
    with pytest.raises(InputError, match="TableLoad.dt"):
        TableLoad(dt=0.0, lateral=np.zeros((2, 3)))
    with pytest.raises(InputError, match="TableLoad.lateral"):
        TableLoad(dt=1.0, lateral=np.zeros(3))
    with pytest.raises(InputError, match="TableLoad.lateral"):
        TableLoad(dt=1.0, lateral=np.array([[0.0, np.inf]]))
    with pytest.raises(InputError, match="TableLoad.axial"):
        TableLoad(dt=1.0, lateral=np.zeros((2, 3)), axial=np.zeros((2, 4)))
    soil = CoulombFriction(friction_coefficient=0.6)
    with pytest.raises(InputError, match="TableLoad.lateral has 3 node columns"):
        PipelineModel(
            pipe=PIPE, length=L, element_length=5.0, soil=soil,
            user_load=TableLoad(dt=1.0, lateral=np.zeros((2, 3))),
        )  # fmt: skip
    with pytest.raises(InputError, match="PipelineModel.user_load"):
        PipelineModel(pipe=PIPE, length=L, element_length=5.0, soil=soil, user_load=3.0)


def test_a_user_load_changes_the_run_identity_and_none_keeps_it():
    from onbottom.dynamics.pipeline import pipeline_identity

    soil = CoulombFriction(friction_coefficient=0.6)
    base = PipelineModel(pipe=PIPE, length=L, element_length=5.0, soil=soil)
    kin = still_water(base.x.size, 10.0)
    s = PipelineSettings()
    sine = TravellingSineLoad(amplitude=100.0, wavelength=40.0, period=8.0)
    loaded = PipelineModel(pipe=PIPE, length=L, element_length=5.0, soil=soil, user_load=sine)
    assert "user_load" not in base.describe()
    assert pipeline_identity(base, kin, s).digest != pipeline_identity(loaded, kin, s).digest
