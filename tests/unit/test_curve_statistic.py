"""The curve statistic: each seed's own bisection, reported as a fractile and the median;
storms stopped once their verdict is known give exactly the full runs' verdicts and L; the
former mean-of-maxima files are read and labelled (tiny grids, short storms)."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from onbottom.cli.main import main
from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.errors import InputError
from onbottom.hydro.reductions import LoadReductions
from onbottom.results import load_dataset, save_dataset
from onbottom.study import stability_curves as sc
from onbottom.study.stability_curves import (
    CurveSettings,
    curve_statistic,
    curves_table,
    seed_quantile,
    stability_curves,
)

ROOT = Path(__file__).resolve().parents[2]
FAST = CurveSettings(seeds=3, build_up_hours=0.02, peak_hours=0.1, tolerance=0.1)


def test_seed_quantile_is_numpy_type_7_and_handles_seeds_without_crossing():
    x = [3.0, 1.0, 7.0, 2.0, 5.0, 4.0, 9.0, 6.0, 8.0, 10.0]
    for p in (0.5, 0.9, 0.75):
        assert seed_quantile(x, [""] * 10, p) == pytest.approx(np.quantile(x, p), rel=1e-15)
    # 10 seeds, 0.9: between the 9th and 10th smallest (9 + 0.1·(10 − 9))
    assert seed_quantile(x, [""] * 10, 0.9) == pytest.approx(9.1)
    # a seed that never moved ranks lowest: the median and 0.9 fractile do not use it
    cens = ["below"] + [""] * 9
    assert seed_quantile([math.nan, *x[1:]], cens, 0.9) == pytest.approx(
        np.quantile([-1e9, *x[1:]], 0.9)
    )
    # a seed beyond the heaviest L tried is needed by the 0.9 fractile: no value
    assert math.isnan(seed_quantile([*x[:9], math.nan], [""] * 9 + ["above"], 0.9))
    assert seed_quantile([*x[:9], math.nan], [""] * 9 + ["above"], 0.5) == pytest.approx(
        np.quantile([*x[:9], 1e9], 0.5)
    )


def test_settings_reject_an_unknown_statistic_and_a_fractile_out_of_range():
    with pytest.raises(InputError, match="statistic"):
        CurveSettings(statistic="mean")
    with pytest.raises(InputError, match="fractile"):
        CurveSettings(fractile=1.0)
    assert CurveSettings().seeds >= 10 and CurveSettings().fractile == 0.9


def test_early_stopped_verdicts_and_l_equal_full_runs_on_a_curve_sweep():
    """Issue 45 item 1 for the curve bisection: the same sweep with storms stopped at the
    criterion and with storms run on (to the runaway stop) gives identical per-seed L, median
    and fractile, bit for bit; the stopped storms are counted."""
    grid = ([5.0, 10.0], [0.4, 0.8])
    early = stability_curves(*grid, soils=["sand"], settings=FAST, n_workers=0)
    full = stability_curves(
        *grid, soils=["sand"], settings=replace(FAST, early_stop=False), n_workers=0
    )
    for c in ("L_stable", "L_10"):
        for v in ("", "_median", "_per_seed", "_per_seed_low", "_per_seed_high"):
            np.testing.assert_array_equal(early[c + v].values, full[c + v].values, c + v)
        assert np.isfinite(early[c].values).all()
        assert int(early[f"{c}_stopped_early"].sum()) > 0
        np.testing.assert_array_equal(
            early[f"{c}_per_seed_stopped_early"].sum("seed"), early[f"{c}_stopped_early"]
        )
        assert int(full[f"{c}_stopped_early"].sum()) == 0
        # each seed's storm at its L_low reached the criterion and stopped there
        target = sc.CRITERIA[c]
        assert np.all(early[f"{c}_seed_min_low"].values >= target)
        assert np.all(early[f"{c}_seed_max_low"].values < target * 1.06)
        assert np.all(full[f"{c}_seed_max_high"].values == early[f"{c}_seed_max_high"].values)
    assert int(early.attrs["stopped_early"]) > 0 and int(early.attrs["early_stop"]) == 1


@pytest.mark.filterwarnings("ignore::onbottom.errors.OutOfRangeWarning")
def test_a_stopped_storm_has_the_verdict_of_the_unstopped_storm():
    """Per storm: stopping at the criterion gives the verdict of the storm run to its end
    (no runaway stop at all), at L on both sides of a seed's crossing."""
    k, m, n = 10.0, 0.4, 0.003
    kins = sc.point_kinematics(k, m, n, FAST)
    us = math.sqrt(k * n * 9.80665 * FAST.diameter)
    d = FAST.diameter
    red = LoadReductions(permeable_seabed=True)
    seen = set()
    for lv in (2.0, 8.0, 30.0):
        pipe, soil = sc._pipe_and_soil("sand", lv, us, FAST)
        for kin in kins[:2]:
            for target in sc.CRITERIA.values():
                runs = [
                    simulate_storm_section(
                        pipe,
                        soil,
                        kin,
                        force_model=FAST.force_model,
                        reductions=red,
                        settings=StormSolverSettings(
                            dt_max=FAST.time_step,
                            stop_displacement_over_d=stop,
                            record_interval=None,
                        ),
                    )
                    for stop in (target, 1.0e6)
                ]
                verdicts = [r.max_displacement >= target * d for r in runs]
                assert verdicts[0] == verdicts[1], (lv, kin.seed, target)
                seen.add(verdicts[0])
                if not verdicts[0]:  # never stopped: the very same run
                    assert runs[0].max_displacement == runs[1].max_displacement
    assert seen == {True, False}  # both verdicts were exercised


