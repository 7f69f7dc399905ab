"""Banded symmetric LDLᵀ factorisation and solve in numba (private), with a Python twin.

The pipeline Jacobian is symmetric with half-bandwidth ``w`` (5 for 3 DOFs per node and
2-node elements); its lower band is stored as ``ab[i, k] = A[i, i − k]`` for k = 0..w
(entries with i − k < 0 unused). :func:`ldl_factor` overwrites ``ab`` with the unit lower
factor L (off-diagonals) and 1/D (``ab[i, 0]``: no division left in the solve) — O(n·w²)
work, no pivoting (the effective
dynamic matrix M/(βΔt²) + K_T is dominated by its diagonal for the steps the solver accepts;
a zero pivot is reported, a negative one is allowed and counted). :func:`ldl_solve` solves
A x = b in place in O(n·w).

Reference: Golub & Van Loan, *Matrix Computations*, 4th ed., §4.3 (band LDLᵀ).
"""

from __future__ import annotations

import numpy as np

from onbottom._jit import njit, pure_python

W_FIXED = 5
"""Half-bandwidth of the pipeline Jacobian (3 DOFs per node, 2-node elements): rows with a full
band take a path with constant trip counts (unrolled by LLVM; the same operations in the same
order, so the same result bit for bit; about half the time of the general loops)."""


@njit(cache=True)
def ldl_factor(ab):
    """Factor the symmetric band matrix held in ``ab`` (n × (w+1)) in place.

    Row by row (``ab[j, 0]`` already holds 1/D_j for j < i): with t_k = L_ik·D_k (kept in a
    work vector), L_ij·D_j = A_ij − Σ_k t_k L_jk and
    D_i = A_ii − Σ_k t_k L_ik. Returns the number of negative pivots, or −1 if a pivot is
    zero or not finite.
    """
    n = ab.shape[0]
    w = ab.shape[1] - 1
    fixed = w == W_FIXED
    t = np.empty(w + 1)
    n_neg = 0
    for i in range(n):
        if fixed and i >= W_FIXED:
            # full band: j = i − W_FIXED + jj, k = i − W_FIXED + kk (same sums as below)
            for jj in range(W_FIXED):
                j = i - W_FIXED + jj
                s = ab[i, W_FIXED - jj]
                for kk in range(jj):
                    s -= t[kk] * ab[j, jj - kk]
                t[jj] = s
                ab[i, W_FIXED - jj] = s * ab[j, 0]
            s = ab[i, 0]
            for kk in range(W_FIXED):
                s -= t[kk] * ab[i, W_FIXED - kk]
        else:
            j0 = i - w
            if j0 < 0:
                j0 = 0
            for j in range(j0, i):
                s = ab[i, i - j]
                for k in range(j0, j):
                    s -= t[k - j0] * ab[j, j - k]
                t[j - j0] = s
                ab[i, i - j] = s * ab[j, 0]
            s = ab[i, 0]
            for k in range(j0, i):
                s -= t[k - j0] * ab[i, i - k]
        if s == 0.0 or not (abs(s) < 1e300):
            return -1
        if s < 0.0:
            n_neg += 1
        ab[i, 0] = 1.0 / s
    return n_neg


@njit(cache=True)
def ldl_solve(ab, b):
    """Solve A x = b in place (``b`` becomes x) with the factor from :func:`ldl_factor`.

    Half-bandwidth 5 and n > 10: the general loops' operations in their order, with the last
    five unknowns of each sweep kept in registers (the store-to-load latency of b[i − 1] was
    on the sweep's critical path)."""
    n = ab.shape[0]
    w = ab.shape[1] - 1
    fixed = w == W_FIXED and n > 2 * W_FIXED
    i_end = W_FIXED if fixed else n
    for i in range(i_end):
        s = b[i]
        j0 = i - w
        if j0 < 0:
            j0 = 0
        for k in range(j0, i):
            s -= ab[i, i - k] * b[k]
        b[i] = s
    if fixed:
        x0 = b[0]
        x1 = b[1]
        x2 = b[2]
        x3 = b[3]
        x4 = b[4]
        for i in range(W_FIXED, n):
            s = b[i]
            s -= ab[i, 5] * x0
            s -= ab[i, 4] * x1
            s -= ab[i, 3] * x2
            s -= ab[i, 2] * x3
            s -= ab[i, 1] * x4
            b[i] = s
            x0, x1, x2, x3, x4 = x1, x2, x3, x4, s
    # D⁻¹ and the backward pass in one sweep (b[i] is scaled before its own update, as in two)
    i_stop = n - 1 - W_FIXED if fixed else -1
    for i in range(n - 1, i_stop, -1):
        s = b[i] * ab[i, 0]
        j1 = i + w
        if j1 > n - 1:
            j1 = n - 1
        for k in range(i + 1, j1 + 1):
            s -= ab[k, k - i] * b[k]
        b[i] = s
    if fixed:
        y1 = b[n - 5]
        y2 = b[n - 4]
        y3 = b[n - 3]
        y4 = b[n - 2]
        y5 = b[n - 1]
        for i in range(n - 1 - W_FIXED, -1, -1):
            s = b[i] * ab[i, 0]
            s -= ab[i + 1, 1] * y1
            s -= ab[i + 2, 2] * y2
            s -= ab[i + 3, 3] * y3
            s -= ab[i + 4, 4] * y4
            s -= ab[i + 5, 5] * y5
            b[i] = s
            y1, y2, y3, y4, y5 = s, y1, y2, y3, y4


ldl_factor_py = pure_python(ldl_factor)
"""Plain-Python twin of :func:`ldl_factor` (same source, interpreted)."""
ldl_solve_py = pure_python(ldl_solve)
"""Plain-Python twin of :func:`ldl_solve`."""
