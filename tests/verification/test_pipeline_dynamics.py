"""Verification of the pipeline FE time integration: rigid slide, energy balance, convergence
in Δt and element size, a very stiff pipe against the storm-section solver, mirror symmetry."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro.short_crested import NodeKinematics, regular_node_kinematics
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.verley_sotberg import VerleySotberg

pytestmark = pytest.mark.verification

PIPE = Pipe(outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9)
SAND = Sand(submerged_unit_weight=1.0e4, friction_coefficient=0.6)


def _model(length=200.0, le=4.0, soil=None, ends="fixed", pipe=PIPE, **kw):
    soil = soil if soil is not None else CoulombFriction(friction_coefficient=0.6)
    return PipelineModel(
        pipe=pipe, length=length, element_length=le, soil=soil, end_conditions=ends, **kw
    )


def _wave(model, duration=80.0, amplitude=1.6, wavelength=400.0, dt=0.05):
    return regular_node_kinematics(
        model.x.size,
        duration,
        dt,
        amplitude,
        10.0,
        ramp=30.0,
        x=model.x,
        wavelength=wavelength,
    )


def test_rigid_slide_of_ten_diameters_makes_no_strain():
    """Free ends, loads in phase along the line, weak friction: the line slides > 10D as a
    rigid body; bending strain stays at round-off and all nodes move together."""
    m = _model(length=100.0, ends="free", soil=CoulombFriction(friction_coefficient=0.1))
    kin = regular_node_kinematics(m.x.size, 40.0, 0.05, 0.0, 10.0)
    kin = NodeKinematics(
        t0=0.0, dt=kin.dt, velocity=kin.velocity + np.float32(1.5), acceleration=kin.acceleration
    )
    r = simulate_pipeline(m, kin, settings=PipelineSettings(dt_max=0.1, record_interval=5.0))
    assert r.success
    assert r.max_displacement > 10.0 * PIPE.outer_diameter
    y = r.data["y"].values
    assert np.ptp(y[-1]) < 1e-9 * r.max_displacement
    assert r.max_strain < 1e-12


def test_energy_balance_over_a_storm_within_one_percent():
    """α = 0: kinetic + strain energy = work of the hydrodynamic loads + work of the soil."""
    m = _model(soil=VerleySotberg.silica(PIPE, SAND))
    r = simulate_pipeline(m, _wave(m), settings=PipelineSettings(alpha=0.0, dt_max=0.05))
    s = r.summary
    assert r.success and s["work_hydro"] > 1e3
    assert abs(s["energy_residual"]) <= 0.01 * s["work_hydro"]
    # the soil dissipates: negative work
    assert s["work_soil"] < 0.0


def _final_y(model, dt, kin=None, alpha=0.0):
    kin = kin if kin is not None else _wave(model)
    r = simulate_pipeline(
        model, kin, settings=PipelineSettings(alpha=alpha, dt_max=dt, record_interval=None)
    )
    assert r.success
    return r.envelopes["max_abs_y"].values


def test_convergence_in_time_step():
    m = _model()
    ys = [_final_y(m, dt) for dt in (0.2, 0.1, 0.05, 0.025)]
    errs = [np.max(np.abs(a - ys[-1])) for a in ys[:-1]]
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 0.01 * np.max(ys[-1])


def test_convergence_in_element_size():
    """Envelope of |y| at the nodes common to all meshes converges as elements shrink."""
    vals = []
    for le in (20.0, 10.0, 5.0, 2.5):
        m = _model(le=le)
        env = _final_y(m, 0.05)
        vals.append(np.interp(np.linspace(0, 200.0, 11), m.x, env))
    errs = [np.max(np.abs(v - vals[-1])) for v in vals[:-1]]
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 0.02 * np.max(vals[-1])


@pytest.mark.parametrize("soil_name", ["coulomb", "verley_sotberg"])
def test_very_stiff_pipe_under_uniform_load_reproduces_the_section_solver(soil_name):
    """Long-crested waves normal to the pipe load every node alike: a free stiff pipe moves as
    one section; its displacement history matches simulate_storm_section within 1 %."""
    soil = (
        CoulombFriction(friction_coefficient=0.35)
        if soil_name == "coulomb"
        else VerleySotberg.silica(PIPE, SAND)
    )
    stiff = Pipe(
        outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=1e12, axial_stiffness=1e12
    )
    m = _model(length=40.0, le=10.0, soil=soil, ends="free", pipe=stiff)
    kin = regular_node_kinematics(m.x.size, 120.0, 0.02, 1.8, 10.0, ramp=30.0)
    r = simulate_pipeline(
        m, kin, settings=PipelineSettings(alpha=0.0, dt_max=0.02, record_interval=1.0)
    )
    sk = StormKinematics(
        sample_interval=kin.dt,
        velocity=kin.velocity[:, 0].astype(float),
        acceleration=kin.acceleration[:, 0].astype(float),
        current=0.0,
        duration=kin.t_end,
        weights=np.ones((1, kin.velocity.shape[0])),
        stage_parameters=[{"significant_velocity": 1.8, "mean_period": 10.0}],
    )
    sec = simulate_storm_section(
        stiff, soil, sk, settings=StormSolverSettings(dt_max=0.02, record_interval=1.0)
    )
    assert r.success and sec.success
    assert r.max_displacement > 0.05 * stiff.outer_diameter
    y_sec = np.interp(r.data["time"].values, sec.data["time"].values, sec.data["y"].values)
    y_fe = r.data["y"].values
    assert np.ptp(y_fe, axis=1).max() < 1e-6 * r.max_displacement
    assert np.max(np.abs(y_fe[:, 2] - y_sec)) <= 0.01 * np.max(np.abs(y_sec))
    assert r.max_displacement == pytest.approx(sec.max_displacement, rel=0.01)


def test_mirrored_load_gives_mirrored_response():
    """Reversing the kinematics along the line mirrors the response; reversing their sign
    reverses the displacements (symmetric soil, symmetric end conditions)."""
    m = _model(soil=VerleySotberg.silica(PIPE, SAND))
    kin = _wave(m, duration=60.0, wavelength=300.0)
    flipped = NodeKinematics(
        t0=0.0,
        dt=kin.dt,
        velocity=np.ascontiguousarray(kin.velocity[:, ::-1]),
        acceleration=np.ascontiguousarray(kin.acceleration[:, ::-1]),
    )
    negated = NodeKinematics(
        t0=0.0, dt=kin.dt, velocity=-kin.velocity, acceleration=-kin.acceleration
    )
    st = PipelineSettings(dt_max=0.05, record_interval=10.0)
    y0 = simulate_pipeline(m, kin, settings=st).data["y"].values
    y1 = simulate_pipeline(m, flipped, settings=st).data["y"].values
    y2 = simulate_pipeline(m, negated, settings=st).data["y"].values
    scale = np.max(np.abs(y0))
    assert scale > 0.01
    np.testing.assert_allclose(y1[:, ::-1], y0, atol=1e-7 * scale)
    np.testing.assert_allclose(y2, -y0, atol=1e-7 * scale)


def test_pipe_passing_the_f109_absolute_check_moves_less_than_half_a_diameter():
    """DNV-RP-F109 §3.6 absolute stability (utilisation < 1) → the FE line moves < 0.5D in
    the same sea state (10 min at the peak, long-crested waves normal to the line)."""
    from onbottom.checks.absolute import absolute_lateral_stability, seabed_roughness
    from onbottom.hydro.short_crested import pipeline_kinematics
    from onbottom.hydro.storm_kinematics import current_normal_to_pipe
    from onbottom.inputs.storm import Current, SeaState, Storm

    pipe = Pipe(
        outer_diameter=0.4, submerged_weight=4000.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    check = absolute_lateral_stability(
        pipe, SAND, hs=3.0, tp=10.0, depth=15.0, current_velocity=0.2
    )
    assert check.passes and check.utilisation > 0.7
    current = Current(velocity=0.2, reference_height=1.0, z0=seabed_roughness(SAND))
    m = _model(
        length=100.0,
        le=5.0,
        soil=VerleySotberg.silica(pipe, SAND),
        pipe=pipe,
        current=current_normal_to_pipe(current, 0.4),
    )
    storm = Storm.standard(
        SeaState(hs=3.0, tp=10.0), build_up_hours=1.0 / 60.0, peak_hours=10.0 / 60.0, seed=4
    )
    kin = pipeline_kinematics(storm, 15.0, m.x)
    r = simulate_pipeline(m, kin, settings=PipelineSettings(record_interval=None))
    assert r.success and r.criteria["0.5D"]
    assert r.max_displacement < 0.5 * pipe.outer_diameter
