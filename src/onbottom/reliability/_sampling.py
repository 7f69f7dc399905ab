"""Sampling estimators of P[g(u) ≤ 0] in the standard normal space, with 95 % intervals.

``g`` takes an (n, d) array of standard normal coordinates u and returns n values (failure:
g ≤ 0); the caller maps u to the physical inputs. Every estimator returns a
:class:`SampleResult` with a confidence interval:

* Monte Carlo: Clopper–Pearson (exact binomial; Clopper & Pearson 1934). No failure: the
  one-sided upper bound 1 − α^(1/n) (≈ 3/n at 95 %), flagged as a bound. Every run failing:
  p = 1 with the interval [(α/2)^(1/n), 1].
* Importance sampling with a unit normal density centred on c (Melchers & Beck 2018 §5.4):
  the weights w = φ(u)/φ(u − c) are independent, so the sample mean of 1_F·w is unbiased and
  its standard error is the weights' sample standard deviation / √n; the interval is
  p̂ ± z·SE (normal), its lower end clipped at 0. The centre comes from a cross-entropy pilot
  (:func:`ce_centre`; Rubinstein & Kroese 2004; Kurtz & Song 2013, one Gaussian, mean only).
* Subset simulation (Au & Beck 2001) with conditional sampling (Papaioannou et al. 2015,
  correlation ρ = 0.8): levels of ``block`` samples, conditional probability p₀ = 0.1, a hard
  cap on the evaluations (a level that would overrun it is not started: the result is then the
  last level's probability, flagged as an upper bound). CV by Au & Beck (2001) Eqs. 27–29: the
  correlation of each level's Markov chains (γ_j) included, the correlation between the levels
  neglected; interval p̂·exp(±z·CV) (log-normal). The estimator is biased by O(1/N) (Au & Beck
  2001 §5): the coverage test in ``tests/verification`` measures what the interval is worth.

The conditional mean of u given failure (``failure_mean``) is the mean of the failing samples
(Monte Carlo, subset simulation's last level) or their weighted mean (importance sampling):
how many standard deviations each input stood from its median in the storms that failed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import special, stats

__all__ = [
    "SampleResult",
    "ce_centre",
    "clopper_pearson",
    "importance",
    "monte_carlo",
    "subset",
]

G = Callable[[np.ndarray], np.ndarray]


@dataclass
class SampleResult:
    """What a sampling estimator found (module docstring)."""

    probability: float
    cv: float
    low: float
    high: float
    interval_kind: str
    upper_bound: bool
    failures: int
    evaluations: int
    method: str
    converged: bool
    history: list[tuple[int, float, float]] = field(default_factory=list)
    levels: list[tuple[float, float]] = field(default_factory=list)
    failure_mean: np.ndarray | None = None


def _z(confidence: float) -> float:
    return float(special.ndtri(0.5 + 0.5 * confidence))


def clopper_pearson(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """Exact binomial interval of k failures in n runs; k = 0: (0, one-sided upper bound)."""
    a = 1.0 - confidence
    if n <= 0:
        return (0.0, 1.0)
    if k <= 0:
        return (0.0, float(-math.expm1(math.log(a) / n)))
    if k >= n:
        return (float(math.exp(math.log(0.5 * a) / n)), 1.0)
    return (
        float(stats.beta.ppf(0.5 * a, k, n - k + 1)),
        float(stats.beta.ppf(1.0 - 0.5 * a, k + 1, n - k)),
    )


def _mc_result(
    k: int, n: int, confidence: float, target_cv: float, u_fail_sum: np.ndarray, history
) -> SampleResult:
    lo, hi = clopper_pearson(k, n, confidence)
    if k == 0:  # no failure: the one-sided bound, flagged
        return SampleResult(
            hi, math.nan, 0.0, hi, "one-sided upper bound (no failure)", True, 0, n,
            "monte_carlo", False, history,
        )  # fmt: skip
    p = k / n
    cv = math.sqrt((1.0 - p) / (n * p))
    return SampleResult(
        p, cv, lo, hi, "Clopper-Pearson", False, k, n, "monte_carlo", cv <= target_cv,
        history, failure_mean=u_fail_sum / k,
    )  # fmt: skip


def monte_carlo(
    g: G,
    d: int,
    rng: np.random.Generator,
    block: int,
    n_max: int,
    target_cv: float,
    confidence: float = 0.95,
    first: tuple[np.ndarray, np.ndarray] | None = None,
) -> SampleResult:
    """Crude Monte Carlo in blocks until ``target_cv`` or ``n_max`` evaluations (``first``: an
    unbiased block already evaluated, (u, g), counted as the first block)."""
    n = k = 0
    u_sum = np.zeros(d)
    history: list[tuple[int, float, float]] = []
    while n < n_max:
        if first is not None:
            u, gv = first
            first = None
        else:
            m = min(block, n_max - n)
            u = rng.standard_normal((m, d))
            gv = g(u)
        fail = gv <= 0.0
        n += u.shape[0]
        k += int(np.count_nonzero(fail))
        u_sum += u[fail].sum(axis=0)
        p = k / n
        cv = math.sqrt((1.0 - p) / (n * p)) if k else math.inf
        history.append((n, p, cv))
        if cv <= target_cv:
            break
    return _mc_result(k, n, confidence, target_cv, u_sum, history)


def importance(
    g: G,
    d: int,
    rng: np.random.Generator,
    centre: np.ndarray,
    block: int,
    n_max: int,
    target_cv: float,
    confidence: float = 0.95,
) -> SampleResult:
    """Importance sampling with N(``centre``, I) in blocks until ``target_cv`` or ``n_max``."""
    c = np.asarray(centre, dtype=float)
    half = 0.5 * float(c @ c)
    n, s1, s2 = 0, 0.0, 0.0
    k = 0
    wu = np.zeros(d)
    history: list[tuple[int, float, float]] = []
    p = cv = math.nan
    while n < n_max:
        m = min(block, n_max - n)
        u = c + rng.standard_normal((m, d))
        fail = g(u) <= 0.0
        w = np.where(fail, np.exp(half - u @ c), 0.0)
        n += m
        k += int(np.count_nonzero(fail))
        s1 += float(w.sum())
        s2 += float((w * w).sum())
        wu += (w[:, None] * u).sum(axis=0)
        p = s1 / n
        var = max(0.0, (s2 / n - p * p) / max(n - 1, 1))
        cv = math.sqrt(var) / p if p > 0.0 else math.inf
        history.append((n, p, cv))
        if cv <= target_cv:
            break
    z = _z(confidence)
    if k == 0:
        return SampleResult(
            0.0, math.nan, 0.0, math.nan, "no failing sample (no estimate)", False, 0, n,
            "importance", False, history,
        )  # fmt: skip
    se = cv * p
    return SampleResult(
        p, cv, max(0.0, p - z * se), p + z * se, "normal, weights' standard error", False, k, n,
        "importance", cv <= target_cv, history, failure_mean=wu / s1,
    )  # fmt: skip


def ce_centre(
    g: G,
    d: int,
    rng: np.random.Generator,
    block: int,
    iterations: int,
    free: np.ndarray | None = None,
    rho: float = 0.1,
) -> tuple[np.ndarray, int, tuple[np.ndarray, np.ndarray], bool]:
    """Cross-entropy centre of importance sampling: ``iterations`` blocks at most, each moving
    the centre to the weighted mean of its ``rho`` fraction of smallest g (the failing samples
    once the ``rho`` quantile reaches 0). ``free``: mask of the coordinates that may move (the
    others stay at 0). Returns (centre, evaluations, the first block (u, g) — an unbiased
    Monte Carlo sample from the origin — and whether the quantile reached failure)."""
    c = np.zeros(d)
    mask = np.ones(d, dtype=bool) if free is None else np.asarray(free, dtype=bool)
    n = 0
    first: tuple[np.ndarray, np.ndarray] | None = None
    reached = False
    for _ in range(max(1, iterations)):
        u = c + rng.standard_normal((block, d))
        gv = g(u)
        n += block
        if first is None:
            first = (u, gv)
        level = max(0.0, float(np.quantile(gv, rho)))
        elite = gv <= level
        logw = 0.5 * float(c @ c) - u[elite] @ c
        w = np.exp(logw - logw.max())
        c = np.where(mask, (w[:, None] * u[elite]).sum(axis=0) / w.sum(), 0.0)
        if level <= 0.0:
            reached = True
            break
    assert first is not None
    return c, n, first, reached


def _chain_gamma(ind: np.ndarray, p: float) -> float:
    """γ of Au & Beck (2001) Eq. 29 for indicators ``ind`` (chains × steps)."""
    nc, ns = ind.shape
    n = nc * ns
    r0 = p * (1.0 - p)
    if ns < 2 or r0 <= 0.0:
        return 0.0
    x = ind.astype(float)
    gamma = 0.0
    for k in range(1, ns):
        rk = float(np.sum(x[:, : ns - k] * x[:, k:])) / (n - k * nc) - p * p
        gamma += 2.0 * (1.0 - k * nc / n) * rk / r0
    return max(0.0, gamma)


def subset(
    g: G,
    d: int,
    rng: np.random.Generator,
    block: int,
    n_max: int,
    confidence: float = 0.95,
    p0: float = 0.1,
    rho: float = 0.8,
) -> SampleResult:
    """Subset simulation (module docstring); ``n_max`` is a hard cap on the evaluations."""
    z = _z(confidence)
    nc = max(1, round(p0 * block))
    ns = max(2, block // nc)
    n_level = nc * ns
    u = rng.standard_normal((block, d))
    gv = g(u)
    n = block
    level0 = True
    p_prev, cv2 = 1.0, 0.0
    history: list[tuple[int, float, float]] = []
    levels: list[tuple[float, float]] = []
    sq = math.sqrt(1.0 - rho * rho)
    while True:
        m = gv.shape[0]
        fail = gv <= 0.0
        k_fail = int(np.count_nonzero(fail))
        room = n + n_level - nc <= n_max
        if k_fail >= nc or (k_fail > 0 and not room):  # this level's failures end the run
            if level0:  # plain Monte Carlo
                r = _mc_result(k_fail, m, confidence, math.inf, u[fail].sum(axis=0), history)
                r.method, r.converged = "subset", True
                r.levels = [(0.0, r.probability)]
                r.history = [(n, r.probability, r.cv)]
                return r
            pj = k_fail / m
            cv2 += (1.0 - pj) / (m * pj) * (1.0 + _chain_gamma(fail.reshape(nc, ns), pj))
            p = p_prev * pj
            cv = math.sqrt(cv2)
            history.append((n, p, cv))
            levels.append((0.0, p))
            return SampleResult(
                p, cv, p * math.exp(-z * cv), min(1.0, p * math.exp(z * cv)),
                "log-normal, Au & Beck CV (chain correlation, levels independent)", False,
                k_fail, n, "subset", True, history, levels, u[fail].mean(axis=0),
            )  # fmt: skip
        order = np.lexsort((rng.random(m), gv))  # ties broken at random
        b = float(gv[order[nc - 1]])
        cond = gv <= b
        pj = int(np.count_nonzero(cond)) / m
        stuck = pj >= 1.0 or (bool(levels) and b >= levels[-1][0])
        if stuck and level0:  # g constant over the first level: Monte Carlo's bound
            r = _mc_result(k_fail, m, confidence, math.inf, np.zeros(d), history)
            r.method, r.history = "subset", [(n, r.probability, r.cv)]
            return r
        if stuck or not room:  # no progress, or the cap: P[g <= b] bounds the probability
            p_b = p_prev if stuck else p_prev * pj
            history.append((n, p_b, math.nan))
            return SampleResult(
                p_b, math.nan, 0.0, p_b, "upper bound (levels stopped short of the limit)",
                True, 0, n, "subset", False, history, levels,
            )  # fmt: skip
        corr = 0.0 if level0 else _chain_gamma(cond.reshape(nc, ns), pj)
        cv2 += (1.0 - pj) / (m * pj) * (1.0 + corr)
        p_prev *= pj
        levels.append((b, p_prev))
        history.append((n, p_prev, math.sqrt(cv2)))
        seeds = order[:nc]
        cu, cg = u[seeds].copy(), gv[seeds].copy()
        us = np.empty((nc, ns, d))
        gs = np.empty((nc, ns))
        us[:, 0], gs[:, 0] = cu, cg
        for step in range(1, ns):
            cand = rho * cu + sq * rng.standard_normal((nc, d))
            gc = g(cand)
            n += nc
            ok = gc <= b
            cu = np.where(ok[:, None], cand, cu)
            cg = np.where(ok, gc, cg)
            us[:, step], gs[:, step] = cu, cg
        u, gv = us.reshape(n_level, d), gs.reshape(n_level)
        level0 = False
