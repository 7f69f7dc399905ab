"""N seeds of one pipeline FE storm run on Dask (``onbottom storm --seeds N`` with ``[pipeline]``).

Each seed is an independent storm (random phases of ``numpy.random.default_rng(seed)``)
simulated with :func:`onbottom.dynamics.pipeline.storm_run.simulate_pipeline_storm`, one NetCDF
file per seed. Seeds run on :func:`onbottom.study.engine.dask_client` (an embedded
``LocalCluster`` or a remote scheduler; the built run is sent to the workers) or in this
process (``workers=0``); one seed runs in this process, with a progress bar. A seed whose run
raises is recorded with status −9 and its message, never dropped. Every seed's file resumes
from its checkpoint after an interruption (Ctrl-C raises :class:`onbottom.errors.RunInterrupted`).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from onbottom.dynamics.pipeline.solver import PipelineResult
from onbottom.dynamics.pipeline.storm_run import PipelineStormRun, simulate_pipeline_storm
from onbottom.errors import InputError
from onbottom.study.storm_seeds import seed_failure

__all__ = [
    "PipelineSeeds",
    "estimate_pipeline_seeds",
    "pipeline_seed_count",
    "run_pipeline_seeds",
    "seed_output",
]


def seed_output(output: str | os.PathLike, seed: int, n: int) -> Path:
    """NetCDF file of ``seed`` among ``n`` seeds: ``output`` itself for one seed, else
    ``<stem>.seed<seed><suffix>`` beside it."""
    b = Path(output)
    return b if n == 1 else b.with_name(f"{b.stem}.seed{seed}{b.suffix}")


def pipeline_seed_count(run: PipelineStormRun, seeds: int | None) -> int:
    """Number of storms: ``seeds``, or the setup's ``seeds`` ([run] seeds of a case) for None.

    Several seeds need a spectral storm: a regular wave or a measured record is deterministic
    (:class:`~onbottom.errors.InputError`).
    """
    n = run.setup.seeds if seeds is None else int(seeds)
    if n > 1 and not hasattr(run.setup.storm, "with_seed"):
        raise InputError(
            f"seeds = {n} is invalid with a regular wave or a measured record ([storm] kind):"
            " the flow is deterministic, run one seed"
        )
    return n


def estimate_pipeline_seeds(run: PipelineStormRun, seeds: int | None, workers: int | None) -> Any:
    """:class:`onbottom.study.budget.Estimate` of ``seeds`` storms of ``run`` (None → the
    setup's seeds) on ``workers`` processes (None → one per core)."""
    from onbottom.study import budget

    n = run.setup.seeds if seeds is None else int(seeds)
    cost = run.cost()
    return budget.pipeline_storms(n, cost.cpu_s, cost.memory_bytes, workers=workers)


@dataclass(frozen=True)
class _PipelineSeedJob:
    """One seed of a pipeline run (picklable: the built run travels to the workers)."""

    run: PipelineStormRun
    output: str
    n: int
    progress: bool
    restart: bool = False

    def simulate(self, seed: int) -> PipelineResult:
        return simulate_pipeline_storm(
            self.run,
            seed,
            output=seed_output(self.output, seed, self.n),
            progress=self.progress,
            restart=self.restart,
        )

    def __call__(self, seed: int) -> dict[str, Any]:
        try:
            r = self.simulate(seed)
        except Exception as exc:  # recorded, not raised: one bad seed must not sink N
            return seed_failure(seed, exc)
        return {"seed": int(seed), **r.to_dict()}


@dataclass(frozen=True)
class PipelineSeeds:
    """Results of :func:`run_pipeline_seeds`.

    Attributes
    ----------
    rows : list of dict
        Per seed: ``seed`` and :meth:`PipelineResult.to_dict` (a failed seed: status −9,
        ``message`` and ``traceback``).
    outputs : list of Path
        NetCDF file of every seed (in the order of ``rows``).
    diameter : float
        Outer diameter D [m].
    n_nodes : int
        FE nodes [-].
    strain_limit : float or None
        Strain limit of the settings [-].
    result : PipelineResult or None
        The run itself when one seed ran (for figures and animations).
    """

    rows: list[dict[str, Any]]
    outputs: list[Path]
    diameter: float
    n_nodes: int
    strain_limit: float | None
    result: PipelineResult | None = None

    @property
    def failures(self) -> list[dict[str, Any]]:
        """seed, status and message of every seed whose run failed."""
        return [
            {"seed": r["seed"], "status": r["status"], "message": r["message"]}
            for r in self.rows
            if not r["success"]
        ]

    @property
    def success(self) -> bool:
        """True when every seed ran to its end (or runaway stop)."""
        return not self.failures and all(r["success"] for r in self.rows)

    def to_dict(self, *, plot: str | None = None, animation: str | None = None) -> dict[str, Any]:
        """JSON payload of ``onbottom storm`` for a pipeline case (docs/json.md:
        ``storm_pipeline``); ``plot`` and ``animation``: the files the caller wrote."""
        rows, failures = self.rows, self.failures
        ok = [r for r in rows if r["success"]]
        n, d = len(rows), self.diameter
        if not ok:
            worst: dict[str, Any] = rows[0]
            maxes = np.array([math.nan])
        else:
            worst = max(ok, key=lambda r: r["max_displacement_m"])
            maxes = np.array([r["max_displacement_m"] for r in ok])
        criteria = {
            key: bool(ok) and all(bool(r["criteria"][key]) for r in ok) for key in ("0.5D", "10D")
        }
        strain_check = (
            None
            if self.strain_limit is None or not ok
            else all(bool(r["criteria"]["strain"]) for r in ok)
        )
        success = self.success
        detail = ""
        verdict = {None: "", True: "PASS", False: "FAIL"}[strain_check]
        if ok:
            eps = max(r["max_strain"] for r in ok)
            detail = (
                f"; worst node x = {worst['worst_node_x_m']:.1f} m; max strain {100 * eps:.3g} %"
                + (
                    ""
                    if strain_check is None
                    else f" (limit {100 * self.strain_limit:.3g} %: {verdict})"
                )
            )
        message = (
            worst["message"] + detail
            if n == 1
            else (
                f"{n} seeds: seed-averaged maximum displacement {np.mean(maxes) / d:.3g}D"
                f" (max {np.max(maxes) / d:.3g}D)"
                + (f"; {len(failures)} seed(s) failed" if failures else "")
                + detail
            )
        )
        return {
            "max_displacement_m": worst.get("max_displacement_m"),
            "max_displacement_over_D": worst.get("max_displacement_over_D"),
            "mean_max_displacement_m": float(np.mean(maxes)),
            "max_strain": max((r["max_strain"] for r in ok), default=None),
            "worst_node_x_m": worst.get("worst_node_x_m"),
            "criteria": criteria,
            "strain_limit": self.strain_limit,
            "strain_check": strain_check,
            "status": worst["status"] if success else min(r["status"] for r in rows),
            "success": success,
            "message": message,
            "diameter_m": d,
            "n_nodes": self.n_nodes,
            "seeds": n,
            "netcdf": str(self.outputs[0]) if n == 1 else [str(o) for o in self.outputs],
            "plot": plot,
            "animation": animation,
            "failures": failures,
            "per_seed": rows,
            "model": "pipeline_fe",
        }


def run_pipeline_seeds(
    run: PipelineStormRun,
    *,
    output: str | os.PathLike,
    seeds: int | None = None,
    progress: bool = False,
    scheduler: str | None = None,
    workers: int | None = None,
    restart: bool = False,
) -> PipelineSeeds:
    """Run the pipeline FE storm ``run`` for ``seeds`` storms.

    Parameters
    ----------
    run : PipelineStormRun
        The built run (:func:`onbottom.cases.pipeline.load_pipeline_run` builds it from a case).
    output : path
        NetCDF file (with several seeds ``<stem>.seedN<suffix>`` beside it), written as
        ``<output>.part`` during the run and renamed when complete; its checkpoint
        ``<output>.ckpt.npz`` resumes an interrupted run of the same identity (removed at the
        end). A finished output of the same run is returned as it is.
    seeds : int or None
        Number of storms (seeds storm.seed, storm.seed + 1, ...); None → ``run.setup.seeds``.
        Several seeds run on Dask (:func:`onbottom.study.engine.dask_client`: ``scheduler``
        address or a local cluster of ``workers`` processes; ``workers=0`` → in this
        process); a seed that raises is recorded (status −9), never dropped; one seed runs
        in this process and its exception propagates.
    progress : bool
        Progress bar (of the run with one seed, of the seeds with several).
    restart : bool
        Discard checkpoints and partial files of an earlier run and start afresh.
    """
    from onbottom.errors import RunInterrupted

    n = pipeline_seed_count(run, seeds)
    job = _PipelineSeedJob(run, os.fspath(output), n, progress and n == 1, restart)
    first = run.setup.storm.seed
    res = None
    try:
        if n == 1:
            res = job.simulate(first)
            rows = [{"seed": int(first), **res.to_dict()}]
        elif workers == 0:
            rows = [job(first + k) for k in range(n)]
        else:
            from onbottom.study.engine import ParallelMap, dask_client

            with dask_client(scheduler_address=scheduler, n_workers=workers) as client:
                rows = ParallelMap(client, batch_size=1, progress=progress)(
                    job, [first + k for k in range(n)]
                )
    except KeyboardInterrupt:
        raise RunInterrupted(
            "interrupted: finished seeds and the checkpoints of unfinished ones are kept"
            f" beside {Path(output)}: run the same command again to resume"
        ) from None
    return PipelineSeeds(
        rows=rows,
        outputs=[seed_output(output, r["seed"], n) for r in rows],
        diameter=run.model.pipe.outer_diameter,
        n_nodes=int(run.model.x.size),
        strain_limit=run.settings.strain_limit,
        result=res,
    )
