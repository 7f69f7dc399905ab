"""Numba kernels of the 2D DEM engine (private).

Physics (PFC2D ``linear`` + ``rrlinear``, see ``docs/theory/dem.md``):

* normal force ``F_n = k_n·δ`` (δ = overlap), no tension, no dashpot;
* incremental shear spring ``F_s ← F_s + k_s·v_t·Δt``, capped at ``μ·F_n``; reset when the
  contact opens;
* rolling spring ``M_r ← M_r + k_r·(ω_j − ω_i)·Δt``, ``k_r = k_s·R̄²``, capped at
  ``μ_r·R̄·F_n``, ``R̄ = R_i R_j/(R_i + R_j)`` (``R̄ = R_i`` against walls/pipe);
* local damping: each component of the unbalanced force and moment gets ``−α·|F|·sign(v)``;
* leapfrog (PFC's velocity-Verlet with half-step velocities).

Data layout
-----------
Particle pairs are a half neighbour list in CSR form: the candidates of disk ``i`` are
``nbr[start[i]:start[i+1]]`` (all ``j > i``, ascending, uint32), with per-pair shear force ``fs``
and rolling moment ``mr`` (history, force on/moment on ``i``); ``owner[k]`` is the ``i`` of entry
``k``. ``rstart``/``ridx`` is the transposed index (entries in which a disk is the ``j`` side,
ascending). A step is two parallel passes over blocks of :data:`BLOCK` disks: the pair pass
evaluates each entry once (force on ``i`` into ``cfx``/``cfy``) and sums each disk's own
entries; the integration pass adds the ``j``-side entries, walls, pipe and gravity in a fixed
order and moves the disk. The result does not depend on the number of threads (bitwise).
Indices are unsigned so that numba emits no negative-index wrap-around code in the hot loops.

Walls: 0 left (x = x0), 1 right (x = x1), 2 bottom (y = y0), 3 lid (y = lid, moving, only
when active). The pipe is a rigid disk moving at a prescribed velocity. Wall/pipe shear and
rolling histories are per particle: ``fsw[i, w]``, ``mrw[i, w]``, w = 0..3, 4 = pipe.
"""

from __future__ import annotations

import numpy as np
from numba import prange

from onbottom._jit import numba_njit as njit

# indices into the parameter vector ``prm``
P_DT = 0
P_GX = 1
P_GY = 2
P_ALPHA = 3
P_KN = 4
P_KS = 5
P_MU = 6
P_MUR = 7
P_KN_P = 8
P_KS_P = 9
P_MU_P = 10
P_MUR_P = 11
P_KN_W = 12
P_KS_W = 13
P_MU_W = 14
P_MUR_W = 15
P_X0 = 16
P_X1 = 17
P_Y0 = 18
P_LID_Y = 19
P_LID_V = 20
P_LID_ON = 21
P_LID_STOP = 22
P_PIPE_X = 23
P_PIPE_Y = 24
P_PIPE_R = 25
P_PIPE_V = 26
P_PIPE_ON = 27
P_SKIN = 28
P_TIME = 29
P_DIAG = 30
N_PRM = 31

# indices into the FIRE state vector ``fire`` (Simulation.fire)
F_ON = 0  # 1: FIRE mixing instead of local damping
F_ALPHA = 1  # mixing fraction α of this step
F_CTR = 2  # α·|v|/|F| (translation) of this step
F_CROT = 3  # α·|ω|/|T| (rotation) of this step
F_RESTART = 4  # 1: zero the velocities this step (power F·v was negative)
F_NPOS = 5  # steps since the last restart
F_ALPHA0 = 6  # α after a restart (Bitzek et al. 2006: 0.1)
F_FALPHA = 7  # α ← α·f_α per step after N_min steps (0.99)
F_NMIN = 8  # N_min (5)
F_RESTARTS = 9  # number of restarts (diagnostics)
N_FIRE = 10
N_BSUM = 5  # FIRE sums per block: F·v, |v|², |F|², ω², T²

BLOCK = 512  # disks per block of the parallel loops (one displacement maximum each)
# cost of one contact or disk sub-step of fine_substeps against one disk of the plain pass
# (gather_integrate_zonal's split; measured on the full-size SM-Dr48 bed: ≈ 32 ns vs 21 ns)
FINE_ITEM_COST = 1.5
N_WALL = 5  # 4 walls + pipe in the per-particle history arrays
PIPE = 4


@njit(cache=True, inline="always")
def contact_update(dnx, dny, overlap, vtan, dw, rbar, kn, ks, mu, mur, fs, mr, dt):
    """Contact law for one contact: returns (F_n, F_s, M_r) after one step.

    ``vtan``: tangential relative velocity of the other body w.r.t. this one at the contact
    (along t = (−n_y, n_x), n pointing from this body to the other); ``dw``: ω_other − ω_this.
    F_s and M_r act on *this* body. Open contact (overlap ≤ 0) → all zero (history reset).
    """
    if overlap <= 0.0:
        return 0.0, 0.0, 0.0
    fn = kn * overlap
    fs_new = fs + ks * vtan * dt
    cap = mu * fn
    if fs_new > cap:
        fs_new = cap
    elif fs_new < -cap:
        fs_new = -cap
    mr_new = 0.0
    if mur > 0.0:
        kr = ks * rbar * rbar
        mr_new = mr + kr * dw * dt
        mcap = mur * rbar * fn
        if mr_new > mcap:
            mr_new = mcap
        elif mr_new < -mcap:
            mr_new = -mcap
    return fn, fs_new, mr_new


@njit(cache=True, boundscheck=False, error_model="numpy")
def _pair_entries(k0, k1, owner, nbr, pos, vel, om, rad, fs, mr, cfx, cfy, cmag, diag, dt, kn,
                  ks, mu, mur):  # fmt: skip
    """List entries k0..k1−1: contact law, history update, force on the owner disk i.

    Flat loop over the entries, without branches on the contact state (selects instead):
    about 20 % faster than a loop per disk with an early exit for open contacts, same bits
    (the law of :func:`contact_update` written out; caps as compare-and-select).
    """
    for kk in range(k0, k1):
        k = np.uint64(kk)  # unsigned indices: no negative-index wrap-around code
        i = owner[k]
        j = nbr[k]
        xi = pos[i, 0]
        yi = pos[i, 1]
        dx = pos[j, 0] - xi
        dy = pos[j, 1] - yi
        ri = rad[i]
        rj = rad[j]
        rsum = ri + rj
        d2 = dx * dx + dy * dy
        touch = d2 < rsum * rsum
        d = np.sqrt(d2)  # d = 0 only for coincident centres (NaN forces, as any DEM would)
        nx = dx / d
        ny = dy / d
        tx = -ny
        ty = nx
        wi = om[i]
        wj = om[j]
        vt = (vel[j, 0] - vel[i, 0]) * tx + (vel[j, 1] - vel[i, 1]) * ty
        vt -= wj * rj + wi * ri
        rbar = ri * rj / rsum
        fn = kn * (rsum - d)
        f = fs[k] + ks * vt * dt
        cap = mu * fn
        f = cap if f > cap else f
        f = -cap if f < -cap else f
        kr = ks * rbar * rbar
        m = mr[k] + kr * (wj - wi) * dt
        mcap = mur * rbar * fn
        m = mcap if m > mcap else m
        m = -mcap if m < -mcap else m
        m = m if mur > 0.0 else 0.0
        cx = -fn * nx + f * tx
        cy = -fn * ny + f * ty
        fs[k] = f if touch else 0.0
        mr[k] = m if touch else 0.0
        cfx[k] = cx if touch else 0.0
        cfy[k] = cy if touch else 0.0
        cmag[k] = np.sqrt(fn * fn + f * f) if touch and diag else 0.0


