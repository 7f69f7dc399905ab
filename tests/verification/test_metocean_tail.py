"""The tail guard, the exponential alternative and storms censored by data gaps
(:mod:`onbottom.metocean.tail`) on the shipped NDBC 44007 record (1996–2005) and by hand.

* NDBC: ξ̂ = −0.39 from 28 storms: both warnings (short tail from a short record; the
  end-point 7.75 m within one σ̂ of the record's 7.10 m). The largest storm (7.10 m, followed by
  a 228-h gap) is flagged as censored, and the censored fit moves ξ̂ upward (−0.39 → −0.22) and
  the 100-year value up (7.44 → 8.08 m).
* The censored likelihood by hand: with every excess censored at ξ = 0 the log-likelihood is
  −Σy/σ; the exponential fit's σ̂ is Σy / (exact excesses).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pyextremes")
pytest.importorskip("virocon")

from onbottom.metocean import MetoceanOptions, analyse_hindcast, read_hindcast
from onbottom.metocean.extremes import _gpd_loglik
from onbottom.metocean.storms import Storms
from onbottom.metocean.tail import censored_storms

pytestmark = pytest.mark.verification

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def ndbc():
    hc = read_hindcast(EXAMPLES / "hindcast_ndbc_44007.csv")
    return hc, analyse_hindcast(hc, MetoceanOptions(sectors=1, contour_points=16))


def test_ndbc_short_tail_is_flagged_with_the_exponential_beside_it(ndbc):
    _, r = ndbc
    t = r.tail
    assert t.storms == 28 and t.shape == pytest.approx(-0.3925, abs=1e-3)
    assert len(t.warnings) == 2
    assert "short tail" in t.warnings[0] and "end-point" in t.warnings[1]
    assert t.endpoint == pytest.approx(7.745, abs=1e-3)
    # ξ = 0: σ̂ = Σ excess / n exact (the censored storm's excess in the sum)
    y = r.hs["omni"].storms.peak - t.threshold
    assert t.exponential_scale == pytest.approx(y.sum() / (y.size - 1), rel=1e-12)
    v, lo, hi = t.exponential[:, -1]  # 100 years
    assert lo < v < hi and v > r.hs["omni"].value[-1] + 1.0  # well above the GPD's 7.44 m


def test_ndbc_largest_storm_is_censored_and_censoring_raises_the_tail(ndbc):
    hc, r = ndbc
    t = r.tail
    assert t.censored_peaks == [("2003-12-07T05", 7.1)]
    k = int(np.argmax(r.hs["omni"].storms.peak))
    assert t.censored[k] and t.censored.sum() == 1
    after = hc.time[r.hs["omni"].storms.index[k] :]
    c = t.censored_fit
    assert c["shape"] > t.shape + 0.1  # −0.39 → −0.22
    assert c["shape"] == pytest.approx(-0.218, abs=0.005)
    assert c["value"][-1] == pytest.approx(8.08, abs=0.02)
    assert c["lower"][-1] < c["value"][-1] < c["upper"][-1]
    assert after.size > 0


def test_censored_likelihood_by_hand():
    y = np.array([0.5, 1.0, 2.0])
    cens = np.array([False, False, True])
    sg = 1.3
    exact = -2 * np.log(sg) - y.sum() / sg  # ξ = 0: density for two, survival for one
    assert float(_gpd_loglik(y, np.array([sg]), np.array([0.0]), cens)[0]) == pytest.approx(exact)
    xi = 0.2
    t = 1 + xi * y / sg
    want = -2 * np.log(sg) - (1 + 1 / xi) * np.log(t[:2]).sum() - np.log(t[2]) / xi
    assert float(_gpd_loglik(y, np.array([sg]), np.array([xi]), cens)[0]) == pytest.approx(want)


def test_censored_storms_by_hand():
    # hourly; a storm at 3..5 followed by 12 missing hours; another at 30..31 then data
    v = np.zeros(60)
    v[3:6] = [5.0, 6.0, 5.5]
    v[30:32] = [5.2, 5.1]
    obs = np.ones(60, dtype=bool)
    obs[6:18] = False
    st = Storms(np.array([4, 30]), np.array([6.0, 5.2]), 4.0, 6.0, 1.0)
    assert list(censored_storms(v, obs, 1.0, st)) == [True, False]
    obs[6:18], obs[6:17] = True, False  # an 11-h gap does not censor
    assert list(censored_storms(v, obs, 1.0, st)) == [False, False]


def test_synthetic_record_has_no_censored_storm():
    hc = read_hindcast(EXAMPLES / "hindcast_synthetic.csv")
    r = analyse_hindcast(hc, MetoceanOptions(sectors=1, contour_points=16))
    assert r.tail.censored_peaks == [] and r.tail.censored_fit == {}


def test_ndbc_contour_check_shows_why_the_contour_exceeds_the_pot_value(ndbc):
    from onbottom.metocean.joint import marginal_tail_check

    hc, r = ndbc
    pot = float(r.hs["omni"].value[-1])
    c = marginal_tail_check(r.joint, hc.hs[hc.observed], 100.0, hc.step_hours, pot)
    assert c["ratio"] == pytest.approx(10.89 / 7.44, rel=0.01)
    # the moment fit follows the data to 1e-4 per sea state (within a factor 2) ...
    for lv in c["levels"][:3]:
        assert 0.5 < lv["fitted"] / lv["empirical"] < 2.0
    # ... the maximum-likelihood Weibull does not (the bulk governs it), and its contour is low
    assert c["levels"][1]["mle"] < 0.01 * c["levels"][1]["empirical"]
    assert c["mle_contour_max_hs"] < pot < c["contour_max_hs"]


def test_tp_given_hs_checked_on_the_storm_peaks(ndbc):
    from onbottom.metocean.joint import tp_at_peaks_check

    hc, r = ndbc
    idx = r.hs["omni"].storms.index
    c = tp_at_peaks_check(r.joint, hc.hs[idx], hc.tp[idx])
    # NDBC: the model's T_p is too long at the peaks by 0.79 SD; KS rejects it
    assert c["n"] == 28 and c["mean_z"] == pytest.approx(-0.79, abs=0.01)
    assert c["ks_p"] < 0.01
    # by construction: peaks drawn from the model itself pass
    rng = np.random.default_rng(3)
    h = rng.uniform(4.0, 7.0, 400)
    t = r.joint.tp_quantile(h, rng.uniform(size=400))
    c0 = tp_at_peaks_check(r.joint, h, t)
    assert abs(c0["mean_z"]) < 0.2 and c0["ks_p"] > 0.001
