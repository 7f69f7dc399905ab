"""Numba kernel of the Verley & Sotberg (1994) sand model and its variants (private).

Contract: :mod:`onbottom.soil.base`. Physics and the choices made where the papers are silent:
:mod:`onbottom.soil.verley_sotberg` and ``docs/theory/verley_sotberg.md``.

The Python twin :func:`verley_sotberg_kernel_py` is the *same source* executed by the Python
interpreter (:func:`onbottom._jit.pure_python`).

params (float64, :data:`N_PARAMS`): see the ``P_*`` indices below.
state (float64, :data:`N_STATE`): common slots of :mod:`onbottom.soil.base` then the ``S_*``
slots below.
"""

from __future__ import annotations

import math

from onbottom._jit import jitted_only, njit, pure_python
from onbottom.soil._coulomb_kernel import friction_return_map
from onbottom.soil._trough import (
    PHASE_BREAKOUT,
    PHASE_OUT,
    PHASE_TROUGH,
    RULE_LEGACY_ELASTIC,
    elastoplastic_soil_work,
    envelope,
    envelope_energy,
    friction_energy,
    overlap,
    push_only_passive,
    region_of,
    sign,
)
from onbottom.soil.base import (
    N_COMMON_STATE,
    OUT_DISSIPATED,
    OUT_FRICTION,
    OUT_PASSIVE,
    OUT_R,
    OUT_REGION,
    OUT_STORED,
    OUT_TANGENT,
    OUT_WORK,
    OUT_Z,
    S_FRICTION,
    S_REGION,
    S_SOIL_WORK,
    S_WORK,
    S_Y,
    S_Z,
)

# ---- parameter slots -------------------------------------------------------------------------
P_MU = 0  # Coulomb friction coefficient μ [-]
P_DELTA = 1  # friction mobilisation displacement [m]
P_D = 2  # pipe outer diameter D [m]
P_GAMMA = 3  # submerged unit weight of the soil γ' [N/m³]
P_A = 4  # passive-force factor A [-] (Youssef & Cassidy 2014 Eqs 11-12; 1 for silica)
P_B = 5  # penetration-growth factor B [-] (Youssef & Cassidy 2014 Eqs 13-14; 1 for silica)
P_Y1 = 6  # end of the elastic region y1 [m]
P_Y2 = 7  # end of the accumulation region y2 [m]
P_Y3 = 8  # end of the breakout region y3 [m]
P_PASSIVE_LAW = 9  # PASSIVE_* code
P_WORK_LAW = 10  # WORK_LAW_* code
P_ZMAX_LAW = 11  # ZMAX_LAW_* code
P_WORK_INTEGRAND = 12  # INTEGRAND_* code
P_ZI = 13  # initial penetration of the first trough z_i [m] (Eq 7/15)
P_PASSIVE_RULE = 14  # RULE_* code of onbottom.soil._trough (elastoplastic / legacy_elastic)
P_B_PLACEMENT = 15  # B_* code: factor B outside or inside the bracket of Eqs 13-14
P_ZMAX_BASE = 16  # ZMAX_BASE_* code: the z_i of Eq 8's cap (as-laid Eq 7, or the trough's)
P_WORK_COUNTING = 17  # COUNT_* code: which region-2 increments add to the work E of Eq 6
P_REVERSAL = 18  # load-reversal threshold θ [-]: |R| >= θ·μV sets the load direction
N_PARAMS = 19