@njit(cache=True, boundscheck=False, error_model="numpy")
def _pair_entries_frictionless(k0, k1, owner, nbr, pos, rad, fs, mr, cfx, cfy, cmag, diag, kn):
    """:func:`_pair_entries` for μ = μ_r = 0 (the compaction's contacts): normal force only.

    With μ = 0 the shear cap is ±0, so the law's shear force and rolling moment are ±0 and the
    contact force is the normal one, −F_n·n (the same value; a ±0 shear term can change only
    the sign of a zero component). The shear and rolling histories are written as zeros, as
    the full law leaves them. Skips the velocity and spin loads of both disks, r̄'s division
    and the caps.
    """
    for kk in range(k0, k1):
        k = np.uint64(kk)
        i = owner[k]
        j = nbr[k]
        dx = pos[j, 0] - pos[i, 0]
        dy = pos[j, 1] - pos[i, 1]
        rsum = rad[i] + rad[j]
        d2 = dx * dx + dy * dy
        touch = d2 < rsum * rsum
        d = np.sqrt(d2)
        fn = kn * (rsum - d)
        cx = -fn * (dx / d)
        cy = -fn * (dy / d)
        fs[k] = 0.0
        mr[k] = 0.0
        cfx[k] = cx if touch else 0.0
        cfy[k] = cy if touch else 0.0
        cmag[k] = np.sqrt(fn * fn) if touch and diag else 0.0


@njit(cache=True, parallel=True, boundscheck=False)
def pair_forces(
    prm, pos, vel, om, rad, start, owner, nbr, fs, mr, cfx, cfy, cmag, sfx, sfy, stq, sa
):  # fmt: skip
    """Forces of all listed disk pairs (blocks of :data:`BLOCK` disks in parallel).

    Contact k (disks i < j, i = ``owner[k]``) stores the force on i in ``cfx[k]``, ``cfy[k]``
    (``cmag[k]`` its magnitude, diagnostics only) and its updated history in ``fs[k]``,
    ``mr[k]``. Then each disk i sums its own contacts (list order) into ``sfx``/``sfy``/
    ``stq`` (torque ``r_i·F_s + M_r``)/``sa``; the other disk j gets −F and ``r_j·F_s − M_r``
    in :func:`gather_integrate`.
    """
    n = rad.shape[0]
    dt = prm[P_DT]
    kn = prm[P_KN]
    ks = prm[P_KS]
    mu = prm[P_MU]
    mur = prm[P_MUR]
    diag = prm[P_DIAG] > 0.5
    frictionless = mu == 0.0 and mur == 0.0
    nblock = (n + BLOCK - 1) // BLOCK
    for b in prange(nblock):
        i0 = b * BLOCK
        i1 = min(n, i0 + BLOCK)
        if frictionless:
            _pair_entries_frictionless(
                start[i0], start[i1], owner, nbr, pos, rad, fs, mr, cfx, cfy, cmag, diag, kn
            )  # fmt: skip
        else:
            _pair_entries(
                start[i0], start[i1], owner, nbr, pos, vel, om, rad, fs, mr, cfx, cfy, cmag,
                diag, dt, kn, ks, mu, mur,
            )  # fmt: skip
        for i in range(i0, i1):
            ri = rad[i]
            fx = 0.0
            fy = 0.0
            tq = 0.0
            a = 0.0
            for kk in range(start[i], start[i + 1]):
                k = np.uint64(kk)
                fx += cfx[k]
                fy += cfy[k]
                if not frictionless:  # else ±0 terms: tq stays +0.0
                    tq += ri * fs[k] + mr[k]
                if diag:
                    a += cmag[k]
            sfx[i] = fx
            sfy[i] = fy
            stq[i] = tq
            sa[i] = a


@njit(cache=True)
def list_owner(start, m):
    """Owner disk i of each list entry (uint32), from the CSR offsets ``start``."""
    owner = np.empty(m, np.uint32)
    for i in range(start.shape[0] - 1):
        for k in range(start[i], start[i + 1]):
            owner[k] = i
    return owner


@njit(cache=True, inline="always", error_model="numpy")
def _sign(v):
    """+1.0, −1.0 or 0.0 (v = ±0) without a branch."""
    return (v > 0.0) * 1.0 - (v < 0.0) * 1.0


@njit(cache=True)
def wall_contact(i, w, nx, ny, overlap, vbx, vby, pos, vel, om, rad, fsw, mrw, kn, ks, mu, mur, dt):
    """Contact of disk i with wall/pipe w (normal n from disk to wall; wall velocity vb).

    Returns (fx, fy, torque) on the disk and updates the per-particle history.
    """
    if overlap <= 0.0:
        fsw[i, w] = 0.0
        mrw[i, w] = 0.0
        return 0.0, 0.0, 0.0
    ri = rad[i]
    tx = -ny
    ty = nx
    vt = (vbx - vel[i, 0]) * tx + (vby - vel[i, 1]) * ty - om[i] * ri
    fn, fsn, mrn = contact_update(
        nx, ny, overlap, vt, -om[i], ri, kn, ks, mu, mur, fsw[i, w], mrw[i, w], dt
    )
    fsw[i, w] = fsn
    mrw[i, w] = mrn
    return -fn * nx + fsn * tx, -fn * ny + fsn * ty, ri * fsn + mrn


@njit(cache=True, inline="always")
def _stiff_contact(vx, vy, w, ri, nx, ny, overlap, vbx, vby, fs, mr, kn, ks, mu, mur, dt):
    """:func:`wall_contact` on scalars: (fx, fy, torque, F_s, M_r) of a wall/pipe contact."""
    if overlap <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    tx = -ny
    ty = nx
    vt = (vbx - vx) * tx + (vby - vy) * ty - w * ri
    fn, fsn, mrn = contact_update(nx, ny, overlap, vt, -w, ri, kn, ks, mu, mur, fs, mr, dt)
    return -fn * nx + fsn * tx, -fn * ny + fsn * ty, ri * fsn + mrn, fsn, mrn


@njit(cache=True, inline="always", error_model="numpy")
def _add_stiff(i, k, vx, vy, w, ri, nx, ny, ov, vby, fsw, mrw, kn, ks, mu, mur, dt, f, diag):
    """Add disk i's contact k with a wall, the lid or the pipe (:func:`_stiff_contact`, its
    history in ``fsw``/``mrw`` updated) to ``f`` = (F_x, F_y, torque, applied magnitude; the
    last summed only with ``diag``); returns the new ``f`` and the contact force (x, y)."""
    cx, cy, ct_, fsn, mrn = _stiff_contact(
        vx, vy, w, ri, nx, ny, ov, 0.0, vby, fsw[i, k], mrw[i, k], kn, ks, mu, mur, dt
    )
    fsw[i, k] = fsn
    mrw[i, k] = mrn
    a = f[3] + np.sqrt(cx * cx + cy * cy) if diag else f[3]
    return (f[0] + cx, f[1] + cy, f[2] + ct_, a), cx, cy


@njit(cache=True, inline="always", error_model="numpy")
def _add_walls_lid(
    i, vx, vy, w, ri, xi, yi, x0, x1, y0, lid_on, ly, lid_v, fsw, mrw, kn, ks, mu, mur, dt, f,
    diag,
):  # fmt: skip
    """Add disk i's contacts with the left, right and bottom walls and (when on) the lid at
    height ``ly`` to ``f`` (:func:`_add_stiff`, in that order); returns the new ``f``."""
    f, _, _ = _add_stiff(
        i, 0, vx, vy, w, ri, -1.0, 0.0, ri - (xi - x0), 0.0, fsw, mrw, kn, ks, mu, mur, dt, f,
        diag,
    )  # fmt: skip
    f, _, _ = _add_stiff(
        i, 1, vx, vy, w, ri, 1.0, 0.0, ri - (x1 - xi), 0.0, fsw, mrw, kn, ks, mu, mur, dt, f, diag
    )
    f, _, _ = _add_stiff(
        i, 2, vx, vy, w, ri, 0.0, -1.0, ri - (yi - y0), 0.0, fsw, mrw, kn, ks, mu, mur, dt, f,
        diag,
    )  # fmt: skip
    if lid_on:
        f, _, _ = _add_stiff(
            i, 3, vx, vy, w, ri, 0.0, 1.0, ri - (ly - yi), lid_v, fsw, mrw, kn, ks, mu, mur, dt,
            f, diag,
        )  # fmt: skip
    return f


