"""Plain-Python twin of the engine step (private; tests only, O(n²) pairs).

Same physics as :mod:`onbottom.dem._kernels` written straightforwardly: all pairs checked,
contact history in a dict keyed by (i, j), walls and pipe as bodies with per-particle history.
"""

from __future__ import annotations

import math

import numpy as np

from onbottom.dem import _kernels as K


def _law(overlap, vt, dw, rbar, kn, ks, mu, mur, fs, mr, dt):
    if overlap <= 0.0:
        return 0.0, 0.0, 0.0
    fn = kn * overlap
    fs = max(-mu * fn, min(mu * fn, fs + ks * vt * dt))
    if mur > 0.0:
        mr = max(-mur * rbar * fn, min(mur * rbar * fn, mr + ks * rbar * rbar * dw * dt))
    else:
        mr = 0.0
    return fn, fs, mr


class ReferenceSystem:
    """Disks + walls + pipe advanced by the plain-Python leapfrog step."""

    def __init__(self, prm, pos, vel, om, rad, mass, inert, inertial_mass=None):
        self.prm = np.array(prm, float)
        self.pos = np.array(pos, float)
        self.vel = np.array(vel, float)
        self.om = np.array(om, float)
        self.th = np.zeros(len(rad))
        self.rad = np.array(rad, float)
        self.mass = np.array(mass, float)  # weight m·g
        self.inertial_mass = np.array(mass if inertial_mass is None else inertial_mass, float)
        self.inert = np.array(inert, float)
        self.pairs: dict[tuple[int, int], list[float]] = {}
        self.walls: dict[tuple[int, int], list[float]] = {}
        self.pipe_force = (0.0, 0.0)

    def _wall(self, i, w, nx, ny, overlap, vbx, vby, kn, ks, mu, mur, dt):
        fs, mr = self.walls.get((i, w), [0.0, 0.0])
        ri = self.rad[i]
        tx, ty = -ny, nx
        vt = (vbx - self.vel[i, 0]) * tx + (vby - self.vel[i, 1]) * ty - self.om[i] * ri
        fn, fs, mr = _law(overlap, vt, -self.om[i], ri, kn, ks, mu, mur, fs, mr, dt)
        self.walls[(i, w)] = [fs, mr]
        return -fn * nx + fs * tx, -fn * ny + fs * ty, ri * fs + mr

    def step(self):
        p = self.prm
        dt = p[K.P_DT]
        n = len(self.rad)
        F = np.zeros((n, 2))
        T = np.zeros(n)
        for i in range(n):
            for j in range(i + 1, n):
                dx, dy = self.pos[j] - self.pos[i]
                d = math.hypot(dx, dy)
                ri, rj = self.rad[i], self.rad[j]
                fs, mr = self.pairs.get((i, j), [0.0, 0.0])
                if d >= ri + rj:
                    self.pairs.pop((i, j), None)
                    continue
                nx, ny = dx / d, dy / d
                tx, ty = -ny, nx
                vt = (self.vel[j] - self.vel[i]) @ (tx, ty) - self.om[j] * rj - self.om[i] * ri
                rbar = ri * rj / (ri + rj)
                fn, fs, mr = _law(
                    ri + rj - d, vt, self.om[j] - self.om[i], rbar, p[K.P_KN], p[K.P_KS],
                    p[K.P_MU], p[K.P_MUR], fs, mr, dt,
                )  # fmt: skip
                self.pairs[(i, j)] = [fs, mr]
                f = np.array([-fn * nx + fs * tx, -fn * ny + fs * ty])
                F[i] += f
                F[j] -= f
                T[i] += ri * fs + mr
                T[j] += rj * fs - mr
        wall = (p[K.P_KN_W], p[K.P_KS_W], p[K.P_MU_W], p[K.P_MUR_W], dt)
        pipe = (p[K.P_KN_P], p[K.P_KS_P], p[K.P_MU_P], p[K.P_MUR_P], dt)
        pfx = pfy = 0.0
        for i in range(n):
            x, y = self.pos[i]
            r = self.rad[i]
            walls = [
                (0, -1.0, 0.0, r - (x - p[K.P_X0]), 0.0, 0.0),
                (1, 1.0, 0.0, r - (p[K.P_X1] - x), 0.0, 0.0),
                (2, 0.0, -1.0, r - (y - p[K.P_Y0]), 0.0, 0.0),
            ]
            if p[K.P_LID_ON] > 0.5:
                walls.append((3, 0.0, 1.0, r - (p[K.P_LID_Y] - y), 0.0, p[K.P_LID_V]))
            for w, nx, ny, ov, vbx, vby in walls:
                fx, fy, t = self._wall(i, w, nx, ny, ov, vbx, vby, *wall)
                F[i] += (fx, fy)
                T[i] += t
            if p[K.P_PIPE_ON] > 0.5:
                dx, dy = p[K.P_PIPE_X] - x, p[K.P_PIPE_Y] - y
                d = math.hypot(dx, dy)
                fx, fy, t = self._wall(
                    i, K.PIPE, dx / d, dy / d, r + p[K.P_PIPE_R] - d, 0.0, p[K.P_PIPE_V], *pipe
                )
                F[i] += (fx, fy)
                T[i] += t
                pfx -= fx
                pfy -= fy
            F[i] += self.mass[i] * np.array([p[K.P_GX], p[K.P_GY]])
        self.pipe_force = (pfx, pfy)
        a = p[K.P_ALPHA]
        F = F - a * np.abs(F) * np.sign(self.vel)
        T = T - a * np.abs(T) * np.sign(self.om)
        self.vel += dt * F / self.inertial_mass[:, None]
        self.om += dt * T / self.inert
        self.pos += dt * self.vel
        self.th += dt * self.om
        p[K.P_TIME] += dt
        if p[K.P_PIPE_ON] > 0.5:
            p[K.P_PIPE_Y] += p[K.P_PIPE_V] * dt
        if p[K.P_LID_ON] > 0.5:
            p[K.P_LID_Y] += p[K.P_LID_V] * dt
