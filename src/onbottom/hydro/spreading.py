"""Directional spreading of waves and the reduction factor R_D (DNV-RP-F109 §3.4.3).

Wave energy spreading (F109 (2010/2017) Eq 3.8, the cos^s form of DNV-RP-C205 §3.5.8):

    D_w(θ) = Γ(1 + s/2) / (√π Γ(½ + s/2)) · cos^s(θ),   |θ| < π/2

Reduction of the significant velocity normal to the pipe (F109 §3.4.3):

    R_D = √( ∫ D_w(θ) sin²(θ_w − θ) dθ ),   U_s ← R_D U_s

θ_w is the angle between the main wave direction and the pipe axis. Expanding sin²(θ_w − θ)
and using the symmetry of D_w and E[cos²θ] = (s + 1)/(s + 2) gives the closed form used here

    R_D² = sin²θ_w (s + 1)/(s + 2) + cos²θ_w /(s + 2)

(the unit test compares it with direct quadrature of the integral). Long-crested waves
(s → ∞; ``s=None`` or 0 here, as in the case-file layout) give R_D = |sin θ_w|.
F109 suggests s = 2–8; the exponent is that of cos^s (not cos^2s).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import in_range

__all__ = ["spreading_factor", "spreading_function"]


def spreading_function(theta: ArrayLike, s: float) -> NDArray:
    """D_w(θ) [1/rad] (F109 Eq 3.8), zero for |θ| >= π/2; ``s`` [-] > 0."""
    s = in_range("spreading_s", s, 0.0, 1.0e3, low_inclusive=False)
    th = np.asarray(theta, dtype=float)
    norm = math.exp(math.lgamma(1.0 + s / 2.0) - math.lgamma(0.5 + s / 2.0)) / math.sqrt(math.pi)
    c = np.cos(th)
    return np.where(np.abs(th) < 0.5 * math.pi, norm * np.abs(c) ** s, 0.0)


def spreading_factor(s: float | None, wave_direction_deg: ArrayLike = 90.0) -> NDArray:
    """R_D [-]: spreading and direction factor on U_s (DNV-RP-F109 §3.4.3).

    Parameters
    ----------
    s : float or None
        Spreading exponent s of cos^s [-], in [0, 1000]; None or 0 → long-crested.
    wave_direction_deg : array_like
        θ_w, angle between wave direction and pipe axis [deg] (90 = waves normal to the pipe).
    """
    th = np.radians(np.asarray(wave_direction_deg, dtype=float))
    if not np.all(np.isfinite(th)):
        in_range("wave_direction_deg", float(np.asarray(wave_direction_deg).flat[0]), -360, 360)
    sin2 = np.sin(th) ** 2
    if s is None or s == 0:
        return np.sqrt(sin2)
    s = in_range("spreading_s", s, 0.0, 1.0e3)
    return np.sqrt(sin2 * (s + 1.0) / (s + 2.0) + (1.0 - sin2) / (s + 2.0))
