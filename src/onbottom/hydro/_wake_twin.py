"""Plain-Python twin of :func:`onbottom.hydro._wake_kernel.wake_kernel` (private).

Written separately from the kernel (named steps instead of one loop body) with the same
arithmetic, so that the twin test compares two codings of the equations of
``docs/theory/wake_model.md``, to round-off.
"""

from __future__ import annotations

import math

from onbottom.hydro._force_contract import FO_DFY_DYD, FO_DFZ_DYD, FO_FY, FO_FZ
from onbottom.hydro._wake_kernel import (
    N_PREP,
    P_CD_STEADY,
    P_CL_STEADY,
    P_CM,
    P_DCD,
    P_DCL,
    P_LAMBDA_D,
    P_LAMBDA_L,
    P_LAMBDA_W,
    P_LIFT_RELATIVE,
    P_ONSET,
    P_REVERSAL_TOL,
    P_SLACK_EXPONENT,
    P_SLACK_THRESHOLD,
    P_WAKE_RATIO,
    PR_CD,
    PR_CL,
    PR_INERTIA,
    PR_Q,
    PR_W,
    S_CD_END,
    S_CL_END,
    S_DIST,
    S_N_REVERSALS,
    S_PEAK,
    S_PREV_STROKE,
    S_Q,
    S_RELAX,
    S_SIGN,
    S_STARTED,
    S_STRENGTH,
    S_T,
    S_TROUGH,
    S_W_END,
    S_WAKE0,
)

__all__ = ["wake_evaluate_py", "wake_kernel_py", "wake_prepare_py"]


def _smoothstep(x, lam):
    if lam <= 0.0 or x >= lam:
        return 1.0
    xi = x / lam
    return xi * xi * (3.0 - 2.0 * xi)


def _terms(params, h, x):
    """W, C_D excess and C_L excess at x = s/D for the history dict ``h``."""
    phi = _smoothstep(x, params[P_ONSET])
    old = 1.0 - phi
    w_new = h["sign"] * (h["wake0"] * math.exp(-x / params[P_LAMBDA_W]))
    d_new = h["relax"] * params[P_DCD] * math.exp(-x / params[P_LAMBDA_D])
    l_new = h["relax"] * params[P_DCL] * math.exp(-x / params[P_LAMBDA_L])
    return (
        phi * w_new + old * h["w_end"],
        phi * d_new + old * h["cd_end"],
        phi * l_new + old * h["cl_end"],
    )


def _strength(params, peak, trough):
    depth = (peak - trough) / peak
    r0 = params[P_SLACK_THRESHOLD]
    lin = (depth - r0) / (1.0 - r0)
    if lin <= 0.0:
        return 0.0
    return 1.0 if lin >= 1.0 else lin ** params[P_SLACK_EXPONENT]


def _history(params, so, t, q, d):
    """History dict after the flow q at time t, from the state ``so``; plus the event kind."""
    keys = (S_SIGN, S_DIST, S_PEAK, S_TROUGH, S_WAKE0, S_RELAX, S_STRENGTH)
    names = ("sign", "dist", "peak", "trough", "wake0", "relax", "strength")
    h = {n: so[k] for n, k in zip(names, keys, strict=True)}
    h.update(w_end=so[S_W_END], cd_end=so[S_CD_END], cl_end=so[S_CL_END])
    if so[S_STARTED] == 0.0:
        sign = math.copysign(1.0, q) if q != 0.0 else 0.0
        h.update(sign=sign, dist=0.0, peak=abs(q), trough=abs(q), wake0=0.0, relax=0.0)
        h["strength"] = 0.0
        return h, None, 0.0
    dt = max(t - so[S_T], 0.0)
    q_old = so[S_Q]
    tol = params[P_REVERSAL_TOL] * max(h["peak"], abs(q_old))
    new_sign = 0.0 if q == 0.0 else math.copysign(1.0, q)
    kind, x_end, after = None, 0.0, 0.0
    if h["sign"] == 0.0:
        if abs(q) > tol:
            h["sign"] = new_sign
    elif new_sign not in (0.0, h["sign"]) and abs(q) > tol:
        frac = abs(q_old) / (abs(q_old) + abs(q)) if q_old * h["sign"] > 0.0 else 0.0
        stroke = h["dist"] + 0.5 * abs(q_old) * frac * dt
        kind, x_end, after = "reversal", stroke / d, 0.5 * abs(q) * (1.0 - frac) * dt
        h["stroke"] = stroke
    elif abs(q) > abs(q_old) and abs(q_old) == h["trough"] and h["trough"] < h["peak"]:
        g = _strength(params, h["peak"], h["trough"])
        if g > h["strength"] * math.exp(-(h["dist"] / d) / params[P_LAMBDA_W]):
            kind, x_end, after = "slack", h["dist"] / d, 0.5 * (abs(q_old) + abs(q)) * dt
            h["stroke"] = h["dist"]
    if kind is None:
        h["dist"] = h["dist"] + 0.5 * (abs(q_old) + abs(q)) * dt
        if abs(q) > h["peak"]:
            h["peak"] = h["trough"] = abs(q)
        elif abs(q) < h["trough"]:
            h["trough"] = abs(q)
        return h, None, 0.0
    w_end, cd_end, cl_end = _terms(params, h, x_end)
    if kind == "reversal":
        g, swing, relax, sign = 1.0, h["peak"], 1.0, new_sign
    else:
        g = _strength(params, h["peak"], h["trough"])
        swing, relax, sign = h["peak"] - h["trough"], 0.0, h["sign"]
    h.update(w_end=w_end, cd_end=cd_end, cl_end=cl_end, sign=sign, relax=relax, strength=g)
    h.update(wake0=params[P_WAKE_RATIO] * swing * g, dist=after, peak=abs(q), trough=abs(q))
    return h, kind, h["stroke"]


