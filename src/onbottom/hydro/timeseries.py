"""Seeded random-phase synthesis of wave and near-bed velocity time series (pure numpy).

A one-sided spectrum S(ω) is discretised in N equal bands Δω; the signal is
x(t) = Σ a_j cos(ω_j t + φ_j), a_j = √(2 S(ω_j) Δω), φ_j uniform on [0, 2π) drawn from
``numpy.random.default_rng(seed)`` (the standard random-phase method, e.g. DNV-RP-C205 §3.5.11;
the variance of x equals M_0 of the discretised spectrum). The same seed gives the same series.
"""

from __future__ import annotations

import math

import numpy as np

from onbottom._validate import positive
from onbottom.hydro.kinematics import seabed_transfer
from onbottom.hydro.spectra import jonswap

__all__ = ["near_bed_velocity_series", "random_phase_series", "regular_velocity_series"]


def random_phase_series(
    omega: np.ndarray, spectrum: np.ndarray, time: np.ndarray, seed: int | None
) -> tuple[np.ndarray, np.ndarray]:
    """Synthesise x(t) and dx/dt from a one-sided spectrum by random phases.

    Parameters
    ----------
    omega : array
        Equally spaced band-centre frequencies ω_j [rad/s], > 0.
    spectrum : array
        S(ω_j) [x²·s/rad].
    time : array
        Times t [s].
    seed : int or None
        Seed of ``numpy.random.default_rng`` for the phases.

    Returns
    -------
    x, dxdt : arrays
        The signal [x] and its time derivative [x/s].
    """
    w = np.asarray(omega, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    t = np.asarray(time, dtype=float)
    dw = float(w[1] - w[0]) if w.size > 1 else 1.0
    amp = np.sqrt(2.0 * np.maximum(s, 0.0) * dw)
    phase = np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, w.size)
    arg = np.outer(t, w) + phase
    x = np.cos(arg) @ amp
    dxdt = -np.sin(arg) @ (amp * w)
    return x, dxdt


def near_bed_velocity_series(
    time: np.ndarray,
    hs: float,
    tp: float,
    depth: float,
    *,
    gamma: float | None = None,
    seed: int | None = 0,
    n_components: int = 256,
    omega_max_factor: float = 5.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Near-bed wave velocity U(t) and dU/dt normal to the pipe from a JONSWAP sea state.

    The JONSWAP spectrum (:func:`onbottom.hydro.spectra.jonswap`) is transferred to the seabed
    with linear wave theory (:func:`onbottom.hydro.kinematics.seabed_transfer`) and synthesised
    with seeded random phases (long-crested waves travelling normal to the pipe).

    Parameters
    ----------
    time : array
        Times [s].
    hs, tp : float
        Significant wave height [m] and peak period [s], > 0.
    depth : float
        Water depth [m], > 0.
    gamma : float or None
        JONSWAP γ [-]; None → DNV rule.
    seed : int or None
        Random-phase seed.
    n_components : int
        Number of frequency bands, >= 8.
    omega_max_factor : float
        Upper frequency as a multiple of ω_p [-], > 1.
    """
    positive("tp", tp)
    if n_components < 8:
        raise ValueError("n_components must be >= 8")
    wp = 2.0 * math.pi / tp
    dw = omega_max_factor * wp / n_components
    w = dw * (np.arange(n_components) + 0.5)
    s_uu = seabed_transfer(w, depth) ** 2 * jonswap(w, hs, tp, gamma)
    return random_phase_series(w, s_uu, time, seed)


def regular_velocity_series(
    time: np.ndarray, amplitude: float, period: float, phase: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """Regular near-bed velocity U(t) = U_w sin(2πt/T + φ) and dU/dt [m/s, m/s²]."""
    t = np.asarray(time, dtype=float)
    w = 2.0 * math.pi / positive("period", period)
    return amplitude * np.sin(w * t + phase), amplitude * w * np.cos(w * t + phase)