@njit(cache=True, inline="always", error_model="numpy")
def _stiff_gap(xi, yi, ri, x0, x1, y0, lid_on, lid_y, pipe_on, px, py, pr):
    """Smallest gap [m] between a disk and the walls, the lid (if on) and the pipe (if on)."""
    gap = min(xi - x0, x1 - xi, yi - y0) - ri
    if lid_on:
        gap = min(gap, lid_y - yi - ri)
    if pipe_on:
        dx = px - xi
        dy = py - yi
        gap = min(gap, np.sqrt(dx * dx + dy * dy) - pr - ri)
    return gap


@njit(cache=True, boundscheck=False, error_model="numpy")
def fine_candidates(prm, pos, rad, fixed, reach, cand):
    """The disks (not fixed) within ``reach`` of a wall, the lid or the pipe, into ``cand``.

    Zonal sub-cycling flags a disk when its gap is below half a skin at the start of a step
    (:func:`collect_fine`); only these candidates are tested at every step. :func:`run_steps`
    refreshes them at every list rebuild and whenever the pipe or the lid has moved half a
    skin since the last refresh, with ``reach`` = 2 skins: until the next refresh a disk moves
    less than a skin from where it was (half a skin from its list-build position, on either
    side) and a stiff body less than half a skin, so a disk outside ``reach`` cannot come
    within half a skin of one. Returns the number of candidates.
    """
    n = rad.shape[0]
    x0 = prm[P_X0]
    x1 = prm[P_X1]
    y0 = prm[P_Y0]
    lid_on = prm[P_LID_ON] > 0.5
    lid_y = prm[P_LID_Y]
    pipe_on = prm[P_PIPE_ON] > 0.5
    px = prm[P_PIPE_X]
    py = prm[P_PIPE_Y]
    pr = prm[P_PIPE_R]
    nc = 0
    for i in range(n):
        gap = _stiff_gap(pos[i, 0], pos[i, 1], rad[i], x0, x1, y0, lid_on, lid_y, pipe_on, px,
                         py, pr)  # fmt: skip
        if gap < reach and not fixed[i]:
            cand[nc] = i
            nc += 1
    return nc


@njit(cache=True, boundscheck=False, error_model="numpy")
def collect_fine(
    prm, pos, rad, cand, ncand, fine, start, rstart, ridx, owner, flist, floc, plist, fs, mr,
    hfs, hmr,
):  # fmt: skip
    """Flag the candidates within half a skin of a wall, the lid or the pipe (``fine[i]`` = 1)
    and list them (``flist``, ``floc[i]`` = position in it; −1 for every other disk), then
    the list entries with at least one flagged disk (``plist``, each pair once), with their
    history copied to ``hfs``/``hmr`` before the pair pass overwrites it.

    Zonal sub-cycling (:func:`fine_substeps`): the flagged disks take ``nsub`` sub-steps per
    step for *all* their contacts; the others (never closer than half a skin to a stiff body
    at the start of a step, so never touching one within the step) take the plain step.
    Returns (number of flagged disks, number of entries).
    """
    margin = 0.5 * prm[P_SKIN]
    x0 = prm[P_X0]
    x1 = prm[P_X1]
    y0 = prm[P_Y0]
    lid_on = prm[P_LID_ON] > 0.5
    lid_y = prm[P_LID_Y]
    pipe_on = prm[P_PIPE_ON] > 0.5
    px = prm[P_PIPE_X]
    py = prm[P_PIPE_Y]
    pr = prm[P_PIPE_R]
    nf = 0
    for c in range(ncand):
        i = cand[c]
        gap = _stiff_gap(pos[i, 0], pos[i, 1], rad[i], x0, x1, y0, lid_on, lid_y, pipe_on, px,
                         py, pr)  # fmt: skip
        if gap < margin:
            fine[i] = 1
            flist[nf] = i
            floc[i] = nf
            nf += 1
        else:
            fine[i] = 0
    npair = 0
    for ll in range(nf):
        i = flist[ll]
        for k in range(start[i], start[i + 1]):
            plist[npair] = k
            hfs[npair] = fs[k]
            hmr[npair] = mr[k]
            npair += 1
        for q in range(rstart[i], rstart[i + 1]):
            k = ridx[q]
            if not fine[owner[k]]:  # a pair of two flagged disks is listed by its owner
                plist[npair] = k
                hfs[npair] = fs[k]
                hmr[npair] = mr[k]
                npair += 1
    return nf, npair


@njit(cache=True, boundscheck=False, error_model="numpy")
def fine_partners(
    prm, pos, vel, om, rad, mass, inert, fixed, plist, npair, owner, nbr, rstart, ridx, fs, mr,
    cfx, cfy, sfx, sfy, stq, floc, cplist, cpv,
):  # fmt: skip
    """The plain partners of the flagged disks for :func:`fine_substeps`, before the plain
    pass moves them: ``floc[c]`` = −2 − their index in ``cplist``, and ``cpv[·]`` their
    velocity over the step (vx, vy, ω; the plain step's, from their force at the start of the
    step with gravity and local damping, as :func:`_gather_integrate_block` computes it) and
    their position at the start (x, y). Returns the number of partners.
    """
    dt = prm[P_DT]
    gx = prm[P_GX]
    gy = prm[P_GY]
    alpha = prm[P_ALPHA]
    ncp = 0
    for p in range(npair):
        k = plist[p]
        for side in range(2):
            c = owner[k] if side == 0 else nbr[k]
            if floc[c] != -1:
                continue
            floc[c] = -2 - ncp
            cplist[ncp] = c
            cpv[ncp, 3] = pos[c, 0]
            cpv[ncp, 4] = pos[c, 1]
            if fixed[c]:
                cpv[ncp, 0] = 0.0
                cpv[ncp, 1] = 0.0
                cpv[ncp, 2] = 0.0
            else:
                rc = rad[c]
                fx = sfx[c]
                fy = sfy[c]
                tq = stq[c]
                for qq in range(rstart[c], rstart[c + 1]):
                    kk = ridx[qq]
                    fx -= cfx[kk]
                    fy -= cfy[kk]
                    tq += rc * fs[kk] - mr[kk]
                mc = mass[c, 0]
                fx += mass[c, 1] * gx
                fy += mass[c, 1] * gy
                vx = vel[c, 0]
                vy = vel[c, 1]
                w = om[c]
                if alpha > 0.0:
                    fx -= alpha * abs(fx) * _sign(vx)
                    fy -= alpha * abs(fy) * _sign(vy)
                    tq -= alpha * abs(tq) * _sign(w)
                cpv[ncp, 0] = vx + dt * fx / mc
                cpv[ncp, 1] = vy + dt * fy / mc
                cpv[ncp, 2] = w + dt * tq / inert[c]
            ncp += 1
    return ncp


