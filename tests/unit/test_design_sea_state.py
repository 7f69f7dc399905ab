"""Design sea states: the vectorised U_s, T_u against the scalar hydro functions; k_U, k_T, R_D."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.hydro import kinematics, spectra
from onbottom.hydro.design_sea_state import (
    design_oscillation,
    jonswap_gamma,
    peak_period_factor,
    peak_velocity_factor,
    significant_bed_velocity,
)
from onbottom.hydro.spreading import spreading_factor, spreading_function


@pytest.mark.parametrize(
    ("hs", "tp", "depth"), [(4.68, 10.8, 13.0), (2.0, 6.0, 50.0), (8.0, 14.0, 200.0)]
)
def test_vectorised_matches_scalar_integration(hs, tp, depth):
    w = np.linspace(1e-3, 15.0 * 2 * math.pi / tp, 60_000)
    s = kinematics.near_bed_velocity_spectrum(w, spectra.jonswap(w, hs, tp), depth)
    us_ref = kinematics.significant_velocity(w, s)
    tu_ref = kinematics.zero_upcrossing_period(w, s)
    us, tu = significant_bed_velocity(hs, tp, depth)
    assert us == pytest.approx(us_ref, rel=2e-4)
    assert tu == pytest.approx(tu_ref, rel=2e-4)


def test_broadcasting_and_pierson_moskowitz():
    us, tu = significant_bed_velocity([2.0, 4.0], 10.0, [[20.0], [40.0]])
    assert us.shape == (2, 2) and tu.shape == (2, 2)
    assert us[0, 1] == pytest.approx(2.0 * us[0, 0])  # linear in H_s
    assert np.all(us[1] < us[0])  # deeper water, smaller bed velocity
    u_pm, _ = significant_bed_velocity(4.0, 10.0, 20.0, spectrum="pierson-moskowitz")
    u_g1, _ = significant_bed_velocity(4.0, 10.0, 20.0, gamma=1.0)
    assert u_pm == pytest.approx(u_g1)


def test_gamma_rule():
    assert jonswap_gamma(4.68, 10.8) == pytest.approx(
        math.exp(5.75 - 1.15 * 10.8 / math.sqrt(4.68))
    )
    assert jonswap_gamma(4.0, 7.0) == 5.0 and jonswap_gamma(1.0, 6.0) == 1.0
    assert jonswap_gamma(4.68, 10.8) == pytest.approx(spectra.jonswap_peak_enhancement(4.68, 10.8))


def test_peak_factors_hand_calculation():
    tau = 1000.0
    a = math.sqrt(2.0 * math.log(tau))
    assert peak_velocity_factor(tau) == pytest.approx(0.5 * (a + 0.5772 / a))
    assert peak_period_factor(0.1, 1.0) == pytest.approx(1.25 - 5 * 0.25 * 0.1)
    assert peak_period_factor(0.1, 5.0) == pytest.approx(1.17 - 5 * 0.17 * 0.1)
    assert peak_period_factor(0.1, 2.15) == pytest.approx(1.23 - 5 * 0.23 * 0.1)
    assert peak_period_factor(0.3, 3.3) == 1.0


def test_spreading_closed_form_matches_quadrature():
    th = np.linspace(-math.pi / 2, math.pi / 2, 20_001)
    for s in (2.0, 4.0, 8.0):
        dw = spreading_function(th, s)
        assert np.trapezoid(dw, th) == pytest.approx(1.0, rel=1e-6)
        for tw in (90.0, 60.0, 30.0):
            ref = math.sqrt(np.trapezoid(dw * np.sin(math.radians(tw) - th) ** 2, th))
            assert spreading_factor(s, wave_direction_deg=tw) == pytest.approx(ref, rel=1e-6)
    assert spreading_factor(None, wave_direction_deg=30.0) == pytest.approx(0.5)
    assert spreading_factor(0, wave_direction_deg=90.0) == pytest.approx(1.0)


def test_design_oscillation_groups():
    o = design_oscillation(4.0, 10.0, 20.0, 0.5, current_velocity=0.5, submerged_weight=1000.0)
    assert o.k == pytest.approx(o.us * o.tu / 0.5)
    assert o.n == pytest.approx(o.us / (9.80665 * o.tu))
    assert o.u_star == pytest.approx(o.k_u * o.us) and o.t_star == pytest.approx(o.k_t * o.tu)
    # s_g identity of F109 §3.5: s_g = 1 + (2/π) N K L
    b = 1025.0 * 9.80665 * math.pi * 0.25 / 4.0
    assert 1 + 2 / math.pi * o.n * o.k * o.l == pytest.approx((1000.0 + b) / b)
    assert o.tau == pytest.approx(10_800.0 / o.tu)


@pytest.mark.parametrize(
    ("kw", "field"),
    [
        ({"hs": -1.0}, "hs"),
        ({"tp": float("nan")}, "tp"),
        ({"depth": 0.0}, "depth"),
        ({"gamma": 9.0}, "gamma"),
    ],
)
def test_bad_inputs(kw, field):
    args = {"hs": 2.0, "tp": 8.0, "depth": 10.0, **kw}
    with pytest.raises(InputError, match=f"{field} = "):
        significant_bed_velocity(**args)
