"""Numba time loop of the pipeline FE model (private).

Equations (docs/theory/pipeline_fe.md): with the nodal DOF vector d = (u_i, v_i, θ_i),

    M ä + f_int(d) + f_spring(d) + f_soil(d, history) = f_hyd(t, ḋ)

M lumped (structural mass on u, structural + added mass on v, section rotary inertia on θ);
f_int the corotational beam (:mod:`._beam_kernel`); f_soil the lateral soil kernel of every
node (``onbottom.soil._dispatch.lateral_step``) times its tributary length plus elastic–plastic
axial friction μ_ax·V (:func:`onbottom.soil._coulomb_kernel.friction_return_map`); f_hyd the
load of the force model (:func:`onbottom.hydro._force_dispatch.force_step`, Morison with relative
velocity and lift by default) times the F109 reductions r_y, r_z of every node.

Time integration: HHT-α (Hilber, Hughes & Taylor 1977), α ∈ [−1/3, 0], β = (1 − α)²/4,
γ = ½ − α; with P = f_hyd − f_int − f_spring − f_soil the step residual is

    r(d₁) = M a₁ − (1 + α) P(t₁, d₁, v₁) + α P_n,
    a₁ = (d₁ − d_n − Δt v_n − Δt²(½ − β) a_n)/(βΔt²),  v₁ = v_n + Δt((1 − γ) a_n + γ a₁),

solved by Newton on the consistent tangent J = M/(βΔt²) + (1 + α)(K_beam + K_spring +
K_soil − ∂f_hyd/∂ḋ · γ/(βΔt)) — banded, factored by :mod:`._banded` in O(n); the factor is
kept (modified Newton) while its measured contraction predicts at most ``REFACTOR_ITERS``
more iterations, and a correction that raised the residual is halved (``MAX_BACKTRACK``).
α = 0 is the average-acceleration Newmark rule. A step that does not converge in
``max_iter`` iterations, or moves any node laterally by more than ``du_max``, is cut to half;
a step that converged in few iterations lets the next grow by ``growth`` up to ``dt_max``.
Accepted steps commit the soil states and the force-model states ``fstate[node, :]`` (from
the evaluation at the accepted d₁, v₁; iterations and rejected steps start from the committed
state). Penetration reductions use the committed penetration of each node (lagged one
step); the lift, and with it the contact load V, is evaluated once per step at t₁ from the
committed force state (with the lagged lateral velocity when the model's lift uses the
relative velocity). The force model's
parameters ``fparams`` are one row, or one row per kinematics sample (the left sample of t).
"""

from __future__ import annotations

import math

import numpy as np
from numba import literally

from onbottom._jit import borrow, call_literal, jitted_only, njit, row_view
from onbottom.dynamics.pipeline._banded import (
    factor_jacobian,
    ldl_solve,
    ldl_solve_backward,
)
from onbottom.dynamics.pipeline._beam_kernel import (
    HALF_BAND,
    NDOF_NODE,
    assemble_internal,
    node_section_forces,
)
from onbottom.dynamics.status import Status
from onbottom.hydro.kernel_contract import (
    FO_DFY_DYD,
    FO_FY,
    FO_FZ,
    FO_SIZE,
    penetration_reduction_y,
    penetration_reduction_z,
)
from onbottom.hydro.kernel_contract import force_step_of as force_step  # literal model id
from onbottom.soil.base import OUT_R, OUT_SIZE, OUT_TANGENT, S_Z
from onbottom.soil.kernel_contract import friction_return_map
from onbottom.soil.kernel_contract import lateral_step_node as lateral_step  # literal id

# ---- settings ------------------------------------------------------------------------------
ST_DT_MAX = 0
ST_DT_MIN = 1
ST_ALPHA = 2
ST_MAX_ITER = 3
ST_RTOL = 4
ST_FSCALE = 5  # force scale of the residual test [N]
ST_DU_MAX = 6  # largest lateral increment of any node per step [m]
ST_V_LIMIT = 7  # lateral displacement limit [m] (inf: none)
ST_STOP_AT_LIMIT = 8  # 1: stop at the limit
ST_GROWTH = 9  # step growth factor after an easy step
ST_RHO = 10  # water density [kg/m³]
ST_D = 11  # outer diameter [m]
ST_FORCE_MODEL = 12  # force model id (onbottom.hydro._force_dispatch)
ST_R_PERM_Z = 13  # r_perm,z [-]
ST_RELVEL = 14  # 1: relative-velocity drag
ST_DELTA_AX = 15  # axial friction mobilisation displacement [m]
ST_FIBRE = 16  # distance of the outer steel fibre from the neutral axis [m]
ST_T_KIN0 = 17  # time of the first kinematics sample [s]
ST_DT_KIN = 18  # kinematics sample interval [s]
ST_PEN_RED = 19  # 1: penetration reductions r_pen,y/z
ST_EA = 20  # reference EA for strain [N]
ST_EI = 21  # reference EI for strain [N·m²]
ST_PREDICTOR = 22  # weight of Δt²·a_n in the Newton start d₁ = d_n + Δt v_n + w Δt² a_n
ST_CTOL = 23  # Newton correction [m] below which a step is accepted (displacement resolution)
ST_Z_LIMIT = 24  # penetration beyond the soil models' range [m] (inf: none)
ST_KIN_K0 = 25  # global index of the first sample held in kin_u/kin_a (a window of the storm)
ST_KIN_NT = 26  # samples of the whole storm's kinematics (<= 0: those held, from index 0)
# user load q(x, t) (user_load.py; add_user_load)
ST_UL_KIND = 27  # UL_NONE, UL_SINE, UL_TABLE
ST_UL_AMP_Y = 28  # sine: lateral amplitude [N/m]
ST_UL_AMP_X = 29  # sine: axial amplitude [N/m]
ST_UL_WAVENUMBER = 30  # sine: 2π/λ [rad/m]
ST_UL_OMEGA = 31  # sine: 2π/T [rad/s]
ST_UL_RAMP = 32  # sine: half-cosine ramp duration [s]
ST_UL_START = 33  # sine: switch-on time [s]
ST_UL_T0 = 34  # table: time of the first row [s]
ST_UL_DT = 35  # table: row interval [s]
N_SETTINGS = 36

