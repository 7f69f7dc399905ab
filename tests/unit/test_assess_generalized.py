"""Unit tests: the generalized level reads the tool's own curve sweeps where they cover the
point (linear interpolation in N, M, K; never extrapolated) and says "not covered" otherwise.

The sweep here is computed by :func:`onbottom.study.stability_curves.stability_curves` itself
(one seed, short storms, a coarse tolerance: a lookup test, not a curve).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from onbottom.assess.generalized import generalized_rows
from onbottom.cases.assess import build_route, parse_route_case
from onbottom.checks.design import run_checks

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document


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


def _gen(s, rows, files, allowable):
    return generalized_rows(rows, files, allowable, seabed_model=s.seabed_model,
                            water_density=s.environment.water_density)  # fmt: skip


def test_covered_points_are_interpolated(sweep):
    path, ds = sweep
    sc, rows = _rows(route_document())
    out = _gen(sc, rows, [str(path)], "0.5D")
    assert len(out) == 2
    interp = RegularGridInterpolator(
        (ds.N.values, ds.M.values, ds.K.values), ds["L_stable"].sel(soil="sand").values
    )
    covered = 0
    for g in out:
        p = g["details"]
        inside = 0.003 <= p["N"] <= 0.01 and 0.0 <= p["M"] <= 2.0 and 5.0 <= p["K"] <= 40.0
        assert g["covered"] == inside, g
        if inside:
            covered += 1
            lreq = float(interp([p["N"], p["M"], p["K"]])[0])
            assert p["L_required"] == pytest.approx(lreq, rel=1e-12)
            assert g["utilisation"] == pytest.approx(lreq / p["L_actual"], rel=1e-12)
            assert g["pass"] == (g["utilisation"] <= 1.0)
        else:
            assert "outside the grid" in g["message"]
    assert covered >= 1  # the test route's main combination lies inside this grid


def test_not_covered_reasons(sweep):
    path, _ = sweep
    sc, rows = _rows(route_document())
    none = _gen(sc, rows, [], "0.5D")
    assert all(not g["covered"] and "no committed" in g["message"] for g in none)
    user = _gen(sc, rows, [str(path)], "user")
    assert all(not g["covered"] and "0.5D and 10D only" in g["message"] for g in user)
    ten = _gen(sc, rows, [str(path)], "10D")  # the sweep has no L_10
    assert all(not g["covered"] and "no sand/L_10" in g["message"] for g in ten)
    doc = route_document()
    doc["route"]["sections"][0]["seabed"] = {"model": "rock", "friction_coefficient": 0.6}
    sc, rows = _rows(doc)
    rock = _gen(sc, rows, [str(path)], "0.5D")
    assert all(not g["covered"] and "no curves" in g["message"] for g in rock)
    assert np.isfinite([g["details"]["K"] for g in rock]).all()


def test_generalized_minimum_weight(sweep):
    from onbottom.assess import assess

    path, _ = sweep
    doc = route_document()
    doc["levels"] = {"generalized": True, "dynamic": False}
    a = assess(build_route(parse_route_case(doc)), n_workers=0, curve_files=[str(path)])
    lv = a.sections[0]["levels"]["generalized"]
    assert lv["covered"] == lv["points"] == 2
    assert lv["success"], lv
    t = lv["value"]
    # at the minimum every combination passes; a little less concrete fails one of them
    sc, _ = _rows(doc)

    def worst(thickness: float) -> float:
        s = sc.pipe.with_layer_thickness("concrete", thickness)
        rows = run_checks(s, sc.seabed, sc.environment, sc.combinations, sc.options)
        gen = _gen(sc, rows, [str(path)], "0.5D")
        return max(g["utilisation"] if g["covered"] else np.inf for g in gen)

    assert worst(t) <= 1.0
    if t > 1e-4 and lv["governing_check"] != "flotation (F109 Eq 3.1)":
        assert worst(t - 1e-4) > 1.0
