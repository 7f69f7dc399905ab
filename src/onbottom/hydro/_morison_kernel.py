"""Numba kernel of the Morison + lift force model (private; contract: ``_force_dispatch``).

Per unit length, before reductions (DNV-RP-F109 (2017) §3.4 Morison form; relative velocity as
in CORUS-3D, Youssef & Cassidy 2014; docs/theory/storm_loads.md):

    F_Y = ½ ρ_w D C_D (U + V − ẏ)|U + V − ẏ| + ρ_w (π D²/4) C_M U̇
    F_Z = ½ ρ_w D C_L (U + V)²        (or (U − ẏ + V)² when ``params[P_LIFT_REL]`` != 0)

∂F_Y/∂ẏ = −ρ_w D C_D |U + V − ẏ|; ∂F_Z/∂ẏ = −ρ_w D C_L (U − ẏ + V) with relative-velocity lift,
else 0. The model is stateless: it uses no state slot and never writes ``state_new``.

Parameters (``params``, one row of :meth:`onbottom.hydro.force_model.MorisonLift.parameter_table`):
``P_CD`` C_D [-], ``P_CM`` C_M [-], ``P_CL`` C_L [-], ``P_LIFT_REL`` 1.0 for lift on the
relative velocity, 0.0 otherwise.

:func:`morison_twin` is the plain-Python twin (tests compare them to round-off).
"""

from __future__ import annotations

import math

from onbottom._jit import jitted_only
from onbottom.hydro._force_contract import FO_DFY_DYD, FO_DFZ_DYD, FO_FY, FO_FZ

P_CD = 0
P_CM = 1
P_CL = 2
P_LIFT_REL = 3
N_PARAMS = 4


@jitted_only
def morison_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Morison drag + inertia and lift (module docstring); stateless."""
    cd = params[P_CD]
    cm = params[P_CM]
    cl = params[P_CL]
    urel = u + vc - ydot
    drag = 0.5 * rho * d * cd * urel * abs(urel)
    inertia = 0.25 * math.pi * rho * d * d * cm * dudt
    out[FO_FY] = drag + inertia
    out[FO_DFY_DYD] = -rho * d * cd * abs(urel)
    if params[P_LIFT_REL] != 0.0:
        s = (u - ydot) + vc
        out[FO_FZ] = 0.5 * rho * d * cl * s * s
        out[FO_DFZ_DYD] = -rho * d * cl * s
    else:
        s = u + vc
        out[FO_FZ] = 0.5 * rho * d * cl * s * s
        out[FO_DFZ_DYD] = 0.0


def morison_twin(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Plain-Python twin of :func:`morison_kernel`, written from the formulas."""
    cd, cm, cl, rel = (float(params[i]) for i in (P_CD, P_CM, P_CL, P_LIFT_REL))
    w = u + vc - ydot
    out[FO_FY] = 0.5 * rho * d * cd * w * abs(w) + rho * math.pi * d**2 / 4.0 * cm * dudt
    out[FO_DFY_DYD] = -rho * d * cd * abs(w)
    s = u + vc - (ydot if rel else 0.0)
    out[FO_FZ] = 0.5 * rho * d * cl * s**2
    out[FO_DFZ_DYD] = -rho * d * cl * s if rel else 0.0
