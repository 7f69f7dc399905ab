"""Inputs that pass the schema but cannot be right, and files a case names: every case is a
named error (the key, its line, exit 1 without a traceback), a note, or the correct result.

* one containment rule for every path a case file names, absolute or relative (``[hydro]
  coefficient_table``, ``[storm] series``, ``[reliability.climate] hindcast``, the route's
  ``[hydro]`` files), opened by ``onbottom --allow-outside-paths``; errors never echo a file's
  content;
* KP sections in order and contiguous (or a ``gap_reason``), KP in metres under ``_km``; seabed
  keys of another soil model; a user allowable displacement above 10D; all-zero or unused
  Morison coefficients; hindcast directions in radians and H_s spikes; reliability limits
  beyond the storms' runaway stop or given twice; ``storms_per_year`` beside a climate.
"""

from __future__ import annotations

import json
import re
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

from onbottom._casefile import CaseFileError, allow_outside_paths
from onbottom.cli.main import main
from onbottom.errors import InputError

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document, route_toml
from storm_cases import MEASURED, REGULAR, write_case

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
SECRET = "TOP-SECRET-FIRST-LINE"


def _secret_file(folder: Path, name: str = "secret.csv") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    p = folder / name
    p.write_text(f"{SECRET},x,y\n{SECRET}2\n1,2,3\n4,5,6\n", encoding="utf-8")
    return p


def _line_of(text: str, needle: str) -> int:
    return next(i for i, ln in enumerate(text.splitlines(), 1) if needle in ln)


def _cli_error(args: list, capsys) -> dict:
    rc = main([*map(str, args), "--json"])
    out = capsys.readouterr()
    assert rc == 1, out
    assert "Traceback" not in out.err
    return json.loads(out.out)["error"]


# ---- paths -----------------------------------------------------------------------------------
@pytest.mark.parametrize("where", ["outside", "absolute", "dotdot"])
def test_storm_series_outside_the_case_folder_is_refused_without_its_content(tmp_path, where):
    from onbottom.cases.storm import load_storm_setup

    other = _secret_file(tmp_path / "elsewhere")
    value = {"outside": str(other), "absolute": "/etc/passwd", "dotdot": "../elsewhere/secret.csv"}
    case = write_case(tmp_path / "case", MEASURED.replace("data/flow.csv", value[where]))
    with pytest.raises(CaseFileError) as err:
        load_storm_setup(case)
    msg = str(err.value)
    assert err.value.field == "storm.series" and "leaves the case file's folder" in msg
    assert err.value.line == _line_of(case.read_text(), "series =")
    assert "--allow-outside-paths" in msg
    assert SECRET not in msg and "root:" not in msg


def test_coefficient_table_absolute_path_is_refused_by_key_and_line(tmp_path):
    from onbottom.cases.storm import load_storm_setup

    extra = '[hydro]\ncoefficient_table = "/etc/passwd"\n'
    case = write_case(tmp_path, REGULAR, extra)
    with pytest.raises(CaseFileError) as err:
        load_storm_setup(case)
    assert err.value.field == "hydro.coefficient_table"
    assert err.value.line == _line_of(case.read_text(), "coefficient_table")
    assert "root:" not in str(err.value)


def test_files_inside_the_folder_never_have_their_content_echoed(tmp_path):
    """A file inside the folder that is not what the key wants: the error names the key and
    the file, not its first line."""
    from onbottom.cases.storm import load_storm_setup

    _secret_file(tmp_path, "table.csv")
    case = write_case(tmp_path, REGULAR, '[hydro]\ncoefficient_table = "table.csv"\n')
    with pytest.raises(InputError) as err:
        load_storm_setup(case)
    assert err.value.field == "hydro.coefficient_table" and err.value.line is not None
    assert SECRET not in str(err.value)
    case = write_case(tmp_path, MEASURED.replace("data/flow.csv", "table.csv"))
    with pytest.raises(InputError) as err:
        load_storm_setup(case)
    assert "storm.series" in str(err.value) and SECRET not in str(err.value)


