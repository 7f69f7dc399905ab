"""Run a reliability case: the climate, the exceedance estimates per limit, the design.

:func:`run_reliability` is what ``onbottom reliability`` calls; it writes the campaign stores
``campaign.zarr`` (the long-term estimates) and ``design.zarr`` (the contour runs) into the
output folder, so a rerun of the same case after a kill resumes where it stopped.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from onbottom.reliability.campaign import Campaign, CampaignStats
from onbottom.reliability.design import ResponseDesignResult, response_based_design
from onbottom.reliability.dynamic import ExceedanceEstimate, estimate_exceedance
from onbottom.reliability.setup import ReliabilitySetup
from onbottom.reliability.storm_model import StormModel

__all__ = [
    "F101_TARGETS",
    "ReliabilityRun",
    "planned_storms",
    "require_packages",
    "run_payload",
    "run_reliability",
    "storm_plan",
    "target_comparison",
]


F101_TARGETS = {"low": 1.0e-3, "medium": 1.0e-4, "high": 1.0e-5}
"""Nominal target annual failure probabilities per pipeline of DNV-OS-F101 (2013), Sec. 2,
Table 2-5, for the ultimate limit state (ULS), per safety class (the SLS row is 1e-2, 1e-3,
1e-3). F109's stability criteria are compared with the ULS row here."""

F101_SOURCE = "DNV-OS-F101 (2013) Sec. 2 Table 2-5, ULS, annual per pipeline"


def target_comparison(estimates: list[ExceedanceEstimate], safety_class: str) -> dict[str, Any]:
    """Each estimate's annual probability against the F101 target of ``safety_class``:
    ``pass`` when the 95 % interval's upper end is below the target, ``fail`` when its lower end
    is above it, ``undecided`` otherwise (the estimate cannot tell)."""
    target = F101_TARGETS[safety_class]
    rows = []
    for e in estimates:
        lo, hi = e.annual_interval
        hi = e.annual if not math.isfinite(hi) else hi
        verdict = "pass" if hi <= target else "fail" if lo > target else "undecided"
        rows.append({"label": e.label, "annual": e.annual, "upper": hi, "verdict": verdict})
    return {
        "source": F101_SOURCE,
        "safety_class": safety_class,
        "annual_target": target,
        "limits": rows,
    }


@dataclass
class ReliabilityRun:
    """What :func:`run_reliability` found."""

    estimates: list[ExceedanceEstimate]
    design: ResponseDesignResult | None
    storms_per_year: float
    diameter: float
    inputs: list[str]
    stats: CampaignStats
    design_stats: CampaignStats | None
    climate: dict[str, Any] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    target: dict[str, Any] = field(default_factory=dict)
    plans: list[dict[str, Any]] = field(default_factory=list)


