"""Pipeline solver plumbing: NetCDF chunks, checkpoint resume and run identity, inputs,
events, the case-file entry point and the plots."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from onbottom.cases.pipeline import load_pipeline_run
from onbottom.dynamics.pipeline import (
    PipelineModel,
    PipelineSettings,
    SoilSection,
    simulate_pipeline,
)
from onbottom.dynamics.pipeline import solver as S
from onbottom.errors import InputError
from onbottom.hydro.short_crested import regular_node_kinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.verley_sotberg import VerleySotberg
from onbottom.study.pipeline_seeds import run_pipeline_seeds

PIPE = Pipe(outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9)
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "pipeline_case.toml"


def _setup(**kw):
    m = PipelineModel(
        pipe=PIPE,
        length=60.0,
        element_length=4.0,
        soil=CoulombFriction(friction_coefficient=0.5),
        **kw,
    )
    kin = regular_node_kinematics(
        m.x.size, 60.0, 0.05, 1.5, 10.0, ramp=20.0, x=m.x, wavelength=200.0
    )
    return m, kin


def test_netcdf_in_chunks_matches_memory_records(tmp_path):
    m, kin = _setup()
    st = PipelineSettings(record_interval=2.0, chunk_duration=7.0)
    mem = simulate_pipeline(m, kin, settings=st)
    disk = simulate_pipeline(m, kin, settings=st, output=tmp_path / "run.nc")
    ds = disk.open_dataset()
    assert ds.sizes["time"] == 31 and ds.sizes["node"] == m.x.size
    np.testing.assert_allclose(ds["time"].values, 2.0 * np.arange(31))
    np.testing.assert_allclose(ds["y"].values, mem.data["y"].values, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(ds["max_abs_y"].values, mem.envelopes["max_abs_y"].values)
    assert ds["y"].attrs["units"] == "m"
    assert json.loads(ds.attrs["summary"])["n_steps"] == mem.summary["n_steps"]


def _interrupt_at_the_third_chunk(monkeypatch, m, kin, st, out):
    """Run to ``out`` with a Ctrl-C raised at the third kernel chunk (checkpoint left)."""
    calls = {"n": 0}
    real = S.K.integrate

    def flaky(*args):
        calls["n"] += 1
        if calls["n"] == 3:
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(S.K, "integrate", flaky)
    with pytest.raises(KeyboardInterrupt):
        simulate_pipeline(m, kin, settings=st, output=out)
    monkeypatch.setattr(S.K, "integrate", real)


def test_interrupted_run_resumes_from_its_checkpoint(tmp_path, monkeypatch):
    m, kin = _setup()
    st = PipelineSettings(record_interval=1.0, chunk_duration=10.0)
    ref = simulate_pipeline(m, kin, settings=st, output=tmp_path / "ref.nc").open_dataset()
    out = tmp_path / "run.nc"
    _interrupt_at_the_third_chunk(monkeypatch, m, kin, st, out)
    assert (tmp_path / "run.nc.ckpt.npz").exists()
    res = simulate_pipeline(m, kin, settings=st, output=out, resume="require")
    ds = res.open_dataset()
    np.testing.assert_array_equal(ds["time"].values, ref["time"].values)
    np.testing.assert_array_equal(ds["y"].values, ref["y"].values)


def test_checkpoint_of_other_inputs_is_not_resumed(tmp_path):
    m, kin = _setup()
    out = tmp_path / "run.nc"
    st = PipelineSettings(record_interval=5.0)
    simulate_pipeline(m, kin, settings=st, output=out)
    m2, _ = _setup(effective_axial_force=-1e4)
    with pytest.raises(InputError, match="another run"):
        simulate_pipeline(m2, kin, settings=st, output=out, resume="require")
    r = simulate_pipeline(m2, kin, settings=st, output=out)  # auto: starts anew
    assert r.success and r.open_dataset().sizes["time"] == 13


def test_runaway_stop_and_lift_off_events():
    light = Pipe(
        outer_diameter=0.4, submerged_weight=150.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    m = PipelineModel(
        pipe=light, length=40.0, element_length=4.0, soil=CoulombFriction(friction_coefficient=0.3),
        end_conditions="free",
    )  # fmt: skip
    kin = regular_node_kinematics(m.x.size, 60.0, 0.05, 2.5, 10.0, ramp=10.0)
    r = simulate_pipeline(
        m, kin, settings=PipelineSettings(stop_displacement_over_d=2.0, record_interval=None)
    )
    assert r.status == 2 and r.success
    assert r.max_displacement >= 2.0 * 0.4
    assert r.summary["time_to_stop_displacement"] < 60.0
    # a runaway stop below a limit fails that limit too (as the section solver)
    assert r.criteria["0.5D"] is False and r.criteria["10D"] is False
    # lift 0.7·½ρDC_L·U² > w_s once U > 1.08 m/s: the pipe is lifted (no soil resistance)
    r = simulate_pipeline(m, kin, duration=15.0, settings=PipelineSettings(record_interval=1.0))
    assert r.summary["n_liftoff"] > 0 and 4.0 < r.summary["first_liftoff_time"] < 15.0
    assert float(r.data["V"].min()) < 0.0
    assert float(np.abs(r.data["F_soil"].values[r.data["V"].values <= 0.0]).max()) == 0.0


def test_route_sections_and_input_errors():
    sand = Sand(submerged_unit_weight=1e4)
    secs = (
        SoilSection(start=0.0, end=20.0, model=VerleySotberg.silica(PIPE, sand)),
        SoilSection(start=20.0, end=60.0, model=CoulombFriction(friction_coefficient=0.4)),
    )
    m = PipelineModel(pipe=PIPE, length=60.0, element_length=4.0, soil=secs)
    a = m.arrays()
    assert list(a["model_ids"][:5]) == [1] * 5 and list(a["model_ids"][5:]) == [0] * 11
    kin = regular_node_kinematics(m.x.size, 20.0, 0.05, 1.5, 10.0, ramp=5.0)
    assert simulate_pipeline(m, kin).success
    with pytest.raises(InputError, match="contiguous"):
        gap = SoilSection(start=25.0, end=60.0, model=secs[1].model)
        PipelineModel(pipe=PIPE, length=60.0, element_length=4.0, soil=(secs[0], gap))
    with pytest.raises(InputError, match="EI"):
        bare = Pipe(outer_diameter=0.4, submerged_weight=600.0)
        PipelineModel(pipe=bare, length=10.0, element_length=1.0, soil=secs[1].model)
    with pytest.raises(InputError, match="end_conditions"):
        PipelineModel(
            pipe=PIPE, length=10.0, element_length=1.0, soil=secs[1].model, end_conditions="x"
        )
    with pytest.raises(InputError, match="node columns"):
        simulate_pipeline(m, regular_node_kinematics(3, 5.0, 0.1, 1.0, 5.0))
    with pytest.raises(InputError, match="alpha"):
        PipelineSettings(alpha=-0.5)


def test_spring_ends_between_free_and_fixed():
    kw = {
        "pipe": PIPE,
        "length": 40.0,
        "element_length": 4.0,
        "soil": CoulombFriction(friction_coefficient=0.3),
    }
    kin = regular_node_kinematics(11, 30.0, 0.05, 0.0, 10.0)
    kin = type(kin)(
        t0=0.0, dt=kin.dt, velocity=kin.velocity + np.float32(1.2), acceleration=kin.acceleration
    )
    st = PipelineSettings(record_interval=None)
    free = simulate_pipeline(PipelineModel(end_conditions="free", **kw), kin, settings=st)
    spring = simulate_pipeline(
        PipelineModel(end_conditions="spring", end_springs=(1e6, 2e4, 1e5), **kw), kin, settings=st
    )
    fixed = simulate_pipeline(PipelineModel(end_conditions="fixed", **kw), kin, settings=st)
    assert free.max_displacement > spring.max_displacement > fixed.max_displacement


def test_run_pipeline_case_example(tmp_path):
    case = tmp_path / "pipeline_case.toml"
    shutil.copy(EXAMPLE, case)
    text = case.read_text().replace("peak_hours = 0.0667             # 4 min", "peak_hours = 0.01")
    case.write_text(text)
    study = run_pipeline_seeds(load_pipeline_run(case), output=case.with_suffix(".nc"))
    payload = study.to_dict()
    for key in ("max_displacement_m", "max_strain", "worst_node_x_m", "criteria", "netcdf"):
        assert key in payload
    assert payload["success"] and payload["n_nodes"] == 51
    import matplotlib.pyplot as plt

    from onbottom.plotting.pipeline import plot_pipeline_result
    from onbottom.results import save_figure

    fig = plot_pipeline_result(study.result, title="example")
    save_figure(fig, tmp_path / "p.png", dpi=110)
    plt.close(fig)
    assert (tmp_path / "p.png").stat().st_size > 1000
    with xr.open_dataset(payload["netcdf"], engine="h5netcdf") as ds:
        assert "strain" in ds and "max_strain" in ds


def test_pipeline_table_errors(tmp_path):
    from onbottom._casefile import CaseFileError

    case = tmp_path / "bad.toml"
    case.write_text(EXAMPLE.read_text().replace("element_length = 4.0", "element_lenght = 4.0"))
    with pytest.raises(CaseFileError, match="did you mean 'element_length'"):
        load_pipeline_run(case)


def test_onbottom_storm_dispatches_a_pipeline_case(tmp_path, capsys):
    """`onbottom storm CASE --json` with a [pipeline] table runs the pipeline FE."""
    from onbottom.cli.main import main

    case = tmp_path / "pipeline_case.toml"
    text = EXAMPLE.read_text().replace(  # 0.01 h: a peak of 3 T_p at least (issue #31)
        "peak_hours = 0.0667             # 4 min", "peak_hours = 0.01"
    )
    case.write_text(text)
    code = main(["storm", str(case), "--json", "-o", str(tmp_path / "out.nc")])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["model"] == "pipeline_fe" and out["strain_check"] in (True, False)
    for key in ("max_displacement_m", "max_strain", "worst_node_x_m"):
        assert isinstance(out[key], float)
    assert set(out["criteria"]) == {"0.5D", "10D"}
    code = main(["storm", str(case), "-o", str(tmp_path / "out.nc")])
    text_out = capsys.readouterr().out
    assert code == 0 and "F109 0.5D criterion" in text_out


def test_animation_is_a_gif(tmp_path):
    from onbottom.plotting.pipeline import animate_pipeline

    m, kin = _setup()
    r = simulate_pipeline(m, kin, duration=10.0, settings=PipelineSettings(record_interval=2.0))
    out = animate_pipeline(r, tmp_path / "a.gif", max_frames=4, dpi=40)
    assert out.read_bytes()[:3] == b"GIF"
    with pytest.raises(InputError, match="record_interval"):
        animate_pipeline(
            simulate_pipeline(
                m, kin, duration=2.0, settings=PipelineSettings(record_interval=None)
            ),
            tmp_path / "b.gif",
        )


@pytest.mark.dask
@pytest.mark.slow
@pytest.mark.long
def test_several_seeds_on_dask_and_in_process(tmp_path, capsys):
    case = tmp_path / "pipeline_case.toml"
    text = EXAMPLE.read_text().replace(  # 0.01 h: a peak of 3 T_p at least (issue #31)
        "peak_hours = 0.0667             # 4 min", "peak_hours = 0.01"
    )
    text = text.replace("build_up_hours = 0.0167         # 1 min", "build_up_hours = 0.003")
    case.write_text(text)
    run = load_pipeline_run(case)
    serial = run_pipeline_seeds(run, seeds=2, workers=0, output=tmp_path / "s.nc").to_dict()
    dask = run_pipeline_seeds(run, seeds=2, workers=2, output=tmp_path / "d.nc").to_dict()
    assert serial["seeds"] == 2 and len(serial["netcdf"]) == 2
    assert [r["seed"] for r in dask["per_seed"]] == [1, 2]
    for a, b in zip(serial["per_seed"], dask["per_seed"], strict=True):
        assert a["max_displacement_m"] == b["max_displacement_m"]
    assert (
        serial["per_seed"][0]["max_displacement_m"] != serial["per_seed"][1]["max_displacement_m"]
    )
    from onbottom.cli.main import main

    args = ["storm", str(case), "--seeds", "2", "--workers", "0", "--plot", str(tmp_path / "p.png")]
    assert main([*args, "--json"]) == 1
    assert "one seed" in json.loads(capsys.readouterr().out)["error"]["message"]


def test_rerun_of_a_finished_or_stopped_run_returns_it(tmp_path):
    light = Pipe(
        outer_diameter=0.4, submerged_weight=150.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    m = PipelineModel(
        pipe=light,
        length=40.0,
        element_length=4.0,
        soil=CoulombFriction(friction_coefficient=0.3),
        end_conditions="free",
    )
    kin = regular_node_kinematics(m.x.size, 60.0, 0.05, 2.5, 10.0, ramp=10.0)
    st = PipelineSettings(stop_displacement_over_d=2.0, record_interval=1.0)
    a = simulate_pipeline(m, kin, settings=st, output=tmp_path / "r.nc")
    b = simulate_pipeline(m, kin, settings=st, output=tmp_path / "r.nc", resume="require")
    assert a.status == b.status == 2
    assert b.summary["final_time"] == a.summary["final_time"] < 60.0
    assert b.open_dataset().sizes["time"] == a.open_dataset().sizes["time"]


def test_case_file_route_sections(tmp_path):

    case = tmp_path / "route.toml"
    case.write_text(
        EXAMPLE.read_text()
        + """