def test_point_statistic_dataset_and_table(tmp_path):
    ds = stability_curves([5.0], [0.4], soils=["sand"], settings=FAST, n_workers=0)
    assert ds["L_stable_per_seed"].dims == ("soil", "N", "M", "K", "seed")
    assert ds["seed"].values.tolist() == [0, 1, 2]
    for c in ("L_stable", "L_10"):
        per = ds[f"{c}_per_seed"].values.ravel()
        assert ds[c].item() == pytest.approx(np.quantile(per, 0.9), rel=1e-12)
        assert ds[f"{c}_median"].item() == pytest.approx(np.median(per), rel=1e-12)
        lo, hi = ds[f"{c}_bracket_low"].item(), ds[f"{c}_bracket_high"].item()
        assert lo <= ds[c].item() <= hi <= lo * (1.0 + FAST.tolerance) * (1 + 1e-12)
        assert ds[c].attrs["statistic"] == "fractile"
    save_dataset(ds, tmp_path / "c.nc")
    back = load_dataset(tmp_path / "c.nc")
    stat = curve_statistic(back)
    assert stat["statistic"] == "fractile" and stat["seeds"] == 3 and stat["fractile"] == 0.9
    assert "0.9 fractile" in stat["label"]
    row = curves_table(back, per_seed=True)[0]
    assert row["statistic"] == "fractile" and row["seeds"] == 3
    assert row["L_stable_per_seed"] == pytest.approx(back["L_stable_per_seed"].values.ravel())
    assert row["L_10_median"] == pytest.approx(back["L_10_median"].item())


def test_the_former_statistic_by_name_and_the_committed_files_are_labelled():
    ds = stability_curves(
        [5.0],
        [0.4],
        soils=["sand"],
        criteria=["L_10"],
        settings=replace(FAST, statistic="mean_of_maxima"),
        n_workers=0,
    )
    assert "seed" not in ds.dims and "L_10_median" not in ds
    assert curve_statistic(ds)["statistic"] == "mean_of_maxima"
    for path in sorted((ROOT / "docs" / "validation" / "stability_curves").glob("*.nc")):
        old = load_dataset(path)
        stat = curve_statistic(old)
        if "statistic" not in old.attrs:  # written before the per-seed statistic
            assert stat["statistic"] == "mean_of_maxima" and "mean of maxima" in stat["label"]
            assert stat["seeds"] == json.loads(old.attrs["parameters"])["seeds"]
        row = curves_table(old, per_seed=True)[0]
        assert row["statistic"] == stat["statistic"]
        if stat["statistic"] == "mean_of_maxima":
            assert math.isnan(row["L_stable_median"]) and row["L_stable_per_seed"] == []


def test_case_file_statistic_and_large_n(tmp_path, capsys):
    """The case file sets the statistic; N up to 0.01 (a shore approach) is accepted; the
    CLI's JSON says the statistic and gives each seed's L."""
    case = tmp_path / "c.toml"
    case.write_text(
        "[curves]\nK = [5.0]\nM = [0.2]\nN = [0.01]\nsoils = ['sand']\ncriteria = ['L_10']\n"
        "seeds = 2\nfractile = 0.75\nbuild_up_hours = 0.02\npeak_hours = 0.05\ntolerance = 0.2\n",
        encoding="utf-8",
    )
    assert main(["curves", str(case), "--workers", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["statistic"] == "fractile" and out["fractile"] == 0.75 and out["seeds"] == 2
    assert any("fewer than 10 seeds" in w for w in out["warnings"])
    p = out["points"][0]
    assert p["N"] == 0.01 and len(p["L_10_per_seed"]) == 2
    assert p["L_10"] == pytest.approx(np.quantile(p["L_10_per_seed"], 0.75))
    ds = load_dataset(case.with_suffix(".nc"))
    assert float(ds.attrs["fractile"]) == 0.75 and ds.attrs["statistic"] == "fractile"


def test_report_section_states_each_files_statistic(tmp_path, monkeypatch):
    """The report's curves section names the statistic and seed count of every committed
    file: a per-seed file beside a file of the former statistic."""
    from onbottom.report.content import SectionContext
    from onbottom.report.sections import stability_curves as section
    from onbottom.report.sections.stability_curves import build

    folder = tmp_path / "stability_curves"
    folder.mkdir(parents=True)
    monkeypatch.setattr(section, "sweep_folder", lambda: folder)
    new = stability_curves([5.0], [0.4], soils=["sand"], settings=FAST, n_workers=0)
    old = new.drop_vars([v for v in new.data_vars if "median" in v or "per_seed" in v])
    old = old.drop_dims("seed")
    for key in ("statistic", "seeds", "fractile", "early_stop", "stopped_early"):
        old.attrs.pop(key, None)
    save_dataset(new, folder / "a_new.nc")
    save_dataset(old, folder / "b_old.nc")
    content = build(SectionContext(name="stability_curves", out_dir=tmp_path, repo_root=tmp_path))
    checks = {c.name: c.value for c in content.checks}
    assert "0.9 fractile (and median) over 3 seeds" in checks["statistic of a_new"]
    assert "mean of maxima over 3 seeds" in checks["statistic of b_old"]
    assert "0.9 fractile" in content.tables[0].caption
    assert "mean of maxima" in content.tables[1].caption
    assert "L_stable_median" in content.tables[0].columns
