"""Unit tests: the generalized level of ``assess`` is F109's generalized method from F109's
tables (:mod:`onbottom.checks.f109_generalized`); the tool's own curve sweeps are the separate
``dynamic_curves`` level (``[levels] dynamic_curves``: the file given is the one used); the
design floor rules (:func:`onbottom.assess.core._design_floor`).

The sweep here is computed by :func:`onbottom.study.stability_curves.stability_curves` itself
(one seed, short storms, a coarse tolerance: a lookup test, not a curve).
"""

from __future__ import annotations

import copy
import sys
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from onbottom._casefile import CaseFileError
from onbottom.assess.generalized import default_curve_files, dynamic_curve_rows, generalized_rows
from onbottom.cases.assess import build_route, parse_route_case
from onbottom.checks import f109_generalized as f109
from onbottom.checks.design import run_checks

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document
from case_helpers import toml_value


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    from onbottom.hydro.force_model import MorisonLift
    from onbottom.results import save_dataset
    from onbottom.study.stability_curves import CurveSettings, stability_curves

    s = CurveSettings(seeds=1, peak_hours=0.05, build_up_hours=0.01, tolerance=0.3,
                      force_model=MorisonLift())  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = stability_curves(
            [5.0, 40.0], [0.0, 2.0], [0.003, 0.01], soils=["sand"], criteria=["L_stable"],
            settings=s, n_workers=0,
        )  # fmt: skip
    path = tmp_path_factory.mktemp("curves") / "tiny.nc"
    save_dataset(ds, path)
    return path, ds


def _rows(doc):
    s = build_route(parse_route_case(doc)).sections[0]
    rows = run_checks(s.pipe, s.seabed, s.environment, s.combinations, s.options)
    return s, rows


def _kw(s):
    return {"seabed_model": s.seabed_model, "water_density": s.environment.water_density}


def test_generalized_rows_are_f109_tables():
    sc, rows = _rows(route_document())
    for allowable, fn in (("0.5D", "l_stable_sand"), ("10D", "l_10_sand")):
        out = generalized_rows(rows, allowable, **_kw(sc))
        assert len(out) == 2
        for g in out:
            p = g["details"]
            assert g["level"] == "generalized"
            args = (p["K"], p["M"], p["N"]) if fn == "l_stable_sand" else (p["K"], p["M"])
            try:
                want = getattr(f109, fn)(*args)
            except f109.NotCoveredError as exc:
                assert not g["covered"] and g["message"] == exc.reason
                continue
            assert g["covered"]
            assert p["L_required"] == pytest.approx(want, rel=1e-12)
            assert g["utilisation"] == pytest.approx(want / p["L_actual"], rel=1e-12)
            assert g["pass"] == (g["utilisation"] <= 1.0)
            # w_s required = L ½ ρ D U_s²; the L actual of the pipe is its own w_s
            wreq = want * 0.5 * sc.environment.water_density * p["diameter"] * p["U_s"] ** 2
            assert p["required_submerged_weight"] == pytest.approx(wreq, rel=1e-12)


def test_generalized_not_covered_reasons():
    sc, rows = _rows(route_document())
    user = generalized_rows(rows, "user", **_kw(sc))
    assert all(not g["covered"] and "0.5D and 10D only" in g["message"] for g in user)
    for model in ("rock", "clay"):
        doc = route_document()
        doc["route"]["sections"][0]["seabed"] = (
            {"model": "rock", "friction_coefficient": 0.6} if model == "rock"
            else {"model": "clay", "undrained_shear_strength": 5.0e3,
                  "submerged_unit_weight": 6.0e3, "unit_weight": 16.0e3,
                  "friction_coefficient": 0.3}
        )  # fmt: skip
        sc, rows = _rows(doc)
        out = generalized_rows(rows, "0.5D", **_kw(sc))
        assert all(not g["covered"] and model in g["message"] for g in out)
        assert np.isfinite([g["details"]["K"] for g in out]).all()


