"""Verification of the metocean statistics against known answers.

* EVA coverage: storm peaks drawn from a known GPD at a known rate (λ = 4 storms a year, 30
  years, exceedances over u = 3 m with ξ = −0.1, σ = 0.8 m) are laid into a 3-hourly series
  and analysed as a hindcast would be (declustering, pyextremes MLE, profile-likelihood
  intervals). The true R-year level is u + σ/ξ((λR)^ξ − 1) (Coles 2001, Eq. 4.13). Over 50
  independent draws the 95 % intervals must contain it at least as often as an exact 95 %
  interval would with probability 0.995 (binomial: at least 43 of 50), and the mean estimate
  must lie within 3 standard errors of the truth. (pyextremes' percentile bootstrap, 100
  samples, covered the truth in 28, 23 and 25 of the first 30 draws for 1, 10 and 100 years:
  too narrow, so not the default.)
* The profile likelihood's maximum is pyextremes' maximum-likelihood return value.
* Contours: virocon's IFORM contour of a given model against the closed form (Rosenblatt
  transform of the β circle) to 1e-9; virocon's fit of a long synthetic record against the
  generating model (T_p quantiles within 1.5 %, H_s quantiles within 3 %).
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pyextremes")
pytest.importorskip("virocon")

from onbottom.metocean.extremes import fit_return_levels, gpd_return_level, profile_interval
from onbottom.metocean.joint import (
    JointModel,
    fit_joint_model,
    iform_contour,
    iform_contour_closed_form,
)
from onbottom.metocean.storms import storm_peaks
from onbottom.metocean.synthetic import EXAMPLE_MODEL, synthetic_hindcast

pytestmark = pytest.mark.verification

U, XI, SIGMA, RATE, YEARS = 3.0, -0.1, 0.8, 4.0, 30.0
RPS = (1.0, 10.0, 100.0)
STEP_H = 3.0


def _gpd_series(seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A 3-hourly series whose storms (> U) have GPD peaks at exactly RATE per year."""
    from scipy import stats

    rng = np.random.default_rng(seed)
    n = int(YEARS * 365.2425 * 24 / STEP_H)
    values = rng.uniform(0.2, 0.8 * U, n)  # calm background, below the threshold
    k = int(RATE * YEARS)
    slots = n // 40  # storms at least 40 steps (120 h) apart: r = 48 h separates them
    centres = 40 * np.sort(rng.choice(slots - 1, size=k, replace=False)) + 20
    peaks = U + stats.genpareto.rvs(XI, scale=SIGMA, size=k, random_state=rng)
    for c, p in zip(centres, peaks, strict=True):  # a storm: rise, peak, decay above U
        values[c] = p
        values[c - 1] = values[c + 1] = U + 0.5 * (p - U)
    t = np.datetime64("2000-01-01T00:00", "s") + (np.arange(n) * 10800).astype("timedelta64[s]")
    return t, values


def test_gpd_return_level_matches_pyextremes_fit_point_values():
    t, v = _gpd_series(0)
    storms = storm_peaks(v, STEP_H, U, 48.0, YEARS)
    assert storms.peak.size == int(RATE * YEARS)
    lv = fit_return_levels(v, t, storms, RPS, n_bootstrap=20)
    # pyextremes' rate: storms per the span first-to-last sample (years of 365.2425 d)
    span = (t[-1] - t[0]) / np.timedelta64(1, "s") / (365.2425 * 86400.0)
    direct = gpd_return_level(np.array(RPS), U, lv.scale, lv.shape, storms.peak.size / span)
    np.testing.assert_allclose(lv.value, direct, rtol=1e-9)


def test_profile_maximum_is_the_pyextremes_mle_and_brackets_it():
    t, v = _gpd_series(1)
    storms = storm_peaks(v, STEP_H, U, 48.0, YEARS)
    lv = fit_return_levels(v, t, storms, RPS)
    span = (t[-1] - t[0]) / np.timedelta64(1, "s") / (365.2425 * 86400.0)
    for i, rp in enumerate(RPS):
        zhat, lo, hi = profile_interval(storms.peak - U, storms.peak.size / span * rp, 0.95)
        assert U + zhat == pytest.approx(lv.value[i], rel=1e-4)  # a free search for the max
        assert lo < zhat < hi
        assert lv.lower[i] == pytest.approx(U + lo, rel=1e-4)
        assert lv.upper[i] == pytest.approx(U + hi, rel=1e-4)


