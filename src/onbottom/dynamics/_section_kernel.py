"""Numba time loop of the load-controlled rigid pipe section (private).

Equation of lateral motion (docs/conventions.md): m·ü = H(t) − R(u, history), with R from
``lateral_step(model_id, ...)`` of :mod:`onbottom.soil.kernel_contract` (rules: onbottom.soil.base).

Each step t → t + Δt solves the implicit equation of an integrator for u_{n+1}:

* backward Euler (``SCHEME_BACKWARD_EULER``): v₁ = (u₁ − u₀)/Δt, a₁ = (v₁ − v₀)/Δt;
* Newmark (``SCHEME_NEWMARK``, γ, β; average acceleration γ = ½, β = ¼):
  a₁ = (u₁ − û)/(βΔt²), v₁ = v₀ + Δt((1 − γ)a₀ + γa₁), û = u₀ + Δt v₀ + Δt²(½ − β)a₀;

both reduce to the scalar residual r(u) = c₀(u − û) + R(u) − H₁ = 0 with c₀ = m/Δt²
(backward Euler, û = u₀ + Δt v₀) or m/(βΔt²). r is solved by Newton iterations on the kernel
tangent dR/du inside a bracket [lo, hi] with r(lo) < 0 < r(hi) that every iteration narrows;
a Newton iterate outside the bracket (or a non-positive Jacobian) is replaced by bisection,
which always converges, also across the kinks and jumps of friction and softening laws.
A step is accepted when r converged, |u₁ − u₀| <= du_max (regions of the soil model are
resolved) and c₀ + dR/du > 0 (the step's root is locally unique); otherwise Δt is halved down
to dt_min. Accepted steps commit the soil state (the kernel's trial state at u₁).

Buffers (float64):
``settings[ST_*]``, ``dyn[D_*]`` (integrator state, mutated), ``rec[n, REC_*]`` (records).
"""

from __future__ import annotations

import math

import numpy as np
from numba import literally

from onbottom._jit import borrow, jitted_only
from onbottom._jit import numba_njit as njit
from onbottom.dynamics._newton import safeguarded_update
from onbottom.dynamics.status import Status
from onbottom.soil.base import (
    OUT_DISSIPATED,
    OUT_FRICTION,
    OUT_PASSIVE,
    OUT_R,
    OUT_REGION,
    OUT_SIZE,
    OUT_STORED,
    OUT_TANGENT,
    OUT_WORK,
    OUT_Z,
)
from onbottom.soil.kernel_contract import lateral_step_of as lateral_step

SCHEME_BACKWARD_EULER = 0
SCHEME_NEWMARK = 1

AFTER_STOP = 0
AFTER_RUNAWAY_END = 1
AFTER_CONTINUE = 2

# settings
ST_SCHEME = 0
ST_DT_MAX = 1
ST_DT_MIN = 2
ST_DU_MAX = 3
ST_RTOL = 4
ST_MAX_ITER = 5
ST_U_LIMIT = 6
ST_AFTER_LIMIT = 7
ST_GAMMA = 8
ST_BETA = 9
ST_MASS = 10
N_SETTINGS = 11

# integrator state
D_T = 0
D_U = 1
D_V = 2
D_A = 3
D_DT = 4
D_CROSSED = 5
D_T_CROSS = 6
D_V_CROSS = 7
D_IDX = 8
D_N_REJECT = 9
D_T_END_RUN = 10
N_DYN = 11

# record columns
REC_T = 0
REC_H = 1
REC_V = 2
REC_U = 3
REC_UDOT = 4
REC_W = 5
REC_FF = 6
REC_FP = 7
REC_FS = 8
REC_WORK = 9
REC_REGION = 10
REC_E_STORED = 11  # elastic energy stored in the soil [N·m/m] (soil kernel OUT_STORED)
REC_E_DISSIPATED = 12  # energy dissipated by the soil since the start [N·m/m]
N_REC = 13

STATUS_CHUNK = int(Status.CHUNK)
STATUS_END = int(Status.END)
STATUS_LIMIT = int(Status.LIMIT)
STATUS_RUNAWAY_END = int(Status.RUNAWAY_END)
STATUS_BUFFER_FULL = int(Status.BUFFER_FULL)
STATUS_STEP_FAILED = int(Status.STEP_FAILED)
STATUS_SOIL_NAN = int(Status.SOIL_NAN)


