"""Wave spectra (pure numpy, array in / array out).

JONSWAP spectrum as given in DNV-RP-C205 (2010/2019) §3.5.5 and used by DNV-RP-F109
(2010/2017) §3.4.3, with the DNV rule for the peak-enhancement factor γ.

Symbols: ω angular frequency [rad/s], H_s significant wave height [m], T_p peak period [s],
S_ηη(ω) one-sided surface-elevation spectrum [m²·s/rad].
"""

from __future__ import annotations

import math

import numpy as np

from onbottom._validate import in_range, positive
from onbottom.constants import GRAVITY

__all__ = ["jonswap", "jonswap_peak_enhancement", "pierson_moskowitz", "spectral_moment"]


def jonswap_peak_enhancement(hs: float, tp: float) -> float:
    """DNV rule for the JONSWAP peak-enhancement factor γ [-].

    φ = T_p/√H_s (T_p in s, H_s in m); γ = 5 for φ ≤ 3.6, exp(5.75 − 1.15 φ) for
    3.6 < φ < 5, 1 for φ ≥ 5 (DNV-RP-C205 §3.5.5.5; DNV-RP-F109 §3.4.3).

    Parameters
    ----------
    hs : float
        Significant wave height H_s [m], > 0.
    tp : float
        Peak period T_p [s], > 0.
    """
    positive("hs", hs)
    positive("tp", tp)
    phi = tp / math.sqrt(hs)
    if phi <= 3.6:
        return 5.0
    if phi < 5.0:
        return math.exp(5.75 - 1.15 * phi)
    return 1.0


def jonswap(omega: np.ndarray, hs: float, tp: float, gamma: float | None = None) -> np.ndarray:
    """JONSWAP surface-elevation spectrum S_ηη(ω) [m²·s/rad].

    S(ω) = α g² ω⁻⁵ exp(−1.25 (ω/ω_p)⁻⁴) γ^exp(−(ω−ω_p)²/(2σ²ω_p²)),
    α = (5/16) H_s² ω_p⁴ / g² · (1 − 0.287 ln γ), σ = 0.07 (ω ≤ ω_p) / 0.09 (ω > ω_p)
    (DNV-RP-C205 §3.5.5, Goda's normalisation of α, so that m0 ≈ H_s²/16 for 1 ≤ γ ≤ 7).

    Parameters
    ----------
    omega : array
        Angular frequencies ω [rad/s], >= 0 (S = 0 at ω = 0).
    hs : float
        Significant wave height H_s [m], > 0.
    tp : float
        Peak period T_p [s], > 0.
    gamma : float or None
        Peak-enhancement factor γ [-] in [1, 7]; None → :func:`jonswap_peak_enhancement`.
    """
    positive("hs", hs)
    positive("tp", tp)
    if gamma is None:
        gamma = jonswap_peak_enhancement(hs, tp)
    in_range("gamma", gamma, 1.0, 7.0)
    w = np.asarray(omega, dtype=float)
    wp = 2.0 * math.pi / tp
    alpha = 5.0 / 16.0 * hs**2 * wp**4 / GRAVITY**2 * (1.0 - 0.287 * math.log(gamma))
    s = np.zeros_like(w)
    pos = w > 0.0
    wv = w[pos]
    sigma = np.where(wv <= wp, 0.07, 0.09)
    peak = gamma ** np.exp(-((wv - wp) ** 2) / (2.0 * sigma**2 * wp**2))
    s[pos] = alpha * GRAVITY**2 * wv**-5.0 * np.exp(-1.25 * (wv / wp) ** -4.0) * peak
    return s


def pierson_moskowitz(omega: np.ndarray, hs: float, tp: float) -> np.ndarray:
    """Pierson–Moskowitz spectrum = JONSWAP with γ = 1 [m²·s/rad] (DNV-RP-C205 §3.5.5)."""
    return jonswap(omega, hs, tp, gamma=1.0)


def spectral_moment(omega: np.ndarray, spectrum: np.ndarray, n: int) -> float:
    """n-th spectral moment M_n = ∫ ωⁿ S(ω) dω (trapezoidal rule) [units of S·ωⁿ⁺¹]."""
    w = np.asarray(omega, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    return float(np.trapezoid(w**n * s, w))