def wake_kernel_py(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Plain-Python twin of :func:`onbottom.hydro._wake_kernel.wake_kernel`."""
    prep = [0.0] * N_PREP
    wake_prepare_py(params, state_old, t, u, dudt, vc, d, rho, state_new, prep)
    wake_evaluate_py(params, prep, u, vc, ydot, d, rho, out)


def wake_prepare_py(params, state_old, t, u, dudt, vc, d, rho, state_new, prep):
    """Plain-Python twin of :func:`onbottom.hydro._wake_kernel.wake_prepare`."""
    q = u + vc
    h, kind, stroke = _history(params, state_old, t, q, d)
    state_new[:] = state_old
    if kind is not None:
        state_new[S_PREV_STROKE] = stroke
    if kind == "reversal":
        state_new[S_N_REVERSALS] = state_old[S_N_REVERSALS] + 1.0
    state_new[S_STARTED] = 1.0
    state_new[S_T] = t
    state_new[S_Q] = q
    for key, slot in (
        ("sign", S_SIGN),
        ("dist", S_DIST),
        ("peak", S_PEAK),
        ("trough", S_TROUGH),
        ("wake0", S_WAKE0),
        ("relax", S_RELAX),
        ("strength", S_STRENGTH),
        ("w_end", S_W_END),
        ("cd_end", S_CD_END),
        ("cl_end", S_CL_END),
    ):
        state_new[slot] = h[key]

    u_wake, ex_d, ex_l = _terms(params, h, h["dist"] / d)
    prep[PR_Q] = q
    prep[PR_W] = u_wake
    prep[PR_CD] = params[P_CD_STEADY] + ex_d
    prep[PR_CL] = params[P_CL_STEADY] + ex_l
    prep[PR_INERTIA] = 0.25 * math.pi * rho * d * d * params[P_CM] * dudt
    return True


def wake_evaluate_py(params, prep, u, vc, ydot, d, rho, out):
    """Plain-Python twin of :func:`onbottom.hydro._wake_kernel.wake_evaluate`."""
    u_wake, c_drag, c_lift = prep[PR_W], prep[PR_CD], prep[PR_CL]
    u_eff = prep[PR_Q] + u_wake
    u_rel = u_eff - ydot
    out[FO_FY] = 0.5 * rho * d * c_drag * u_rel * abs(u_rel) + prep[PR_INERTIA]
    out[FO_DFY_DYD] = -rho * d * c_drag * abs(u_rel)
    relative = params[P_LIFT_RELATIVE] != 0.0
    u_lift = ((u - ydot) + vc) + u_wake if relative else u_eff
    out[FO_FZ] = 0.5 * rho * d * c_lift * u_lift * u_lift
    out[FO_DFZ_DYD] = -rho * d * c_lift * u_lift if relative else 0.0