# ---- Newton controls (docs/theory/pipeline_fe.md, "Newton and step control") ---------------
REFACTOR_ITERS = 2.0  # refactor when modified Newton would need more iterations than this
MAX_BACKTRACK = 3  # halvings of a correction that raised the residual, per step

UL_NONE = 0
UL_SINE = 1
UL_TABLE = 2

# ---- node columns --------------------------------------------------------------------------
ND_X0 = 0  # initial position along the axis [m]
ND_TRIB = 1  # tributary length ℓ [m]
ND_MASS_U = 2  # lumped axial mass [kg]
ND_MASS_V = 3  # lumped lateral mass incl. added mass [kg]
ND_J = 4  # rotary inertia [kg·m²]
ND_CURRENT = 5  # steady current normal to the pipe [m/s]
ND_MU_AX = 6  # axial friction coefficient [-]
ND_WS = 7  # submerged weight [N/m]
ND_R_TR_Y = 8  # trench reduction r_tr,y [-]
ND_R_TR_Z = 9  # trench reduction r_tr,z [-]
N_NODE_COLS = 10

# ---- vectors (rows of vec[N_VEC, ndof]) -----------------------------------------------------
V_D = 0
V_V = 1
V_A = 2
V_P = 3  # committed net force P_n
V_FH = 4  # committed external nodal force (hydrodynamic + user load)
V_FS = 5  # committed soil nodal force (lateral + axial)
N_VEC = 6

# ---- scalars -------------------------------------------------------------------------------
SC_T = 0
SC_DT = 1
SC_NSTEP = 2
SC_NREJ = 3
SC_NITER = 4
SC_W_HYD = 5  # work of the external loads (hydrodynamic + user load) [J]
SC_W_SOIL = 6  # work of the soil forces [J] (negative: dissipated)
SC_N_LIFT = 7  # node-steps with lift-off (V <= 0)
SC_T_LIFT = 8  # first lift-off time [s] (nan: none)
SC_K_OUT = 9  # index of the next output time
SC_T_LIMIT = 10  # time the displacement limit was first reached [s] (nan: none)
SC_NEG_PIVOT = 11  # steps whose Jacobian had a negative pivot
SC_N_FACTOR = 12  # band factorisations
SC_LIFT_NODE = 13  # node of the first lift-off
SC_T_ZLIMIT = 14  # first time a node's penetration exceeded ST_Z_LIMIT [s] (nan: never)
SC_ZLIMIT_NODE = 15  # that node (-1: none); the run goes on, the caller flags the result
N_SCAL = 16

# ---- record fields (rec[k, F_*, node]) ---------------------------------------------------------
F_U = 0  # axial displacement [m]
F_V = 1  # lateral displacement [m]
F_VDOT = 2  # lateral velocity [m/s]
F_Z = 3  # penetration [m]
F_SOIL = 4  # lateral soil resistance R [N/m]
F_HYD = 5  # lateral hydrodynamic load F_Y [N/m]
F_VCONT = 6  # vertical contact load V [N/m]
F_MOM = 7  # bending moment [N·m]
F_NAX = 8  # effective axial force [N]
F_STRAIN = 9  # largest fibre strain |N|/EA + |M|c/EI [-]
N_FIELDS = 10

# ---- envelopes (env[E_*, node]) ---------------------------------------------------------------
E_ABS_V = 0
E_MAX_V = 1
E_MIN_V = 2
E_STRAIN = 3
E_ABS_M = 4
E_MAX_N = 5
E_MIN_N = 6
E_MIN_VCONT = 7
E_MAX_Z = 8
N_ENV = 9

STATUS_CHUNK = int(Status.CHUNK)
STATUS_END = int(Status.END)
STATUS_LIMIT = int(Status.LIMIT)
STATUS_STEP_FAILED = int(Status.STEP_FAILED)
STATUS_SOIL_NAN = int(Status.SOIL_NAN)
STATUS_SINGULAR = int(Status.SINGULAR)


