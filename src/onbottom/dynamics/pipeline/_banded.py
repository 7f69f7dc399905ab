"""Banded symmetric LDLᵀ factorisation and solve in numba (private), with a Python twin.

The pipeline Jacobian is symmetric with half-bandwidth ``w`` (5 for 3 DOFs per node and
2-node elements); its lower band is stored as ``ab[i, k] = A[i, i − k]`` for k = 0..w
(entries with i − k < 0 unused). :func:`factor_jacobian` forms the HHT-α Jacobian from the
tangent band (scale, lumped mass, fixed DOFs decoupled), overwrites ``ab`` with the unit
lower factor L (off-diagonals) and 1/D (``ab[i, 0]``: no division left in the solve) and does
the forward pass of the solve on a right-hand side, all in one sweep — O(n·w²) work, no
pivoting (the effective dynamic matrix M/(βΔt²) + K_T is dominated by its diagonal for the
steps the solver accepts; a zero pivot is reported, a negative one is allowed and counted);
:func:`ldl_solve_backward` finishes that solve. :func:`ldl_factor` factors a band as it is;
:func:`ldl_solve` solves A x = b in place with a kept factor, O(n·w).

Half-bandwidth 5 (:data:`W_FIXED`) takes paths with constant trip counts and the previous
rows' factor kept in registers (the factor's and the solve's loop-carried chains are a few
floating-point latencies per row; a load of what the previous row stored adds a
store-to-load forwarding delay to each). The factor does the general loops' operations in
their order (the same result bit for bit); the solve's backward pass subtracts the terms of
row i in descending column order, x_{i+1} last (the general loops too), so that the latest
unknown ends the sum instead of starting it.

Reference: Golub & Van Loan, *Matrix Computations*, 4th ed., §4.3 (band LDLᵀ).
"""

from __future__ import annotations

import numpy as np

from onbottom._jit import borrow, jitted_only, pure_python

W_FIXED = 5
"""Half-bandwidth of the pipeline Jacobian (3 DOFs per node, 2-node elements): rows with a full
band take a path with constant trip counts and the previous rows in registers."""


@jitted_only
def factor_jacobian(ab, scale, mass, c_a, fixed, b):
    """Form J = c_a·M + scale·K from the tangent band K in ``ab``, factor it in place and
    start the solve of J x = b: ``b`` becomes L⁻¹b (:func:`ldl_solve_backward` finishes it).

    ``scale`` is 1 + α (HHT-α) [-], ``mass`` the lumped mass of each DOF [kg; kg·m² for a
    rotation], ``c_a`` = 1/(βΔt²) [1/s²], ``fixed`` non-zero on fixed DOFs (their row and
    column of J zero, a unit diagonal). Row by row (``ab[j, 0]`` already holds 1/D_j for
    j < i): with t_k = L_ik·D_k, L_ij·D_j = J_ij − Σ_k t_k L_jk and D_i = J_ii − Σ_k t_k L_ik,
    then y_i = b_i − Σ_k L_ik y_k — the same operations, in the same order, as forming J in
    ``ab``, factoring it and the forward pass of :func:`ldl_solve` (bit for bit), in one pass.
    Returns the number of negative pivots, or −1 if a pivot is zero or not finite.
    """
    n = ab.shape[0]
    w = ab.shape[1] - 1
    i_gen = n
    if w == W_FIXED and n > W_FIXED:
        i_gen = W_FIXED
    t = np.empty(w + 1)
    n_neg = 0
    # general rows: ab[j, 0] holds 1/D_j for j < i; with t_k = L_ik·D_k,
    # L_ij·D_j = A_ij − Σ_k t_k L_jk and D_i = A_ii − Σ_k t_k L_ik
    for i in range(i_gen):
        j0 = i - w
        if j0 < 0:
            j0 = 0
        # row i of J = c_a·M + scale·K, fixed DOFs decoupled (zero row and column, unit
        # diagonal)
        if fixed[i] != 0.0:
            for k in range(1, i - j0 + 1):
                ab[i, k] = 0.0
            ab[i, 0] = 1.0
        else:
            for k in range(1, i - j0 + 1):
                if fixed[i - k] != 0.0:
                    ab[i, k] = 0.0
                else:
                    ab[i, k] *= scale
            ab[i, 0] = ab[i, 0] * scale + mass[i] * c_a
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
        y = b[i]
        for k in range(j0, i):
            y -= ab[i, i - k] * b[k]
        b[i] = y
    if i_gen == n:
        return n_neg
    # full rows of half-bandwidth 5, the same operations: rN = 1/D of row i − N, aK/bK/cK/eK
    # = L of rows i − 1/i − 2/i − 3/i − 4 at column offset K (ab[row, K])
    i0 = W_FIXED
    r1 = ab[i0 - 1, 0]
    r2 = ab[i0 - 2, 0]
    r3 = ab[i0 - 3, 0]
    r4 = ab[i0 - 4, 0]
    r5 = ab[i0 - 5, 0]
    a1 = ab[i0 - 1, 1]
    a2 = ab[i0 - 1, 2]
    a3 = ab[i0 - 1, 3]
    a4 = ab[i0 - 1, 4]
    b1 = ab[i0 - 2, 1]
    b2 = ab[i0 - 2, 2]
    b3 = ab[i0 - 2, 3]
    c1 = ab[i0 - 3, 1]
    c2 = ab[i0 - 3, 2]
    e1 = ab[i0 - 4, 1]
    x0 = b[i0 - 5]
    x1 = b[i0 - 4]
    x2 = b[i0 - 3]
    x3 = b[i0 - 2]
    x4 = b[i0 - 1]
    for i in range(W_FIXED, n):
        q0 = ab[i, 0]
        q1 = ab[i, 1]
        q2 = ab[i, 2]
        q3 = ab[i, 3]
        q4 = ab[i, 4]
        q5 = ab[i, 5]
        if fixed[i] != 0.0:  # the forming above, on the row in registers
            q0 = 1.0
            q1 = q2 = q3 = q4 = q5 = 0.0
        else:
            q0 = q0 * scale + mass[i] * c_a
            q1 = 0.0 if fixed[i - 1] != 0.0 else q1 * scale
            q2 = 0.0 if fixed[i - 2] != 0.0 else q2 * scale
            q3 = 0.0 if fixed[i - 3] != 0.0 else q3 * scale
            q4 = 0.0 if fixed[i - 4] != 0.0 else q4 * scale
            q5 = 0.0 if fixed[i - 5] != 0.0 else q5 * scale
        t0 = q5
        l5 = t0 * r5
        s = q4
        s -= t0 * e1
        t1 = s
        l4 = s * r4
        s = q3
        s -= t0 * c2
        s -= t1 * c1
        t2 = s
        l3 = s * r3
        s = q2
        s -= t0 * b3
        s -= t1 * b2
        s -= t2 * b1
        t3 = s
        l2 = s * r2
        s = q1
        s -= t0 * a4
        s -= t1 * a3
        s -= t2 * a2
        s -= t3 * a1
        t4 = s
        l1 = s * r1
        s = q0
        s -= t0 * l5
        s -= t1 * l4
        s -= t2 * l3
        s -= t3 * l2
        s -= t4 * l1
        if s == 0.0 or not (abs(s) < 1e300):
            return -1
        if s < 0.0:
            n_neg += 1
        d = 1.0 / s
        ab[i, 0] = d
        ab[i, 1] = l1
        ab[i, 2] = l2
        ab[i, 3] = l3
        ab[i, 4] = l4
        ab[i, 5] = l5
        r5, r4, r3, r2, r1 = r4, r3, r2, r1, d
        e1 = c1
        c1, c2 = b1, b2
        b1, b2, b3 = a1, a2, a3
        a1, a2, a3, a4 = l1, l2, l3, l4
        y = b[i]
        y -= l5 * x0
        y -= l4 * x1
        y -= l3 * x2
        y -= l2 * x3
        y -= l1 * x4
        b[i] = y
        x0, x1, x2, x3, x4 = x1, x2, x3, x4, y
    return n_neg


