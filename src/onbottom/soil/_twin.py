"""Plain-Python twins of numba kernels built from the same source (private).

A kernel's twin must give the same results with the Python interpreter. Keeping a second,
hand-written copy of a long algorithm in sync is error-prone, so :func:`pure_python` builds the
twin from the jitted function's own source (``py_func``) and rebinds every jitted helper it
calls, recursively, to its ``py_func``. The twin tests then compare numba's compiled semantics
(typing, integer/float conversions, branch order) with Python's on the same algorithm.
"""

from __future__ import annotations

import types
from collections.abc import Callable

from numba.core.dispatcher import Dispatcher

__all__ = ["pure_python"]


def pure_python(fn: Callable, _memo: dict | None = None) -> Callable:
    """Return ``fn`` with every jitted function it reaches rebound to plain Python.

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
