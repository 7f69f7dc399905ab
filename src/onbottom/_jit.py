"""The project's numba decorator for hot-loop kernels (private).

:func:`njit` is :func:`numba.njit` with ``error_model="numpy"`` unless the caller says
otherwise: a float division by zero gives ±inf or NaN (IEEE 754), as numpy does, instead of
numba's default Python error model, which tests every divisor and raises ZeroDivisionError,
and makes every call between kernels check an exception status. The kernels never rely on
that exception (each solver checks its results for finiteness), and the tests and checks
cost 30–45 % of a soil kernel call (issue 33: Coulomb kernel 70 → 38 ns, V&S 0.17 →
0.12 µs per node call). Results are bit-identical wherever no division by zero occurs.

Kernel modules import it in place of numba's: ``from onbottom._jit import njit``. numba is
imported when this module is, i.e. only with a kernel module.
"""

from __future__ import annotations

import numba

__all__ = ["njit"]


def njit(*args, **kwargs):
    """:func:`numba.njit` with ``error_model="numpy"`` by default (same call forms)."""
    kwargs.setdefault("error_model", "numpy")
    return numba.njit(*args, **kwargs)
