"""Unit tests: ``onbottom calibrate`` and ``onbottom sweep`` commands."""

from __future__ import annotations

import json
import tomllib

import pytest

from onbottom.calibration.paper import PAPER_TABLE2, virtual_record
from onbottom.calibration.records import save_record
from onbottom.cli.main import main
from onbottom.results import load_dataset


@pytest.fixture(scope="module")
def record_csv(tmp_path_factory):
    rec = virtual_record("Inclined 1", PAPER_TABLE2["Inclined 1"], noise=0.0, sample_interval=2.0)
    return save_record(rec, tmp_path_factory.mktemp("rec") / "inclined1.csv")


def test_calibrate_recovers_c_and_writes_toml(record_csv, tmp_path, capsys):
    out = tmp_path / "fitted.toml"
    code = main(
        [
            "calibrate",
            str(record_csv),
            "--vary",
            "C",
            "--start",
            "A=0.25,B=0.35,C=1.2,mu=0.48",
            "--method",
            "local",
            "-o",
            str(out),
            "--plot-dir",
            str(tmp_path / "plots"),
            "--json",
        ]
    )
    assert code == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["fits"][0]["parameters"]["C"]["value"] == pytest.approx(0.79, abs=0.005)
    fitted = tomllib.loads(out.read_text())
    assert fitted["parameters"]["C"]["value"] == pytest.approx(0.79, abs=0.005)
    assert fitted["parameters"]["A"]["vary"] is False
    assert (tmp_path / "plots" / "fit_Inclined_1.png").stat().st_size > 0


def test_calibrate_rejects_bad_bounds(record_csv, capsys):
    assert main(["calibrate", str(record_csv), "--bounds", "A=0.1-0.5"]) == 1
    assert "LOWER:UPPER" in capsys.readouterr().err
    assert main(["calibrate", str(record_csv), "--vary", "A,phi"]) == 1
    assert "--vary" in capsys.readouterr().err


def test_sweep_command_writes_grid(tmp_path, capsys):
    grid = tmp_path / "grid.toml"
    grid.write_text(
        '[sweep]\nfunction = "centrifuge_response"\n'
        "[grid]\nA = [0.25, 0.35]\nmu = { start = 0.48, stop = 0.6, num = 2 }\n"
        '[fixed]\ntest = "Inclined 1"\n'
    )
    out = tmp_path / "sweep.nc"
    assert main(["sweep", str(grid), "-o", str(out), "--workers", "0", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["dims"] == {"A": 2, "mu": 2} and summary["n_failed"] == 0
    ds = load_dataset(out)
    assert ds["cycles_to_limit"].dims == ("A", "mu")
    # stronger soil (larger μ) holds the pipe for more cycles
    assert float(ds["cycles_to_limit"].sel(A=0.25, mu=0.6)) > float(
        ds["cycles_to_limit"].sel(A=0.25, mu=0.48)
    )


def test_sweep_misfit_builtin_and_bad_function(record_csv, tmp_path, capsys):
    import shutil

    grid = tmp_path / "grid.toml"
    shutil.copy(record_csv, tmp_path / record_csv.name)  # files of a grid lie beside it
    grid.write_text(
        f'[sweep]\nfunction = "misfit"\n[grid]\nC = [0.79, 1.0]\n'
        f'[fixed]\nrecord = "{record_csv.name}"\nA = 0.25\nB = 0.35\nmu = 0.48\n'
    )
    out = tmp_path / "m.nc"
    assert main(["sweep", str(grid), "-o", str(out), "--workers", "0", "--no-progress"]) == 0
    ds = load_dataset(out)
    assert float(ds["misfit"].sel(C=0.79)) < 1e-4 < float(ds["misfit"].sel(C=1.0))
    grid.write_text('[sweep]\nfunction = "nope"\n[grid]\nA = [1]\n')
    assert main(["sweep", str(grid), "-o", str(out)]) == 1
    assert "not a registered function" in capsys.readouterr().err