# ---- own state slots -------------------------------------------------------------------------
S_Y0 = N_COMMON_STATE  # origin (centre) of the current trough y0 [m]
S_ZI = N_COMMON_STATE + 1  # initial penetration of the current trough z_i [m]
S_SMAX = N_COMMON_STATE + 2  # largest |y - y0| reached in the current trough [m]
S_Z2 = N_COMMON_STATE + 3  # penetration frozen on first passing y2 [m] (0 before)
S_PHASE = N_COMMON_STATE + 4  # PHASE_* code
S_DIR = N_COMMON_STATE + 5  # sign of the last non-zero displacement increment (+1, -1, 0)
S_PASSIVE = N_COMMON_STATE + 6  # committed passive force [N/m] (for the work integral)
# memo of the fractional power (z/D)^1.25 of the peak passive force: the last
# penetration it was evaluated at and its value, one pair for z (trough) or z2 (breakout, out)
# and one for z3. A hit returns the stored value, which is the same function of the same z,
# so the memo changes no result; a zero state is a valid memo (0^1.25 = 0).
S_MEMO_Z = N_COMMON_STATE + 7  # penetration of the memo [m]
S_MEMO_P = N_COMMON_STATE + 8  # its (z/D)^1.25 [-]
S_MEMO_Z3 = N_COMMON_STATE + 9  # residual penetration z3 of the second memo [m]
S_MEMO_P3 = N_COMMON_STATE + 10  # its (z3/D)^1.25 [-]
# which increments count (P_WORK_COUNTING): load direction, gate and turning points
S_LOAD_DIR = N_COMMON_STATE + 11  # load direction from the soil reaction (+1, -1, 0 unknown)
S_GATE = N_COMMON_STATE + 12  # 1 once the load has reversed in the current trough, else 0
S_TP_POS = N_COMMON_STATE + 13  # largest s = y - y0 > 0 at a turning point in the trough [m]
S_TP_NEG = N_COMMON_STATE + 14  # largest -s at a turning point on the side s < 0 [m]
S_TURNED2 = N_COMMON_STATE + 15  # 1 once the pipe has turned in region 2 of the trough, else 0
S_TP_LAST = N_COMMON_STATE + 16  # s of the last turning point in the trough (0: its start) [m]
S_HALF = N_COMMON_STATE + 17  # longest half-cycle |Δs| between turns in the trough [m]
N_STATE = N_COMMON_STATE + 18

# ---- codes -----------------------------------------------------------------------------------
# phases (onbottom.soil._trough): PHASE_TROUGH regions 1-2, y2 not yet passed;
# PHASE_BREAKOUT y2 passed, y3 not; PHASE_OUT y3 passed, out of the trough until next reversal

PASSIVE_VERLEY_SOTBERG = 0  # Eqs 3-4 (switch at K_s = 20)
PASSIVE_DNV_F109 = 1  # DNV-RP-F109 §3.4.6 (switch at κ_s = 26.7)

WORK_LAW_RECONSTRUCTION = 0  # Eq 6 as reconstructed (spec [R])
WORK_LAW_NONE = 1  # no work-driven growth: z stays at z_i in region 2

ZMAX_LAW_RECONSTRUCTION = 0  # Eq 8 with the factor 0.5 (spec [R])
ZMAX_LAW_NO_HALF = 1  # alternative reading of Eq 8 without the factor 0.5

B_OUTSIDE = 0  # z/D = z_i/D + B·0.23·[E/(γ'D³)]^0.5·... and + B·0.5·[s/(K_s D)]^0.5
B_INSIDE = 1  # B inside the powers: factor B^0.5 (0.23·[B·E/(γ'D³)]^0.5, 0.5·[B·s/(K_s D)]^0.5)

ZMAX_BASE_AS_LAID = 0  # Eq 8 about the as-laid z_i of Eq 7 (P_ZI): no ratchet over troughs
ZMAX_BASE_TROUGH = 1  # Eq 8 about the current trough's z_i (= z3 of the last breakout)

# which region-2 increments add to E (docs/theory/verley_sotberg.md, "Which increments count")
COUNT_ANY_REGION2 = 0  # every region-2 increment (the first reading; one-way pushes dig in)
COUNT_SWEPT_GROUND = 1  # only |s| within the largest turning-point excursion (bound)
COUNT_TWO_SIDED = 2  # only |s| within the smaller of the two sides' turning excursions (bound)
COUNT_LOAD_REVERSAL = 3  # every region-2 increment of a trough in which the load has reversed
COUNT_LOAD_REVERSAL_DRIFT = 4  # the same; after a turn in region 2 not beyond turns + longest swing
COUNT_LOAD_REVERSAL_SWEPT = 5  # the same; after a turn in region 2 not beyond the turns (strict)
COUNT_LOAD_REVERSAL_SIDE = 6  # the same; new ground not after a turn on the same side (walking)

INTEGRAND_TOTAL = 0  # E += |F_h Δy| with F_h = friction + passive
INTEGRAND_PASSIVE = 1  # E += |F_r Δy|

KS_SWITCH_VS = 20.0
KS_SWITCH_F109 = 26.7


@jitted_only
def peak_passive(params, z, v_load):
    """Peak passive force F_r [N/m] at penetration ``z`` under vertical load ``v_load``.

    V&S Eqs 3-4 (Youssef & Cassidy Eqs 11-12 with the factor A) or DNV-RP-F109 §3.4.6.
    Zero for V <= 0 (lift-off) or z <= 0.
    """
    if v_load <= 0.0 or z <= 0.0:
        return 0.0
    return peak_passive_from_power(params, penetration_power(params, z), v_load)


