"""Directional spreading of waves: the reduction factor R_D and cos^s directions.

Wave energy spreading (DNV-RP-F109 (2010/2017) Eq 3.8, the cos^s form of DNV-RP-C205 §3.5.8):

    D_w(θ) = Γ(1 + s/2) / (√π Γ(½ + s/2)) · cos^s(θ),   |θ| < π/2

Reduction of the significant velocity normal to the pipe (DNV-RP-F109 §3.4.3):

    R_D = √( ∫ D_w(θ) sin²(θ_w − θ) dθ ),   U_s ← R_D U_s

θ_w is the angle between the main wave direction and the pipe axis. Expanding sin²(θ_w − θ)
and using the symmetry of D_w and E[cos²θ] = (s + 1)/(s + 2) gives the closed form used here
(exact; the unit test compares it with direct quadrature of the integral)

    R_D² = sin²θ_w (s + 1)/(s + 2) + cos²θ_w /(s + 2)

Long-crested waves (s → ∞; ``s=None`` or 0 here, as in the case-file layout) give
R_D = |sin θ_w|. F109 suggests s = 2–8; the exponent is that of cos^s (not cos^2s).

R_D depends on θ_w only through the line of the waves: θ_w is folded into [0°, 90°] first, so
mirrored directions (θ_w, 180° − θ_w, θ_w + 180°, −θ_w) give bitwise the same value. The sign
of the flow normal to the pipe is :func:`direction_sign`.

For a single-summation short-crested sea (one direction per frequency component,
:mod:`onbottom.hydro.short_crested`) :func:`directions_cos_s` draws the directions from D_w.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import in_range

__all__ = ["direction_sign", "directions_cos_s", "spreading_factor", "spreading_function"]


def spreading_function(theta: ArrayLike, s: float) -> NDArray:
    """D_w(θ) [1/rad] (F109 Eq 3.8), zero for |θ| >= π/2; ``s`` [-] > 0."""
    s = in_range("spreading_s", s, 0.0, 1.0e3, low_inclusive=False)
    th = np.asarray(theta, dtype=float)
    norm = math.exp(math.lgamma(1.0 + s / 2.0) - math.lgamma(0.5 + s / 2.0)) / math.sqrt(math.pi)
    c = np.cos(th)
    return np.where(np.abs(th) < 0.5 * math.pi, norm * np.abs(c) ** s, 0.0)


def spreading_factor(spreading_s: float | None, *, wave_direction_deg: ArrayLike = 90.0) -> NDArray:
    """R_D [-]: spreading and direction factor on U_s (DNV-RP-F109 §3.4.3, closed form).

    Parameters
    ----------
    spreading_s : float or None
        Spreading exponent s of cos^s [-], in [0, 1000]; None or 0 → long-crested
        (R_D = |sin θ_w|).
    wave_direction_deg : array_like
        θ_w, angle between wave direction and pipe axis [deg] (90 = waves normal to the pipe);
        any finite value (folded into [0°, 90°]). Keyword-only, so that the order of the two
        arguments cannot be mistaken.

    Returns
    -------
    ndarray
        R_D [-] in [0, 1], the shape of ``wave_direction_deg`` (0-d for a scalar).
    """
    deg = np.asarray(wave_direction_deg, dtype=float)
    bad = np.flatnonzero(~np.isfinite(deg))
    if bad.size:
        in_range("wave_direction_deg", float(deg.flat[bad[0]]), -360.0, 360.0)
    folded = np.fmod(np.abs(deg), 180.0)
    folded = np.where(folded > 90.0, 180.0 - folded, folded)
    sin_w = np.sin(np.radians(folded))
    if spreading_s is None or spreading_s == 0:
        return np.abs(sin_w)
    s = in_range("spreading_s", spreading_s, 0.0, 1.0e3)
    sin2 = sin_w**2
    return np.sqrt(sin2 * (s + 1.0) / (s + 2.0) + (1.0 - sin2) / (s + 2.0))


def direction_sign(direction_deg: float) -> float:
    """Sign of the flow normal to the pipe, sign(sin θ_w) [-]; +1 along the pipe axis.

    Waves travelling towards −y (sin θ_w < 0) give −U; θ_w [deg].
    """
    sin_w = math.sin(math.radians(direction_deg))
    if abs(sin_w) < 1e-12:
        return 1.0
    return math.copysign(1.0, sin_w)


def directions_cos_s(uniform: np.ndarray, mean_deg: float, spreading_s: float) -> np.ndarray:
    """Directions [rad] θ = θ_m + δ with δ from D_w(δ) ∝ cos^s δ, |δ| < π/2 (F109 Eq 3.8).

    Inverse-CDF transform (4001-point trapezoidal grid) of the uniform numbers ``uniform`` in
    [0, 1); ``mean_deg`` θ_m [deg]; ``spreading_s`` [-] = 0 → every θ = θ_m (long-crested).
    """
    mean = math.radians(mean_deg)
    u = np.asarray(uniform, dtype=float)
    if spreading_s <= 0.0:
        return np.full(u.shape, mean)
    g = np.linspace(-0.5 * math.pi, 0.5 * math.pi, 4001)
    pdf = np.cos(g) ** spreading_s
    cdf = np.concatenate(([0.0], np.cumsum(0.5 * (pdf[1:] + pdf[:-1]) * np.diff(g))))
    cdf /= cdf[-1]
    return mean + np.interp(u, cdf, g)
