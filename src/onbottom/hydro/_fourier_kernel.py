"""Numba kernel of the Fourier force model in irregular flow (private).

Contract: :mod:`onbottom.hydro._force_contract` (signature, ``out`` slots, 16 state slots).
Theory and every choice made here: ``docs/theory/fourier_model.md``; the Python side is
:class:`onbottom.hydro.fourier.FourierModel`. Plain-Python twin: built from this source with
``onbottom._jit.pure_python`` in the tests (same arithmetic, interpreted).

Per half-cycle of the total ambient flow W = U + V_c (Sørensen, Bryndum & Jacobsen 1986;
Bryndum, Jacobsen & Tsahalis 1992, JOMAE 114:231; structure only, see the theory page)

    F_Y = s · ½ρD Û² [A₀ʸ + Σₙ (Aₙʸ cos nθ + Bₙʸ sin nθ)] + ½ρD C_D [W_r|W_r| − W|W|]
    F_Z =     ½ρD Û² [A₀ᶻ + Σₙ (Aₙᶻ cos nθ + Bₙᶻ sin nθ)]

s = ±1 the half-cycle's flow direction, θ ∈ [0, π] its phase, W_r = W − ẏ; the coefficients
are bilinear in (K̂, M̂) = (Û T̂ / D, s V_c / Û) of the half-cycle, fixed at its start, clamped
to the grid. Û, T̂ are the wave amplitude and period estimated from the completed half-cycles
with the memory weight w: Û ← (1 − w) a_k + w Û, a_k = P_k − s_k V_c (P_k the peak |W|), and
T̂ ← (1 − w) T_k / f(s_k V_c / a_k) + w T̂ with f(m) = ½ + asin(m)/π the fraction of a regular
wave's period that a half-cycle following (m > 0) or opposing (m < 0) the current lasts. The
phase (``P_PHASE``): "time", θ = π τ / T̂_h with τ the time since the zero crossing that began
the half-cycle and T̂_h = T̂ f(M̂) its predicted duration; or "flow", θ from the wave's
instantaneous phase φ = atan2(ω̂ U, U̇), ω̂ = 2π/T̂ (:func:`flow_phase`), which reaches π exactly
at every zero crossing. Both are exact in regular flow with a current.

Before two zero crossings (no completed half-cycle yet) and when a half-cycle outlasts its
prediction by more than ``OVERRUN`` (τ > 1.05 T̂_h; up to there the "time" phase is held at
π): a steady current, M > 1, a long irregular half-wave, the force falls back to the quasi-steady
Morison law with the model's C_D, C_L, C_M:
F_Y = ½ρD C_D W_r|W_r| + ρ (π D²/4) C_M U̇, F_Z = ½ρD C_L W².

params (one float64 row): [N, n_K, n_M, w, C_D, C_L, C_M, phase (0 time, 1 flow),
K grid (n_K), M grid (n_M), coefficients (n_K, n_M, 2, 2N+1)], each coefficient vector
ordered A₀, A₁, B₁, …, A_N, B_N, component 0 = Y, 1 = Z (packed by
:meth:`onbottom.hydro.fourier.FourierModel.params`).
"""

from __future__ import annotations

import math

from onbottom._jit import jitted_only
from onbottom.hydro._force_contract import FO_DFY_DYD, FO_DFZ_DYD, FO_FY, FO_FZ, N_FORCE_STATE

P_NHARM = 0
"""Harmonic order N used (integer-valued; read rounded, so that a solver's blend of two equal
rows, (1 − a)·N + a·N, cannot truncate it)."""
P_NK = 1
"""Number of K grid values."""
P_NM = 2
"""Number of M grid values."""
P_MEMORY = 3
"""Memory weight w in [0, 1)."""
P_CD = 4
"""Quasi-steady drag coefficient C_D (fallback law and relative-motion correction)."""
P_CL = 5
"""Quasi-steady lift coefficient C_L (fallback law)."""
P_CM = 6
"""Inertia coefficient C_M (fallback law)."""
P_PHASE = 7
"""Phase rule: 0 = elapsed time (θ = π τ / T̂_h), 1 = flow (θ from the instantaneous wave
phase of U, U̇ with the estimated period, :func:`flow_phase`); the scale is Û in both."""
P_HEADER = 8
"""First slot of the K grid; the M grid and the coefficients follow."""

