"""Numba kernel for elastic–perfectly-plastic Coulomb friction (private).

params: [mu, mobilisation_displacement]
"""

from __future__ import annotations

from onbottom._jit import jitted_only
from onbottom.soil._trough import spring_work
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

P_MU = 0
P_DELTA = 1


@jitted_only
def friction_return_map(f_old: float, dy: float, v_load: float, mu: float, delta: float):
    """Elastic predictor / plastic corrector for the Coulomb force (resisting +y).

    Stiffness k = μ·V/δ so that full friction μV mobilises after a displacement δ from rest.
    The predictor starts from the committed force returned into the current capacity ±μV (V
    may have dropped since), so a reversal unloads from the capacity.
    Returns (force, tangent). With V <= 0 the pipe is lifted off: force 0, tangent 0.
    """
    if v_load <= 0.0:
        return 0.0, 0.0
    cap = mu * v_load
    k = cap / delta
    f_trial = min(max(f_old, -cap), cap) + k * dy
    if f_trial > cap:
        return cap, 0.0
    if f_trial < -cap:
        return -cap, 0.0
    return f_trial, k


@jitted_only
def coulomb_kernel(params, state_old, y_new, v_load, state_new, out):
    mu = params[P_MU]
    delta = params[P_DELTA]
    dy = y_new - state_old[S_Y]
    f, k = friction_return_map(state_old[S_FRICTION], dy, v_load, mu, delta)
    # the common slots are all written below; a longer row (a solver's nodes on several
    # models) keeps its other slots
    for i in range(N_COMMON_STATE, state_old.shape[0]):
        state_new[i] = state_old[i]
    state_new[S_Y] = y_new
    state_new[S_FRICTION] = f
    state_new[S_Z] = 0.0
    state_new[S_WORK] = state_old[S_WORK] + abs(0.5 * (f + state_old[S_FRICTION]) * dy)
    state_new[S_REGION] = 0.0
    stored = 0.0
    k_fr = 0.0
    if mu * v_load > 0.0:
        stored = 0.5 * f * f * delta / (mu * v_load)
        k_fr = mu * v_load / delta
    f0 = min(max(state_old[S_FRICTION], -mu * v_load), mu * v_load)
    w_f = spring_work(f0, f, f0 + k_fr * dy, k_fr)
    state_new[S_SOIL_WORK] = state_old[S_SOIL_WORK] + w_f
    out[OUT_R] = f
    out[OUT_FRICTION] = f
    out[OUT_PASSIVE] = 0.0
    out[OUT_TANGENT] = k
    out[OUT_Z] = 0.0
    out[OUT_WORK] = state_new[S_WORK]
    out[OUT_REGION] = 0.0
    out[OUT_STORED] = stored
    out[OUT_DISSIPATED] = state_new[S_SOIL_WORK] - stored


def friction_return_map_py(f_old, dy, v_load, mu, delta):
    """Plain-Python twin of :func:`friction_return_map`."""
    if v_load <= 0.0:
        return 0.0, 0.0
    cap = mu * v_load
    k = cap / delta
    f_trial = min(max(f_old, -cap), cap) + k * dy
    if f_trial > cap:
        return cap, 0.0
    if f_trial < -cap:
        return -cap, 0.0
    return f_trial, k


def coulomb_kernel_py(params, state_old, y_new, v_load, state_new, out):
    """Plain-Python twin of :func:`coulomb_kernel`."""
    dy = y_new - state_old[S_Y]
    f, k = friction_return_map_py(state_old[S_FRICTION], dy, v_load, params[P_MU], params[P_DELTA])
    state_new[:] = state_old
    state_new[S_Y] = y_new
    state_new[S_FRICTION] = f
    state_new[S_Z] = 0.0
    state_new[S_WORK] = state_old[S_WORK] + abs(0.5 * (f + state_old[S_FRICTION]) * dy)
    state_new[S_REGION] = 0.0
    cap = params[P_MU] * v_load
    stored = 0.5 * f * f * params[P_DELTA] / cap if cap > 0.0 else 0.0
    k_fr = cap / params[P_DELTA] if cap > 0.0 else 0.0
    f0 = min(max(state_old[S_FRICTION], -cap), cap) if cap > 0.0 else 0.0
    state_new[S_SOIL_WORK] = state_old[S_SOIL_WORK] + spring_work.py_func(
        f0, f, f0 + k_fr * dy, k_fr
    )
    soil_work = state_new[S_SOIL_WORK]
    out[:] = (f, f, 0.0, k, 0.0, state_new[S_WORK], 0.0, stored, soil_work - stored)
