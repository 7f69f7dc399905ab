"""Numba helpers shared by the trough-based passive models (V&S sand, V&L clay) (private)."""

from __future__ import annotations

from numba import njit

__all__ = ["envelope", "overlap", "region_of", "sign"]

PHASE_TROUGH = 0.0
"""Pipe inside its trough; the peak displacement has not been passed."""
PHASE_BREAKOUT = 1.0
"""Peak displacement passed, residual displacement not passed: the pipe climbs out."""
PHASE_OUT = 2.0
"""Residual displacement passed: out of the trough until the next reversal."""


@njit(cache=True)
def envelope(a, fr1, fr2, fr3, y1, y2, y3):
    """Passive envelope magnitude and slope at distance ``a`` = |u − y0| from the trough centre.

    Piecewise linear through (0, 0), (y1, fr1), (y2, fr2), (y3, fr3), constant beyond y3;
    requires 0 < y1 <= y2 < y3 (a zero-length segment is skipped).
    """
    if a <= y1:
        k = fr1 / y1
        return k * a, k
    if a <= y2:
        k = (fr2 - fr1) / (y2 - y1)
        return fr1 + k * (a - y1), k
    if a <= y3:
        k = (fr3 - fr2) / (y3 - y2)
        return fr2 + k * (a - y2), k
    return fr3, 0.0


@njit(cache=True)
def overlap(a, b, lo, hi):
    """Length of the segment between ``a`` and ``b`` that lies inside [lo, hi]."""
    lo2 = max(min(a, b), lo)
    hi2 = min(max(a, b), hi)
    if hi2 > lo2:
        return hi2 - lo2
    return 0.0


@njit(cache=True)
def sign(x):
    """Sign of ``x`` as a float (0 for 0)."""
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return 0.0


@njit(cache=True)
def region_of(a, y1, y2, y3):
    """Region code 1–4 of the distance ``a`` from the trough centre."""
    if a <= y1:
        return 1.0
    if a <= y2:
        return 2.0
    if a <= y3:
        return 3.0
    return 4.0
