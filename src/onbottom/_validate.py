"""Uniform input checks: every failure names the field, the value and the allowed range."""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable
from numbers import Integral, Real

from onbottom.errors import InputError, OutOfRangeWarning

__all__ = [
    "FRICTION_COEFFICIENT",
    "PIPE_DIAMETER_M",
    "SOIL_UNIT_WEIGHT_N_M3",
    "file_token",
    "finite",
    "header_mismatch",
    "in_range",
    "integer",
    "non_negative",
    "one_of",
    "plausible",
    "positive",
    "warn_outside",
]


def _number(field: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InputError(f"{field} = {value!r} is invalid: expected a real number")
    x = float(value)
    if math.isnan(x):
        raise InputError(f"{field} = nan is invalid: expected a finite real number")
    return x


def finite(field: str, value: object) -> float:
    """Return ``value`` as float; raise :class:`InputError` unless it is a finite real."""
    x = _number(field, value)
    if not math.isfinite(x):
        raise InputError(f"{field} = {x!r} is invalid: expected a finite real number")
    return x


def positive(field: str, value: object) -> float:
    """Return ``value`` as float; raise unless it is finite and > 0."""
    x = finite(field, value)
    if x <= 0.0:
        raise InputError(f"{field} = {x!r} is invalid: must be > 0 (allowed range (0, inf))")
    return x


def non_negative(field: str, value: object) -> float:
    """Return ``value`` as float; raise unless it is finite and >= 0."""
    x = finite(field, value)
    if x < 0.0:
        raise InputError(f"{field} = {x!r} is invalid: must be >= 0 (allowed range [0, inf))")
    return x


def in_range(
    field: str,
    value: object,
    low: float,
    high: float,
    *,
    low_inclusive: bool = True,
    high_inclusive: bool = True,
) -> float:
    """Return ``value`` as float; raise unless ``low <= value <= high`` (bounds as chosen)."""
    x = _number(field, value)
    lo_ok = x >= low if low_inclusive else x > low
    hi_ok = x <= high if high_inclusive else x < high
    if not (lo_ok and hi_ok):
        lb = "[" if low_inclusive else "("
        hb = "]" if high_inclusive else ")"
        raise InputError(f"{field} = {x!r} is invalid: must lie in {lb}{low:g}, {high:g}{hb}")
    return x


def integer(field: str, value: object, low: int | None = None, high: int | None = None) -> int:
    """Return ``value`` as int; raise unless it is a whole number in ``[low, high]``.

    ``16.0`` is accepted, ``16.7`` is an error (never truncated), as are booleans and NaN.
    """
    if isinstance(value, bool):
        raise InputError(f"{field} = {value!r} is invalid: expected a whole number")
    if isinstance(value, Integral):
        n = int(value)
    else:
        x = finite(field, value)
        if x != math.floor(x):
            raise InputError(
                f"{field} = {x!r} is invalid: expected a whole number (it is never truncated)"
            )
        n = int(x)
    if (low is not None and n < low) or (high is not None and n > high):
        lo = "-inf" if low is None else str(low)
        hi = "inf" if high is None else str(high)
        raise InputError(f"{field} = {n} is invalid: must lie in [{lo}, {hi}]")
    return n


def plausible(
    field: str,
    value: object,
    *,
    error: tuple[float, float],
    usual: tuple[float, float],
    unit: str,
    what: str,
    stacklevel: int = 3,
) -> float:
    """Engineering plausibility of an input: an error outside ``error``, a warning outside
    ``usual``.

    ``error`` bounds are inclusive; a value outside them is no engineering input (a pipe of
    500 m, a unit weight of 0.0075 kN/m³ typed in the wrong unit): :class:`InputError` naming
    the field, the value, the allowed range and the unit. A value inside ``error`` but outside
    ``usual`` gives :class:`OutOfRangeWarning` (``what`` says what the usual range is).
    """
    x = finite(field, value)
    lo, hi = error
    if not (lo <= x <= hi):
        raise InputError(
            f"{field} = {x!r} {unit} is invalid: must lie in the plausible range"
            f" [{lo:g}, {hi:g}] {unit} (check the unit)"
        )
    ulo, uhi = usual
    if not (ulo <= x <= uhi):
        warnings.warn(
            f"{field} = {x:.4g} {unit} is unusual: {what} lies in [{ulo:g}, {uhi:g}] {unit}",
            OutOfRangeWarning,
            stacklevel=stacklevel,
        )
    return x


# Engineering plausibility ranges (error range, usual range) shared by the inputs.
PIPE_DIAMETER_M = ((0.005, 5.0), (0.05, 2.0))
"""Outer diameter D [m]: errors outside 5 mm–5 m (mm typed as m); usual 0.05–2 m (pipelines
and their coatings; a model pipe of a laboratory test can be smaller)."""
SOIL_UNIT_WEIGHT_N_M3 = ((1.0e3, 2.5e4), (3.0e3, 1.8e4))
"""Submerged (effective) unit weight γ' [N/m³]: errors below 1 or above 25 kN/m³ (kN typed
as N); usual 3–18 kN/m³ (submerged soils ~4–12; dry centrifuge sand up to ~17)."""
FRICTION_COEFFICIENT = ((0.0, 2.0), (0.1, 1.2))
"""Pipe–soil friction μ [-]: usual 0.1–1.2 (DNV-RP-F109: clay 0.2, sand 0.6)."""


def one_of(field: str, value: object, allowed: Iterable[str]) -> str:
    """Return ``value``; raise unless it is one of the ``allowed`` names."""
    options = tuple(allowed)
    if value not in options:
        raise InputError(
            f"{field} = {value!r} is invalid: must be one of {', '.join(map(repr, options))}"
        )
    return str(value)


def warn_outside(
    name: str, value: float, low: float, high: float, source: str, *, stacklevel: int = 3
) -> None:
    """Emit :class:`OutOfRangeWarning` if ``value`` is outside ``[low, high]``.

    ``source`` names the correlation whose calibration range is exceeded.
    """
    if not (low <= value <= high):
        warnings.warn(
            f"{name} = {value:.4g} is outside the calibration range [{low:g}, {high:g}] "
            f"of {source}; the result is an extrapolation",
            OutOfRangeWarning,
            stacklevel=stacklevel,
        )


_TOKEN_MAX = 12


def file_token(text: str, known: Iterable[str] = ()) -> str:
    """A cell of a data file fit for an error message: quoted when it is one of ``known`` or
    a close misspelling of one, or a short token of a column name or a number (at most
    :data:`_TOKEN_MAX` letters, digits, spaces and ``_ . + - / [ ] ^``); else only its length.
    Error messages never echo a file's content beyond that (a case file can name any file the
    user can read: a line such as /etc/passwd's must not reach a terminal or a log)."""
    import difflib
    import re

    t = str(text).strip()
    names = list(known)
    if t in names or difflib.get_close_matches(t, names, n=1, cutoff=0.75):
        return repr(t)
    if len(t) <= _TOKEN_MAX and re.fullmatch(r"[A-Za-z0-9_.+\-/\[\]^ ]*", t):
        return repr(t)
    return f"<{len(t)} characters>"


def header_mismatch(found: Iterable[str], expected: Iterable[str]) -> str:
    """Why a header line is not ``expected``, without echoing it (:func:`file_token`): the
    expected columns it lacks, the misspellings of expected ones it has, and how many other
    columns there are."""
    import difflib

    exp = list(expected)
    got = [str(c).strip() for c in found]
    parts = [f"{len(got)} column(s)"]
    missing = [c for c in exp if c not in got]
    if missing:
        parts.append(f"missing {', '.join(missing)}")
    near: list[str] = []
    other: list[str] = []
    for c in got:
        if c in exp:
            continue
        close = difflib.get_close_matches(c, exp, n=1, cutoff=0.75)
        if close:
            near.append(f"{c!r} (did you mean {close[0]!r}?)")
        else:
            other.append(file_token(c))
    if near:
        parts.append(", ".join(near))
    if other:
        parts.append(f"other column(s) {', '.join(other[:8])}")
    order = [c for c in got if c in exp]
    if not missing and not near and not other and order != exp:
        parts.append("the columns are in another order")
    return "; ".join(parts)
