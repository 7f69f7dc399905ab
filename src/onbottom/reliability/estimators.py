"""Probability of failure P[g(X) ≤ 0] with openturns: Monte Carlo, FORM, importance sampling
around the FORM design point, subset simulation.

The limit state ``g`` is a Python callable taking an (n, d) array of inputs (columns in the
order of ``parameters``, SI units) and returning n values; g ≤ 0 is failure. It is evaluated
in blocks (vectorised), and every evaluation is counted.

Estimators (Lemaire 2009, *Structural Reliability*, ch. 6–8; FORM and the probability
transformation by openturns ≥ 1.27, the sampling by :mod:`onbottom.reliability._sampling`,
every sampled probability with a 95 % interval):

* ``"monte_carlo"``: crude sampling; CV = √((1 − p)/(n p)), so p = 1e-4 at CV 0.1 needs 10⁶
  evaluations — the reference for cheap limit states only. Clopper–Pearson interval; no
  failure: the one-sided 95 % bound 1 − 0.05^(1/n) ≈ 3/n, flagged (``upper_bound``); every
  sample failing: p = 1.
* ``"form"``: first-order reliability method (Hasofer–Lind index β, design point u*, p ≈ Φ(−β));
  exact for a limit state linear in the standard normal space; no CV (a point approximation).
  Gives the importance factors α_i² (share of each input in β², Σ = 1): the sensitivity of the
  result to each uncertain input.
* ``"importance"``: FORM first, then importance sampling in the standard space with a unit
  normal density centred on u* (Melchers & Beck 2018, §5.4); unbiased, CV and interval from the
  weights. When the median point (the origin of the standard space) fails, Monte Carlo runs
  instead (``method`` says so): a centre away from such a domain misses most of it.
* ``"subset"``: subset simulation (Au & Beck 2001) with conditional probability 0.1 and
  ``block_size`` samples per level; ``max_evaluations`` is a hard cap; CV with the chains'
  correlation (the levels' neglected). ``target_cv`` is only compared with it.

Sampling stops at ``target_cv`` or ``max_evaluations``. ``seed`` seeds the sampling (numpy)
and openturns' generator, so results are reproducible.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy import special

from onbottom._validate import in_range, integer, one_of
from onbottom.errors import InputError
from onbottom.reliability import _sampling
from onbottom.reliability.distributions import UncertainParameter

__all__ = ["METHODS", "FailureProbability", "estimate_failure_probability", "lifetime_probability"]

METHODS = ("monte_carlo", "form", "importance", "subset")
"""Estimators of :func:`estimate_failure_probability`."""


@dataclass(frozen=True, slots=True)
class FailureProbability:
    """Result of :func:`estimate_failure_probability`.

    Attributes
    ----------
    probability : float
        Estimate of P[g ≤ 0].
    cv : float
        Its coefficient of variation (NaN for FORM).
    method : str
        The estimator.
    evaluations : int
        Limit-state evaluations spent (FORM's included for ``"importance"``).
    reliability_index : float
        β = −Φ⁻¹(p).
    importance : dict of str to float
        FORM importance factors α_i² per random input (empty for Monte Carlo and subset).
    design_point : dict of str to float
        FORM design point in the inputs' units (empty for Monte Carlo and subset).
    converged : bool
        Whether ``target_cv`` was reached (FORM: whether the optimiser converged).
    seed : int
        Seed of the run.
    low, high : float
        95 % interval (:mod:`onbottom.reliability._sampling`; NaN for FORM).
    interval_kind : str
        How the interval was made.
    upper_bound : bool
        ``probability`` is a one-sided bound (Monte Carlo with no failure; subset simulation
        stopped at ``max_evaluations`` short of the limit).
    failures : int
        Failing samples.
    """

    probability: float
    cv: float
    method: str
    evaluations: int
    reliability_index: float
    importance: dict[str, float] = field(default_factory=dict)
    design_point: dict[str, float] = field(default_factory=dict)
    converged: bool = True
    seed: int = 0
    low: float = math.nan
    high: float = math.nan
    interval_kind: str = ""
    upper_bound: bool = False
    failures: int = 0

    def interval(self) -> tuple[float, float]:
        """The 95 % interval of the estimate (``interval_kind``; NaN for FORM)."""
        return (self.low, self.high)


def lifetime_probability(annual: float, years: float) -> float:
    """P[failure in ``years``] = 1 − (1 − p_annual)^years (independent years)."""
    in_range("annual probability", annual, 0.0, 1.0)
    in_range("years", years, 0.0, 1.0e4)
    return float(-np.expm1(years * np.log1p(-annual))) if annual < 1.0 else 1.0


class _Counter:
    def __init__(self, g: Callable[[np.ndarray], np.ndarray], d: int) -> None:
        self.g, self.d, self.calls = g, d, 0

    def __call__(self, x) -> list[list[float]]:
        a = np.asarray(x, dtype=float).reshape(-1, self.d)
        self.calls += a.shape[0]
        y = np.asarray(self.g(a), dtype=float).reshape(-1)
        if y.shape[0] != a.shape[0]:
            raise InputError(
                f"limit state returned {y.shape[0]} values for {a.shape[0]} input rows"
            )
        if not np.all(np.isfinite(y)):
            raise InputError("limit state returned non-finite values")
        return y.reshape(-1, 1)


def _event(g, parameters: Sequence[UncertainParameter]):
    import openturns as ot

    d = len(parameters)
    counter = _Counter(g, d)
    f = ot.PythonFunction(d, 1, func_sample=counter)
    dist = ot.JointDistribution([p.openturns() for p in parameters])
    dist.setDescription([p.name for p in parameters])
    y = ot.CompositeRandomVector(f, ot.RandomVector(dist))
    return ot.ThresholdEvent(y, ot.LessOrEqual(), 0.0), dist, counter


def _beta(p: float) -> float:
    return float(-special.ndtri(p)) if 0.0 < p < 1.0 else (math.inf if p <= 0.0 else -math.inf)


def estimate_failure_probability(
    limit_state: Callable[[np.ndarray], np.ndarray],
    parameters: Sequence[UncertainParameter],
    *,
    method: str = "importance",
    target_cv: float = 0.1,
    max_evaluations: int = 100_000,
    block_size: int = 1000,
    seed: int = 0,
    form_max_calls: int = 2000,
    form_tolerance: float = 1e-10,
    form_strict: bool = True,
) -> FailureProbability:
    """Estimate P[g(X) ≤ 0] (see the module docstring).

    Parameters
    ----------
    limit_state : callable
        g(x) for an (n, d) array x (columns in the order of ``parameters``) → n values.
    parameters : sequence of UncertainParameter
        The inputs (``fixed`` ones pass their value).
    method : str
        One of :data:`METHODS`.
    target_cv : float
        Stop sampling at this coefficient of variation, in (0, 1].
    max_evaluations : int
        Most limit-state evaluations of the sampling, in [100, 10⁹].
    block_size : int
        Rows per call of ``limit_state``, in [1, 10⁶].
    seed : int
        Seed of openturns' generator.
    form_max_calls : int
        Most limit-state calls of FORM's optimiser (Cobyla), in [10, 10⁶].
    form_tolerance : float
        Cobyla's absolute, relative and residual tolerances in the standard space, in
        (0, 0.1] (1e-10 for cheap limit states; 1e-3 for a storm, whose g is noisy at that
        scale).
    form_strict : bool
        False: Abdo–Rackwitz with finite-difference gradients instead of Cobyla (a few
        iterations of d + 1 calls, for a smooth but costly g such as a storm with its seed
        frozen), and an optimiser stopped at ``form_max_calls`` returns its last point (a
        centre for importance sampling) instead of raising.
    """
    import openturns as ot

    one_of("method", method, METHODS)
    in_range("target_cv", target_cv, 0.0, 1.0, low_inclusive=False)
    n_max = integer("max_evaluations", max_evaluations, 100, 10**9)
    block = integer("block_size", block_size, 1, 10**6)
    seed = integer("seed", seed, 0, 2**32 - 1)
    if not parameters:
        raise InputError("parameters = [] is invalid: at least one uncertain input")
    names = [p.name for p in parameters]
    if len(set(names)) != len(names):
        raise InputError(f"parameters = {names!r} is invalid: names must be unique")
    ot.RandomGenerator.SetSeed(seed)
    event, dist, counter = _event(limit_state, parameters)

    importance: dict[str, float] = {}
    design: dict[str, float] = {}
    to_x = dist.getInverseIsoProbabilisticTransformation()
    d = len(parameters)
    used = method
    if method == "importance":  # the origin (median point) fails: failure is not rare
        median = np.asarray(to_x([0.0] * d), dtype=float).reshape(1, d)
        if float(counter(median)[0, 0]) <= 0.0:
            used = "monte_carlo"
    centre = None
    if used in ("form", "importance"):
        res = _run_form(event, dist, counter, form_max_calls, form_tolerance, form_strict)
        p_form = float(res.getEventProbability())
        if res.getIsStandardPointOriginInFailureSpace():
            p_form = 1.0 - p_form
        alphas = list(res.getImportanceFactors())
        importance = {
            n: float(a) for n, a, p in zip(names, alphas, parameters, strict=True) if p.is_random
        }
        design = {
            n: float(v) for n, v in zip(names, res.getPhysicalSpaceDesignPoint(), strict=True)
        }
        if method == "form":
            return _form_result(res, p_form, importance, design, dist, counter, method, seed)
        centre = np.asarray(res.getStandardSpaceDesignPoint(), dtype=float)
    r = _sample(used, counter, to_x, d, block, n_max, target_cv, seed, centre)
    p = r.probability
    return FailureProbability(
        probability=p,
        cv=r.cv,
        method=used,
        evaluations=counter.calls,
        reliability_index=_beta(p),
        importance=importance,
        design_point=design,
        converged=r.converged,
        seed=seed,
        low=r.low,
        high=r.high,
        interval_kind=r.interval_kind,
        upper_bound=r.upper_bound,
        failures=r.failures,
    )


def _run_form(event, dist, counter, form_max_calls, form_tolerance, form_strict):
    """Stage of :func:`estimate_failure_probability`: FORM's design point (openturns result)
    with Cobyla (``form_strict``) or Abdo–Rackwitz, started at the inputs' mean."""
    import openturns as ot

    solver = ot.Cobyla() if form_strict else ot.AbdoRackwitz()
    solver.setMaximumCallsNumber(integer("form_max_calls", form_max_calls, 10, 10**6))
    in_range("form_tolerance", form_tolerance, 0.0, 0.1, low_inclusive=False)
    if not form_strict:
        solver.setCheckStatus(False)
    for set_tol in (
        solver.setMaximumAbsoluteError,
        solver.setMaximumRelativeError,
        solver.setMaximumResidualError,
    ):  # the design point to 1e-10 in the standard space
        set_tol(form_tolerance)
    g_mean = float(counter(np.array([list(dist.getMean())]))[0, 0])
    solver.setMaximumConstraintError(  # on g = 0, g's scale
        (1e-9 if form_strict else form_tolerance) * max(1.0, abs(g_mean))
    )
    solver.setStartingPoint(dist.getMean())  # physical space (openturns 1.27)
    form = ot.FORM(solver, event)
    form.run()
    return form.getResult()


def _form_result(res, p_form, importance, design, dist, counter, method, seed):
    """Stage of :func:`estimate_failure_probability`: the FORM answer, ``converged`` when the
    design point lies on g = 0 (to 1e-6 of g at the median point)."""
    g_dp = float(counter(np.array([list(design.values())]))[0, 0])
    median = [dist.getMarginal(i).computeQuantile(0.5)[0] for i in range(len(design))]
    g_0 = float(counter(np.array([median]))[0, 0])
    ok = abs(g_dp) <= 1e-6 * max(abs(g_0), 1e-300)
    return FailureProbability(
        probability=p_form,
        cv=math.nan,
        method=method,
        evaluations=counter.calls,
        reliability_index=float(res.getHasoferReliabilityIndex()),
        importance=importance,
        design_point=design,
        converged=ok,
        seed=seed,
    )


def _sample(used, counter, to_x, d, block, n_max, target_cv, seed, centre):
    """Stage of :func:`estimate_failure_probability`: the sampling estimator ``used`` in the
    standard normal space (blocks of ``block`` rows through ``counter``)."""

    def g_u(u: np.ndarray) -> np.ndarray:
        out = []
        for i in range(0, u.shape[0], block):
            x = np.asarray(to_x(np.ascontiguousarray(u[i : i + block])))
            out.append(counter(x).reshape(-1))
        return np.concatenate(out)

    rng = np.random.default_rng([seed, 0x5EED])
    if used == "monte_carlo":
        return _sampling.monte_carlo(g_u, d, rng, block, n_max, target_cv)
    if used == "importance":
        return _sampling.importance(g_u, d, rng, centre, block, n_max, target_cv)
    return _sampling.subset(g_u, d, rng, min(block, n_max), n_max)