@njit(cache=True, boundscheck=False, error_model="numpy")
def fine_substeps(
    prm, nsub, pos, vel, om, th, rad, mass, inert, ref, flist, nf, floc, plist, npair, owner,
    nbr, fsw, mrw, pfx, pfy, unb, app, hfs, hmr, dacc, cplist, ncp, cpv,
):  # fmt: skip
    """Zonal sub-cycling: the flagged disks take ``nsub`` leapfrog sub-steps of Δt/nsub.

    Nodal-partition sub-cycling (Belytschko, Yen & Mullen 1979, Comput. Methods Appl. Mech.
    Eng. 17:259) written for DEM. The plain disks take the plain leapfrog step with every
    contact force at the start of the step (the pair pass's, also for their contacts with
    flagged disks), exactly as without sub-cycling. Every force on a flagged disk (soil
    contacts, walls, lid, pipe, gravity) and its local damping are evaluated at every
    sub-step, against the other disk of a contact at its current sub-step position when it
    is flagged too, else at its position on its plain step, x + q·h·v, with v the velocity
    the plain step will give it (its force at the start of the step with gravity and local
    damping: exact), both from :func:`fine_partners` (``cpv``, ``ncp`` partners), which runs
    before the plain pass, so that this pass may run beside it (:func:`gather_integrate_zonal`).
    A disk at rest stays at rest (the earlier r-RESPA impulse form made resting disks swing
    within a step, and local damping of that swing held them with a net force). The two
    partitions exchange the same force at the start of a step but not over it, so momentum is
    conserved to O(Δt) while the contact force changes (exactly at rest); giving the plain disks
    the mean of the sub-step forces instead is momentum-exact but lags them by 3Δt/8, a viscous
    drag that dissipated 0.5 % of the energy of a disk gas in 20,000 steps (this form: no
    drift).
    Pair histories advance by the sub-steps (``hfs``/``hmr``, written back by
    :func:`run_steps` after the plain pass). Stores the mean pipe force over the sub-steps,
    and the mean unbalanced and applied force, of each flagged disk. Touches only the flagged
    disks, the pair histories ``hfs``/``hmr`` and its work arrays. Returns the flagged disks'
    largest squared displacement since the last list build.
    """
    dt = prm[P_DT]
    h = dt / nsub
    gx = prm[P_GX]
    gy = prm[P_GY]
    alpha = prm[P_ALPHA]
    kn = prm[P_KN]
    ks = prm[P_KS]
    mu = prm[P_MU]
    mur = prm[P_MUR]
    knw = prm[P_KN_W]
    ksw = prm[P_KS_W]
    muw = prm[P_MU_W]
    murw = prm[P_MUR_W]
    knp = prm[P_KN_P]
    ksp = prm[P_KS_P]
    mup = prm[P_MU_P]
    murp = prm[P_MUR_P]
    x0 = prm[P_X0]
    x1 = prm[P_X1]
    y0 = prm[P_Y0]
    lid_on = prm[P_LID_ON] > 0.5
    lid_y = prm[P_LID_Y]
    lid_v = prm[P_LID_V]
    lid_stop = prm[P_LID_STOP]
    pipe_on = prm[P_PIPE_ON] > 0.5
    px = prm[P_PIPE_X]
    py = prm[P_PIPE_Y]
    pr = prm[P_PIPE_R]
    pv = prm[P_PIPE_V]
    diag = prm[P_DIAG] > 0.5
    gmag = np.sqrt(gx * gx + gy * gy)
    # dacc per flagged disk: 0-2 force/torque of the sub-step, 3 applied magnitude,
    # 4-5 pipe force sum, 6-7 unbalanced force sum, 8 applied magnitude sum
    for ll in range(nf):
        for c in range(4, 9):
            dacc[ll, c] = 0.0
    for q in range(nsub):
        for ll in range(nf):
            for c in range(4):
                dacc[ll, c] = 0.0
        tq_ = q * h
        for p in range(npair):
            k = plist[p]
            i = owner[k]
            j = nbr[k]
            li = floc[i]
            lj = floc[j]
            if li >= 0:
                vxi = vel[i, 0]
                vyi = vel[i, 1]
                wi = om[i]
                xi = pos[i, 0]
                yi = pos[i, 1]
            else:
                vxi = cpv[-2 - li, 0]
                vyi = cpv[-2 - li, 1]
                wi = cpv[-2 - li, 2]
                xi = cpv[-2 - li, 3] + tq_ * vxi
                yi = cpv[-2 - li, 4] + tq_ * vyi
            if lj >= 0:
                vxj = vel[j, 0]
                vyj = vel[j, 1]
                wj = om[j]
                xj = pos[j, 0]
                yj = pos[j, 1]
            else:
                vxj = cpv[-2 - lj, 0]
                vyj = cpv[-2 - lj, 1]
                wj = cpv[-2 - lj, 2]
                xj = cpv[-2 - lj, 3] + tq_ * vxj
                yj = cpv[-2 - lj, 4] + tq_ * vyj
            ri = rad[i]
            rj = rad[j]
            rsum = ri + rj
            dx = xj - xi
            dy = yj - yi
            d2 = dx * dx + dy * dy
            if d2 >= rsum * rsum:
                hfs[p] = 0.0
                hmr[p] = 0.0
                continue
            d = np.sqrt(d2)
            nx = dx / d
            ny = dy / d
            tx = -ny
            ty = nx
            vt = (vxj - vxi) * tx + (vyj - vyi) * ty
            vt -= wj * rj + wi * ri
            rbar = ri * rj / rsum
            fn, f, m = contact_update(
                nx, ny, rsum - d, vt, wj - wi, rbar, kn, ks, mu, mur, hfs[p], hmr[p], h
            )
            hfs[p] = f
            hmr[p] = m
            cx = -fn * nx + f * tx
            cy = -fn * ny + f * ty
            mag = np.sqrt(fn * fn + f * f)
            if li >= 0:
                dacc[li, 0] += cx
                dacc[li, 1] += cy
                dacc[li, 2] += ri * f + m
                dacc[li, 3] += mag
            if lj >= 0:
                dacc[lj, 0] -= cx
                dacc[lj, 1] -= cy
                dacc[lj, 2] += rj * f - m
                dacc[lj, 3] += mag
        ly = lid_y + lid_v * tq_
        if lid_v < 0.0 and ly < lid_stop:
            ly = lid_stop
        pyq = py + pv * tq_
        for ll in range(nf):
            i = flist[ll]
            ri = rad[i]
            xi = pos[i, 0]
            yi = pos[i, 1]
            vx = vel[i, 0]
            vy = vel[i, 1]
            w = om[i]
            fx = dacc[ll, 0]
            fy = dacc[ll, 1]
            tq = dacc[ll, 2]
            a = dacc[ll, 3]
            fx, fy, tq, a = _add_walls_lid(
                i, vx, vy, w, ri, xi, yi, x0, x1, y0, lid_on, ly, lid_v, fsw, mrw, knw, ksw, muw,
                murw, h, (fx, fy, tq, a), True,
            )  # fmt: skip
            if pipe_on:
                dx = px - xi
                dy = pyq - yi
                d = np.sqrt(dx * dx + dy * dy)
                if d > 0.0 and d < ri + pr:
                    cx, cy, ct_, fsn, mrn = _stiff_contact(
                        vx, vy, w, ri, dx / d, dy / d, ri + pr - d, 0.0, pv, fsw[i, PIPE],
                        mrw[i, PIPE], knp, ksp, mup, murp, h,
                    )  # fmt: skip
                    fsw[i, PIPE] = fsn
                    mrw[i, PIPE] = mrn
                    fx += cx
                    fy += cy
                    tq += ct_
                    a += np.sqrt(cx * cx + cy * cy)
                    dacc[ll, 4] += cx
                    dacc[ll, 5] += cy
                else:
                    fsw[i, PIPE] = 0.0
                    mrw[i, PIPE] = 0.0
            m = mass[i, 0]
            mg = mass[i, 1]
            fx += mg * gx
            fy += mg * gy
            dacc[ll, 6] += fx
            dacc[ll, 7] += fy
            dacc[ll, 8] += a + mg * gmag
            if alpha > 0.0:
                fx -= alpha * abs(fx) * _sign(vx)
                fy -= alpha * abs(fy) * _sign(vy)
                tq -= alpha * abs(tq) * _sign(w)
            vx += h * fx / m
            vy += h * fy / m
            w += h * tq / inert[i]
            vel[i, 0] = vx
            vel[i, 1] = vy
            om[i] = w
            pos[i, 0] = xi + h * vx
            pos[i, 1] = yi + h * vy
            th[i] += h * w
    inv = 1.0 / nsub
    for c in range(ncp):  # back to "plain, not a partner" for the next step
        floc[cplist[c]] = -1
    dmax = 0.0
    for ll in range(nf):
        i = flist[ll]
        pfx[i] = dacc[ll, 4] * inv
        pfy[i] = dacc[ll, 5] * inv
        if diag:
            ux = dacc[ll, 6] * inv
            uy = dacc[ll, 7] * inv
            unb[i] = np.sqrt(ux * ux + uy * uy)
            app[i] = dacc[ll, 8] * inv
        ex = pos[i, 0] - ref[i, 0]
        ey = pos[i, 1] - ref[i, 1]
        dmax = max(dmax, ex * ex + ey * ey)
        floc[i] = -1
    return dmax


