"""Issue #31 item 4: one JSON contract.

docs/json.md is generated from the registry ``onbottom.cli.json_contract`` and must be current;
the actual ``--json`` keys of the commands equal the documented ones (top level and the nested
tables with fixed keys), every output carries ``schema_version``, and ``max_displacement_m`` is
the worst seed with ``mean_max_displacement_m`` beside it, section and pipeline alike.
Runs are kept to seconds (short storms, one-point grids).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from onbottom.cli.json_contract import CONTRACT, SCHEMA_VERSION, documented_keys, render_markdown
from onbottom.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

SECTION = (
    (EXAMPLES / "storm_case.toml")
    .read_text(encoding="utf-8")
    .replace("build_up_hours = 0.5", "build_up_hours = 0.0")
    .replace("peak_hours = 3.0", "peak_hours = 0.02")
)
PIPELINE = (
    (EXAMPLES / "pipeline_case.toml")
    .read_text(encoding="utf-8")
    .replace("record_interval = 2.0 ", "record_interval = 2.0\nduration = 4.0 ")
)
CURVES = """
[curves]
K = [5.0]
M = [0.0]
N = [0.003]
soils = ["sand"]
criteria = ["L_stable"]
seeds = 1
build_up_hours = 0.0
peak_hours = 0.01
tolerance = 0.5
diameter = 0.5
"""
GRID = """
[sweep]
function = "centrifuge_response"
[grid]
A = [0.25]
[fixed]
test = "Inclined 1"
"""


def _json(args: list[str], capsys) -> tuple[int, dict]:
    code = main([*args, "--json"])
    return code, json.loads(capsys.readouterr().out)


def _keys_match(out: dict, name: str, criteria: tuple[str, ...] = ()) -> None:
    assert out["schema_version"] == SCHEMA_VERSION
    o = CONTRACT[name]
    if o.open_keys:
        assert documented_keys(name) <= set(out), sorted(documented_keys(name) - set(out))
    else:
        assert set(out) == documented_keys(name), (
            f"undocumented: {sorted(set(out) - documented_keys(name))},"
            f" missing: {sorted(documented_keys(name) - set(out))}"
        )
    for table in o.nested:
        value = out[table.removesuffix("[]")]
        items = value if table.endswith("[]") else [value]
        assert items, table
        for item in items:
            assert set(item) == documented_keys(name, table, criteria), (table, sorted(item))


def test_docs_page_is_generated_from_the_registry():
    page = (ROOT / "docs" / "json.md").read_text(encoding="utf-8")
    assert page == render_markdown(), "regenerate: python -m onbottom.cli.json_contract"
    assert "json.md" in (ROOT / "mkdocs.yml").read_text(encoding="utf-8")


def test_error_object(capsys, tmp_path):
    code, out = _json(["stability", str(tmp_path / "missing.toml")], capsys)
    assert code == 1
    _keys_match(out, "error")


@pytest.mark.parametrize(
    ("name", "args"),
    [
        ("stability", ["stability", str(EXAMPLES / "stability_case.toml")]),
        ("loads", ["loads", str(EXAMPLES / "stability_case.toml")]),
        ("report_list", ["report", "--list"]),
        ("backbone", ["backbone", "--diameter", "1", "--weight-kn", "10.52", "--gamma-kn", "7.5"]),
        (
            "penetration",
            ["penetration", "--diameter", "0.5", "--gamma-kn", "16.7", "--phi-deg", "35"],
        ),
    ],
)
def test_fast_commands(name, args, capsys):
    code, out = _json(args, capsys)
    assert code == 0
    _keys_match(out, name)


def test_storm_section_one_seed_and_seeds(tmp_path, capsys):
    case = tmp_path / "s.toml"
    case.write_text(SECTION, encoding="utf-8")
    code, one = _json(["storm", str(case), "--quiet", "-o", str(tmp_path / "one.nc")], capsys)
    assert code == 0
    _keys_match(one, "storm_section")
    assert one["mean_max_displacement_m"] == one["max_displacement_m"]
    args = ["storm", str(case), "--seeds", "2", "--workers", "0", "-o", str(tmp_path / "s.nc")]
    code, many = _json(args, capsys)
    assert code == 0
    _keys_match(many, "storm_seeds")
    st = many["statistics"]
    assert many["max_displacement_m"] == st["max"] >= many["mean_max_displacement_m"] == st["mean"]


def test_storm_pipeline(tmp_path, capsys):
    case = tmp_path / "p.toml"
    case.write_text(PIPELINE, encoding="utf-8")
    code, out = _json(["storm", str(case), "-o", str(tmp_path / "p.nc")], capsys)
    assert code == 0
    _keys_match(out, "storm_pipeline")
    assert out["mean_max_displacement_m"] == out["max_displacement_m"]  # one seed


def test_curves(tmp_path, capsys):
    case = tmp_path / "c.toml"
    case.write_text(CURVES, encoding="utf-8")
    code, out = _json(["curves", str(case), "--workers", "0", "--quiet"], capsys)
    assert code == 0
    _keys_match(out, "curves", ("L_stable",))
    point = out["points"][0]
    assert point["L_stable_L_low"] <= point["L_stable"] <= point["L_stable_L_high"]
    assert point["L_stable_converged"] is True


def test_sweep_simulate_report(tmp_path, capsys):
    grid = tmp_path / "g.toml"
    grid.write_text(GRID, encoding="utf-8")
    code, out = _json(["sweep", str(grid), "-o", str(tmp_path / "g.nc"), "--workers", "0"], capsys)
    assert code == 0
    _keys_match(out, "sweep")
    args = ["simulate", str(EXAMPLES / "section_preset.toml"), "-o", str(tmp_path / "s.nc")]
    code, out = _json([*args, "--quiet"], capsys)
    assert code in (0, 3)
    _keys_match(out, "simulate")
    code, out = _json(["report", "--only", "f114", "--out", str(tmp_path / "r")], capsys)
    assert code == 0
    _keys_match(out, "report")
