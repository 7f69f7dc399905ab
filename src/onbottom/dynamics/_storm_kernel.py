"""Numba time loop of a pipe section in a storm, loads fed back by the pipe's motion (private).

Equation of lateral motion per unit length (docs/theory/storm_section.md):

    (m + m_a) ÿ = F_Y(t, ẏ, z) − R(y, V(t), history),    m_a = ρ_w (π D²/4) C_a
    F_Y = r_y(z) [ ½ ρ_w D C_D (U + V_c − ẏ)|U + V_c − ẏ| + ρ_w (π D²/4) C_M U̇ ]
    V(t) = w_s − F_Z,   F_Z = r_z(z) ½ ρ_w D C_L (U + V_c)²

(the force model's kernel through :func:`onbottom.hydro._force_dispatch.force_step`, Morison +
lift by default, its outputs F_Y, ∂F_Y/∂ẏ, F_Z times the reductions r_y, r_z here). R from
``onbottom.soil._dispatch.lateral_step`` with V(t) as its vertical load. r_y = r_const,y ·
r_pen,y(z/D), r_z = r_const,z · r_pen,z(z/D) (DNV-RP-F109 (2017) Eqs 3.17–3.20) with z the
penetration of the committed soil state at the start of the step (one-step lag, as CORUS-3D
updates them "every increment").

Each step t → t + Δt is Newmark (γ, β; default average acceleration ½, ¼) for the increment Δy:
a₁ = (Δy − Δŷ)/(βΔt²), ẏ₁ = ẏ₀ + Δt(1 − γ)a₀ + γ/(βΔt)·(Δy − Δŷ), Δŷ = Δt ẏ₀ + Δt²(½ − β)a₀,
residual r(Δy) = M a₁ + R(y₀ + Δy) − F_Y(t₁, ẏ₁) = 0, with the velocity-dependent drag inside the
Newton iteration: dr/dΔy = M/(βΔt²) + dR/dy − (dF_Y/dẏ)·γ/(βΔt) (dF_Y/dẏ <= 0 adds damping). The
Newton iterate is safeguarded by a bracket and bisection as in ``_section_kernel.solve_step``.
A step is accepted when r converged and |Δy| <= du_max; otherwise Δt is halved down to dt_min.
After easy steps Δt doubles back up to dt_max.

Energy accounting (trapezoidal, signed): W_hydro += ½(F₀ + F₁)Δy, W_soil += ½(R₀ + R₁)Δy; with
average-acceleration Newmark ½M(ẏ₁² − ẏ₀²) = W_hydro − W_soil holds to round-off per step.

Validity: the first time the committed penetration exceeds ``ST_Z_LIMIT`` (D/2 for the
Verley & Sotberg and Verley & Lund models) is kept in ``D_T_ZLIMIT`` (and y in
``D_Y_ZLIMIT``); the run goes on and the caller flags the result, as the section solver does.

Events: lift-off (V <= 0) — the pipe is free of soil while lifted (``LIFTOFF_FREE``, the soil
kernels return zero resistance) or the run stops (``LIFTOFF_STOP``); |y| >= y_limit stops the run
(runaway).

Force-model state: ``fstate`` (``N_FORCE_STATE`` slots, zeros at the start) is committed with
the soil state when a step is accepted, from the force evaluation at the accepted (t₁, ẏ₁); the
Newton iterations and rejected steps evaluate the model from the committed state only. A model
with the optional two-stage form (rule 7 of :mod:`onbottom.hydro._force_dispatch`: the wake
model) is prepared once per trial step (its history and ``exp`` terms, which do not depend on
ẏ) and evaluated per iterate from that, bit for bit the one-call kernel's values; its one-call
kernel is not compiled into this module's functions
(:func:`onbottom.hydro.kernel_contract.force_step_unprepared_of`).

Compiling: :func:`integrate` is the only entry point (``n0 < 0`` runs the start); the other
functions of this module are inlined into it at numba-IR level (``inline="always"``), so a
storm compiles one function over the soil and force models' kernels, not one per helper (each
compiled function links, re-optimises and re-emits the machine code of everything it calls).

Buffers (float64): ``settings[ST_*]``, ``dyn[D_*]`` (state + running summary, mutated),
``kin_u``, ``kin_a`` (U, U̇ at t = j·Δt_s), ``fparams[nc, n_params]`` (the force model's
parameters: one row, or one row per flow sample j), ``fstate[N_FORCE_STATE]`` (committed force
state, mutated), ``rec[n, REC_*]`` (records every ``ST_REC_INTERVAL`` seconds; a zero-row
buffer records nothing).
"""

