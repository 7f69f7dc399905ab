"""``onbottom stability`` and ``onbottom loads``: tables, JSON, case-file and option errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from onbottom.cli.main import main

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "stability_case.toml"

SHEET = """
[pipe]
steel_outer_diameter = 0.2191
wall_thickness = 0.0127
contents_density = 1025.0
[[pipe.layers]]
name = "corrosion"
thickness = 0.0055
density = 1335.0
[[pipe.layers]]
name = "concrete"
thickness = 0.08255
density = 3043.5
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
reference_height = 1.0
"""


def _case(tmp_path, text: str) -> str:
    p = tmp_path / "case.toml"
    p.write_text(text, encoding="utf-8")
    return str(p)


def test_example_json_has_checks_and_design(capsys):
    assert main(["stability", str(EXAMPLE), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {"checks", "design"} <= set(data)
    row = data["checks"][0]
    assert {"name", "combination", "utilisation", "pass"} <= set(row)
    names = {r["combination"] for r in data["checks"] if r["name"] == "absolute_lateral"}
    assert len(names) == 3
    d = data["design"]
    assert d["success"] is True and d["variable"] == "concrete_thickness"
    assert 0.0 < d["value"] < 0.04  # the case's 40 mm passes, so less is needed
    assert d["utilisation"] == pytest.approx(1.0, abs=1e-3)
    assert data["all_pass"] is True


def test_sheet_pipe_fails_absolute_check_table(tmp_path, capsys):
    assert main(["stability", _case(tmp_path, SHEET)]) == 0
    out = capsys.readouterr().out
    assert "absolute_lateral" in out and "FAIL" in out and "design" in out
    assert "D = 0.3952 m" in out and "s_g = 2.7583" in out


def test_no_feasible_design_is_reported_not_crashed(tmp_path, capsys):
    text = SHEET + '[design]\nsolve_for = "concrete_thickness"\nthickness_max = 0.1\n'
    # no valid result: exit 3 (issue 10), with the report still printed
    assert main(["stability", _case(tmp_path, text), "--json"]) == 3
    d = json.loads(capsys.readouterr().out)["design"]
    assert d["success"] is False and d["value"] is None
    assert "no value in the range passes" in d["message"] and d["best_utilisation"] > 1.0


@pytest.mark.parametrize(
    ("edit", "field"),
    [
        (("[waves]", "[wave]"), "wave"),
        (("hs = 4.68", "hs = -4.68"), "waves.hs"),
        (("hs = 4.68", 'hs = "4.68"'), "waves.hs"),
        (("velocity = 0.91", "velocty = 0.91"), "current.velocty"),
        (('model = "sand"', 'model = "gravel"'), "seabed.model"),
        (("wall_thickness = 0.0127", "wall_thickness = 0.0127\nouter_diameter = 0.4"), "pipe"),
        (("submerged_unit_weight = 10.0e3", "friction_coefficient = 0.6"), "seabed"),
    ],
)
def test_case_file_errors_name_the_field(tmp_path, capsys, edit, field):
    text = SHEET.replace(*edit)
    assert main(["stability", _case(tmp_path, text), "--json"]) == 1
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["field"].startswith(field)
    assert err["type"] == "CaseFileError"


def test_design_table_errors(tmp_path, capsys):
    text = SHEET + '[design]\nsolve_for = "concrete_thickness"\nlayer = "insulation"\n'
    assert main(["stability", _case(tmp_path, text)]) == 1
    assert "insulation" in capsys.readouterr().err
    text = SHEET + "[design]\nsafety_class = 'medium'\n"
    assert main(["stability", _case(tmp_path, text)]) == 1
    assert "design.safety_class" in capsys.readouterr().err


def test_missing_file_exits_1(tmp_path, capsys):
    assert main(["stability", str(tmp_path / "nope.toml"), "--json"]) == 1
    assert "not found" in json.loads(capsys.readouterr().out)["error"]["message"]


def test_loads_json_plot_and_netcdf(tmp_path, capsys):
    png, nc = tmp_path / "vh.png", tmp_path / "vh.nc"
    args = ["loads", _case(tmp_path, SHEET), "--duration-hours", "0.5", "--seed", "3"]
    assert main([*args, "--plot", str(png), "-o", str(nc), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    c = data["combinations"][0]
    assert data["seed"] == 3 and c["n_cycles"] > 150
    assert 0.0 < c["fraction_20_45"] < 1.0
    assert png.stat().st_size > 1000 and nc.stat().st_size > 1000


@pytest.mark.parametrize(
    ("extra", "needle"),
    [
        (["--plot", "out.txt"], "--plot"),
        (["--seed", "-1"], "seed"),
        (["--duration-hours", "0"], "duration"),
    ],
)
def test_loads_option_errors(tmp_path, capsys, extra, needle):
    code = main(["loads", _case(tmp_path, SHEET), *extra])
    assert code != 0
    cap = capsys.readouterr()
    assert needle in cap.err + cap.out
