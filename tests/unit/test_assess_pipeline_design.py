"""The pipeline FE in the design search of ``onbottom assess`` (assess/pipeline.py, core.py).

The FE storm of a failing trial stops once |y| passes the allowable: its verdict must be the
full run's. The governing section's design, summary row and exit condition follow the FE."""

from __future__ import annotations

from dataclasses import replace

import pytest

from onbottom.assess.core import _apply_pipeline
from onbottom.assess.pipeline import pipeline_trial
from onbottom.cases.assess import example_path, load_route


@pytest.fixture(scope="module")
def route():
    r = load_route(example_path(), seeds=1)
    # a 1-hour window of the deep end's storm on a short line keeps the runs to seconds
    return replace(r, pipeline=replace(r.pipeline, length=100.0, element_length=10.0,
                                       duration=3600.0))  # fmt: skip


GOV = {"section": "deep end", "index": 2, "combination": "100-yr wave + 10-yr current",
       "seed": 1, "variable": "concrete_thickness"}  # fmt: skip


@pytest.mark.parametrize("value", [0.0, 0.008, 0.03])
def test_stop_at_allowable_gives_the_full_runs_verdict(route, value):
    full, _ = pipeline_trial(route, GOV, value)
    stopped, _ = pipeline_trial(route, GOV, value, stop_at_allowable=True)
    assert stopped["pass"] == full["pass"]
    assert stopped["max_displacement_m"] <= full["max_displacement_m"] * (1 + 1e-9)
    if full["pass"]:  # a passing run never reaches the stop: the same run
        assert stopped["max_displacement_m"] == pytest.approx(full["max_displacement_m"])
    else:
        assert stopped["max_displacement_m"] > stopped["allowable_m"]


def _section(index, design, level="dynamic"):
    lv = {level: {"success": True, "value": design}}
    return {"index": index, "name": f"s{index}", "design_value": design,
            "governing_level": level, "levels": lv}  # fmt: skip


def test_a_raised_design_governs_the_section(route):
    pipe = {"index": 1, "pass": True, "raised": True, "design_value": 0.01,
            "at_section_design": {"max_displacement_m": 0.19, "max_displacement_over_D": 0.76},
            "search": {"message": "ascent"}}  # fmt: skip
    out = _apply_pipeline(route, [_section(0, 0.006), _section(1, 0.008)], pipe)
    assert out[0]["design_value"] == 0.006 and "pipeline_fe" not in out[0]["levels"]
    assert out[1]["design_value"] == 0.01
    assert out[1]["governing_level"] == "pipeline_fe"
    assert out[1]["levels"]["pipeline_fe"]["value"] == 0.01
    assert "0.76 D" in out[1]["levels"]["pipeline_fe"]["message"]


def test_no_design_passing_the_fe_leaves_the_section_without_design(route):
    pipe = {"index": 1, "pass": False, "raised": False, "design_value": None,
            "search": {"message": "the upper bound 0.2 fails"}}  # fmt: skip
    out = _apply_pipeline(route, [_section(0, 0.006), _section(1, 0.008)], pipe)
    assert out[1]["design_value"] is None and out[1]["governing_level"] is None
    assert "upper bound 0.2 fails" in out[1]["no_design_reason"]
    assert out[1]["levels"]["pipeline_fe"]["success"] is False


def test_the_fe_checks_every_sections_design_in_its_task():
    """``[pipeline] sections = "every"``, ``mesh = "rule"``: each section's result carries its
    own FE check (on its worst storm, at its design, mesh by the stated rule) and its
    ``pipeline_fe`` level; the route's ``pipeline`` is the governing section's check."""
    import sys
    from pathlib import Path

    from onbottom.assess import assess
    from onbottom.assess.pipeline import MESH_RULE, section_storm
    from onbottom.cases.assess import build_route, parse_route_case

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from assess_cases import route_document

    doc = route_document(sections=1, seeds=1, peak_hours=0.05)
    doc["levels"]["pipeline_fe"] = True
    doc["pipeline"] = {"sections": "every", "mesh": "rule", "end_conditions": "pinned"}
    built = build_route(parse_route_case(doc))
    a = assess(built, n_workers=0)
    for s in a.sections:
        p = s["pipeline_fe"]
        gov = section_storm(built, s | {"design_value": p["section_design"]})
        assert (p["section"], p["combination"], p["seed"]) == (
            s["name"], gov["combination"], gov["seed"])  # fmt: skip
        assert p["mesh"]["rule"] == MESH_RULE
        assert p["length_m"] == pytest.approx(p["mesh"]["length"])
        assert p["n_nodes"] == p["mesh"]["n_elements"] + 1
        assert "pipeline_fe" in s["levels"]
        if p["pass"] and not p["raised"]:
            assert s["design_value"] == p["section_design"]
    heaviest = max(a.sections, key=lambda s: s["design_value"])
    assert a.pipeline["section"] == heaviest["name"]


@pytest.fixture(scope="module")
def every(tmp_path_factory):
    """A two-section route with ``[pipeline] sections = "every"``, run into an output folder
    (in this process), its outputs written: (route, assessment, folder, files written)."""
    import sys
    from pathlib import Path

    from onbottom.assess import assess
    from onbottom.assess.output import write_outputs
    from onbottom.cases.assess import build_route, parse_route_case

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from assess_cases import route_document

    doc = route_document(sections=2, seeds=1, peak_hours=0.05)
    doc["levels"]["pipeline_fe"] = True
    doc["pipeline"] = {"sections": "every", "mesh": "rule", "end_conditions": "pinned"}
    built = build_route(parse_route_case(doc))
    out = tmp_path_factory.mktemp("every")
    a = assess(built, out=out, n_workers=0)
    files = write_outputs(a, out, pdf=False)["files"]
    return built, a, out, files


