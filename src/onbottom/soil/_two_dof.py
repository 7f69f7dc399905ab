"""Helpers of the two-DOF (second-form) soil contract (private; rules 2.1–2.7 of
:mod:`onbottom.soil.base`)."""

from __future__ import annotations

import math

from onbottom._jit import numba_njit as njit
from onbottom.soil.base import OUT2_DH_DV, OUT2_DZ_DV, OUT2_DZ_DY, OUT_TANGENT


@njit(cache=True)
def stiffness_from_hybrid(out, k):
    """Displacement-controlled stiffness of a two-DOF kernel result, by partial inversion.

    ``out``: a kernel's output of length >= ``OUT2_SIZE`` holding the hybrid tangent of (H, z)
    with respect to (y, V) (rule 2.2). Writes into ``k`` (2 × 2) the tangent of (H, V) with
    respect to (y, z), for a solver with a vertical degree of freedom::

        ∂V/∂z = 1/(∂z/∂V)            ∂V/∂y = −(∂z/∂y)/(∂z/∂V)
        ∂H/∂z = (∂H/∂V)/(∂z/∂V)      ∂H/∂y = ∂H/∂y|_V − (∂H/∂V)(∂z/∂y)/(∂z/∂V)

    Row 0 is H, row 1 is V; column 0 is y, column 1 is z [N/m²]. Returns False (and leaves
    ``k`` unchanged) when ∂z/∂V <= 0: the model is rigid vertically there, no finite
    stiffness exists.
    """
    dz_dv = out[OUT2_DZ_DV]
    if not (dz_dv > 0.0) or not math.isfinite(dz_dv):
        return False
    dh_dy = out[OUT_TANGENT]
    dh_dv = out[OUT2_DH_DV]
    dz_dy = out[OUT2_DZ_DY]
    k[1, 1] = 1.0 / dz_dv
    k[1, 0] = -dz_dy / dz_dv
    k[0, 1] = dh_dv / dz_dv
    k[0, 0] = dh_dy - dh_dv * dz_dy / dz_dv
    return True
