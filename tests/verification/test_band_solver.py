"""Verification of the banded LDLᵀ factor and solve of the pipeline FE (``_banded``).

The factor is checked bit for bit against the textbook band LDLᵀ (Golub & Van Loan, *Matrix
Computations*, 4th ed., §4.3) written here in plain Python with its sums in ascending column
order, the operation order of the kernel before its register-window rewrite; the Jacobian
forming fused into the factor against forming it first and factoring after. The solve sums
the backward pass in another order than that reference, so it is checked within a bound:
the componentwise residual bound of a triangular-factor solve, |b − A x̂| ≤ γ_m (|L||D||Lᵀ|)|x̂|
(Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., Thm 9.4 and §10.4; m the
terms per row of the factor's and the solve's sums, here 4(w + 2) to cover the reciprocal
pivot), and against SciPy's banded Cholesky (SPD) and a dense LU solve (indefinite). The
count of negative pivots is the number of negative eigenvalues (Sylvester's law of inertia).
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from onbottom.dynamics.pipeline import _banded as BD

pytestmark = pytest.mark.verification

EPS = np.finfo(float).eps


def _band(n, w, rng, spd):
    """Random lower band (n × (w+1)); SPD: diagonally dominant; else every third pivot
    negative-leaning (an indefinite matrix)."""
    ab = rng.normal(size=(n, w + 1))
    ab[:, 0] = (8.0 if spd else 2.5) * w + rng.uniform(0.0, 1.0, n)
    if not spd:
        ab[::3, 0] *= -1.0
    for i in range(n):
        ab[i, i + 1 :] = 0.0
    return ab


def _dense(ab):
    n, w1 = ab.shape
    a = np.zeros((n, n))
    for i in range(n):
        for k in range(min(w1, i + 1)):
            a[i, i - k] = a[i - k, i] = ab[i, k]
    return a


def _reference_factor(ab):
    """Textbook band LDLᵀ (ascending sums; L below the diagonal, 1/D on it)."""
    n, w = ab.shape[0], ab.shape[1] - 1
    t = [0.0] * (w + 1)
    n_neg = 0
    for i in range(n):
        j0 = max(i - w, 0)
        for j in range(j0, i):
            s = ab[i, i - j]
            for k in range(j0, j):
                s -= t[k - j0] * ab[j, j - k]
            t[j - j0] = s
            ab[i, i - j] = s * ab[j, 0]
        s = ab[i, 0]
        for k in range(j0, i):
            s -= t[k - j0] * ab[i, i - k]
        if s == 0.0 or not abs(s) < 1e300:
            return -1
        n_neg += s < 0.0
        ab[i, 0] = 1.0 / s
    return n_neg


def _reference_solve(f, b):
    """Forward and backward substitution with ascending sums (the order before the rewrite)."""
    n, w = f.shape[0], f.shape[1] - 1
    x = b.copy()
    for i in range(n):
        for k in range(max(i - w, 0), i):
            x[i] -= f[i, i - k] * x[k]
    for i in range(n - 1, -1, -1):
        s = x[i] * f[i, 0]
        for k in range(i + 1, min(i + w, n - 1) + 1):
            s -= f[k, k - i] * x[k]
        x[i] = s
    return x


def _form(ab, scale, mass, c_a, fixed):
    """The Jacobian forming of the pipeline time loop, done before the factor."""
    n, w1 = ab.shape
    ab *= scale
    ab[:, 0] += mass * c_a
    for j in np.flatnonzero(fixed):
        ab[j, 1:] = 0.0
        for k in range(1, w1):
            if j + k < n:
                ab[j + k, k] = 0.0
        ab[j, 0] = 1.0


def _factors(f):
    """Dense unit-lower L and diagonal D from the factor held in the band."""
    n, w1 = f.shape
    lo = np.eye(n)
    for i in range(n):
        for k in range(1, min(w1, i + 1)):
            lo[i, i - k] = f[i, k]
    return lo, 1.0 / f[:, 0]


SIZES = [1, 4, 5, 6, 10, 11, 12, 60, 1503]


@pytest.mark.parametrize("n", SIZES)
@pytest.mark.parametrize("spd", [True, False])
@pytest.mark.parametrize("w", [5, 3])
def test_factor_equals_the_textbook_band_ldlt_bit_for_bit(n, spd, w):
    ab = _band(n, w, np.random.default_rng(n + 7 * w), spd)
    ref = ab.copy()
    neg_ref = _reference_factor(ref)
    for factor in (BD.ldl_factor, BD.ldl_factor_py):
        f = ab.copy()
        assert factor(f) == neg_ref
        np.testing.assert_array_equal(f, ref)


@pytest.mark.parametrize("n", [6, 7, 11, 12, 60, 301])
def test_factor_jacobian_equals_forming_factoring_and_solving(n):
    """The fused pass gives, bit for bit, what the time loop's separate forming, ldl_factor
    and ldl_solve gave (fixed DOFs first, last, inside and adjacent): the factor, and with
    ldl_solve_backward the solution."""
    rng = np.random.default_rng(n)
    ab = _band(n, 5, rng, spd=False)
    mass = rng.uniform(1.0, 3.0, n)
    fixed = np.zeros(n)
    fixed[[0, 1, n // 2, n // 2 + 1, n - 1]] = 1.0
    b = rng.normal(size=n)
    ref = ab.copy()
    _form(ref, 0.9, mass, 40.0, fixed)
    neg_ref = BD.ldl_factor(ref)
    assert neg_ref == _reference_factor(_form_copy(ab, mass, fixed))
    x_ref = b.copy()
    BD.ldl_solve(ref, x_ref)
    for fj, back in (
        (BD.factor_jacobian, BD.ldl_solve_backward),
        (BD.factor_jacobian_py, BD.ldl_solve_backward_py),
    ):
        f = ab.copy()
        x = b.copy()
        assert fj(f, 0.9, mass, 40.0, fixed, x) == neg_ref
        np.testing.assert_array_equal(f, ref)
        back(f, x)
        np.testing.assert_array_equal(x, x_ref)


def _form_copy(ab, mass, fixed):
    c = ab.copy()
    _form(c, 0.9, mass, 40.0, fixed)
    return c


@pytest.mark.parametrize("n", [12, 60, 200])
def test_negative_pivots_are_the_negative_eigenvalues(n):
    for seed in range(3):
        ab = _band(n, 5, np.random.default_rng(100 * n + seed), spd=False)
        n_eig = int(np.sum(np.linalg.eigvalsh(_dense(ab)) < 0.0))
        assert BD.ldl_factor(ab.copy()) == n_eig


@pytest.mark.parametrize("n", [6, 11, 12, 60, 200])
@pytest.mark.parametrize("spd", [True, False])
def test_solve_within_the_residual_bound_and_like_scipy(n, spd):
    rng = np.random.default_rng(3 * n + spd)
    w = 5
    ab = _band(n, w, rng, spd)
    a = _dense(ab)
    b = rng.normal(size=n)
    f = ab.copy()
    BD.ldl_factor(f)
    x = b.copy()
    BD.ldl_solve(f, x)
    xp = b.copy()
    BD.ldl_solve_py(f, xp)
    np.testing.assert_array_equal(x, xp)
    # componentwise residual bound of the computed factor and solve
    lo, d = _factors(f)
    ldl = np.abs(lo) @ np.diag(np.abs(d)) @ np.abs(lo.T)
    m = 4 * (w + 2)
    gamma = m * EPS / (1.0 - m * EPS)
    assert np.all(np.abs(b - a @ x) <= gamma * (ldl @ np.abs(x)) + 4 * EPS * np.abs(b))
    # the ascending-order solve of the same factor: equal within the same bound's scale
    x_ref = _reference_solve(f, b)
    cond = np.linalg.cond(a, np.inf)
    assert np.max(np.abs(x - x_ref)) <= 4 * gamma * cond * np.max(np.abs(x_ref))
    if spd:
        upper = np.zeros((w + 1, n))  # scipy's upper form: upper[w + i − j, j] = A[i, j]
        for i in range(n):
            for k in range(min(w + 1, i + 1)):
                upper[w - k, i] = ab[i, k]
        x_sp = scipy.linalg.solveh_banded(upper, b)
    else:
        x_sp = np.linalg.solve(a, b)
    np.testing.assert_allclose(x, x_sp, rtol=0.0, atol=100 * EPS * cond * np.max(np.abs(x_sp)))


def test_solve_of_the_pipeline_size_against_the_old_order():
    """1503 DOFs (the 500-element benchmark): the solution differs from the ascending-order
    solve by round-off only (relative 1e-12 at most on these conditioned matrices)."""
    rng = np.random.default_rng(45)
    for spd in (True, False):
        ab = _band(1503, 5, rng, spd)
        f = ab.copy()
        BD.ldl_factor(f)
        b = rng.normal(size=1503)
        x = b.copy()
        BD.ldl_solve(f, x)
        x_ref = _reference_solve(f, b)
        assert np.max(np.abs(x - x_ref)) <= 1e-12 * np.max(np.abs(x_ref))