def test_every_section_writes_its_fe_results(every):
    """One NetCDF per section checked (``pipeline/NN-<section>.nc``), complete, holding the
    verdict the route reports for that section (max |y| = the envelope's maximum) and the
    provenance of the other results; named in results.json and the files written."""
    import json

    import numpy as np

    from onbottom.assess.core import pipeline_file
    from onbottom.results import load_dataset

    route, a, out, files = every
    nc = sorted((out / "pipeline").glob("*.nc"))
    assert [f.name for f in nc] == ["00-section-0.nc", "01-section-1.nc"]
    saved = json.loads((out / "results.json").read_text(encoding="utf-8"))
    for s, js in zip(a.sections, saved["sections"], strict=True):
        p = s["pipeline_fe"]
        f = pipeline_file(out, s["index"], s["name"])
        assert p["netcdf"] == js["pipeline_fe"]["netcdf"] == str(f) and str(f) in files
        ds = load_dataset(f)
        assert ds.attrs["run_status"] == "complete"
        assert float(ds["max_displacement"]) == p["max_displacement_m"]
        assert float(ds["max_abs_y"].max()) == p["max_displacement_m"]
        assert bool(ds["passed"]) == p["pass"]
        assert float(ds["allowable"]) == p["allowable_m"]
        x = np.nan if p["design_value"] is None else p["design_value"]
        assert float(ds["design_value"]) == pytest.approx(x, nan_ok=True)
        assert np.array_equal(ds["x"].values, p["envelopes"]["x"])
        assert ds.sizes["node"] == p["n_nodes"]
        attrs = ds.attrs
        assert attrs["model"] == "onbottom.assess.pipeline_fe"
        assert attrs["seed"] == p["seed"] and attrs["assess_section"] == s["name"]
        assert attrs["case_identity"] == route.identity and route.identity
        assert attrs["run_identity"] == s["identity"] and s["identity"]
        assert attrs["onbottom_version"] and attrs["onbottom_content_hash"]
        params = json.loads(attrs["parameters"])
        assert params["n_nodes"] == p["n_nodes"] and params["sections"] == "every"
        assert ds["max_displacement"].attrs["units"] == "m"
    assert a.pipeline["netcdf"] in {s["pipeline_fe"]["netcdf"] for s in a.sections}
    assert not list(out.glob("pipeline.nc")) and not list(out.rglob("*.tmp"))


def test_the_report_names_each_sections_fe_results(every):
    _route, a, out, _files = every
    page = (out / "report.html").read_text(encoding="utf-8")
    for s in a.sections:
        assert f"Pipeline FE of {s['name']}" in page
        assert f"pipeline/{s['index']:02d}-section-{s['index']}.nc" in page
    checked = sum(bool(s["pipeline_fe"]["pass"]) for s in a.sections)
    assert f"{checked} of 2 pass" in page
    assert (out / "tables" / "assess_s0-pipeline.csv").is_file()


def test_a_section_whose_fe_results_are_gone_is_run_again(every):
    """Resume: a saved section is reused with its FE results; without them it is run again,
    and the reason names the file."""
    from onbottom.assess import assess

    route, a, out, _files = every
    again = assess(route, out=out, n_workers=0)
    assert again.reused == ["section 0", "section 1"]
    gone = out / "pipeline" / "01-section-1.nc"
    gone.unlink()
    third = assess(route, out=out, n_workers=0)
    assert third.reused == ["section 0"]
    assert third.recomputed[0][0] == "section 1"
    assert "pipeline/01-section-1.nc" in third.recomputed[0][1]
    assert gone.is_file()
    assert (
        third.sections[1]["pipeline_fe"]["max_displacement_m"]
        == (a.sections[1]["pipeline_fe"]["max_displacement_m"])
    )


def test_a_governing_run_whose_netcdf_is_gone_is_run_again(tmp_path):
    """Resume in the governing-section mode: the saved FE run is reused while its
    ``pipeline.nc`` is there and complete; without it the FE runs again and writes it."""
    import sys
    from pathlib import Path

    from onbottom.assess import assess
    from onbottom.cases.assess import build_route, parse_route_case

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from assess_cases import route_document

    doc = route_document(sections=1, seeds=1, peak_hours=0.05)
    doc["levels"]["pipeline_fe"] = True
    doc["pipeline"] = {"mesh": "rule", "end_conditions": "pinned"}
    built = build_route(parse_route_case(doc))
    first = assess(built, out=tmp_path, n_workers=0)
    nc = tmp_path / "pipeline.nc"
    assert nc.is_file() and not first.pipeline.get("reused")
    assert assess(built, out=tmp_path, n_workers=0).pipeline.get("reused") is True
    nc.unlink()
    third = assess(built, out=tmp_path, n_workers=0)
    assert not third.pipeline.get("reused")
    assert nc.is_file()
    assert third.pipeline["max_displacement_m"] == first.pipeline["max_displacement_m"]
