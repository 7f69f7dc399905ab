"""The validation page dynamic curves vs F109's generalized method: its generator on a tiny
synthetic sweep with hand-made F109 functions (ratios, "not covered" by exception or result,
the M trend), and the page's tables recomputed from the committed files."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from onbottom.report.curves_vs_f109 import (
    NOT_COVERED,
    F109Functions,
    committed_sweeps,
    current_block,
    page_block,
    ratio_rows,
    render_sweep,
)

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "validation" / "dynamic_curves_vs_f109.md"


def _sweep(statistic: str | None = "fractile") -> xr.Dataset:
    """soil sand/clay × N 0.003 × M 0, 1, 4 × K 10, 20; L = 10 (1 + M)(1 + soil)/K·10."""
    soils, ms, ks = ["sand", "clay"], [0.0, 1.0, 4.0], [10.0, 20.0]
    shape = (2, 1, 3, 2)
    base = np.empty(shape)
    for a in range(2):
        for i, m in enumerate(ms):
            for j, k in enumerate(ks):
                base[a, 0, i, j] = 10.0 * (1.0 + m) * (1.0 + a) * 10.0 / k
    dims = ("soil", "N", "M", "K")
    ds = xr.Dataset(
        {"L_stable": (dims, base), "L_10": (dims, base / 2.0)},
        coords={"soil": soils, "N": [0.003], "M": ms, "K": ks},
        attrs={"parameters": '{"clay_gc": 0.5, "seeds": 10}'},
    )
    if statistic:
        ds.attrs.update(statistic=statistic, seeds=10, fractile=0.9)
    ds["L_10"][0, 0, 0, 1] = math.nan  # no L of ours at sand, M = 0, K = 20
    return ds


def _functions(calls: list | None = None) -> F109Functions:
    def l_stable_sand(k, m, n):
        if m > 2.0:
            raise ValueError(f"M = {m} is outside F109's table")
        return 5.0 * (2.0 + m) ** 2 / k * (1.0 if m != 1.0 else 2.0)  # a peak at M = 1

    def l_10_sand(k, m):
        return None if k > 15.0 else 2.0 * (2.0 + m) ** 2 / k

    def l_stable_clay(k, m, n, gc):
        if calls is not None:
            calls.append(gc)
        return math.nan if m == 4.0 else 20.0 * gc

    def l_10_clay(k, m, n, gc):
        if m == 4.0:
            raise LookupError("no row")
        return 10.0 * gc

    return F109Functions(l_stable_sand, l_10_sand, l_stable_clay, l_10_clay)


def test_ratios_by_hand_and_not_covered_by_exception_or_result():
    calls: list[float] = []
    rows = ratio_rows(_sweep(), _functions(calls))
    idx = {(r["soil"], r["criterion"], r["M"], r["K"]): r for r in rows}
    assert len(rows) == 2 * 2 * 3 * 2
    r = idx[("sand", "L_stable", 0.0, 10.0)]  # ours 10, F109 5·4/10 = 2
    assert r["ours"] == pytest.approx(10.0) and r["f109"] == pytest.approx(2.0)
    assert r["ratio"] == pytest.approx(5.0)
    r = idx[("sand", "L_stable", 1.0, 20.0)]  # ours 10·2·0.5 = 10, F109 5·9/20·2 = 4.5
    assert r["ratio"] == pytest.approx(10.0 / 4.5)
    assert idx[("sand", "L_stable", 4.0, 10.0)]["f109"] is None  # ValueError
    assert "outside F109" in idx[("sand", "L_stable", 4.0, 10.0)]["note"]
    assert idx[("sand", "L_10", 1.0, 20.0)]["f109"] is None  # None returned
    assert idx[("sand", "L_10", 0.0, 20.0)]["ratio"] is None  # our L is NaN
    assert idx[("clay", "L_stable", 4.0, 10.0)]["f109"] is None  # NaN returned
    assert idx[("clay", "L_10", 4.0, 10.0)]["f109"] is None  # LookupError
    r = idx[("clay", "L_10", 0.0, 10.0)]  # ours 10·1·2/2 = 10, F109 10·0.5 = 5
    assert r["ratio"] == pytest.approx(2.0)
    assert set(calls) == {0.5}  # the sweep's own G_c


def test_other_errors_of_the_f109_functions_are_not_swallowed():
    f = _functions()

    def broken(k, m, n):
        raise RuntimeError("a bug, not an uncovered point")

    with pytest.raises(RuntimeError, match="a bug"):
        ratio_rows(_sweep(), F109Functions(broken, f.l_10_sand, f.l_stable_clay, f.l_10_clay))


def test_rendered_tables_and_m_trend():
    text = render_sweep("synthetic", _sweep(), _functions())
    assert "0.9 fractile" in text and "10 seeds" in text
    lines = text.splitlines()
    start = lines.index("**sand, L_stable: ratio ours / F109**")
    assert lines[start + 2] == "| N | K | M = 0 | M = 1 | M = 4 |"
    assert lines[start + 4] == f"| 0.003 | 10 | 5.00 | {20 / 9:.2f} | {NOT_COVERED} |"
    by_m = lines[lines.index("| | M = 0 | M = 1 | M = 4 |".replace("| |", "|  |")) :]
    sand = next(ln for ln in by_m if ln.startswith("| sand, L_stable |"))
    # M = 0: ratio 5 at K = 10 (10/2) and at K = 20 (5/1): geometric mean 5
    assert sand.split(" | ")[1] == "5.00 [5.00–5.00]"
    trend = next(ln for ln in lines if ln.startswith("| sand, L_stable, N = 0.003 |"))
    # ours: L/(2+M)² = 2.5, 2.22, 1.39 (K 10): peak at M = 0; F109 not covered at M = 4
    assert trend == f"| sand, L_stable, N = 0.003 | 0 / {NOT_COVERED} | 0 / {NOT_COVERED} |"
    clay = next(ln for ln in lines if ln.startswith("| clay, L_stable, N = 0.003 |"))
    assert clay.split(" | ")[1].startswith("0 / ")


def test_a_file_of_the_former_statistic_is_labelled():
    text = render_sweep("old", _sweep(statistic=None), _functions())
    assert "mean of maxima over 10 seeds" in text


def test_the_page_tables_are_those_of_the_committed_files():
    """The generated block of the page equals the one recomputed now from the committed
    sweeps and onbottom.checks.f109_generalized (or says that module is missing)."""
    text = PAGE.read_text(encoding="utf-8")
    want = page_block(ROOT)
    assert current_block(text) == want, (
        "the page is not current: run `PYTHONPATH=src python tools/curves_vs_f109.py`"
    )
    for phrase in ("No model parameter is fitted", "C*_Y and C*_Z", "candidate causes"):
        assert phrase in text


def test_with_f109s_tables_the_committed_sand_sweeps_are_compared():
    g = pytest.importorskip("onbottom.checks.f109_generalized")
    from onbottom.results import load_dataset

    f = F109Functions(g.l_stable_sand, g.l_10_sand, g.l_stable_clay, g.l_10_clay)
    files = committed_sweeps(ROOT)
    assert files
    rows = ratio_rows(load_dataset(files[0]), f)
    covered = [r for r in rows if r["soil"] == "sand" and r["ratio"] is not None]
    assert covered, "F109's generalized tables cover none of the committed sand points"
    for r in covered:
        assert r["ratio"] == pytest.approx(r["ours"] / r["f109"])