@jitted_only(error_model="python")
def loads_at(t, pt, ph, pv, i0):
    """Linear interpolation of (H, V) at t, searching forward from index i0 (pt[i0] <= t)."""
    n = pt.shape[0]
    if t >= pt[n - 1]:
        return ph[n - 1], pv[n - 1], n - 2
    if t <= pt[0]:
        return ph[0], pv[0], 0
    i = i0
    if i < 0 or pt[i] > t:
        i = 0
    while i < n - 2 and pt[i + 1] < t:
        i += 1
    f = (t - pt[i]) / (pt[i + 1] - pt[i])
    return ph[i] + f * (ph[i + 1] - ph[i]), pv[i] + f * (pv[i + 1] - pv[i]), i


@jitted_only(error_model="python")
def solve_step(model_id, params, state_old, u0, du_hat, c0, h1, v1, rtol, max_iter, trial, out):
    """Solve r(Δu) = c0·(Δu − Δû) + R(u0 + Δu) − h1 = 0 for the increment Δu.

    Safeguarded Newton (see module docstring). Working with the increment keeps the inertia
    term exact when c0 = m/Δt² is large (u0 itself may be metres). Returns
    (Δu, converged, iterations); on return ``trial``/``out`` hold the kernel result at u0 + Δu.
    """
    scale = abs(h1) + abs(v1) + 1.0
    tol_r = rtol * scale
    # np.bool_, not the literal False: one specialisation of safeguarded_update, not two
    have_lo = np.bool_(False)
    have_hi = np.bool_(False)
    lo = 0.0
    hi = 0.0
    du = du_hat
    eps_u = 4.0e-16 * (abs(u0) + abs(du_hat) + 1e-12)
    for it in range(max_iter):
        lateral_step(
            model_id, borrow(params), borrow(state_old), u0 + du, v1, borrow(trial), borrow(out)
        )
        big_r = out[OUT_R]
        if not math.isfinite(big_r):
            return du, False, it + 1
        r = c0 * (du - du_hat) + big_r - h1
        if abs(r) <= tol_r:
            return du, True, it + 1
        du_next, lo, hi, have_lo, have_hi, closed = safeguarded_update(
            du, r, c0, out[OUT_TANGENT], lo, hi, have_lo, have_hi, eps_u
        )
        if closed:
            # a jump of R across the root (discontinuous law), or the root resolved to the
            # precision of u: accept the bracket point
            return du, True, it + 1
        if abs(du_next - du) <= eps_u:
            # Newton correction below the resolution of u: converged to machine precision
            lateral_step(
                model_id, borrow(params), borrow(state_old), u0 + du_next, v1, borrow(trial),
                borrow(out),
            )  # fmt: skip
            return du_next, True, it + 1
        du = du_next
    return du, False, max_iter


@njit(cache=True)
def initial_record(model_id, params, state, dyn, pt, ph, pv, settings, rec, n):
    """Write the record of the initial point and set the initial acceleration (Newmark)."""
    literally(model_id)  # compile only the soil model used (soil._dispatch.lateral_step_of)
    trial = np.empty_like(state)
    out = np.empty(OUT_SIZE)
    h0, v0, _ = loads_at(dyn[D_T], pt, ph, pv, 0)
    lateral_step(model_id, params, state, dyn[D_U], v0, trial, out)
    dyn[D_A] = (h0 - out[OUT_R]) / settings[ST_MASS]
    _write(rec, n, dyn[D_T], h0, v0, dyn[D_U], dyn[D_V], out)


@jitted_only(error_model="python")
def _write(rec, n, t, h, v, u, udot, out):
    rec[n, REC_T] = t
    rec[n, REC_H] = h
    rec[n, REC_V] = v
    rec[n, REC_U] = u
    rec[n, REC_UDOT] = udot
    rec[n, REC_W] = out[OUT_Z]
    rec[n, REC_FF] = out[OUT_FRICTION]
    rec[n, REC_FP] = out[OUT_PASSIVE]
    rec[n, REC_FS] = out[OUT_R]
    rec[n, REC_WORK] = out[OUT_WORK]
    rec[n, REC_REGION] = out[OUT_REGION]
    rec[n, REC_E_STORED] = out[OUT_STORED]
    rec[n, REC_E_DISSIPATED] = out[OUT_DISSIPATED]


