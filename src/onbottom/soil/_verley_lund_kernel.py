"""Numba kernel of the Verley & Lund (1995) clay model as in DNV-RP-F109 §3.4.6 (private).

Contract: :mod:`onbottom.soil.base`; physics and model choices: :mod:`onbottom.soil.verley_lund`
and ``docs/theory/verley_lund_clay.md``. The twin :func:`verley_lund_kernel_py` is the same
source run by the Python interpreter (:func:`onbottom._jit.pure_python`).
"""

from __future__ import annotations

from onbottom._jit import jitted_only, pure_python
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
P_KR = 3  # passive coefficient 4.1·s_u·D·G_c^-0.39 [N/m]: F_R = P_KR·(z/D)^1.31
P_BRK0 = 4  # breakout displacement y_brk = (P_BRK0 + P_BRK1·z/D)·D
P_BRK1 = 5
P_YRES = 6  # residual displacement y_res [m]
P_ZRES = 7  # residual penetration z_res [m]
P_ZI = 8  # initial penetration z_i [m]
P_PASSIVE_RULE = 9  # RULE_* code of onbottom.soil._trough (elastoplastic / legacy_elastic)
N_PARAMS = 10

# ---- own state slots -------------------------------------------------------------------------
S_Y0 = N_COMMON_STATE  # centre of the current trough y0 [m]
S_ZT = N_COMMON_STATE + 1  # penetration of the current trough z_t [m]
S_SMAX = N_COMMON_STATE + 2  # largest |y - y0| reached in the current trough [m]
S_PHASE = N_COMMON_STATE + 3  # phase code (onbottom.soil._trough)
S_DIR = N_COMMON_STATE + 4  # sign of the last non-zero displacement increment
S_PASSIVE = N_COMMON_STATE + 5  # committed passive force [N/m]
N_STATE = N_COMMON_STATE + 6


@jitted_only
def clay_passive(params, z):
    """F_R = 4.1·s_u·D·G_c^−0.39·(z/D)^1.31 [N/m] (F109 §3.4.6 with F_C·κ_c = s_u·D)."""
    if z <= 0.0:
        return 0.0
    return params[P_KR] * (z / params[P_D]) ** 1.31


@jitted_only
def verley_lund_kernel(params, state_old, y_new, v_load, state_new, out):
    """Verley & Lund clay kernel (contract: :mod:`onbottom.soil.base`)."""
    d = params[P_D]
    y_res = params[P_YRES]
    for i in range(state_old.shape[0]):
        state_new[i] = state_old[i]

    y_old = state_old[S_Y]
    dy = y_new - y_old
    direction = sign(dy)
    f_old = state_old[S_FRICTION]
    f, k_f = friction_return_map(f_old, dy, v_load, params[P_MU], params[P_DELTA])

    phase = state_old[S_PHASE]
    y0 = state_old[S_Y0]
    zt = state_old[S_ZT]
    smax = state_old[S_SMAX]
    z = state_old[S_Z]

    # out of the trough and reversing: a new trough at the turning point, z_t = z_res [I]
    legacy = params[P_PASSIVE_RULE] == RULE_LEGACY_ELASTIC
    p_old = state_old[S_PASSIVE]
    if phase == PHASE_OUT and direction != 0.0 and direction != state_old[S_DIR]:
        y0 = y_old
        zt = z
        smax = 0.0
        phase = PHASE_TROUGH
        if not legacy:
            p_old = 0.0  # the berm pushed so far is left: its force released (dissipated)

    s_new = y_new - y0
    a_new = abs(s_new)
    smax = max(smax, a_new)
    y_brk = (params[P_BRK0] + params[P_BRK1] * zt / d) * d
    z_res = min(zt, params[P_ZRES])

    if phase == PHASE_TROUGH and smax > y_brk:
        phase = PHASE_BREAKOUT
    if phase == PHASE_BREAKOUT:
        z = zt + (z_res - zt) * (min(smax, y_res) - y_brk) / (y_res - y_brk)
        if a_new > y_res:
            phase = PHASE_OUT
            z = z_res
    elif phase == PHASE_TROUGH:
        z = zt

    fr_peak = clay_passive(params, zt)
    fr_res = clay_passive(params, z_res)
    mag, slope = envelope(a_new, fr_peak, fr_peak, fr_res, y_brk, y_brk, y_res)
    k_u = fr_peak / y_brk
    if legacy:
        passive = sign(s_new) * mag
        e_passive = envelope_energy(a_new, fr_peak, fr_peak, fr_res, y_brk, y_brk, y_res)
    else:
        passive, slope = push_only_passive(p_old, dy, s_new, mag, slope, k_u)
        e_passive = 0.0
        if k_u > 0.0:
            e_passive = 0.5 * passive * passive / k_u
    if v_load <= 0.0:
        passive = 0.0
        slope = 0.0
        e_passive = 0.0

    r_new = f + passive
    r_old = f_old + state_old[S_PASSIVE]
    work = state_old[S_WORK] + 0.5 * (abs(r_old) + abs(r_new)) * abs(dy)
    if not legacy:
        r_old = f_old + p_old
    if legacy:
        soil_work = state_old[S_SOIL_WORK] + 0.5 * (r_old + r_new) * dy
    else:
        # each spring: work along its return-mapped increment, from its start force
        soil_work = state_old[S_SOIL_WORK] + elastoplastic_soil_work(
            f_old, f, p_old, passive, s_new, mag, k_u, dy, v_load, params[P_MU], params[P_DELTA]
        )
    stored = friction_energy(f, v_load, params[P_MU], params[P_DELTA]) + e_passive

    region = region_of(a_new, y_brk, y_brk, y_res)  # 1 rising, 3 softening, 4 residual
    state_new[S_Y] = y_new
    state_new[S_FRICTION] = f
    state_new[S_Z] = z
    state_new[S_WORK] = work
    state_new[S_REGION] = region
    state_new[S_SOIL_WORK] = soil_work
    state_new[S_Y0] = y0
    state_new[S_ZT] = zt
    state_new[S_SMAX] = smax
    state_new[S_PHASE] = phase
    if direction != 0.0:
        state_new[S_DIR] = direction
    state_new[S_PASSIVE] = passive

    out[OUT_R] = r_new
    out[OUT_FRICTION] = f
    out[OUT_PASSIVE] = passive
    out[OUT_TANGENT] = k_f + slope
    out[OUT_Z] = z
    out[OUT_WORK] = work
    out[OUT_REGION] = region
    out[OUT_STORED] = stored
    out[OUT_DISSIPATED] = soil_work - stored


verley_lund_kernel_py = pure_python(verley_lund_kernel)
"""Plain-Python twin of :func:`verley_lund_kernel` (same source, interpreted)."""

__all__ = [
    "N_PARAMS",
    "N_STATE",
    "clay_passive",
    "verley_lund_kernel",
    "verley_lund_kernel_py",
]
