"""Cost of one wake-kernel evaluation against the Morison kernels (prints figures; not a test).

Both loops run a fixed pipe through the same 3-h record (T_p/40 sampling) inside one njit
driver: the wake model calls ``wake_kernel`` and copies its 16-slot state each step; the
Morison loop calls ``morison_kernel`` (stateless). Wall-clock medians of 5 repeats; they
depend on the machine's load: report ``uptime`` with them.

    python benchmarks/wake_kernel.py
"""

from __future__ import annotations

import os
import statistics
import sys
import time

import numpy as np
from numba import njit

from onbottom.hydro._force_contract import FO_FY, FO_FZ, FO_SIZE, N_FORCE_STATE
from onbottom.hydro._morison_kernel import morison_kernel
from onbottom.hydro._wake_kernel import wake_kernel
from onbottom.hydro.wake import WakeModel
from onbottom.hydro.wake_calibration import jonswap_record

SMOKE = "--smoke" in sys.argv[1:]
"""Tiny size (CI: the script finishes and prints its figures)."""


@njit(cache=True)
def _wake_loop(params, t, u, dudt, vc, d, rho):
    s_old = np.zeros(N_FORCE_STATE)
    s_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    acc = 0.0
    for i in range(t.shape[0]):
        wake_kernel(params, s_old, t[i], u[i], dudt[i], vc, 0.0, d, rho, s_new, out)
        for j in range(N_FORCE_STATE):
            s_old[j] = s_new[j]
        acc += out[FO_FY] + out[FO_FZ]
    return acc


@njit(cache=True)
def _morison_loop(params, t, u, dudt, vc, d, rho):
    s_old = np.zeros(N_FORCE_STATE)
    s_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    acc = 0.0
    for i in range(t.shape[0]):
        morison_kernel(params, s_old, t[i], u[i], dudt[i], vc, 0.0, d, rho, s_new, out)
        acc += out[FO_FY] + out[FO_FZ]
    return acc


def _median(fn, repeats: int = 5) -> float:
    times = []
    for _ in range(1 if SMOKE else repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    rec = jonswap_record(6.0, 10.0, 30.0, n_components=1024)
    t, u, dudt = rec["t"], rec["u"], rec["dudt"]
    p = WakeModel().parameters()
    _wake_loop(p, t, u, dudt, 0.3, 0.5, 1025.0)
    pm = np.array([1.0, 3.29, 0.9, 0.0])  # C_D, C_M, C_L, lift-relative flag
    _morison_loop(pm, t, u, dudt, 0.3, 0.5, 1025.0)
    tw = _median(lambda: _wake_loop(p, t, u, dudt, 0.3, 0.5, 1025.0))
    tm = _median(lambda: _morison_loop(pm, t, u, dudt, 0.3, 0.5, 1025.0))
    n = t.size
    print(f"load average: {os.getloadavg()}")
    print(f"{n} evaluations (3 h at T_p/40)")
    print(f"wake kernel:    {tw * 1e3:8.2f} ms  ({tw / n * 1e9:6.1f} ns per evaluation)")
    print(f"Morison kernel: {tm * 1e3:8.2f} ms  ({tm / n * 1e9:6.1f} ns per evaluation)")
    print(f"ratio: {tw / tm:.2f}")


if __name__ == "__main__":
    main()