from __future__ import annotations

import math

import numpy as np
from numba import literally

from onbottom._jit import borrow, njit, row_view
from onbottom.dynamics._newton import safeguarded_update
from onbottom.dynamics.status import Status
from onbottom.hydro.kernel_contract import (
    FO_DFY_DYD,
    FO_FY,
    FO_FZ,
    FO_SIZE,
    N_FORCE_PREP,
    penetration_reduction_y,
    penetration_reduction_z,
)
from onbottom.hydro.kernel_contract import force_evaluate_of as force_evaluate
from onbottom.hydro.kernel_contract import force_prepare_of as force_prepare
from onbottom.hydro.kernel_contract import force_step_unprepared_of as force_step
from onbottom.soil.base import (
    OUT_FRICTION,
    OUT_PASSIVE,
    OUT_R,
    OUT_REGION,
    OUT_SIZE,
    OUT_TANGENT,
    OUT_WORK,
    OUT_Z,
    S_Z,
)
from onbottom.soil.kernel_contract import lateral_step_of as lateral_step

LIFTOFF_FREE = 0
LIFTOFF_STOP = 1

# settings
ST_DT_MAX = 0
ST_DT_MIN = 1
ST_DU_MAX = 2
ST_RTOL = 3
ST_MAX_ITER = 4
ST_Y_LIMIT = 5
ST_MASS = 6  # m + m_a
ST_GAMMA = 7
ST_BETA = 8
ST_RHO = 9
ST_D = 10
ST_WS = 11
ST_RY_CONST = 12
ST_RZ_CONST = 13
ST_USE_PEN = 14
ST_LIFTOFF = 15
ST_REC_INTERVAL = 16
ST_CURRENT = 17
ST_DTS = 18
ST_T_END = 19
ST_FORCE_MODEL = 20  # force model id (onbottom.hydro._force_dispatch)
ST_Z_LIMIT = 21  # penetration beyond the soil model's range [m] (inf: none)
N_SETTINGS = 22

# dynamic state and running summary
D_T = 0
D_Y = 1
D_YD = 2
D_A = 3
D_DT = 4
D_N_REJECT = 5
D_N_STEPS = 6
D_N_ITER = 7
D_YMAX = 8
D_T_YMAX = 9
D_N_LIFTOFF = 10
D_T_LIFTOFF = 11
D_LIFTED = 12
D_W_HYDRO = 13
D_W_SOIL = 14
D_F_PREV = 15
D_R_PREV = 16
D_NEXT_REC = 17
D_ZMAX = 18
D_ZMIN = 19
D_T_LIMIT = 20
D_FZ_MAX = 21
D_V_MIN = 22
D_T_ZLIMIT = 23  # time the penetration first exceeded ST_Z_LIMIT [s] (-1: never)
D_Y_ZLIMIT = 24  # displacement y at that time [m]
N_DYN = 25

# record columns
REC_T = 0
REC_Y = 1
REC_YD = 2
REC_Z = 3
REC_FY = 4
REC_FZ = 5
REC_V = 6
REC_FF = 7
REC_FP = 8
REC_R = 9
REC_W_HYDRO = 10
REC_W_SOIL = 11
REC_U = 12
REC_RY = 13
REC_RZ = 14
REC_REGION = 15
REC_SOIL_WORK = 16
N_REC = 17

STATUS_CHUNK = int(Status.CHUNK)
STATUS_END = int(Status.END)
STATUS_LIMIT = int(Status.LIMIT)
STATUS_LIFTOFF = int(Status.LIFTOFF)
STATUS_BUFFER_FULL = int(Status.BUFFER_FULL)
STATUS_STEP_FAILED = int(Status.STEP_FAILED)
STATUS_SOIL_NAN = int(Status.SOIL_NAN)


@njit(cache=True, inline="always")
def flow_at(t, kin_u, kin_a, dts):
    """U, U̇ at time t by linear interpolation of the samples; index of the left sample."""
    n = kin_u.shape[0]
    x = t / dts
    j = int(x)
    if j >= n - 1:
        return kin_u[n - 1], kin_a[n - 1], n - 1
    if j < 0:
        return kin_u[0], kin_a[0], 0
    f = x - j
    return (
        kin_u[j] + f * (kin_u[j + 1] - kin_u[j]),
        kin_a[j] + f * (kin_a[j + 1] - kin_a[j]),
        j,
    )


