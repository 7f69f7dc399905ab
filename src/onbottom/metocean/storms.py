"""Storms: peaks over a threshold, declustered (Coles 2001, §4.3 and §5.3.2).

A *storm* is a cluster of exceedances of the threshold u; two exceedances belong to the same
storm when less than the declustering time r separates them (runs declustering: a new storm
starts after more than r with no exceedance). Each storm contributes its peak. The peaks are
close to independent when r exceeds the correlation time of the sea states (typically 24–72 h
for H_s) — which makes the generalised Pareto model of the excesses usable (Coles 2001,
Theorem 4.1). The definition is the one of pyextremes' ``get_extremes(method="POT")`` (the
twin test checks it); this module adds threshold choice by a target storm rate and
directional sectors.

Directional storms (Forristall 2004, "On the use of directional wave criteria"): the series
of sector k keeps H_s where the wave direction lies in sector k and is 0 elsewhere; each
sector's storms are the declustered peaks of that series, so a storm that turns through two
sectors counts once in each with its largest H_s there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from onbottom._validate import in_range, integer, positive
from onbottom.errors import InputError

__all__ = [
    "Storms",
    "decluster",
    "sector_edges",
    "sector_mask",
    "storm_peaks",
    "threshold_for_rate",
]


@dataclass(frozen=True, eq=False, slots=True)
class Storms:
    """Declustered storm peaks of one series.

    Attributes
    ----------
    index : ndarray of int
        Sample index of each storm's peak.
    peak : ndarray
        Peak value of each storm (units of the series).
    threshold : float
        u (units of the series).
    r_hours : float
        Declustering time r [h].
    years : float
        Length of the record [years].
    """

    index: np.ndarray
    peak: np.ndarray
    threshold: float
    r_hours: float
    years: float

    @property
    def rate(self) -> float:
        """Mean number of storms per year, λ [1/year]."""
        return len(self.peak) / self.years


def decluster(
    values: np.ndarray, step_hours: float, threshold: float, r_hours: float
) -> np.ndarray:
    """Indices of the storm peaks of an evenly sampled series (runs declustering).

    Exceedances are values strictly above ``threshold``; a new cluster starts when the time
    since the previous exceedance is more than ``r_hours``. Returns the index of each
    cluster's largest value (the first, on ties).
    """
    v = np.asarray(values, dtype=float)
    exc = np.flatnonzero(v > threshold)
    if exc.size == 0:
        return exc
    gap = np.diff(exc) * step_hours > r_hours
    starts = np.concatenate(([0], np.flatnonzero(gap) + 1))
    # cluster maxima: reduceat on the values, then the first index reaching it
    peaks = np.maximum.reduceat(v[exc], starts)
    ends = np.concatenate((starts[1:], [exc.size]))
    out = np.empty(starts.size, dtype=np.int64)
    for k, (a, b) in enumerate(zip(starts, ends, strict=True)):
        seg = exc[a:b]
        out[k] = seg[np.argmax(v[seg] == peaks[k])]
    return out


def storm_peaks(
    values: np.ndarray, step_hours: float, threshold: float, r_hours: float, years: float
) -> Storms:
    """:class:`Storms` of ``values`` above ``threshold`` declustered with ``r_hours``."""
    positive("r_hours", r_hours)
    idx = decluster(values, step_hours, threshold, r_hours)
    return Storms(
        index=idx,
        peak=np.asarray(values, dtype=float)[idx],
        threshold=float(threshold),
        r_hours=float(r_hours),
        years=float(years),
    )


def threshold_for_rate(
    values: np.ndarray, step_hours: float, r_hours: float, years: float, rate: float
) -> float:
    """A threshold u with about ``rate`` declustered storms per year (at most rate·years).

    The storm count is not monotone in u (a low threshold merges everything into a few long
    clusters), so the search comes down from the top: the k-th largest distinct value for
    k = 1, 2, 4, … until the count first exceeds rate·years, then bisection between the last
    two k. Returns the lowest threshold found whose count does not exceed the target.
    """
    positive("rate", rate)
    v = np.asarray(values, dtype=float)
    cand = np.unique(v[v > 0.0])[::-1]  # descending
    if cand.size < 2:
        raise InputError("threshold_for_rate: the series has fewer than 2 positive values")
    target = rate * years

    def count(k: int) -> int:
        return decluster(v, step_hours, cand[k], r_hours).size

    ok, k = 0, 1
    while k < cand.size and count(k) <= target:
        ok, k = k, 2 * k
    if k >= cand.size:
        k = cand.size - 1
        if count(k) <= target:
            return float(cand[k])
    while k - ok > 1:  # count(ok) <= target < count(k)
        mid = (ok + k) // 2
        if count(mid) <= target:
            ok = mid
        else:
            k = mid
    return float(cand[ok])


def sector_edges(n_sectors: int) -> tuple[np.ndarray, np.ndarray]:
    """Centres and half-width of ``n_sectors`` equal sectors, the first centred on north.

    Returns (centres [deg], half width [deg]); sector k covers
    [centre_k − w, centre_k + w) modulo 360.
    """
    n = integer("sectors", n_sectors, 1, 36)
    width = 360.0 / n
    return np.arange(n) * width, np.full(n, width / 2.0)


def sector_mask(direction_deg: np.ndarray, n_sectors: int, k: int) -> np.ndarray:
    """Boolean mask of the samples whose direction lies in sector ``k`` of ``n_sectors``."""
    n = integer("sectors", n_sectors, 1, 36)
    in_range("sector", k, 0, n - 1)
    if n == 1:
        return np.ones(np.shape(direction_deg), dtype=bool)
    width = 360.0 / n
    rel = np.mod(np.asarray(direction_deg, dtype=float) + width / 2.0, 360.0)
    return np.floor(rel / width).astype(np.int64) == k
