"""Rate of the pipeline FE's band LDLᵀ: factor and solve of a 1503-DOF Jacobian (500 elements).

Each kernel of ``onbottom.dynamics.pipeline._banded`` is called ``--reps`` times inside one njit
driver on a diagonally dominant random band of half-bandwidth 5 (the pipeline's; the cost
does not depend on the values) with the three DOFs of each end node fixed, and timed in CPU
seconds of this process (``time.process_time``; the least of ``--repeat`` timings, less that
of the driver's copy of its input). Printed per call and per row:

- ``factor_jacobian``: the Jacobian formed (scale 1 + α, lumped mass, fixed DOFs), factored and
  the solve's forward pass done in one sweep — what the time loop calls when it refactors;
- ``ldl_solve_backward``: the rest of that solve;
- ``ldl_factor`` and ``ldl_solve``: the factor alone and a full solve with a kept factor;
- ``form, ldl_factor, ldl_solve``: the same work as three separate sweeps (for comparison);
- SciPy's ``solveh_banded`` (LAPACK banded Cholesky and solve, one call from Python).

With the counters of the 500-element 3.5-h benchmark storm (``--factors-per-step``: 138,674
factorisations / 126,810 tried steps; ``--iterations-per-step`` 2.32, one solve per iteration
but the last) it prints the band solver's cost per step.

    NUMBA_NUM_THREADS=1 python benchmarks/band_solver_rate.py
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
import scipy.linalg
from numba import njit

from onbottom._jit import borrow
from onbottom.dynamics.pipeline._banded import (
    W_FIXED,
    factor_jacobian,
    ldl_factor,
    ldl_solve,
    ldl_solve_backward,
)

SCALE = 0.9  # 1 + α with the default α = −0.1
C_A = 400.0  # 1/(βΔt²) [1/s²]


@njit(cache=True)
def _copy(reps, ab0, ab, b0, b):
    for _ in range(reps):
        ab[:, :] = ab0
        b[:] = b0


@njit(cache=True)
def _jacobian(reps, ab0, ab, b0, b, mass, fixed):
    neg = 0
    for _ in range(reps):
        ab[:, :] = ab0
        b[:] = b0
        neg = factor_jacobian(borrow(ab), SCALE, borrow(mass), C_A, borrow(fixed), borrow(b))
    return neg


@njit(cache=True)
def _factor(reps, ab0, ab, b0, b):
    neg = 0
    for _ in range(reps):
        ab[:, :] = ab0
        b[:] = b0
        neg = ldl_factor(borrow(ab))
    return neg


@njit(cache=True)
def _backward(reps, ab0, ab, b0, b):
    for _ in range(reps):
        ab[:, :] = ab0
        b[:] = b0
        ldl_solve_backward(borrow(ab), borrow(b))


@njit(cache=True)
def _solve(reps, ab0, ab, b0, b):
    for _ in range(reps):
        ab[:, :] = ab0
        b[:] = b0
        ldl_solve(borrow(ab), borrow(b))


@njit(cache=True)
def _separate(reps, ab0, ab, b0, b, mass, fixed):
    """The Jacobian formed in its own sweep, then factored, then solved."""
    n = ab.shape[0]
    for _ in range(reps):
        ab[:, :] = ab0
        b[:] = b0
        for j in range(n):
            for k in range(W_FIXED + 1):
                ab[j, k] *= SCALE
            ab[j, 0] += mass[j] * C_A
        for j in range(n):
            if fixed[j] != 0.0:
                for k in range(1, W_FIXED + 1):
                    ab[j, k] = 0.0
                    if j + k < n:
                        ab[j + k, k] = 0.0
                ab[j, 0] = 1.0
        ldl_factor(borrow(ab))
        ldl_solve(borrow(ab), borrow(b))


def _least(fn, reps: int, repeat: int) -> float:
    """Least CPU seconds of fn(reps) over ``repeat`` timings."""
    fn(1)
    best = np.inf
    for _ in range(repeat):
        c0 = time.process_time()
        fn(reps)
        best = min(best, time.process_time() - c0)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dofs", type=int, default=1503, help="rows (3 per node)")
    ap.add_argument("--reps", type=int, default=2000, help="calls per timing")
    ap.add_argument("--repeat", type=int, default=9, help="timings (least kept)")
    ap.add_argument("--factors-per-step", type=float, default=138674 / 126810)
    ap.add_argument("--iterations-per-step", type=float, default=2.32)
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    a = ap.parse_args()
    if a.smoke:
        a.dofs, a.reps, a.repeat = 63, 20, 2
    n = a.dofs
    print(f"load average: {os.getloadavg()}")
    rng = np.random.default_rng(0)
    k = rng.normal(size=(n, W_FIXED + 1))
    k[:, 0] = 8.0 * W_FIXED + rng.uniform(0.0, 1.0, n)
    for i in range(min(n, W_FIXED)):
        k[i, i + 1 :] = 0.0
    mass = rng.uniform(0.5, 1.5, n) / C_A
    fixed = np.zeros(n)
    fixed[:3] = fixed[-3:] = 1.0
    b0 = rng.normal(size=n)
    fac = k.copy()  # a factor, for the solves
    ldl_factor(fac)
    ab, b = np.empty_like(k), np.empty(n)

    base = _least(lambda r: _copy(r, k, ab, b0, b), a.reps, a.repeat)

    def per_call(fn) -> float:
        return max(_least(fn, a.reps, a.repeat) - base, 0.0) / a.reps * 1e6

    rows = {
        "factor_jacobian (form, factor, forward)": per_call(
            lambda r: _jacobian(r, k, ab, b0, b, mass, fixed)
        ),
        "ldl_solve_backward": per_call(lambda r: _backward(r, fac, ab, b0, b)),
        "ldl_factor": per_call(lambda r: _factor(r, k, ab, b0, b)),
        "ldl_solve": per_call(lambda r: _solve(r, fac, ab, b0, b)),
        "form, ldl_factor, ldl_solve (3 sweeps)": per_call(
            lambda r: _separate(r, k, ab, b0, b, mass, fixed)
        ),
    }
    upper = np.zeros((W_FIXED + 1, n))  # SciPy's upper form of the same (SPD) band
    for i in range(n):
        for q in range(min(W_FIXED + 1, i + 1)):
            upper[W_FIXED - q, i] = k[i, q]
    c0 = time.process_time()
    reps_sp = max(a.reps // 10, 1)
    for _ in range(reps_sp):
        scipy.linalg.solveh_banded(upper, b0, check_finite=False)
    rows["scipy solveh_banded (LAPACK, from Python)"] = (time.process_time() - c0) / reps_sp * 1e6
    print(f"{n} DOFs, half-bandwidth {W_FIXED}; CPU time per call (least of {a.repeat}):")
    for name, us in rows.items():
        print(f"  {name:42s} {us:8.2f} us  {1e3 * us / n:6.2f} ns/row")
    f, it = a.factors_per_step, a.iterations_per_step
    kept = max(it - 1.0 - f, 0.0)  # solves with a kept factor
    step = f * (rows["factor_jacobian (form, factor, forward)"] + rows["ldl_solve_backward"])
    step += kept * rows["ldl_solve"]
    sep = f * rows["form, ldl_factor, ldl_solve (3 sweeps)"] + kept * rows["ldl_solve"]
    print(
        f"band solver per Newton step ({f:.3f} factorisations, {it:.2f} iterations): "
        f"{step:.2f} us (three sweeps: {sep:.2f} us)"
    )


if __name__ == "__main__":
    main()
