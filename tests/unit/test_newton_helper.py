"""Unit test: the safeguarded Newton iterate shared by the section and storm kernels."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics._newton import safeguarded_update


def _solve(update, c, x_hat, force, resist, tangent, eps=1e-15, max_iter=60):
    """The kernels' loop around the iterate: r(x) = c (x − x̂) + R(x) − F."""
    lo = hi = 0.0
    have_lo = have_hi = False
    x = x_hat
    for _ in range(max_iter):
        r = c * (x - x_hat) + resist(x) - force
        if abs(r) <= 1e-12 * (abs(force) + 1.0):
            return x
        x_next, lo, hi, have_lo, have_hi, closed = update(
            x, r, c, tangent(x), lo, hi, have_lo, have_hi, eps
        )
        if closed:
            return x
        x = x_next
    raise AssertionError("no convergence")


def _coulomb(mu_v=1.0, k=1e3):
    # elastic-perfectly plastic: R = k x up to mu_v, then mu_v (a kink: Newton alone cycles)
    return (lambda x: max(-mu_v, min(mu_v, k * x))), (lambda x: k if abs(k * x) < mu_v else 0.0)


@pytest.mark.parametrize("force", [0.3, 0.999, 1.5, -2.0])
def test_root_of_a_kinked_law(force):
    resist, tangent = _coulomb()
    c = 10.0
    x = _solve(safeguarded_update, c, 0.0, force, resist, tangent)
    # hand solution: elastic if |F| < mu V (x = F/(c + k)), else x = (F ∓ mu V)/c
    exact = (
        force / (c + 1e3)
        if abs(force) / (c + 1e3) * 1e3 < 1.0
        else (force - math.copysign(1.0, force)) / c
    )
    assert x == pytest.approx(exact, rel=1e-9, abs=1e-15)


def test_numba_equals_its_python_twin():
    rng = np.random.default_rng(0)
    for _ in range(200):
        x, r, c, t, lo, hi, eps = rng.normal(size=7)
        args = (
            x,
            r,
            abs(c) + 0.1,
            t,
            min(lo, hi),
            max(lo, hi),
            bool(lo > 0),
            bool(hi > 0),
            abs(eps),
        )
        assert safeguarded_update(*args) == safeguarded_update.py_func(*args)


def test_bracket_and_bisection():
    # a Newton point outside the bracket falls back to its midpoint
    x_next, lo, hi, have_lo, have_hi, closed = safeguarded_update(
        1.0, 5.0, 1.0, -0.5, 0.0, 2.0, True, False, 1e-12
    )
    assert (lo, hi, have_lo, have_hi, closed) == (0.0, 1.0, True, True, False)
    assert x_next == 0.5
    # a bracket narrower than eps: accept x
    assert safeguarded_update(1.0, 1.0, 1.0, 1.0, 1.0 - 1e-16, 2.0, True, False, 1e-12)[5]