@jitted_only
def ldl_factor(ab):
    """Factor the symmetric band matrix held in ``ab`` (n × (w+1)) in place.

    :func:`factor_jacobian` with nothing to form (scale 1, no mass, no fixed DOF: x·1 = x and
    x + 0 = x exactly, the same factor) and a zero right-hand side. Returns the number of
    negative pivots, or −1 if a pivot is zero or not finite.
    """
    n = ab.shape[0]
    return factor_jacobian(ab, 1.0, np.zeros(n), 0.0, np.zeros(n), np.zeros(n))


@jitted_only
def ldl_solve(ab, b):
    """Solve A x = b in place (``b`` becomes x) with the factor from :func:`ldl_factor`.

    Forward L y = b (the terms of row i in ascending column order), then x = D⁻¹ y − Lᵀ x in
    one backward sweep (the terms of row i in descending order, x_{i+1} last). Half-bandwidth
    5 and n > 10: the same operations with the last five unknowns of each sweep in registers.
    """
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
    ldl_solve_backward(borrow(ab), borrow(b))


@jitted_only
def ldl_solve_backward(ab, b):
    """The second half of :func:`ldl_solve`: x = D⁻¹y − Lᵀx in place of y = L⁻¹b in ``b``
    (the terms of row i in descending column order, x_{i+1} last; b[i] is scaled by 1/D_i
    before its own update)."""
    n = ab.shape[0]
    w = ab.shape[1] - 1
    fixed = w == W_FIXED and n > 2 * W_FIXED
    i_stop = n - 1 - W_FIXED if fixed else -1
    for i in range(n - 1, i_stop, -1):
        s = b[i] * ab[i, 0]
        j1 = i + w
        if j1 > n - 1:
            j1 = n - 1
        for k in range(j1, i, -1):
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
            s -= ab[i + 5, 5] * y5
            s -= ab[i + 4, 4] * y4
            s -= ab[i + 3, 3] * y3
            s -= ab[i + 2, 2] * y2
            s -= ab[i + 1, 1] * y1
            b[i] = s
            y1, y2, y3, y4, y5 = s, y1, y2, y3, y4


factor_jacobian_py = pure_python(factor_jacobian)
"""Plain-Python twin of :func:`factor_jacobian` (same source, interpreted)."""
ldl_factor_py = pure_python(ldl_factor)
"""Plain-Python twin of :func:`ldl_factor`."""
ldl_solve_backward_py = pure_python(ldl_solve_backward)
"""Plain-Python twin of :func:`ldl_solve_backward`."""
ldl_solve_py = pure_python(ldl_solve)
"""Plain-Python twin of :func:`ldl_solve`."""
