"""Unit tests: the route case file of ``onbottom assess`` (strict schema, named errors)."""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import pytest

from onbottom._casefile import CaseFileError
from onbottom.cases.assess import example_path, load_route_case, parse_route_case

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("path", [example_path(), ROOT / "examples" / "assess_route.toml"])
def test_example_routes_load(path):
    case = load_route_case(path)
    assert len(case.route.sections) == 3
    assert case.solve_for == "concrete_thickness"
    kps = [(s.kp_start, s.kp_end) for s in case.route.sections]
    assert kps == sorted(kps) and kps[0][0] == 0.0
    # shared metocean: the offshore sections read [metocean.open_sea]
    assert case.section_metocean(1) == case.section_metocean(2)


def test_section_documents_are_the_single_section_cases():
    case = parse_route_case(route_document())
    st = case.stability_document(0)
    assert st["environment"]["water_depth"] == 30.0
    assert st["design"]["solve_for"] == "concrete_thickness"
    sd = case.storm_document(0, "installation")
    assert sd["pipe"]["condition"] == "installation"  # the combination's condition
    assert sd["waves"]["hs"] == 3.0 and sd["waves"]["tp"] == 9.0
    assert sd["run"]["seeds"] == 2


def test_kp_in_metres_or_kilometres():
    doc = route_document()
    s = doc["route"]["sections"][0]
    del s["kp_start_km"], s["kp_end_km"]
    s["kp_start_m"], s["kp_end_m"] = 2000.0, 10000.0
    assert parse_route_case(doc).route.sections[0].kp_end == 10000.0


def _bad(mutate, field_part: str):
    doc = route_document(sections=2)
    mutate(doc)
    with pytest.raises(CaseFileError) as err:
        parse_route_case(doc)
    assert field_part in str(err.value), str(err.value)
    return err.value


def test_named_errors_before_any_work():
    secs = lambda d: d["route"]["sections"]  # noqa: E731
    _bad(lambda d: secs(d)[1].update(name="section 0"), "must be unique")
    _bad(lambda d: secs(d)[1].update(kp_start_km=5.0), "overlaps")
    _bad(lambda d: secs(d)[0].update(kp_end_km=1.0), "KP end")
    _bad(lambda d: secs(d)[0].update(kp_start_m=1.0), "not both")
    _bad(lambda d: secs(d)[0].update(metocean="nowhere", waves=None), "metocean")
    _bad(lambda d: d["levels"].update(pipeline_fe=True, dynamic=False), "levels.pipeline_fe")
    _bad(lambda d: d.update(pipeline={"length": 50.0, "element_length": 30.0}), "half the")
    _bad(lambda d: d["dynamic"].update(allowable="user"), "allowable_displacement_m")
    _bad(lambda d: secs(d)[0].update(colour="red"), "colour")
    # physical consistency of a section (inputs/consistency.py via the stability loader):
    # a sea state higher than 0.78 x the depth names the section and the key
    e = _bad(lambda d: secs(d)[1].update(water_depth=4.0), "route.sections[1]")
    assert "section 1" in str(e)
    # the design layer must exist in the build-up
    _bad(lambda d: d["design"].update(layer="ballast"), "design.layer")


def test_metocean_reference_and_own_tables_exclusive():
    doc = route_document()
    doc["metocean"] = {"open": {"waves": {"hs": 4.0, "tp": 10.0}}}
    doc["route"]["sections"][0]["metocean"] = "open"
    with pytest.raises(CaseFileError, match="not both"):
        parse_route_case(doc)
    s = doc["route"]["sections"][0]
    for k in ("waves", "current", "combinations"):
        del s[k]
    case = parse_route_case(copy.deepcopy(doc))
    assert case.stability_document(0)["waves"]["hs"] == 4.0


def test_error_names_the_route_key():
    doc = route_document()
    doc["metocean"] = {"open": {"waves": {"hs": 4.0, "tp": 10.0}}}
    s = doc["route"]["sections"][0]
    for k in ("waves", "current", "combinations"):
        del s[k]
    s["metocean"] = "open"
    s["water_depth"] = 4.0  # H_s = 4 m breaks in 4 m of water
    with pytest.raises(CaseFileError) as err:
        parse_route_case(doc)
    assert err.value.field == "metocean.open.waves.hs"
    assert "route.sections[0] ('section 0')" in str(err.value)
    doc = route_document()
    doc["route"]["sections"][0]["seabed"]["initial_penetration"] = 0.9  # deeper than D
    with pytest.raises(CaseFileError) as err:
        parse_route_case(doc)
    assert err.value.field == "route.sections[0].seabed.initial_penetration"
