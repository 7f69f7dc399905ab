"""DNV-RP-F109 load reduction factors (2017 edition, Eqs 3.17–3.22; 2010 edition §3.4.6).

r_tot,y = r_perm,y · r_pen,y · r_tr,y ;  r_tot,z = r_perm,z · r_pen,z · r_tr,z      (Eq 3.17)
r_perm,y = 1 ;  r_perm,z = 0.7 (permeable seabed; vertical load only)                (Eq 3.18)
r_pen,y = 1 − 1.4 z_p/D ≥ 0.3                                                      (Eq 3.19)
r_pen,z = 1 for z_p/D ≤ 0.1 ;  1 − 1.3 (z_p/D − 0.1) ≥ 0 otherwise                  (Eq 3.20)
r_tr,y = 1 − 0.18 (θ − 5)^0.25 (z_t/D)^0.42                                        (Eq 3.21)
r_tr,z = 1 − 0.14 (θ − 5)^0.43 (z_t/D)^0.46                                        (Eq 3.22)

z_p penetration, z_t trench depth, θ trench wall angle [deg]. Validity: 5° ≤ θ ≤ 45°,
z_t/D ≤ 1; r_pen for z_p/D ≤ 0.5 (DNV-RP-F109 (2017) Eqs 3.17–3.22).
The plain-numpy functions here are the twins of the numba kernels in
:mod:`onbottom.hydro._load_kernels`. :class:`LoadReductions` is the time-domain choice of the
storm-section and pipeline solvers, which apply r_y, r_z to the force model's output
(:mod:`onbottom.hydro._force_dispatch`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from onbottom._validate import in_range, non_negative, warn_outside

__all__ = [
    "PERMEABLE_SEABED_REDUCTION_Z",
    "LoadReductions",
    "penetration_reduction",
    "trench_reduction",
]

PERMEABLE_SEABED_REDUCTION_Z = 0.7
"""r_perm,z [-] for a permeable seabed (DNV-RP-F109 (2017) Eq 3.18); r_perm,y = 1."""

_SOURCE = "DNV-RP-F109 (2017) Eqs 3.19–3.22"


def penetration_reduction(z_over_d: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """Load reductions for penetration (r_pen,y, r_pen,z) [-] (F109 (2017) Eqs 3.19–3.20).

    Parameters
    ----------
    z_over_d : array or float
        Pipe penetration over outer diameter z_p/D [-], >= 0 (valid up to 0.5; beyond, an
        :class:`~onbottom.errors.OutOfRangeWarning` and the bounded formulas are used).
    """
    z = np.asarray(z_over_d, dtype=float)
    if z.ndim == 0:
        non_negative("z_over_d", float(z))
    elif np.any(~np.isfinite(z)) or np.any(z < 0.0):
        bad = z[~np.isfinite(z) | (z < 0.0)][0]
        non_negative("z_over_d", float(bad))
    if z.size:
        warn_outside("z_p/D", float(np.max(z)), 0.0, 0.5, _SOURCE)
    r_y = np.maximum(1.0 - 1.4 * z, 0.3)
    r_z = np.where(z <= 0.1, 1.0, np.maximum(1.0 - 1.3 * (z - 0.1), 0.0))
    return r_y, r_z


def trench_reduction(trench_depth_over_d: float, wall_angle_deg: float) -> tuple[float, float]:
    """Load reductions for a trench (r_tr,y, r_tr,z) [-] (F109 (2017) Eqs 3.21–3.22).

    Parameters
    ----------
    trench_depth_over_d : float
        Trench depth over outer diameter z_t/D [-], in [0, 1]; 0 → no trench (1, 1).
    wall_angle_deg : float
        Trench wall angle θ [deg], in [5, 45].
    """
    zt = in_range("trench_depth_over_d", trench_depth_over_d, 0.0, 1.0)
    th = in_range("wall_angle_deg", wall_angle_deg, 5.0, 45.0)
    if zt == 0.0:
        return 1.0, 1.0
    r_y = 1.0 - 0.18 * (th - 5.0) ** 0.25 * zt**0.42
    r_z = 1.0 - 0.14 * (th - 5.0) ** 0.43 * zt**0.46
    return float(r_y), float(r_z)


@dataclass(frozen=True, kw_only=True, slots=True)
class LoadReductions:
    """DNV-RP-F109 (2017) load reductions applied in the time domain (Eqs 3.17–3.22).

    Parameters
    ----------
    permeable_seabed : bool
        r_perm,z = 0.7 (Eq 3.18) when True (sand, rock); 1 for clay.
    penetration : bool
        Apply r_pen,y, r_pen,z (Eqs 3.19–3.20) from the soil's current penetration.
    trench_depth_over_d : float
        z_t/D [-], in [0, 1]; 0 = no trench.
    trench_angle_deg : float
        Trench wall angle θ [deg], in [5, 45] (used when z_t > 0).
    """

    permeable_seabed: bool = True
    penetration: bool = True
    trench_depth_over_d: float = 0.0
    trench_angle_deg: float = 45.0

    def __post_init__(self) -> None:
        in_range("LoadReductions.trench_depth_over_d", self.trench_depth_over_d, 0.0, 1.0)
        in_range("LoadReductions.trench_angle_deg", self.trench_angle_deg, 5.0, 45.0)

    def constant_factors(self) -> tuple[float, float]:
        """(r_perm,y·r_tr,y, r_perm,z·r_tr,z) [-], the parts that do not change with z."""
        ry, rz = trench_reduction(self.trench_depth_over_d, self.trench_angle_deg)
        if self.permeable_seabed:
            rz *= PERMEABLE_SEABED_REDUCTION_Z
        return ry, rz
