"""Benchmark of the Fourier force kernel against a Morison kernel of the same contract.

Drives each kernel through one 3.5-h irregular record with a current (Δt = 0.05 s, 252,000
evaluations) from a jitted loop and prints the time per evaluation, best of 5, after
compilation. The Morison kernel here is a stand-in written to the same signature (the
project's ``hydro/_morison_kernel.py`` belongs to the force-contract work); LLVM inlines such a
small kernel into the loop, which a solver's dispatch call does not allow, so it is a lower
bound. As a yardstick of a non-inlined kernel call in the same loop the project's Coulomb soil
kernel is timed too (a solver step calls a soil kernel several times per Newton iteration).

    python benchmarks/bench_fourier_kernel.py
"""

from __future__ import annotations

import math
import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numpy as np
from numba import njit

from onbottom.hydro._fourier_kernel import fourier_kernel
from onbottom.hydro.fourier import FourierModel
from onbottom.soil._coulomb_kernel import coulomb_kernel

SMOKE = "--smoke" in sys.argv[1:]
"""Tiny size (CI: the script finishes and prints its figures)."""


@njit(cache=False)
def morison_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Morison drag + inertia + lift with relative velocity (stand-in, same contract)."""
    for i in range(state_old.size):
        state_new[i] = state_old[i]
    wr = u + vc - ydot
    out[0] = (
        0.5 * rho * d * params[0] * wr * abs(wr) + 0.25 * math.pi * rho * d * d * params[1] * dudt
    )
    out[1] = -rho * d * params[0] * abs(wr)
    out[2] = 0.5 * rho * d * params[2] * (u + vc) ** 2
    out[3] = 0.0


@njit(cache=False)
def drive_fourier(params, t, u, dudt, vc):
    st = np.zeros(16)
    sn = np.zeros(16)
    out = np.zeros(4)
    acc = 0.0
    for i in range(t.size):
        fourier_kernel(params, st, t[i], u[i], dudt[i], vc, 0.0, 0.5, 1025.0, sn, out)
        st[:] = sn
        acc += out[0]
    return acc


@njit(cache=False)
def drive_morison(params, t, u, dudt, vc):
    st = np.zeros(16)
    sn = np.zeros(16)
    out = np.zeros(4)
    acc = 0.0
    for i in range(t.size):
        morison_kernel(params, st, t[i], u[i], dudt[i], vc, 0.0, 0.5, 1025.0, sn, out)
        st[:] = sn
        acc += out[0]
    return acc


@njit(cache=False)
def drive_coulomb(params, t, u, dudt, vc):
    st = np.zeros(16)
    sn = np.zeros(16)
    out = np.zeros(16)
    acc = 0.0
    for i in range(t.size):
        coulomb_kernel(params, st, 0.01 * u[i], 1000.0, sn, out)
        st[:] = sn
        acc += out[0]
    return acc


def main() -> None:
    """Print the time per evaluation of both kernels."""
    rng = np.random.default_rng(1)
    om = np.linspace(0.4, 1.6, 60)
    amp = rng.uniform(0.02, 0.06, om.size)
    ph = rng.uniform(0.0, 2.0 * math.pi, om.size)
    t = np.arange(1, (2000 if SMOKE else int(3.5 * 3600 / 0.05)) + 1) * 0.05
    u = np.zeros_like(t)
    dudt = np.zeros_like(t)
    for a, w, p in zip(amp, om, ph, strict=True):
        u += a * np.cos(w * t + p)
        dudt -= a * w * np.sin(w * t + p)
    fparams = FourierModel.example().params()
    mparams = np.array([0.7, 3.29, 0.9])
    cases = (
        ("morison", drive_morison, mparams),
        ("fourier", drive_fourier, fparams),
        ("coulomb", drive_coulomb, np.array([0.6, 0.01])),
    )
    for name, fn, p in cases:
        fn(p, t[:100], u[:100], dudt[:100], 0.2)
        best = math.inf
        for _ in range(1 if SMOKE else 5):
            t0 = time.perf_counter()
            fn(p, t, u, dudt, 0.2)
            best = min(best, time.perf_counter() - t0)
        print(
            f"{name:8s} {best * 1e3:8.2f} ms per 3.5-h record, {best / t.size * 1e9:6.1f} ns/eval"
        )


if __name__ == "__main__":
    main()