def run_reliability(
    setup: ReliabilitySetup,
    out: Path,
    *,
    n_workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int], None] | None = None,
    on_estimate: Callable[[ExceedanceEstimate, dict[str, Any]], None] | None = None,
) -> ReliabilityRun:
    """Estimate every limit of the case and, with ``[reliability.design]``, the design.

    ``on_estimate`` is called with each limit's estimate and its :func:`storm_plan` (the
    storms and CPU time the estimator needs for the case's ``target_cv``) as soon as it is
    known, before the next limit runs (the CLI prints it).
    """
    climate, result, info, notes = _climate(setup)
    rate = climate.rate if climate is not None else float(setup.storms_per_year)
    user = list(setup.inputs)
    model = StormModel(
        setup.storm,
        inputs=tuple(p.name for p in user),
        climate=climate,
        pipe_heading_deg=setup.climate.pipe_heading_deg if setup.climate else 0.0,
        soil_kind=setup.seabed_model,
        stop_at=stop_displacement(setup),
    )
    params = (climate.parameters() if climate is not None else []) + user
    out.mkdir(parents=True, exist_ok=True)
    estimates = []
    plans = []
    with Campaign(
        model,
        out / "campaign.zarr",
        task_size=setup.task_size,
        n_workers=n_workers,
        scheduler=scheduler,
        progress=progress,
    ) as camp:
        for label, limit in setup.limits:
            e = estimate_exceedance(
                camp,
                params,
                limit,
                label=label,
                method=setup.method,
                target_cv=setup.target_cv,
                max_storms=setup.max_storms,
                block_size=setup.block_size,
                seed=setup.seed,
                storms_per_year=rate,
                design_life_years=setup.design_life_years,
                pilot_storms=setup.form_storms,
            )
            estimates.append(e)
            plans.append(storm_plan(e, setup.target_cv, camp.stats))
            if on_estimate is not None:
                on_estimate(e, plans[-1])
        stats = camp.stats
        fails = camp.store.failures()
    notes += _estimate_notes(setup, estimates, len(fails))
    design, dstats = None, None
    if setup.design is not None and result is not None:
        design, dstats, note = _design(setup, result, climate, user, out, n_workers, scheduler,
                                       progress)  # fmt: skip
        if note:
            notes.append(f"design: {note}")
    return ReliabilityRun(
        estimates=estimates,
        design=design,
        storms_per_year=rate,
        diameter=model.diameter,
        inputs=[p.name for p in params],
        stats=stats,
        design_stats=dstats,
        climate=info,
        notes=notes,
        target=target_comparison(estimates, setup.safety_class),
        plans=plans,
    )


def _climate(setup: ReliabilitySetup) -> tuple[Any, Any, dict[str, Any], list[str]]:
    """Stage of :func:`run_reliability`: the storm climate fitted to the case's hindcast
    (climate, metocean result, its summary, the hindcast's notes); Nones without one."""
    if setup.climate is None:
        return None, None, {}, []
    from onbottom.metocean import MetoceanOptions, analyse_hindcast, read_hindcast
    from onbottom.metocean.hindcast import hindcast_notes
    from onbottom.reliability.climate import StormClimate

    rps = {1.0, 10.0, 100.0}
    if setup.design is not None:
        rps.add(float(setup.design.return_period))
    hc = read_hindcast(setup.climate.hindcast)
    early_notes = list(hindcast_notes(hc))
    result = analyse_hindcast(
        hc,
        MetoceanOptions(
            sectors=setup.climate.sectors,
            return_periods=tuple(sorted(rps)),
            storm_rate=setup.climate.storm_rate,
        ),
    )
    climate = StormClimate.from_result(result, current=setup.climate.current)
    info = {
        "hindcast": str(setup.climate.hindcast),
        "rate": climate.rate,
        "threshold": climate.threshold,
        "gpd_scale": climate.gpd_scale,
        "gpd_shape": climate.gpd_shape,
        "sectors": list(climate.sectors),
        "sector_frequencies": list(climate.sector_frequencies),
        "current_model": None if climate.current is None else climate.current.as_dict(),
        "joint_model": climate.joint.as_dict(),
    }
    return climate, result, info, early_notes


def _estimate_notes(
    setup: ReliabilitySetup, estimates: list[ExceedanceEstimate], n_failed: int
) -> list[str]:
    """Stage of :func:`run_reliability`: the notes on the estimates (failed runs, CV above
    target, upper bounds, a short storm, a small subset level)."""
    notes: list[str] = []
    if n_failed:
        notes.append(f"{n_failed} storm runs raised (counted as exceedances); see the store")
    for e in estimates:
        notes.extend(f"{e.label}: {n}" for n in e.notes)
        if e.method != "subset" and e.cv > setup.target_cv:
            notes.append(
                f"{e.label}: CV {e.cv:.2f} above the target {setup.target_cv:g} at max_storms"
            )
        if e.upper_bound:
            notes.append(
                f"{e.label}: the probability is an upper bound ({e.interval_kind}), not an estimate"
            )
    peak_h = max(st.duration_s for st in setup.storm.storm.stages) / 3600.0
    if peak_h < 3.0 - 1e-9:
        notes.append(
            f"storm peak {peak_h:g} h: shorter than DNV-RP-F109's 3-h design sea state;"
            " the probabilities are for that shorter storm (peak_hours in the case)"
        )
    if setup.method == "subset" and setup.block_size < 500:
        notes.append(
            f"subset simulation with {setup.block_size} storms a level: biased upward and its"
            " interval too narrow below about 500 (docs/theory/reliability.md)"
        )
    return notes


