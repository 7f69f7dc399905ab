"""The two-DOF soil contract in the three solvers (issue 29 item 3).

The parabolic V–H test model (:class:`onbottom.soil.vh_parabolic.ParabolicVH`) runs in the
centrifuge section, the storm section and the pipeline; with V_p = ∞ and no vertical flow it
is Coulomb friction, and each solver then gives Coulomb's lateral history bit for bit (contract
rule 2.7); with a finite V_p and vertical flow the sliding resistance is μV(1 − V/V_p) and the
pipe moves vertically by ∂g/∂V per unit plastic slip (a closed form in the section).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.dynamics.programmes import from_arrays
from onbottom.dynamics.section import SolverSettings, simulate_section
from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro.force_model import MorisonLift
from onbottom.hydro.short_crested import regular_node_kinematics
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs.pipe import Pipe
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.vh_parabolic import ParabolicVH

pytestmark = pytest.mark.verification

MU, DELTA = 0.6, 1.0e-3
STIFF = Pipe(
    outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=1e12, axial_stiffness=1e12
)
FORCE = MorisonLift(cd=0.7, cm=3.29, cl=0.9, added_mass=2.29)


def _coulomb():
    return CoulombFriction(friction_coefficient=MU, mobilisation_displacement=DELTA)


def _vh_coulomb_limit():
    return ParabolicVH(
        friction_coefficient=MU,
        bearing_capacity=math.inf,
        flow_coefficient=0.0,
        mobilisation_displacement=DELTA,
    )


def _vh(vp, mu_flow=0.3, kp=0.0):
    return ParabolicVH(
        friction_coefficient=MU,
        bearing_capacity=vp,
        flow_coefficient=mu_flow,
        hardening_stiffness=kp,
        mobilisation_displacement=DELTA,
    )


# ---- centrifuge section (load-controlled H and V) -------------------------------------------


def _section(soil, v_amp=200.0):
    t = np.linspace(0.0, 40.0, 801)
    h = 700.0 * np.sin(2.0 * np.pi * t / 10.0)
    v = 1000.0 + v_amp * np.sin(2.0 * np.pi * t / 7.0)
    s = SolverSettings(dt_max=0.01, max_displacement_increment=0.01)
    return simulate_section(from_arrays(t, h, v), soil, mass=1000.0, settings=s)


def test_section_coulomb_limit_equals_coulomb():
    a = _section(_coulomb())
    b = _section(_vh_coulomb_limit())
    assert a.success and b.success
    assert np.ptp(a.data["y"].values) > 0.1  # it slides both ways, under a varying V
    for name in ("y", "y_dot", "F_friction"):
        np.testing.assert_array_equal(b.data[name].values, a.data[name].values)
    assert np.all(b.data["z"].values == 0.0)


def test_section_vh_capacity_and_vertical_flow_closed_form():
    # constant V = 1000, V_p = 4000, k_p = 0: sliding at C = μV(1 − V/V_p) = 450 N/m (not
    # μV = 600), and z = ∂g/∂V · Σ|plastic slip| with ∂g/∂V = −μ′(1 − 2V/V_p) = −0.15 (heave)
    r = _section(_vh(4000.0), v_amp=0.0)
    assert r.success
    f = r.data["F_friction"].values
    u = r.data["y"].values
    w = r.data["z"].values
    assert np.max(np.abs(f)) == pytest.approx(450.0, rel=1e-12)
    k = MU * 1000.0 / DELTA
    slip = np.abs(np.diff(u) - np.diff(f) / k)
    assert w[-1] == pytest.approx(-0.15 * np.sum(slip), rel=1e-9)
    assert w[-1] < -0.01  # the pipe rose by more than 1 cm
    c = _section(_coulomb(), v_amp=0.0)
    assert np.ptp(u) > np.ptp(c.data["y"].values)  # less capacity: it slides further


# ---- storm section (hydrodynamic loads, V = w_s − F_Z) ---------------------------------------


def _kinematics(amp=1.8, duration=60.0):
    kin = regular_node_kinematics(5, duration, 0.02, amp, 10.0, ramp=20.0)
    sk = StormKinematics(
        sample_interval=kin.dt,
        velocity=kin.velocity[:, 0].astype(float),
        acceleration=kin.acceleration[:, 0].astype(float),
        current=0.0,
        duration=kin.t_end,
        weights=np.ones((1, kin.velocity.shape[0])),
        stage_parameters=[{"significant_velocity": amp, "mean_period": 10.0}],
    )
    return kin, sk


def _storm(soil):
    _, sk = _kinematics()
    s = StormSolverSettings(dt_max=0.01, record_interval=0.1)
    return simulate_storm_section(STIFF, soil, sk, force_model=FORCE, settings=s)


def test_storm_section_coulomb_limit_equals_coulomb():
    a = _storm(_coulomb())
    b = _storm(_vh_coulomb_limit())
    assert a.success and b.success
    assert a.max_displacement > 0.05  # slides
    assert np.ptp(a.data["V"].values) > 100.0  # the lift varies the vertical load
    for name in ("y", "y_dot", "F_friction", "V"):
        np.testing.assert_array_equal(b.data[name].values, a.data[name].values)


def test_storm_section_runs_with_the_vh_model_and_couples_v_and_h():
    # V_p = 3 w_s, k_p > 0: while V = w_s − F_Z < V_p/2 the sliding pipe heaves and V_p
    # softens; when V is back above V_p/2 it penetrates again (both directions of flow)
    r = _storm(_vh(3.0 * STIFF.submerged_weight, kp=1.0e5))
    c = _storm(_coulomb())
    assert r.success
    z = r.data["z"].values
    assert z.min() < -1e-3 and np.diff(z).max() > 1e-5
    v = r.data["V"].values
    f = np.abs(r.data["F_friction"].values)
    assert np.all(f <= MU * np.maximum(v, 0.0) * (1.0 + 1e-12))  # never above Coulomb
    assert r.max_displacement > c.max_displacement  # lower capacity: it slides further


# ---- pipeline (corotational FE, soil per node) ----------------------------------------------


def _pipeline(soil):
    kin, _ = _kinematics(duration=40.0)
    m = PipelineModel(
        pipe=STIFF,
        length=40.0,
        element_length=10.0,
        soil=soil,
        end_conditions="free",
        force_model=FORCE,
    )
    s = PipelineSettings(alpha=0.0, dt_max=0.01, record_interval=0.5)
    return simulate_pipeline(m, kin, settings=s)


def test_pipeline_runs_with_the_vh_model():
    a = _pipeline(_coulomb())
    b = _pipeline(_vh_coulomb_limit())
    c = _pipeline(_vh(3.0 * STIFF.submerged_weight, kp=1.0e5))
    assert a.success and b.success and c.success
    assert a.max_displacement > 0.05
    # Coulomb limit: the same lateral history (records are float32)
    np.testing.assert_array_equal(b.data["y"].values, a.data["y"].values)
    # coupled: every node heaves alike (very stiff pipe, uniform flow) and slides further
    z = c.data["z"].values
    assert z.min() < -1e-3
    assert np.ptp(z, axis=1).max() <= 1e-4 * np.abs(z).max()
    assert c.max_displacement > a.max_displacement