def test_allow_outside_paths_opens_the_rule(tmp_path, capsys):
    """``onbottom --allow-outside-paths``: the series outside the folder is read (the next
    error, of another key, is reached); without the option the path is refused; the option
    does not stay on for the next command."""
    flow = _secret_file(tmp_path / "elsewhere")
    storm = MEASURED.replace("data/flow.csv", str(flow)) + "sample_interval = 0.5\n"
    case = write_case(tmp_path / "case", storm)
    err = _cli_error(["--allow-outside-paths", "storm", case], capsys)
    assert err["field"] == "storm.sample_interval", err
    err = _cli_error(["storm", case], capsys)
    assert err["field"] == "storm.series" and "leaves the case file's folder" in err["message"]
    try:
        allow_outside_paths(True)
        from onbottom.cases.storm import load_storm_setup

        with pytest.raises(CaseFileError, match="storm.sample_interval"):
            load_storm_setup(case)
    finally:
        allow_outside_paths(False)


def test_route_hydro_files_follow_the_same_rule(tmp_path):
    from onbottom.cases.assess import load_route_case

    for value in ("/etc/passwd", "../x.csv"):
        doc = route_document()
        doc["hydro"] = {"model": "morison", "coefficient_table": value}
        case = tmp_path / "route.toml"
        case.write_text(route_toml(doc), encoding="utf-8")
        with pytest.raises(CaseFileError) as err:
            load_route_case(case)
        assert err.value.field == "hydro.coefficient_table"
        assert err.value.line == _line_of(case.read_text(), "coefficient_table")
        assert "root:" not in str(err.value)


def test_route_coefficient_table_is_relative_to_the_case_not_the_working_folder(
    tmp_path, monkeypatch
):
    from onbottom.cases.assess import load_route_case

    table = (
        "K,M,C_D,C_M,C_L\n-,-,-,-,-\n1,0,1.0,3.0,1.0\n1,5,0.8,3.0,0.8\n500,0,2.0,2.0,2.0\n"
        "500,5,1.6,2.0,1.6\n"
    )
    (tmp_path / "c.csv").write_text(table, encoding="utf-8")
    doc = route_document()
    doc["hydro"] = {"model": "morison", "coefficient_table": "c.csv"}
    case = tmp_path / "route.toml"
    case.write_text(route_toml(doc), encoding="utf-8")
    monkeypatch.chdir(ROOT)  # not the case's folder
    rc = load_route_case(case)
    assert Path(rc.hydro.coefficient_table) == (tmp_path / "c.csv").resolve()


# ---- the route ---------------------------------------------------------------------------------
def _route_error(tmp_path: Path, doc: dict) -> CaseFileError:
    from onbottom.cases.assess import load_route_case

    case = tmp_path / "route.toml"
    case.write_text(route_toml(doc), encoding="utf-8")
    with pytest.raises(CaseFileError) as err:
        load_route_case(case)
    assert err.value.line is not None, str(err.value)
    return err.value


def test_kp_gap_needs_a_reason_and_is_reported(tmp_path):
    from onbottom.cases.assess import build_route, load_route_case

    doc = route_document(sections=2)
    doc["route"]["sections"][1]["kp_start_km"] = 10.5  # a 0.5 km hole
    err = _route_error(tmp_path, doc)
    assert err.field == "route.sections[1].kp_start_km" and "hole" in str(err)
    assert "gap_reason" in str(err)
    doc["route"]["sections"][1]["gap_reason"] = "pipeline crossing, assessed separately"
    case = tmp_path / "route.toml"
    case.write_text(route_toml(doc), encoding="utf-8")
    route = build_route(load_route_case(case))
    assert "KP 10–10.5 km" in route.sections[1].gap and "crossing" in route.sections[1].gap
    doc = route_document(sections=2)
    doc["route"]["sections"][1]["gap_reason"] = "no gap here"
    assert _route_error(tmp_path, doc).field == "route.sections[1].gap_reason"


def test_kp_sections_out_of_order_and_metres_for_km_are_refused(tmp_path):
    doc = route_document(sections=3)
    s = doc["route"]["sections"]
    s[1], s[2] = s[2], s[1]
    err = _route_error(tmp_path, doc)
    assert "KP order" in str(err)
    doc = route_document(sections=2)
    for k, sec in enumerate(doc["route"]["sections"]):  # metres typed under _km
        sec["kp_start_km"], sec["kp_end_km"] = 3000.0 * k, 3000.0 * (k + 1)
    err = _route_error(tmp_path, doc)
    assert err.field == "route.sections[1].kp_end_km" and "kp_start_m" in str(err)
    doc = route_document()
    sec = doc["route"]["sections"][0]
    del sec["kp_start_km"], sec["kp_end_km"]
    sec["kp_start_m"], sec["kp_end_m"] = 2.0, 10.0  # km typed under _m
    err = _route_error(tmp_path, doc)
    assert err.field == "route.sections[0].kp_end_m" and "shorter than" in str(err)