def _design(setup, result, climate, user, out, n_workers, scheduler, progress):
    """Stage of :func:`run_reliability`: the response-based design on the IFORM contour of
    ``[reliability.design]``; returns (design, campaign counters, extrapolation note)."""
    from onbottom.metocean.joint import iform_contour
    from onbottom.metocean.run import extrapolation_note

    d = setup.design
    peak_h = setup.storm.storm.stages[0].duration_s / 3600.0
    contour = iform_contour(result.joint, d.return_period, peak_h, d.contour_points)
    omni = result.hs["omni"]
    hs_r = float(omni.value[list(omni.return_periods).index(float(d.return_period))])
    tp_r = float(result.joint.tp_quantile(hs_r, 0.5))
    fixed = [p for p in user if p.name not in ("hs", "tp")]
    cm = climate.current if climate is not None else None
    dmodel = StormModel(
        setup.storm,
        inputs=("hs", "tp", *(p.name for p in fixed))
        + (("current_velocity",) if cm is not None else ()),
        soil_kind=setup.seabed_model,
    )
    with Campaign(
        dmodel,
        out / "design.zarr",
        task_size=1,
        n_workers=n_workers,
        scheduler=scheduler,
        progress=progress,
    ) as dc:
        design = response_based_design(
            dc,
            {p.name: p.mean() for p in fixed},
            contour,
            (hs_r, tp_r),
            return_period=d.return_period,
            seeds=d.seeds,
            top_points=d.top_points,
            top_seeds=d.top_seeds,
            fractile=d.fractile,
            # with the hindcast's current: the median current given each point's H_s
            current_given_hs=None if cm is None else (lambda h: float(cm.quantile(h, 0.5))),
        )
        dstats = dc.stats
    note = extrapolation_note(float(d.return_period), float(result.hindcast.years))
    return design, dstats, note


def storm_plan(e: ExceedanceEstimate, target_cv: float, stats: CampaignStats) -> dict[str, Any]:
    """The storms and CPU time the estimator of ``e`` needs for the coefficient of variation
    ``target_cv`` (the interval's half-width is about 1.96·CV of the probability), from its
    variance and the campaign's measured rate.

    Monte Carlo: Var p̂ = p(1 − p)/n, so n = (1 − p)/(p·CV²); with no failing storm yet (p only
    bounded from above) the same count at the bound, for any method: Monte Carlo needs at least
    that many (``lower_bound``). Importance sampling and subset simulation:
    the variance falls as 1/n at a fixed sampling density (centre, level probability), so
    n = n_used·(CV/target)², the pilot storms on top. CPU seconds: n times the measured CPU
    time of a storm in the workers (:meth:`CampaignStats.cpu_seconds_per_run`, the median over
    the recent tasks, free of the first tasks' compilation; NaN when no storm was computed in
    this run, all read back).

    Returns ``label``, ``target_cv``, ``method`` (of the count), ``storms`` (needed),
    ``storms_used``,
    ``lower_bound`` (True when p is only bounded), ``cpu_seconds_per_storm``,
    ``cpu_seconds``.
    """
    p = e.probability
    lower = bool(e.upper_bound or e.failures == 0)
    mc = e.method == "monte_carlo" or lower or not math.isfinite(e.cv) or e.cv <= 0.0
    if mc:
        n = (1.0 - p) / (p * target_cv**2) if 0.0 < p < 1.0 else math.nan
    else:
        n = (e.storms - e.pilot_storms) * (e.cv / target_cv) ** 2 + e.pilot_storms
    rate = stats.cpu_seconds_per_run()
    storms = float(math.ceil(n)) if math.isfinite(n) else math.nan
    return {
        "label": e.label,
        "target_cv": float(target_cv),
        "method": "monte_carlo" if mc else e.method,
        "storms": storms,
        "storms_used": int(e.storms),
        "lower_bound": lower,
        "cpu_seconds_per_storm": float(rate),
        "cpu_seconds": float(storms * rate),
    }