@njit(cache=True)
def integrate(model_id, params, state, dyn, pt, ph, pv, settings, t_stop, rec, n0):
    """Advance from dyn[D_T] until t_stop, the programme end, an event, or a full buffer.

    ``state`` (committed soil state) and ``dyn`` are updated in place; records are appended to
    ``rec`` from row ``n0``. Returns (rows written in total, status).
    """
    literally(model_id)  # compile only the soil model used (soil._dispatch.lateral_step_of)
    m = settings[ST_MASS]
    scheme = int(settings[ST_SCHEME])
    dt_max = settings[ST_DT_MAX]
    dt_min = settings[ST_DT_MIN]
    du_max = settings[ST_DU_MAX]
    rtol = settings[ST_RTOL]
    max_iter = int(settings[ST_MAX_ITER])
    u_limit = settings[ST_U_LIMIT]
    after = int(settings[ST_AFTER_LIMIT])
    gam = settings[ST_GAMMA]
    beta = settings[ST_BETA]
    t_end = pt[pt.shape[0] - 1]
    cap = rec.shape[0]
    trial = np.empty_like(state)
    out = np.empty(OUT_SIZE)
    n = n0
    idx = int(dyn[D_IDX])
    while True:
        t = dyn[D_T]
        if t >= t_end - 1e-12 * (1.0 + abs(t_end)):
            return n, STATUS_END
        if t >= t_stop:
            return n, STATUS_CHUNK
        if n >= cap:
            return n, STATUS_BUFFER_FULL
        u = dyn[D_U]
        v = dyn[D_V]
        a = dyn[D_A]
        dt = min(dyn[D_DT], dt_max)
        if t + dt > t_end - 0.01 * dt_min:
            dt = t_end - t
        t1 = t + dt
        h1, v1, idx1 = loads_at(t1, pt, ph, pv, idx)
        if scheme == SCHEME_NEWMARK:
            c0 = m / (beta * dt * dt)
            du_hat = dt * v + dt * dt * (0.5 - beta) * a
        else:
            c0 = m / (dt * dt)
            du_hat = dt * v
        du, conv, iters = solve_step(
            model_id, borrow(params), borrow(state), u, du_hat, c0, h1, v1, rtol, max_iter,
            borrow(trial), borrow(out),
        )  # fmt: skip
        if not math.isfinite(out[OUT_R]):
            return n, STATUS_SOIL_NAN
        u1 = u + du
        ok = conv and abs(du) <= du_max and (c0 + out[OUT_TANGENT]) > 0.0
        if not ok:
            if dt > dt_min * 1.000001:
                dyn[D_DT] = max(0.5 * dt, dt_min)
                dyn[D_N_REJECT] += 1.0
                continue
            if not conv:
                return n, STATUS_STEP_FAILED
            # at dt_min: accept a converged step even if large or locally non-unique
        # ---- commit
        if scheme == SCHEME_NEWMARK:
            a1 = (du - du_hat) / (beta * dt * dt)
            v1dot = v + dt * ((1.0 - gam) * a + gam * a1)
        else:
            v1dot = du / dt
            a1 = (v1dot - v) / dt
        for i in range(state.shape[0]):
            state[i] = trial[i]
        dyn[D_T] = t1
        dyn[D_U] = u1
        dyn[D_V] = v1dot
        dyn[D_A] = a1
        idx = idx1
        dyn[D_IDX] = idx1
        _write(borrow(rec), n, t1, h1, v1, u1, v1dot, borrow(out))
        n += 1
        if iters <= 4 and abs(du) < 0.5 * du_max:
            dyn[D_DT] = min(2.0 * dt, dt_max)
        else:
            dyn[D_DT] = dt
        # ---- events
        if math.isfinite(u_limit):
            if dyn[D_CROSSED] == 0.0 and abs(u1) >= u_limit:
                frac = (u_limit - abs(u)) / max(abs(u1) - abs(u), 1e-300)
                frac = min(max(frac, 0.0), 1.0)
                dyn[D_CROSSED] = 1.0
                dyn[D_T_CROSS] = t + frac * dt
                dyn[D_V_CROSS] = v1dot
                if after == AFTER_STOP:
                    return n, STATUS_LIMIT
            elif dyn[D_CROSSED] == 1.0 and after == AFTER_RUNAWAY_END:
                if v1dot * dyn[D_V_CROSS] <= 0.0:
                    return n, STATUS_RUNAWAY_END