@njit(cache=True, parallel=True, boundscheck=False, error_model="numpy")
def gather_integrate(
    prm,
    pos,
    vel,
    om,
    th,
    rad,
    mass,
    inert,
    rstart,
    ridx,
    cfx,
    cfy,
    cmag,
    fs,
    mr,
    sfx,
    sfy,
    stq,
    sa,
    fsw,
    mrw,
    pfx,
    pfy,
    unb,
    app,
    fixed,
    ref,
    dmax,
    zonal,
    fine,
    fire,
    bsum,
    stiff,
):
    """Sum contact, wall, pipe and body forces per disk; local damping; leapfrog update.

    ``zonal``: the flagged disks (``fine[i]``) are moved by :func:`fine_substeps`, which
    returns their displacement for the list rebuild, and are skipped.
    ``fire[F_ON]`` > 0.5: FIRE mixing instead of local damping, with the coefficients in
    ``fire``; per-block FIRE sums go to ``bsum[b, :]`` (never with ``zonal``).
    """
    n = rad.shape[0]
    dt = prm[P_DT]
    gx = prm[P_GX]
    gy = prm[P_GY]
    alpha = prm[P_ALPHA]
    knw = prm[P_KN_W]
    ksw = prm[P_KS_W]
    muw = prm[P_MU_W]
    murw = prm[P_MUR_W]
    knp = prm[P_KN_P]
    ksp = prm[P_KS_P]
    mup = prm[P_MU_P]
    murp = prm[P_MUR_P]
    x0 = prm[P_X0]
    x1 = prm[P_X1]
    y0 = prm[P_Y0]
    lid_on = prm[P_LID_ON] > 0.5
    lid_y = prm[P_LID_Y]
    lid_v = prm[P_LID_V]
    pipe_on = prm[P_PIPE_ON] > 0.5
    px = prm[P_PIPE_X]
    py = prm[P_PIPE_Y]
    pr = prm[P_PIPE_R]
    pv = prm[P_PIPE_V]
    diag = prm[P_DIAG] > 0.5
    fire_mix = fire[F_ON] > 0.5
    fa = fire[F_ALPHA]
    ctr = fire[F_CTR]
    crot = fire[F_CROT]
    restart = fire[F_RESTART] > 0.5
    frictionless = prm[P_MU] == 0.0 and prm[P_MUR] == 0.0  # soil–soil: no torques
    nblock = (n + BLOCK - 1) // BLOCK
    for b in prange(nblock):
        i0 = b * BLOCK
        i1 = min(n, (b + 1) * BLOCK)
        if fire_mix:
            dmax[b] = _gather_integrate_block_fire(
                i0, i1, dt, gx, gy, knw, ksw, muw, murw, knp, ksp, mup, murp, x0, x1,
                y0, lid_on, lid_y, lid_v, pipe_on, px, py, pr, pv, diag, pos, vel, om, th, rad,
                mass, inert, rstart, ridx, cfx, cfy, cmag, fs, mr, sfx, sfy, stq, sa, fsw, mrw,
                pfx, pfy, unb, app, fixed, ref, fa, ctr, crot, restart, bsum, b, stiff,
                frictionless,
            )  # fmt: skip
        else:
            dmax[b] = _gather_integrate_block(
                i0, i1, dt, gx, gy, alpha, knw, ksw, muw, murw, knp, ksp, mup, murp, x0, x1,
                y0, lid_on, lid_y, lid_v, pipe_on, px, py, pr, pv, diag, pos, vel, om, th, rad,
                mass, inert, rstart, ridx, cfx, cfy, cmag, fs, mr, sfx, sfy, stq, sa, fsw, mrw,
                pfx, pfy, unb, app, fixed, ref, zonal, fine, stiff, frictionless,
            )  # fmt: skip


@njit(cache=True, parallel=True, boundscheck=False, error_model="numpy")
def gather_integrate_zonal(
    prm, pos, vel, om, th, rad, mass, inert, rstart, ridx, cfx, cfy, cmag, fs, mr, sfx, sfy,
    stq, sa, fsw, mrw, pfx, pfy, unb, app, fixed, ref, dmax, fine, stiff, nsub, flist, nf,
    floc, plist, npair, owner, nbr, hfs, hmr, dacc, cplist, ncp, cpv, dfine, nw,
):  # fmt: skip
    """:func:`gather_integrate` (zonal, damped) with :func:`fine_substeps` run beside it.

    The serial sub-step pass touches only the flagged disks, which the plain pass skips, and
    reads the plain partners from :func:`fine_partners`' copy, so the two passes share no memory
    that either writes: of the ``nw`` workers (one per thread), worker 0 takes the sub-step pass
    (its displacement maximum into ``dfine[0]``) and the first blocks, the other workers the
    remaining blocks in equal shares, sized from :data:`FINE_ITEM_COST` so that the workers end
    together. Which worker moves a disk never changes what it computes: the bits do not depend
    on the split or on the number of threads.
    """
    n = rad.shape[0]
    dt = prm[P_DT]
    gx = prm[P_GX]
    gy = prm[P_GY]
    alpha = prm[P_ALPHA]
    knw = prm[P_KN_W]
    ksw = prm[P_KS_W]
    muw = prm[P_MU_W]
    murw = prm[P_MUR_W]
    knp = prm[P_KN_P]
    ksp = prm[P_KS_P]
    mup = prm[P_MU_P]
    murp = prm[P_MUR_P]
    x0 = prm[P_X0]
    x1 = prm[P_X1]
    y0 = prm[P_Y0]
    lid_on = prm[P_LID_ON] > 0.5
    lid_y = prm[P_LID_Y]
    lid_v = prm[P_LID_V]
    pipe_on = prm[P_PIPE_ON] > 0.5
    px = prm[P_PIPE_X]
    py = prm[P_PIPE_Y]
    pr = prm[P_PIPE_R]
    pv = prm[P_PIPE_V]
    diag = prm[P_DIAG] > 0.5
    frictionless = prm[P_MU] == 0.0 and prm[P_MUR] == 0.0
    nblock = (n + BLOCK - 1) // BLOCK
    fine_blocks = FINE_ITEM_COST * nsub * (npair + nf) / BLOCK  # the sub-step pass, in blocks
    first = int(min(float(nblock), max(0.0, (nblock + fine_blocks) / nw - fine_blocks)) + 0.5)
    for t in prange(nw):
        if t == 0:
            dfine[0] = fine_substeps(
                prm, nsub, pos, vel, om, th, rad, mass, inert, ref, flist, nf, floc, plist,
                npair, owner, nbr, fsw, mrw, pfx, pfy, unb, app, hfs, hmr, dacc, cplist, ncp,
                cpv,
            )  # fmt: skip
            b0 = 0
            b1 = first
        else:
            b0 = first + (t - 1) * (nblock - first) // (nw - 1)
            b1 = first + t * (nblock - first) // (nw - 1)
        for b in range(b0, b1):
            i0 = b * BLOCK
            i1 = min(n, (b + 1) * BLOCK)
            dmax[b] = _gather_integrate_block(
                i0, i1, dt, gx, gy, alpha, knw, ksw, muw, murw, knp, ksp, mup, murp, x0, x1,
                y0, lid_on, lid_y, lid_v, pipe_on, px, py, pr, pv, diag, pos, vel, om, th, rad,
                mass, inert, rstart, ridx, cfx, cfy, cmag, fs, mr, sfx, sfy, stq, sa, fsw, mrw,
                pfx, pfy, unb, app, fixed, ref, True, fine, stiff, frictionless,
            )  # fmt: skip


