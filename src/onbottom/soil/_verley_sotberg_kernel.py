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

from onbottom._jit import njit, pure_python
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


@njit(cache=True)
def peak_passive(params, z, v_load):
    """Peak passive force F_r [N/m] at penetration ``z`` under vertical load ``v_load``.

    V&S Eqs 3-4 (Youssef & Cassidy Eqs 11-12 with the factor A) or DNV-RP-F109 §3.4.6.
    Zero for V <= 0 (lift-off) or z <= 0.
    """
    if v_load <= 0.0 or z <= 0.0:
        return 0.0
    return peak_passive_from_power(params, penetration_power(params, z), v_load)


@njit(cache=True)
def penetration_power(params, z):
    """(z/D)^1.25 of V&S Eqs 3-4 (0 for z <= 0)."""
    if z <= 0.0:
        return 0.0
    return (z / params[P_D]) ** 1.25


@njit(cache=True)
def memo_power(params, z, key, value):
    """(z/D)^1.25, taken from the memo (``key``, ``value``) when z equals its key."""
    if z == key:
        return value
    return penetration_power(params, z)


@njit(cache=True)
def peak_passive_from_power(params, zp, v_load):
    """:func:`peak_passive` from the power zp = (z/D)^1.25 (z > 0, V > 0)."""
    d = params[P_D]
    g = params[P_GAMMA]
    ks = g * d * d / v_load
    base = params[P_A] * g * d * d * zp
    if params[P_PASSIVE_LAW] == PASSIVE_DNV_F109:
        if ks <= KS_SWITCH_F109:
            return base * (5.0 - 0.15 * ks)
        return base
    if ks <= KS_SWITCH_VS:
        return base * (5.0 - 0.15 * ks)
    return 2.0 * base


@njit(cache=True)
def _peak(params, z, zp, v_load):
    """:func:`peak_passive` at z given its power zp = (z/D)^1.25 (same arithmetic)."""
    if v_load <= 0.0 or z <= 0.0:
        return 0.0
    return peak_passive_from_power(params, zp, v_load)


@njit(cache=True)
def residual_ratio(z2_over_d):
    """z3/z2 (V&S Eqs 9-10)."""
    if z2_over_d <= 0.1:
        return 0.82 - 3.2 * z2_over_d
    return 0.5


@njit(cache=True)
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
    b = params[P_B]
    if params[P_B_PLACEMENT] == B_INSIDE:
        b = math.sqrt(b)
    ks = g * d * d / v_load
    z_work = zi
    if work > 0.0:
        # square roots as math.sqrt, not ** 0.5: numba calls libm's pow for a float exponent
        # (sqrt is correctly rounded, pow within 1 ulp of it)
        z_work = zi + b * 0.23 * d * math.sqrt(work / (g * d**3)) * (ks * smax / d) ** (-0.31)
    half = 0.5
    if params[P_ZMAX_LAW] == ZMAX_LAW_NO_HALF:
        half = 1.0
    base = zi if params[P_ZMAX_BASE] == ZMAX_BASE_TROUGH else params[P_ZI]
    z_cap = base + b * half * d * math.sqrt(smax / (ks * d))
    z_new = min(z_work, z_cap)
    if z_new > z_old:
        return z_new
    return z_old


