"""Verification of the current's joint model with H_s (onbottom.metocean.current) and of its
use in the storm climate of the reliability campaign.

A series drawn from a **known** dependence: 25 years, 3-hourly; H_s of the example model
(AR(1) normal score z, τ = 24 h, mapped to the Weibull of DNV-RP-C205 §3.6.3); the current
U = F_U⁻¹(Φ(ρ z + √(1 − ρ²) ε)) with ε an independent AR(1) score (same τ), F_U Weibull
(α_U = 0.30 m/s, β_U = 1.8), ρ = 0.6. The generator is written here, independently of the
model's own transformation.

Tolerances (fixed before the run): serial correlation ρ₁ = exp(−3/24) inflates the variance of
the estimates by (1 + ρ₁²)/(1 − ρ₁²) ≈ 8, so the 73 048 states count as ≈ 9 000 independent
ones: standard error of ρ̂ ≈ (1 − ρ²)/√9000 ≈ 0.007, of β̂ ≈ 0.8 %, of α̂ ≈ 0.6 %. Asserted:
|ρ̂ − ρ| < 0.03, β̂ within 4 %, α̂ within 3 %, and the median and 90 % current given the
6-m H_s within 5 % of the generating model's (each ≥ 4 standard errors).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, signal, special, stats

from onbottom.metocean.current import CurrentModel, fit_current_model
from onbottom.metocean.joint import fit_joint_model
from onbottom.metocean.synthetic import EXAMPLE_MODEL, weibull_hs_quantile

pytestmark = pytest.mark.verification

RHO, SCALE, SHAPE = 0.6, 0.30, 1.8


def _ar1(rng, n, rho1):
    e = rng.standard_normal(n) * math.sqrt(1.0 - rho1 * rho1)
    e[0] = rng.standard_normal()
    return signal.lfilter([1.0], [1.0, -rho1], e)


def _draw(seed: int, years: float = 25.0):
    rng = np.random.default_rng(seed)
    n = round(years * 365.2425 * 8)
    rho1 = math.exp(-3.0 / 24.0)
    z = _ar1(rng, n, rho1)
    eps = _ar1(rng, n, rho1)
    hs = np.asarray(weibull_hs_quantile(EXAMPLE_MODEL, special.ndtr(z)))
    q = special.ndtr(RHO * z + math.sqrt(1.0 - RHO**2) * eps)
    u = SCALE * np.power(-np.log1p(-q), 1.0 / SHAPE)
    t = np.exp(EXAMPLE_MODEL.tp_mu(hs) + EXAMPLE_MODEL.tp_sigma(hs) * _ar1(rng, n, rho1))
    return hs, t, u


def _true_quantile(h: float, p: float) -> float:
    m = EXAMPLE_MODEL
    fh = 1.0 - math.exp(-(((h - m.hs_location) / m.hs_scale) ** m.hs_shape))
    zc = RHO * special.ndtri(fh) + math.sqrt(1.0 - RHO**2) * special.ndtri(p)
    return SCALE * (-math.log1p(-special.ndtr(zc))) ** (1.0 / SHAPE)


def test_fit_recovers_a_known_dependence():
    hs, tp, u = _draw(5)
    joint = fit_joint_model(hs, tp)  # the H_s marginal the metocean analysis uses
    m = fit_current_model(
        hs,
        u,
        hs_scale=joint.hs_scale,
        hs_shape=joint.hs_shape,
        hs_location=joint.hs_location,
    )
    assert abs(m.rho - RHO) < 0.03
    assert m.shape == pytest.approx(SHAPE, rel=0.04)
    assert m.scale == pytest.approx(SCALE, rel=0.03)
    for p in (0.5, 0.9):
        assert float(m.quantile(6.0, p)) == pytest.approx(_true_quantile(6.0, p), rel=0.05)


def test_independent_current_gives_rho_near_zero():
    rng = np.random.default_rng(2)
    hs, _, _ = _draw(3, years=10.0)
    u = stats.weibull_min.rvs(SHAPE, scale=SCALE, size=hs.size, random_state=rng)
    m = fit_current_model(hs, u, hs_scale=1.0, hs_shape=1.35, hs_location=0.25)
    assert abs(m.rho) < 0.03  # serially independent U: SE ≈ 1/√(H_s's n_eff ≈ 3600) ≈ 0.017


def test_rosenblatt_mapping_by_hand_and_its_marginal():
    m = CurrentModel(
        scale=SCALE,
        shape=SHAPE,
        rho=RHO,
        hs_scale=EXAMPLE_MODEL.hs_scale,
        hs_shape=EXAMPLE_MODEL.hs_shape,
        hs_location=EXAMPLE_MODEL.hs_location,
    )
    for h, p in ((1.0, 0.5), (6.0, 0.9), (9.0, 0.1)):
        # 1e-8: the reference forms 1 − F_H by subtraction (round-off in the tail at 9 m)
        assert float(m.quantile(h, p)) == pytest.approx(_true_quantile(h, p), rel=1e-8)
    # with H_s drawn from its own Weibull, U has the Weibull marginal F_U (copula property)
    rng = np.random.default_rng(0)
    n = 200_000
    h = weibull_hs_quantile(EXAMPLE_MODEL, rng.uniform(size=n))
    u = m.speed(h, rng.standard_normal(n))
    for q in (0.5, 0.9, 0.99):
        assert np.quantile(u, q) == pytest.approx(float(m.marginal_quantile(q)), rel=0.01)


def test_storm_climate_draws_the_conditional_current():
    """P[U > u0 | storm] of the climate's Monte Carlo against quadrature over the storm-peak
    GPD: P = ∫ φ(v) [1 − Φ((z_U(u0) − ρ z_H(h(v)))/√(1 − ρ²))] dv (3 binomial SE)."""
    from dataclasses import replace

    from reliability_cases import CLIMATE

    cm = CurrentModel(
        scale=SCALE, shape=SHAPE, rho=RHO, hs_scale=1.0, hs_shape=1.35, hs_location=0.25
    )
    climate = replace(CLIMATE, current=cm)
    names = [p.name for p in climate.parameters()]
    assert names == ["u_hs", "u_tp", "u_direction", "u_current"]
    u0 = 0.55
    zu0 = special.ndtri(1.0 - math.exp(-((u0 / SCALE) ** SHAPE)))

    def integrand(v):
        zh = float(cm.hs_score(float(climate.peak_hs(v))))
        return stats.norm.pdf(v) * special.ndtr(-(zu0 - RHO * zh) / math.sqrt(1.0 - RHO**2))

    exact, _ = integrate.quad(integrand, -10.0, 10.0, epsabs=1e-14, limit=200)
    rng = np.random.default_rng(4)
    n = 400_000
    ss = climate.sea_state(rng.standard_normal((n, 4)))
    got = np.mean(ss["current"] > u0)
    assert abs(got - exact) < 3.0 * math.sqrt(exact * (1.0 - exact) / n)
    assert 0.05 < exact < 0.95  # a discriminating level
