"""Verification: return values of a record with missing sea states use the storm rate per
**observed** year (issue 34, the real buoy record has 5.6 % missing hours).

A 20-year synthetic record (the example model) with its years 6–10 blanked (25 % missing):
the omnidirectional return values equal Coles (2001) Eq. 4.13 with the fitted GPD and the rate
λ = storms / observed years, to 1e-6 — not pyextremes' storms / first-to-last span, which would
understate λ by a quarter; and the 10-year value agrees with the complete record's within the
two intervals (the blanked years hold no information, they must not move the estimate far).
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pyextremes")
pytest.importorskip("virocon")

from onbottom.metocean.analysis import MetoceanOptions, analyse_hindcast
from onbottom.metocean.extremes import gpd_return_level
from onbottom.metocean.hindcast import Hindcast
from onbottom.metocean.synthetic import synthetic_hindcast

pytestmark = pytest.mark.verification


def test_return_values_use_the_rate_per_observed_year():
    d = synthetic_hindcast(years=20.0, seed=21)
    n = d["hs"].size
    blank = np.zeros(n, dtype=bool)
    blank[n // 4 : n // 2] = True
    hs = np.where(blank, np.nan, d["hs"])
    tp = np.where(blank, np.nan, d["tp"])
    wd = np.where(blank, np.nan, d["wave_direction_deg"])
    hc = Hindcast(d["time"], hs, tp, wd, None, None, "synthetic, 25 % missing")
    full = Hindcast(d["time"], d["hs"], d["tp"], d["wave_direction_deg"], None, None, "full")
    assert hc.years == pytest.approx(0.75 * full.years, rel=1e-3)
    o = MetoceanOptions(sectors=1, return_periods=(1.0, 10.0, 100.0))
    lv = analyse_hindcast(hc, o).hs["omni"]
    rate = lv.storms.peak.size / hc.years
    expect = gpd_return_level(
        np.array([1.0, 10.0, 100.0]), lv.storms.threshold, lv.scale, lv.shape, rate
    )
    np.testing.assert_allclose(lv.value, expect, rtol=1e-6)
    assert np.all((lv.lower < lv.value) & (lv.value < lv.upper))
    ref = analyse_hindcast(full, o).hs["omni"]
    assert max(lv.lower[1], ref.lower[1]) < min(lv.upper[1], ref.upper[1])  # intervals overlap
