"""Unit tests: hydro formulas against hand calculations (DNV-RP-F109 / DNV-RP-C205 forms)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.constants import GRAVITY, RHO_SEAWATER
from onbottom.hydro import (
    MorisonCoefficients,
    horizontal_force,
    jonswap,
    jonswap_peak_enhancement,
    lift_force,
    mean_current_over_pipe,
    near_bed_velocity_series,
    near_bed_velocity_spectrum,
    regular_wave_bed_velocity,
    seabed_transfer,
    significant_velocity,
    spectral_moment,
    wave_number,
    zero_upcrossing_period,
)


@pytest.mark.parametrize(("hs", "tp"), [(4.0, 8.0), (4.0, 10.0), (8.0, 12.0), (2.0, 14.0)])
def test_jonswap_m0_is_hs_squared_over_16(hs, tp):
    w = np.linspace(1e-3, 6.0, 60_000)
    m0 = spectral_moment(w, jonswap(w, hs, tp), 0)
    # Goda's α normalisation: m0 = Hs²/16 within about 1% for 1 <= γ <= 7
    assert m0 == pytest.approx(hs**2 / 16.0, rel=0.015)


def test_jonswap_peak_at_omega_p_and_gamma_rule():
    assert jonswap_peak_enhancement(4.0, 7.0) == 5.0  # φ = 3.5
    assert jonswap_peak_enhancement(4.0, 8.0) == pytest.approx(math.exp(5.75 - 1.15 * 4.0))
    assert jonswap_peak_enhancement(4.0, 10.0) == 1.0  # φ = 5
    w = np.linspace(0.2, 2.0, 18_001)
    s = jonswap(w, 4.0, 8.0, gamma=3.3)
    assert w[np.argmax(s)] == pytest.approx(2 * math.pi / 8.0, abs=2e-4)


def test_wave_number_satisfies_dispersion_and_limits():
    w = np.array([0.2, 0.6, 1.0, 3.0])
    d = 30.0
    k = wave_number(w, d)
    np.testing.assert_allclose(GRAVITY * k * np.tanh(k * d), w**2, rtol=1e-12)
    # deep water: k = ω²/g ; shallow: k = ω/√(g d)
    assert wave_number(3.0, 1000.0)[0] == pytest.approx(9.0 / GRAVITY, rel=1e-12)
    assert wave_number(0.01, 5.0)[0] == pytest.approx(0.01 / math.sqrt(GRAVITY * 5.0), rel=1e-4)


def test_regular_wave_bed_velocity_hand_calc():
    # H = 5 m, T = 10 s, d = 50 m: k from dispersion, U = πH/(T sinh kd)
    k = wave_number(2 * math.pi / 10.0, 50.0)[0]
    expected = math.pi * 5.0 / (10.0 * math.sinh(k * 50.0))
    assert regular_wave_bed_velocity(5.0, 10.0, 50.0) == pytest.approx(expected, rel=1e-12)
    assert seabed_transfer(np.array([0.0]), 50.0)[0] == 0.0


def test_significant_velocity_and_period_of_narrow_band():
    # a narrow band at ω0: U_s = 2√M0, T_u → 2π/ω0
    w = np.linspace(0.99, 1.01, 201)
    s = np.full(w.size, 0.5 / 0.02)  # M0 = 0.5
    assert significant_velocity(w, s) == pytest.approx(2.0 * math.sqrt(0.5), rel=1e-9)
    assert zero_upcrossing_period(w, s) == pytest.approx(2 * math.pi, rel=1e-4)


def test_velocity_series_is_seeded_and_has_spectral_variance():
    t = np.arange(0.0, 3600.0, 0.5)
    u1, _ = near_bed_velocity_series(t, 4.0, 10.0, 40.0, seed=3)
    u2, _ = near_bed_velocity_series(t, 4.0, 10.0, 40.0, seed=3)
    u3, _ = near_bed_velocity_series(t, 4.0, 10.0, 40.0, seed=4)
    np.testing.assert_array_equal(u1, u2)
    assert not np.allclose(u1, u3)
    w = np.linspace(1e-3, 5 * 2 * math.pi / 10.0, 4000)
    m0 = spectral_moment(w, near_bed_velocity_spectrum(w, jonswap(w, 4.0, 10.0), 40.0), 0)
    assert np.var(u1) == pytest.approx(m0, rel=0.15)


def test_morison_and_lift_hand_calc():
    c = MorisonCoefficients(drag=1.0, inertia=3.29, lift=0.9)
    # U = 1, V = 0.5, dU/dt = 0.2, D = 0.5: drag ½ρD C_D (1.5)² + inertia π/4 ρ D² C_M 0.2
    fh = horizontal_force(np.array([1.0]), np.array([0.2]), 0.5, 0.5, c)[0]
    exp = 0.5 * RHO_SEAWATER * 0.5 * 1.0 * 2.25 + 0.25 * math.pi * RHO_SEAWATER * 0.25 * 3.29 * 0.2
    assert fh == pytest.approx(exp, rel=1e-12)
    # drag keeps the sign of the flow
    assert horizontal_force(np.array([-2.0]), np.array([0.0]), 0.0, 1.0, c)[0] < 0.0
    fl = lift_force(np.array([1.0]), 0.5, 0.5, c)[0]
    assert fl == pytest.approx(0.5 * RHO_SEAWATER * 0.5 * 0.9 * 2.25, rel=1e-12)


def test_mean_current_over_pipe_is_mean_of_log_profile():
    v_ref, zr, d, z0 = 1.0, 3.0, 0.8, 1e-5
    z = np.linspace(0.0, d, 200_001)
    prof = v_ref * np.log((z + z0) / z0) / math.log((zr + z0) / z0)
    mean_numeric = np.trapezoid(prof, z) / d
    assert mean_current_over_pipe(v_ref, zr, d, z0) == pytest.approx(mean_numeric, rel=1e-5)
    assert mean_current_over_pipe(v_ref, zr, d, z0, angle_deg=30.0) == pytest.approx(
        0.5 * mean_current_over_pipe(v_ref, zr, d, z0), rel=1e-12
    )
