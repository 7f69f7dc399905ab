"""The floor of a section storm: the arithmetic its equations need per step, nothing else.

:func:`floor_storm` integrates the equation of lateral motion of
:mod:`onbottom.dynamics._storm_kernel` through the same flow samples, with the Morison + lift
formula of :mod:`onbottom.hydro._morison_kernel` written out and the Verley & Sotberg kernel
called directly: per step the flow interpolation, the DNV-RP-F109 penetration reductions, then
Newton iterations of force, soil and residual to the kernel's tolerance (the safeguarded
iterate of :mod:`onbottom.dynamics._newton`: plain Newton stalls at the soil's kinks), then
the Newmark update. Fixed steps, no step control, no dispatch, no events, no
summary, no records. It is the lower bound against which ``storm_kernel_floor.py`` sets the
storm kernel (not a solver: it has no step cut-back, so a storm that needs one is not its
business).
"""

from __future__ import annotations

import math

import numpy as np

from onbottom._jit import borrow, njit
from onbottom.dynamics._newton import safeguarded_update
from onbottom.soil._verley_sotberg_kernel import verley_sotberg_kernel
from onbottom.soil.base import OUT_R, OUT_SIZE, OUT_TANGENT, S_Z


@njit(cache=True)
def floor_storm(params, state0, ku, ka, dts, prows, vc, d, rho, ws, mass, ry_c, rz_c, dt,
                n_steps, rtol, max_iter):  # fmt: skip
    """Integrate ``n_steps`` fixed steps ``dt`` [s]; returns (y_max [m], soil evaluations).

    ``prows`` the Morison rows (C_D, C_M, C_L, lift on the relative velocity) per flow sample
    or one row; ``ry_c``, ``rz_c`` the constant load reductions; the rest as
    :mod:`onbottom.dynamics._storm_kernel`'s settings (average-acceleration Newmark).
    """
    state = state0.copy()
    trial = np.empty_like(state)
    out = np.empty(OUT_SIZE)
    n = ku.shape[0]
    nc = prows.shape[0]
    c0 = mass / (0.25 * dt * dt)
    cv = 0.5 / (0.25 * dt)
    ainert = 0.25 * math.pi * rho * d * d
    half_rho_d = 0.5 * rho * d
    y = 0.0
    yd = 0.0
    a = 0.0
    ymax = 0.0
    evals = 0
    for i in range(n_steps):
        t1 = (i + 1) * dt
        # flow at t1
        x = t1 / dts
        j = int(x)
        if j >= n - 1:
            j = n - 2
        f = x - j
        u = ku[j] + f * (ku[j + 1] - ku[j])
        du = ka[j] + f * (ka[j + 1] - ka[j])
        jr = j if nc > 1 else 0
        cd = prows[jr, 0]
        cm = prows[jr, 1]
        cl = prows[jr, 2]
        # reductions from the committed penetration (F109 Eqs 3.19-3.20)
        zd = state[S_Z] / d
        ry = ry_c * max(1.0 - 1.4 * zd, 0.3) if zd > 0.0 else ry_c
        rz = rz_c * max(1.0 - 1.3 * (zd - 0.1), 0.0) if zd > 0.1 else rz_c
        s = u + vc
        v = ws - rz * half_rho_d * cl * s * s
        finert = ainert * cm * du
        dy_hat = dt * yd + dt * dt * 0.25 * a
        yd_base = yd + dt * 0.5 * a
        tol = rtol * (ws + abs(mass * a) + 1.0)
        dy = dy_hat
        have_lo = np.bool_(False)
        have_hi = np.bool_(False)
        lo = 0.0
        hi = 0.0
        eps = 4.0e-16 * (abs(y) + abs(dy_hat) + 1e-12)
        for _ in range(max_iter):
            yd1 = yd_base + cv * (dy - dy_hat)
            w = s - yd1
            fy = ry * (half_rho_d * cd * w * abs(w) + finert)
            dfdyd = -ry * rho * d * cd * abs(w)
            verley_sotberg_kernel(
                borrow(params), borrow(state), y + dy, v, borrow(trial), borrow(out)
            )
            evals += 1
            r = c0 * (dy - dy_hat) + out[OUT_R] - fy
            if abs(r) <= tol:
                break
            dy_next, lo, hi, have_lo, have_hi, closed = safeguarded_update(
                dy, r, c0 - dfdyd * cv, out[OUT_TANGENT], lo, hi, have_lo, have_hi, eps
            )
            if closed:
                break
            dy = dy_next
        a1 = (dy - dy_hat) / (0.25 * dt * dt)
        yd = yd + dt * 0.5 * (a + a1)
        a = a1
        y += dy
        if abs(y) > ymax:
            ymax = abs(y)
        for k in range(state.shape[0]):
            state[k] = trial[k]
    return ymax, evals
