"""Dynamic limit state: P[a storm moves the pipe more than a limit], through a campaign.

The limit state of one storm is g = 1 − Y/y_lim, with Y the section's maximum lateral
displacement in the storm (:class:`~onbottom.reliability.storm_model.StormModel`, or any
campaign model with a ``max_displacement`` output) and y_lim the limit (0.5D, 10D or metres).
Its inputs are the continuous uncertain inputs X (sea state from the long-term model, current,
soil) **and the storm seed**.

The seed, treated honestly: the storm's random phases are an input like the others. It enters
as S ~ U(0, 1), mapped to a standard normal u_S like every input (S = Φ(u_S)), and the storm's
integer seed is ⌊S·2³¹⌋. g is then a deterministic function of (X, S). The estimators
(:mod:`onbottom.reliability._sampling`) work in the standard normal space of (u_X, u_S):

* Monte Carlo draws S with the rest: every run is an independent storm; Clopper–Pearson
  interval, a flagged one-sided bound when no storm fails, p = 1 when all do;
* importance sampling (the default) centres a unit normal on (c_X, 0), c_X from a
  cross-entropy pilot (blocks of ``pilot_storms`` storms moving the centre to the weighted
  mean of the worst 10 %, then of the failing storms): u_S keeps its own distribution, so its
  weight factor is 1 and the estimator stays unbiased; interval from the weights' standard
  error. When 10 % or more of the pilot's first (unbiased) block fails, failure is not rare and
  Monte Carlo runs instead (the first block reused);
* subset simulation (Au & Beck 2001) runs its Markov chains in (u_X, u_S): a move of u_S is a
  new storm, kept only when it stays beyond the level's threshold. ``max_storms`` is a hard
  cap; the interval uses Au & Beck's CV with the chains' correlation (levels independent);
  the estimator's O(1/N) bias is large at 100 storms a level (docs/theory/reliability.md).

The default (importance sampling) was chosen by a coverage test on a closed-form limit state
through this very code path (``tests/verification/test_reliability_coverage.py``).

What drives failure, two measures, reported side by side:

* ``failure_mean``: E[u_i | failure], the mean standardized input given failure (the failing
  storms of Monte Carlo or subset simulation's last level; the weighted failing storms of
  importance sampling): how many standard deviations from its median input i stood in the
  storms that failed — the inputs that make a storm fail;
* ``importance``: SRRC², the squared standardised rank regression coefficients of Y on each
  continuous input over the first unbiased block (Saltelli et al. 2004 §1.2.5): the share of
  the variance of Y **over all storms** (the bulk of the response) each input explains; 1 − R²
  is the share no monotone additive function of X explains — the storm seed and interactions.

Numerical failures (a run whose status is < 0 other than −3, or that raised) count as
exceedances (conservative) and are counted in ``failed_runs``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import special, stats

from onbottom._validate import in_range, integer, one_of, positive
from onbottom.errors import InputError
from onbottom.reliability import _sampling
from onbottom.reliability.campaign import Campaign
from onbottom.reliability.distributions import UncertainParameter
from onbottom.reliability.estimators import lifetime_probability
from onbottom.status import Status

__all__ = [
    "DYNAMIC_METHODS",
    "SEED_INPUT",
    "ExceedanceEstimate",
    "estimate_exceedance",
    "rank_importance",
    "seed_parameter",
    "seeds_from_uniform",
]

DYNAMIC_METHODS = ("subset", "importance", "monte_carlo")
"""Estimators of :func:`estimate_exceedance`."""

SEED_INPUT = "storm_seed"
"""Name of the seed input, S ~ U(0, 1)."""

_SEED_SPAN = 2**31


def seed_parameter() -> UncertainParameter:
    """The seed input S ~ U(0, 1)."""
    return UncertainParameter(SEED_INPUT, "uniform", {"low": 0.0, "high": 1.0})


def seeds_from_uniform(s: np.ndarray) -> np.ndarray:
    """Integer storm seeds ⌊S·2³¹⌋ of S in [0, 1]."""
    v = np.clip(np.asarray(s, dtype=float), 0.0, np.nextafter(1.0, 0.0))
    return np.floor(v * _SEED_SPAN).astype(np.int64)


@dataclass(frozen=True)
class ExceedanceEstimate:
    """P[max lateral displacement in a storm > limit], per storm, year and design life.

    Attributes
    ----------
    label : str
        The limit as given ("0.5D", "10D", "2.0 m").
    limit : float
        y_lim [m].
    probability : float
        Per storm.
    cv : float
        Coefficient of variation of ``probability``.
    method : str
    storms : int
        Storm runs the estimate asked for (read back from the store or computed).
    computed : int
        Of which computed in this call.
    failed_runs : int
        Runs that failed numerically (counted as exceedances).
    annual, lifetime : float
        1 − exp(−λ p); 1 − (1 − annual)^years.
    reliability_index : float
        −Φ⁻¹(p).
    history : list of (storms, probability, cv)
        Convergence of the estimator (per block; per level for subset simulation).
    curve : list of (displacement [m], exceedance probability per storm)
        Subset simulation's intermediate levels (the exceedance curve below the limit).
    importance : dict of str to float
        Sensitivity of the result to each input (see ``importance_kind``).
    importance_kind : str
        What ``importance`` is (SRRC² over the first unbiased block).
    design_point : dict of str to float
        Importance sampling's centre in the inputs' units (empty otherwise).
    upper_bound : bool
        ``probability`` is an upper bound, with no CV: Monte Carlo with no failing storm (the
        one-sided bound), or subset simulation stopped at ``max_storms`` before its levels
        reached the limit (the last level's probability).
    interval, annual_interval, lifetime_interval : (float, float)
        The ``confidence`` intervals of the per-storm, annual and lifetime probabilities.
    interval_kind : str
        How the interval was made (Clopper–Pearson, the weights' standard error, ...).
    confidence : float
        Level of the intervals.
    failures : int
        Failing storms of the estimate.
    failure_mean : dict of str to float
        E[u_i | failure] per input, the storm seed included (module docstring).
    pilot_storms : int
        Storms of importance sampling's pilot (included in ``storms``).
    stopped_early : int
        Storms of the estimate that stopped early at the campaign model's ``stop_at`` (above
        every limit asked: their verdict is that of the whole storm, their displacement a lower
        bound of it) [-]; 0 without an early stop.
    notes : list of str
        Fallbacks and warnings of the estimate.
    """

    label: str
    limit: float
    probability: float
    cv: float
    method: str
    storms: int
    computed: int
    failed_runs: int
    annual: float
    lifetime: float
    reliability_index: float
    history: list[tuple[int, float, float]] = field(default_factory=list)
    curve: list[tuple[float, float]] = field(default_factory=list)
    importance: dict[str, float] = field(default_factory=dict)
    importance_kind: str = ""
    design_point: dict[str, float] = field(default_factory=dict)
    upper_bound: bool = False
    interval: tuple[float, float] = (math.nan, math.nan)
    annual_interval: tuple[float, float] = (math.nan, math.nan)
    lifetime_interval: tuple[float, float] = (math.nan, math.nan)
    interval_kind: str = ""
    confidence: float = 0.95
    failures: int = 0
    failure_mean: dict[str, float] = field(default_factory=dict)
    pilot_storms: int = 0
    stopped_early: int = 0
    notes: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """Plain numbers (JSON)."""

        def num(v: float) -> float | None:
            return float(v) if math.isfinite(v) else None

        return {
            "label": self.label,
            "limit": self.limit,
            "probability": self.probability,
            "cv": num(self.cv),
            "method": self.method,
            "storms": self.storms,
            "computed": self.computed,
            "failed_runs": self.failed_runs,
            "annual": self.annual,
            "lifetime": self.lifetime,
            "reliability_index": num(self.reliability_index),
            "history": [[n, p, num(c)] for n, p, c in self.history],
            "curve": [[y, p] for y, p in self.curve],
            "importance": self.importance,
            "importance_kind": self.importance_kind,
            "design_point": self.design_point,
            "upper_bound": self.upper_bound,
            "interval": [num(v) for v in self.interval],
            "annual_interval": [num(v) for v in self.annual_interval],
            "lifetime_interval": [num(v) for v in self.lifetime_interval],
            "interval_kind": self.interval_kind,
            "confidence": self.confidence,
            "failures": self.failures,
            "failure_mean": self.failure_mean,
            "failure_mean_kind": "E[u | failure]: mean standardized input of the failing storms",
            "pilot_storms": self.pilot_storms,
            "stopped_early": self.stopped_early,
            "notes": list(self.notes),
        }


def rank_importance(x: np.ndarray, y: np.ndarray, names: Sequence[str]) -> dict[str, float]:
    """Shares of the variance of ``y``'s ranks: each column's SRRC² scaled to share R², and the
    residual 1 − R² (key ``"storm_seed and interactions"``); the shares sum to one.
    Rank-transform, standardise, least squares (Saltelli et al. 2004 §1.2.5)."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    ok = np.isfinite(y) & np.all(np.isfinite(x), axis=1)
    x, y = x[ok], y[ok]
    if x.shape[0] == 0:  # no finite storm result: nothing to rank
        return {}
    keep = [j for j in range(x.shape[1]) if np.ptp(x[:, j]) > 0.0]
    if x.shape[0] < len(keep) + 3 or np.ptp(y) == 0.0:
        return {}
    rx = np.column_stack([stats.rankdata(x[:, j]) for j in keep])
    ry = stats.rankdata(y)
    rx = (rx - rx.mean(0)) / rx.std(0)
    ry = (ry - ry.mean()) / ry.std()
    coef, *_ = np.linalg.lstsq(rx, ry, rcond=None)
    r2 = min(max(1.0 - float(np.mean((ry - rx @ coef) ** 2)), 0.0), 1.0)
    # SRRC² sum to R² only for uncorrelated columns; the sample's chance correlations (a
    # first block of tens of storms) make the raw sum exceed 1. Shares: each input's SRRC²
    # scaled so that the inputs share R² and the remainder 1 − R² (Σ = 1).
    total = float(np.sum(coef * coef))
    scale = r2 / total if total > 0.0 else 0.0
    out = {names[j]: float(c * c * scale) for j, c in zip(keep, coef, strict=True)}
    out[f"{SEED_INPUT} and interactions"] = 1.0 - r2
    return out


class _LimitState:
    """g(x) = 1 − Y/y_lim over rows (X..., S), through the campaign; counts and keeps the first
    block of (X, Y)."""

    def __init__(self, campaign: Campaign, limit: float, frozen_seed: int | None = None) -> None:
        self.campaign = campaign
        self.limit = limit
        self.frozen = frozen_seed
        self.k = campaign.model.output_names.index("max_displacement")
        names = campaign.model.output_names
        self.k_stop = names.index("stopped_early") if "stopped_early" in names else None
        self.stopped = 0
        self.calls = 0
        self.computed0 = campaign.stats.computed
        self.failed = 0
        self.first: tuple[np.ndarray, np.ndarray] | None = None
        self.error: OSError | None = None

    def __call__(self, x: np.ndarray) -> np.ndarray:
        a = np.atleast_2d(np.asarray(x, dtype=float))
        if self.error is not None:  # the store cannot be written: end openturns' run quickly
            return np.full(a.shape[0], -1.0)
        if self.frozen is None:
            xs, seeds = a[:, :-1], seeds_from_uniform(a[:, -1])
        else:
            xs, seeds = a, np.full(a.shape[0], self.frozen, dtype=np.int64)
        try:
            out, status = self.campaign.evaluate(xs, seeds)
        except OSError as exc:
            # raised into openturns it would be printed with a traceback and come back as
            # an InternalException: kept, and raised by check() after openturns returns
            self.error = exc
            return np.full(a.shape[0], -1.0)
        y = out[:, self.k].copy()
        if self.k_stop is not None:
            self.stopped += int(np.count_nonzero(out[:, self.k_stop] == 1.0))
        bad = ~np.isfinite(y) | ((status < 0) & (status != Status.OUTSIDE_VALIDITY))
        self.failed += int(np.count_nonzero(bad))
        y[bad] = np.inf
        self.calls += a.shape[0]
        if self.first is None:
            self.first = (xs.copy(), y.copy())
        g = 1.0 - y / self.limit
        return np.where(np.isfinite(g), g, -1.0)

    def check(self) -> None:
        """Raise the ``OSError`` (a store that cannot be written) met during a run, if any."""
        if self.error is not None:
            raise self.error


def _annual(p: float, rate: float) -> float:
    return float(-math.expm1(-rate * p)) if math.isfinite(p) else math.nan


def _life(annual: float, years: float) -> float:
    return lifetime_probability(annual, years) if math.isfinite(annual) else math.nan


def estimate_exceedance(
    campaign: Campaign,
    parameters: Sequence[UncertainParameter],
    limit: float,
    *,
    label: str | None = None,
    method: str = "importance",
    target_cv: float = 0.1,
    max_storms: int = 10_000,
    block_size: int = 500,
    seed: int = 0,
    storms_per_year: float = 1.0,
    design_life_years: float = 25.0,
    pilot_storms: int = 200,
    pilot_iterations: int = 4,
    confidence: float = 0.95,
) -> ExceedanceEstimate:
    """Estimate P[Y > ``limit``] per storm (module docstring) and per year and design life, each
    with its ``confidence`` interval.

    Parameters
    ----------
    campaign : Campaign
        Runs the model (its ``input_names`` are the names of ``parameters`` in order).
    parameters : sequence of UncertainParameter
        Continuous inputs X (the seed is added here).
    limit : float
        y_lim [m], > 0.
    label : str or None
        How the limit was given (default: metres).
    method : str
        One of :data:`DYNAMIC_METHODS`.
    target_cv : float
        Stop at this CV (Monte Carlo, importance sampling), in (0, 1].
    max_storms : int
        Most storms of the estimate, pilot included, in [10, 10⁹]: a hard cap (subset
        simulation does not start a level that would overrun it; its last level's probability
        is then an upper bound).
    block_size : int
        Storms per block (per level for subset simulation), in [10, 10⁶].
    seed : int
        Seed of the sampling (the same seed draws the same storms: a rerun reads them back
        from the store).
    storms_per_year : float
        λ [1/year], > 0.
    design_life_years : float
        Design life [years], in [0, 10⁴].
    pilot_storms : int
        Storms per iteration of importance sampling's cross-entropy pilot, in [10, 10⁵].
    pilot_iterations : int
        Most iterations of the pilot, in [1, 20].
    confidence : float
        Level of the intervals, in (0.5, 1).
    """
    import openturns as ot

    positive("limit", limit)
    one_of("method", method, DYNAMIC_METHODS)
    in_range("target_cv", target_cv, 0.0, 1.0, low_inclusive=False)
    n_max = integer("max_storms", max_storms, 10, 10**9)
    block = integer("block_size", block_size, 10, 10**6)
    seed = integer("seed", seed, 0, 2**32 - 1)
    n_pilot = integer("pilot_storms", pilot_storms, 10, 10**5)
    iters = integer("pilot_iterations", pilot_iterations, 1, 20)
    in_range("confidence", confidence, 0.5, 1.0, low_inclusive=False, high_inclusive=False)
    positive("storms_per_year", storms_per_year)
    names = [p.name for p in parameters]
    if tuple(names) != tuple(campaign.model.input_names):
        raise InputError(
            f"parameters = {names!r} is invalid: expected the model's inputs"
            f" {list(campaign.model.input_names)!r} in order"
        )
    cont = ot.JointDistribution([p.openturns() for p in parameters])
    to_x = cont.getInverseIsoProbabilisticTransformation()
    d = len(parameters)
    ls = _LimitState(campaign, limit)

    def g(u: np.ndarray) -> np.ndarray:
        x = np.asarray(to_x(np.ascontiguousarray(u[:, :d])))
        s = special.ndtr(u[:, d : d + 1])
        return ls(np.hstack([x, s]))

    rng = np.random.default_rng([seed, 0x5EED])
    r, used, notes, design, pilot_calls = _run_estimator(
        method, g, d, rng, block, n_max, target_cv, confidence, n_pilot, iters, ls, to_x, names
    )
    ls.check()
    return _estimate(
        r, used, notes, design, pilot_calls, ls, campaign, names, limit, label,
        storms_per_year, design_life_years, confidence,
    )  # fmt: skip


def _run_estimator(method, g, d, rng, block, n_max, target_cv, confidence, n_pilot, iters, ls,
                   to_x, names):  # fmt: skip
    """Stage of :func:`estimate_exceedance`: run ``method`` on g in the standard space of
    (u_X, u_S); returns (sampling result, method used, notes, design point, pilot storms)."""
    notes: list[str] = []
    design: dict[str, float] = {}
    used = method
    pilot_calls = 0
    if method == "monte_carlo":
        r = _sampling.monte_carlo(g, d + 1, rng, block, n_max, target_cv, confidence)
    elif method == "subset":
        r = _sampling.subset(g, d + 1, rng, block, n_max, confidence)
    else:
        free = np.r_[np.ones(d, dtype=bool), False]  # the seed keeps its own distribution
        m = min(n_pilot, max(10, n_max // 2))
        iters = min(iters, max(1, (n_max // 2) // m))  # the pilot takes half the cap at most
        centre, pilot_calls, first, reached = _sampling.ce_centre(g, d + 1, rng, m, iters, free)
        origin_fails = float(np.mean(first[1] <= 0.0)) >= 0.1
        if origin_fails:  # failure is not rare: Monte Carlo, the pilot's first block included
            used = "monte_carlo"
            notes.append(
                "importance sampling fell back to Monte Carlo: at least 10 % of the pilot's"
                " unbiased storms failed (the failure domain holds the median storm)"
            )
            r = _sampling.monte_carlo(
                g, d + 1, rng, block, n_max, target_cv, confidence, first=first
            )
            pilot_calls = ls.calls - r.evaluations
        else:
            if not reached:
                notes.append(
                    f"the pilot's {iters} iterations did not reach the limit: importance"
                    " sampling centred on its last level (unbiased, less efficient)"
                )
            design = dict(zip(names, (float(v) for v in to_x(list(centre[:d]))), strict=True))
            r = _sampling.importance(
                g, d + 1, rng, centre, block, max(1, n_max - pilot_calls), target_cv, confidence
            )
            if r.failures == 0:  # no estimate: the pilot's unbiased block bounds p
                hi = _sampling.clopper_pearson(0, first[0].shape[0], confidence)[1]
                r.probability, r.low, r.high, r.upper_bound = hi, 0.0, hi, True
                r.interval_kind = (
                    "one-sided upper bound from the pilot's unbiased block (no failing storm)"
                )
    return r, used, notes, design, pilot_calls


def _estimate(r, used, notes, design, pilot_calls, ls, campaign, names, limit, label,
              storms_per_year, design_life_years, confidence) -> ExceedanceEstimate:  # fmt: skip
    """Stage of :func:`estimate_exceedance`: the estimate per storm, per year and per design
    life with their intervals, what drives failure, and the campaign's counts."""
    p = r.probability
    annual = _annual(p, storms_per_year)
    lo_a, hi_a = _annual(r.low, storms_per_year), _annual(r.high, storms_per_year)
    kind = (
        "SRRC^2 shares of R^2 (rank regression on the first unbiased block: the bulk of the"
        " response)"
    )
    importance = rank_importance(ls.first[0], ls.first[1], names) if ls.first else {}
    fmean: dict[str, float] = {}
    if r.failure_mean is not None:
        fmean = {n: float(v) for n, v in zip([*names, SEED_INPUT], r.failure_mean, strict=True)}
    curve = [(float(limit * (1.0 - max(b, 0.0))), float(pk)) for b, pk in r.levels]
    return ExceedanceEstimate(
        label=label or f"{limit:g} m",
        limit=float(limit),
        probability=p,
        cv=r.cv,
        method=used,
        storms=ls.calls,
        computed=campaign.stats.computed - ls.computed0,
        failed_runs=ls.failed,
        annual=annual,
        lifetime=_life(annual, design_life_years),
        reliability_index=float(-special.ndtri(p)) if 0.0 < p < 1.0 else math.nan,
        history=[(n + pilot_calls, pk, c) for n, pk, c in r.history],
        curve=curve,
        importance=importance,
        importance_kind=kind,
        design_point=design,
        upper_bound=r.upper_bound,
        interval=(r.low, r.high),
        annual_interval=(lo_a, hi_a),
        lifetime_interval=(_life(lo_a, design_life_years), _life(hi_a, design_life_years)),
        interval_kind=r.interval_kind,
        confidence=confidence,
        failures=r.failures,
        failure_mean=fmean,
        pilot_storms=pilot_calls,
        notes=notes,
        stopped_early=ls.stopped,
    )
