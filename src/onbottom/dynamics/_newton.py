"""The safeguarded Newton iterate shared by the section and storm kernels (numba).

Both kernels solve one scalar equation per time step for the displacement increment x,

    r(x) = c·(x − x̂) + R(x) − F(x) = 0,

with c > 0 the inertia (and damping) coefficient and r increasing in x wherever the soil's
tangent is not too negative. :func:`safeguarded_update` is one iterate: it keeps the bracket
[lo, hi] of the root from the signs of r seen so far, takes the Newton step on the Jacobian
c + dR/dx when that is positive (else the step on c alone, always descending), and falls back
to bisection when the Newton point leaves the bracket. The residual itself — the soil kernel
alone (section) or the force model then the soil (storm) — stays in each kernel's loop.
Theory: docs/theory/section_dynamics.md ("Nonlinear solution"); tests: the plain-Python
twin (``safeguarded_update.py_func``) and hand solutions of a kinked, Coulomb-like law in
tests/unit/test_newton_helper.py.
"""

from __future__ import annotations

from onbottom._jit import jitted_only

__all__ = ["safeguarded_update"]


@jitted_only
def safeguarded_update(x, r, c, tangent, lo, hi, have_lo, have_hi, eps):
    """One safeguarded Newton iterate from ``x`` with residual ``r`` = r(x).

    Parameters: ``c`` the positive part of the Jacobian (inertia, damping) [N/m²], ``tangent``
    the soil's dR/dx at x [N/m²], ``lo``/``hi`` and ``have_lo``/``have_hi`` the bracket so far,
    ``eps`` the resolution of x [m].

    Returns ``(x_next, lo, hi, have_lo, have_hi, closed)``; ``closed`` is True when the
    bracket has shrunk to ``eps`` (a jump of R across the root, or the root resolved to the
    precision of x): accept ``x`` (then ``x_next`` is ``x``).
    """
    if r > 0.0:
        hi = x
        have_hi = True
    else:
        lo = x
        have_lo = True
    if have_lo and have_hi and (hi - lo) <= eps:
        return x, lo, hi, have_lo, have_hi, True
    jac = c + tangent
    if jac > 0.0:
        x_next = x - r / jac
    else:
        x_next = x - r / c
    if have_lo and have_hi:
        if not (lo < x_next < hi):
            x_next = 0.5 * (lo + hi)
    elif have_hi and x_next >= hi:
        x_next = x - r / c
    elif have_lo and x_next <= lo:
        x_next = x - r / c
    return x_next, lo, hi, have_lo, have_hi, False
