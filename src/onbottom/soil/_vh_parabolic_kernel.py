"""Numba kernel of the parabolic V–H force-resultant test model (private).

Second-form (two-degree-of-freedom) kernel of :mod:`onbottom.soil.base`; the model and its
sources: :mod:`onbottom.soil.vh_parabolic`, docs/theory/vh_parabolic.md.

params: [mu, mu_flow, delta, k_p]; model state slot ``S_VP`` (vertical capacity V_p [N/m]).

One increment, vertical load V given (mixed control), from the committed (H₀, z₀, V_p,0):

1. V <= 0: lift-off — H = 0, z and V_p frozen, every tangent 0.
2. Bearing: V > V_p,0 moves the pipe down until the hardened capacity carries V:
   z_a = z₀ + (V − V_p,0)/k_p, V_p,a = V (k_p = 0: no equilibrium, R = NaN).
3. Lateral predictor (as Coulomb): C = μV(1 − V/V_p,a), k = μV/δ,
   H_tr = clamp(H₀, ±C) + k·Δy.
4. |H_tr| <= C: elastic, H = H_tr, z = z_a. Otherwise plastic: H = sign(H_tr)·C, plastic
   multiplier Δλ = (|H_tr| − C)/k (= lateral plastic slip), vertical plastic flow
   Δz = Δλ·∂g/∂V with g = |H| − μ′V(1 − V/V_p) (flow direction at V, V_p,a), z = z_a + Δz,
   V_p = V_p,a + k_p·Δz.
"""

from __future__ import annotations

import math