@njit(cache=True)
def counted_length(params, state, s_old, s_new, y1, y2):
    """Length [m] of the increment s_old -> s_new that adds to the work E of Eq 6 [I].

    Region 2 is y1 <= |s| <= y2 (both sides). ``P_WORK_COUNTING`` limits it: to ground inside
    the amplitude of the trough's turning points (swept ground), inside the smaller of the two
    sides' turning excursions (two-sided), or to a trough whose load has reversed (gate);
    the drift variants further limit it, once the pipe has turned in region 2, to ground
    inside its turning amplitude plus the longest half-cycle it has made in the trough
    (``COUNT_LOAD_REVERSAL_DRIFT``) or without that allowance (``COUNT_LOAD_REVERSAL_SWEPT``),
    or to that amplitude only when the pipe last turned on the same side of the trough centre
    (``COUNT_LOAD_REVERSAL_SIDE``: a pipe that turns back and goes on is walking; a swing
    from the other side is cyclic motion, however fast its amplitude grows).
    """
    mode = params[P_WORK_COUNTING]
    hi = y2
    if mode == COUNT_ANY_REGION2:
        hi = y2
    elif mode == COUNT_SWEPT_GROUND:
        hi = min(y2, max(state[S_TP_POS], state[S_TP_NEG]))
    elif mode == COUNT_TWO_SIDED:
        hi = min(y2, min(state[S_TP_POS], state[S_TP_NEG]))
    else:
        if state[S_GATE] <= 0.0:
            return 0.0
        if mode == COUNT_LOAD_REVERSAL_SIDE:
            # beyond the turning amplitude only on a swing from the other side of the centre
            if state[S_TURNED2] > 0.0 and sign(s_new) * sign(state[S_TP_LAST]) > 0.0:
                hi = min(y2, max(state[S_TP_POS], state[S_TP_NEG]))
        elif mode != COUNT_LOAD_REVERSAL and state[S_TURNED2] > 0.0:
            reach = max(state[S_TP_POS], state[S_TP_NEG])
            if mode == COUNT_LOAD_REVERSAL_DRIFT:
                reach = reach + state[S_HALF]
            hi = min(y2, reach)
    if hi <= y1:
        return 0.0
    return overlap(s_old, s_new, y1, hi) + overlap(s_old, s_new, -hi, -y1)


