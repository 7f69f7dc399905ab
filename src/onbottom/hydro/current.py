"""Steady current at pipe level (DNV-RP-F109 (2010/2017) §3.3, Eq 3.3, log profile).

The mean current normal to the pipe over its diameter D is
V = V(z_r) · [(1 + z_0/D) ln(D/z_0 + 1) − 1] / ln(z_r/z_0 + 1) · sin θ_c,
the exact mean of the logarithmic profile V(z) ∝ ln((z + z_0)/z_0) over 0 ≤ z ≤ D.
Seabed roughness z_0 from DNV-RP-F109 Table 3-1.
"""

from __future__ import annotations

import math

from onbottom._validate import in_range, positive

__all__ = ["SEABED_ROUGHNESS", "mean_current_over_pipe"]

SEABED_ROUGHNESS: dict[str, float] = {
    "silt and clay": 5.0e-6,
    "fine sand": 1.0e-5,
    "medium sand": 4.0e-5,
    "coarse sand": 1.0e-4,
    "gravel": 3.0e-4,
    "pebble": 2.0e-3,
    "cobble": 1.0e-2,
    "boulder": 4.0e-2,
}
"""Seabed roughness z_0 [m] by seabed type (DNV-RP-F109 Table 3-1)."""


def mean_current_over_pipe(
    reference_velocity: float,
    reference_height: float,
    diameter: float,
    roughness: float,
    angle_deg: float = 90.0,
) -> float:
    """Mean current velocity over the pipe diameter, normal to the pipe [m/s] (F109 Eq 3.3).

    Parameters
    ----------
    reference_velocity : float
        Current V(z_r) at the reference height [m/s], >= 0.
    reference_height : float
        Reference height above the seabed z_r [m], > 0.
    diameter : float
        Pipe outer diameter D [m], > 0.
    roughness : float
        Seabed roughness z_0 [m], > 0 (see :data:`SEABED_ROUGHNESS`).
    angle_deg : float
        Angle θ_c between the current and the pipe axis [deg], in [0, 180] (90 = normal).
    """
    in_range("reference_velocity", reference_velocity, 0.0, 10.0)
    zr = positive("reference_height", reference_height)
    d = positive("diameter", diameter)
    z0 = positive("roughness", roughness)
    in_range("angle_deg", angle_deg, 0.0, 180.0)
    num = (1.0 + z0 / d) * math.log(d / z0 + 1.0) - 1.0
    return reference_velocity * num / math.log(zr / z0 + 1.0) * math.sin(math.radians(angle_deg))
