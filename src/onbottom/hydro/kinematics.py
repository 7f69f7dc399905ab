"""Linear wave kinematics at the seabed (pure numpy).

Linear (Airy) wave theory transfers a surface-elevation spectrum to the near-bed velocity
spectrum normal to the pipe: G(ω) = ω / sinh(k d), ω² = g k tanh(k d),
S_UU(ω) = G²(ω) S_ηη(ω); U_s = 2√M_0, T_u = 2π√(M_0/M_2)
(DNV-RP-F109 (2010/2017) §3.4.3; DNV-RP-C205 §3.2).
"""

from __future__ import annotations

import math

import numpy as np

from onbottom._validate import positive
from onbottom.constants import GRAVITY
from onbottom.hydro.spectra import spectral_moment

__all__ = [
    "near_bed_velocity_spectrum",
    "regular_wave_bed_velocity",
    "seabed_transfer",
    "significant_velocity",
    "wave_number",
    "zero_upcrossing_period",
]


def wave_number(omega: np.ndarray | float, depth: float) -> np.ndarray:
    """Wave number k [rad/m] solving ω² = g k tanh(k d) (Newton iterations, |error| < 1e-12).

    Parameters
    ----------
    omega : array or float
        Angular frequency ω [rad/s], >= 0.
    depth : float
        Water depth d [m], > 0.
    """
    positive("depth", depth)
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    k = np.zeros_like(w)
    pos = w > 0.0
    wv = w[pos]
    # explicit start (deep-water value blended with shallow-water value) then Newton
    w2 = wv**2
    kk = np.maximum(w2 / GRAVITY, wv / math.sqrt(GRAVITY * depth))
    # f = g k tanh(kd) − ω², f' = g tanh(kd) + g k d (1 − tanh²(kd)); the work arrays are
    # reused (in-place operations, the same operations in the same order)
    th, gk, f, df = (np.empty_like(kk) for _ in range(4))
    for _ in range(50):
        np.multiply(kk, depth, out=th)
        np.tanh(th, out=th)
        np.multiply(GRAVITY, kk, out=gk)
        np.multiply(gk, th, out=f)
        f -= w2
        np.multiply(th, th, out=df)
        np.subtract(1.0, df, out=df)
        gk *= depth
        df *= gk
        np.multiply(GRAVITY, th, out=gk)
        df += gk
        f /= df  # the Newton step
        kk -= f
        np.abs(f, out=f)
        np.maximum(kk, 1e-30, out=df)
        df *= 1e-14
        if np.all(f <= df):
            break
    k[pos] = kk
    return k


def seabed_transfer(omega: np.ndarray, depth: float) -> np.ndarray:
    """Transfer function G(ω) = ω / sinh(k d) from surface elevation to near-bed velocity [1/s]."""
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    k = wave_number(w, depth)
    g = np.zeros_like(w)
    pos = w > 0.0
    kd = k[pos] * depth
    # for very large kd sinh overflows: G → 0
    with np.errstate(over="ignore"):
        g[pos] = np.where(kd < 700.0, w[pos] / np.sinh(np.minimum(kd, 700.0)), 0.0)
    return g


def near_bed_velocity_spectrum(
    omega: np.ndarray, surface_spectrum: np.ndarray, depth: float
) -> np.ndarray:
    """Near-bed velocity spectrum S_UU(ω) = G²(ω) S_ηη(ω) [m²/s/rad] (DNV-RP-F109 §3.4.3)."""
    return seabed_transfer(omega, depth) ** 2 * np.asarray(surface_spectrum, dtype=float)


def significant_velocity(omega: np.ndarray, velocity_spectrum: np.ndarray) -> float:
    """Significant near-bed velocity U_s = 2√M_0 [m/s] (DNV-RP-F109 §3.4.3)."""
    return 2.0 * math.sqrt(spectral_moment(omega, velocity_spectrum, 0))


def zero_upcrossing_period(omega: np.ndarray, velocity_spectrum: np.ndarray) -> float:
    """Mean zero-up-crossing period T_u = 2π√(M_0/M_2) of the near-bed velocity [s]."""
    m0 = spectral_moment(omega, velocity_spectrum, 0)
    m2 = spectral_moment(omega, velocity_spectrum, 2)
    return 2.0 * math.pi * math.sqrt(m0 / m2)


def regular_wave_bed_velocity(height: float, period: float, depth: float) -> float:
    """Near-bed velocity amplitude U_w = π H / (T sinh(k d)) of a regular Airy wave [m/s].

    Parameters
    ----------
    height : float
        Wave height H [m], > 0.
    period : float
        Wave period T [s], > 0.
    depth : float
        Water depth d [m], > 0.
    """
    positive("height", height)
    positive("period", period)
    w = 2.0 * math.pi / period
    return float(0.5 * height * seabed_transfer(np.array([w]), depth)[0])