@jitted_only
def penetration_power(params, z):
    """(z/D)^1.25 of V&S Eqs 3-4 (0 for z <= 0)."""
    return _power(z, params[P_D])


@jitted_only
def _power(z, d):
    """(z/D)^1.25 at diameter ``d`` (0 for z <= 0)."""
    if z <= 0.0:
        return 0.0
    return (z / d) ** 1.25


@jitted_only
def _memo_power(z, d, key, value):
    """(z/D)^1.25, taken from the memo (``key``, ``value``) when z equals its key."""
    if z == key:
        return value
    return _power(z, d)


@jitted_only
def passive_factor(ks, f109):
    """Factor of A·γ'D²·(z/D)^1.25 in the peak passive force at K_s = γ'D²/V.

    V&S Eqs 3-4: 5 − 0.15 K_s up to K_s = 20, then 2; DNV-RP-F109 §3.4.6 (``f109``): the
    same up to κ_s = 26.7, then 1.
    """
    if f109:
        if ks <= KS_SWITCH_F109:
            return 5.0 - 0.15 * ks
        return 1.0
    if ks <= KS_SWITCH_VS:
        return 5.0 - 0.15 * ks
    return 2.0


@jitted_only
def peak_passive_from_power(params, zp, v_load):
    """:func:`peak_passive` from the power zp = (z/D)^1.25 (z > 0, V > 0)."""
    d = params[P_D]
    g = params[P_GAMMA]
    ks = g * d * d / v_load
    base = params[P_A] * g * d * d * zp
    return base * passive_factor(ks, params[P_PASSIVE_LAW] == PASSIVE_DNV_F109)


@jitted_only
def residual_ratio(z2_over_d):
    """z3/z2 (V&S Eqs 9-10)."""
    if z2_over_d <= 0.1:
        return 0.82 - 3.2 * z2_over_d
    return 0.5


@jitted_only
def grown_penetration(params, z_old, zi, work, smax, v_load):
    """Penetration after work ``work`` and amplitude ``smax`` in region 2 (never below z_old).

    z = max(z_old, min(Eq 6, Eq 8)) with the factor B (Youssef & Cassidy Eqs 13-14). Eq 6
    grows from the trough's z_i; Eq 8's cap is about the as-laid z_i of Eq 7 (``P_ZI``,
    default) or the trough's (``ZMAX_BASE_TROUGH``, the earlier rule, which let each new
    trough restart the cap from z3 and ratchet z up under sustained sliding).
    """
    if v_load <= 0.0 or smax <= 0.0 or params[P_WORK_LAW] == WORK_LAW_NONE:
        return z_old
    d = params[P_D]
    g = params[P_GAMMA]
    b, half = _growth_factors(params)
    base = zi if params[P_ZMAX_BASE] == ZMAX_BASE_TROUGH else params[P_ZI]
    return _grown(z_old, zi, work, smax, g * d * d / v_load, d, g * d**3, b, half, base)


@njit(cache=True, inline="always")
def _growth_factors(params):
    """The factor B of Eqs 13-14 (B^0.5 inside the bracket) and Eq 8's factor (0.5 or 1)."""
    b = params[P_B]
    if params[P_B_PLACEMENT] == B_INSIDE:
        b = math.sqrt(b)
    half = 0.5
    if params[P_ZMAX_LAW] == ZMAX_LAW_NO_HALF:
        half = 1.0
    return b, half


@jitted_only
def _grown(z_old, zi, work, smax, ks, d, gd3, b, half, base):
    """:func:`grown_penetration` (V > 0, growth on) from K_s, γ'D³, B, Eq 8's factor and the
    base of its cap."""
    if smax <= 0.0:
        return z_old
    # square roots as math.sqrt, not ** 0.5: numba calls libm's pow for a float exponent
    # (sqrt is correctly rounded, pow within 1 ulp of it)
    z_cap = base + b * half * d * math.sqrt(smax / (ks * d))
    if z_cap <= z_old:
        # min(Eq 6, Eq 8) <= z_old whatever Eq 6 gives: its power is not needed (the pipe
        # has dug to Eq 8's cap for its amplitude, the usual case under cyclic motion)
        return z_old
    z_work = zi
    if work > 0.0:
        z_work = zi + b * 0.23 * d * math.sqrt(work / gd3) * (ks * smax / d) ** (-0.31)
    z_new = min(z_work, z_cap)
    if z_new > z_old:
        return z_new
    return z_old


