"""Numba kernels of the DNV-RP-F109 penetration load reductions (private).

Shared by the storm-section solver and the pipeline FE, which multiply the force model's
output (:mod:`onbottom.hydro._force_dispatch`) by r_y = r_const,y · r_pen,y(z/D) and
r_z = r_const,z · r_pen,z(z/D). Plain-Python twin:
:func:`onbottom.hydro.reductions.penetration_reduction`; tests compare them. The Morison
force law is in :mod:`onbottom.hydro._morison_kernel`.
"""

from __future__ import annotations

from onbottom._jit import jitted_only


@jitted_only
def penetration_reduction_y(z_over_d):
    """r_pen,y = max(1 − 1.4 z_p/D, 0.3) (DNV-RP-F109 (2017) Eq 3.19); 1 for z_p <= 0."""
    if z_over_d <= 0.0:
        return 1.0
    return max(1.0 - 1.4 * z_over_d, 0.3)


@jitted_only
def penetration_reduction_z(z_over_d):
    """r_pen,z = 1 for z_p/D <= 0.1, else max(1 − 1.3 (z_p/D − 0.1), 0) (F109 (2017) Eq 3.20)."""
    if z_over_d <= 0.1:
        return 1.0
    return max(1.0 - 1.3 * (z_over_d - 0.1), 0.0)
