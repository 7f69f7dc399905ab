"""Force models in both solvers: a per-sea-state Morison model in the pipeline FE, and the
force-model state committed only on accepted steps (storm section and pipeline)."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dynamics import _storm_kernel as SK
from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.dynamics.pipeline import _pipeline_kernel as PK
from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.errors import InputError
from onbottom.hydro._morison_kernel import morison_twin
from onbottom.hydro.force_model import MorisonLift
from onbottom.hydro.short_crested import pipeline_kinematics, regular_node_kinematics
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.storm import SeaState, Storm
from onbottom.soil.coulomb import CoulombFriction

PIPE = Pipe(outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9)
STAGE_1 = (0.9, 3.0, 0.7)  # (C_D, C_M, C_L) of the first sea state


def _rule(k, m):
    """Stage 1 (K < 30 here) gets STAGE_1; the stronger stage 2 other coefficients."""
    return STAGE_1 if k < 30.0 else (1.4, 3.29, 1.2)


def test_pipeline_runs_a_per_sea_state_morison_model():
    """Two sea states without build-up: up to the stage change the per-sea-state run is the
    constant run with the first stage's coefficients, bit for bit; after it they part."""
    storm = Storm(
        stages=(
            SeaState(hs=2.0, tp=8.0, duration_s=40.0, direction_deg=90.0),
            SeaState(hs=5.0, tp=11.0, duration_s=40.0, direction_deg=90.0),
        ),
        build_up_s=0.0,
        transition_s=0.0,
        seed=4,
    )
    depth = 15.0
    m_const = PipelineModel(
        pipe=PIPE, length=24.0, element_length=4.0, soil=CoulombFriction(friction_coefficient=0.6),
        force_model=MorisonLift(cd=STAGE_1[0], cm=STAGE_1[1], cl=STAGE_1[2], added_mass=2.29),
        current=0.3,
    )  # fmt: skip
    m_sea = PipelineModel(
        pipe=PIPE, length=24.0, element_length=4.0, soil=CoulombFriction(friction_coefficient=0.6),
        force_model=MorisonLift.per_sea_state(_rule), current=0.3,
    )  # fmt: skip
    kin = pipeline_kinematics(storm, depth, m_sea.x)
    k = [p["significant_velocity"] * p["mean_period"] / 0.4 for p in kin.stage_parameters]
    assert k[0] < 30.0 < k[1]  # the rule gives each stage its coefficients
    st = PipelineSettings(record_interval=1.0)
    r_sea = simulate_pipeline(m_sea, kin, settings=st)
    r_const = simulate_pipeline(m_const, kin, settings=st)
    assert r_sea.success and r_sea.summary["final_time"] == pytest.approx(80.0)
    assert r_sea.run_id != r_const.run_id
    t = r_sea.data["time"].values
    before, after = t < 39.0, t > 45.0
    f_sea, f_const = r_sea.data["F_hydro"].values, r_const.data["F_hydro"].values
    assert np.array_equal(f_sea[before], f_const[before])
    assert np.max(np.abs(f_sea[after] - f_const[after])) > 0.1 * np.max(np.abs(f_const[after]))
    # a sea-state dependent model needs the stages: refused on a regular wave
    with pytest.raises(InputError, match="stage_parameters"):
        simulate_pipeline(m_sea, regular_node_kinematics(m_sea.x.size, 10.0, 0.1, 1.0, 8.0))


