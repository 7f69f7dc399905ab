"""Numba kernel of the wake force model (private; contract: :mod:`onbottom.hydro._force_contract`).

A documented **reconstruction** of the public structure of the wake model of Lambrakos, Chao,
Beckmann & Brannon (1987, Ocean Eng. 14(2):117–136) and its "Wake II" refinement (Soedigdo,
Lambrakos & Edge 1999, Ocean Eng. 26:431–462; Sabag, Edge & Soedigdo 2000, Ocean Eng.
27:1295–1319) — not the licensed coefficients. Equations and symbols:
``docs/theory/wake_model.md``. Per unit length, with the total ambient flow q = U + V:

    s        = ∫_{t_r}^{t} |q| dτ                      distance travelled since the last reversal
    U_w(s)   = U_w0 · exp(−s / (λ_w D)),  U_w0 = α_w · max|q| of the previous half-cycle
    U_e      = q + σ · U_w(s)                            σ = sign of the present half-cycle
    C_D(s)   = C_D∞ + a · ΔC_D · exp(−s / (λ_D D))     a = 0 before the first reversal, else 1
    C_L(s)   = C_L∞ + a · ΔC_L · exp(−s / (λ_L D))
    F_Y      = ½ ρ D C_D(s) (U_e − ẏ)|U_e − ẏ| + ρ (π D²/4) C_M U̇
    F_Z      = ½ ρ D C_L(s) U_e²        (or (U_e − ẏ)² when P_LIFT_RELATIVE = 1)

A reversal is a change of sign of q (the current is part of the flow: with |V| > max|U| the flow
never reverses and the coefficients stay at C_D∞, C_L∞). The instant of reversal inside a step is
found by linear interpolation of q; s is integrated by the trapezoidal rule. The history uses
the ambient flow only (not ẏ), so ∂F/∂ẏ comes from the relative velocity alone.

With α_w = ΔC_D = ΔC_L = 0 the forces are, bit for bit, those of
:func:`onbottom.hydro._morison_kernel.morison_kernel` with C_D = C_D∞, C_M, C_L = C_L∞ (both
lift options).

params (``P_*``, one row of :meth:`onbottom.hydro.wake.WakeModel.parameter_table`):
C_D∞, C_L∞, C_M, ΔC_D, ΔC_L, λ_D, λ_L, α_w, λ_w, lift-relative flag, reversal tolerance.

state (``S_*``; zeros = flow at rest, no history): see the constants below. Odd under mirror
(u, U̇, V, ẏ → −): S_Q and S_SIGN; every other slot is even.
"""

from __future__ import annotations

import math

from numba import njit

from onbottom.hydro._force_contract import FO_DFY_DYD, FO_DFZ_DYD, FO_FY, FO_FZ

P_CD_STEADY = 0
"""C_D∞ [-]: drag coefficient far from a reversal (steady flow)."""
P_CL_STEADY = 1
"""C_L∞ [-]: lift coefficient far from a reversal."""
P_CM = 2
"""C_M [-]: inertia coefficient on the ambient acceleration U̇ (Froude–Krylov + added mass)."""
P_DCD = 3
"""ΔC_D [-]: drag coefficient excess at a reversal."""
P_DCL = 4
"""ΔC_L [-]: lift coefficient excess at a reversal."""
P_LAMBDA_D = 5
"""λ_D [-]: relaxation distance of C_D in diameters."""
P_LAMBDA_L = 6
"""λ_L [-]: relaxation distance of C_L in diameters."""
P_WAKE_RATIO = 7
"""α_w [-]: wake velocity at a reversal / peak |U + V| of the previous half-cycle."""
P_LAMBDA_W = 8
"""λ_w [-]: decay distance of the wake velocity in diameters."""
P_LIFT_RELATIVE = 9
"""1.0: lift from the relative velocity U_e − ẏ; 0.0: from U_e (default, as Morison lift)."""
P_REVERSAL_TOL = 10
"""Relative flow below which a sign change is not a reversal: |q| <= tol · running peak [-]."""
N_PARAMS = 11