S_INIT = 0
"""1 once a sample has been seen (0 in a zero state: flow at rest)."""
S_T = 1
"""Time of the last evaluated sample [s]."""
S_W = 2
"""Total ambient flow W = U + V_c at that sample [m/s] (signed)."""
S_SIGN = 3
"""Direction s of the current half-cycle: +1, −1, or 0 while the flow has been at rest."""
S_T_START = 4
"""Time the current half-cycle began [s] (its zero crossing, linearly interpolated)."""
S_PEAK = 5
"""Running peak |W| of the current half-cycle [m/s]."""
S_NCROSS = 6
"""Zero crossings seen; >= 1 means the current half-cycle began at a crossing."""
S_UM = 7
"""Estimated wave amplitude Û [m/s]; > 0 once one half-cycle has completed."""
S_TW = 8
"""Estimated wave period T̂ [s]."""
S_XK = 9
"""Fractional grid index of K̂ in the table (cell i + fraction f, clamped), set at the crossing."""
S_NCLAMP = 10
"""Half-cycles whose (K̂, M̂) lay outside the table's grid (clamped)."""
S_K = 11
"""K̂ of the current half-cycle [-]."""
S_M = 12
"""M̂ = s V_c / Û of the current half-cycle [-] (> 0 following the current)."""
S_TH = 13
"""Predicted duration T̂_h of the current half-cycle [s]."""
S_MODE = 14
"""1 if the last evaluation used the Fourier series, 0 the quasi-steady fallback."""
S_XM = 15
"""Fractional grid index of M̂ in the table, set at the crossing."""

OVERRUN = 0.05
"""A half-cycle may outlast its predicted duration T̂_h by this fraction with the phase held at
θ = π (so that the O(Δt²) error of the estimates in regular flow never switches to the
fallback law); beyond (1 + OVERRUN) T̂_h the quasi-steady law applies."""

M_CLIP = 0.95
"""|m| limit in f(m) = ½ + asin(m)/π, so that a weak opposing half-cycle cannot give an
unbounded period estimate."""


@jitted_only
def half_cycle_fraction(m):
    """f(m) = ½ + asin(m)/π: a half-cycle's share of a regular wave's period [-].

    m = s V_c / U_m (> 0: the half-cycle flows with the current); clipped to ±``M_CLIP``.
    """
    if m > M_CLIP:
        m = M_CLIP
    elif m < -M_CLIP:
        m = -M_CLIP
    return 0.5 + math.asin(m) / math.pi


@jitted_only
def locate(params, start, n, x):
    """Cell ``i`` and fraction ``f`` of ``x`` on the grid ``params[start:start+n]``.

    Returns (i, f, outside): clamped to the end values (f = 0 or 1) when ``x`` lies outside,
    ``outside`` = 1.0 then; a one-point grid gives (0, 0.0, x != grid).
    """
    lo = params[start]
    if n == 1:
        return 0, 0.0, 1.0 if x != lo else 0.0
    hi = params[start + n - 1]
    if x <= lo:
        return 0, 0.0, 1.0 if x < lo else 0.0
    if x >= hi:
        return n - 2, 1.0, 1.0 if x > hi else 0.0
    i = 0
    while i < n - 2 and params[start + i + 1] <= x:
        i += 1
    a = params[start + i]
    return i, (x - a) / (params[start + i + 1] - a), 0.0


@jitted_only
def grid_index(params, start, n, x):
    """Fractional index i + f of ``x`` on the grid ``params[start:start+n]`` (clamped) and 1.0
    if ``x`` lies outside the grid, else 0.0."""
    i, f, outside = locate(params, start, n, x)
    return i + f, outside


