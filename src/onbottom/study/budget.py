"""Run-time and memory estimates of many-storm runs, checked before they start.

``onbottom storm --seeds``, ``onbottom curves`` and ``onbottom sweep`` print nothing for
minutes to days; a grid of 10⁶ storms started by a typo should be refused at once, with the
estimate and what to change. :func:`check` raises :class:`~onbottom.errors.BudgetError` (an
input error, exit status 1) where an estimate exceeds :data:`BUDGET_WALL_HOURS` of wall-clock
time on the workers or :data:`BUDGET_MEMORY_BYTES` of memory; ``--force`` runs it anyway.

The figures are deliberately rough (within a factor of about 2 on the machines measured):

* :data:`SECTION_STEP_SECONDS`: one step of the pipe-section storm solver. Measured: a 3.5-h
  storm at a 0.1-s step (126,000 steps) takes 0.15–0.20 s wall on one core of the shared
  2-core machine (docs/theory/storm_section.md, "Speed"), i.e. 1.2–1.6 µs per step; 2 µs is
  used (loaded machine);
* :data:`SECTION_STORM_OVERHEAD_SECONDS`: the flow synthesis (FFT) and set-up of one storm;
* :data:`SWEEP_POINT_SECONDS`: one point of a sweep of a registered function (a centrifuge
  test run by the section solver takes 0.1–1 s; 1 s is used);
* memory: the near-bed flow of one storm (velocity and acceleration, float64, at T_p/50) per
  worker, and :data:`RESULT_BYTES_PER_RUN` per run of the gathered result.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from onbottom.errors import BudgetError

__all__ = [
    "BUDGET_MEMORY_BYTES",
    "BUDGET_WALL_HOURS",
    "Estimate",
    "check",
    "combined",
    "curve_points",
    "pipeline_storms",
    "section_storms",
    "sweep_points",
]

SECTION_STEP_SECONDS = 2.0e-6
"""Wall-clock seconds per solver step of a pipe-section storm on one core (see above)."""

SECTION_STORM_OVERHEAD_SECONDS = 0.05
"""Flow synthesis and set-up of one storm [s]."""

SWEEP_POINT_SECONDS = 1.0
"""Wall-clock seconds per point of a sweep (a section-solver run) on one core."""

RESULT_BYTES_PER_RUN = 2_000
"""Bytes of the gathered result per storm or sweep point (a row of a dozen numbers, labels)."""

BUDGET_WALL_HOURS = 12.0
"""Longest estimated wall-clock time accepted without ``--force`` [h]."""

BUDGET_MEMORY_BYTES = 8.0e9
"""Largest estimated memory accepted without ``--force`` [bytes]."""


@dataclass(frozen=True)
class Estimate:
    """An estimate of a run: ``runs`` storms or points, ``wall_s`` on ``workers`` workers,
    ``memory_bytes`` in all; ``what`` says what is counted."""

    runs: float
    wall_s: float
    memory_bytes: float
    workers: int
    what: str

    def describe(self) -> str:
        return (
            f"{self.what}: about {_duration(self.wall_s)} on {self.workers} worker(s) and"
            f" {self.memory_bytes / 1e9:.2g} GB"
        )


def _duration(seconds: float) -> str:
    if seconds < 120.0:
        return f"{seconds:.3g} s"
    if seconds < 7200.0:
        return f"{seconds / 60.0:.3g} min"
    if seconds < 3.0 * 86400.0:
        return f"{seconds / 3600.0:.3g} h"
    return f"{seconds / 86400.0:.3g} days"


def _workers(workers: int | None) -> int:
    if workers is None:
        return max(1, os.cpu_count() or 1)
    return max(1, int(workers))


def _storm_seconds(duration_s: float, time_step: float) -> float:
    steps = duration_s / max(time_step, 1e-9)
    return SECTION_STORM_OVERHEAD_SECONDS + SECTION_STEP_SECONDS * steps


def _flow_bytes(duration_s: float, tp: float) -> float:
    samples = duration_s / max(tp / 50.0, 1e-3)
    return 2.0 * 8.0 * samples


def section_storms(
    n_storms: int,
    duration_s: float,
    time_step: float,
    *,
    tp: float,
    workers: int | None,
) -> Estimate:
    """``n_storms`` pipe-section storms of ``duration_s`` [s] at the largest step
    ``time_step`` [s] (peak period ``tp`` [s]) on ``workers`` (None: one per core)."""
    w = _workers(workers)
    per = _storm_seconds(duration_s, time_step)
    wall = per * math.ceil(n_storms / w)
    mem = w * _flow_bytes(duration_s, tp) * 1.5 + n_storms * RESULT_BYTES_PER_RUN
    return Estimate(n_storms, wall, mem, w, f"{n_storms} storms of {duration_s / 3600:.3g} h")


def curve_points(
    n_points: int,
    seeds: int,
    duration_s: float,
    time_step: float,
    *,
    tolerance: float,
    l_min: float,
    l_max: float,
    tp: float,
    workers: int | None,
) -> Estimate:
    """A curves grid of ``n_points`` (soil × N × M × K × criterion): per point the bracket
    search (about 3 evaluations) and the bisection in log L from [l_min, l_max] down to a
    relative width ``tolerance``, each evaluation ``seeds`` storms at most."""
    bisections = math.ceil(math.log2(max(math.log(l_max / l_min) / math.log1p(tolerance), 1.0)))
    evaluations = 3 + bisections
    storms = n_points * evaluations * seeds
    w = _workers(workers)
    per_point = evaluations * seeds * _storm_seconds(duration_s, time_step)
    wall = per_point * math.ceil(n_points / w)
    mem = w * seeds * _flow_bytes(duration_s, tp) * 1.5 + n_points * RESULT_BYTES_PER_RUN
    return Estimate(
        storms,
        wall,
        mem,
        w,
        f"{n_points} curve points × about {evaluations} evaluations × {seeds} seeds ="
        f" {storms:.3g} storms of {duration_s / 3600:.3g} h",
    )


def pipeline_storms(
    n_storms: int,
    run_seconds: float,
    memory_bytes: float,
    *,
    workers: int | None,
) -> Estimate:
    """``n_storms`` pipeline-FE storms, each estimated at ``run_seconds`` [s] on one core and
    ``memory_bytes`` of kinematics (:func:`onbottom.dynamics.pipeline.storm_run.run_cost`:
    ~1 µs per node-step, ~0.5 MB per node-hour)."""
    w = min(_workers(workers), max(n_storms, 1))
    wall = run_seconds * math.ceil(n_storms / w)
    mem = w * memory_bytes + n_storms * RESULT_BYTES_PER_RUN
    return Estimate(n_storms, wall, mem, w, f"{n_storms} pipeline storms")


def combined(first: Estimate, then: Estimate) -> Estimate:
    """Two parts of one run, one after the other on the same workers: runs, wall time and
    memory add (a worker may hold both parts' data), the workers are the larger count."""
    return Estimate(
        first.runs + then.runs,
        first.wall_s + then.wall_s,
        first.memory_bytes + then.memory_bytes,
        max(first.workers, then.workers),
        f"{first.what} + {then.what}",
    )


def sweep_points(n_points: int, *, workers: int | None) -> Estimate:
    """A sweep of ``n_points`` grid points of a registered function."""
    w = _workers(workers)
    wall = SWEEP_POINT_SECONDS * math.ceil(n_points / w)
    mem = n_points * RESULT_BYTES_PER_RUN
    return Estimate(n_points, wall, mem, w, f"{n_points:.3g} sweep points (~1 s each)")


def check(estimate: Estimate, *, force: bool, field: str) -> None:
    """Raise :class:`BudgetError` naming ``field`` where ``estimate`` exceeds the budget
    (unless ``force``)."""
    if force:
        return
    over = []
    if estimate.wall_s > BUDGET_WALL_HOURS * 3600.0:
        over.append(f"more than {BUDGET_WALL_HOURS:g} h")
    if estimate.memory_bytes > BUDGET_MEMORY_BYTES:
        over.append(f"more than {BUDGET_MEMORY_BYTES / 1e9:g} GB")
    if not over:
        return
    err = BudgetError(
        f"{field} is refused: the run is estimated at {estimate.describe()} ({' and '.join(over)},"
        " the budget of a run); make the grid, the number of seeds or the storms smaller, add"
        " workers, or pass --force to run it anyway"
    )
    err.field = field  # type: ignore[attr-defined]
    raise err