# inlined into the kernel (numba IR): a called helper costs the kernel a status check after the
# call, whose error exit keeps numba from pruning the reference counts of the kernel's arrays
@njit(cache=True, inline="always")
def counted_length(mode, gate, turned2, tp_pos, tp_neg, tp_last, swing, s_old, s_new, y1, y2):
    """Length [m] of the increment s_old -> s_new that adds to the work E of Eq 6 [I].

    Region 2 is y1 <= |s| <= y2 (both sides). ``mode`` (``P_WORK_COUNTING``) limits it: to
    ground inside the amplitude of the trough's turning points (swept ground), inside the
    smaller of the two sides' turning excursions (two-sided), or to a trough whose load has
    reversed (gate); the drift variants further limit it, once the pipe has turned in region 2,
    to ground inside its turning amplitude plus the longest half-cycle it has made in the
    trough (``COUNT_LOAD_REVERSAL_DRIFT``) or without that allowance
    (``COUNT_LOAD_REVERSAL_SWEPT``), or to that amplitude only when the pipe last turned on the
    same side of the trough centre (``COUNT_LOAD_REVERSAL_SIDE``: a pipe that turns back and
    goes on is walking; a swing from the other side is cyclic motion, however fast its
    amplitude grows). The other arguments are the trough's state slots ``S_GATE``,
    ``S_TURNED2``, ``S_TP_POS``, ``S_TP_NEG``, ``S_TP_LAST`` and ``S_HALF`` (``swing``).
    """
    hi = y2
    if mode == COUNT_ANY_REGION2:
        hi = y2
    elif mode == COUNT_SWEPT_GROUND:
        hi = min(y2, max(tp_pos, tp_neg))
    elif mode == COUNT_TWO_SIDED:
        hi = min(y2, min(tp_pos, tp_neg))
    else:
        if gate <= 0.0:
            return 0.0
        if mode == COUNT_LOAD_REVERSAL_SIDE:
            # beyond the turning amplitude only on a swing from the other side of the centre
            if turned2 > 0.0 and sign(s_new) * sign(tp_last) > 0.0:
                hi = min(y2, max(tp_pos, tp_neg))
        elif mode != COUNT_LOAD_REVERSAL and turned2 > 0.0:
            reach = max(tp_pos, tp_neg)
            if mode == COUNT_LOAD_REVERSAL_DRIFT:
                reach = reach + swing
            hi = min(y2, reach)
    if hi <= y1:
        return 0.0
    return overlap(s_old, s_new, y1, hi) + overlap(s_old, s_new, -hi, -y1)