@jitted_only
def kinematics_at(t, kin_u, kin_a, t0, dtk, k0, nt, uk, ak):
    """Linear interpolation of the near-bed velocity and acceleration of every node at t.

    ``kin_u``/``kin_a`` hold samples k0 ... k0 + rows − 1 of a storm of ``nt`` samples (the
    driver keeps the window over every time a call of :func:`integrate` reaches); the sample
    index and the weight are those of the whole storm, so a window gives the whole array's
    values bit for bit. ``nt`` <= 0: the arrays are the whole storm (k0 = 0)."""
    if nt <= 0:
        nt = kin_u.shape[0]
        k0 = 0
    s = (t - t0) / dtk
    if s <= 0.0:
        i0 = 0
        f = 0.0
    elif s >= nt - 1:
        i0 = nt - 2
        f = 1.0
    else:
        i0 = int(s)
        f = s - i0
    if nt == 1:
        for i in range(uk.shape[0]):
            uk[i] = kin_u[0, i]
            ak[i] = kin_a[0, i]
        return
    g = 1.0 - f
    j = i0 - k0
    if j < 0 or j + 1 >= kin_u.shape[0]:  # outside the window: the driver's error, never silent
        for i in range(uk.shape[0]):
            uk[i] = math.nan
            ak[i] = math.nan
        return
    for i in range(uk.shape[0]):
        uk[i] = g * kin_u[j, i] + f * kin_u[j + 1, i]
        ak[i] = g * kin_a[j, i] + f * kin_a[j + 1, i]


@jitted_only
def parameter_row(settings, fparams, t):
    """The force model's parameters at time t: the only row, or that of the left sample."""
    n = fparams.shape[0]
    if n == 1:
        return fparams[0]
    k = int((t - settings[ST_T_KIN0]) / settings[ST_DT_KIN])
    if k < 0:
        k = 0
    elif k > n - 1:
        k = n - 1
    return fparams[k]


@jitted_only
def node_loads(force_id, settings, nodes, sstate, fparams, fstate, t, uk, ak, v0, vcont, ry, fscr,
               fout):  # fmt: skip
    """Contact load V = W_s − r_z F_Z and lateral reduction r_y of every node at time t.

    F_Z from the force model at the committed state ``fstate`` (``fscr`` receives the unused
    trial state), with the lagged lateral velocity ``v0`` (the DOF vector of the last
    committed step) as ẏ when the relative velocity is on.
    """
    d = settings[ST_D]
    rho = settings[ST_RHO]
    relvel = settings[ST_RELVEL] != 0.0
    prow = parameter_row(settings, fparams, t)
    pen = settings[ST_PEN_RED] != 0.0
    r_perm_z = settings[ST_R_PERM_Z]
    for i in range(uk.shape[0]):
        zd = sstate[i, S_Z] / d if pen else 0.0
        rz = r_perm_z * nodes[i, ND_R_TR_Z]
        r_y = nodes[i, ND_R_TR_Y]
        if pen:
            rz *= penetration_reduction_z(zd)
            r_y *= penetration_reduction_y(zd)
        ydot = v0[NDOF_NODE * i + 1] if relvel else 0.0
        force_step(
            force_id, borrow(prow), row_view(fstate, i), t, uk[i], ak[i], nodes[i, ND_CURRENT],
            ydot, d, rho, borrow(fscr), borrow(fout),
        )  # fmt: skip
        vcont[i] = nodes[i, ND_WS] - rz * fout[FO_FZ]
        ry[i] = r_y


@jitted_only
def evaluate(
    soil_id, force_id,
    settings, props, nodes, fixed, spring, model_ids, sparams, sstate, axst, fparams, fstate,
    t1, d1, v1, uk, ak, vcont, ry, c_v, want_k,
    p, fh, fs, ab, trial, ftrial, node_r, node_f, node_fa, fe, ke, out, fout, mom, nax, kt_u,
    kt_v,
):  # fmt: skip
    """Net force P(d₁, v₁) = f_hyd − f_int − f_spring − f_soil and (``want_k``) its negative
    Jacobian K_T = ∂(−P)/∂d + c_v·∂(−f_hyd)/∂ḋ into the band ``ab`` (not yet with mass).

    The soil and force models are evaluated from the committed ``sstate``, ``fstate`` into
    ``trial``, ``ftrial`` (committed by the caller when the step is accepted).

    The nodal bending moment and axial force at d₁ are written to ``mom``, ``nax``; the nodal
    (soil + drag) tangents on u and v to ``kt_u``, ``kt_v`` (see :func:`assemble_tangent`).
    Returns False if a soil kernel gave NaN.
    """
    ndof = d1.shape[0]
    for j in range(ndof):
        p[j] = 0.0
        fh[j] = 0.0
        fs[j] = 0.0
    if want_k:
        for j in range(ndof):
            for k in range(ab.shape[1]):
                ab[j, k] = 0.0
    # internal forces (assembled as +f_int into p, then negated)
    assemble_internal(
        borrow(d1), borrow(props), borrow(p), borrow(ab), want_k, borrow(fe), borrow(ke),
        borrow(mom), borrow(nax),
    )  # fmt: skip
    for j in range(ndof):
        p[j] = -p[j] - spring[j] * d1[j]
        if want_k:
            ab[j, 0] += spring[j]
    dd = settings[ST_D]
    rho = settings[ST_RHO]
    prow = parameter_row(settings, fparams, t1)
    relvel = settings[ST_RELVEL] != 0.0
    delta_ax = settings[ST_DELTA_AX]
    for i in range(nodes.shape[0]):
        iu = NDOF_NODE * i
        iv = iu + 1
        ell = nodes[i, ND_TRIB]
        ydot = v1[iv] if relvel else 0.0
        force_step(
            force_id, borrow(prow), row_view(fstate, i), t1, uk[i], ak[i], nodes[i, ND_CURRENT],
            ydot, dd, rho, row_view(ftrial, i), borrow(fout),
        )  # fmt: skip
        f_y = ry[i] * fout[FO_FY]
        dfdv = ry[i] * fout[FO_DFY_DYD] if relvel else 0.0
        lateral_step(
            soil_id, model_ids[i], row_view(sparams, i), row_view(sstate, i), d1[iv], vcont[i],
            row_view(trial, i), borrow(out),
        )  # fmt: skip
        big_r = out[OUT_R]
        if not math.isfinite(big_r):
            return False
        fa, ka = friction_return_map(
            axst[i, 1], d1[iu] - axst[i, 0], vcont[i], nodes[i, ND_MU_AX], delta_ax
        )
        node_r[i] = big_r
        node_f[i] = f_y
        node_fa[i] = fa
        fh[iv] = ell * f_y
        fs[iv] = -ell * big_r
        fs[iu] = -ell * fa
        p[iv] += fh[iv] + fs[iv]
        p[iu] += fs[iu]
        kt_v[i] = ell * (out[OUT_TANGENT] - c_v * dfdv)
        kt_u[i] = ell * ka
        if want_k:
            ab[iv, 0] += kt_v[i]
            ab[iu, 0] += kt_u[i]
    return True


