"""Stability curves: bisection on L, table form, validity cap, CLI outputs (tiny storms)."""

from __future__ import annotations

import csv
import json
import math

import pytest

from onbottom.cli.main import main
from onbottom.constants import GRAVITY
from onbottom.errors import InputError
from onbottom.results import load_dataset
from onbottom.study.stability_curves import (
    CurveSettings,
    clay_validity_limit,
    curves_table,
    find_weight_parameter,
    point_kinematics,
    stability_curves,
)

FAST = CurveSettings(seeds=2, build_up_hours=0.02, peak_hours=0.1, tolerance=0.1)


def test_point_kinematics_scales():
    k, m, n = 10.0, 0.3, 0.004
    kins = point_kinematics(k, m, n, FAST)
    us = math.sqrt(k * n * GRAVITY * FAST.diameter)
    assert len(kins) == 2 and kins[0].seed == 0 and kins[1].seed == 1
    assert kins[0].current == pytest.approx(m * us)
    assert kins[0].stage_parameters[0]["significant_velocity"] == pytest.approx(us, rel=1e-3)
    tu = kins[0].stage_parameters[0]["mean_period"]
    assert us * tu / FAST.diameter == pytest.approx(k, rel=1e-3)


def test_bisection_brackets_the_target_and_l10_below_lstable():
    a = find_weight_parameter("sand", 10.0, 0.2, 0.003, "L_stable", FAST)
    b = find_weight_parameter("sand", 10.0, 0.2, 0.003, "L_10", FAST)
    assert a["success"] and b["success"]
    for r in (a, b):
        assert r["L_low"] < r["L"] < r["L_high"] <= r["L_low"] * 1.1 + 1e-12
    assert b["L"] < a["L"]
    with pytest.raises(InputError):
        find_weight_parameter("gravel", 10.0, 0.2, 0.003, "L_10", FAST)


def test_clay_validity_limit_by_hand():
    s = FAST
    su = s.clay_gc * s.diameter * s.clay_unit_weight
    lv = clay_validity_limit(10.0, 0.003, s)
    ws = lv * 0.5 * s.water_density * s.diameter * 10.0 * 0.003 * GRAVITY * s.diameter
    assert ws / (s.diameter * su) * s.clay_gc**0.3 == pytest.approx(2.5)


def test_grid_dataset_table_and_cli(tmp_path, capsys):
    ds = stability_curves([5.0], [0.0, 0.4], soils=["sand"], settings=FAST, n_workers=0)
    assert ds["L_stable"].dims == ("soil", "N", "M", "K")
    rows = curves_table(ds)
    assert len(rows) == 2 and rows[1]["L_10/(2+M)^2"] == pytest.approx(rows[1]["L_10"] / 2.4**2)
    assert int(ds.attrs["total_storms"]) > 0
    case = tmp_path / "curves.toml"
    case.write_text(
        "[curves]\nK = [5.0]\nM = [0.2]\nsoils = ['sand']\ncriteria = ['L_10']\nseeds = 1\n"
        "build_up_hours = 0.02\npeak_hours = 0.05\ntolerance = 0.2\n",
        encoding="utf-8",
    )
    assert main(["curves", str(case), "--workers", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["points"][0]["L_10"] > 0 and out["failures"] == []
    assert load_dataset(case.with_suffix(".nc"))["L_10"].attrs["units"] == "1"
    with open(case.with_suffix(".csv"), encoding="utf-8") as fh:
        assert next(csv.DictReader(fh))["soil"] == "sand"
    assert case.with_suffix(".png").stat().st_size > 5_000
