"""Numba kernel of the wake force model (private; contract: :mod:`onbottom.hydro._force_contract`).

A documented **reconstruction** of the public structure of the wake model of Lambrakos, Chao,
Beckmann & Brannon (1987, Ocean Eng. 14(2):117–136) and its "Wake II" refinement (Soedigdo,
Lambrakos & Edge 1999, Ocean Eng. 26:431–462; Sabag, Edge & Soedigdo 2000, Ocean Eng.
27:1295–1319) — not the licensed coefficients. Equations and symbols:
``docs/theory/wake_model.md``. Per unit length, with the total ambient flow q = U + V:

    events   reversal: q changes sign (strength g = 1);
             slack: |q| passes a local minimum without a sign change, depth
             r = 1 − min|q|/peak|q| of the segment, strength g = ((r − r_0)/(1 − r_0))^β
             clipped to [0, 1]; it starts a new segment only when g exceeds the memory
             a · exp(−s/(λ_w D)) left of the present one
    s        = distance travelled by the flow since the last event (∫|q| dτ)
    U_w0     = α_w · g · max(peak |q| of the last two segments)
    φ(s)     = smoothstep 3ξ² − 2ξ³, ξ = min(s/(λ_o D), 1)   (φ = 1 when λ_o = 0)
    W(s)     = φ · σ U_w0 exp(−s/(λ_w D)) + (1 − φ) · W_end      W_end: W at the event
    C_D(s)   = C_D∞ + φ · a ΔC_D exp(−s/(λ_D D)) + (1 − φ) · ΔC_D,end       a = g
    C_L(s)   = C_L∞ + φ · a ΔC_L exp(−s/(λ_L D)) + (1 − φ) · ΔC_L,end
    U_e      = q + W
    F_Y      = ½ ρ D C_D (U_e − ẏ)|U_e − ẏ| + ρ (π D²/4) C_M U̇
    F_Z      = ½ ρ D C_L U_e²        (or (U_e − ẏ)² when P_LIFT_RELATIVE = 1)

σ is the sign of the present segment. A steady current has no events (steady C_D∞, C_L∞
exactly); a current with M = V/U ≥ 1 has one slack per wave period (depth 2/(1 + M) in a
regular flow), none once 2/(1 + M) <= r_0. The instant of a reversal inside a step is found by
linear interpolation of q; a slack is placed at the sample of the minimum; s is integrated by
the trapezoidal rule. The history uses the ambient flow only (not ẏ), so ∂F/∂ẏ comes from the
relative velocity alone. W and the coefficients are continuous in time at every event (the
old values are blended out over λ_o), C¹ in s.

With α_w = ΔC_D = ΔC_L = 0 the forces are, bit for bit, those of
:func:`onbottom.hydro._morison_kernel.morison_kernel` with C_D = C_D∞, C_M, C_L = C_L∞ (both
lift options).

params (``P_*``, one row of :meth:`onbottom.hydro.wake.WakeModel.parameter_table`):
C_D∞, C_L∞, C_M, ΔC_D, ΔC_L, λ_D, λ_L, α_w, λ_w, lift-relative flag, reversal tolerance, β,
r_0, λ_o.

The small helpers (:func:`_sign`, :func:`_onset`, :func:`_history_terms`,
:func:`_slack_strength`) are inlined at numba-IR level (``inline="always"``): fewer functions to
compile, the same operations.

state (``S_*``; zeros = flow at rest, no history): see the constants below. Odd under mirror
(u, U̇, V, ẏ → −): S_Q, S_SIGN and S_W_END; every other slot is even.
"""

from __future__ import annotations

import math

from onbottom._jit import jitted_only, njit
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
P_SLACK_EXPONENT = 11
"""β [-]: exponent of the slack strength g = ((r − r_0)/(1 − r_0))^β."""
P_SLACK_THRESHOLD = 12
"""r_0 [-]: slack depth r = 1 − min|q|/peak|q| below which a slack makes no wake (in [0, 1))."""
P_ONSET = 13
"""λ_o [-]: onset distance in diameters over which a new wake replaces the old one (0: a step)."""
N_PARAMS = 14

