"""Fit model parameters to test records: grid sweeps, global search, local polish, uncertainty.

The search works in *normalised* coordinates θ_j = (x_j − lower_j)/(upper_j − lower_j) ∈ [0, 1]
so that one finite-difference step and one tolerance fit every parameter.

1. **Grid sweep** (:func:`grid_search`), as in Youssef & Cassidy (2014): the misfit on the
   outer product of parameter values (a misfit map), run on the sweep engine.
2. **Global search**: :func:`scipy.optimize.differential_evolution` within the bounds (seeded,
   Latin-hypercube start, population evaluated in parallel through a map on a Dask client).
3. **Local polish**: :func:`scipy.optimize.least_squares` (trust-region reflective, bounds)
   on the residual vector of :mod:`onbottom.calibration.objective`, from the global optimum.
4. **Uncertainty**: with the Jacobian J of the residuals at the optimum (physical units),
   ``cov = s²·(JᵀJ)⁻¹`` with ``s² = Σr²/(m − p)`` (pseudo-inverse when singular), standard
   errors ``sqrt(diag cov)`` and the correlation matrix; :func:`misfit_slices` gives 1-D
   slices of the misfit through the optimum as a check on the linearisation.
   ``s²`` assumes that every residual carries the same noise variance. That holds for the
   history terms (one residual per sample of u and w) when the measurement noise of each
   channel is proportional to its scale; the scalar terms (penetrations, maximum displacement,
   time to the limit) are derived from the same histories, are not independent observations,
   and a single noisy sample can dominate them. For standard errors meant as statistics, fit
   with the history terms only (zero weights on the others); otherwise read them as indicative.

Non-smooth responses
--------------------
The simulated response is not a smooth function of the parameters: the time to reach the
displacement limit jumps when the last cycle changes, the stick–slip friction switches, and
the soil model changes region at fixed displacements. Finite-difference derivatives with a
tiny step therefore see either zero or a jump. The Jacobian here uses *central differences
with steps that are a sizeable fraction of each parameter's range* (``fd_step``, one-sided near
a bound): by default the polish runs first with 2 % of the range — large enough to average over
the discontinuities — and then again with 0.5 % from that optimum, to resolve the narrow A–μ
valley (friction and passive resistance trade off). On synthetic records of Inclined 1 a
single 2 % step stalled in that valley while the continuation reached the truth. The global
search needs no derivatives at all. Standard errors from a linearisation of a non-smooth
response are indicative; compare them with the misfit slices.
"""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import xarray as xr

from onbottom._validate import in_range, one_of
from onbottom.calibration.objective import (
    Misfit,
    MisfitWeights,
    evaluate_misfit,
    failed_residuals,
    residuals,
)
from onbottom.calibration.parameters import Parameter
from onbottom.calibration.records import TestRecord
from onbottom.errors import InputError
from onbottom.status import Status
from onbottom.study.engine import ParallelMap, SerialMap, dask_client
from onbottom.study.functions import register
from onbottom.study.sweep import sweep

__all__ = [
    "CalibrationResult",
    "Objective",
    "Simulator",
    "calibrate",
    "grid_search",
    "misfit_slices",
    "record_misfit",
]

logger = logging.getLogger(__name__)

Simulator = Callable[[TestRecord, Mapping[str, float]], Any]
"""``simulator(record, params) -> xr.Dataset | result``: simulate the record's test with the
parameter values ``params`` (name → value). A result with ``success = False`` or an exception
counts as a failed run (residuals :data:`~onbottom.calibration.objective.FAILED_RESIDUAL`)."""


def _default_simulator() -> Simulator:
    from onbottom.calibration.simulators import CentrifugeSimulator

    return CentrifugeSimulator()