def test_bootstrap_interval_brackets_the_estimate_and_is_reproducible():
    t, v = _gpd_series(2)
    storms = storm_peaks(v, STEP_H, U, 48.0, YEARS)
    a = fit_return_levels(v, t, storms, RPS, ci_method="bootstrap", n_bootstrap=60, seed=3)
    b = fit_return_levels(v, t, storms, RPS, ci_method="bootstrap", n_bootstrap=60, seed=3)
    assert np.all(a.lower < a.value) and np.all(a.value < a.upper)
    np.testing.assert_array_equal(a.lower, b.lower)
    np.testing.assert_array_equal(a.upper, b.upper)


def test_eva_intervals_cover_the_known_return_levels_over_50_draws():
    from scipy import stats

    truth = gpd_return_level(np.array(RPS), U, SIGMA, XI, RATE)
    draws = 50
    need = int(stats.binom.ppf(0.005, draws, 0.95))  # P[X < need] <= 0.005 for exact intervals
    covered = np.zeros(len(RPS), dtype=int)
    est = np.empty((draws, len(RPS)))
    for s in range(draws):
        t, v = _gpd_series(100 + s)
        storms = storm_peaks(v, STEP_H, U, 48.0, YEARS)
        lv = fit_return_levels(v, t, storms, RPS)
        covered += (lv.lower <= truth) & (truth <= lv.upper)
        est[s] = lv.value
    assert need == 43
    assert np.all(covered >= need), (covered, truth)
    se = est.std(axis=0, ddof=1) / np.sqrt(draws)
    assert np.all(np.abs(est.mean(axis=0) - truth) < 3.0 * se), (est.mean(axis=0), truth, se)


def _true_joint() -> JointModel:
    m = EXAMPLE_MODEL
    return JointModel(
        hs_scale=m.hs_scale,
        hs_shape=m.hs_shape,
        hs_location=m.hs_location,
        mu=(m.tp_a0, m.tp_a1, m.tp_a2),
        sigma=(m.tp_b0, m.tp_b1, m.tp_b2),
    )


@pytest.mark.parametrize("rp", [1.0, 100.0])
def test_virocon_iform_contour_equals_closed_form(rp):
    model = _true_joint()
    h1, t1 = iform_contour(model, rp, 3.0, n_points=90)
    h2, t2 = iform_contour_closed_form(model, rp, 3.0, n_points=90)
    np.testing.assert_allclose(h1, h2, rtol=1e-9)
    np.testing.assert_allclose(t1, t2, rtol=1e-9)
    # the contour's highest H_s is the Weibull quantile at Φ(β)
    from scipy import special

    beta = -special.ndtri(3.0 / (rp * 365.2425 * 24.0))
    assert h1.max() == pytest.approx(float(model.hs_quantile(special.ndtr(beta))), rel=1e-9)


def test_joint_fit_recovers_the_generating_model():
    d = synthetic_hindcast(EXAMPLE_MODEL, years=25.0, step_hours=3.0, seed=7)
    fit = fit_joint_model(d["hs"], d["tp"])
    true = _true_joint()
    p = np.array([0.5, 0.9, 0.99, 0.999])
    np.testing.assert_allclose(fit.hs_quantile(p), true.hs_quantile(p), rtol=0.03)
    for h in (1.0, 2.0, 3.0, 4.0):
        for q in (0.05, 0.5, 0.95):
            assert fit.tp_quantile(h, q) == pytest.approx(float(true.tp_quantile(h, q)), rel=0.015)
    # storm-peak H_s, beyond most of the data (64, 4 and 1 sea states above 4.5, 5.5, 6.5 m):
    # within 3 % at 5 m; at 6-7 m the fit drifts long (median +1.8 %, +2.7 %; 95 % up to +4.9 %,
    # docs/theory/metocean.md) — checked against the 5-9 % scale found on the buoy record
    for h, tol in ((5.0, 0.03), (6.0, 0.1), (7.0, 0.1)):
        for q in (0.05, 0.5, 0.95):
            assert fit.tp_quantile(h, q) == pytest.approx(float(true.tp_quantile(h, q)), rel=tol)


@pytest.mark.slow
@pytest.mark.long
def test_reference_storm_levels_of_the_example_model_are_what_a_2000_year_draw_gives():
    """The constants the report and the theory page compare the example's analysis with."""
    from onbottom.metocean.synthetic import STORM_LEVELS_2000Y, simulated_storm_levels

    got = simulated_storm_levels()
    for r, ref in STORM_LEVELS_2000Y.items():
        assert got[r] == pytest.approx(ref, abs=0.005)