[[pipeline.sections]]
start = 0.0
end = 120.0

[[pipeline.sections]]
start = 120.0
end = 200.0
model = "clay"
undrained_shear_strength = 5000.0
submerged_unit_weight = 6000.0
unit_weight = 16000.0
friction_coefficient = 0.2
axial_friction_coefficient = 0.3
"""
    )
    run = load_pipeline_run(case)
    m = run.model
    ids = m.arrays()["model_ids"]
    x = m.x
    assert set(ids[x < 120.0]) == {1} and set(ids[x >= 120.0]) == {2}
    assert m.sections[1].mu_axial == 0.3 and m.sections[0].mu_axial == 0.6
    assert run.settings.strain_limit == 0.002
    assert m.fibre_distance == pytest.approx(0.2191 / 2)


def test_simple_pipe_form_takes_ei_ea_mass_from_the_pipeline_table(tmp_path):
    from onbottom._casefile import CaseFileError

    text = EXAMPLE.read_text()
    _head, tail = text.split("[seabed]", 1)
    simple = "[pipe]\nouter_diameter = 0.3\nsubmerged_weight = 900.0\n\n[seabed]" + tail
    case = tmp_path / "simple.toml"
    case.write_text(simple)
    with pytest.raises(CaseFileError, match="EI must be > 0"):
        load_pipeline_run(case)
    case.write_text(
        simple.replace(
            "[pipeline]\n",
            "[pipeline]\nbending_stiffness = 9.1e6\naxial_stiffness = 1.7e9\nmass = 150.0\n",
        )
    )
    m = load_pipeline_run(case).model
    assert (m.ei, m.ea, m.pipe.structural_mass) == (9.1e6, 1.7e9, 150.0)
    assert m.fibre_distance == pytest.approx(0.15)  # D/2 without a build-up


def test_case_file_displacement_increment_is_taken_as_given(tmp_path):
    """[solver] max_displacement_increment_over_d reaches the pipeline unchanged (it was raised
    silently to at least 0.05 before)."""

    case = tmp_path / "small_increment.toml"
    text = EXAMPLE.read_text().replace(
        "[solver]\n", "[solver]\nmax_displacement_increment_over_d = 0.01\n", 1
    )
    case.write_text(text)
    assert load_pipeline_run(case).settings.max_displacement_increment_over_d == 0.01
    assert load_pipeline_run(EXAMPLE).settings.max_displacement_increment_over_d == 0.05