@njit(cache=True, boundscheck=False, error_model="numpy")
def _gather_integrate_block(
    i0, i1, dt, gx, gy, alpha, knw, ksw, muw, murw, knp, ksp, mup, murp, x0, x1, y0, lid_on,
    lid_y, lid_v, pipe_on, px, py, pr, pv, diag, pos, vel, om, th, rad, mass, inert, rstart,
    ridx, cfx, cfy, cmag, fs, mr, sfx, sfy, stq, sa, fsw, mrw, pfx, pfy, unb, app, fixed, ref,
    zonal, fine, stiff, frictionless,
):  # fmt: skip
    """Disks i0..i1−1 of :func:`gather_integrate`; returns their largest squared displacement
    since the last list build (new positions vs ``ref``)."""
    dmax = 0.0
    for ii in range(i0, i1):
        i = np.uint64(ii)  # unsigned: no negative-index wrap-around code
        if zonal and fine[i]:  # moved (and its displacement taken) by fine_substeps
            stiff[i] = 1  # its wall and pipe histories are fine_substeps' business
            continue
        ri = rad[i]
        fx = sfx[i]
        fy = sfy[i]
        tq = stq[i]
        for q in range(rstart[ii], rstart[ii + 1]):
            k = ridx[np.uint64(q)]
            fx -= cfx[k]
            fy -= cfy[k]
            if not frictionless:  # else ±0 terms: tq keeps its value (+0.0)
                tq += ri * fs[k] - mr[k]
        a = 0.0
        if diag:
            a = sa[i]
            for q in range(rstart[ii], rstart[ii + 1]):
                a += cmag[ridx[q]]
        xi = pos[i, 0]
        yi = pos[i, 1]
        # walls: left, right, bottom, lid
        vx = vel[i, 0]
        vy = vel[i, 1]
        w = om[i]
        # stiff[i] = 0: the disk's wall, lid and pipe histories are zero, and for a disk
        # clear of them their contact laws add zeros and write zeros (skipped: same bits)
        near = (xi - x0 < ri) | (x1 - xi < ri) | (yi - y0 < ri) | (lid_on & (lid_y - yi < ri))
        if near or stiff[i]:
            fx, fy, tq, a = _add_walls_lid(
                i, vx, vy, w, ri, xi, yi, x0, x1, y0, lid_on, lid_y, lid_v, fsw, mrw, knw, ksw,
                muw, murw, dt, (fx, fy, tq, a), diag,
            )  # fmt: skip
        if stiff[i]:  # else already zero
            pfx[i] = 0.0
            pfy[i] = 0.0
        if pipe_on:
            dx = px - xi
            dy = py - yi
            d = np.sqrt(dx * dx + dy * dy)
            if d > 0.0 and d < ri + pr:
                wx, wy, wt = wall_contact(
                    i, PIPE, dx / d, dy / d, ri + pr - d, 0.0, pv, pos, vel, om, rad, fsw,
                    mrw, knp, ksp, mup, murp, dt,
                )  # fmt: skip
                fx += wx
                fy += wy
                tq += wt
                if diag:
                    a += np.sqrt(wx * wx + wy * wy)
                pfx[i] = wx
                pfy[i] = wy
                near = True
            elif stiff[i]:
                fsw[i, PIPE] = 0.0
                mrw[i, PIPE] = 0.0
        stiff[i] = near
        m = mass[i, 0]
        mg = mass[i, 1]
        fx += mg * gx
        fy += mg * gy
        if diag:
            a += mg * np.sqrt(gx * gx + gy * gy)
            unb[i] = np.sqrt(fx * fx + fy * fy)
            app[i] = a
        if fixed[i]:
            vel[i, 0] = 0.0
            vel[i, 1] = 0.0
            om[i] = 0.0
            ex = xi - ref[i, 0]
            ey = yi - ref[i, 1]
            dmax = max(dmax, ex * ex + ey * ey)
            continue
        # local (non-viscous) damping, PFC: -alpha |F| sign(v) per component
        vx = vel[i, 0]
        vy = vel[i, 1]
        w = om[i]
        if alpha > 0.0:
            # branch-free (the signs of the velocities of a settled bed are random, so
            # branches mispredict); bitwise equal to "v > 0: F −= α|F|; v < 0: F += α|F|"
            fx -= alpha * abs(fx) * _sign(vx)
            fy -= alpha * abs(fy) * _sign(vy)
            tq -= alpha * abs(tq) * _sign(w)
        vx += dt * fx / m
        vy += dt * fy / m
        w += dt * tq / inert[i]
        vel[i, 0] = vx
        vel[i, 1] = vy
        om[i] = w
        xi = xi + dt * vx
        yi = yi + dt * vy
        pos[i, 0] = xi
        pos[i, 1] = yi
        th[i] += dt * w
        ex = xi - ref[i, 0]
        ey = yi - ref[i, 1]
        dmax = max(dmax, ex * ex + ey * ey)
    return dmax


@njit(cache=True, boundscheck=False, error_model="numpy")
def _gather_integrate_block_fire(
    i0, i1, dt, gx, gy, knw, ksw, muw, murw, knp, ksp, mup, murp, x0, x1, y0, lid_on, lid_y,
    lid_v, pipe_on, px, py, pr, pv, diag, pos, vel, om, th, rad, mass, inert, rstart, ridx, cfx,
    cfy, cmag, fs, mr, sfx, sfy, stq, sa, fsw, mrw, pfx, pfy, unb, app, fixed, ref, fa, ctr,
    crot, restart, bsum, b, stiff, frictionless,
):  # fmt: skip
    """:func:`_gather_integrate_block` with FIRE mixing instead of local damping: the
    velocities are mixed (FIRE), and the block's FIRE sums are stored in ``bsum[b]``."""
    dmax = 0.0
    sp = 0.0
    sv2 = 0.0
    sf2 = 0.0
    sw2 = 0.0
    st2 = 0.0
    for ii in range(i0, i1):
        i = np.uint64(ii)
        ri = rad[i]
        fx = sfx[i]
        fy = sfy[i]
        tq = stq[i]
        for q in range(rstart[ii], rstart[ii + 1]):
            k = ridx[np.uint64(q)]
            fx -= cfx[k]
            fy -= cfy[k]
            if not frictionless:  # else ±0 terms: tq keeps its value (+0.0)
                tq += ri * fs[k] - mr[k]
        a = 0.0
        if diag:
            a = sa[i]
            for q in range(rstart[ii], rstart[ii + 1]):
                a += cmag[ridx[q]]
        xi = pos[i, 0]
        yi = pos[i, 1]
        vx = vel[i, 0]
        vy = vel[i, 1]
        w = om[i]
        # stiff[i] = 0: the disk's wall, lid and pipe histories are zero, and for a disk
        # clear of them their contact laws add zeros and write zeros (skipped: same bits)
        near = (xi - x0 < ri) | (x1 - xi < ri) | (yi - y0 < ri) | (lid_on & (lid_y - yi < ri))
        if near or stiff[i]:
            fx, fy, tq, a = _add_walls_lid(
                i, vx, vy, w, ri, xi, yi, x0, x1, y0, lid_on, lid_y, lid_v, fsw, mrw, knw, ksw,
                muw, murw, dt, (fx, fy, tq, a), diag,
            )  # fmt: skip
        if stiff[i]:  # else already zero
            pfx[i] = 0.0
            pfy[i] = 0.0
        if pipe_on:
            dx = px - xi
            dy = py - yi
            d = np.sqrt(dx * dx + dy * dy)
            if d > 0.0 and d < ri + pr:
                wx, wy, wt = wall_contact(
                    i, PIPE, dx / d, dy / d, ri + pr - d, 0.0, pv, pos, vel, om, rad, fsw,
                    mrw, knp, ksp, mup, murp, dt,
                )  # fmt: skip
                fx += wx
                fy += wy
                tq += wt
                if diag:
                    a += np.sqrt(wx * wx + wy * wy)
                pfx[i] = wx
                pfy[i] = wy
                near = True
            elif stiff[i]:
                fsw[i, PIPE] = 0.0
                mrw[i, PIPE] = 0.0
        stiff[i] = near
        m = mass[i, 0]
        mg = mass[i, 1]
        fx += mg * gx
        fy += mg * gy
        if diag:
            a += mg * np.sqrt(gx * gx + gy * gy)
            unb[i] = np.sqrt(fx * fx + fy * fy)
            app[i] = a
        if fixed[i]:
            vel[i, 0] = 0.0
            vel[i, 1] = 0.0
            om[i] = 0.0
            ex = xi - ref[i, 0]
            ey = yi - ref[i, 1]
            dmax = max(dmax, ex * ex + ey * ey)
            continue
        vx = vel[i, 0]
        vy = vel[i, 1]
        w = om[i]
        sp += fx * vx + fy * vy + tq * w
        sv2 += vx * vx + vy * vy
        sf2 += fx * fx + fy * fy
        sw2 += w * w
        st2 += tq * tq
        if restart:
            vx = 0.0
            vy = 0.0
            w = 0.0
        else:
            vx = (1.0 - fa) * vx + ctr * fx
            vy = (1.0 - fa) * vy + ctr * fy
            w = (1.0 - fa) * w + crot * tq
        vx += dt * fx / m
        vy += dt * fy / m
        w += dt * tq / inert[i]
        vel[i, 0] = vx
        vel[i, 1] = vy
        om[i] = w
        xi = xi + dt * vx
        yi = yi + dt * vy
        pos[i, 0] = xi
        pos[i, 1] = yi
        th[i] += dt * w
        ex = xi - ref[i, 0]
        ey = yi - ref[i, 1]
        dmax = max(dmax, ex * ex + ey * ey)
    bsum[b, 0] = sp
    bsum[b, 1] = sv2
    bsum[b, 2] = sf2
    bsum[b, 3] = sw2
    bsum[b, 4] = st2
    return dmax