@jitted_only
def add_user_load(settings, uload, nodes, t, p, fext):
    """Add the user load's nodal forces ℓ·q(x, t) at time t to ``p`` and ``fext``.

    Kinds (``settings[ST_UL_KIND]``, :mod:`.user_load`): none; the travelling sinusoid
    q = r(t)·A·sin(kx − ω(t − t_s)), r the half-cosine ramp; the table ``uload[t_k, (y, x),
    node]`` linear in time, held outside. Lateral on v, axial on u. Independent of the motion.
    """
    kind = int(settings[ST_UL_KIND])
    if kind == UL_NONE:
        return
    n_nodes = nodes.shape[0]
    if kind == UL_SINE:
        tau = t - settings[ST_UL_START]
        if tau <= 0.0:
            return
        ramp = settings[ST_UL_RAMP]
        r = 1.0
        if tau < ramp:
            r = 0.5 * (1.0 - math.cos(math.pi * tau / ramp))
        ay = r * settings[ST_UL_AMP_Y]
        ax = r * settings[ST_UL_AMP_X]
        kw = settings[ST_UL_WAVENUMBER]
        om = settings[ST_UL_OMEGA]
        for i in range(n_nodes):
            sn = math.sin(kw * nodes[i, ND_X0] - om * tau) * nodes[i, ND_TRIB]
            iu = NDOF_NODE * i
            p[iu] += ax * sn
            fext[iu] += ax * sn
            p[iu + 1] += ay * sn
            fext[iu + 1] += ay * sn
        return
    nt = uload.shape[0]
    s = (t - settings[ST_UL_T0]) / settings[ST_UL_DT]
    i0 = 0
    f = 0.0
    if nt > 1:
        if s >= nt - 1:
            i0 = nt - 2
            f = 1.0
        elif s > 0.0:
            i0 = int(s)
            f = s - i0
    i1 = i0 + 1 if nt > 1 else i0
    g = 1.0 - f
    for i in range(n_nodes):
        ell = nodes[i, ND_TRIB]
        qy = (g * uload[i0, 0, i] + f * uload[i1, 0, i]) * ell
        qx = (g * uload[i0, 1, i] + f * uload[i1, 1, i]) * ell
        iu = NDOF_NODE * i
        p[iu] += qx
        fext[iu] += qx
        p[iu + 1] += qy
        fext[iu + 1] += qy


@jitted_only
def assemble_tangent(d1, props, spring, ab, fe, ke, mom, nax, kt_u, kt_v, scratch):
    """K_T at d₁ into ``ab`` from the beam and the nodal tangents stored by :func:`evaluate`
    at the same d₁ (same band as ``evaluate(..., want_k=True)``, without re-running the soil
    and load kernels)."""
    ndof = d1.shape[0]
    for j in range(ndof):
        scratch[j] = 0.0
        for k in range(ab.shape[1]):
            ab[j, k] = 0.0
    # np.bool_(True), not the literal True: numba compiles a separate specialisation of the
    # callee for each literal argument (first-run compile cost)
    assemble_internal(
        borrow(d1), borrow(props), borrow(scratch), borrow(ab), np.bool_(True), borrow(fe),
        borrow(ke), borrow(mom), borrow(nax),
    )  # fmt: skip
    for j in range(ndof):
        ab[j, 0] += spring[j]
    for i in range(kt_u.shape[0]):
        ab[NDOF_NODE * i, 0] += kt_u[i]
        ab[NDOF_NODE * i + 1, 0] += kt_v[i]


