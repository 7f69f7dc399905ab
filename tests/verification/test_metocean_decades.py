"""NDBC 44007: the 1996–2005 fit against what 2006–2017 observed, and the pooled fit
(docs/validation/ndbc_44007_decades.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pyextremes")
pytest.importorskip("virocon")

from onbottom.metocean import MetoceanOptions, analyse_hindcast, read_hindcast
from onbottom.metocean.hindcast import Hindcast

pytestmark = pytest.mark.verification

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
OPTIONS = MetoceanOptions(sectors=1, contour_points=16)


@pytest.fixture(scope="module")
def records():
    a = read_hindcast(EXAMPLES / "hindcast_ndbc_44007.csv")
    b = read_hindcast(EXAMPLES / "hindcast_ndbc_44007_2006_2017.csv")
    step = np.timedelta64(1, "h")
    gap = np.arange(a.time[-1] + step, b.time[0], step)
    nan = np.full(gap.size, np.nan)
    pooled = Hindcast(
        time=np.concatenate([a.time, gap, b.time]),
        hs=np.concatenate([a.hs, nan, b.hs]),
        tp=np.concatenate([a.tp, nan, b.tp]),
        wave_direction_deg=None,
        current_speed=None,
        current_direction_deg=None,
        source="pooled",
    )
    return a, b, pooled


def test_later_decade_exceeds_the_first_decades_end_point(records):
    a, b, _ = records
    ra, rb = analyse_hindcast(a, OPTIONS), analyse_hindcast(b, OPTIONS)
    assert ra.tail.warnings  # the guard fires on the first decade
    later = np.sort(rb.hs["omni"].storms.peak)[::-1]
    above = later[later > ra.tail.endpoint]
    np.testing.assert_allclose(above, [11.70, 9.64, 8.12, 8.11], atol=0.005)
    assert ra.hs["omni"].value[-1] < 7.5  # the bounded fit's 100-year value
    assert [p for _, p in rb.tail.censored_peaks] == [9.64, 8.12]


def test_pooled_record_and_the_first_decades_alternatives(records):
    a, _, pooled = records
    ra, rp = analyse_hindcast(a, OPTIONS), analyse_hindcast(pooled, OPTIONS)
    v = rp.hs["omni"].value[-1]
    assert v == pytest.approx(11.48, abs=0.02) and rp.hs["omni"].storms.peak.size == 60
    assert len(rp.tail.censored_peaks) == 3
    ex = ra.tail.exponential[:, -1]  # the first decade's exponential interval holds it
    assert ex[1] < v < ex[2]
    assert ra.tail.censored_fit["lower"][-1] < v < ra.tail.censored_fit["upper"][-1]
