"""Fourier table fitting: known coefficients recovered from synthetic signals; hand values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.hydro.fourier_fit import (
    FourierRun,
    fit_fourier_table,
    fit_run,
    half_cycles,
    morison_regular_run,
)
from onbottom.hydro.fourier_table import fourier_basis

RHO, D = 1025.0, 0.4


def _known(kc: float, mh: float, n: int) -> np.ndarray:
    """Arbitrary but smooth 'true' coefficients (2, 2N+1) of a cell (K, M_h)."""
    j = np.arange(2 * n + 1)
    y = (0.8 + 0.05 * kc + 0.3 * mh) / (1.0 + j) * np.cos(0.7 * j + mh)
    z = (0.5 + 0.02 * kc - 0.2 * mh) / (1.0 + j * j) * np.sin(0.3 * j + 1.0)
    return np.vstack((y, z))


def _synthetic_run(kc: float, m: float, n: int, spc: int = 1000, cycles: int = 4) -> FourierRun:
    """Regular flow U_m sin ωt + V with forces built from _known per half-cycle, exact phases."""
    um = 0.9
    period = kc * D / um
    omega = 2.0 * math.pi / period
    v = m * um
    a = math.asin(m)
    t = (np.arange(cycles * spc + 1) + 0.37) * (period / spc)
    w = um * np.sin(omega * t) + v
    phase = np.mod(omega * t + a, 2.0 * math.pi)  # 0 at the start of a + half-cycle
    plus = phase < math.pi + 2.0 * a
    theta = np.where(
        plus,
        math.pi * phase / (math.pi + 2.0 * a),
        math.pi * (phase - math.pi - 2.0 * a) / (math.pi - 2.0 * a),
    )
    s = np.where(plus, 1.0, -1.0)
    fy = np.empty_like(t)
    fz = np.empty_like(t)
    scale = 0.5 * RHO * D * um * um
    for sign, mh in ((1.0, m), (-1.0, -m)):
        sel = s == sign
        c = _known(kc, mh, n)
        b = fourier_basis(theta[sel], n)
        fy[sel] = sign * scale * (b @ c[0])
        fz[sel] = scale * (b @ c[1])
    return FourierRun(t, w, fy, fz, current=v, label=f"K={kc} M={m}")


def test_fit_recovers_known_coefficients_without_current():
    n = 5
    fit = fit_run(_synthetic_run(8.0, 0.0, n), diameter=D, rho=RHO, harmonics=n)
    assert fit.keulegan_carpenter == pytest.approx(8.0, rel=1e-8)
    assert fit.current_ratio == 0.0 and list(fit.rows) == [0.0]
    assert fit.counts[0.0] == 7  # 4 cycles, first and last half-cycles incomplete
    # stated tolerance: 1e-8 (crossing times by a cubic, peaks by a parabola: O(Δt⁴))
    np.testing.assert_allclose(fit.rows[0.0], _known(8.0, 0.0, n), atol=1e-8)
    assert fit.rms < 1e-8
    summary = fit.summary()  # the --json row of onbottom fourier-fit
    assert summary["half_cycles"] == 7 and summary["K"] == fit.keulegan_carpenter
    assert (summary["M"], summary["U_m"], summary["T"]) == (0.0, fit.amplitude, fit.period)
    assert summary["rms"] == fit.rms


def test_fit_recovers_known_coefficients_with_current():
    n = 4
    fit = fit_run(_synthetic_run(12.0, 0.3, n, spc=2000), diameter=D, rho=RHO, harmonics=n)
    assert fit.keulegan_carpenter == pytest.approx(12.0, rel=1e-8)
    assert fit.current_ratio == pytest.approx(0.3, rel=1e-8)
    assert sorted(fit.rows) == pytest.approx([-0.3, 0.3], rel=1e-8)
    for mh, coef in fit.rows.items():
        np.testing.assert_allclose(coef, _known(12.0, round(mh, 6), n), atol=1e-6)


def test_morison_run_gives_the_hand_coefficients():
    """Morison at M = 0: W|W| = U_m² sin²θ = U_m² (1 − cos 2θ)/2 and ρ(πD²/4)C_M U̇ =
    ½ρD U_m² (π² C_M / K) cos θ, so A₀ = C_D/2, A₂ = −C_D/2, A₁ = π² C_M / K (Y) and
    A₀ = C_L/2, A₂ = −C_L/2 (Z), every other coefficient 0."""
    kc, cd, cm, cl = 10.0, 0.7, 3.29, 0.9
    run = morison_regular_run(kc, 0.0, cd=cd, cm=cm, cl=cl, diameter=D, rho=RHO)
    fit = fit_run(run, diameter=D, rho=RHO, harmonics=3)
    expect = np.zeros((2, 7))
    expect[0, [0, 1, 3]] = (cd / 2, math.pi**2 * cm / kc, -cd / 2)
    expect[1, [0, 3]] = (cl / 2, -cl / 2)
    np.testing.assert_allclose(fit.rows[0.0], expect, atol=1e-12)


def test_table_from_runs_and_errors():
    runs = [morison_regular_run(k, m, cd=0.7, cm=3.29, cl=0.9) for k in (5, 10) for m in (0, 0.4)]
    tab = fit_fourier_table(runs, diameter=1.0, rho=1025.0, harmonics=3, source="test")
    np.testing.assert_array_equal(tab.m_grid, [-0.4, 0.0, 0.4])
    np.testing.assert_array_equal(tab.k_grid, [5.0, 10.0])
    with pytest.raises(InputError, match="two runs give the cell"):
        fit_fourier_table([runs[0], runs[0]], diameter=1.0, rho=1025.0, harmonics=3)
    with pytest.raises(InputError, match=r"missing cell \(K=10, M=-0.4\)"):
        fit_fourier_table(runs[:3], diameter=1.0, rho=1025.0, harmonics=3)
    t = np.linspace(0.0, 10.0, 101)
    steady = FourierRun(t, np.full_like(t, 0.5), np.ones_like(t), np.ones_like(t), 0.5)
    with pytest.raises(InputError, match="no complete half-cycle"):
        fit_run(steady, diameter=1.0, rho=1025.0)
    with pytest.raises(InputError, match="not strictly increasing at sample 3"):
        FourierRun(t[[0, 1, 2, 2, 4, 5, 6, 7, 8]], t[:9], t[:9], t[:9])
    with pytest.raises(InputError, match=r"force_y\[2\] = nan"):
        FourierRun(t[:9], t[:9], np.where(np.arange(9) == 2, np.nan, 0.0), t[:9])


def test_half_cycles_of_a_sine():
    t = np.linspace(0.0, 3.0, 3001)
    hc = half_cycles(t, np.sin(2.0 * math.pi * t + 0.1))
    assert [h.sign for h in hc] == [-1, 1, -1, 1, -1]
    for h in hc:
        assert h.end - h.start == pytest.approx(0.5, abs=1e-12)
        assert h.peak == pytest.approx(1.0, abs=1e-9)  # parabola through 3 samples