@jitted_only
def _record(settings, props, nodes, vec, sstate, node_r, node_f, vcont, rec, k, mom, nax):
    node_section_forces(vec[V_D], props, mom, nax)
    c = settings[ST_FIBRE]
    ea = settings[ST_EA]
    ei = settings[ST_EI]
    for i in range(nodes.shape[0]):
        iu = NDOF_NODE * i
        rec[k, F_U, i] = vec[V_D, iu]
        rec[k, F_V, i] = vec[V_D, iu + 1]
        rec[k, F_VDOT, i] = vec[V_V, iu + 1]
        rec[k, F_Z, i] = sstate[i, S_Z]
        rec[k, F_SOIL, i] = node_r[i]
        rec[k, F_HYD, i] = node_f[i]
        rec[k, F_VCONT, i] = vcont[i]
        rec[k, F_MOM, i] = mom[i]
        rec[k, F_NAX, i] = nax[i]
        rec[k, F_STRAIN, i] = abs(nax[i]) / ea + abs(mom[i]) * c / ei


@njit(cache=True)
def integrate(
    soil_id, force_id,
    settings, props, nodes, fixed, spring, model_ids, sparams, sstate, axst, fparams, fstate,
    kin_u, kin_a, uload, vec, scal, nodal, t_out, t_end, t_stop, rec, rec_t, env, init,
):  # fmt: skip
    """Advance from scal[SC_T] to t_stop (a chunk end), t_end, an event or a full buffer.

    ``nodal`` (3 × n_nodes: soil resistance R, hydrodynamic load F_Y [N/m], axial friction
    [N/m] at the committed state) is state too. Records the state at the times ``t_out``
    (steps land on them) into ``rec``/``rec_t`` from row 0; ``vec``, ``scal``, ``sstate``,
    ``axst``, ``fstate`` and ``env`` are updated in place. Returns (rows written, status).

    With ``init`` true it only sets the start (:func:`initial_acceleration`): a₀ = M⁻¹P(t₀,
    d₀, v₀) and the committed P, f_ext (hydrodynamic + user load), f_soil; returns (0,
    ``STATUS_END``), or ``STATUS_SOIL_NAN`` when a soil kernel gave NaN. One entry point for
    both: numba optimises and machine-compiles an entry point together with its whole tree of
    callees, so a second entry point cost that once more on a first run.
    """
    literally(soil_id)  # compile only the models used (soil._dispatch.lateral_step_node)
    literally(force_id)
    n_nodes = nodes.shape[0]
    ndof = NDOF_NODE * n_nodes
    alpha = settings[ST_ALPHA]
    beta = 0.25 * (1.0 - alpha) * (1.0 - alpha)
    gam = 0.5 - alpha
    dt_max = settings[ST_DT_MAX]
    dt_min = settings[ST_DT_MIN]
    max_iter = int(settings[ST_MAX_ITER])
    tol = settings[ST_RTOL] * settings[ST_FSCALE]
    du_max = settings[ST_DU_MAX]
    v_limit = settings[ST_V_LIMIT]
    growth = settings[ST_GROWTH]
    t0k = settings[ST_T_KIN0]
    dtk = settings[ST_DT_KIN]
    k0k = int(settings[ST_KIN_K0])
    ntk = int(settings[ST_KIN_NT])
    pred = settings[ST_PREDICTOR]
    ctol = settings[ST_CTOL]
    z_limit = settings[ST_Z_LIMIT]
    fibre = settings[ST_FIBRE]
    ea = settings[ST_EA]
    ei = settings[ST_EI]
    mass = np.empty(ndof)
    for i in range(n_nodes):
        mass[NDOF_NODE * i] = nodes[i, ND_MASS_U]
        mass[NDOF_NODE * i + 1] = nodes[i, ND_MASS_V]
        mass[NDOF_NODE * i + 2] = nodes[i, ND_J]
    uk = np.empty(n_nodes)
    ak = np.empty(n_nodes)
    vcont = np.empty(n_nodes)
    ry = np.empty(n_nodes)
    ab = np.zeros((ndof, HALF_BAND + 1))
    trial = np.empty_like(sstate)
    ftrial = np.zeros_like(fstate)
    fscr = np.zeros(fstate.shape[1])
    fout = np.empty(FO_SIZE)
    node_r = nodal[0]
    node_f = nodal[1]
    node_fa = nodal[2]
    fe = np.empty(6)
    ke = np.empty((6, 6))
    out = np.empty(OUT_SIZE)
    d1 = np.empty(ndof)
    v1 = np.empty(ndof)
    a1 = np.empty(ndof)
    p1 = np.empty(ndof)
    fh1 = np.empty(ndof)
    fs1 = np.empty(ndof)
    res = np.empty(ndof)
    mom = np.empty(n_nodes)
    nax = np.empty(n_nodes)
    kt_u = np.empty(n_nodes)
    kt_v = np.empty(n_nodes)
    scratch = np.empty(ndof)
    dlast = np.zeros(ndof)  # the last Newton correction (backtracking)
    d0 = vec[V_D]
    v0 = vec[V_V]
    a0 = vec[V_A]
    pn = vec[V_P]
    n_rec = np.int64(0)  # not the literal 0: one specialisation of _record, not two
    if init:
        t = scal[SC_T]
        kinematics_at(t, kin_u, kin_a, t0k, dtk, k0k, ntk, uk, ak)
        node_loads(force_id, settings, nodes, sstate, fparams, fstate, t, uk, ak, v0, vcont, ry,
                   fscr, fout)  # fmt: skip
        ok = evaluate(
            soil_id, force_id,
            settings, props, nodes, fixed, spring, model_ids, sparams, sstate, axst, fparams,
            fstate, t, d0, v0, uk, ak, vcont, ry, 0.0, np.bool_(False),
            pn, vec[V_FH], vec[V_FS], ab, trial, ftrial, node_r, node_f, node_fa, fe, ke, out,
            fout, mom, nax, kt_u, kt_v,
        )  # fmt: skip
        add_user_load(settings, uload, nodes, t, pn, vec[V_FH])
        for j in range(ndof):
            if fixed[j] != 0.0 or mass[j] <= 0.0:
                a0[j] = 0.0
            else:
                a0[j] = pn[j] / mass[j]
        return n_rec, STATUS_END if ok else STATUS_SOIL_NAN
    cap = rec.shape[0]
    n_out = t_out.shape[0]
    # initial record when the first output time is the current time
    kinematics_at(scal[SC_T], kin_u, kin_a, t0k, dtk, k0k, ntk, uk, ak)
    node_loads(force_id, settings, nodes, sstate, fparams, fstate, scal[SC_T], uk, ak, v0, vcont,
               ry, fscr, fout)  # fmt: skip
    while True:
        t = scal[SC_T]
        k_out = int(scal[SC_K_OUT])
        if k_out < n_out and t >= t_out[k_out] - 1e-9 * (1.0 + abs(t)):
            if n_rec >= cap:
                return n_rec, STATUS_CHUNK
            _record(
                borrow(settings), borrow(props), borrow(nodes), borrow(vec), borrow(sstate),
                borrow(node_r), borrow(node_f), borrow(vcont), borrow(rec), n_rec, borrow(mom),
                borrow(nax),
            )  # fmt: skip
            rec_t[n_rec] = t
            n_rec += 1
            scal[SC_K_OUT] = k_out + 1
            continue
        if t >= t_end - 1e-9 * (1.0 + abs(t_end)):
            return n_rec, STATUS_END
        if t >= t_stop - 1e-9 * (1.0 + abs(t_stop)):
            return n_rec, STATUS_CHUNK
        dt_nom = min(scal[SC_DT], dt_max)
        dt = dt_nom
        limit_t = min(t_end, t_stop)
        if k_out < n_out:
            limit_t = min(limit_t, t_out[k_out])
        clipped = False
        if t + dt >= limit_t - 1e-9 * dt_min:
            dt = limit_t - t
            clipped = True
        t1 = t + dt
        kinematics_at(t1, borrow(kin_u), borrow(kin_a), t0k, dtk, k0k, ntk, borrow(uk), borrow(ak))
        node_loads(
            force_id, borrow(settings), borrow(nodes), borrow(sstate), borrow(fparams),
            borrow(fstate), t1, borrow(uk), borrow(ak), borrow(v0), borrow(vcont), borrow(ry),
            borrow(fscr), borrow(fout),
        )  # fmt: skip
        c_a = 1.0 / (beta * dt * dt)
        c_v = gam / (beta * dt)
        for j in range(ndof):
            if fixed[j] != 0.0:
                d1[j] = d0[j]
            else:
                d1[j] = d0[j] + dt * v0[j] + pred * dt * dt * a0[j]
        conv = False
        iters = 0
        neg = 0
        r_prev = math.inf
        n_back = 0
        for it in range(max_iter):
            iters = it + 1
            for j in range(ndof):
                a1[j] = c_a * (d1[j] - d0[j] - dt * v0[j]) - (0.5 / beta - 1.0) * a0[j]
                v1[j] = v0[j] + dt * ((1.0 - gam) * a0[j] + gam * a1[j])
            # the tangent is assembled on the first iteration, later only when needed
            want_k = it == 0
            ok = evaluate(
                soil_id, force_id,
                borrow(settings), borrow(props), borrow(nodes), borrow(fixed), borrow(spring),
                borrow(model_ids), borrow(sparams), borrow(sstate), borrow(axst),
                borrow(fparams), borrow(fstate), t1, borrow(d1), borrow(v1), borrow(uk),
                borrow(ak), borrow(vcont), borrow(ry), c_v, want_k,
                borrow(p1), borrow(fh1), borrow(fs1), borrow(ab), borrow(trial), borrow(ftrial),
                borrow(node_r), borrow(node_f), borrow(node_fa), borrow(fe), borrow(ke),
                borrow(out), borrow(fout), borrow(mom), borrow(nax), borrow(kt_u), borrow(kt_v),
            )  # fmt: skip
            if not ok:
                return n_rec, STATUS_SOIL_NAN
            add_user_load(borrow(settings), borrow(uload), borrow(nodes), t1, borrow(p1),
                          borrow(fh1))  # fmt: skip
            # res holds −r (the Newton right-hand side; −0.0 on fixed DOFs, as −(0.0))
            rmax = 0.0
            for j in range(ndof):
                if fixed[j] != 0.0:
                    res[j] = -0.0
                else:
                    res[j] = -(mass[j] * a1[j] - (1.0 + alpha) * p1[j] + alpha * pn[j])
                    if abs(res[j]) > rmax:
                        rmax = abs(res[j])
            if rmax <= tol and it > 0:
                conv = True
                break
            if rmax <= 1e-3 * tol:
                conv = True
                break
            if it > 0 and rmax > r_prev and n_back < MAX_BACKTRACK:
                # the last correction raised the residual (Newton cycling across a kink of the
                # soil or friction law): backtrack to half of it and evaluate again
                n_back += 1
                for j in range(ndof):
                    dlast[j] *= 0.5
                    d1[j] -= dlast[j]
                continue
            # modified Newton: keep the factor while the iterations its contraction predicts
            # to reach tol, log(tol/r)/log(r/r_prev), are at most REFACTOR_ITERS (a refactor
            # costs about one residual evaluation); otherwise assemble the consistent tangent
            # at d₁ and refactor
            refactor = want_k or rmax >= r_prev
            if not refactor:
                refactor = math.log(tol / rmax) / math.log(rmax / r_prev) > REFACTOR_ITERS
            if refactor:
                if not want_k:
                    assemble_tangent(
                        borrow(d1), borrow(props), borrow(spring), borrow(ab), borrow(fe),
                        borrow(ke), borrow(mom), borrow(nax), borrow(kt_u), borrow(kt_v),
                        borrow(scratch),
                    )  # fmt: skip
                # Jacobian: mass + (1 + α) K_T, fixed DOFs decoupled, formed as it is
                # factored; the solve's forward pass on res done in the same sweep
                neg = factor_jacobian(
                    borrow(ab), 1.0 + alpha, borrow(mass), c_a, borrow(fixed), borrow(res)
                )
                scal[SC_N_FACTOR] += 1.0
                if neg < 0:
                    return n_rec, STATUS_SINGULAR
                ldl_solve_backward(borrow(ab), borrow(res))
            else:
                ldl_solve(borrow(ab), borrow(res))
            r_prev = rmax
            cmax = 0.0  # largest translational correction (u, v; not θ)
            for i in range(n_nodes):
                cu = abs(res[NDOF_NODE * i])
                cv = abs(res[NDOF_NODE * i + 1])
                if cu > cmax:
                    cmax = cu
                if cv > cmax:
                    cmax = cv
            if it > 0 and cmax <= ctol:
                # the correction is below the displacement resolution: the residual sits on a
                # jump of a discontinuous soil law (or at round-off); accept the evaluated state
                conv = True
                break
            for j in range(ndof):
                d1[j] += res[j]
                dlast[j] = res[j]
        scal[SC_NITER] += iters
        dv_max = 0.0
        for i in range(n_nodes):
            dv = abs(d1[NDOF_NODE * i + 1] - d0[NDOF_NODE * i + 1])
            if dv > dv_max:
                dv_max = dv
        good = conv and dv_max <= du_max
        if not good:
            if dt > dt_min * 1.000001:
                scal[SC_DT] = max(0.5 * dt, dt_min)
                scal[SC_NREJ] += 1.0
                continue
            if not conv:
                return n_rec, STATUS_STEP_FAILED
        if neg > 0:
            scal[SC_NEG_PIVOT] += 1.0
        # ---- commit
        whyd = 0.0
        wsoil = 0.0
        vmax = 0.0
        for j in range(ndof):
            dd = d1[j] - d0[j]
            whyd += 0.5 * (vec[V_FH, j] + fh1[j]) * dd
            wsoil += 0.5 * (vec[V_FS, j] + fs1[j]) * dd
            d0[j] = d1[j]
            v0[j] = v1[j]
            a0[j] = a1[j]
            pn[j] = p1[j]
            vec[V_FH, j] = fh1[j]
            vec[V_FS, j] = fs1[j]
        scal[SC_W_HYD] += whyd
        scal[SC_W_SOIL] += wsoil
        for i in range(n_nodes):
            for c in range(sstate.shape[1]):
                sstate[i, c] = trial[i, c]
            for c in range(fstate.shape[1]):
                fstate[i, c] = ftrial[i, c]
            axst[i, 0] = d1[NDOF_NODE * i]
            axst[i, 1] = node_fa[i]
            z = sstate[i, S_Z]
            if z > z_limit and scal[SC_ZLIMIT_NODE] < 0.0:
                scal[SC_T_ZLIMIT] = t1
                scal[SC_ZLIMIT_NODE] = i
            if vcont[i] <= 0.0:
                if scal[SC_N_LIFT] == 0.0:
                    scal[SC_T_LIFT] = t1
                    scal[SC_LIFT_NODE] = i
                scal[SC_N_LIFT] += 1.0
            v = d0[NDOF_NODE * i + 1]
            av = abs(v)
            if av > env[E_ABS_V, i]:
                env[E_ABS_V, i] = av
            if v > env[E_MAX_V, i]:
                env[E_MAX_V, i] = v
            if v < env[E_MIN_V, i]:
                env[E_MIN_V, i] = v
            mi = mom[i]
            ni = nax[i]
            eps = abs(ni) / ea + abs(mi) * fibre / ei
            if eps > env[E_STRAIN, i]:
                env[E_STRAIN, i] = eps
            if abs(mi) > env[E_ABS_M, i]:
                env[E_ABS_M, i] = abs(mi)
            if ni > env[E_MAX_N, i]:
                env[E_MAX_N, i] = ni
            if ni < env[E_MIN_N, i]:
                env[E_MIN_N, i] = ni
            if vcont[i] < env[E_MIN_VCONT, i]:
                env[E_MIN_VCONT, i] = vcont[i]
            if z > env[E_MAX_Z, i]:
                env[E_MAX_Z, i] = z
            if av > vmax:
                vmax = av
        scal[SC_T] = t1
        scal[SC_NSTEP] += 1.0
        if not clipped:
            if iters <= 4 and dv_max < 0.5 * du_max:
                scal[SC_DT] = min(dt * growth, dt_max)
            else:
                scal[SC_DT] = dt
        if vmax >= v_limit and math.isnan(scal[SC_T_LIMIT]):
            scal[SC_T_LIMIT] = t1
            if settings[ST_STOP_AT_LIMIT] != 0.0:
                if n_rec < cap:
                    _record(
                        settings, props, nodes, vec, sstate, node_r, node_f, vcont, rec, n_rec,
                        mom, nax,
                    )  # fmt: skip
                    rec_t[n_rec] = t1
                    n_rec += 1
                return n_rec, STATUS_LIMIT


