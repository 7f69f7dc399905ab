"""Dynamic limit state: P[a storm moves the pipe more than a limit], through a campaign.

The limit state of one storm is g = 1 − Y/y_lim, with Y the section's maximum lateral
displacement in the storm (:class:`~onbottom.reliability.storm_model.StormModel`, or any
campaign model with a ``max_displacement`` output) and y_lim the limit (0.5D, 10D or metres).
Its inputs are the continuous uncertain inputs X (sea state from the long-term model, current,
soil) **and the storm seed**.

The seed, treated honestly: the storm's random phases are an input like the others. It enters
as S ~ U(0, 1) — openturns maps it, as every input, to a standard normal u_S — and the storm's
integer seed is ⌊S·2³¹⌋. g is then a deterministic function of (X, S), and

* Monte Carlo draws S with the rest: every run is an independent storm;
* subset simulation (Au & Beck 2001) runs its Markov chains in (u_X, u_S): the component-wise
  Metropolis step on u_S proposes a new storm, kept only when it stays beyond the level's
  threshold — the chains sample the storm phases conditional on failure, exactly as they
  sample the sea state. The estimate integrates over the seeds; the CV is openturns' (a lower
  bound: it neglects the correlation between levels, docs/theory/reliability.md);
* importance sampling centres a unit normal on (u*_X, 0): u_S keeps its own distribution, so its
  weight factor is 1 and the estimator stays unbiased. The design point u*_X comes from FORM on
  the continuous inputs with the seed **frozen** (common random numbers: one storm realisation,
  which makes g continuous in X) or, when FORM fails, the failing storm nearest the origin of a
  pilot Monte Carlo sample. A poor u*_X costs efficiency (a larger CV, reported), never bias;
* FORM alone is not offered for the dynamic limit state: with the seed frozen it answers for
  one realisation of the phases, not for the storm.

Sensitivity: FORM importance factors α² (importance sampling; seed frozen), and for Monte
Carlo and subset simulation the squared standardised rank regression coefficients (SRRC²) of
Y on each continuous input over the first block of runs (an unbiased sample of the inputs);
1 − R² of that regression is the share of the variance that no monotone additive function of X
explains — the storm seed and interactions.

Numerical failures (a run whose status is < 0 other than −3, or that raised) count as
exceedances (conservative) and are counted in ``failed_runs``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import special, stats

from onbottom._validate import in_range, integer, one_of, positive
from onbottom.errors import InputError
from onbottom.reliability.campaign import Campaign
from onbottom.reliability.distributions import UncertainParameter
from onbottom.reliability.estimators import estimate_failure_probability, lifetime_probability

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
        ``"FORM alpha^2 (seed frozen)"``,
        ``"SRRC^2 shares of R^2 (rank regression, first block)"`` or,
        when FORM fails, ``"pilot centre u_i^2/|u|^2 (FORM did not converge)"``.
    design_point : dict of str to float
        FORM design point (importance sampling only).
    upper_bound : bool
        Subset simulation stopped at ``max_storms`` before its levels reached the limit:
        ``probability`` is then an upper bound (the last level's), with no CV.
    stopped_early : int
        Storms of the estimate that stopped early at the campaign model's ``stop_at`` (above
        every limit asked: their verdict is that of the whole storm, their displacement a lower
        bound of it) [-]; 0 without an early stop.
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
    stopped_early: int = 0

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
            "stopped_early": self.stopped_early,
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
        bad = ~np.isfinite(y) | ((status < 0) & (status != -3))
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


def _pilot_centre(ls: _LimitState, cont, n: int, seed: int) -> tuple[list[float], int]:
    """Importance sampling's centre when FORM fails: of ``n`` Monte Carlo storms (seed free),
    the failing one nearest the origin in the standard space of X (Melchers & Beck 2018 §5.4:
    a design-point estimate from samples); the origin when none fails."""
    rng = np.random.default_rng([seed, 7])
    d = cont.getDimension()
    u = rng.standard_normal((n, d))
    x = np.asarray(cont.getInverseIsoProbabilisticTransformation()(u))
    s = rng.uniform(size=(n, 1))
    g = ls(np.hstack([x, s]))
    ls.check()
    fail = np.flatnonzero(g <= 0.0)
    if not fail.size:
        return [0.0] * d, n
    k = fail[np.argmin(np.sum(u[fail] ** 2, axis=1))]
    return [float(v) for v in u[k]], n


def estimate_exceedance(
    campaign: Campaign,
    parameters: Sequence[UncertainParameter],
    limit: float,
    *,
    label: str | None = None,
    method: str = "subset",
    target_cv: float = 0.2,
    max_storms: int = 10_000,
    block_size: int = 500,
    seed: int = 0,
    storms_per_year: float = 1.0,
    design_life_years: float = 25.0,
    form_storms: int = 150,
) -> ExceedanceEstimate:
    """Estimate P[Y > ``limit``] per storm (module docstring) and per year and design life.

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
        Most storms of the estimate, in [10, 10⁹] (subset: max(2, max_storms // block_size)
        levels of ``block_size`` storms; the last level's probability bounds the estimate).
    block_size : int
        Storms per block (per level for subset simulation), in [10, 10⁶].
    seed : int
        Seed of openturns' generator (the same seed draws the same storms: a rerun reads them
        back from the store).
    storms_per_year : float
        λ [1/year], > 0.
    design_life_years : float
        Design life [years], in [0, 10⁴].
    form_storms : int
        Most runs of the FORM search (importance sampling), in [10, 10⁵].
    """
    import openturns as ot

    positive("limit", limit)
    one_of("method", method, DYNAMIC_METHODS)
    in_range("target_cv", target_cv, 0.0, 1.0, low_inclusive=False)
    n_max = integer("max_storms", max_storms, 10, 10**9)
    block = integer("block_size", block_size, 10, 10**6)
    seed = integer("seed", seed, 0, 2**32 - 1)
    positive("storms_per_year", storms_per_year)
    names = [p.name for p in parameters]
    if tuple(names) != tuple(campaign.model.input_names):
        raise InputError(
            f"parameters = {names!r} is invalid: expected the model's inputs"
            f" {list(campaign.model.input_names)!r} in order"
        )
    allp = [*parameters, seed_parameter()]
    ls = _LimitState(campaign, limit)
    form_calls = 0
    importance: dict[str, float] = {}
    kind = "SRRC^2 shares of R^2 (rank regression, first block)"
    design: dict[str, float] = {}
    history: list[tuple[int, float, float]] = []
    curve: list[tuple[float, float]] = []
    ot.RandomGenerator.SetSeed(seed)

    def make_event(g, params):
        f = ot.PythonFunction(len(params), 1, func_sample=lambda x: g(np.asarray(x)).reshape(-1, 1))
        dist = ot.JointDistribution([p.openturns() for p in params])
        y = ot.CompositeRandomVector(f, ot.RandomVector(dist))
        return ot.ThresholdEvent(y, ot.LessOrEqual(), 0.0)

    event = make_event(ls, allp)
    if method == "importance":
        cont = ot.JointDistribution([p.openturns() for p in parameters])
        n_form = integer("form_storms", form_storms, 10, 10**5)
        frozen = _LimitState(campaign, limit, frozen_seed=_SEED_SPAN // 2)
        try:
            form = estimate_failure_probability(
                frozen,
                list(parameters),
                method="form",
                form_max_calls=n_form,
                form_tolerance=1e-3,
                form_strict=False,
            )
        except RuntimeError:  # the optimiser's point is off g = 0: a pilot sample instead
            form = None
        frozen.check()
        form_calls = frozen.calls
        if form is not None:
            importance, design = form.importance, form.design_point
            kind = "FORM alpha^2 (seed frozen)"
            u_x = list(cont.getIsoProbabilisticTransformation()([design[n] for n in names]))
        else:
            u_x, pilot = _pilot_centre(ls, cont, n_form, seed)
            form_calls += pilot
            norm2 = sum(v * v for v in u_x)
            if norm2 > 0.0:
                importance = {n: v * v / norm2 for n, v in zip(names, u_x, strict=True)}
            kind = "pilot centre u_i^2/|u|^2 (FORM did not converge)"
            design = dict(
                zip(names, cont.getInverseIsoProbabilisticTransformation()(u_x), strict=True)
            )
        ot.RandomGenerator.SetSeed(seed)
        inst = ot.Normal(ot.Point([*u_x, 0.0]), ot.CovarianceMatrix(len(allp)))
        algo = ot.ProbabilitySimulationAlgorithm(
            ot.StandardEvent(event), ot.ImportanceSamplingExperiment(inst)
        )
    elif method == "monte_carlo":
        algo = ot.ProbabilitySimulationAlgorithm(event, ot.MonteCarloExperiment())
    else:
        algo = ot.SubsetSampling(event)
        algo.setConditionalProbability(0.1)
        # L = max_storms/block levels: openturns stops once the level probability 0.1^k falls
        # below the minimum; half of 0.1^(L-1) stops after level L (away from round-off ties);
        # L at most 300 (0.1^299 is still a positive double; beyond it P would underflow)
        levels = min(max(2, n_max // block), 300)
        algo.setMinimumProbability(0.5 * 0.1 ** (levels - 1))
        algo.setMaximumOuterSampling(1)  # block_size storms per level
    algo.setBlockSize(block)
    if method != "subset":
        algo.setMaximumOuterSampling(max(1, n_max // block))
        algo.setMaximumCoefficientOfVariation(target_cv)
        algo.setConvergenceStrategy(ot.Full())
    bound = False
    try:
        algo.run()
    except RuntimeError as exc:  # subset: the levels reached the minimum probability
        ls.check()
        if method != "subset" or "too small" not in str(exc):
            raise
        bound = True
    ls.check()
    if bound:
        probs = list(algo.getProbabilityEstimatePerStep())
        p = float(probs[-1])
        if float(list(algo.getThresholdPerStep())[-1]) <= 0.0:
            # the last level reached the limit (openturns stops on p < minimum even then):
            # an estimate, with the CV of independent levels (Au & Beck 2001, Eq. 18, γ = 0)
            bound = False
            cond = [probs[0]] + [b / a for a, b in itertools.pairwise(probs)]
            cv = math.sqrt(sum((1.0 - q) / (q * block) for q in cond if q > 0.0))
        else:  # P < the last level's probability: an upper bound, no CV
            cv = math.nan
    else:
        r = algo.getResult()
        p = float(r.getProbabilityEstimate())
        cv = float(r.getCoefficientOfVariation()) if p > 0.0 else math.inf
    if method == "subset":
        probs = list(algo.getProbabilityEstimatePerStep())
        thr = list(algo.getThresholdPerStep())
        for i, (pk, tk) in enumerate(zip(probs, thr, strict=True)):
            history.append((block * (i + 1), float(pk), math.nan))
            curve.append((float(limit * (1.0 - max(tk, 0.0))), float(pk)))
        if history and not bound:
            history[-1] = (history[-1][0], history[-1][1], cv)
    else:
        h = algo.getConvergenceStrategy().getSample()
        for i in range(h.getSize()):
            pk, var = float(h[i, 0]), float(h[i, 1])
            cvk = math.sqrt(var) / pk if pk > 0.0 else math.inf
            history.append((block * (i + 1), pk, cvk))
    if method != "importance" and ls.first is not None:
        importance = rank_importance(ls.first[0], ls.first[1], names)
    annual = float(-math.expm1(-storms_per_year * p))
    return ExceedanceEstimate(
        label=label or f"{limit:g} m",
        limit=float(limit),
        probability=p,
        cv=cv,
        method=method,
        storms=ls.calls + form_calls,
        computed=campaign.stats.computed - ls.computed0,
        failed_runs=ls.failed,
        annual=annual,
        lifetime=lifetime_probability(annual, design_life_years),
        reliability_index=float(-special.ndtri(p)) if 0.0 < p < 1.0 else math.nan,
        history=history,
        curve=curve,
        importance=importance,
        importance_kind=kind,
        design_point=design,
        upper_bound=bound,
        stopped_early=ls.stopped,
    )
