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

:func:`pure_python` builds a kernel's plain-Python twin from the kernel's own source; it lives
here, in a base module, so that the kernels of every package (soil, hydro, dynamics) share it.
"""

from __future__ import annotations

import operator
import types
from collections.abc import Callable

import numba
from numba.core.dispatcher import Dispatcher

__all__ = ["call_literal", "njit", "pure_python"]


def njit(*args, **kwargs):
    """:func:`numba.njit` with ``error_model="numpy"`` by default (same call forms)."""
    kwargs.setdefault("error_model", "numpy")
    return numba.njit(*args, **kwargs)


def call_literal(kernel, n_literal, *args):
    """Call ``kernel(*args)`` with its first ``n_literal`` arguments (ints) as numba literals.

    For kernels that call ``numba.literally`` on those arguments (model ids: the kernel then
    compiles only the models used, issue 33). Called from Python, such a kernel first types
    its arguments as plain ints, raises inside numba and is retyped with literals; numba does
    not remember that, and pays it again on every call (~0.05–0.3 s for a storm kernel). Here
    the literal signature is built directly: the specialisation is compiled (or loaded from
    numba's on-disk cache) once per process and called through its entry point. ``kernel`` a
    plain Python function (a test's ``py_func``) is just called.
    """
    overloads = getattr(kernel, "overloads", None)
    if overloads is None:
        return kernel(*args)
    sig = tuple(
        numba.types.literal(operator.index(a)) if i < n_literal else kernel.typeof_pyval(a)
        for i, a in enumerate(args)
    )
    cres = overloads.get(sig)
    if cres is None:
        kernel.compile(sig)
        cres = overloads[sig]
    return cres.entry_point(*args)


def pure_python(fn: Callable, _memo: dict | None = None) -> Callable:
    """Return ``fn`` with every jitted function it reaches rebound to plain Python.

    A kernel's twin must give the same results with the Python interpreter. Keeping a second,
    hand-written copy of a long algorithm in sync is error-prone, so this builds the twin from
    the jitted function's own source (``py_func``) and rebinds every jitted helper it calls,
    recursively, to its ``py_func``. The twin tests then compare numba's compiled semantics
    (typing, integer/float conversions, branch order) with Python's on the same algorithm.

    ``fn`` is a numba dispatcher (or a Python function). Helpers reached through module
    globals are rebound recursively; the original functions are left untouched.
    """
    memo = {} if _memo is None else _memo
    py = fn.py_func if isinstance(fn, Dispatcher) else fn
    if py in memo:
        return memo[py]
    glb = dict(py.__globals__)
    twin = types.FunctionType(py.__code__, glb, py.__name__ + "_py", py.__defaults__)
    twin.__doc__ = f"Plain-Python twin of :func:`{py.__name__}`."
    memo[py] = twin
    for name in py.__code__.co_names:
        obj = glb.get(name)
        if isinstance(obj, Dispatcher):
            glb[name] = pure_python(obj, memo)
    return twin
