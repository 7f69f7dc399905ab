"""``[storm] kind = "regular"`` / ``"measured"`` in case files, the CLI and the pipeline."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from onbottom._casefile import CaseFileError
from onbottom.cases.storm import load_storm_setup
from onbottom.cli.main import main
from onbottom.hydro.kinematics import regular_wave_bed_velocity
from onbottom.hydro.storm_kinematics import StormKinematics
from storm_cases import MEASURED, PIPELINE, REGULAR
from storm_cases import write_case as _write


def _series(folder, n=301, dt=0.2):
    t = dt * np.arange(n)
    u = 0.6 * np.sin(2 * np.pi * t / 8.0)
    (folder / "data").mkdir(parents=True, exist_ok=True)
    lines = ["t [s],U [m/s]"] + [f"{a:.4f},{b:.9f}" for a, b in zip(t, u, strict=True)]
    (folder / "data" / "flow.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")


def test_regular_case_builds_airy_flow(tmp_path):
    setup = load_storm_setup(_write(tmp_path, REGULAR))
    kin = setup.storm
    assert isinstance(kin, StormKinematics)
    amp = regular_wave_bed_velocity(3.0, 10.0, 13.0)
    assert kin.stage_parameters[0]["significant_velocity"] == pytest.approx(amp)
    assert kin.duration == pytest.approx((0.0028 + 0.0139) * 3600.0, abs=0.2)
    assert kin.current > 0.0  # the [current] normal to the pipe, mean over D
    assert kin.velocity[0] == 0.0  # build-up from rest


def test_measured_case_path_is_relative_to_the_case_folder(tmp_path, monkeypatch):
    folder = tmp_path / "cases" / "site"
    _series(folder)
    case = _write(folder, MEASURED)
    monkeypatch.chdir(tmp_path)  # not the case's folder
    kin = load_storm_setup(case).storm
    assert kin.sample_interval == pytest.approx(0.2)
    assert kin.duration == pytest.approx(60.0)
    assert kin.stage_parameters[0]["mean_period"] == pytest.approx(8.0, rel=0.02)


@pytest.mark.parametrize(
    ("storm", "field", "match"),
    [
        (MEASURED, "storm.series", "no file"),
        ('[storm]\nkind = "regular"\nheight = 3.0\n', "storm", "needs height"),
        ('[storm]\nkind = "spectral"\nheight = 3.0\n', "storm", "height is for kind"),
        (REGULAR + "[run]\nseeds = 3\n", "run", "deterministic"),
        ('[storm]\nkind = "regular"\nheight = 12.0\nperiod = 5.0\n', "storm.height", "Miche"),
        ('[storm]\nkind = "measured"\nseries = "f.csv"\npeak_hours = 1.0\n', "storm", "record"),
        ('[storm]\nkind = "tidal"\n', "storm.kind", "tidal"),
    ],
)
def test_flow_case_errors_are_named(tmp_path, storm, field, match):
    with pytest.raises(CaseFileError, match=match) as info:
        load_storm_setup(_write(tmp_path, storm))
    assert (info.value.field or "").startswith(field)


def test_measured_series_error_names_the_key_and_the_line(tmp_path):
    folder = tmp_path / "c"
    (folder / "data").mkdir(parents=True)
    (folder / "data" / "flow.csv").write_text(
        "t [s],U [m/s]\n0,0\n0.5,0.1\n0.5,0.2\n1.5,0\n", encoding="utf-8"
    )
    with pytest.raises(CaseFileError, match=r"storm.series: .*line 4 duplicates") as info:
        load_storm_setup(_write(folder, MEASURED))
    assert info.value.field == "storm.series"


def test_cli_runs_a_regular_wave_section_and_refuses_seeds(tmp_path, capsys):
    case = _write(tmp_path, REGULAR)
    assert main(["storm", str(case), "--json", "--quiet"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["success"] and out["status"] == 1
    assert math.isfinite(out["max_displacement_m"])
    assert case.with_suffix(".nc").exists()
    assert main(["storm", str(case), "--json", "--seeds", "2"]) != 0
    assert "deterministic" in capsys.readouterr().out


def test_cli_runs_a_measured_record_on_the_pipeline(tmp_path, capsys):
    folder = tmp_path / "p"
    _series(folder, n=151)
    case = _write(folder, MEASURED, PIPELINE)
    assert main(["storm", str(case), "--json", "--quiet"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "pipeline_fe" and out["success"]
    assert out["per_seed"][0]["summary"]["final_time"] == pytest.approx(30.0)
    # long-crested, in phase: every node of a uniform free line moves alike
    import xarray as xr

    with xr.open_dataset(out["netcdf"], engine="h5netcdf") as ds:
        ymax = ds["max_abs_y"].values
    assert ymax.max() > 0.0
    assert np.ptp(ymax) <= 1e-6 * ymax.max()


def test_regular_example_case_loads():
    from pathlib import Path

    case = Path(__file__).resolve().parents[2] / "examples" / "storm_regular_case.toml"
    kin = load_storm_setup(case).storm
    assert kin.stage_parameters[0]["kind"] == "regular"
    assert kin.duration == pytest.approx(0.3 * 3600.0, abs=0.5)
