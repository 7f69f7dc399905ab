"""CLI: ``onbottom simulate`` on the example case files and ``onbottom reproduce`` (fast mode)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

from onbottom.cli.main import main
from onbottom.dynamics.status import Status
from onbottom.results import load_dataset

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_simulate_user_case_writes_netcdf_and_plot(tmp_path, capsys):
    nc = tmp_path / "run.nc"
    png = tmp_path / "run.png"
    code = main(
        [
            "simulate",
            str(EXAMPLES / "section_case.toml"),
            "-o",
            str(nc),
            "--plot",
            str(png),
            "--json",
            "--quiet",
        ]
    )
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["success"] and out["cycles_to_limit"] > 10
    ds = load_dataset(nc)
    assert ds["y"].attrs["units"] == "m" and ds.attrs["model"] == "simulate_section"
    assert png.stat().st_size > 10_000


def test_simulate_preset_and_bad_case(tmp_path, capsys):
    assert (
        main(
            [
                "simulate",
                str(EXAMPLES / "section_preset.toml"),
                "-o",
                str(tmp_path / "p.nc"),
                "--json",
                "--quiet",
            ]
        )
        == 0
    )
    assert json.loads(capsys.readouterr().out)["status"] == Status.RUNAWAY_END  # 3 in 0.1
    bad = tmp_path / "bad.toml"
    bad.write_text('[preset]\ntest = "Inclined 9"\n')
    assert main(["simulate", str(bad), "-o", str(tmp_path / "b.nc"), "--quiet"]) == 1
    assert "Inclined 9" in capsys.readouterr().err


def test_the_section_case_builds_the_run_that_simulate_runs():
    from onbottom.cases.section import load_section_run
    from onbottom.dynamics.section_run import SectionRun

    run = load_section_run(EXAMPLES / "section_case.toml")
    assert isinstance(run, SectionRun)
    assert run.attrs == {"case_file": str(EXAMPLES / "section_case.toml")}
    preset = load_section_run(EXAMPLES / "section_preset.toml")
    assert preset.attrs["source"].startswith("Youssef & Cassidy (2014)")


def test_reproduce_fast(tmp_path, capsys):
    code = main(["reproduce", "--out", str(tmp_path), "--no-plots", "--no-sensitivity", "--quiet"])
    assert code == 0
    rows = list(csv.DictReader((tmp_path / "table.csv").open()))
    assert len(rows) == 14
    assert {r["parameter_set"] for r in rows} == {"table2", "recommended"}
    assert len(list((tmp_path / "netcdf").glob("*.nc"))) == 14
    assert "Inclined 1" in (tmp_path / "table.md").read_text()