_INTEGRATE = integrate  # the compiled entry point (tests may replace ``integrate`` itself)


def initial_acceleration(
    soil_id, force_id,
    settings, props, nodes, fixed, spring, model_ids, sparams, sstate, axst, fparams, fstate,
    kin_u, kin_a, uload, vec, scal, nodal, t_out, t_end, rec, rec_t, env,
):  # fmt: skip
    """Set a₀ = M⁻¹P(t₀, d₀, v₀) and the committed P, f_ext (hydrodynamic + user load),
    f_soil at the start: :func:`integrate` with ``init`` (the same compiled entry point and
    arguments). Returns False if a soil kernel gave NaN."""
    _n, status = call_literal(
        _INTEGRATE, 2, soil_id, force_id,
        settings, props, nodes, fixed, spring, model_ids, sparams, sstate, axst, fparams, fstate,
        kin_u, kin_a, uload, vec, scal, nodal, t_out, t_end, t_end, rec, rec_t, env, True,
    )  # fmt: skip
    return status != STATUS_SOIL_NAN


@njit(cache=True)
def static_solve(props, fixed, spring, f_ext, d, n_load_steps, max_iter, tol):
    """Static equilibrium f_int(d) + k_s d = f_ext of the bare beam (no soil), for tests.

    The load is applied in ``n_load_steps`` equal increments, each solved by Newton on the
    consistent tangent. ``d`` (initial guess in, solution out). Returns the iterations of the
    last increment, or −1 when an increment did not converge.
    """
    ndof = d.shape[0]
    ab = np.zeros((ndof, HALF_BAND + 1))
    f = np.empty(ndof)
    res = np.empty(ndof)
    fe = np.empty(6)
    ke = np.empty((6, 6))
    mom = np.empty(ndof // NDOF_NODE)
    nax = np.empty(ndof // NDOF_NODE)
    no_mass = np.zeros(ndof)
    its = 0
    for ls in range(1, n_load_steps + 1):
        lam = ls / n_load_steps
        conv = False
        for it in range(max_iter):
            for j in range(ndof):
                f[j] = spring[j] * d[j]
                for k in range(HALF_BAND + 1):
                    ab[j, k] = 0.0
                ab[j, 0] = spring[j]
            assemble_internal(d, props, f, ab, np.bool_(True), fe, ke, mom, nax)
            rmax = 0.0
            for j in range(ndof):
                if fixed[j] != 0.0:
                    res[j] = 0.0
                else:
                    res[j] = lam * f_ext[j] - f[j]
                    rmax = max(rmax, abs(res[j]))
            if rmax <= tol:
                conv = True
                its = it
                break
            # the bare tangent (scale 1, no mass) with the fixed DOFs decoupled, factored,
            # then the backward half of the solve
            if factor_jacobian(ab, 1.0, no_mass, 0.0, fixed, res) < 0:
                return -1
            ldl_solve_backward(ab, res)
            for j in range(ndof):
                d[j] += res[j]
        if not conv:
            return -1
    return its


@njit(cache=True)
def tangent_band(props, fixed, spring, d):
    """Band of the tangent stiffness K_T(d) of the bare beam (fixed DOFs not removed)."""
    ndof = d.shape[0]
    ab = np.zeros((ndof, HALF_BAND + 1))
    f = np.zeros(ndof)
    fe = np.empty(6)
    ke = np.empty((6, 6))
    nn = ndof // NDOF_NODE
    assemble_internal(d, props, f, ab, np.bool_(True), fe, ke, np.empty(nn), np.empty(nn))
    for j in range(ndof):
        ab[j, 0] += spring[j]
    return ab
