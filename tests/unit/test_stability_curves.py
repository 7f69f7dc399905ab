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


def test_points_outside_the_soil_model_are_marked(tmp_path, monkeypatch):
    """A storm that buries the pipe (status −3) counts with its displacement and marks its
    point in the NetCDF, the CSV rows, the figure and the report (issue 30 item 5)."""
    import types

    import matplotlib.pyplot as plt

    from onbottom.dynamics.section import STATUS_OUTSIDE_VALIDITY
    from onbottom.plotting.storm import plot_stability_curves
    from onbottom.report.content import SectionContext
    from onbottom.report.sections.stability_curves import build
    from onbottom.results import save_dataset
    from onbottom.study import stability_curves as sc

    def fake(pipe, soil, kin, **kw):
        us = kin.stage_parameters[0]["significant_velocity"]
        lv = pipe.submerged_weight / (0.5 * FAST.water_density * pipe.outer_diameter * us * us)
        buried = kin.current != 0.0  # with a current (M > 0) every storm buries the pipe
        return types.SimpleNamespace(
            status=STATUS_OUTSIDE_VALIDITY if buried else 1,
            success=not buried,
            message="outside the model's validity" if buried else "end",
            max_displacement=20.0 / lv * pipe.outer_diameter,  # L_stable = 40, L_10 = 2
        )

    monkeypatch.setattr(sc, "simulate_storm_section", fake)
    ds = stability_curves([5.0], [0.0, 4.0], soils=["sand"], settings=FAST, n_workers=0)
    for crit, lv in (("L_stable", 40.0), ("L_10", 2.0)):
        assert ds[crit].values.ravel() == pytest.approx([lv, lv], rel=0.1)
        assert ds[f"{crit}_out_of_range"].values.ravel().tolist() == [0, 1]
    assert ds["out_of_range"].values.ravel().tolist() == [0, 1]
    rows = curves_table(ds)
    assert [r["L_stable_out_of_range"] for r in rows] == [0, 1]
    assert [r["L_10_out_of_range"] for r in rows] == [0, 1]
    fig = plot_stability_curves(ds)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert "outside soil model range" in labels
    open_marker = next(
        ln for ln in fig.axes[0].get_lines() if ln.get_label() == "outside soil model range"
    )
    assert open_marker.get_markerfacecolor() == "white"
    assert len(open_marker.get_xdata()) == 1  # only the M = 4 point
    plt.close(fig)
    folder = tmp_path / "stability_curves"  # stands in for the shipped package data
    folder.mkdir(parents=True)
    import onbottom.report.sections.stability_curves as section

    monkeypatch.setattr(section, "sweep_folder", lambda: folder)
    save_dataset(ds, folder / "fake.nc")
    back = load_dataset(folder / "fake.nc")
    assert back["L_10_out_of_range"].values.ravel().tolist() == [0, 1]
    content = build(SectionContext(name="stability_curves", out_dir=tmp_path, repo_root=tmp_path))
    table = content.tables[0]
    assert "L_stable_out_of_range" in table.columns
    check = next(c for c in content.checks if "outside" in c.name)
    assert check.value == 1
