"""Numba kernel of the loose-layer generator: random sequential addition of disks.

Private: :mod:`onbottom.dem.preparation` wraps it (``Preparation.layer_generation =
"random"``). Its plain-Python twin is :func:`rsa_positions_python`, used by the tests on
small inputs (same algorithm, same random numbers, same result).
"""

from __future__ import annotations

import numpy as np

from onbottom._jit import numba_njit as njit


@njit(cache=True)
def rsa_positions(diam, x0, width, y0, height, u, max_tries):
    """Random sequential addition of disks into the rectangle [x0, x0+width] × [y0, y0+height].

    Disk k (in the given order) is tried at uniform random centres (``u[t]``: pairs of uniform
    numbers in [0, 1), consumed in order, shared by all disks) inside the rectangle shrunk by
    its radius until it overlaps no disk placed before it (cell grid of cells ≥ the largest
    diameter); at most ``max_tries`` tries per disk. Returns (positions (n, 2), number of
    uniform pairs used); a disk that found no place has a NaN position (the caller gives up
    or retries taller).
    """
    n = diam.shape[0]
    pos = np.full((n, 2), np.nan)
    dmax = 0.0
    for k in range(n):
        dmax = max(dmax, diam[k])
    ncx = max(1, int(width / dmax))
    ncy = max(1, int(height / dmax))
    cw = width / ncx
    ch = height / ncy
    head = np.full(ncx * ncy, -1, np.int64)
    nxt = np.full(n, -1, np.int64)
    t = 0
    nu = u.shape[0]
    for k in range(n):
        r = 0.5 * diam[k]
        placed = False
        for _ in range(max_tries):
            if t >= nu:
                return pos, t
            x = x0 + r + u[t, 0] * (width - 2.0 * r)
            y = y0 + r + u[t, 1] * (height - 2.0 * r)
            t += 1
            cx = min(ncx - 1, int((x - x0) / cw))
            cy = min(ncy - 1, int((y - y0) / ch))
            free = True
            for jy in range(max(0, cy - 1), min(ncy, cy + 2)):
                for jx in range(max(0, cx - 1), min(ncx, cx + 2)):
                    m = head[jy * ncx + jx]
                    while m >= 0:
                        dx = pos[m, 0] - x
                        dy = pos[m, 1] - y
                        rs = r + 0.5 * diam[m]
                        if dx * dx + dy * dy < rs * rs:
                            free = False
                            break
                        m = nxt[m]
                    if not free:
                        break
                if not free:
                    break
            if free:
                pos[k, 0] = x
                pos[k, 1] = y
                c = cy * ncx + cx
                nxt[k] = head[c]
                head[c] = k
                placed = True
                break
        if not placed:
            return pos, t
    return pos, t


def rsa_positions_python(
    diam: np.ndarray,
    x0: float,
    width: float,
    y0: float,
    height: float,
    u: np.ndarray,
    max_tries: int,
) -> tuple[np.ndarray, int]:
    """Plain-Python twin of :func:`rsa_positions` (all pairs tested, no cell grid)."""
    n = len(diam)
    pos = np.full((n, 2), np.nan)
    t = 0
    for k in range(n):
        r = 0.5 * diam[k]
        for _ in range(max_tries):
            if t >= len(u):
                return pos, t
            x = x0 + r + u[t, 0] * (width - 2.0 * r)
            y = y0 + r + u[t, 1] * (height - 2.0 * r)
            t += 1
            d2 = (pos[:k, 0] - x) ** 2 + (pos[:k, 1] - y) ** 2
            if np.all(d2 >= (r + 0.5 * diam[:k]) ** 2):
                pos[k] = (x, y)
                break
        else:
            return pos, t
    return pos, t
