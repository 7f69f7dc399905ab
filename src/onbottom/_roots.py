"""Bracketed scalar root finding by Brent's method, without scipy (private).

:func:`brentq` is Brent's (1973) procedure *zero*: inverse quadratic interpolation, the secant
step and bisection, with Brent's safeguard that falls back to bisection whenever the
interpolated step is poor, so it never takes more than about (log₂(|b − a|/tol))² steps and
usually a few. Reference: R. P. Brent, *Algorithms for Minimization without Derivatives*,
Prentice-Hall 1973, ch. 4 (procedure *zero*).

It is here so that the DNV-RP-F109 design solve (``onbottom stability``) does not import
``scipy.optimize`` (whose import would be most of the command's start-up). It stops on the
same criterion as ``scipy.optimize.brentq`` (a bracket narrower than ``xtol + rtol·|x|``)
but takes its own steps, so the two may return different points of that bracket
(``tests/unit/test_roots.py`` compares them).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable

__all__ = ["brentq"]

_EPS = sys.float_info.epsilon


def brentq(
    f: Callable[[float], float],
    a: float,
    b: float,
    *,
    xtol: float = 2e-12,
    rtol: float = 4.0 * _EPS,
    maxiter: int = 100,
) -> float:
    """A root of ``f`` in [a, b], where f(a) and f(b) differ in sign (or one is zero).

    Parameters
    ----------
    f
        A continuous function of one float (units of ``a`` and ``b`` in, any unit out).
    a, b
        The bracket [same unit as the root].
    xtol, rtol
        The returned x lies in a bracket of the root narrower than ``xtol + rtol·|x|``
        (``xtol`` in the unit of x, > 0; ``rtol`` ≥ 4·machine epsilon). Defaults as
        ``scipy.optimize.brentq``.
    maxiter
        Largest number of steps (each one evaluation of ``f``).

    Raises
    ------
    ValueError
        f(a) and f(b) have the same sign, f gave NaN, or a tolerance is out of range.
    RuntimeError
        No convergence within ``maxiter`` steps.
    """
    if not xtol > 0.0:
        raise ValueError(f"xtol = {xtol!r} is invalid: must be > 0")
    if not rtol >= 4.0 * _EPS:
        raise ValueError(f"rtol = {rtol!r} is invalid: must be >= {4.0 * _EPS!r}")
    a, b = float(a), float(b)
    fa, fb = float(f(a)), float(f(b))
    if math.isnan(fa) or math.isnan(fb):
        raise ValueError("f gave NaN at an end of the bracket")
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0):
        raise ValueError("f(a) and f(b) must have different signs")
    # c: the point that brackets the root with b; b: the best estimate; a: the previous b
    c, fc = a, fa
    d = e = b - a
    for _ in range(maxiter):
        if (fb > 0.0) == (fc > 0.0):
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 0.5 * (xtol + rtol * abs(b))
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return b
        if abs(e) < tol or abs(fa) <= abs(fb):
            d = e = m  # bisection
        else:
            s = fb / fa
            if a == c:  # secant
                p = 2.0 * m * s
                q = 1.0 - s
            else:  # inverse quadratic interpolation
                q = fa / fc
                r = fb / fc
                p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            e_old, e = e, d
            if 2.0 * p < 3.0 * m * q - abs(tol * q) and p < abs(0.5 * e_old * q):
                d = p / q
            else:
                d = e = m
        a, fa = b, fb
        b += d if abs(d) > tol else math.copysign(tol, m)
        fb = float(f(b))
        if math.isnan(fb):
            raise ValueError(f"f gave NaN at x = {b!r}")
    raise RuntimeError(f"no convergence in {maxiter} steps (last x = {b!r})")
