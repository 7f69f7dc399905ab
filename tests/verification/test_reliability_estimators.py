"""Verification of the failure-probability estimators on closed-form limit states.

A pipe held by friction alone under a static lateral load: g = μ W − F with W = 1500 N/m,
μ ~ N(0.6, 0.06), F ~ N(480, 75) N/m. g is normal, so P[g ≤ 0] = Φ(−β) with
β = (0.6 W − 480)/√((0.06 W)² + 75²) = 3.585 (p = 1.685e-4), and the importance factors are
(0.06 W)²/((0.06 W)² + 75²) = 0.590 for μ and 0.410 for F. With log-normal resistance and
load, g = R − S fails when ln R − ln S ≤ 0, again a closed form.

* FORM is exact for both (1e-6).
* Importance sampling at the FORM design point: over 20 seeds at a target CV of 0.05, the
  interval p̂(1 ± 1.96 CV) contains the exact p at least as often as an exact estimator's would
  with probability 0.995 (binomial), and the mean estimate is within 3 standard errors.
* Subset simulation (1000 samples per level): over 20 seeds the mean estimate is within 3
  standard errors of the exact p.
* Monte Carlo and importance sampling agree (3 combined standard deviations) where both are
  affordable (p ≈ 4e-2).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

pytest.importorskip("openturns")

from onbottom.reliability import (
    UncertainParameter,
    estimate_failure_probability,
    lifetime_probability,
)

pytestmark = pytest.mark.verification

W = 1500.0


def _friction(f_mean: float = 480.0):
    params = [
        UncertainParameter("friction_coefficient", "normal", {"mean": 0.6, "std": 0.06}),
        UncertainParameter("load", "normal", {"mean": f_mean, "std": 75.0}),
    ]
    beta = (0.6 * W - f_mean) / math.hypot(0.06 * W, 75.0)
    return (lambda x: x[:, 0] * W - x[:, 1]), params, beta


def test_form_is_exact_for_the_friction_only_pipe():
    g, params, beta = _friction()
    r = estimate_failure_probability(g, params, method="form")
    assert r.converged
    assert r.reliability_index == pytest.approx(beta, rel=1e-6)
    assert r.probability == pytest.approx(stats.norm.cdf(-beta), rel=1e-5)
    a_mu = (0.06 * W) ** 2 / ((0.06 * W) ** 2 + 75.0**2)
    assert r.importance["friction_coefficient"] == pytest.approx(a_mu, rel=1e-4)
    assert r.importance["load"] == pytest.approx(1.0 - a_mu, rel=1e-4)
    dp = r.design_point
    assert dp["friction_coefficient"] * W - dp["load"] == pytest.approx(0.0, abs=1e-3)


def test_form_is_exact_for_lognormal_resistance_and_load():
    params = [
        UncertainParameter("resistance", "lognormal", {"mean": 900.0, "std": 120.0}),
        UncertainParameter("load", "lognormal", {"mean": 400.0, "std": 90.0}),
    ]
    z = [math.sqrt(math.log1p((s / m) ** 2)) for m, s in ((900.0, 120.0), (400.0, 90.0))]
    lam = [math.log(m) - 0.5 * zz**2 for m, zz in zip((900.0, 400.0), z, strict=True)]
    beta = (lam[0] - lam[1]) / math.hypot(*z)
    r = estimate_failure_probability(lambda x: x[:, 0] - x[:, 1], params, method="form")
    assert r.reliability_index == pytest.approx(beta, rel=1e-5)


def test_importance_sampling_meets_its_stated_cv_over_20_seeds():
    g, params, beta = _friction()
    exact = stats.norm.cdf(-beta)
    draws = 20
    need = int(stats.binom.ppf(0.005, draws, 0.95))
    hits, est = 0, []
    for s in range(draws):
        r = estimate_failure_probability(g, params, method="importance", target_cv=0.05, seed=s)
        assert r.converged and r.cv <= 0.05
        assert r.evaluations < 20_000  # 1e-4 without 1e6 runs
        lo, hi = r.interval()
        hits += lo <= exact <= hi
        est.append(r.probability)
    assert hits >= need, (hits, need)
    est = np.array(est)
    assert abs(est.mean() - exact) < 3.0 * est.std(ddof=1) / math.sqrt(draws)


def test_subset_simulation_is_unbiased_over_20_seeds():
    g, params, beta = _friction()
    exact = stats.norm.cdf(-beta)
    est = np.array(
        [
            estimate_failure_probability(g, params, method="subset", seed=s).probability
            for s in range(20)
        ]
    )
    assert abs(est.mean() - exact) < 3.0 * est.std(ddof=1) / math.sqrt(est.size)


def test_monte_carlo_and_importance_sampling_agree_where_both_are_affordable():
    g, params, beta = _friction(f_mean=700.0)
    mc = estimate_failure_probability(
        g, params, method="monte_carlo", target_cv=0.02, max_evaluations=400_000, seed=1
    )
    imp = estimate_failure_probability(g, params, method="importance", target_cv=0.02, seed=2)
    assert mc.converged and imp.converged
    sd = math.hypot(mc.cv * mc.probability, imp.cv * imp.probability)
    assert abs(mc.probability - imp.probability) < 3.0 * sd
    assert abs(mc.probability - stats.norm.cdf(-beta)) < 3.0 * mc.cv * mc.probability


def test_lifetime_probability():
    assert lifetime_probability(1e-4, 1.0) == pytest.approx(1e-4)
    assert lifetime_probability(1e-4, 50.0) == pytest.approx(1.0 - (1.0 - 1e-4) ** 50, rel=1e-12)
    assert lifetime_probability(0.0, 30.0) == 0.0
