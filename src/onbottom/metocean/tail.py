"""What a GPD tail fit can be trusted with: a short-tail guard, the exponential alternative and
storms censored by data gaps.

**Tail guard.** A GPD with ξ < 0 has a finite end-point x_F = u − σ/ξ, and every return value
stays below it. Fitted from a few dozen storms, ξ̂ is uncertain by about ±0.2 (Coles 2001,
§4.4), so a strongly negative ξ̂ from a short record reads a sampling accident as a physical
limit: ten years of NDBC 44007 (1996–2005) give ξ̂ = −0.39 from 28 storms, an end-point of
7.75 m and a 100-year H_s of 7.44 m, while the next ten years held four storms above 7.75 m,
the largest 11.8 m. The guard warns when

* ξ̂ < :data:`SHORT_TAIL_SHAPE` (−0.2) from fewer than :data:`SHORT_TAIL_STORMS` (50) storms, or
* the fitted end-point lies within one σ̂ of the record's maximum (the data reach the bound
  the fit imposes),

and gives the ξ = 0 (exponential) fit beside it: σ̂ = Σy / n_exact (maximum likelihood, the
censored excesses included in the sum), x_R = u + σ̂ ln(λR), its interval from the profile
likelihood of σ (x_R is increasing in σ).

**Censored storms.** Buoys fail in storms: a gap of 12 h or more in the record starting at, or
right after, a storm's last exceedance means the storm's true peak may have come in the gap.
Such a storm's peak is a lower bound of its true peak: a right-censored observation. It
contributes the survival function, not the density, to the GPD likelihood
(:func:`onbottom.metocean.extremes._gpd_loglik`); the censored fit's maximum likelihood and
profile intervals use that likelihood. On the shipped NDBC record the largest storm (7.10 m,
followed by a 228-h gap) is censored, and the censored fit moves ξ̂ upward.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from onbottom.metocean.extremes import _gpd_loglik, gpd_return_level, profile_interval
from onbottom.metocean.storms import Storms

__all__ = [
    "GAP_HOURS",
    "SHORT_TAIL_SHAPE",
    "SHORT_TAIL_STORMS",
    "TailCheck",
    "censored_storms",
    "check_tail",
    "fit_censored_gpd",
]

SHORT_TAIL_SHAPE = -0.2
"""ξ̂ below which a fit from fewer than :data:`SHORT_TAIL_STORMS` storms is flagged."""

SHORT_TAIL_STORMS = 50
"""Storms below which a strongly negative ξ̂ is flagged."""

GAP_HOURS = 12.0
"""Shortest run of missing sea states [h] that censors a storm ending at it."""


def censored_storms(
    values: np.ndarray,
    observed: np.ndarray,
    step_hours: float,
    storms: Storms,
    gap_hours: float = GAP_HOURS,
) -> np.ndarray:
    """Boolean mask over ``storms.peak``: the storm's cluster ends at or next to a gap.

    Parameters
    ----------
    values : ndarray
        The series the storms were declustered from (missing values as 0 or NaN).
    observed : ndarray of bool
        Mask of the observed samples.
    step_hours : float
        Sampling step [h].
    storms : Storms
        The storms (runs declustering with ``storms.r_hours`` above ``storms.threshold``).
    gap_hours : float
        Shortest gap [h] that censors.
    """
    v = np.where(np.asarray(observed, dtype=bool), np.asarray(values, dtype=float), 0.0)
    miss = ~np.asarray(observed, dtype=bool)
    n = v.size
    # runs of missing samples: start index and length
    d = np.diff(np.concatenate(([0], miss.astype(np.int8), [0])))
    starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    long_starts = starts[(ends - starts) * step_hours >= gap_hours]
    exc = np.flatnonzero(v > storms.threshold)
    out = np.zeros(storms.peak.size, dtype=bool)
    if exc.size == 0 or long_starts.size == 0:
        return out
    gap = np.diff(exc) * step_hours > storms.r_hours
    c_first = exc[np.concatenate(([0], np.flatnonzero(gap) + 1))]
    c_last = exc[np.concatenate((np.flatnonzero(gap), [exc.size - 1]))]
    for k, peak_i in enumerate(storms.index):
        j = int(np.searchsorted(c_first, peak_i, side="right")) - 1
        if j < 0:
            continue
        a, b = c_first[j], min(c_last[j] + 1, n)  # a long gap starting in (a, b] censors
        out[k] = bool(np.any((long_starts > a) & (long_starts <= b)))
    return out


def fit_censored_gpd(
    excess: np.ndarray, censored: np.ndarray, start: tuple[float, float]
) -> tuple[float, float]:
    """Maximum-likelihood (σ, ξ) of GPD excesses with right-censored ones (Nelder–Mead on
    (ln σ, ξ) from ``start``)."""
    from scipy.optimize import minimize

    y = np.asarray(excess, dtype=float)

    def neg(p: np.ndarray) -> float:
        ll = float(_gpd_loglik(y, np.array([math.exp(p[0])]), np.array([p[1]]), censored)[0])
        return -ll if math.isfinite(ll) else 1e300

    best = None
    for xi0 in (start[1], 0.0, 0.2):
        r = minimize(
            neg,
            np.array([math.log(start[0]), xi0]),
            method="Nelder-Mead",
            options={"xatol": 1e-9, "fatol": 1e-12, "maxiter": 4000},
        )
        if best is None or r.fun < best.fun:
            best = r
    assert best is not None
    return float(math.exp(best.x[0])), float(best.x[1])


def _exponential(
    y: np.ndarray, cens: np.ndarray, u: float, m: np.ndarray, confidence: float
) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    from scipy import stats
    from scipy.optimize import brentq

    n = int(y.size - np.count_nonzero(cens))
    s = float(y.sum())
    sig = s / n

    def ll(sg: float) -> float:
        return -n * math.log(sg) - s / sg

    crit = 0.5 * float(stats.chi2.ppf(confidence, 1))
    f = lambda sg: ll(sig) - ll(sg) - crit  # noqa: E731
    lo = brentq(f, sig * 1e-3, sig)
    hi = brentq(f, sig, sig * 1e3)
    lm = np.log(m)
    return sig, u + sig * lm, u + lo * lm, u + hi * lm


@dataclass(frozen=True)
class TailCheck:
    """The tail guard, the exponential alternative and the censored fit of one series.

    Attributes
    ----------
    storms : int
        Storms fitted.
    shape, scale, threshold : float
        The GPD fit checked (ξ̂ [-], σ̂ and u in the series' units).
    endpoint : float
        x_F = u − σ̂/ξ̂ for ξ̂ < 0, else inf.
    record_max : float
        Largest storm peak of the record.
    warnings : list of str
        Why the fit's tail should not be read as a design value (empty: none).
    return_periods : ndarray
        R [years].
    exponential_scale : float
        σ̂ of the ξ = 0 fit.
    exponential : ndarray (3, n)
        Its value, lower and upper bound per return period.
    censored : ndarray of bool
        Mask over the storms: censored by a gap.
    censored_peaks : list of (time, peak)
        The censored storms (ISO time, value).
    censored_fit : dict
        ``shape``, ``scale``, ``value``, ``lower``, ``upper`` of the fit with the censored
        peaks as censored (empty when none is).
    """

    storms: int
    shape: float
    scale: float
    threshold: float
    endpoint: float
    record_max: float
    warnings: list[str]
    return_periods: np.ndarray
    exponential_scale: float
    exponential: np.ndarray
    censored: np.ndarray
    censored_peaks: list[tuple[str, float]] = field(default_factory=list)
    censored_fit: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """Plain data (JSON)."""

        def f(v: float) -> float | None:
            return float(v) if math.isfinite(v) else None

        return {
            "storms": self.storms,
            "shape": f(self.shape),
            "scale": f(self.scale),
            "threshold": f(self.threshold),
            "endpoint": f(self.endpoint),
            "record_max": f(self.record_max),
            "warnings": list(self.warnings),
            "return_periods": [float(r) for r in self.return_periods],
            "exponential": {
                "scale": f(self.exponential_scale),
                "value": [f(v) for v in self.exponential[0]],
                "lower": [f(v) for v in self.exponential[1]],
                "upper": [f(v) for v in self.exponential[2]],
            },
            "censored_peaks": [[t, float(p)] for t, p in self.censored_peaks],
            "censored_fit": {
                k: (f(v) if np.isscalar(v) else [f(x) for x in v])
                for k, v in self.censored_fit.items()
            },
        }


def check_tail(
    levels,
    values: np.ndarray,
    observed: np.ndarray,
    time: np.ndarray,
    step_hours: float,
    rate: float,
    gap_hours: float = GAP_HOURS,
) -> TailCheck:
    """:class:`TailCheck` of a fit (:class:`~onbottom.metocean.extremes.ReturnLevels`) of the
    series ``values`` (NaN or ``observed`` False where missing), ``rate`` storms per year."""
    st = levels.storms
    rps = np.asarray(levels.return_periods, dtype=float)
    xi, sg, u = float(levels.shape), float(levels.scale), float(st.threshold)
    y = st.peak - u
    rmax = float(st.peak.max()) if st.peak.size else math.nan
    end = u - sg / xi if xi < 0.0 else math.inf
    warn = []
    if math.isfinite(xi) and xi < SHORT_TAIL_SHAPE and st.peak.size < SHORT_TAIL_STORMS:
        warn.append(
            f"short tail from a short record: xi = {xi:.2f} < {SHORT_TAIL_SHAPE} from"
            f" {st.peak.size} storms (< {SHORT_TAIL_STORMS}); the fit caps every return value"
            f" below its end-point {end:.3g}: compare the exponential (xi = 0) values"
        )
    if math.isfinite(end) and end - rmax < sg:
        warn.append(
            f"the fitted end-point {end:.3g} lies within one scale ({sg:.3g}) of the record's"
            f" largest storm {rmax:.3g}: the data reach the bound the fit imposes"
        )
    cens = censored_storms(values, observed, step_hours, st, gap_hours)
    m = rate * rps
    nanr = np.full((3, rps.size), np.nan)
    exp_s, expo = math.nan, nanr
    if st.peak.size >= 2:
        exp_s, v, lo, hi = _exponential(y, cens, u, m, levels.confidence)
        expo = np.vstack([v, lo, hi])
    tt = np.asarray(time).astype("datetime64[h]")
    peaks = [(str(tt[i]), float(p)) for i, p, c in zip(st.index, st.peak, cens, strict=True) if c]
    cfit: dict = {}
    if cens.any() and math.isfinite(xi):
        csg, cxi = fit_censored_gpd(y, cens, (sg, xi))
        val = gpd_return_level(rps, u, csg, cxi, rate)
        lo = np.empty(rps.size)
        hi = np.empty(rps.size)
        for i, mi in enumerate(m):
            _, a, b = profile_interval(y, mi, levels.confidence, mle=(csg, cxi), censored=cens)
            lo[i], hi[i] = u + a, u + b
        cfit = {"shape": cxi, "scale": csg, "value": val, "lower": lo, "upper": hi}
    return TailCheck(
        storms=int(st.peak.size),
        shape=xi,
        scale=sg,
        threshold=u,
        endpoint=end,
        record_max=rmax,
        warnings=warn,
        return_periods=rps,
        exponential_scale=exp_s,
        exponential=expo,
        censored=cens,
        censored_peaks=peaks,
        censored_fit=cfit,
    )
