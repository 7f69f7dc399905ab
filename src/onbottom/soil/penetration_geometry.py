"""Contact geometry of a partially embedded pipe (DNVGL-RP-F114 §4.2, as cited in §3.1 of the
project's reference notes).

Symbols
-------
D      outer diameter of the pipe [m]
z      penetration (embedment) of the pipe invert below the original seabed [m], >= 0
B      chord (contact) width at the seabed level [m]
A_bm   penetrated cross-sectional area below the original seabed [m²]

Equations (DNVGL-RP-F114, May 2017; third-party transcription, see docs/theory/dnv_rp_f114.md)::

    B    = 2·√(D·z − z²)                                    z <  D/2
    B    = D                                                z >= D/2
    A_bm = asin(B/D)·D²/4 − B·(D/4)·cos(asin(B/D))          z <  D/2
    A_bm = π·D²/8 + D·(z − D/2)                             z >= D/2

The segment is evaluated as ``(D²/4)·(α − sin α·cos α)`` with ``α = atan2(B/D, 1 − 2z/D)``,
algebraically identical to the asin form above (α = asin(B/D) for z <= D/2).
For ``z >= D/2`` the area counts the whole displaced soil column above the pipe's widest
section (the standard's convention), not only the immersed part of the pipe. Both functions are
continuous at ``z = D/2`` (B = D, A_bm = πD²/8) and vanish at ``z = 0``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import positive
from onbottom.errors import InputError

__all__ = ["as_penetration", "contact_width", "penetrated_area"]


def as_penetration(z: ArrayLike, diameter: float, *, field: str = "z") -> NDArray[np.float64]:
    """Validate penetrations ``0 <= z <= D`` and return them as a float array.

    Parameters
    ----------
    z : array_like
        Penetration of the pipe invert [m].
    diameter : float
        Outer diameter D [m], > 0.
    field : str
        Name used in the error message.

    Raises
    ------
    InputError
        If any ``z`` is not finite or lies outside ``[0, D]`` (the F114 expressions are for a
        partially embedded pipe).
    """
    d = positive("diameter", diameter)
    arr = np.asarray(z, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{field} contains non-finite values: expected finite penetrations [m]")
    if arr.size and (arr.min() < 0.0 or arr.max() > d * (1.0 + 1e-12)):
        bad = float(arr.min() if arr.min() < 0.0 else arr.max())
        raise InputError(
            f"{field} = {bad!r} m is invalid: must lie in [0, D] = [0, {d:g}] m "
            "(partially embedded pipe)"
        )
    return np.minimum(arr, d)


def contact_width(z: ArrayLike, diameter: float) -> NDArray[np.float64]:
    """Contact (chord) width B(z) [m] of a pipe penetrated by ``z``.

    Parameters
    ----------
    z : array_like
        Penetration of the invert [m], ``0 <= z <= D``.
    diameter : float
        Outer diameter D [m], > 0.

    Returns
    -------
    ndarray
        B [m], same shape as ``z``: ``2·√(D·z − z²)`` below ``D/2``, ``D`` from ``D/2`` on
        (DNVGL-RP-F114 §4.2).
    """
    zz = as_penetration(z, diameter)
    d = float(diameter)
    half = zz < 0.5 * d
    chord = 2.0 * np.sqrt(np.maximum(d * zz - zz * zz, 0.0))
    return np.where(half, chord, d)


def penetrated_area(z: ArrayLike, diameter: float) -> NDArray[np.float64]:
    """Penetrated (displaced) cross-sectional area A_bm(z) [m²].

    Parameters
    ----------
    z : array_like
        Penetration of the invert [m], ``0 <= z <= D``.
    diameter : float
        Outer diameter D [m], > 0.

    Returns
    -------
    ndarray
        A_bm [m²]: the circular segment below the seabed for ``z < D/2``; for ``z >= D/2`` the
        half circle plus the rectangle ``D·(z − D/2)`` (DNVGL-RP-F114 §4.2).
    """
    zz = as_penetration(z, diameter)
    d = float(diameter)
    b = contact_width(zz, d)
    # half-angle α of the wetted arc: sin α = B/D, cos α = 1 − 2z/D. arctan2 keeps full
    # precision near z = D/2, where asin(B/D) of the textbook form loses half the digits.
    cos_a = 1.0 - 2.0 * zz / d
    angle = np.arctan2(b / d, cos_a)
    segment = (d * d / 4.0) * (angle - (b / d) * cos_a)
    deep = np.pi * d * d / 8.0 + d * (zz - 0.5 * d)
    return np.where(zz < 0.5 * d, segment, deep)