def test_dynamic_curve_rows_interpolate(sweep):
    path, ds = sweep
    sc, rows = _rows(route_document())
    out = dynamic_curve_rows(rows, [str(path)], "0.5D", **_kw(sc))
    interp = RegularGridInterpolator(
        (ds.N.values, ds.M.values, ds.K.values), ds["L_stable"].sel(soil="sand").values
    )
    covered = 0
    for g in out:
        p = g["details"]
        assert g["level"] == "dynamic_curves" and "F109" not in g["message"]
        inside = 0.003 <= p["N"] <= 0.01 and 0.0 <= p["M"] <= 2.0 and 5.0 <= p["K"] <= 40.0
        assert g["covered"] == inside, g
        if inside:
            covered += 1
            lreq = float(interp([p["N"], p["M"], p["K"]])[0])
            assert p["L_required"] == pytest.approx(lreq, rel=1e-12)
            assert g["utilisation"] == pytest.approx(lreq / p["L_actual"], rel=1e-12)
        else:
            assert "outside the grid" in g["message"]
    assert covered >= 1
    none = dynamic_curve_rows(rows, [], "0.5D", **_kw(sc))
    assert all(not g["covered"] and "no readable curve sweep" in g["message"] for g in none)
    ten = dynamic_curve_rows(rows, [str(path)], "10D", **_kw(sc))  # the sweep has no L_10
    assert all(not g["covered"] and "no sand/L_10" in g["message"] for g in ten)


def test_shipped_sweeps_are_package_data():
    files = default_curve_files()
    assert {Path(f).name for f in files} >= {"wake.nc", "morison.nc"}
    assert all("onbottom" in Path(f).parts and "data" in Path(f).parts for f in files)
    assert not any("docs" in Path(f).parts for f in files)


def test_dynamic_curves_key_uses_the_file_given(sweep, tmp_path):
    from onbottom.cases.assess import load_route

    path, _ = sweep
    doc = route_document()
    (tmp_path / "mine.nc").write_bytes(path.read_bytes())
    text = "[levels]\ndynamic_curves = 'mine.nc'\ngeneralized = true\n"
    body = copy.deepcopy(doc)
    body.pop("levels")
    head = "".join(f"{k} = {toml_value(v)}\n" for k, v in body.items())
    case = tmp_path / "route.toml"
    case.write_text(head + text, encoding="utf-8")
    route = load_route(case)
    assert route.levels.dynamic_curves == (str((tmp_path / "mine.nc").resolve()),)
    # true: the shipped sweeps; false: none
    case.write_text(head + "[levels]\ndynamic_curves = true\n", encoding="utf-8")
    assert load_route(case).levels.dynamic_curves == tuple(default_curve_files())
    # a missing file is a named error on the key, with its line
    case.write_text(head + "[levels]\ndynamic_curves = 'gone.nc'\n",
                    encoding="utf-8")  # fmt: skip
    with pytest.raises(CaseFileError, match=r"levels\.dynamic_curves.*not found") as err:
        load_route(case)
    assert err.value.line is not None
    # the removed key is refused by the strict schema
    case.write_text(head + "[levels]\ngeneralized_curves = 'mine.nc'\n",
                    encoding="utf-8")  # fmt: skip
    with pytest.raises(CaseFileError, match="generalized_curves"):
        load_route(case)


def test_generalized_minimum_and_floor():
    from onbottom.assess import assess

    doc = route_document()
    doc["levels"] = {"generalized": True, "dynamic": False, "absolute": True}
    a = assess(build_route(parse_route_case(doc)), n_workers=0)
    s = a.sections[0]
    lv = s["levels"]["generalized"]
    assert lv["covered"] == lv["points"] == 2 and lv["success"], lv
    t = lv["value"]
    sc, _ = _rows(doc)

    def worst(thickness: float) -> float:
        p = sc.pipe.with_layer_thickness("concrete", thickness)
        rows = run_checks(p, sc.seabed, sc.environment, sc.combinations, sc.options)
        gen = generalized_rows(rows, "0.5D", **_kw(sc))
        return max(g["utilisation"] if g["covered"] else np.inf for g in gen)

    assert worst(t) <= 1.0
    if t > 1e-4 and lv["governing_check"] != "flotation (F109 Eq 3.1)":
        assert worst(t - 1e-4) > 1.0
    # the design is never below the generalized requirement
    assert s["design_value"] >= t - 1e-12
    fl = s["design_floor"]
    assert fl["rule"] in ("at_or_above_generalized", "generalized_floor")
    assert fl["words"]