@njit(cache=True)
def verley_sotberg_kernel(params, state_old, y_new, v_load, state_new, out):
    """Verley & Sotberg kernel (contract: :mod:`onbottom.soil.base`)."""
    y1 = params[P_Y1]
    y2 = params[P_Y2]
    y3 = params[P_Y3]
    d = params[P_D]
    for i in range(state_old.shape[0]):
        state_new[i] = state_old[i]

    y_old = state_old[S_Y]
    dy = y_new - y_old
    direction = sign(dy)
    f_old = state_old[S_FRICTION]
    f, k_f = friction_return_map(f_old, dy, v_load, params[P_MU], params[P_DELTA])

    phase = state_old[S_PHASE]
    y0 = state_old[S_Y0]
    zi = state_old[S_ZI]
    smax = state_old[S_SMAX]
    z2 = state_old[S_Z2]
    z = state_old[S_Z]
    work = state_old[S_WORK]

    legacy = params[P_PASSIVE_RULE] == RULE_LEGACY_ELASTIC
    p_old = state_old[S_PASSIVE]
    memo_z = state_old[S_MEMO_Z]
    memo_p = state_old[S_MEMO_P]
    memo_z3 = state_old[S_MEMO_Z3]
    memo_p3 = state_old[S_MEMO_P3]
    # out of the trough and reversing: a new trough starts at the turning point [I]
    if phase == PHASE_OUT and direction != 0.0 and direction != state_old[S_DIR]:
        y0 = y_old
        zi = z
        smax = 0.0
        z2 = 0.0
        work = 0.0
        phase = PHASE_TROUGH
        # the new trough has no turning points yet and its load has not reversed in it
        state_new[S_GATE] = 0.0
        state_new[S_TP_POS] = 0.0
        state_new[S_TP_NEG] = 0.0
        state_new[S_TURNED2] = 0.0
        state_new[S_TP_LAST] = 0.0
        state_new[S_HALF] = 0.0
        if not legacy:
            # the pipe leaves the berm it pushed: its force is released at the turning
            # point (a jump at zero displacement; the stored energy is dissipated)
            p_old = 0.0

    s_old = y_old - y0
    s_new = y_new - y0
    a_new = abs(s_new)

    if phase == PHASE_TROUGH:
        # a turning point of the pipe in the trough: s_old, where the motion reversed
        if direction != 0.0 and state_old[S_DIR] != 0.0 and direction != state_old[S_DIR]:
            if s_old > state_new[S_TP_POS]:
                state_new[S_TP_POS] = s_old
            if -s_old > state_new[S_TP_NEG]:
                state_new[S_TP_NEG] = -s_old
            if abs(s_old) > y1:
                state_new[S_TURNED2] = 1.0
            state_new[S_HALF] = max(state_new[S_HALF], abs(s_old - state_new[S_TP_LAST]))
            state_new[S_TP_LAST] = s_old
        # work and penetration growth over the part of the increment inside region 2 that
        # counts (P_WORK_COUNTING)
        du2 = counted_length(params, state_new, s_old, s_new, y1, y2)
        smax_c = min(max(smax, a_new), y2)
        if du2 > 0.0 and v_load > 0.0:
            memo_p = memo_power(params, z, memo_z, memo_p)
            memo_z = z
            fr2 = _peak(params, z, memo_p, v_load)
            if legacy:
                mag_p, _slope = envelope(min(a_new, y2), 0.3 * fr2, fr2, fr2, y1, y2, y3)
                p_pred = sign(s_new) * mag_p
            else:
                mag_p, slope_p = envelope(a_new, 0.3 * fr2, fr2, fr2, y1, y2, y3)
                p_pred, _k = push_only_passive(p_old, dy, s_new, mag_p, slope_p, 0.3 * fr2 / y1)
            if params[P_WORK_INTEGRAND] == INTEGRAND_PASSIVE:
                mean = 0.5 * (abs(p_old) + abs(p_pred))
            else:
                mean = 0.5 * (abs(f_old + p_old) + abs(f + p_pred))
            work = work + mean * du2
            z = grown_penetration(params, z, zi, work, smax_c, v_load)
        smax = max(smax, a_new)
        if a_new > y2:
            # first passage of y2: breakout starts, z2 frozen, work reset
            phase = PHASE_BREAKOUT
            z2 = z
            work = 0.0
    else:
        smax = max(smax, a_new)

    if phase == PHASE_BREAKOUT:
        z3 = residual_ratio(z2 / d) * z2
        reach = min(smax, y3)
        z = z2 + (z3 - z2) * (reach - y2) / (y3 - y2)
        if a_new > y3:
            phase = PHASE_OUT
            z = z3

    # passive force about y0 bounded by the envelope
    if phase == PHASE_TROUGH:
        memo_p = memo_power(params, z, memo_z, memo_p)
        memo_z = z
        fr2 = _peak(params, z, memo_p, v_load)
        fr3 = fr2
    else:
        memo_p = memo_power(params, z2, memo_z, memo_p)
        memo_z = z2
        fr2 = _peak(params, z2, memo_p, v_load)
        z3 = residual_ratio(z2 / d) * z2
        memo_p3 = memo_power(params, z3, memo_z3, memo_p3)
        memo_z3 = z3
        fr3 = _peak(params, z3, memo_p3, v_load)
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
        soil_work = state_old[S_SOIL_WORK] + 0.5 * (f_old + state_old[S_PASSIVE] + r_new) * dy
    else:
        # each spring: work along its return-mapped increment, from its start force
        soil_work = state_old[S_SOIL_WORK] + elastoplastic_soil_work(
            f_old, f, p_old, passive, s_new, mag, k_u, dy, v_load, params[P_MU], params[P_DELTA]
        )
    stored = friction_energy(f, v_load, params[P_MU], params[P_DELTA]) + e_passive

    # load direction from the soil reaction: at rest or sliding slowly the reaction R
    # equilibrates the applied load, so a change of its sign beyond θ·μV (hysteresis) is a
    # reversal of the load; the berm pushing back under a one-way load cannot make R < 0
    if v_load > 0.0:
        thr = params[P_REVERSAL] * params[P_MU] * v_load
        new_dir = 0.0
        if r_new >= thr:
            new_dir = 1.0
        elif r_new <= -thr:
            new_dir = -1.0
        if new_dir != 0.0:
            if state_old[S_LOAD_DIR] != 0.0 and new_dir != state_old[S_LOAD_DIR]:
                if phase == PHASE_TROUGH:
                    state_new[S_GATE] = 1.0
            state_new[S_LOAD_DIR] = new_dir

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
    if direction != 0.0:
        state_new[S_DIR] = direction
    state_new[S_PASSIVE] = passive
    state_new[S_MEMO_Z] = memo_z
    state_new[S_MEMO_P] = memo_p
    state_new[S_MEMO_Z3] = memo_z3
    state_new[S_MEMO_P3] = memo_p3

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