S_STARTED = 0
"""1.0 once the kernel has been evaluated (0.0: the first call, no time step yet)."""
S_T = 1
"""Time of the state [s]."""
S_Q = 2
"""Total ambient flow q = U + V at S_T [m/s] (odd)."""
S_SIGN = 3
"""Sign σ of the present half-cycle: +1, −1, or 0 while the flow has been at rest (odd)."""
S_DIST = 4
"""Distance s travelled by the wave flow (∫|U| dτ) since the last event [m]."""
S_PEAK = 5
"""Running peak of |q| in the present half-cycle [m/s]."""
S_WAKE0 = 6
"""Wake velocity U_w0 set at the last reversal [m/s]."""
S_RELAX = 7
"""Relaxation amplitude a of the coefficients: 1 after a reversal, 0 before it and after a slack."""
S_N_REVERSALS = 8
"""Number of reversals so far [-] (diagnostic)."""
S_PREV_STROKE = 9
"""Distance travelled in the previous segment (half-cycle or slack to slack) [m] (diagnostic)."""
S_TROUGH = 11
"""Smallest |q| since the present segment's running peak was last raised [m/s]."""
S_W_END = 12
"""Signed wake velocity W at the last event [m/s] (odd); blended out over the onset."""
S_CD_END = 13
"""C_D excess at the last event [-]; blended out over the onset."""
S_CL_END = 14
"""C_L excess at the last event [-]; blended out over the onset."""
S_STRENGTH = 15
"""Strength g of the last event: 1 for a reversal, g(r) for a slack, 0 before any [-]."""
N_USED_STATE = 16

PR_Q = 0
"""q = U + V at the step end [m/s] (slots of ``prep``, written by :func:`wake_prepare`)."""
PR_W = 1
"""Wake velocity W at the step end [m/s]."""
PR_CD = 2
"""C_D = C_D∞ + excess at the step end [-]."""
PR_CL = 3
"""C_L = C_L∞ + excess at the step end [-]."""
PR_INERTIA = 4
"""Inertia force ρ (π D²/4) C_M U̇ [N/m]."""
N_PREP = 5


@njit(cache=True, inline="always")
def _sign(x):
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return 0.0


@njit(cache=True, inline="always")
def _onset(x, lam):
    """φ: C¹ smoothstep from 0 at x = 0 to 1 at x = λ_o (distances in D); 1 when λ_o = 0."""
    if lam <= 0.0:
        return 1.0
    xi = x / lam
    if xi >= 1.0:
        return 1.0
    return xi * xi * (3.0 - 2.0 * xi)


@njit(cache=True, inline="always")
def _history_terms(params, sign, wake0, relax, w_end, cd_end, cl_end, x):
    """(W, C_D excess, C_L excess) at x = s/D into the present segment (blended onset)."""
    phi = _onset(x, params[P_ONSET])
    keep = 1.0 - phi
    w = phi * (sign * (wake0 * math.exp(-x / params[P_LAMBDA_W]))) + keep * w_end
    exd = phi * (relax * params[P_DCD] * math.exp(-x / params[P_LAMBDA_D])) + keep * cd_end
    exl = phi * (relax * params[P_DCL] * math.exp(-x / params[P_LAMBDA_L])) + keep * cl_end
    return w, exd, exl


@njit(cache=True, inline="always")
def _slack_strength(params, peak, trough):
    """g(r) of a slack of depth r = (peak − trough)/peak (module doc), in [0, 1]."""
    r = (peak - trough) / peak
    r0 = params[P_SLACK_THRESHOLD]
    lin = (r - r0) / (1.0 - r0)
    if lin <= 0.0:
        return 0.0
    if lin >= 1.0:
        return 1.0
    return lin ** params[P_SLACK_EXPONENT]


