"""Scalar-output functions for parametric sweeps, and the registry ``onbottom sweep`` uses.

Each function takes keyword arguments (the swept and fixed parameters) and returns a mapping
of scalar outputs, the form :func:`onbottom.study.sweep.sweep` expects.

A sweep file names its function; only functions *registered by name* here can be run — a
data file never imports anything (``"subprocess:getoutput"`` is just an unknown name). Built-in:
``centrifuge_response`` (below) and ``misfit`` (registered by
:mod:`onbottom.calibration.fit`). Register your own from Python::

    from onbottom.study.functions import register

    @register("my_response")
    def my_response(*, a: float, b: float) -> dict[str, float]: ...
"""

from __future__ import annotations

import difflib
import inspect
import math
import re
import warnings
from collections.abc import Callable
from typing import Any

from onbottom.dynamics.centrifuge import run_centrifuge_test
from onbottom.errors import InputError, OutOfRangeWarning

__all__ = [
    "centrifuge_response",
    "check_arguments",
    "get_function",
    "register",
    "registered",
]

_REGISTRY: dict[str, Callable[..., Any]] = {}
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_.-]*$")


def register(
    name: str, fn: Callable[..., Any] | None = None, *, replace: bool = False
) -> Callable[..., Any]:
    """Register ``fn`` under ``name`` for sweeps (usable as ``@register("name")``).

    ``name``: letters, digits, ``_ . -`` (no ``:``). Registering another function under a
    taken name raises unless ``replace`` is true.
    """
    if not isinstance(name, str) or not _NAME.match(name):
        raise InputError(
            f"function name {name!r} is invalid: use letters, digits, '_', '.', '-' (no ':')"
        )

    def deco(f: Callable[..., Any]) -> Callable[..., Any]:
        if not callable(f):
            raise InputError(f"register({name!r}) is invalid: {f!r} is not callable")
        old = _REGISTRY.get(name)
        if old is not None and old is not f and not replace:
            raise InputError(
                f"function name {name!r} is invalid: already registered (pass replace=True)"
            )
        _REGISTRY[name] = f
        return f

    return deco if fn is None else deco(fn)


def registered() -> tuple[str, ...]:
    """Names of the registered sweep functions."""
    return tuple(sorted(_REGISTRY))


def get_function(name: str) -> Callable[..., Any]:
    """The function registered as ``name``; never imports anything.

    Raises :class:`~onbottom.errors.InputError` naming ``sweep.function``, the registered
    names and the closest one.
    """
    fn = _REGISTRY.get(name) if isinstance(name, str) else None
    if fn is None:
        names = registered()
        msg = (
            f"sweep.function = {name!r} is invalid: not a registered function (registered:"
            f" {', '.join(names)}); sweeps run only functions registered by name"
            " (onbottom.study.functions.register), never code named in a data file"
        )
        close = difflib.get_close_matches(str(name), names, n=1, cutoff=0.6)
        if close:
            msg += f"; did you mean {close[0]!r}?"
        raise InputError(msg)
    return fn


def check_arguments(fn: Callable[..., Any], names: list[str], *, where: str) -> None:
    """Raise if ``fn`` takes no keyword argument called one of ``names``."""
    try:
        params = inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values()):
        return
    allowed = [
        n
        for n, p in params.items()
        if p.kind in (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
        and n != "rng"
    ]
    for n in names:
        if n not in allowed:
            msg = (
                f"{where}.{n} is invalid: the function takes no argument {n!r} (allowed:"
                f" {', '.join(allowed)})"
            )
            close = difflib.get_close_matches(n, allowed, n=1, cutoff=0.6)
            if close:
                msg += f"; did you mean {close[0]!r}?"
            raise InputError(msg)


def centrifuge_response(
    *,
    test: str = "Inclined 1",
    A: float | None = None,
    B: float | None = None,
    C: float | None = None,
    mu: float | None = None,
    gamma: float | None = None,
    dt: float | None = None,
) -> dict[str, float]:
    """Response of one centrifuge test preset to A, B, C, μ, γ' (section solver).

    Parameters
    ----------
    test : str
        Preset name ("Inclined 1" ... "Irregular"); see :mod:`onbottom.dynamics.centrifuge`.
    A, B, C, mu : float or None
        Verley & Sotberg calcareous factors and friction coefficient [-]; None = the test's
        Table 2 value.
    gamma : float or None
        Submerged unit weight γ' [N/m³]; None = the preset default.
    dt : float or None
        Largest time step [s]; None = the preset default.

    Returns
    -------
    dict
        ``initial_penetration``, ``max_penetration``, ``max_abs_displacement`` [m],
        ``final_time`` [s], ``time_to_limit`` [s] and ``cycles_to_limit`` [-] (NaN if the
        limit was not reached), ``success`` (1/0). Out-of-range warnings of the soil
        correlations are counted in ``n_warnings`` rather than raised.
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        res = run_centrifuge_test(test, A=A, B=B, C=C, mu=mu, gamma=gamma, dt=dt)
    out = {k: float(v) for k, v in res.summary.items()}
    out["time_to_limit"] = math.nan if res.time_to_limit is None else float(res.time_to_limit)
    out["cycles_to_limit"] = math.nan if res.cycles_to_limit is None else float(res.cycles_to_limit)
    out["success"] = float(res.success)
    out["n_warnings"] = float(len(caught))
    return out


register("centrifuge_response", centrifuge_response)