@jitted_only
def series(params, xk, xm, theta):
    """(Y, Z) values of A₀ + Σₙ (Aₙ cos nθ + Bₙ sin nθ), coefficients bilinear in the cell.

    xk, xm: fractional grid indices of K and M (:func:`grid_index`); cos nθ, sin nθ by the
    angle-addition recurrence, shared by both components.
    """
    nh = int(params[P_NHARM] + 0.5)
    nk = int(params[P_NK] + 0.5)
    nm = int(params[P_NM] + 0.5)
    ncoef = 2 * nh + 1
    ik = min(int(xk), nk - 1)
    im = min(int(xm), nm - 1)
    fk = xk - ik
    fm = xm - im
    ik1 = ik + 1 if ik + 1 < nk else ik
    im1 = im + 1 if im + 1 < nm else im
    base = P_HEADER + nk + nm
    o00 = base + (ik * nm + im) * 2 * ncoef
    o10 = base + (ik1 * nm + im) * 2 * ncoef
    o01 = base + (ik * nm + im1) * 2 * ncoef
    o11 = base + (ik1 * nm + im1) * 2 * ncoef
    w00 = (1.0 - fk) * (1.0 - fm)
    w10 = fk * (1.0 - fm)
    w01 = (1.0 - fk) * fm
    w11 = fk * fm
    c1 = math.cos(theta)
    s1 = math.sin(theta)
    sy = 0.0
    sz = 0.0
    cn = 1.0
    sn = 0.0
    for j in range(ncoef):
        if j > 0 and j % 2 == 1:
            c_next = cn * c1 - sn * s1
            sn = sn * c1 + cn * s1
            cn = c_next
        basis = cn if j % 2 == 1 or j == 0 else sn
        cy = w00 * params[o00 + j] + w10 * params[o10 + j]
        cy += w01 * params[o01 + j] + w11 * params[o11 + j]
        cz = w00 * params[o00 + ncoef + j] + w10 * params[o10 + ncoef + j]
        cz += w01 * params[o01 + ncoef + j] + w11 * params[o11 + ncoef + j]
        sy += cy * basis
        sz += cz * basis
    return sy, sz


@jitted_only
def flow_phase(u_h, dudt_h, vc_h, period):
    """Half-cycle phase θ [rad] and wave amplitude A [m/s] from the instantaneous flow.

    u_h, dudt_h, vc_h: U, U̇, V_c in the half-cycle's frame (multiplied by its direction s);
    period: the estimated wave period T̂ [s]. With ω = 2π/T̂, the wave's local phase
    φ = atan2(ω U, U̇) and amplitude A = √(U² + (U̇/ω)²) (U = A sin φ, U̇ = A ω cos φ in a
    regular wave); the half-cycle spans φ ∈ (−α, π + α), α = asin(V/A) (clipped to
    ±asin ``M_CLIP``), mapped linearly to θ ∈ [0, π]. At a zero crossing of U + V this gives
    θ = π (and θ = 0 just after it) exactly, in any flow; in a regular wave θ = π τ / T_h.
    """
    omega = 2.0 * math.pi / period
    a = math.sqrt(u_h * u_h + (dudt_h / omega) ** 2)
    if a <= 0.0:
        return 0.0, 0.0
    phi = math.atan2(omega * u_h, dudt_h)
    if phi < -0.5 * math.pi:
        phi += 2.0 * math.pi
    m = vc_h / a
    if m > M_CLIP:
        m = M_CLIP
    elif m < -M_CLIP:
        m = -M_CLIP
    alpha = math.asin(m)
    theta = math.pi * (phi + alpha) / (math.pi + 2.0 * alpha)
    if theta < 0.0:
        theta = 0.0
    elif theta > math.pi:
        theta = math.pi
    return theta, a