def _levels(gen=None, dyn=None, cb=None, unbounded=None):
    lv = {}
    if gen is not None:
        lv["generalized"] = {"success": True, "value": gen}
    if dyn is not None:
        lv["dynamic"] = {"success": True, "value": dyn}
        if cb is not None:
            lv["dynamic"]["coulomb_bound"] = cb
        if unbounded is not None:
            lv["dynamic"]["unbounded_value"] = unbounded
    return lv


def test_design_floor_rules():
    from onbottom.assess.core import FLOOR_RULES, _design_floor

    route = build_route(parse_route_case(route_document()))
    sec = route.sections[0]
    rows = [{"covered": True}]
    f = _design_floor(route, sec, _levels(gen=0.05, dyn=0.01), rows, "dynamic", 0.01)
    assert f["rule"] == "generalized_floor" and f["words"] == FLOOR_RULES["generalized_floor"]
    assert 0.0 < f["dynamic_over_generalized_weight"] < 1.0
    f = _design_floor(route, sec, _levels(gen=0.05, dyn=0.06), rows, "generalized", 0.05)
    assert f["rule"] == "at_or_above_generalized" and f["dynamic_over_generalized_weight"] > 1
    opt = replace(route, levels=replace(route.levels, allow_below_generalized="site test data"))
    f = _design_floor(opt, sec, _levels(gen=0.05, dyn=0.01), rows, "dynamic", 0.01)
    assert f["rule"] == "allowed_below_generalized" and "site test data" in f["words"]
    # not covered by the tables: the Coulomb bound (raised / at or above / opted in)
    f = _design_floor(route, sec, _levels(dyn=0.03, cb=0.03, unbounded=0.01), rows, "dynamic",
                      0.03)  # fmt: skip
    assert f["rule"] == "coulomb_floor" and f["coulomb_value"] == 0.03
    f = _design_floor(route, sec, _levels(dyn=0.03, cb=0.02), rows, "dynamic", 0.03)
    assert f["rule"] == "at_or_above_coulomb"
    opt = replace(route, levels=replace(route.levels, allow_below_coulomb="monitored line"))
    f = _design_floor(opt, sec, _levels(dyn=0.01, cb=0.02), rows, "dynamic", 0.01)
    assert f["rule"] == "allowed_below_coulomb" and "monitored line" in f["words"]
    f = _design_floor(route, sec, _levels(dyn=0.01), rows, "dynamic", 0.01)
    assert f["rule"] == "not_covered"
    f = _design_floor(route, sec, _levels(dyn=0.01), [], "dynamic", 0.01)
    assert f["rule"] == "not_checked"


def test_design_floor_holds_with_the_generalized_level_off():
    """[levels] generalized = false is no unnamed way below the standard: F109's requirement,
    computed for the floor alone, still raises a lighter dynamic design."""
    from onbottom.assess.core import _design_floor

    route = build_route(parse_route_case(route_document()))
    sec = route.sections[0]
    levels = _levels(dyn=0.01)
    requirement = {"success": True, "value": 0.05}
    f = _design_floor(route, sec, levels, [{"covered": True}], "dynamic", 0.01, requirement)
    assert f["rule"] == "generalized_floor" and f["generalized_value"] == 0.05
    assert 0.0 < f["dynamic_over_generalized_weight"] < 1.0


def test_coulomb_trial_swaps_the_soil_only():
    from onbottom.assess.core import _coulomb_trial
    from onbottom.soil.coulomb import CoulombFriction

    doc = route_document()
    doc["levels"] = {"generalized": True, "dynamic": True}
    sec = build_route(parse_route_case(doc)).sections[0]
    a = sec.trial_storm(0, 0.03)
    b = _coulomb_trial(sec.trial_storm)(0, 0.03)
    assert isinstance(b.soil, CoulombFriction) and not isinstance(a.soil, CoulombFriction)
    assert b.soil.friction_coefficient == sec.seabed.friction_coefficient
    assert b.pipe == a.pipe and b.storm == a.storm and b.current == a.current