class Objective:
    """Residual vector of all records as a function of the normalised varied parameters.

    Picklable (sent to Dask workers). ``theta`` has one entry per varied parameter in [0, 1].
    """

    def __init__(
        self,
        records: Sequence[TestRecord],
        parameters: Sequence[Parameter],
        simulator: Simulator,
        weights: MisfitWeights,
    ):
        self.records = tuple(records)
        self.parameters = tuple(parameters)
        self.simulator = simulator
        self.weights = weights
        self.varied = [p for p in self.parameters if p.vary]
        self.lower = np.array([p.lower for p in self.varied])
        self.span = np.array([p.span for p in self.varied])

    def values(self, theta: np.ndarray) -> dict[str, float]:
        """Parameter values (all, physical units) at normalised ``theta``."""
        x = self.lower + np.asarray(theta, dtype=float) * self.span
        out = {p.name: p.value for p in self.parameters}
        out.update({p.name: float(v) for p, v in zip(self.varied, x, strict=True)})
        return out

    def simulate(self, record: TestRecord, params: Mapping[str, float]) -> xr.Dataset | None:
        """Run the simulator; None if it raised or reported failure."""
        try:
            res = self.simulator(record, params)
        except Exception as exc:  # a failed run is data for the optimiser, not a crash
            logger.debug("simulation of %s failed at %s: %s", record.name, params, exc)
            return None
        if getattr(res, "success", True) is False:
            return None
        return res if isinstance(res, xr.Dataset) else res.data

    def record_residuals(self, record: TestRecord, params: Mapping[str, float]) -> np.ndarray:
        sim = self.simulate(record, params)
        if sim is None:
            return failed_residuals(record, self.weights)
        try:
            return residuals(record, sim, self.weights)
        except InputError:
            return failed_residuals(record, self.weights)

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        params = self.values(theta)
        return np.concatenate([self.record_residuals(r, params) for r in self.records])

    def scalar(self, theta: np.ndarray) -> float:
        """Σ r² (the misfit) at ``theta``."""
        r = self(theta)
        return float(r @ r)


class _Scalar:
    """Picklable ``theta -> misfit`` for differential evolution."""

    def __init__(self, objective: Objective):
        self.objective = objective

    def __call__(self, theta: np.ndarray) -> float:
        return self.objective.scalar(theta)


class _GridPoint:
    """Picklable sweep function: misfit (total and per record) at one grid point."""

    def __init__(self, objective: Objective):
        self.objective = objective

    def __call__(self, **point: Any) -> dict[str, float]:
        point.pop("rng", None)
        params = {p.name: p.value for p in self.objective.parameters}
        params.update({k: float(v) for k, v in point.items()})
        out: dict[str, float] = {}
        total = 0.0
        n_failed = 0
        for i, rec in enumerate(self.objective.records):
            sim = self.objective.simulate(rec, params)
            if sim is None:
                n_failed += 1
                r = failed_residuals(rec, self.objective.weights)
            else:
                r = residuals(rec, sim, self.objective.weights)
            m = float(r @ r)
            out[f"misfit_{i}"] = m
            total += m
        out["misfit"] = total
        out["n_failed_simulations"] = float(n_failed)
        return out


