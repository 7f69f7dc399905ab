"""`onbottom metocean` end to end on the shipped synthetic hindcast, and its case fragments
pasted into the stability example."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pyextremes")
pytest.importorskip("virocon")

from onbottom.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "hindcast_synthetic.csv"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("met") / "out"
    args = [
        "metocean",
        str(EXAMPLE),
        "--out",
        str(out),
        "--sectors",
        "4",
        "--pipe-heading-deg",
        "0",
        "--json",
    ]
    return out, args


def test_end_to_end_on_the_shipped_example(run, capsys):
    import xarray as xr

    out, args = run
    assert main(args) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["sectors"] == ["N", "E", "S", "W"]
    assert payload["return_periods"] == [1.0, 10.0, 100.0]
    assert payload["years"] == pytest.approx(25.0, abs=1e-3)
    omni = payload["table"][0]
    assert omni["sector"] == "omni"
    hs = np.array(omni["hs"])
    assert np.all(np.diff(hs) > 0) and np.all(np.array(omni["hs_lower"]) < hs)
    assert np.all(hs < np.array(omni["hs_upper"]))
    # every sector's value lies at or below the record's: each sector sees a subset of storms
    for row in payload["table"][1:]:
        assert row["hs"][2] <= omni["hs_upper"][2]
    names = {Path(f).name for f in payload["files"]}
    assert {"design_table.csv", "metocean.nc", "return_levels.png", "contours.png"} <= names
    assert {"case_omni.toml", "case_N.toml", "case_W.toml"} <= names
    ds = xr.load_dataset(out / "metocean.nc")
    np.testing.assert_allclose(ds["hs_return_value"].sel(sector="omni").values, hs)
    assert ds["hs_return_value"].attrs["units"] == "m"
    assert json.loads(ds.attrs["parameters"])["ci_method"] == "profile"
    assert ds.attrs["pyextremes_version"] and ds.attrs["virocon_version"]
    lines = (out / "design_table.csv").read_text().splitlines()
    assert lines[1].startswith("-,deg,m,m,m,s") and len(lines) == 2 + 5
    # the joint model recovers the generating Weibull (alpha 1.0 m, beta 1.35, gamma 0.25 m)
    jm = payload["joint_model"]
    assert jm["hs_scale"] == pytest.approx(1.0, rel=0.1)
    assert jm["hs_shape"] == pytest.approx(1.35, rel=0.1)
    _docs_numbers_are_these(payload)
    _contract_and_report_page(payload, out)


def _contract_and_report_page(payload, out):
    """The --json keys are the documented ones (docs/json.md), the current's joint model is
    in the table, and report.html shows the sections, the figures and the tables' CSV."""
    from onbottom.cli.json_contract import SCHEMA_VERSION, documented_keys

    assert payload["schema_version"] == SCHEMA_VERSION
    assert set(payload) == documented_keys("metocean")
    for row in payload["table"]:
        assert set(row) == documented_keys("metocean", "table[]")
    assert set(payload["joint_model"]) == documented_keys("metocean", "joint_model")
    cm = payload["current_model"]
    assert cm["scale"] > 0 and -1 < cm["rho"] < 1
    omni = payload["table"][0]
    pairs = zip(omni["current_with_hs"], omni["current_with_hs_p90"], strict=True)
    assert all(a < b for a, b in pairs)
    html = (out / "report.html").read_text(encoding="utf-8")
    for text in (
        "Storms and return values",
        "Joint model and environmental contours",
        "DNV-RP-F109 design table",
        "Assumptions and limits",
        'src="return_levels.png"',
        'src="contours.png"',
        "hindcast SHA-256",
    ):
        assert text in html, text
    assert (out / "tables" / "design_table_1.csv").is_file()
    assert str(out / "report.html") in payload["files"]


def _docs_numbers_are_these(payload):
    """The numbers docs/theory/metocean.md states for the shipped example (to half a unit of
    their last decimal): the omni table, the fitted Weibull, the 100-year contour's H_s."""
    from onbottom.metocean.synthetic import STORM_LEVELS_2000Y

    text = (ROOT / "docs" / "theory" / "metocean.md").read_text(encoding="utf-8")
    rows = re.findall(
        r"^\| (\d+) \| ([\d.]+) \[([\d.]+), ([\d.]+)\] m \| ([\d.]+) m \|$", text, re.M
    )
    assert [r[0] for r in rows] == ["1", "10", "100"]
    omni = payload["table"][0]
    for i, (rp, v, lo, hi, ref) in enumerate(rows):
        assert omni["hs"][i] == pytest.approx(float(v), abs=0.005)
        assert omni["hs_lower"][i] == pytest.approx(float(lo), abs=0.005)
        assert omni["hs_upper"][i] == pytest.approx(float(hi), abs=0.005)
        assert STORM_LEVELS_2000Y[float(rp)] == pytest.approx(float(ref), abs=0.005)
    m = re.search(r"fitted joint model: α = ([\d.]+) m, β = ([\d.]+), γ = ([\d.]+) m", text)
    jm = payload["joint_model"]
    assert jm["hs_scale"] == pytest.approx(float(m.group(1)), abs=5e-4)
    assert jm["hs_shape"] == pytest.approx(float(m.group(2)), abs=5e-4)
    assert jm["hs_location"] == pytest.approx(float(m.group(3)), abs=5e-4)
    c = re.search(r"100-year IFORM contour reaches H_s = ([\d.]+) m", text)
    assert payload["contour_max_hs"]["100"] == pytest.approx(float(c.group(1)), abs=0.005)


