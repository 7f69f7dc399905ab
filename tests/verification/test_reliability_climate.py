"""Verification of the storm climate as reliability inputs (onbottom.reliability.climate).

A climate with known parameters (λ = 3 storms a year over u = 4 m, GPD σ = 0.7 m, ξ = −0.1;
T_p | H_s of DNV-RP-C205 form) and three limit states with closed forms:

* g = x − H_s(u): P[failure | storm] = (1 + ξ(x − u)/σ)^(−1/ξ); FORM is exact (g is monotone
  in u_hs alone) and importance sampling meets its CV;
* g = t − T_p(u): P = ∫ φ(v) [1 − Φ((ln t − μ(h(v)))/σ(h(v)))] dv by quadrature; importance
  sampling and subset simulation agree with it within 3 of their stated CVs (subset: of the
  empirical spread over seeds, its stated CV being optimistic);
* the sectors drawn by u_direction have the stated frequencies (binomial, 3 standard errors).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, special, stats

pytest.importorskip("openturns")

from onbottom.reliability import StormClimate, estimate_failure_probability
from reliability_cases import CLIMATE, JOINT

pytestmark = pytest.mark.verification


def _hs_state(x):
    return lambda u: x - CLIMATE.sea_state(u)["hs"]


def test_hs_exceedance_form_exact_and_importance_sampling_within_cv():
    x = 6.5
    exact = CLIMATE.exceedance_per_storm(x)
    assert exact == pytest.approx((1.0 - 0.1 * (x - 4.0) / 0.7) ** 10.0, rel=1e-12)
    params = CLIMATE.parameters()
    form = estimate_failure_probability(_hs_state(x), params, method="form")
    assert form.probability == pytest.approx(exact, rel=1e-6)
    assert form.importance["u_hs"] == pytest.approx(1.0, abs=1e-6)
    imp = estimate_failure_probability(
        _hs_state(x), params, method="importance", target_cv=0.05, seed=3
    )
    assert abs(imp.probability - exact) < 3.0 * imp.cv * imp.probability
    annual = CLIMATE.annual_probability(exact)
    assert annual == pytest.approx(1.0 - math.exp(-3.0 * exact), rel=1e-12)


def test_tp_exceedance_against_quadrature():
    t = 14.0

    def integrand(v):
        h = CLIMATE.peak_hs(v)
        z = (math.log(t) - JOINT.tp_mu(h)) / JOINT.tp_sigma(h)
        return stats.norm.pdf(v) * special.ndtr(-z)

    exact, _ = integrate.quad(integrand, -10.0, 10.0, epsabs=1e-14, limit=200)
    params = CLIMATE.parameters()[:2]

    def g(u):
        return t - CLIMATE.sea_state(np.column_stack([u, np.zeros(len(u))]))["tp"]

    imp = estimate_failure_probability(g, params, method="importance", target_cv=0.03, seed=1)
    assert abs(imp.probability - exact) < 3.0 * imp.cv * imp.probability
    sub = np.array(
        [
            estimate_failure_probability(g, params, method="subset", seed=s).probability
            for s in range(12)
        ]
    )
    assert abs(sub.mean() - exact) < 3.0 * sub.std(ddof=1) / math.sqrt(sub.size)


def test_sector_frequencies():
    rng = np.random.default_rng(0)
    n = 200_000
    k = CLIMATE.sea_state(rng.standard_normal((n, 3)))["sector"]
    counts = np.bincount(k, minlength=4) / n
    f = np.array(CLIMATE.sector_frequencies)
    assert np.all(np.abs(counts - f) < 3.0 * np.sqrt(f * (1 - f) / n))


def test_climate_of_an_analysed_hindcast():
    from onbottom.metocean.analysis import MetoceanOptions, analyse_hindcast
    from onbottom.metocean.hindcast import Hindcast
    from onbottom.metocean.synthetic import synthetic_hindcast

    d = synthetic_hindcast(years=10.0, seed=11)
    hc = Hindcast(d["time"], d["hs"], d["tp"], d["wave_direction_deg"], None, None, "synthetic")
    res = analyse_hindcast(hc, MetoceanOptions(sectors=4, return_periods=(10.0,)))
    c = StormClimate.from_result(res)
    omni = res.hs["omni"]
    assert c.rate == pytest.approx(omni.storms.peak.size / hc.years)
    assert sum(c.sector_frequencies) == pytest.approx(1.0)
    # the climate's 10-year storm peak is the analysis' 10-year return value (same GPD, rate)
    p = 1.0 / (10.0 * c.rate)
    h10 = float(c.peak_hs(special.ndtri(1.0 - p)))
    assert h10 == pytest.approx(float(omni.value[0]), rel=2e-3)