def _counting_force(model_id, params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """A stateful test model: Morison forces; slot 0 counts the evaluations on the committed
    path, slot 1 keeps the time and slot 2 the pipe velocity of the last committed one."""
    morison_twin(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)
    state_new[0] = state_old[0] + 1.0
    state_new[1] = t
    state_new[2] = ydot


def _python_kernels(monkeypatch, module, names):
    """Run ``names`` of a kernel module as plain Python with the counting force model; returns
    the dict where the wrapped ``integrate`` leaves its arguments."""
    captured: dict = {}
    for name in names:
        monkeypatch.setattr(module, name, getattr(module, name).py_func)
    monkeypatch.setattr(module, "force_step", _counting_force)
    integrate = module.integrate.py_func

    def spy(*args):
        captured["args"] = args
        return integrate(*args)

    monkeypatch.setattr(module, "integrate", spy)
    if hasattr(module, "_INTEGRATE"):  # the start's entry point: Python too, never compiled
        monkeypatch.setattr(module, "_INTEGRATE", integrate)  # against the Python globals above
    return captured


def _ramped_storm() -> StormKinematics:
    """A 30-s regular flow (U = 1.8 m/s, T = 8 s) ramped over its first period, 0.2 m/s of
    current: enough to slide a light pipe back and forth with rejected steps."""
    t = np.arange(0.0, 30.0 + 1e-9, 0.1)
    u = 1.8 * np.sin(2 * np.pi * t / 8.0) * np.minimum(t / 8.0, 1.0)
    return StormKinematics(
        sample_interval=0.1, velocity=u, acceleration=np.gradient(u, 0.1), current=0.2,
        duration=30.0, weights=np.ones((1, t.size)),
        stage_parameters=[{"significant_velocity": 1.8, "mean_period": 8.0}],
    )  # fmt: skip


def test_section_commits_the_force_state_on_accepted_steps_only(monkeypatch):
    captured = _python_kernels(monkeypatch, SK, ["forces", "solve_step", "initial"])
    kin = _ramped_storm()
    res = simulate_storm_section(
        Pipe(outer_diameter=0.4, submerged_weight=300.0),
        CoulombFriction(friction_coefficient=0.4),
        kin,
        settings=StormSolverSettings(
            dt_max=0.2, max_displacement_increment_over_d=0.005, record_interval=0.0
        ),
    )
    fstate = captured["args"][6]  # integrate(model_id, force_id, params, state, st, fp, fstate, ..)
    s = res.summary
    assert res.success and s["n_rejected"] > 0 and s["mean_newton_iterations"] > 1.0
    # one count per accepted step, although the model was evaluated far more often
    assert fstate[0] == s["n_steps"]
    assert fstate[1] == s["final_time"]
    assert fstate[2] == res.data["y_dot"].values[-1]


def test_pipeline_commits_the_force_state_on_accepted_steps_only(monkeypatch):
    captured = _python_kernels(monkeypatch, PK, ["evaluate", "node_loads", "parameter_row"])
    light = Pipe(
        outer_diameter=0.4, submerged_weight=250.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    m = PipelineModel(
        pipe=light, length=16.0, element_length=4.0, soil=CoulombFriction(friction_coefficient=0.4),
        end_conditions="free",
    )  # fmt: skip
    kin = regular_node_kinematics(m.x.size, 12.0, 0.05, 2.0, 6.0, ramp=4.0)
    r = simulate_pipeline(
        m, kin, settings=PipelineSettings(
            dt_max=0.2, max_displacement_increment_over_d=0.01, record_interval=None
        ),
    )  # fmt: skip
    fstate = captured["args"][12]  # integrate(soil_id, force_id, settings, ..., fstate, ...)
    s = r.summary
    assert r.success and s["n_rejected"] > 0
    np.testing.assert_array_equal(fstate[:, 0], s["n_steps"])
    np.testing.assert_array_equal(fstate[:, 1], s["final_time"])


# Recorded with the code before the force-model contract (ea855bb) by the same calls. The
# contract applies the F109 reductions to the kernel's output, which reassociates two products
# (dF_Y/dẏ and F_Z) — the only change at round-off (6e39e48); with it, section and pipeline
# results are bitwise those of 6e39e48 (commit messages). Relative tolerance 1e-8: round-off
# grows along a storm (1e-11 here).
_BEFORE = {
    "n_steps": 6000, "work_hydro": 134.19653163839553, "max_penetration": 0.09021221116028481,
    "min_contact_force": 672.416843457171, "ymax": 0.1646680755352786,
    "yfin": 0.14323883261500392, "p_ymax": 0.017320657591205303, "p_steps": 600.0,
    "p_work_hydro": 100.61158188088699, "p_strain": 0.00016762065832959716,
}  # fmt: skip


def test_example_cases_match_the_results_before_the_force_contract():
    import dataclasses
    from pathlib import Path

    from onbottom.cases.pipeline import load_pipeline_run
    from onbottom.cases.storm import load_storm_setup

    ex = Path(__file__).resolve().parents[2] / "examples"
    setup = load_storm_setup(ex / "storm_case.toml")
    # the numbers below were taken with the former reading of V&S Eq 6 (every region-2
    # increment counted): pin it, so that this stays a regression test of the force contract
    former = dataclasses.replace(setup.soil, work_counting="any_region2")
    setup = dataclasses.replace(setup, soil=former)
    peak = dataclasses.replace(setup.storm.stages[0], duration_s=540.0)
    storm = dataclasses.replace(setup.storm, build_up_s=60.0, stages=(peak,))
    kw = setup.kwargs()
    kw["settings"] = StormSolverSettings(dt_max=0.1, record_interval=None)
    r = simulate_storm_section(setup.pipe, setup.soil, storm, **kw)
    got = {k: r.summary[k] for k in ("n_steps", "work_hydro", "max_penetration")}
    got["min_contact_force"] = r.summary["min_contact_force"]
    got.update(ymax=r.max_displacement, yfin=r.final_displacement)
    run = load_pipeline_run(ex / "pipeline_case.toml")
    soil = run.model.soil
    if hasattr(soil, "work_counting"):
        soil = dataclasses.replace(soil, work_counting="any_region2")
    model = dataclasses.replace(run.model, length=24.0, soil=soil)
    s = run.setup
    kin = pipeline_kinematics(s.storm, s.depth, model.x, sample_interval=s.sample_interval)
    settings = dataclasses.replace(run.settings, record_interval=None)
    p = simulate_pipeline(model, kin, duration=60.0, settings=settings)
    got.update(
        p_ymax=p.max_displacement,
        p_steps=p.summary["n_steps"],
        p_work_hydro=p.summary["work_hydro"],
        p_strain=p.max_strain,
    )
    for key, value in _BEFORE.items():
        # the pipeline's Newton rule changed after these numbers (issue 33: backtracking and a
        # cost-based refactorisation rule): its converged state moves within the Newton
        # tolerance (p_ymax by 1.8e-9 m = 1e-7 relative); the step count is unchanged
        rel = 1e-6 if key in ("p_ymax", "p_work_hydro", "p_strain") else 1e-8
        assert got[key] == pytest.approx(value, rel=rel), key


@pytest.mark.parametrize("lift_relative", [False, True])
def test_section_two_stage_wake_equals_one_call_bit_for_bit(monkeypatch, lift_relative):
    """The storm section prepares the wake model once per trial step (contract rule 7) and
    evaluates it per Newton iterate; with the prepare stage off (every evaluation the one-call
    kernel, as before) the records are the same bit for bit, rejected steps included."""
    from onbottom.hydro.wake import WakeModel

    for name in ("forces", "solve_step", "initial", "integrate", "prepare_forces"):
        monkeypatch.setattr(SK, name, getattr(SK, name).py_func)
    kin = _ramped_storm()

    def run():
        return simulate_storm_section(
            Pipe(outer_diameter=0.4, submerged_weight=300.0),
            CoulombFriction(friction_coefficient=0.4),
            kin,
            force_model=WakeModel(lift_relative_velocity=lift_relative),
            settings=StormSolverSettings(
                dt_max=0.2, max_displacement_increment_over_d=0.005, record_interval=0.1
            ),
        )

    two_stage = run()
    monkeypatch.setattr(SK, "prepare_forces", lambda *args: False)
    one_call = run()
    assert two_stage.success and two_stage.summary["n_rejected"] > 0
    for v in two_stage.data.data_vars:
        np.testing.assert_array_equal(two_stage.data[v].values, one_call.data[v].values)
    assert two_stage.summary == one_call.summary