@njit(cache=True)
def max_displacement2(pos, ref):
    """Largest squared displacement since the last list build [m²] (serial, deterministic)."""
    n = pos.shape[0]
    m = 0.0
    for i in range(n):
        dx = pos[i, 0] - ref[i, 0]
        dy = pos[i, 1] - ref[i, 1]
        d2 = dx * dx + dy * dy
        if d2 > m:
            m = d2
    return m


@njit(cache=True)
def _insertion_sort(a, lo, hi):
    for p in range(lo + 1, hi):
        v = a[p]
        q = p - 1
        while q >= lo and a[q] > v:
            a[q + 1] = a[q]
            q -= 1
        a[q + 1] = v


@njit(cache=True, parallel=True)
def build_list(pos, rad, skin, old_start, old_nbr, old_fs, old_mr):
    """Cell-list half neighbour list with cut-off ``r_i + r_j + skin``; history carried over.

    Returns (start, nbr, fs, mr, rstart, ridx). The history of a pair (i, j) present in both
    the old and the new list is copied (sorted two-pointer merge per disk).
    """
    n = rad.shape[0]
    rmax = 0.0
    xmin = np.inf
    xmax = -np.inf
    ymin = np.inf
    ymax = -np.inf
    for i in range(n):
        if rad[i] > rmax:
            rmax = rad[i]
        x = pos[i, 0]
        y = pos[i, 1]
        xmin = min(xmin, x)
        xmax = max(xmax, x)
        ymin = min(ymin, y)
        ymax = max(ymax, y)
    cs = 2.0 * rmax + skin
    ncx = max(1, int((xmax - xmin) / cs) + 1)
    ncy = max(1, int((ymax - ymin) / cs) + 1)
    ncell = ncx * ncy
    cell_of = np.empty(n, np.int64)
    ccount = np.zeros(ncell + 1, np.int64)
    for i in range(n):
        cx = min(ncx - 1, max(0, int((pos[i, 0] - xmin) / cs)))
        cy = min(ncy - 1, max(0, int((pos[i, 1] - ymin) / cs)))
        c = cy * ncx + cx
        cell_of[i] = c
        ccount[c + 1] += 1
    for c in range(ncell):
        ccount[c + 1] += ccount[c]
    cfill = ccount[:-1].copy()
    cpart = np.empty(n, np.int64)
    for i in range(n):
        c = cell_of[i]
        cpart[cfill[c]] = i
        cfill[c] += 1
    cnt = np.zeros(n + 1, np.int64)
    for i in prange(n):
        c = cell_of[i]
        cx = c % ncx
        cy = c // ncx
        xi = pos[i, 0]
        yi = pos[i, 1]
        ri = rad[i]
        m = 0
        for oy in range(max(0, cy - 1), min(ncy, cy + 2)):
            for ox in range(max(0, cx - 1), min(ncx, cx + 2)):
                cc = oy * ncx + ox
                for q in range(ccount[cc], ccount[cc + 1]):
                    j = cpart[q]
                    if j <= i:
                        continue
                    dx = pos[j, 0] - xi
                    dy = pos[j, 1] - yi
                    cut = ri + rad[j] + skin
                    if dx * dx + dy * dy < cut * cut:
                        m += 1
        cnt[i + 1] = m
    for i in range(n):
        cnt[i + 1] += cnt[i]
    start = cnt
    m_tot = start[n]
    nbr = np.empty(m_tot, np.uint32)
    fs = np.zeros(m_tot)
    mr = np.zeros(m_tot)
    for i in prange(n):
        c = cell_of[i]
        cx = c % ncx
        cy = c // ncx
        xi = pos[i, 0]
        yi = pos[i, 1]
        ri = rad[i]
        p = start[i]
        for oy in range(max(0, cy - 1), min(ncy, cy + 2)):
            for ox in range(max(0, cx - 1), min(ncx, cx + 2)):
                cc = oy * ncx + ox
                for q in range(ccount[cc], ccount[cc + 1]):
                    j = cpart[q]
                    if j <= i:
                        continue
                    dx = pos[j, 0] - xi
                    dy = pos[j, 1] - yi
                    cut = ri + rad[j] + skin
                    if dx * dx + dy * dy < cut * cut:
                        nbr[p] = j
                        p += 1
        _insertion_sort(nbr, start[i], start[i + 1])
        # merge the history of the old list (both sorted by j)
        a = old_start[i]
        a_end = old_start[i + 1]
        for k in range(start[i], start[i + 1]):
            j = nbr[k]
            while a < a_end and old_nbr[a] < j:
                a += 1
            if a < a_end and old_nbr[a] == j:
                fs[k] = old_fs[a]
                mr[k] = old_mr[a]
    rstart = np.zeros(n + 1, np.int64)
    for k in range(m_tot):
        rstart[nbr[k] + 1] += 1
    for i in range(n):
        rstart[i + 1] += rstart[i]
    rfill = rstart[:-1].copy()
    ridx = np.empty(m_tot, np.uint32)
    for k in range(m_tot):
        j = nbr[k]
        ridx[rfill[j]] = k
        rfill[j] += 1
    return start, nbr, fs, mr, rstart, ridx