from onbottom._jit import jitted_only, pure_python
from onbottom.soil._trough import spring_work
from onbottom.soil.base import (
    N_COMMON_STATE,
    OUT2_DH_DV,
    OUT2_DZ_DV,
    OUT2_DZ_DY,
    OUT2_SIZE,
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
P_MU_FLOW = 1
P_DELTA = 2
P_KP = 3
N_PARAMS = 4

S_VP = N_COMMON_STATE  # vertical bearing capacity V_p [N/m] (hardens with z)
N_STATE = N_COMMON_STATE + 1

REGION_ELASTIC = 0.0
REGION_SLIDING = 1.0
REGION_BEARING = 2.0  # vertical bearing failure in this increment (z moved down to carry V)
REGION_LIFTED = 3.0


@jitted_only(error_model="python")
def yield_function(h, v, vp, mu):
    """f(V, H) = |H| − μV(1 − V/V_p) [N/m]: < 0 inside the surface, 0 on it."""
    return abs(h) - mu * v * (1.0 - v / vp)


@jitted_only(error_model="python")
def flow_direction(v, vp, mu_flow):
    """∂g/∂V = −μ′(1 − 2V/V_p) of the plastic potential g = |H| − μ′V(1 − V/V_p) [-].

    Vertical plastic displacement per unit lateral plastic slip: < 0 (heave) for V < V_p/2,
    > 0 (penetration) for V > V_p/2.
    """
    return -mu_flow * (1.0 - 2.0 * v / vp)


@jitted_only(error_model="python")
def vh_parabolic_kernel(params, state_old, y_new, v_load, state_new, out):
    mu = params[P_MU]
    mu_f = params[P_MU_FLOW]
    delta = params[P_DELTA]
    kp = params[P_KP]
    dy = y_new - state_old[S_Y]
    h_old = state_old[S_FRICTION]
    z_old = state_old[S_Z]
    vp_old = state_old[S_VP]
    for i in range(state_old.shape[0]):
        state_new[i] = state_old[i]
    state_new[S_Y] = y_new
    coupled = out.shape[0] >= OUT2_SIZE
    if v_load <= 0.0:
        # 1. lift-off: no contact, the soil state is frozen
        state_new[S_FRICTION] = 0.0
        state_new[S_WORK] = state_old[S_WORK] + abs(0.5 * h_old * dy)
        state_new[S_REGION] = REGION_LIFTED
        out[OUT_R] = 0.0
        out[OUT_FRICTION] = 0.0
        out[OUT_PASSIVE] = 0.0
        out[OUT_TANGENT] = 0.0
        out[OUT_Z] = z_old
        out[OUT_WORK] = state_new[S_WORK]
        out[OUT_REGION] = REGION_LIFTED
        out[OUT_STORED] = 0.0
        out[OUT_DISSIPATED] = state_new[S_SOIL_WORK]
        if coupled:
            out[OUT2_DH_DV] = 0.0
            out[OUT2_DZ_DY] = 0.0
            out[OUT2_DZ_DV] = 0.0
        return
    # 2. bearing: V above the vertical capacity
    z_a = z_old
    vp_a = vp_old
    dza_dv = 0.0
    dvp_dv = 0.0
    region = REGION_ELASTIC
    if v_load > vp_old:
        if kp <= 0.0:
            for i in range(out.shape[0]):
                out[i] = 0.0
            out[OUT_R] = math.nan  # no equilibrium without hardening (contract rule 2.6)
            return
        z_a = z_old + (v_load - vp_old) / kp
        vp_a = v_load
        dza_dv = 1.0 / kp
        dvp_dv = 1.0
        region = REGION_BEARING
    # 3. lateral predictor; fric = μV, written as in the Coulomb kernel so that V_p = ∞
    # (C = μV·1.0) reproduces it bit for bit
    fric = mu * v_load
    k = fric / delta
    cap = fric * (1.0 - v_load / vp_a)
    # dC/dV with V_p,a = V_p,a(V): μ(1 − 2V/V_p) + μV²/V_p²·dV_p/dV
    dcap_dv = mu * (1.0 - 2.0 * v_load / vp_a) + mu * v_load * v_load / (vp_a * vp_a) * dvp_dv
    h0 = min(max(h_old, -cap), cap)
    dh0_dv = 0.0
    if h_old > cap:
        dh0_dv = dcap_dv
    elif h_old < -cap:
        dh0_dv = -dcap_dv
    h_tr = h0 + k * dy
    dhtr_dv = dh0_dv + mu / delta * dy
    if h_tr > cap or h_tr < -cap:
        # 4. plastic: return to the surface, vertical flow from the potential
        s = 1.0 if h_tr > 0.0 else -1.0
        h = s * cap
        tangent = 0.0
        dh_dv = s * dcap_dv
        dlam = (s * h_tr - cap) / k
        n_v = flow_direction(v_load, vp_a, mu_f)
        dz = dlam * n_v
        z = z_a + dz
        vp = vp_a + kp * dz
        dz_dy = s * n_v
        dlam_dv = (s * dhtr_dv - dcap_dv) / k - dlam * (mu / delta) / k
        dn_dv = 2.0 * mu_f * (1.0 / vp_a - v_load * dvp_dv / (vp_a * vp_a))
        dz_dv = dza_dv + dlam_dv * n_v + dlam * dn_dv
        if region == REGION_ELASTIC:
            region = REGION_SLIDING
    else:
        h = h_tr
        tangent = k
        dh_dv = dhtr_dv
        z = z_a
        vp = vp_a
        dz_dy = 0.0
        dz_dv = dza_dv
    state_new[S_FRICTION] = h
    state_new[S_Z] = z
    state_new[S_VP] = vp
    state_new[S_WORK] = state_old[S_WORK] + abs(0.5 * (h + h_old) * dy)
    state_new[S_REGION] = region
    # soil work: the lateral spring along its return-mapped increment plus V·Δz
    w = spring_work(h0, h, h_tr, k) + v_load * (z - z_old)
    state_new[S_SOIL_WORK] = state_old[S_SOIL_WORK] + w
    stored = 0.5 * h * h / k
    out[OUT_R] = h
    out[OUT_FRICTION] = h
    out[OUT_PASSIVE] = 0.0
    out[OUT_TANGENT] = tangent
    out[OUT_Z] = z
    out[OUT_WORK] = state_new[S_WORK]
    out[OUT_REGION] = region
    out[OUT_STORED] = stored
    out[OUT_DISSIPATED] = state_new[S_SOIL_WORK] - stored
    if coupled:
        out[OUT2_DH_DV] = dh_dv
        out[OUT2_DZ_DY] = dz_dy
        out[OUT2_DZ_DV] = dz_dv


vh_parabolic_kernel_py = pure_python(vh_parabolic_kernel)
yield_function_py = pure_python(yield_function)
flow_direction_py = pure_python(flow_direction)