@dataclass(frozen=True, kw_only=True)
class CalibrationResult:
    """Outcome of :func:`calibrate` (inputs are never modified).

    Attributes
    ----------
    parameters : tuple of Parameter
        All parameters, ``value`` = fitted value (fixed ones unchanged), bounds as given.
    names : tuple of str
        Names of the varied parameters (order of the covariance matrix).
    std_errors : dict
        Standard error of each varied parameter [its units] (NaN if not estimable).
    covariance, correlation : numpy.ndarray
        p×p matrices over the varied parameters (read-only).
    misfit : float
        Σ r² at the optimum [-].
    misfits : tuple of Misfit
        Per-record breakdown at the optimum.
    residuals : numpy.ndarray
        Residual vector at the optimum (read-only).
    success : bool
        ``status.success``.
    status : Status
        :attr:`~onbottom.status.Status.CONVERGED` (6); ``NOT_CONVERGED`` (−5): a least-squares
        stage stopped at its evaluation limit; ``NO_SOLUTION`` (−6): every simulation failed
        at the fitted parameters.
    message : str
    n_evaluations : int
        Simulations of the full record set (objective evaluations, Jacobian included).
    method : str
    wall_time : float
        [s].
    history : dict
        Misfit after each stage (``"start"``, ``"global"``, ``"local"``).
    """

    parameters: tuple[Parameter, ...]
    names: tuple[str, ...]
    std_errors: dict[str, float]
    covariance: np.ndarray
    correlation: np.ndarray
    misfit: float
    misfits: tuple[Misfit, ...]
    residuals: np.ndarray
    success: bool
    status: Status
    message: str
    n_evaluations: int
    method: str
    wall_time: float
    record_names: tuple[str, ...] = ()
    history: dict[str, float] = field(default_factory=dict)

    @property
    def values(self) -> dict[str, float]:
        """Fitted values of all parameters (name → value)."""
        return {p.name: p.value for p in self.parameters}

    def interval(self, name: str, z: float = 1.96) -> tuple[float, float]:
        """Approximate confidence interval value ± z·std_error (default 95 %)."""
        v = self.values[name]
        s = self.std_errors.get(name, math.nan)
        return (v - z * s, v + z * s)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "success": self.success,
            "status": int(self.status),
            "message": self.message,
            "method": self.method,
            "records": list(self.record_names),
            "misfit": self.misfit,
            "n_evaluations": self.n_evaluations,
            "wall_time": self.wall_time,
            "parameters": {
                p.name: {
                    "value": p.value,
                    "lower": p.lower,
                    "upper": p.upper,
                    "vary": p.vary,
                    "units": p.units,
                    "std_error": self.std_errors.get(p.name),
                }
                for p in self.parameters
            },
            "correlation": {
                "names": list(self.names),
                "matrix": self.correlation.tolist(),
            },
            "history": dict(self.history),
            "misfit_terms": [dict(m.terms) for m in self.misfits],
        }

    def to_toml(self) -> str:
        """The fitted parameters as TOML (``[parameters.NAME]`` tables)."""
        lines = [
            "# onbottom calibration result",
            f"records = [{', '.join(_toml_str(n) for n in self.record_names)}]",
            f"success = {str(self.success).lower()}",
            f"message = {_toml_str(self.message)}",
            f"misfit = {self.misfit!r}",
            f"n_evaluations = {self.n_evaluations}",
            f"method = {_toml_str(self.method)}",
            "",
        ]
        for p in self.parameters:
            se = self.std_errors.get(p.name, math.nan)
            lines += [
                f"[parameters.{p.name}]",
                f"value = {p.value!r}",
                f"lower = {p.lower!r}",
                f"upper = {p.upper!r}",
                f"vary = {str(p.vary).lower()}",
                f"units = {_toml_str(p.units)}",
            ]
            if p.vary and math.isfinite(se):
                lines.append(f"std_error = {se!r}")
            lines.append("")
        if self.names:
            lines.append("[correlation]")
            lines.append(f"names = [{', '.join(_toml_str(n) for n in self.names)}]")
            rows = ", ".join(
                "[" + ", ".join(_toml_float(x) for x in row) + "]" for row in self.correlation
            )
            lines.append(f"matrix = [{rows}]")
        return "\n".join(lines) + "\n"


def _toml_str(s: str) -> str:
    return '"' + str(s).replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


def _toml_float(x: float) -> str:
    return repr(float(x)) if math.isfinite(x) else "nan"


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