def test_rock_seabed_with_sand_keys_is_refused(tmp_path):
    doc = route_document()
    doc["route"]["sections"][0]["seabed"] = {
        "model": "rock",
        "submerged_unit_weight": 10.0e3,
        "d50": 0.25e-3,
        "friction_coefficient": 0.6,
    }
    err = _route_error(tmp_path, doc)
    assert "submerged_unit_weight, d50 do not apply to model = 'rock'" in str(err)
    assert err.field.startswith("route.sections[0].seabed")


def test_seabed_keys_of_another_model_in_a_stability_case(tmp_path):
    from onbottom.cases.stability import load_stability_case

    text = (EXAMPLES / "stability_case.toml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^(\[seabed\]\s*\n)", r"\1undrained_shear_strength = 5.0e3\n", text)
    case = tmp_path / "case.toml"
    case.write_text(text, encoding="utf-8")
    with pytest.raises(CaseFileError, match="undrained_shear_strength does not apply") as err:
        load_stability_case(case)
    assert err.value.field == "seabed" and err.value.line is not None


def test_allowable_displacement_of_a_kilometre_is_refused(tmp_path):
    doc = route_document()
    doc["dynamic"] |= {"allowable": "user", "allowable_displacement_m": 1000.0}
    err = _route_error(tmp_path, doc)
    assert err.field == "dynamic.allowable_displacement_m" and "10D" in str(err)
    doc["dynamic"]["allowable_displacement_m"] = 1.0  # about 3.4 D of this pipe: accepted
    from onbottom.cases.assess import parse_route_case

    assert parse_route_case(doc).dynamic.allowable_displacement_m == 1.0


def test_zero_or_unused_force_coefficients_are_refused(tmp_path):
    from onbottom.cases.storm import load_storm_setup

    case = write_case(tmp_path, REGULAR, "[hydro]\ncd = 0.0\ncm = 0.0\ncl = 0.0\n")
    with pytest.raises(CaseFileError, match="no wave or current force") as err:
        load_storm_setup(case)
    assert err.value.field == "hydro.cd" and err.value.line is not None
    case = write_case(tmp_path, REGULAR, '[hydro]\nmodel = "wake"\ncd = 1.2\n')
    with pytest.raises(CaseFileError, match="hydro.cd = 1.2 is not used by hydro.model = 'wake'"):
        load_storm_setup(case)
    doc = route_document()  # assess: the wake model by default
    doc["hydro"] = {"cd": 1.2}
    assert _route_error(tmp_path, doc).field == "hydro.cd"


# ---- hindcasts ---------------------------------------------------------------------------------
def _hindcast(n: int = 400, **cols):
    from onbottom.metocean.hindcast import Hindcast

    rng = np.random.default_rng(0)
    t = np.datetime64("2000-01-01T00:00:00") + np.arange(n) * np.timedelta64(3, "h")
    hs = 2.0 + np.abs(np.sin(np.arange(n) / 15.0)) + 0.1 * rng.random(n)
    base = {
        "time": t,
        "hs": hs,
        "tp": 8.0 + hs,
        "wave_direction_deg": rng.uniform(0.0, 360.0, n),
        "current_speed": None,
        "current_direction_deg": None,
    }
    return Hindcast(**(base | cols))


def test_hindcast_directions_in_radians_are_refused():
    rng = np.random.default_rng(1)
    with pytest.raises(InputError, match="look like radians") as err:
        _hindcast(wave_direction_deg=rng.uniform(0.0, 2.0 * np.pi, 400))
    assert err.value.field == "wave_direction_deg"
    _hindcast()  # degrees: accepted


def test_hindcast_spike_is_a_named_note_and_the_synthetic_record_has_none():
    from onbottom.metocean.hindcast import hindcast_notes, read_hindcast

    h = _hindcast()
    assert hindcast_notes(h) == []
    hs = np.array(h.hs)
    hs[100:108] = 25.0  # one day at 25 m in a 2-3 m sea (3-hourly)
    (note,) = hindcast_notes(_hindcast(hs=hs, tp=np.maximum(8.0 + hs, 18.0)))
    assert note.startswith("hs: 1 outlier(s)") and "25 m" in note and "2000-01-13" in note
    assert hindcast_notes(read_hindcast(EXAMPLES / "hindcast_synthetic.csv")) == []