def _case_with(fragment: str, example: str = "stability_case.toml") -> str:
    """An example case with its [waves], [current], [[combinations]] replaced."""
    text = (ROOT / "examples" / example).read_text(encoding="utf-8")
    kept, skip = [], False
    for line in text.splitlines():
        head = re.match(r"^\s*\[\[?([a-z_.]+)\]\]?", line)
        if head:
            skip = head.group(1) in ("waves", "current", "combinations")
        if not skip:
            kept.append(line)
    return "\n".join(kept) + "\n\n" + fragment


def test_case_fragment_pastes_into_a_stability_case(run, tmp_path):
    from onbottom.cases.stability import load_stability_case

    out, args = run
    if not (out / "case_W.toml").exists():
        assert main(args) == 0
    frag = (out / "case_W.toml").read_text(encoding="utf-8")
    case_path = tmp_path / "case.toml"
    case_path.write_text(_case_with(frag), encoding="utf-8")
    case = load_stability_case(case_path)
    combos = case.load_combinations()
    assert [c.name for c in combos] == [
        "100-yr wave + 10-yr current",
        "10-yr wave + 100-yr current",
    ]
    table = {
        r.split(",")[0]: r.split(",") for r in (out / "design_table.csv").read_text().splitlines()
    }
    head = (out / "design_table.csv").read_text().splitlines()[0].split(",")
    w = dict(zip(head, table["W"], strict=True))
    assert combos[0].sea_state.hs == pytest.approx(float(w["hs_100y"]), abs=0.006)
    assert combos[0].current.velocity == pytest.approx(float(w["current_10y"]), abs=6e-4)
    assert combos[1].sea_state.hs == pytest.approx(float(w["hs_10y"]), abs=0.006)
    assert combos[1].current.velocity == pytest.approx(float(w["current_100y"]), abs=6e-4)
    # waves from W on a N-S pipe: normal to the pipe
    assert combos[0].sea_state.direction_deg % 180.0 == pytest.approx(90.0)
    # the same fragment in the storm example: [waves] is the storm's peak, [current] its current
    from onbottom.cases.storm import load_storm_setup

    storm_path = tmp_path / "storm.toml"
    storm_path.write_text(_case_with(frag, "storm_case.toml"), encoding="utf-8")
    setup = load_storm_setup(storm_path)
    assert max(st.hs for st in setup.storm.stages) == pytest.approx(float(w["hs_100y"]), abs=0.006)
    assert setup.current.velocity == pytest.approx(float(w["current_10y"]), abs=6e-4)


def test_input_errors_exit_1_with_the_field(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text(
        "time,hs,tp,wave_direction_deg\nUTC,ft,s,deg\n2000-01-01T00:00:00Z,1,8,90\n",
        encoding="utf-8",
    )
    assert main(["metocean", str(bad), "--out", str(tmp_path / "o"), "--json"]) == 1
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["field"] == "hs" and "'ft'" in err["message"]
    assert (
        main(["metocean", str(EXAMPLE), "--out", str(tmp_path / "o"), "--return-periods", "10,x"])
        == 1
    )


@pytest.mark.slow
def test_report_section_runs_and_passes(tmp_path):
    from onbottom.report import build_report

    res = build_report(tmp_path, only=["metocean"])
    (sec,) = [s for s in res.sections if s.name == "metocean"]
    assert sec.state == "ok", sec.reason
    assert res.n_fail == 0
    html = res.index.read_text(encoding="utf-8")
    assert "100-year H_s (omni) against the generating model" in html
    assert (tmp_path / "figures" / "metocean_contours.png").is_file()


def test_no_direction_column_falls_back_to_one_sector(tmp_path, capsys):
    """The shipped NDBC hindcast has no wave direction: without --sectors the analysis is
    omnidirectional, with a note (an explicit --sectors 8 still asks for the column)."""
    ndbc = ROOT / "examples" / "hindcast_ndbc_44007.csv"
    out = tmp_path / "o"
    args = ["metocean", str(ndbc), "--out", str(out), "--no-figures", "--no-report", "--json"]
    assert main(args) in (0, 3)
    payload = json.loads(capsys.readouterr().out)
    assert len(payload["sectors"]) == 1
    assert any("no wave direction column" in n for n in payload["notes"])
    assert main([*args, "--sectors", "8"]) == 1