@njit(cache=True, inline="always")
def parameter_row(fparams, j):
    """The force model's parameters for flow sample j: the only row, or row j (clamped)."""
    nc = fparams.shape[0]
    jj = j if nc > 1 else 0
    if jj >= nc:
        jj = nc - 1
    return row_view(fparams, jj)


@njit(cache=True, inline="always")
def load_reductions(settings, z):
    """(r_y, r_z) = (r_const,y·r_pen,y(z/D), r_const,z·r_pen,z(z/D)) at the penetration z [m]."""
    ry = settings[ST_RY_CONST]
    rz = settings[ST_RZ_CONST]
    if settings[ST_USE_PEN] != 0.0:
        d = settings[ST_D]
        ry *= penetration_reduction_y(z / d)
        rz *= penetration_reduction_z(z / d)
    return ry, rz


@njit(cache=True, inline="always")
def forces(force_id, settings, prow, fstate, t, u, dudt, ydot, fstate_new, fout):
    """The force model ``force_id`` (``settings[ST_FORCE_MODEL]``, passed as a literal) with the
    parameter row ``prow`` from the committed ``fstate``:
    :func:`onbottom.hydro._force_dispatch.force_step` writing ``fstate_new`` and ``fout``
    (F_Y, ∂F_Y/∂ẏ, F_Z, ∂F_Z/∂ẏ before reductions)."""
    force_step(
        force_id,
        prow,
        fstate,
        t,
        u,
        dudt,
        settings[ST_CURRENT],
        ydot,
        settings[ST_D],
        settings[ST_RHO],
        fstate_new,
        fout,
    )


@njit(cache=True, inline="always")
def prepare_forces(force_id, settings, prow, fstate, t, u, dudt, fstate_new, fprep):
    """The force model's once-per-step stage at the trial step end t (contract rule 7 of
    :mod:`onbottom.hydro._force_dispatch`): writes ``fstate_new`` and ``fprep``; False when the
    model has none (then every evaluation calls :func:`forces`)."""
    return force_prepare(
        force_id, prow, fstate, t, u, dudt, settings[ST_CURRENT], settings[ST_D],
        settings[ST_RHO], fstate_new, fprep,
    )  # fmt: skip


@njit(cache=True, inline="always")
def solve_step(model_id, force_id, params, state, settings, prow, fs, t1, u1, a1dot, y0, yd0, a0,
               dt, ry, rz, trial, out, fs_new, fout, prepared, fprep):  # fmt: skip
    """Solve the Newmark residual for Δy (module docstring); returns (Δy, converged, iters).

    ``prow``, ``fs``: the force parameters of the step and the committed force state;
    ``fs_new``, ``fout`` scratch of the force model (as ``trial``, ``out`` of the soil model);
    ``prepared``: :func:`prepare_forces` has filled ``fs_new`` and ``fprep`` for this step, so
    each iterate calls only the model's per-iterate stage (bit for bit :func:`forces`);
    ``ry``, ``rz`` the load reductions of the step (from the committed penetration). Each
    iterate evaluates the force model, then the soil under V = w_s − r_z F_Z (the force and
    soil calls are written out here, not wrapped, to keep the hot loop's calls few).
    """
    m = settings[ST_MASS]
    gam = settings[ST_GAMMA]
    beta = settings[ST_BETA]
    rtol = settings[ST_RTOL]
    ws = settings[ST_WS]
    max_iter = int(settings[ST_MAX_ITER])
    vc = settings[ST_CURRENT]
    d = settings[ST_D]
    rho = settings[ST_RHO]
    c0 = m / (beta * dt * dt)
    cv = gam / (beta * dt)
    dy_hat = dt * yd0 + dt * dt * (0.5 - beta) * a0
    yd_base = yd0 + dt * (1.0 - gam) * a0
    scale = ws + abs(m * a0) + 1.0
    tol_r = rtol * scale
    # np.bool_, not the literal False: one specialisation of safeguarded_update, not two
    have_lo = np.bool_(False)
    have_hi = np.bool_(False)
    lo = 0.0
    hi = 0.0
    dy = dy_hat
    eps = 4.0e-16 * (abs(y0) + abs(dy_hat) + 1e-12)
    for it in range(max_iter):
        yd1 = yd_base + cv * (dy - dy_hat)
        if prepared:
            force_evaluate(force_id, prow, fprep, u1, vc, yd1, d, rho, fout)
        else:
            forces(force_id, settings, prow, fs, t1, u1, a1dot, yd1, fs_new, fout)
        fy = ry * fout[FO_FY]
        dfdyd = ry * fout[FO_DFY_DYD]
        lateral_step(
            model_id, borrow(params), borrow(state), y0 + dy, ws - rz * fout[FO_FZ],
            borrow(trial), borrow(out),
        )  # fmt: skip
        big_r = out[OUT_R]
        if not math.isfinite(big_r):
            return dy, False, it + 1
        r = c0 * (dy - dy_hat) + big_r - fy
        if abs(r) <= tol_r:
            return dy, True, it + 1
        dy_next, lo, hi, have_lo, have_hi, closed = safeguarded_update(
            dy, r, c0 - dfdyd * cv, out[OUT_TANGENT], lo, hi, have_lo, have_hi, eps
        )
        if closed:
            return dy, True, it + 1
        if abs(dy_next - dy) <= eps:
            yd1 = yd_base + cv * (dy_next - dy_hat)
            if prepared:
                force_evaluate(force_id, prow, fprep, u1, vc, yd1, d, rho, fout)
            else:
                forces(force_id, settings, prow, fs, t1, u1, a1dot, yd1, fs_new, fout)
            lateral_step(
                model_id, borrow(params), borrow(state), y0 + dy_next, ws - rz * fout[FO_FZ],
                borrow(trial), borrow(out),
            )  # fmt: skip
            return dy_next, True, it + 1
        dy = dy_next
    return dy, False, max_iter