@jitted_only
def fourier_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Fourier force model: F_Y, ∂F_Y/∂ẏ, F_Z, ∂F_Z/∂ẏ at time ``t`` (see the module docstring).

    params: the packed row (layout above); state_old / state_new: 16 slots ``S_*``; t [s];
    u [m/s], dudt [m/s²]: ambient wave-induced velocity and acceleration; vc [m/s]: current;
    ydot [m/s]: pipe velocity; d [m]: outer diameter; rho [kg/m³]: water density.
    """
    for i in range(N_FORCE_STATE):
        state_new[i] = state_old[i]
    w = u + vc
    if state_old[S_INIT] == 0.0:
        # first sample of a run: the current half-cycle began before it (incomplete)
        state_new[S_INIT] = 1.0
        state_new[S_SIGN] = 1.0 if w > 0.0 else (-1.0 if w < 0.0 else 0.0)
        state_new[S_T_START] = t
        state_new[S_PEAK] = abs(w)
    else:
        s_old = state_old[S_SIGN]
        if s_old == 0.0:
            if w != 0.0:
                # flow starting from rest: a half-cycle that did not begin at a crossing
                state_new[S_SIGN] = 1.0 if w > 0.0 else -1.0
                state_new[S_T_START] = t
                state_new[S_PEAK] = abs(w)
        elif w * s_old < 0.0:
            # zero crossing between the last sample and this one
            w_old = state_old[S_W]
            t_old = state_old[S_T]
            if w_old * s_old > 0.0:
                tc = t_old + (t - t_old) * w_old / (w_old - w)
            else:
                tc = t_old
            if state_old[S_NCROSS] >= 1.0:
                # the ending half-cycle is complete: update the wave estimates
                peak = state_old[S_PEAK]
                tk = tc - state_old[S_T_START]
                amp = peak - s_old * vc
                if amp < 0.5 * peak:
                    amp = 0.5 * peak
                if tk > 0.0 and amp > 0.0:
                    period = tk / half_cycle_fraction(s_old * vc / amp)
                    if state_old[S_UM] > 0.0:
                        mem = params[P_MEMORY]
                        amp = (1.0 - mem) * amp + mem * state_old[S_UM]
                        period = (1.0 - mem) * period + mem * state_old[S_TW]
                    state_new[S_UM] = amp
                    state_new[S_TW] = period
            state_new[S_NCROSS] = state_old[S_NCROSS] + 1.0
            s_new = -s_old
            state_new[S_SIGN] = s_new
            state_new[S_T_START] = tc
            state_new[S_PEAK] = abs(w)
            if state_new[S_UM] > 0.0:
                um = state_new[S_UM]
                kc = um * state_new[S_TW] / d
                mh = s_new * vc / um
                state_new[S_K] = kc
                state_new[S_M] = mh
                state_new[S_TH] = state_new[S_TW] * half_cycle_fraction(mh)
                nk = int(params[P_NK] + 0.5)
                xk, out_k = grid_index(params, P_HEADER, nk, kc)
                xm, out_m = grid_index(params, P_HEADER + nk, int(params[P_NM] + 0.5), mh)
                state_new[S_XK] = xk
                state_new[S_XM] = xm
                if out_k > 0.0 or out_m > 0.0:
                    state_new[S_NCLAMP] = state_old[S_NCLAMP] + 1.0
        elif abs(w) > state_old[S_PEAK]:
            state_new[S_PEAK] = abs(w)
    state_new[S_T] = t
    state_new[S_W] = w

    q = 0.5 * rho * d
    cd = params[P_CD]
    wr = w - ydot
    tau = t - state_new[S_T_START]
    th = state_new[S_TH]
    if state_new[S_UM] > 0.0 and state_new[S_NCROSS] >= 2.0 and th > 0.0:
        in_series = tau <= (1.0 + OVERRUN) * th
    else:
        in_series = False
    if in_series:
        s = state_new[S_SIGN]
        if params[P_PHASE] == 0.0:
            theta = math.pi * min(tau / th, 1.0)
            amp = state_new[S_UM]
        else:
            theta, _ = flow_phase(s * u, s * dudt, s * vc, state_new[S_TW])
            amp = state_new[S_UM]
        amp2 = q * amp * amp
        sy, sz = series(params, state_new[S_XK], state_new[S_XM], theta)
        fy = s * amp2 * sy + q * cd * (wr * abs(wr) - w * abs(w))
        fz = amp2 * sz
        state_new[S_MODE] = 1.0
    else:
        fy = q * cd * wr * abs(wr) + 0.25 * math.pi * rho * d * d * params[P_CM] * dudt
        fz = q * params[P_CL] * w * w
        state_new[S_MODE] = 0.0
    out[FO_FY] = fy
    out[FO_DFY_DYD] = -2.0 * q * cd * abs(wr)
    out[FO_FZ] = fz
    out[FO_DFZ_DYD] = 0.0
