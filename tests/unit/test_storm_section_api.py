"""Storm-section API: inputs, events (lift-off, runaway), results, case files and the CLI."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from onbottom.cli.main import main
from onbottom.dynamics.storm_section import (
    LoadReductions,
    StormSolverSettings,
    simulate_storm_section,
)
from onbottom.errors import InputError
from onbottom.hydro.force_model import MorisonLift
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.results import load_dataset
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.verley_sotberg import VerleySotberg

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _steady(v, duration=60.0):
    n = int(duration) + 1
    return StormKinematics(
        sample_interval=1.0,
        velocity=np.zeros(n),
        acceleration=np.zeros(n),
        current=v,
        duration=float(duration),
        weights=np.ones((1, n)),
        stage_parameters=[{"significant_velocity": 0.0, "mean_period": 1.0}],
    )


def test_settings_and_reductions_validation():
    with pytest.raises(InputError, match="dt_max"):
        StormSolverSettings(dt_max=0.0)
    with pytest.raises(InputError, match="dt_min"):
        StormSolverSettings(dt_max=0.1, dt_min=1.0)
    with pytest.raises(InputError, match="liftoff"):
        StormSolverSettings(liftoff="bounce")
    with pytest.raises(InputError, match="newmark_beta"):
        StormSolverSettings(newmark_gamma=0.9, newmark_beta=0.25)
    with pytest.raises(InputError, match="trench_angle_deg"):
        LoadReductions(trench_depth_over_d=0.5, trench_angle_deg=60.0)
    assert LoadReductions().constant_factors() == (1.0, 0.7)
    assert LoadReductions(permeable_seabed=False).constant_factors() == (1.0, 1.0)
    ry, rz = LoadReductions(trench_depth_over_d=0.5, trench_angle_deg=25.0).constant_factors()
    # F109 Eqs 3.21-3.22 by hand
    assert ry == pytest.approx(1 - 0.18 * 20**0.25 * 0.5**0.42)
    assert rz == pytest.approx(0.7 * (1 - 0.14 * 20**0.43 * 0.5**0.46))


def test_bad_arguments():
    pipe = Pipe(outer_diameter=0.4, submerged_weight=800.0)
    soil = CoulombFriction(friction_coefficient=0.6)
    storm = Storm(stages=(SeaState(hs=2.0, tp=8.0, duration_s=60.0),))
    with pytest.raises(InputError, match="depth"):
        simulate_storm_section(pipe, soil, storm)
    with pytest.raises(InputError, match="storm"):
        simulate_storm_section(pipe, soil, "storm", depth=10.0)
    with pytest.raises(InputError, match="soil"):
        simulate_storm_section(pipe, "sand", storm, depth=10.0)
    with pytest.raises(InputError, match="pipe"):
        simulate_storm_section(0.4, soil, storm, depth=10.0)


def test_liftoff_event_stop_and_free():
    pipe = Pipe(outer_diameter=0.4, submerged_weight=200.0)
    soil = CoulombFriction(friction_coefficient=0.6)
    kin = _steady(2.0)  # lift ½ρDC_L V² r_z = 0.7·0.5·1025·0.4·0.9·4 = 517 N/m > w_s
    stop = simulate_storm_section(
        pipe, soil, kin, settings=StormSolverSettings(liftoff="stop", record_interval=None)
    )
    assert stop.success and stop.status == 3 and "lift-off" in stop.message
    assert stop.summary["n_liftoff"] == 1 and stop.summary["first_liftoff_time"] == 0.0
    free = simulate_storm_section(
        pipe,
        soil,
        kin,
        settings=StormSolverSettings(record_interval=0.0, stop_displacement_over_d=1e6),
    )
    assert free.status == 1 and "lift-off" in free.message
    # free of soil while lifted: no soil force, the pipe is carried by the current
    assert np.all(free.data["F_soil"].values == 0.0)
    assert np.all(free.data["V"].values < 0.0)
    assert free.final_displacement > 10.0


def test_runaway_stop_and_criteria():
    pipe = Pipe(outer_diameter=0.4, submerged_weight=300.0)
    soil = CoulombFriction(friction_coefficient=0.6)
    r = simulate_storm_section(
        pipe,
        soil,
        _steady(1.5, 120.0),
        force_model=MorisonLift(cl=0.0),
        settings=StormSolverSettings(record_interval=None, stop_displacement_over_d=10.0),
    )
    assert r.status == 2 and "runaway" in r.message
    assert r.max_displacement >= 4.0
    assert r.criteria == {"0.5D": False, "10D": False}
    d = r.to_dict()
    assert set(d) >= {"max_displacement_m", "final_displacement_m", "criteria", "status", "message"}
    with pytest.raises(InputError, match="record_interval"):
        r.save("x.nc")


def test_dataset_units_and_penetration_reduction():
    pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm(stages=(SeaState(hs=4.68, tp=10.8, duration_s=300.0),), build_up_s=30.0)
    r = simulate_storm_section(
        pipe, soil, storm, depth=13.0, current=Current(velocity=0.91, z0=5.2e-6)
    )
    ds = r.data
    for name, unit in (("y", "m"), ("F_hydro", "N/m"), ("V", "N/m"), ("time", "s")):
        assert ds[name].attrs["units"] == unit
    z = ds["z"].values / pipe.outer_diameter
    np.testing.assert_allclose(ds["r_y"].values[1:], np.maximum(1 - 1.4 * z[:-1], 0.3), rtol=1e-12)
    assert ds.attrs["model"] == "simulate_storm_section" and ds.attrs["cd"] == 0.7


# ---- CLI ---------------------------------------------------------------------------------
_CASE = """
[pipe]
outer_diameter = 0.3951
submerged_weight = 1500.0
[seabed]
model = "sand"
submerged_unit_weight = 10.0e3
[environment]
water_depth = 13.0
[waves]
hs = 4.68
tp = 10.8
[current]
velocity = 0.91
z0 = 5.2e-6
[storm]
build_up_hours = 0.02
peak_hours = 0.1
[solver]
record_interval = 1.0
"""


def test_cli_storm_json_keys(tmp_path, capsys):
    case = tmp_path / "c.toml"
    case.write_text(_CASE, encoding="utf-8")
    png = tmp_path / "c.png"
    code = main(["storm", str(case), "--json", "--quiet", "--plot", str(png)])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) >= {"max_displacement_m", "final_displacement_m", "criteria", "status"}
    assert set(out["criteria"]) == {"0.5D", "10D"} and out["status"] == 1
    ds = load_dataset(case.with_suffix(".nc"))
    assert ds["y"].attrs["units"] == "m" and png.stat().st_size > 10_000


def test_cli_storm_seeds_in_process(tmp_path, capsys):
    case = tmp_path / "c.toml"
    case.write_text(_CASE.replace("peak_hours = 0.1", "peak_hours = 0.03"), encoding="utf-8")
    code = main(["storm", str(case), "--seeds", "3", "--workers", "0", "--json"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["seeds"] == 3 and out["statistics"]["n_seeds"] == 3
    # one meaning per key (issue #31): the worst seed, the seed mean beside it
    assert out["max_displacement_m"] == pytest.approx(out["statistics"]["max"])
    assert out["mean_max_displacement_m"] == pytest.approx(out["statistics"]["mean"])


def test_cli_storm_errors_are_json(tmp_path, capsys):
    case = tmp_path / "bad.toml"
    case.write_text(_CASE.replace("[storm]", "[storm]\nsede = 1"), encoding="utf-8")
    code = main(["storm", str(case), "--json"])
    assert code == 1
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["field"] == "storm.sede" and "seed" in err["message"]


def test_cli_storm_dispatches_pipeline_cases(tmp_path, capsys, monkeypatch):
    case = tmp_path / "p.toml"
    case.write_text(_CASE + "\n[pipeline]\nlength = 100.0\n", encoding="utf-8")
    calls = {}

    def run_pipeline(path, **options):
        calls["path"] = path
        calls["options"] = options
        return {"max_displacement_m": 0.1, "criteria": {"0.5D": True, "10D": True}}

    import onbottom.cli.storm as storm_cli

    monkeypatch.setattr(storm_cli, "_run_pipeline", run_pipeline)
    assert main(["storm", str(case), "--json", "--seeds", "2"]) == 0
    assert calls["path"] == case and calls["options"]["seeds"] == 2
    assert json.loads(capsys.readouterr().out)["max_displacement_m"] == 0.1


def test_example_storm_case_parses():
    from onbottom.cases.storm import load_storm_setup

    setup = load_storm_setup(EXAMPLES / "storm_case.toml")
    assert setup.storm.duration_s == 12600.0 and setup.storm.build_up_s == 1800.0
    assert setup.soil.name == "verley_sotberg" and setup.settings.dt_max == 0.1


_STAGES = """
[pipe]
outer_diameter = 0.4
submerged_weight = 1200.0
[seabed]
model = "clay"
undrained_shear_strength = 5.0e3
submerged_unit_weight = 8.0e3
unit_weight = 18.0e3
[environment]
water_depth = 20.0
[current]
velocity = 0.3
[storm]
build_up_hours = 0.01
decay_hours = 0.01
[[storm.stages]]
hs = 3.0
tp = 9.0
duration_hours = 0.03
[[storm.stages]]
hs = 5.0
tp = 11.0
duration_hours = 0.05
spreading_s = 4.0
"""


def test_staged_clay_case_and_text_output(tmp_path, capsys):
    from onbottom.cases.storm import load_storm_setup

    case = tmp_path / "s.toml"
    case.write_text(_STAGES, encoding="utf-8")
    setup = load_storm_setup(case)
    assert [s.hs for s in setup.storm.stages] == [3.0, 5.0]
    assert setup.storm.duration_s == pytest.approx(36.0 + 108.0 + 180.0 + 36.0)
    assert setup.soil.name == "verley_lund"
    assert setup.reductions.constant_factors() == (1.0, 1.0)  # clay: r_perm,z = 1
    assert setup.z0 == 5e-6  # F109 Table 3-1, silt and clay
    assert main(["storm", str(case), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "reached the end of the storm" in out and "F109  10D criterion  PASS" in out
    bad = tmp_path / "b.toml"
    bad.write_text(_STAGES.replace("decay_hours = 0.01", "peak_hours = 1.0"), encoding="utf-8")
    assert main(["storm", str(bad), "--json"]) == 1
    assert "not both" in json.loads(capsys.readouterr().out)["error"]["message"]