@njit(cache=True, inline="always")
def _write(rec, n, t, y, yd, fy, fz, v, u, ry, rz, dyn, out):
    rec[n, REC_T] = t
    rec[n, REC_Y] = y
    rec[n, REC_YD] = yd
    rec[n, REC_Z] = out[OUT_Z]
    rec[n, REC_FY] = fy
    rec[n, REC_FZ] = fz
    rec[n, REC_V] = v
    rec[n, REC_FF] = out[OUT_FRICTION]
    rec[n, REC_FP] = out[OUT_PASSIVE]
    rec[n, REC_R] = out[OUT_R]
    rec[n, REC_W_HYDRO] = dyn[D_W_HYDRO]
    rec[n, REC_W_SOIL] = dyn[D_W_SOIL]
    rec[n, REC_U] = u
    rec[n, REC_RY] = ry
    rec[n, REC_RZ] = rz
    rec[n, REC_REGION] = out[OUT_REGION]
    rec[n, REC_SOIL_WORK] = out[OUT_WORK]


@njit(cache=True, inline="always")
def initial(model_id, force_id, params, state, settings, fparams, fstate, kin_u, kin_a, dyn, rec):
    """Initial acceleration, running summary and first record (pipe at rest at y = 0);
    through :func:`integrate` (``n0 < 0``), inlined there. A model with the two-stage form
    (rule 7) is evaluated through its stages, as the steps are: bit for bit its kernel."""
    trial = np.empty(state.shape[0])
    out = np.empty(OUT_SIZE)
    fs_new = np.zeros(fstate.shape[0])
    fout = np.empty(FO_SIZE)
    fprep = np.zeros(N_FORCE_PREP)
    dts = settings[ST_DTS]
    t0 = dyn[D_T]
    u0, a0, j = flow_at(t0, kin_u, kin_a, dts)
    ry, rz = load_reductions(settings, state[S_Z])
    prow = parameter_row(fparams, j)
    if prepare_forces(force_id, settings, prow, fstate, t0, u0, a0, fs_new, fprep):
        force_evaluate(
            force_id, prow, fprep, u0, settings[ST_CURRENT], dyn[D_YD], settings[ST_D],
            settings[ST_RHO], fout,
        )  # fmt: skip
    else:
        forces(force_id, settings, prow, fstate, t0, u0, a0, dyn[D_YD], fs_new, fout)
    fy = ry * fout[FO_FY]
    fz = rz * fout[FO_FZ]
    v = settings[ST_WS] - fz
    lateral_step(model_id, params, state, dyn[D_Y], v, trial, out)
    dyn[D_A] = (fy - out[OUT_R]) / settings[ST_MASS]
    dyn[D_F_PREV] = fy
    dyn[D_R_PREV] = out[OUT_R]
    dyn[D_ZMAX] = out[OUT_Z]
    dyn[D_ZMIN] = out[OUT_Z]
    dyn[D_FZ_MAX] = fz
    dyn[D_V_MIN] = v
    dyn[D_YMAX] = abs(dyn[D_Y])
    dyn[D_T_LIMIT] = -1.0
    dyn[D_T_LIFTOFF] = -1.0
    dyn[D_T_ZLIMIT] = -1.0
    if out[OUT_Z] > settings[ST_Z_LIMIT]:
        dyn[D_T_ZLIMIT] = dyn[D_T]
        dyn[D_Y_ZLIMIT] = dyn[D_Y]
    if v <= 0.0:
        dyn[D_LIFTED] = 1.0
        dyn[D_N_LIFTOFF] = 1.0
        dyn[D_T_LIFTOFF] = dyn[D_T]
    n = 0
    if rec.shape[0] > 0:
        # np.int64(0), not 0: a literal argument compiles a second specialisation of _write
        _write(rec, np.int64(0), dyn[D_T], dyn[D_Y], dyn[D_YD], fy, fz, v, u0, ry, rz, dyn, out)
        n = 1
    dyn[D_NEXT_REC] = dyn[D_T] + settings[ST_REC_INTERVAL]
    return n