def test_extrapolation_note_is_the_metocean_one():
    from onbottom.metocean.run import extrapolation_note

    assert extrapolation_note(100.0, 25.0) is None
    note = extrapolation_note(1.0e4, 25.0)
    assert note.startswith("return periods up to 10000 years from a 25.0-year record")


# ---- reliability ---------------------------------------------------------------------------
def _reliability(tmp_path: Path, **subs: str) -> Path:
    text = (EXAMPLES / "reliability_case.toml").read_text(encoding="utf-8")
    shutil.copy(EXAMPLES / "hindcast_synthetic.csv", tmp_path)
    for key, value in subs.items():
        text = re.sub(rf"(?m)^{key} = [^#\n]*", f"{key} = {value} ", text)
    p = tmp_path / "case.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _reliability_error(case: Path) -> CaseFileError:
    from onbottom.cases.reliability import load_reliability_setup

    with pytest.raises(CaseFileError) as err:
        load_reliability_setup(case)
    assert err.value.line is not None, str(err.value)
    return err.value


def test_reliability_limits_in_range_and_unique(tmp_path):
    err = _reliability_error(_reliability(tmp_path, limits='["0.5D", "1e9D"]'))
    assert err.field == "reliability.limits[1]" and "never exceeded" in str(err)
    err = _reliability_error(_reliability(tmp_path, limits='["0.5D", "10D", "0.5D"]'))
    assert err.field == "reliability.limits[2]" and "same limit" in str(err)
    err = _reliability_error(_reliability(tmp_path, limits='["0.5D", 1e9]'))
    assert err.field == "reliability.limits[1]"


def test_storms_per_year_beside_a_climate_is_a_conflict(tmp_path):
    case = _reliability(tmp_path, design_life_years="25.0\nstorms_per_year = 2.0")
    err = _reliability_error(case)
    assert err.field == "reliability.storms_per_year" and "conflicts with" in str(err)
    assert err.line == _line_of(case.read_text(), "storms_per_year")


def test_reliability_hindcast_outside_the_folder_is_refused(tmp_path, capsys):
    case = _reliability(tmp_path)
    text = case.read_text().replace('"hindcast_synthetic.csv"', '"/etc/passwd"')
    case.write_text(text, encoding="utf-8")
    err = _cli_error(["reliability", case, "--workers", "0"], capsys)
    assert err["field"] == "reliability.climate.hindcast" and "root:" not in err["message"]


def test_reliability_errors_name_case_keys_not_internal_names(tmp_path):
    err = _reliability_error(_reliability(tmp_path, top_points="20"))
    assert err.field == "reliability.design.top_points"
    assert "ReliabilitySetup" not in str(err) and "ContourDesign" not in str(err)


def test_route_storm_errors_name_the_dynamic_keys_not_the_storm_document(tmp_path):
    doc = route_document()
    doc["dynamic"]["peak_hours"] = 1.0e-4  # shorter than 3 peak periods
    err = _route_error(tmp_path, doc)
    assert err.field == "dynamic.peak_hours"
    assert err.line == _line_of((tmp_path / "route.toml").read_text(), "peak_hours")
    assert "storm.peak_hours" not in str(err) and "sections[0].storm" not in str(err)


def test_contour_points_the_contour_cannot_take_are_refused_by_the_schema(tmp_path):
    """4 points passed the schema and failed after the hindcast analysis as ``n_points``."""
    err = _reliability_error(_reliability(tmp_path, contour_points="4"))
    assert err.field == "reliability.design.contour_points" and "n_points" not in str(err)


def test_metocean_notes_a_25_m_spike_in_the_shipped_hindcast():
    import dataclasses

    from onbottom.metocean.hindcast import read_hindcast
    from onbottom.metocean.run import run_metocean_analysis

    h = read_hindcast(EXAMPLES / "hindcast_synthetic.csv")
    hs = np.array(h.hs)
    hs[1000:1008] = 25.0  # one day (3-hourly) at 25 m
    spiky = dataclasses.replace(h, hs=hs, tp=np.maximum(np.array(h.tp), 18.0))
    notes = run_metocean_analysis(spiky).notes
    assert any(n.startswith("hs: 1 outlier(s)") and "25 m" in n for n in notes), notes
