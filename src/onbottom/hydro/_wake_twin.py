"""Plain-Python twin of :func:`onbottom.hydro._wake_kernel.wake_kernel` (private).

Written separately from the kernel (named steps instead of one loop body) with the same
arithmetic, so that the twin test compares two codings of the equations of
``docs/theory/wake_model.md``, to round-off.
"""

from __future__ import annotations

import math

from onbottom.hydro._force_contract import FO_DFY_DYD, FO_DFZ_DYD, FO_FY, FO_FZ
from onbottom.hydro._wake_kernel import (
    P_CD_STEADY,
    P_CL_STEADY,
    P_CM,
    P_DCD,
    P_DCL,
    P_LAMBDA_D,
    P_LAMBDA_L,
    P_LAMBDA_W,
    P_LIFT_RELATIVE,
    P_REVERSAL_TOL,
    P_WAKE_RATIO,
    S_DIST,
    S_N_REVERSALS,
    S_PEAK,
    S_PREV_STROKE,
    S_Q,
    S_RELAX,
    S_SIGN,
    S_STARTED,
    S_T,
    S_WAKE0,
)

__all__ = ["wake_kernel_py"]


def _history(params, state_old, t, q):
    """(sign, distance, peak, wake0, relax, reversed, stroke) after the flow q at time t."""
    if state_old[S_STARTED] == 0.0:
        return math.copysign(1.0, q) if q != 0.0 else 0.0, 0.0, abs(q), 0.0, 0.0, False, 0.0
    dt = max(t - state_old[S_T], 0.0)
    q_old = state_old[S_Q]
    sign = state_old[S_SIGN]
    dist, peak = state_old[S_DIST], state_old[S_PEAK]
    wake0, relax = state_old[S_WAKE0], state_old[S_RELAX]
    tol = params[P_REVERSAL_TOL] * max(peak, abs(q_old))
    new_sign = 0.0 if q == 0.0 else math.copysign(1.0, q)
    travelled = 0.5 * (abs(q_old) + abs(q)) * dt
    if sign == 0.0:
        return (
            (new_sign if abs(q) > tol else 0.0),
            dist + travelled,
            max(peak, abs(q)),
            (wake0),
            relax,
            False,
            0.0,
        )
    if new_sign not in (0.0, sign) and abs(q) > tol:
        frac = abs(q_old) / (abs(q_old) + abs(q)) if q_old * sign > 0.0 else 0.0
        stroke = dist + 0.5 * abs(q_old) * frac * dt
        after = 0.5 * abs(q) * (1.0 - frac) * dt
        return new_sign, after, abs(q), params[P_WAKE_RATIO] * peak, 1.0, True, stroke
    return sign, dist + travelled, max(peak, abs(q)), wake0, relax, False, 0.0


def wake_kernel_py(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Plain-Python twin of :func:`onbottom.hydro._wake_kernel.wake_kernel`."""
    q = u + vc
    sign, dist, peak, wake0, relax, reversed_, stroke = _history(params, state_old, t, q)
    state_new[:] = state_old
    if reversed_:
        state_new[S_N_REVERSALS] = state_old[S_N_REVERSALS] + 1.0
        state_new[S_PREV_STROKE] = stroke
    state_new[S_STARTED] = 1.0
    state_new[S_T] = t
    state_new[S_Q] = q
    state_new[S_SIGN] = sign
    state_new[S_DIST] = dist
    state_new[S_PEAK] = peak
    state_new[S_WAKE0] = wake0
    state_new[S_RELAX] = relax

    s_over_d = dist / d
    c_drag = params[P_CD_STEADY] + relax * params[P_DCD] * math.exp(-s_over_d / params[P_LAMBDA_D])
    c_lift = params[P_CL_STEADY] + relax * params[P_DCL] * math.exp(-s_over_d / params[P_LAMBDA_L])
    u_wake = wake0 * math.exp(-s_over_d / params[P_LAMBDA_W])
    u_eff = q + sign * u_wake
    u_rel = u_eff - ydot
    out[FO_FY] = 0.5 * rho * d * c_drag * u_rel * abs(u_rel) + (
        0.25 * math.pi * rho * d * d * params[P_CM] * dudt
    )
    out[FO_DFY_DYD] = -rho * d * c_drag * abs(u_rel)
    relative = params[P_LIFT_RELATIVE] != 0.0
    u_lift = ((u - ydot) + vc) + sign * u_wake if relative else u_eff
    out[FO_FZ] = 0.5 * rho * d * c_lift * u_lift * u_lift
    out[FO_DFZ_DYD] = -rho * d * c_lift * u_lift if relative else 0.0