@jitted_only
def _history_step(params, state_old, t, u, dudt, vc, d, rho, state_new):
    """The part of an evaluation that does not depend on ẏ: writes ``state_new`` (the history
    after the flow at t) and returns (q, W, C_D, C_L, inertia force ρ (π D²/4) C_M U̇)."""
    for i in range(state_old.shape[0]):
        state_new[i] = state_old[i]
    q = u + vc
    aq = abs(q)
    if state_old[S_STARTED] == 0.0:
        # first evaluation: the flow starts from rest, no history (no wake, no relaxation)
        sign = _sign(q)
        dist = 0.0
        peak = aq
        trough = aq
        wake0 = 0.0
        relax = 0.0
        strength = 0.0
    else:
        dt = t - state_old[S_T]
        if dt < 0.0:
            dt = 0.0
        q_old = state_old[S_Q]
        aq_old = abs(q_old)
        sign = state_old[S_SIGN]
        dist = state_old[S_DIST]
        peak = state_old[S_PEAK]
        trough = state_old[S_TROUGH]
        wake0 = state_old[S_WAKE0]
        relax = state_old[S_RELAX]
        strength = state_old[S_STRENGTH]
        s_new = _sign(q)
        tol = params[P_REVERSAL_TOL] * max(peak, aq_old)
        event = False
        reversal = False
        g = 1.0
        x_end = 0.0
        dist_after = 0.0
        if sign == 0.0:
            # at rest so far: the first motion sets the direction, it is not a reversal
            if aq > tol:
                sign = s_new
        elif s_new != 0.0 and s_new != sign and aq > tol:
            # reversal inside the step: q crosses zero at the fraction f of the step
            denom = aq_old + aq
            f = aq_old / denom if q_old * sign > 0.0 else 0.0
            stroke = dist + 0.5 * aq_old * f * dt
            x_end = stroke / d
            event = True
            reversal = True
            state_new[S_N_REVERSALS] = state_old[S_N_REVERSALS] + 1.0
            state_new[S_PREV_STROKE] = stroke
            dist_after = 0.5 * aq * (1.0 - f) * dt
        elif aq > aq_old and aq_old == trough and trough < peak:
            # slack: |q| passed a local minimum at the previous sample without changing sign
            g = _slack_strength(params, peak, trough)
            if g > strength * math.exp(-(dist / d) / params[P_LAMBDA_W]):
                x_end = dist / d
                event = True
                state_new[S_PREV_STROKE] = dist
                dist_after = 0.5 * (aq_old + aq) * dt
        if event:
            w, exd, exl = _history_terms(
                params,
                sign,
                wake0,
                relax,
                state_old[S_W_END],
                state_old[S_CD_END],
                state_old[S_CL_END],
                x_end,
            )
            state_new[S_W_END] = w
            state_new[S_CD_END] = exd
            state_new[S_CL_END] = exl
            wake0 = params[P_WAKE_RATIO] * (peak - trough if not reversal else peak) * g
            strength = g
            if reversal:
                relax = 1.0
                sign = s_new
            else:
                relax = 0.0
            dist = dist_after
            peak = aq
            trough = aq
        else:
            dist = dist + 0.5 * (aq_old + aq) * dt
            if aq > peak:
                peak = aq
                trough = aq
            elif aq < trough:
                trough = aq
    state_new[S_STARTED] = 1.0
    state_new[S_T] = t
    state_new[S_Q] = q
    state_new[S_SIGN] = sign
    state_new[S_DIST] = dist
    state_new[S_PEAK] = peak
    state_new[S_TROUGH] = trough
    state_new[S_WAKE0] = wake0
    state_new[S_RELAX] = relax
    state_new[S_STRENGTH] = strength

    x = dist / d
    uw, exd, exl = _history_terms(
        params,
        sign,
        wake0,
        relax,
        state_new[S_W_END],
        state_new[S_CD_END],
        state_new[S_CL_END],
        x,
    )
    cd = params[P_CD_STEADY] + exd
    cl = params[P_CL_STEADY] + exl
    inertia = 0.25 * math.pi * rho * d * d * params[P_CM] * dudt
    return q, uw, cd, cl, inertia


@jitted_only
def _forces(params, q, uw, cd, cl, inertia, u, vc, ydot, d, rho, out):
    """The ẏ-dependent part: F_Y, ∂F_Y/∂ẏ, F_Z, ∂F_Z/∂ẏ from the history terms (module doc)."""
    ue = q + uw
    urel = ue - ydot
    drag = 0.5 * rho * d * cd * urel * abs(urel)
    out[FO_FY] = drag + inertia
    out[FO_DFY_DYD] = -rho * d * cd * abs(urel)
    if params[P_LIFT_RELATIVE] != 0.0:
        s = ((u - ydot) + vc) + uw  # the Morison kernel's order: bit for bit when W = 0
        out[FO_FZ] = 0.5 * rho * d * cl * s * s
        out[FO_DFZ_DYD] = -rho * d * cl * s
    else:
        out[FO_FZ] = 0.5 * rho * d * cl * ue * ue
        out[FO_DFZ_DYD] = 0.0


@jitted_only
def wake_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Wake-model forces per unit length and the state after this evaluation (see module doc).

    The one-call form of the contract: :func:`wake_prepare` then :func:`wake_evaluate`, with
    the same operations in the same order (bit for bit the same values)."""
    q, uw, cd, cl, inertia = _history_step(params, state_old, t, u, dudt, vc, d, rho, state_new)
    _forces(params, q, uw, cd, cl, inertia, u, vc, ydot, d, rho, out)


@jitted_only
def wake_prepare(params, state_old, t, u, dudt, vc, d, rho, state_new, prep):
    """Once-per-step stage (contract rule 7): the history after the flow at t into
    ``state_new`` and the ẏ-independent terms into ``prep`` (``PR_*`` slots); returns True."""
    q, uw, cd, cl, inertia = _history_step(params, state_old, t, u, dudt, vc, d, rho, state_new)
    prep[PR_Q] = q
    prep[PR_W] = uw
    prep[PR_CD] = cd
    prep[PR_CL] = cl
    prep[PR_INERTIA] = inertia
    return True


@jitted_only
def wake_evaluate(params, prep, u, vc, ydot, d, rho, out):
    """Per-iterate stage (contract rule 7): the forces at ``ydot`` from the terms
    :func:`wake_prepare` left in ``prep``; the same values as :func:`wake_kernel`."""
    _forces(
        params, prep[PR_Q], prep[PR_W], prep[PR_CD], prep[PR_CL], prep[PR_INERTIA], u, vc, ydot,
        d, rho, out,
    )  # fmt: skip