def _jacobian(
    objective: Objective, theta: np.ndarray, r0: np.ndarray, step: float, pmap: Callable
) -> tuple[np.ndarray, int]:
    """Finite-difference Jacobian dr/dθ (central; one-sided at a bound); parallel via pmap."""
    p = theta.size
    points: list[np.ndarray] = []
    plan: list[tuple[int, int, int, float]] = []  # (j, index_plus, index_minus, denominator)
    for j in range(p):
        up = theta.copy()
        dn = theta.copy()
        if theta[j] + step <= 1.0 and theta[j] - step >= 0.0:
            up[j] += step
            dn[j] -= step
            plan.append((j, len(points), len(points) + 1, 2.0 * step))
            points += [up, dn]
        elif theta[j] + step <= 1.0:
            up[j] += step
            plan.append((j, len(points), -1, step))
            points.append(up)
        else:
            dn[j] -= step
            plan.append((j, -1, len(points), step))
            points.append(dn)
    values = pmap(objective, points)
    jac = np.empty((r0.size, p))
    for j, ip, im, den in plan:
        rp = values[ip] if ip >= 0 else r0
        rm = values[im] if im >= 0 else r0
        jac[:, j] = (rp - rm) / den
    return jac, len(points)


def _uncertainty(
    jac_theta: np.ndarray, r: np.ndarray, span: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    m, p = jac_theta.shape
    jac = jac_theta / span[np.newaxis, :]  # d r / d x (physical units)
    if m <= p:
        nan = np.full((p, p), np.nan)
        return nan, nan
    s2 = float(r @ r) / (m - p)
    cov = s2 * np.linalg.pinv(jac.T @ jac)
    sd = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(sd, sd)
    return cov, corr


def calibrate(
    records: TestRecord | Sequence[TestRecord],
    parameters: Sequence[Parameter],
    *,
    simulator: Simulator | None = None,
    weights: MisfitWeights | None = None,
    method: str = "global",
    seed: int | None = 0,
    popsize: int = 10,
    maxiter: int = 40,
    tol: float = 0.01,
    max_nfev: int = 30,
    fd_step: float | Sequence[float] = (0.02, 0.005),
    client: Any = None,
    scheduler_address: str | None = None,
    n_workers: int | None = 0,
    progress: bool = False,
) -> CalibrationResult:
    """Fit the varied ``parameters`` so that simulations reproduce ``records``.

    Parameters
    ----------
    records : TestRecord or sequence of TestRecord
        Tests fitted together (one parameter set for all); fit each alone for a Table-2 style
        per-test calibration (:func:`onbottom.calibration.summary.fit_each`).
    parameters : sequence of Parameter
        All simulator parameters; those with ``vary=True`` are fitted within their bounds.
    simulator : callable or None
        ``simulator(record, params)``; default
        :class:`~onbottom.calibration.simulators.CentrifugeSimulator` (section solver with the
        centrifuge load programme named by ``record.programme``).
    weights : MisfitWeights or None
        Misfit term weights (default all 1).
    method : {"global", "local"}
        ``"global"``: differential evolution, then least-squares polish. ``"local"``: least
        squares from the parameters' values.
    seed : int or None
        Seed of differential evolution.
    popsize, maxiter, tol : int, int, float
        Differential-evolution population multiplier, generations, relative tolerance.
    max_nfev : int
        Limit of least-squares iterations (each costs 1 + Jacobian evaluations).
    fd_step : float or sequence of float
        Finite-difference step(s) as a fraction of each parameter's range, each in
        (0, 0.25]. With several, the polish is repeated with each step in turn from the
        previous optimum (continuation: a coarse step to average over the non-smooth
        response, then a fine one to resolve narrow valleys); the covariance uses the last.
    client, scheduler_address, n_workers
        Parallel evaluation of the population and the Jacobian columns on Dask (see
        :func:`onbottom.study.engine.dask_client`); ``n_workers=0`` (default, with no client
        or address) evaluates serially in this process.
    progress : bool
        Show progress bars for the parallel evaluations.

    Returns
    -------
    CalibrationResult
    """
    recs = (records,) if isinstance(records, TestRecord) else tuple(records)
    if not recs:
        raise InputError("records is invalid: give at least one TestRecord")
    params = tuple(parameters)
    names = [p.name for p in params]
    if len(set(names)) != len(names):
        raise InputError(f"parameters repeat a name: {names}")
    varied = [p for p in params if p.vary]
    if not varied:
        raise InputError("no parameter has vary=True: nothing to calibrate")
    one_of("method", method, ("global", "local"))
    fd_steps = tuple(np.atleast_1d(np.asarray(fd_step, dtype=float)).tolist())
    if not fd_steps:
        raise InputError("fd_step is invalid: give at least one step")
    for st in fd_steps:
        in_range("fd_step", st, 0.0, 0.25, low_inclusive=False)
    objective = Objective(
        recs, params, simulator or _default_simulator(), weights or MisfitWeights()
    )
    t0 = time.perf_counter()
    # configuration errors (unknown parameter, record without programme) must not be mistaken
    # for failed runs: simulate once at the start values and let InputError through
    start_values = {p.name: p.value for p in params}
    for rec in recs:
        try:
            objective.simulator(rec, start_values)
        except InputError:
            raise
        except Exception as exc:  # a failing start point is allowed; the search moves on
            logger.info("start values fail for %s: %s", rec.name, exc)
    serial = client is None and scheduler_address is None and n_workers == 0
    if serial:
        result = _calibrate(
            objective, SerialMap(), method, seed, popsize, maxiter, tol, max_nfev, fd_steps, t0
        )
    else:
        with dask_client(client, scheduler_address=scheduler_address, n_workers=n_workers) as c:
            pmap = ParallelMap(c, progress=progress)
            result = _calibrate(
                objective, pmap, method, seed, popsize, maxiter, tol, max_nfev, fd_steps, t0
            )
    return replace(result, n_evaluations=result.n_evaluations + 1)  # + the check run above


def _calibrate(
    objective: Objective,
    pmap: Callable,
    method: str,
    seed: int | None,
    popsize: int,
    maxiter: int,
    tol: float,
    max_nfev: int,
    fd_steps: tuple[float, ...],
    t0: float,
    xtol: float = 1e-6,
) -> CalibrationResult:
    """The fit in stages: start point, global search (``method="global"``), local least
    squares per finite-difference step, then the result with its uncertainty and misfits."""
    varied = objective.varied
    theta0 = np.array([(v.value - v.lower) / v.span for v in varied])
    r_start = objective(theta0)
    history: dict[str, float] = {"start": float(r_start @ r_start)}
    messages: list[str] = []
    n_eval = 1
    if method == "global":
        theta0, nfev = _global_search(
            objective, pmap, theta0, seed, popsize, maxiter, tol, history, messages
        )
        n_eval += nfev
    cached = _CachedObjective(objective, pmap)
    theta, r, status = _local_search(cached, theta0, fd_steps, max_nfev, xtol, history, messages)
    # Jacobian at the optimum for the uncertainty (the solver's last one may be older)
    jac_theta = cached.jacobian(fd_steps[-1])(theta)
    n_eval += cached.n_fun + cached.n_jac
    return _result(objective, method, theta, r, jac_theta, status, messages, n_eval, history, t0)


def _global_search(
    objective: Objective,
    pmap: Callable,
    theta0: np.ndarray,
    seed: int | None,
    popsize: int,
    maxiter: int,
    tol: float,
    history: dict[str, float],
    messages: list[str],
) -> tuple[np.ndarray, int]:
    """Differential evolution on the unit cube from ``theta0``: its best point, evaluations."""
    from scipy.optimize import differential_evolution

    de = differential_evolution(
        _Scalar(objective),
        bounds=[(0.0, 1.0)] * len(objective.varied),
        seed=seed,
        popsize=popsize,
        maxiter=maxiter,
        tol=tol,
        init="latinhypercube",
        polish=False,
        updating="deferred",
        workers=pmap,
        x0=theta0,
    )
    history["global"] = float(de.fun)
    # DE stopping at maxiter is normal here: the polish that follows decides convergence
    messages.append(f"differential evolution: {de.message}")
    return np.clip(de.x, 0.0, 1.0), int(de.nfev)


class _CachedObjective:
    """The residuals of the last point asked (least squares asks twice) and finite-difference
    Jacobians, counting the simulations of each."""

    def __init__(self, objective: Objective, pmap: Callable) -> None:
        self.objective, self.pmap = objective, pmap
        self.cache: dict[bytes, np.ndarray] = {}
        self.n_fun = self.n_jac = 0

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        key = np.asarray(theta, dtype=float).tobytes()
        if key not in self.cache:
            self.cache.clear()
            self.cache[key] = self.objective(theta)
            self.n_fun += 1
        return self.cache[key]

    def jacobian(self, step: float) -> Callable[[np.ndarray], np.ndarray]:
        def jac(theta: np.ndarray) -> np.ndarray:
            r0 = self(theta)
            j, n = _jacobian(self.objective, np.asarray(theta, dtype=float), r0, step, self.pmap)
            self.n_jac += n
            return j

        return jac


def _local_search(
    fun: _CachedObjective,
    theta: np.ndarray,
    fd_steps: tuple[float, ...],
    max_nfev: int,
    xtol: float,
    history: dict[str, float],
    messages: list[str],
) -> tuple[np.ndarray, np.ndarray, Status]:
    """Bounded least squares (trf) once per finite-difference step, each from the last:
    the optimum, its residuals and the status (NOT_CONVERGED if a stage hit ``max_nfev``)."""
    from scipy.optimize import least_squares

    p = theta.size
    status = Status.CONVERGED
    for k, step in enumerate(fd_steps):
        lsq = least_squares(
            fun,
            theta,
            jac=fun.jacobian(step),
            bounds=(np.zeros(p), np.ones(p)),
            method="trf",
            x_scale=1.0,
            max_nfev=max_nfev,
            xtol=xtol,
            ftol=1e-8,
            gtol=1e-10,
        )
        theta = np.clip(lsq.x, 0.0, 1.0)
        r = fun(theta)
        history[f"local[{k}]"] = float(r @ r)
        messages.append(f"least squares (step {step:g}): {lsq.message}")
        if lsq.status == 0:  # scipy's own code: the evaluation limit was reached
            status = Status.NOT_CONVERGED
    history["local"] = float(r @ r)
    return theta, r, status


def _result(
    objective: Objective,
    method: str,
    theta: np.ndarray,
    r: np.ndarray,
    jac_theta: np.ndarray,
    status: Status,
    messages: list[str],
    n_eval: int,
    history: dict[str, float],
    t0: float,
) -> CalibrationResult:
    """The fitted parameters, their uncertainty and each record's misfit at the optimum."""
    varied = objective.varied
    cov, corr = _uncertainty(jac_theta, r, objective.span)
    x = objective.lower + theta * objective.span
    fitted = tuple(
        replace(par, value=float(x[varied.index(par)])) if par.vary else par
        for par in objective.parameters
    )
    std = {
        v.name: float(math.sqrt(cov[i, i])) if cov[i, i] >= 0 else math.nan
        for i, v in enumerate(varied)
    }
    values = {par.name: par.value for par in fitted}
    misfits = []
    all_failed = True
    for rec in objective.records:
        sim = objective.simulate(rec, values)
        n_eval += 1
        if sim is None:
            misfits.append(
                Misfit(terms={}, contributions={}, total=math.nan, measured={}, simulated={})
            )
        else:
            all_failed = False
            misfits.append(evaluate_misfit(rec, sim, objective.weights))
    if all_failed:
        status = Status.NO_SOLUTION
        messages.append("the simulation failed at the fitted parameters")
    return CalibrationResult(
        parameters=fitted,
        names=tuple(v.name for v in varied),
        std_errors=std,
        covariance=_readonly(cov),
        correlation=_readonly(corr),
        misfit=float(r @ r),
        misfits=tuple(misfits),
        residuals=_readonly(r),
        success=status.success,
        status=status,
        message="; ".join(messages),
        n_evaluations=n_eval,
        method=method,
        wall_time=time.perf_counter() - t0,
        record_names=tuple(rec.name for rec in objective.records),
        history=history,
    )


def grid_search(
    records: TestRecord | Sequence[TestRecord],
    parameters: Sequence[Parameter],
    grid: Mapping[str, Sequence[float]],
    *,
    simulator: Simulator | None = None,
    weights: MisfitWeights | None = None,
    client: Any = None,
    scheduler_address: str | None = None,
    n_workers: int | None = 0,
    progress: bool = False,
) -> xr.Dataset:
    """Misfit on the outer product of ``grid`` (the paper's parametric study), on the sweep engine.

    Parameters not in ``grid`` keep their ``value``. Returns the :func:`~onbottom.study.sweep.sweep`
    dataset with ``misfit`` (total), ``misfit_<i>`` per record, ``n_failed_simulations``, and
    attributes ``best_<name>`` at the minimum.
    """
    recs = (records,) if isinstance(records, TestRecord) else tuple(records)
    known = {p.name for p in parameters}
    unknown = set(grid) - known
    if unknown:
        raise InputError(f"grid names {sorted(unknown)} are not parameters ({sorted(known)})")
    objective = Objective(
        recs, parameters, simulator or _default_simulator(), weights or MisfitWeights()
    )
    ds = sweep(
        _GridPoint(objective),
        grid,
        client=client,
        scheduler_address=scheduler_address,
        n_workers=n_workers,
        progress=progress,
    )
    ds.attrs["records"] = ", ".join(r.name for r in recs)
    ds["misfit"].attrs["long_name"] = "misfit Σr² over all records"
    if np.isfinite(ds["misfit"]).any():
        best = ds["misfit"].where(np.isfinite(ds["misfit"])).argmin(...)
        for name, idx in best.items():
            ds.attrs[f"best_{name}"] = float(ds[name].values[int(idx)])
        ds.attrs["best_misfit"] = float(ds["misfit"].min())
    return ds


def misfit_slices(
    result: CalibrationResult,
    records: TestRecord | Sequence[TestRecord],
    *,
    simulator: Simulator | None = None,
    weights: MisfitWeights | None = None,
    n: int = 11,
    half_width: float = 0.2,
    n_workers: int | None = 0,
    client: Any = None,
) -> dict[str, xr.Dataset]:
    """1-D slices of the misfit through the optimum, one per varied parameter.

    Each slice varies one parameter over ``value ± half_width·range`` (clipped to its bounds)
    with the others at their fitted values — a direct look at the valley that the covariance
    linearises (a profile would re-optimise the others; slices are cheaper).
    """
    out: dict[str, xr.Dataset] = {}
    fitted = result.parameters
    for par in fitted:
        if not par.vary:
            continue
        lo = max(par.lower, par.value - half_width * par.span)
        hi = min(par.upper, par.value + half_width * par.span)
        values = np.unique(np.append(np.linspace(lo, hi, n), par.value))
        out[par.name] = grid_search(
            records,
            fitted,
            {par.name: values},
            simulator=simulator,
            weights=weights,
            n_workers=n_workers,
            client=client,
        )
    return out


def record_misfit(
    *,
    record: TestRecord,
    simulator: Simulator | None = None,
    weights: MisfitWeights | None = None,
    **params: float,
) -> dict[str, float]:
    """Misfit of one simulation of ``record`` at parameter values ``params`` (for sweeps).

    Returns ``misfit`` (Σr²) and ``term_<name>`` for each term; raises if the simulation
    fails (the sweep records the failure).
    """
    sim_fn = simulator or _default_simulator()
    res = sim_fn(record, {k: float(v) for k, v in params.items()})
    if getattr(res, "success", True) is False:
        raise RuntimeError(f"simulation failed: {getattr(res, 'message', '')}")
    m = evaluate_misfit(record, res, weights)
    return {"misfit": m.total, **{f"term_{k}": v for k, v in m.terms.items()}}


register("misfit", record_misfit)