EARLY_STOP_MARGIN = 1e-6
"""Relative margin of the early stop above the largest limit [-]: a stopped storm's
displacement is strictly beyond every limit."""


def stop_displacement(setup: ReliabilitySetup) -> float | None:
    """Where the campaign's storms stop [m]: just above the largest limit asked (every
    exceedance verdict is known there, :mod:`onbottom.reliability.storm_model`). Every
    estimator reads only the verdicts beyond the largest limit: Monte Carlo and importance
    sampling count failures (the cross-entropy pilot's levels are quantiles of g that stop at
    g = 0, and a stopped storm has g < 0 for every limit), subset simulation's levels lie
    below the limit."""
    return max(v for _, v in setup.limits) * (1.0 + EARLY_STOP_MARGIN)


def planned_storms(setup: ReliabilitySetup) -> int:
    """An upper estimate of the storms a case runs (progress bar total)."""
    n = len(setup.limits) * setup.max_storms
    if setup.method == "importance":
        n += len(setup.limits) * setup.form_storms
    if setup.design is not None:
        d = setup.design
        n += d.contour_points * d.seeds + d.top_points * d.top_seeds + d.top_seeds
    return int(n)


def require_packages() -> None:
    """Raise :class:`~onbottom.errors.InputError` naming the optional packages a reliability
    run needs (openturns, zarr) when they are not installed."""
    import importlib.util

    from onbottom.errors import InputError

    missing = [m for m in ("openturns", "zarr") if importlib.util.find_spec(m) is None]
    if missing:
        raise InputError(
            f"onbottom reliability needs the optional package(s) {', '.join(missing)}:"
            " pip install 'onbottom[reliability,metocean]'"
        )


def run_payload(r: ReliabilityRun) -> dict[str, Any]:
    """The results of a run as plain data (the ``onbottom reliability --json`` keys except
    ``case``, ``out`` and ``files``): ``success`` (false when a storm run failed numerically),
    ``diameter`` [m], ``storms_per_year`` [1/year], ``inputs`` (the random inputs, the storm
    seed last), ``climate``, ``estimates``, ``design``, ``campaign`` (requested, computed,
    reused, failed, seconds_per_storm [s]), ``target`` (:func:`target_comparison`), ``plan``
    (per limit, :func:`storm_plan`) and ``notes``."""
    stats = [s for s in (r.stats, r.design_stats) if s is not None]
    computed = sum(s.computed for s in stats)
    failed = sum(s.failed for s in stats) + sum(e.failed_runs for e in r.estimates)
    return {
        "success": failed == 0,
        "diameter": r.diameter,
        "storms_per_year": r.storms_per_year,
        "inputs": [*r.inputs, "storm_seed"],
        "climate": r.climate,
        "estimates": [e.to_dict() for e in r.estimates],
        "design": None if r.design is None else r.design.to_dict(),
        "campaign": {
            "requested": sum(s.requested for s in stats),
            "computed": computed,
            "reused": sum(s.reused for s in stats),
            "failed": sum(s.failed for s in stats),
            "seconds_per_storm": (
                sum(s.compute_seconds for s in stats) / computed if computed else math.nan
            ),
        },
        "target": r.target,
        "plan": r.plans,
        "notes": r.notes,
    }


def _finite(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None
