"""The machine's own rate, apart from the DEM engine's: a frozen reference workload.

This 2-core VM runs the same code at rates up to 1.5 times apart between periods (issue
#15: the same SM-Dr48 compaction took 20.4 min one day and 28.1 min on another with a faster
engine), so a wall time of a whole DEM case says as much about the machine as about the
engine. This script times a workload that never changes with the engine: a frozen copy of
the shape of the DEM step (a flat pass over a half neighbour list of a 60,000-disk bed with
linear contact forces, then a per-disk gather and leapfrog update, blocks of 512 disks in
parallel), on a fixed, seeded bed. Its ns per disk-step on a given machine and day is the
yardstick: divide a case's wall time by it (or compare it between two days) to tell a faster
engine from a faster machine. ``dem_full_case.py`` records it before and after a case.

Do not edit the kernels below: a changed kernel is a different yardstick (bump ``VERSION``).

Run::

    python benchmarks/machine_rate.py            # 2 threads and 1 thread
    python benchmarks/machine_rate.py --json
"""

from __future__ import annotations

import argparse
import json
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numba
import numpy as np
from numba import njit, prange

VERSION = 1
BLOCK = 512


def bed(n_side: int = 245, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A jittered square bed of n_side² touching disks and its half neighbour list (CSR)."""
    rng = np.random.default_rng(seed)
    h = 1.0e-3
    ij = np.stack(np.meshgrid(np.arange(n_side), np.arange(n_side), indexing="ij"), -1)
    pos = (ij.reshape(-1, 2)[:, ::-1] * h + rng.uniform(-0.02, 0.02, (n_side**2, 2)) * h).copy()
    # neighbours within 1.5 h among the 8 around each disk, j > i (row-major numbering)
    idx = np.arange(n_side**2).reshape(n_side, n_side)
    lists = [[] for _ in range(n_side**2)]
    for dr, dc in ((0, 1), (1, -1), (1, 0), (1, 1)):
        a = idx[max(0, -dr) : n_side - max(0, dr), max(0, -dc) : n_side - max(0, dc)]
        b = idx[max(0, dr) : n_side + min(0, dr), max(0, dc) : n_side + min(0, dc)]
        for i, j in zip(a.ravel(), b.ravel(), strict=True):
            lists[min(i, j)].append(max(i, j))
    start = np.zeros(n_side**2 + 1, np.int64)
    start[1:] = np.cumsum([len(x) for x in lists])
    nbr = np.array([j for x in lists for j in sorted(x)], np.int64)
    return pos, start, nbr


@njit(cache=True, parallel=True)
def _step(pos, vel, start, nbr, fx, fy, sfx, sfy, r, k, dt):
    n = pos.shape[0]
    nb = (n + BLOCK - 1) // BLOCK
    for b in prange(nb):
        i0 = b * BLOCK
        i1 = min(n, i0 + BLOCK)
        for i in range(i0, i1):
            for e in range(start[i], start[i + 1]):
                j = nbr[e]
                dx = pos[j, 0] - pos[i, 0]
                dy = pos[j, 1] - pos[i, 1]
                d = np.sqrt(dx * dx + dy * dy)
                ov = 2.0 * r - d
                f = k * ov if ov > 0.0 else 0.0
                fx[e] = -f * dx / d
                fy[e] = -f * dy / d
        for i in range(i0, i1):
            ax = 0.0
            ay = 0.0
            for e in range(start[i], start[i + 1]):
                ax += fx[e]
                ay += fy[e]
            sfx[i] = ax
            sfy[i] = ay
    for b in prange(nb):
        i0 = b * BLOCK
        i1 = min(n, i0 + BLOCK)
        for i in range(i0, i1):
            vel[i, 0] = 0.999 * vel[i, 0] + sfx[i] * dt
            vel[i, 1] = 0.999 * vel[i, 1] + sfy[i] * dt
            pos[i, 0] += vel[i, 0] * dt
            pos[i, 1] += vel[i, 1] * dt


def measure(threads: int, steps: int = 1500, repeat: int = 3) -> float:
    """Best ns per disk-step of the reference workload on ``threads`` threads."""
    pos0, start, nbr = bed()
    n = pos0.shape[0]
    m = nbr.shape[0]
    fx, fy = np.empty(m), np.empty(m)
    sfx, sfy = np.empty(n), np.empty(n)
    r, k, dt = 0.505e-3, 1e3, 1e-7
    previous = numba.get_num_threads()
    numba.set_num_threads(threads)
    try:
        best = np.inf
        for _ in range(repeat):
            pos, vel = pos0.copy(), np.zeros_like(pos0)
            _step(pos, vel, start, nbr, fx, fy, sfx, sfy, r, k, dt)  # compile / warm
            t0 = time.perf_counter()
            for _ in range(steps):
                _step(pos, vel, start, nbr, fx, fy, sfx, sfy, r, k, dt)
            best = min(best, (time.perf_counter() - t0) / steps / n * 1e9)
    finally:
        numba.set_num_threads(previous)
    return float(best)


def reference(threads: tuple[int, ...] = (2, 1), steps: int = 1500, repeat: int = 3) -> dict:
    """The yardstick on this machine now: ns per disk-step per thread count, with the load."""
    out: dict = {"version": VERSION, "load": os.getloadavg()[0]}
    for t in threads:
        if t <= numba.config.NUMBA_NUM_THREADS:
            out[f"ns_per_disk_step_{t}_threads"] = measure(t, steps, repeat)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    ref = reference(steps=20, repeat=1) if args.smoke else reference()
    if args.json:
        print(json.dumps(ref))
        return
    print(f"machine reference v{ref['version']} (load {ref['load']:.2f})")
    for key, value in ref.items():
        if key.startswith("ns_"):
            print(f"  {key}: {value:.2f}")


if __name__ == "__main__":
    main()