@njit(cache=True)
def integrate(
    model_id, force_id, params, state, settings, fparams, fstate, kin_u, kin_a, dyn, t_stop, rec,
    n0,
):  # fmt: skip
    """Advance from dyn[D_T] to t_stop, the storm end, an event or a full record buffer.

    Returns (rows written in total, status). With ``n0 < 0``: the start instead
    (:func:`initial`, inlined here; returns (its rows, ``STATUS_CHUNK``); ``t_stop`` unused),
    so that one compiled function holds the whole storm: :func:`initial` and
    :func:`solve_step` are inlined at numba-IR level (``inline="always"``), not compiled as
    functions of their own, each of which would link, re-optimise and re-emit the soil and
    force models' machine code once more.
    """
    literally(model_id)  # compile only the soil and force models used (module docstring)
    literally(force_id)
    if n0 < 0:
        return initial(
            model_id, force_id, params, state, settings, fparams, fstate, kin_u, kin_a, dyn, rec
        ), STATUS_CHUNK
    dt_max = settings[ST_DT_MAX]
    dt_min = settings[ST_DT_MIN]
    du_max = settings[ST_DU_MAX]
    y_limit = settings[ST_Y_LIMIT]
    t_end = settings[ST_T_END]
    dts = settings[ST_DTS]
    rec_dt = settings[ST_REC_INTERVAL]
    stop_on_lift = settings[ST_LIFTOFF] == LIFTOFF_STOP
    cap = rec.shape[0]
    trial = np.empty(state.shape[0])
    out = np.empty(OUT_SIZE)
    fs_new = np.zeros(fstate.shape[0])
    fout = np.empty(FO_SIZE)
    fprep = np.zeros(N_FORCE_PREP)
    n = n0
    while True:
        t = dyn[D_T]
        if t >= t_end - 1e-9 * (1.0 + t_end):
            return n, STATUS_END
        if t >= t_stop:
            return n, STATUS_CHUNK
        if cap > 0 and n >= cap:
            return n, STATUS_BUFFER_FULL
        y0 = dyn[D_Y]
        yd0 = dyn[D_YD]
        a0 = dyn[D_A]
        dt = min(dyn[D_DT], dt_max)
        if t + dt > t_end - 0.01 * dt_min:
            dt = t_end - t
        t1 = t + dt
        u1, a1dot, j = flow_at(t1, kin_u, kin_a, dts)
        prow = parameter_row(fparams, j)
        ry, rz = load_reductions(settings, state[S_Z])
        prepared = prepare_forces(
            force_id, borrow(settings), prow, borrow(fstate), t1, u1, a1dot, borrow(fs_new),
            borrow(fprep),
        )  # fmt: skip
        dy, conv, iters = solve_step(
            model_id, force_id, borrow(params), borrow(state), borrow(settings), prow,
            borrow(fstate), t1, u1, a1dot, y0, yd0, a0, dt, ry, rz, borrow(trial), borrow(out),
            borrow(fs_new), borrow(fout), prepared, borrow(fprep),
        )  # fmt: skip
        dyn[D_N_ITER] += iters
        if not math.isfinite(out[OUT_R]):
            return n, STATUS_SOIL_NAN
        ok = conv and abs(dy) <= du_max
        if not ok:
            if dt > dt_min * 1.000001:
                dyn[D_DT] = max(0.5 * dt, dt_min)
                dyn[D_N_REJECT] += 1.0
                continue
            if not conv:
                return n, STATUS_STEP_FAILED
        # ---- commit
        gam = settings[ST_GAMMA]
        beta = settings[ST_BETA]
        dy_hat = dt * yd0 + dt * dt * (0.5 - beta) * a0
        a1 = (dy - dy_hat) / (beta * dt * dt)
        yd1 = yd0 + dt * ((1.0 - gam) * a0 + gam * a1)
        # the force model at the accepted (t₁, ẏ₁): its loads and the force state to commit
        # (with a prepared model, fs_new already holds that state: it does not depend on ẏ)
        if prepared:
            force_evaluate(
                force_id, prow, fprep, u1, settings[ST_CURRENT], yd1, settings[ST_D],
                settings[ST_RHO], fout,
            )  # fmt: skip
        else:
            forces(force_id, settings, prow, fstate, t1, u1, a1dot, yd1, fs_new, fout)
        fy = ry * fout[FO_FY]
        fz = rz * fout[FO_FZ]
        v = settings[ST_WS] - fz
        r1 = out[OUT_R]
        dyn[D_W_HYDRO] += 0.5 * (dyn[D_F_PREV] + fy) * dy
        dyn[D_W_SOIL] += 0.5 * (dyn[D_R_PREV] + r1) * dy
        dyn[D_F_PREV] = fy
        dyn[D_R_PREV] = r1
        for i in range(state.shape[0]):
            state[i] = trial[i]
        for i in range(fstate.shape[0]):
            fstate[i] = fs_new[i]
        y1 = y0 + dy
        dyn[D_T] = t1
        dyn[D_Y] = y1
        dyn[D_YD] = yd1
        dyn[D_A] = a1
        dyn[D_N_STEPS] += 1.0
        if abs(y1) > dyn[D_YMAX]:
            dyn[D_YMAX] = abs(y1)
            dyn[D_T_YMAX] = t1
        z1 = out[OUT_Z]
        if z1 > dyn[D_ZMAX]:
            dyn[D_ZMAX] = z1
        if z1 < dyn[D_ZMIN]:
            dyn[D_ZMIN] = z1
        if z1 > settings[ST_Z_LIMIT] and dyn[D_T_ZLIMIT] < 0.0:
            dyn[D_T_ZLIMIT] = t1  # left the soil model's range: flagged, the run goes on
            dyn[D_Y_ZLIMIT] = y1
        if fz > dyn[D_FZ_MAX]:
            dyn[D_FZ_MAX] = fz
        if v < dyn[D_V_MIN]:
            dyn[D_V_MIN] = v
        if iters <= 4 and abs(dy) < 0.5 * du_max:
            dyn[D_DT] = min(2.0 * dt, dt_max)
        else:
            dyn[D_DT] = dt
        # ---- events
        status = STATUS_CHUNK
        if v <= 0.0:
            if dyn[D_LIFTED] == 0.0:
                dyn[D_LIFTED] = 1.0
                dyn[D_N_LIFTOFF] += 1.0
                if dyn[D_T_LIFTOFF] < 0.0:
                    dyn[D_T_LIFTOFF] = t1
                if stop_on_lift:
                    status = STATUS_LIFTOFF
        else:
            dyn[D_LIFTED] = 0.0
        if abs(y1) >= y_limit and status == STATUS_CHUNK:
            dyn[D_T_LIMIT] = t1
            status = STATUS_LIMIT
        last = status != STATUS_CHUNK or t1 >= t_end - 1e-9 * (1.0 + t_end)
        if cap > 0 and (last or t1 >= dyn[D_NEXT_REC] - 1e-9):
            _write(rec, n, t1, y1, yd1, fy, fz, v, u1, ry, rz, dyn, out)
            n += 1
            dyn[D_NEXT_REC] = t1 + rec_dt
        if status != STATUS_CHUNK:
            return n, status