S_STARTED = 0
"""1.0 once the kernel has been evaluated (0.0: the first call, no time step yet)."""
S_T = 1
"""Time of the state [s]."""
S_Q = 2
"""Total ambient flow q = U + V at S_T [m/s] (odd)."""
S_SIGN = 3
"""Sign σ of the present half-cycle: +1, −1, or 0 while the flow has been at rest (odd)."""
S_DIST = 4
"""Distance s travelled by the flow since the last reversal [m]."""
S_PEAK = 5
"""Running peak of |q| in the present half-cycle [m/s]."""
S_WAKE0 = 6
"""Wake velocity U_w0 set at the last reversal [m/s]."""
S_RELAX = 7
"""Relaxation amplitude a: 0 before the first reversal, 1 after."""
S_N_REVERSALS = 8
"""Number of reversals so far [-] (diagnostic)."""
S_PREV_STROKE = 9
"""Distance travelled in the previous half-cycle [m] (diagnostic)."""
N_USED_STATE = 10


@njit(cache=True)
def _sign(x):
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return 0.0


@njit(cache=True)
def wake_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Wake-model forces per unit length and the state after this evaluation (see module doc)."""
    for i in range(state_old.shape[0]):
        state_new[i] = state_old[i]
    q = u + vc
    aq = abs(q)
    if state_old[S_STARTED] == 0.0:
        # first evaluation: the flow starts from rest, no history (no wake, no relaxation)
        sign = _sign(q)
        dist = 0.0
        peak = aq
        wake0 = 0.0
        relax = 0.0
    else:
        dt = t - state_old[S_T]
        if dt < 0.0:
            dt = 0.0
        q_old = state_old[S_Q]
        aq_old = abs(q_old)
        sign = state_old[S_SIGN]
        dist = state_old[S_DIST]
        peak = state_old[S_PEAK]
        wake0 = state_old[S_WAKE0]
        relax = state_old[S_RELAX]
        s_new = _sign(q)
        tol = params[P_REVERSAL_TOL] * max(peak, aq_old)
        if sign == 0.0:
            # at rest so far: the first motion sets the direction, it is not a reversal
            if aq > tol:
                sign = s_new
            dist = dist + 0.5 * (aq_old + aq) * dt
            peak = max(peak, aq)
        elif s_new != 0.0 and s_new != sign and aq > tol:
            # reversal inside the step: q crosses zero at the fraction f of the step
            denom = aq_old + aq
            f = aq_old / denom if q_old * sign > 0.0 else 0.0
            stroke = dist + 0.5 * aq_old * f * dt
            wake0 = params[P_WAKE_RATIO] * peak
            relax = 1.0
            state_new[S_N_REVERSALS] = state_old[S_N_REVERSALS] + 1.0
            state_new[S_PREV_STROKE] = stroke
            sign = s_new
            dist = 0.5 * aq * (1.0 - f) * dt
            peak = aq
        else:
            dist = dist + 0.5 * (aq_old + aq) * dt
            peak = max(peak, aq)
    state_new[S_STARTED] = 1.0
    state_new[S_T] = t
    state_new[S_Q] = q
    state_new[S_SIGN] = sign
    state_new[S_DIST] = dist
    state_new[S_PEAK] = peak
    state_new[S_WAKE0] = wake0
    state_new[S_RELAX] = relax

    x = dist / d
    cd = params[P_CD_STEADY] + relax * params[P_DCD] * math.exp(-x / params[P_LAMBDA_D])
    cl = params[P_CL_STEADY] + relax * params[P_DCL] * math.exp(-x / params[P_LAMBDA_L])
    uw = sign * (wake0 * math.exp(-x / params[P_LAMBDA_W]))
    ue = q + uw
    urel = ue - ydot
    drag = 0.5 * rho * d * cd * urel * abs(urel)
    inertia = 0.25 * math.pi * rho * d * d * params[P_CM] * dudt
    out[FO_FY] = drag + inertia
    out[FO_DFY_DYD] = -rho * d * cd * abs(urel)
    if params[P_LIFT_RELATIVE] != 0.0:
        s = ((u - ydot) + vc) + uw  # the Morison kernel's order: bit for bit when U_w = 0
        out[FO_FZ] = 0.5 * rho * d * cl * s * s
        out[FO_DFZ_DYD] = -rho * d * cl * s
    else:
        out[FO_FZ] = 0.5 * rho * d * cl * ue * ue
        out[FO_DFZ_DYD] = 0.0
