"""The flow synthesiser's stages against analytic properties (hand calculations)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from onbottom.hydro import flow_synthesis as fs
from onbottom.hydro.spectra import spectral_moment
from onbottom.hydro.spreading import spreading_factor, spreading_function
from onbottom.inputs.storm import SeaState, Storm


def test_harmonic_record_has_the_variance_m0_of_its_spectrum():
    # over the whole repeat period N Δt the harmonics are orthogonal, so the sample variance
    # equals Σ a_j²/2 = Σ S_UU(ω_j) Δω = M_0 of the discretised spectrum exactly (to rounding)
    n_fft, dt = 8192, 0.2
    _, dw = fs.harmonic_grid(n_fft, dt, fast=False)
    omega = dw * np.arange(n_fft // 2 + 1)
    s = np.zeros_like(omega)
    band = (omega > 0.0) & (omega < 3.0)
    s[band] = fs.bed_spectrum(omega[band], 20.0, 4.0, 10.0, 3.3)
    amp = fs.spectral_amplitudes(s, dw)
    phase = fs.random_phases(3, omega.size)
    u, a = fs.harmonic_series(0.5 * n_fft * amp * np.exp(1j * phase), omega, n_fft, n_fft)
    m0 = float(np.sum(s) * dw)
    m2 = float(np.sum(omega**2 * s) * dw)
    assert np.mean(u) == pytest.approx(0.0, abs=1e-12)
    assert np.var(u) == pytest.approx(m0, rel=1e-10)
    assert np.var(a) == pytest.approx(m2, rel=1e-10)  # U̇ has the spectrum ω² S_UU


def test_direct_sum_variance_tends_to_the_spectral_moment():
    # many components over a long record: var(U) → M_0 of the continuous S_UU (sampling error)
    hs, tp, d = 3.0, 9.0, 25.0
    t = np.arange(0.0, 20_000.0, 0.5)
    u, _ = fs.near_bed_velocity_series(t, hs, tp, d, gamma=2.0, seed=1, n_components=2000)
    w = np.linspace(1e-3, 5.0 * 2.0 * math.pi / tp, 20_000)
    m0 = spectral_moment(w, fs.bed_spectrum(w, d, hs, tp, 2.0), 0)
    assert np.var(u) == pytest.approx(m0, rel=0.05)


def test_three_sums_are_one_record():
    # direct sum, offset-grid FFT and the same bands agree to rounding
    t, u, du = fs.bed_velocity_record(3.0, 9.0, 20.0, 2.0, 5, 256, 400.0, 32)
    w, _ = fs.midpoint_grid(9.0, 256, 5.0)
    u2, du2 = fs.random_phase_series(w, fs.bed_spectrum(w, 20.0, 3.0, 9.0, 2.0), t, 5)
    np.testing.assert_allclose(u, u2, atol=1e-10 * np.max(np.abs(u2)))
    np.testing.assert_allclose(du, du2, atol=1e-10 * np.max(np.abs(du2)))


def test_stage_weights_blend_linearly_by_hand():
    a = SeaState(hs=2.0, tp=8.0, duration_s=100.0)
    b = SeaState(hs=3.0, tp=9.0, duration_s=100.0)
    storm = Storm(stages=(a, b), transition_s=20.0, build_up_s=10.0)
    t = np.array([5.0, 50.0, 105.0, 110.0, 115.0, 150.0])
    w, dw = fs.stage_weights(storm, t)
    # build-up: envelope t/10 at 5 s; stage 2 starts at 10 + 100 s, blend 100…120 s:
    # w_1 = (t − 100)/20
    np.testing.assert_allclose(w[0], [0.5, 1.0, 0.75, 0.5, 0.25, 0.0])
    np.testing.assert_allclose(w[1], [0.0, 0.0, 0.25, 0.5, 0.75, 1.0])
    np.testing.assert_allclose(dw[1], [0.0, 0.0, 0.05, 0.05, 0.05, 0.0])
    np.testing.assert_allclose(dw[0][0], 0.1)  # 1/build_up_s


@pytest.mark.parametrize("s", [0.5, 1.0, 2.0, 4.0, 8.0, 20.0])
@pytest.mark.parametrize("direction", [0.0, 30.0, 70.0, 90.0])
def test_spreading_factor_is_the_f109_integral(s, direction):
    # R_D² = ∫ D_w(θ) sin²(θ_w − θ) dθ over |θ| < π/2 (DNV-RP-F109 §3.4.3, Eq 3.8 D_w)
    tw = math.radians(direction)
    ref, _ = quad(
        lambda th: float(spreading_function(th, s)) * math.sin(tw - th) ** 2,
        -0.5 * math.pi,
        0.5 * math.pi,
        epsabs=1e-14,
        epsrel=1e-13,
    )
    assert float(spreading_factor(s, wave_direction_deg=direction)) == pytest.approx(
        math.sqrt(ref), rel=1e-10
    )
    # closed form for waves normal to the pipe: R_D² = (s + 1)/(s + 2)
    if direction == 90.0:
        assert float(spreading_factor(s, wave_direction_deg=90.0)) == pytest.approx(
            math.sqrt((s + 1.0) / (s + 2.0)), rel=1e-15
        )


def test_section_flow_is_scaled_by_rd_and_the_direction_sign():
    sea = SeaState(hs=3.0, tp=9.0, duration_s=300.0)
    base = fs.section_storm_flow(Storm(stages=(sea,), seed=2), 15.0, 0.2, 5.0)[0]
    for direction, s in ((90.0, 8.0), (250.0, 4.0), (60.0, 0.0)):
        sea_k = SeaState(hs=3.0, tp=9.0, duration_s=300.0, direction_deg=direction, spreading_s=s)
        st = Storm(stages=(sea_k,), seed=2)
        u = fs.section_storm_flow(st, 15.0, 0.2, 5.0)[0]
        rd = float(spreading_factor(s, wave_direction_deg=direction))
        sign = math.copysign(1.0, math.sin(math.radians(direction)))
        np.testing.assert_allclose(u, sign * rd * base, rtol=1e-12, atol=1e-15)


def test_section_flow_equals_the_record_of_all_drawn_phases():
    # the synthesiser draws phases for the harmonics that carry energy only: the record is bit
    # for bit that of one phase per harmonic j = 0 … N/2 from the same generator (the first
    # draws are the same), every stage scaled and blended as in the module docstring
    a = SeaState(hs=3.0, tp=9.0, duration_s=120.0, direction_deg=60.0, spreading_s=4.0)
    b = SeaState(hs=4.0, tp=11.0, duration_s=150.0, direction_deg=280.0)
    storm = Storm(stages=(a, b), seed=7, build_up_s=30.0, decay_s=40.0, transition_s=20.0)
    dts, depth = 0.2, 25.0
    u, acc, weights = fs.section_storm_flow(storm, depth, dts, 5.0)
    n = math.ceil(storm.duration_s / dts) + 1
    nfft, dw = fs.harmonic_grid(n, dts, fast=True)
    nbins = nfft // 2 + 1
    omega = dw * np.arange(nbins)
    active = (omega > 0.0) & (omega <= 5.0 * 2.0 * math.pi / 9.0) & (omega < math.pi / dts)
    rot = np.exp(1j * fs.random_phases(7, nbins))
    w, dwt = fs.stage_weights(storm, np.arange(n) * dts)
    u_ref, a_ref = np.zeros(n), np.zeros(n)
    for k, sea in enumerate(storm.stages):
        s_uu = np.zeros(nbins)
        s_uu[active] = fs.bed_spectrum(omega[active], depth, sea.hs, sea.tp, None)
        rd = float(spreading_factor(sea.spreading_s, wave_direction_deg=sea.direction_deg))
        sign = math.copysign(1.0, math.sin(math.radians(sea.direction_deg)))
        spec = (0.5 * nfft) * fs.spectral_amplitudes(s_uu, dw) * rot * (rd * sign)
        uk, ak = fs.harmonic_series(spec, omega, nfft, n)
        fs.add_stage(u_ref, a_ref, w[k], dwt[k], uk, ak)
    assert np.array_equal(u, u_ref)
    assert np.array_equal(acc, a_ref)
    assert np.array_equal(weights, w)