@jitted_only
def verley_sotberg_kernel(params, state_old, y_new, v_load, state_new, out):
    """Verley & Sotberg kernel (contract: :mod:`onbottom.soil.base`).

    Every parameter and committed state slot is read into a local first and every state slot
    written once at the end (the arrays may alias as far as the compiler knows, so reads
    after writes would be repeated and shared subexpressions not shared).
    """
    mu = params[P_MU]
    delta = params[P_DELTA]
    d = params[P_D]
    g = params[P_GAMMA]
    y1 = params[P_Y1]
    y2 = params[P_Y2]
    y3 = params[P_Y3]
    f109 = params[P_PASSIVE_LAW] == PASSIVE_DNV_F109
    legacy = params[P_PASSIVE_RULE] == RULE_LEGACY_ELASTIC
    integrand_passive = params[P_WORK_INTEGRAND] == INTEGRAND_PASSIVE
    growth = params[P_WORK_LAW] != WORK_LAW_NONE
    mode = params[P_WORK_COUNTING]
    reversal = params[P_REVERSAL]
    agdd = params[P_A] * g * d * d  # A·γ'D² of Eqs 3-4
    b_fac, half = _growth_factors(params)
    cap_trough = params[P_ZMAX_BASE] == ZMAX_BASE_TROUGH
    zi_laid = params[P_ZI]

    y_old = state_old[S_Y]
    f_old = state_old[S_FRICTION]
    z = state_old[S_Z]
    work = state_old[S_WORK]
    soil_work_old = state_old[S_SOIL_WORK]
    y0 = state_old[S_Y0]
    zi = state_old[S_ZI]
    smax = state_old[S_SMAX]
    z2 = state_old[S_Z2]
    phase = state_old[S_PHASE]
    dir_old = state_old[S_DIR]
    p_committed = state_old[S_PASSIVE]
    memo_z = state_old[S_MEMO_Z]
    memo_p = state_old[S_MEMO_P]
    memo_z3 = state_old[S_MEMO_Z3]
    memo_p3 = state_old[S_MEMO_P3]
    load_dir = state_old[S_LOAD_DIR]
    gate = state_old[S_GATE]
    tp_pos = state_old[S_TP_POS]
    tp_neg = state_old[S_TP_NEG]
    turned2 = state_old[S_TURNED2]
    tp_last = state_old[S_TP_LAST]
    swing = state_old[S_HALF]

    dy = y_new - y_old
    direction = sign(dy)
    f, k_f = friction_return_map(f_old, dy, v_load, mu, delta)
    # K_s = γ'D²/V and the factor of the peak passive force at it (Eqs 3-4), once per call
    ks = 0.0
    fac = 0.0
    if v_load > 0.0:
        ks = g * d * d / v_load
        fac = passive_factor(ks, f109)

    p_old = p_committed
    # out of the trough and reversing: a new trough starts at the turning point [I]
    if phase == PHASE_OUT and direction != 0.0 and direction != dir_old:
        y0 = y_old
        zi = z
        smax = 0.0
        z2 = 0.0
        work = 0.0
        phase = PHASE_TROUGH
        # the new trough has no turning points yet and its load has not reversed in it
        gate = 0.0
        tp_pos = 0.0
        tp_neg = 0.0
        turned2 = 0.0
        tp_last = 0.0
        swing = 0.0
        if not legacy:
            # the pipe leaves the berm it pushed: its force is released at the turning
            # point (a jump at zero displacement; the stored energy is dissipated)
            p_old = 0.0

    s_old = y_old - y0
    s_new = y_new - y0
    a_new = abs(s_new)

    if phase == PHASE_TROUGH:
        # a turning point of the pipe in the trough: s_old, where the motion reversed
        if direction != 0.0 and dir_old != 0.0 and direction != dir_old:
            if s_old > tp_pos:
                tp_pos = s_old
            if -s_old > tp_neg:
                tp_neg = -s_old
            if abs(s_old) > y1:
                turned2 = 1.0
            swing = max(swing, abs(s_old - tp_last))
            tp_last = s_old
        # work and penetration growth over the part of the increment inside region 2 that
        # counts (P_WORK_COUNTING)
        du2 = 0.0
        if max(abs(s_old), a_new) > y1:  # else the increment lies in region 1: nothing counts
            du2 = counted_length(
                mode, gate, turned2, tp_pos, tp_neg, tp_last, swing, s_old, s_new, y1, y2
            )
        if du2 > 0.0 and v_load > 0.0:
            memo_p = _memo_power(z, d, memo_z, memo_p)
            memo_z = z
            fr2 = agdd * memo_p * fac if z > 0.0 else 0.0
            if legacy:
                mag_p, _slope = envelope(min(a_new, y2), 0.3 * fr2, fr2, fr2, y1, y2, y3)
                p_pred = sign(s_new) * mag_p
            else:
                mag_p, slope_p = envelope(a_new, 0.3 * fr2, fr2, fr2, y1, y2, y3)
                p_pred, _k = push_only_passive(p_old, dy, s_new, mag_p, slope_p, 0.3 * fr2 / y1)
            if integrand_passive:
                mean = 0.5 * (abs(p_old) + abs(p_pred))
            else:
                mean = 0.5 * (abs(f_old + p_old) + abs(f + p_pred))
            work = work + mean * du2
            if growth:
                base = zi if cap_trough else zi_laid
                smax_c = min(max(smax, a_new), y2)
                z = _grown(z, zi, work, smax_c, ks, d, g * d**3, b_fac, half, base)
        smax = max(smax, a_new)
        if a_new > y2:
            # first passage of y2: breakout starts, z2 frozen, work reset
            phase = PHASE_BREAKOUT
            z2 = z
            work = 0.0
    else:
        smax = max(smax, a_new)

    # passive force about y0 bounded by the envelope
    if phase == PHASE_TROUGH:
        memo_p = _memo_power(z, d, memo_z, memo_p)
        memo_z = z
        fr2 = 0.0
        if v_load > 0.0 and z > 0.0:
            fr2 = agdd * memo_p * fac
        fr3 = fr2
    else:
        z3 = residual_ratio(z2 / d) * z2
        if phase == PHASE_BREAKOUT:
            reach = min(smax, y3)
            z = z2 + (z3 - z2) * (reach - y2) / (y3 - y2)
            if a_new > y3:
                phase = PHASE_OUT
                z = z3
        memo_p = _memo_power(z2, d, memo_z, memo_p)
        memo_z = z2
        memo_p3 = _memo_power(z3, d, memo_z3, memo_p3)
        memo_z3 = z3
        fr2 = 0.0
        fr3 = 0.0
        if v_load > 0.0:
            if z2 > 0.0:
                fr2 = agdd * memo_p * fac
            if z3 > 0.0:
                fr3 = agdd * memo_p3 * fac
    fr1 = 0.3 * fr2
    mag, slope = envelope(a_new, fr1, fr2, fr3, y1, y2, y3)
    k_u = fr1 / y1
    if legacy:
        passive = sign(s_new) * mag
        e_passive = envelope_energy(a_new, fr1, fr2, fr3, y1, y2, y3)
    else:
        passive, slope = push_only_passive(p_old, dy, s_new, mag, slope, k_u)
        e_passive = 0.0
        if k_u > 0.0:
            e_passive = 0.5 * passive * passive / k_u
    if v_load <= 0.0:
        passive = 0.0
        slope = 0.0
        e_passive = 0.0

    # energy bookkeeping: soil work (trapezoid over the increment), stored, dissipated
    r_new = f + passive
    if legacy:
        # trapezoidal work of a nonlinear-elastic force (the variant's own bookkeeping)
        soil_work = soil_work_old + 0.5 * (f_old + p_committed + r_new) * dy
    else:
        # each spring: work along its return-mapped increment, from its start force
        soil_work = soil_work_old + elastoplastic_soil_work(
            f_old, f, p_old, passive, s_new, mag, k_u, dy, v_load, mu, delta
        )
    stored = friction_energy(f, v_load, mu, delta) + e_passive

    # load direction from the soil reaction: at rest or sliding slowly the reaction R
    # equilibrates the applied load, so a change of its sign beyond θ·μV (hysteresis) is a
    # reversal of the load; the berm pushing back under a one-way load cannot make R < 0
    if v_load > 0.0:
        thr = reversal * mu * v_load
        new_dir = 0.0
        if r_new >= thr:
            new_dir = 1.0
        elif r_new <= -thr:
            new_dir = -1.0
        if new_dir != 0.0:
            if load_dir != 0.0 and new_dir != load_dir and phase == PHASE_TROUGH:
                gate = 1.0
            load_dir = new_dir

    region = region_of(a_new, y1, y2, y3)
    state_new[S_Y] = y_new
    state_new[S_FRICTION] = f
    state_new[S_Z] = z
    state_new[S_WORK] = work
    state_new[S_REGION] = region
    state_new[S_SOIL_WORK] = soil_work
    state_new[S_Y0] = y0
    state_new[S_ZI] = zi
    state_new[S_SMAX] = smax
    state_new[S_Z2] = z2
    state_new[S_PHASE] = phase
    state_new[S_DIR] = direction if direction != 0.0 else dir_old
    state_new[S_PASSIVE] = passive
    state_new[S_MEMO_Z] = memo_z
    state_new[S_MEMO_P] = memo_p
    state_new[S_MEMO_Z3] = memo_z3
    state_new[S_MEMO_P3] = memo_p3
    state_new[S_LOAD_DIR] = load_dir
    state_new[S_GATE] = gate
    state_new[S_TP_POS] = tp_pos
    state_new[S_TP_NEG] = tp_neg
    state_new[S_TURNED2] = turned2
    state_new[S_TP_LAST] = tp_last
    state_new[S_HALF] = swing
    # a longer state row (a solver's nodes on several models) keeps its other slots
    for i in range(N_STATE, state_old.shape[0]):
        state_new[i] = state_old[i]

    out[OUT_R] = r_new
    out[OUT_FRICTION] = f
    out[OUT_PASSIVE] = passive
    out[OUT_TANGENT] = k_f + slope
    out[OUT_Z] = z
    out[OUT_WORK] = work
    out[OUT_REGION] = region
    out[OUT_STORED] = stored
    out[OUT_DISSIPATED] = soil_work - stored


peak_passive_py = pure_python(peak_passive)
"""Plain-Python twin of :func:`peak_passive` (the F109 checks call it: nothing compiled)."""
verley_sotberg_kernel_py = pure_python(verley_sotberg_kernel)
"""Plain-Python twin of :func:`verley_sotberg_kernel` (same source, interpreted)."""