@njit(cache=True)
def run_steps(
    nsteps,
    prm,
    pos,
    vel,
    om,
    th,
    rad,
    mass,
    inert,
    fixed,
    ref,
    start,
    nbr,
    fs,
    mr,
    rstart,
    ridx,
    fsw,
    mrw,
    pfx,
    pfy,
    unb,
    app,
    nsub,
    fire,
    nthreads,
):
    """Advance ``nsteps`` steps; rebuild the list when a disk moved more than skin/2.

    Moves the pipe and the lid (``prm`` is updated in place, as is the time ``prm[P_TIME]``).
    ``nsub`` > 1: zonal sub-cycling, the disks within half a skin of a wall, the lid or the
    pipe take ``nsub`` sub-steps per step (:func:`fine_candidates`, :func:`collect_fine`,
    :func:`fine_substeps`).
    ``fire``: FIRE state (``F_*`` indices), updated in place after every step when on.
    ``nthreads``: numba's thread count for the call (the workers of the zonal pass).
    ``mass`` (n, 2): each disk's inertial mass (column 0: divides the force) and its
    gravitational mass (column 1: its weight is ``mass[:, 1]·g``); equal columns but for
    inertial mass scaling (``Simulation(inertial_mass_floor=…)``).
    Returns the (possibly new) list arrays and the number of rebuilds.
    """
    skin = prm[P_SKIN]
    half2 = 0.25 * skin * skin
    nreb = 0
    n = rad.shape[0]
    m = nbr.shape[0]
    cfx = np.empty(m)
    cfy = np.empty(m)
    cmag = np.empty(m)
    sfx = np.empty(n)
    sfy = np.empty(n)
    stq = np.empty(n)
    sa = np.empty(n)
    dmax = np.empty((n + BLOCK - 1) // BLOCK)
    bsum = np.zeros(((n + BLOCK - 1) // BLOCK, N_BSUM))
    dt = prm[P_DT]
    owner = list_owner(start, m)
    disp2 = max_displacement2(pos, ref)
    zonal = nsub > 1
    nz = n if zonal else 0
    mz = m if zonal else 0
    fine = np.zeros(n, np.uint8)
    stiff = np.ones(n, np.uint8)  # 0: the disk's wall, lid and pipe histories are zero
    flist = np.empty(nz, np.int64)
    floc = np.full(nz, -1, np.int64)
    cand = np.empty(nz, np.int64)
    ncand = 0
    cand_stale = True
    cand_pipe_y = 0.0
    cand_lid_y = 0.0
    dacc = np.empty((nz, 9))
    cplist = np.empty(nz, np.int64)
    cpv = np.empty((nz, 5))
    dfine = np.zeros(1)
    plist = np.empty(mz, np.int64)
    hfs = np.empty(mz)
    hmr = np.empty(mz)
    for s in range(nsteps):
        # diagnostics (unbalanced-force ratio) only on the last step of the call
        prm[P_DIAG] = 1.0 if s == nsteps - 1 else 0.0
        if disp2 > half2:
            start, nbr, fs, mr, rstart, ridx = build_list(pos, rad, skin, start, nbr, fs, mr)
            ref[:, :] = pos
            nreb += 1
            cand_stale = True
            m = nbr.shape[0]
            owner = list_owner(start, m)
            cfx = np.empty(m)
            cfy = np.empty(m)
            cmag = np.empty(m)
            if zonal:
                plist = np.empty(m, np.int64)
                hfs = np.empty(m)
                hmr = np.empty(m)
        nf = 0
        npair = 0
        if zonal:
            moved = max(abs(prm[P_PIPE_Y] - cand_pipe_y), abs(prm[P_LID_Y] - cand_lid_y))
            if cand_stale or moved > 0.5 * skin:
                for c in range(ncand):
                    fine[cand[c]] = 0
                ncand = fine_candidates(prm, pos, rad, fixed, 2.0 * skin, cand)
                cand_pipe_y = prm[P_PIPE_Y]
                cand_lid_y = prm[P_LID_Y]
                cand_stale = False
            nf, npair = collect_fine(
                prm, pos, rad, cand, ncand, fine, start, rstart, ridx, owner, flist, floc, plist,
                fs, mr, hfs, hmr,
            )  # fmt: skip
        pair_forces(
            prm, pos, vel, om, rad, start, owner, nbr, fs, mr, cfx, cfy, cmag, sfx, sfy, stq, sa
        )  # fmt: skip
        dfine[0] = 0.0
        if zonal:
            ncp = fine_partners(
                prm, pos, vel, om, rad, mass, inert, fixed, plist, npair, owner, nbr, rstart,
                ridx, fs, mr, cfx, cfy, sfx, sfy, stq, floc, cplist, cpv,
            )  # fmt: skip
            gather_integrate_zonal(
                prm, pos, vel, om, th, rad, mass, inert, rstart, ridx, cfx, cfy, cmag, fs, mr,
                sfx, sfy, stq, sa, fsw, mrw, pfx, pfy, unb, app, fixed, ref, dmax, fine, stiff,
                nsub, flist, nf, floc, plist, npair, owner, nbr, hfs, hmr, dacc, cplist, ncp,
                cpv, dfine, nthreads,
            )  # fmt: skip
        else:
            gather_integrate(
                prm, pos, vel, om, th, rad, mass, inert, rstart, ridx, cfx, cfy, cmag, fs, mr,
                sfx, sfy, stq, sa, fsw, mrw, pfx, pfy, unb, app, fixed, ref, dmax, False, fine,
                fire, bsum, stiff,
            )  # fmt: skip
        if zonal:
            for p in range(npair):  # the pair histories advanced by the sub-steps
                fs[plist[p]] = hfs[p]
                mr[plist[p]] = hmr[p]
        if fire[F_ON] > 0.5:
            fire_update(fire, bsum)
        disp2 = dfine[0]
        for b in range(dmax.shape[0]):
            if dmax[b] > disp2:
                disp2 = dmax[b]
        prm[P_TIME] += dt
        if prm[P_PIPE_ON] > 0.5:
            prm[P_PIPE_Y] += prm[P_PIPE_V] * dt
        if prm[P_LID_ON] > 0.5:
            y = prm[P_LID_Y] + prm[P_LID_V] * dt
            if prm[P_LID_V] < 0.0 and y <= prm[P_LID_STOP]:
                y = prm[P_LID_STOP]
                prm[P_LID_V] = 0.0
            prm[P_LID_Y] = y
    return start, nbr, fs, mr, rstart, ridx, nreb


@njit(cache=True)
def fire_update(fire, bsum):
    """FIRE decision for the next step from this step's block sums (Bitzek et al. 2006).

    Power P = Σ F·v + T·ω > 0: the mixing continues (α ← α·f_α once more than N_min steps
    have passed since the last restart); P ≤ 0: restart (velocities zeroed next step,
    α ← α_0). The time step stays fixed (its growth would pass the contact stability limit).
    """
    p = 0.0
    v2 = 0.0
    f2 = 0.0
    w2 = 0.0
    t2 = 0.0
    for b in range(bsum.shape[0]):
        p += bsum[b, 0]
        v2 += bsum[b, 1]
        f2 += bsum[b, 2]
        w2 += bsum[b, 3]
        t2 += bsum[b, 4]
    if p > 0.0:
        fire[F_RESTART] = 0.0
        fire[F_NPOS] += 1.0
        if fire[F_NPOS] > fire[F_NMIN]:
            fire[F_ALPHA] *= fire[F_FALPHA]
    else:
        fire[F_RESTART] = 1.0
        fire[F_NPOS] = 0.0
        fire[F_ALPHA] = fire[F_ALPHA0]
        fire[F_RESTARTS] += 1.0
    a = fire[F_ALPHA]
    fire[F_CTR] = a * np.sqrt(v2 / f2) if f2 > 0.0 else 0.0
    fire[F_CROT] = a * np.sqrt(w2 / t2) if t2 > 0.0 else 0.0


@njit(cache=True)
def pipe_force(pfx, pfy):
    """Force of the soil on the pipe (serial sum in disk order) [N per m]: (F_x, F_y)."""
    sx = 0.0
    sy = 0.0
    for i in range(pfx.shape[0]):
        sx -= pfx[i]
        sy -= pfy[i]
    return sx, sy


@njit(cache=True)
def ratio_sums(unb, app):
    """(Σ unbalanced-force magnitudes, Σ applied-force magnitudes), serial."""
    su = 0.0
    sa = 0.0
    for i in range(unb.shape[0]):
        su += unb[i]
        sa += app[i]
    return su, sa
