"""N seeds of one storm case on Dask (local cluster by default): statistics of max displacement.

Each seed is an independent storm (random phases from ``numpy.random.default_rng(seed)``)
simulated with :func:`onbottom.dynamics.storm_section.simulate_storm_section` in summary-only
mode. Seeds run on :func:`onbottom.study.engine.dask_client` (an embedded ``LocalCluster`` of
single-threaded worker processes, or a remote scheduler) or in this process (``n_workers=0``).
A seed whose run raises is recorded with status −9 and its message, never dropped. The result
of a seed depends only on its inputs and seed, not on the worker that ran it: the same seeds
give bitwise the same numbers on 1 and on 2 workers (tested).

With ``store`` (a folder; ``onbottom storm --seeds`` uses ``<output>.tasks``) every finished
seed is written at once to its own small file (:class:`onbottom.results.TaskStore`, with the
run identity of its inputs), so a run interrupted at any moment — Ctrl-C, kill -9 — resumes
without repeating the seeds it finished; Ctrl-C raises :class:`onbottom.errors.RunInterrupted`
saying how many seeds are kept.
"""

from __future__ import annotations

import logging
import math
import traceback
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import xarray as xr

from onbottom.dynamics.status import Status, status_message
from onbottom.dynamics.storm_section import (
    CRITERIA_OVER_D,
    STATUS_OUTSIDE_VALIDITY,
    StormSolverSettings,
    simulate_storm_section,
)
from onbottom.errors import InputError, RunInterrupted
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.storm import Storm
from onbottom.results import TaskStore, annotate, provenance
from onbottom.soil.base import LateralResistanceModel

__all__ = ["STATUS_ERROR", "SeedStudy", "run_storm_seeds", "seed_failure", "seed_list"]

logger = logging.getLogger(__name__)

STATUS_ERROR = int(Status.RAISED)
"""Status recorded for a seed whose run raised an exception."""


def seed_failure(seed: int, exc: BaseException) -> dict[str, Any]:
    """The result row of a seed whose run raised ``exc`` (call it in the ``except`` block: the
    row keeps the last frames of the traceback): status :data:`STATUS_ERROR`, not a success."""
    return {
        "seed": int(seed),
        "status": STATUS_ERROR,
        "success": False,
        "message": status_message(Status.RAISED, f"{type(exc).__name__}: {exc}"),
        "traceback": traceback.format_exc(limit=3),
    }


def seed_list(first: int, n: int) -> list[int]:
    """Seeds first, first + 1, ..., first + n − 1."""
    if int(n) < 1:
        raise InputError(f"seeds = {n!r} is invalid: must be >= 1")
    return [int(first) + i for i in range(int(n))]


@dataclass(frozen=True)
class _SeedJob:
    pipe: Pipe
    soil: LateralResistanceModel
    storm: Storm
    kwargs: dict[str, Any]

    def __call__(self, seed: int) -> dict[str, Any]:
        try:
            r = simulate_storm_section(
                self.pipe, self.soil, self.storm.with_seed(int(seed)), **self.kwargs
            )
        except Exception as exc:  # recorded, not raised: one bad seed must not sink N
            return seed_failure(seed, exc)
        return {
            "seed": int(seed),
            "status": r.status,
            "success": r.success,
            "message": r.message,
            "max_displacement": r.max_displacement,
            "final_displacement": r.final_displacement,
            "time_of_max": r.summary["time_of_max"],
            "n_liftoff": r.summary["n_liftoff"],
            "max_penetration": r.summary["max_penetration"],
            "out_of_range_time": r.summary["out_of_range_time"],
            "n_steps": r.summary["n_steps"],
        }


@dataclass(frozen=True)
class SeedStudy:
    """Results of :func:`run_storm_seeds`.

    Attributes
    ----------
    data : xarray.Dataset
        Per seed (dimension ``seed``): max_displacement, final_displacement [m], status,
        time_of_max [s], n_liftoff, max_penetration [m], out_of_range_time [s] (−1: never),
        out_of_range (1: the run left the soil model's range, status −3; its numbers are
        kept and counted in the statistics); NaN for failed seeds.
    statistics : dict
        Over the successful seeds: mean, std, min, max and the ``fractile`` of the maximum
        displacement [m]; n_seeds, n_failed; mean_over_D.
    criteria : dict
        {"0.5D", "10D"}: True if the seed-averaged maximum displacement <= limit·D.
    failures : list of dict
        seed, status, message of every failed seed.
    """

    data: xr.Dataset
    statistics: dict[str, float]
    criteria: dict[str, bool]
    failures: list[dict[str, Any]] = field(default_factory=list)

    @property
    def success(self) -> bool:
        """True when no seed failed."""
        return not self.failures

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (keys of ``onbottom storm --seeds N --json`` for a pipe section):
        the worst and mean maximum displacement [m], the mean |final displacement| [m] of the
        seeds that ran to their end, the F109 criteria, status, message and statistics."""
        st = self.statistics
        d = float(self.data.attrs["diameter"])
        ok_rows = (self.data["status"].values > 0) | (self.data["out_of_range"].values == 1)
        final = self.data["final_displacement"].values[ok_rows]
        return {
            "max_displacement_m": st["max"],
            "mean_max_displacement_m": st["mean"],
            "final_displacement_m": float(abs(final).mean()) if final.size else None,
            "criteria": self.criteria,
            "status": int(Status.END if self.success else Status.RAISED),
            "success": self.success,
            "message": (
                f"{self.data.sizes['seed']} seeds: seed-averaged maximum displacement"
                f" {st['mean'] / d:.3g}D (max {st['max'] / d:.3g}D, {st['fractile_level']:g}"
                f" fractile {st['fractile'] / d:.3g}D)"
                + (f"; {st['n_failed']} seed(s) failed" if self.failures else "")
            ),
            "statistics": st,
            "failures": self.failures,
            "seeds": self.data.sizes["seed"],
            "diameter_m": d,
        }


def _collect(
    rows: list[dict[str, Any]], diameter: float, fractile: float, attrs: dict
) -> SeedStudy:
    seeds = np.array([r["seed"] for r in rows], dtype=np.int64)
    names = (
        "max_displacement",
        "final_displacement",
        "time_of_max",
        "n_liftoff",
        "max_penetration",
        "out_of_range_time",
        "n_steps",
    )
    cols = {k: np.array([r.get(k, math.nan) for r in rows], dtype=float) for k in names}
    status = np.array([r["status"] for r in rows], dtype=np.int64)
    # a seed that left the soil model's range ran to its end: its numbers count, flagged
    # (status −3 and ``out_of_range``), and it is listed with the failures (exit code 3)
    flagged = status == STATUS_OUTSIDE_VALIDITY
    ok = np.array([bool(r["success"]) for r in rows]) | flagged
    failures = [
        {"seed": r["seed"], "status": r["status"], "message": r["message"]}
        for r in rows
        if not r["success"]
    ]
    ymax = cols["max_displacement"][ok]
    if ymax.size:
        stats = {
            "mean": float(np.mean(ymax)),
            "std": float(np.std(ymax, ddof=1)) if ymax.size > 1 else 0.0,
            "min": float(np.min(ymax)),
            "max": float(np.max(ymax)),
            "fractile": float(np.quantile(ymax, fractile)),
            "fractile_level": float(fractile),
        }
    else:
        stats = {k: math.nan for k in ("mean", "std", "min", "max", "fractile")}
        stats["fractile_level"] = float(fractile)
    stats["n_seeds"] = len(rows)
    stats["n_failed"] = len(failures) - int(flagged.sum())
    stats["n_out_of_range"] = int(flagged.sum())
    stats["mean_over_D"] = stats["mean"] / diameter
    criteria = {k: bool(stats["mean"] <= lim * diameter) for k, lim in CRITERIA_OVER_D.items()}
    ds = xr.Dataset(
        {
            **{k: ("seed", v) for k, v in cols.items()},
            "status": ("seed", status),
            "out_of_range": ("seed", flagged.astype(np.int8)),
        },
        coords={"seed": seeds},
        attrs=provenance(
            "run_storm_seeds",
            None,
            diameter=diameter,
            **{f"stat_{k}": v for k, v in stats.items()},
            **attrs,
        ),
    )
    for k, unit in (
        ("max_displacement", "m"),
        ("final_displacement", "m"),
        ("time_of_max", "s"),
        ("max_penetration", "m"),
        ("out_of_range_time", "s"),
        ("out_of_range", "1"),
        ("n_liftoff", "1"),
        ("n_steps", "1"),
        ("status", "1"),
    ):
        ds[k].attrs.setdefault("units", unit)
    return SeedStudy(data=annotate(ds), statistics=stats, criteria=criteria, failures=failures)


def run_storm_seeds(
    pipe: Pipe,
    soil: LateralResistanceModel,
    storm: Storm,
    *,
    seeds: int | Sequence[int] = 10,
    fractile: float = 0.9,
    n_workers: int | None = None,
    scheduler: str | None = None,
    client: Any = None,
    progress: bool = False,
    store: Any = None,
    restart: bool = False,
    identity: Any = None,
    **kwargs: Any,
) -> SeedStudy:
    """Run ``storm`` with many seeds and summarise the maximum displacement.

    Parameters
    ----------
    pipe, soil, storm
        As :func:`~onbottom.dynamics.storm_section.simulate_storm_section`; ``storm.seed`` is
        the first seed when ``seeds`` is a count.
    seeds : int or sequence of int
        Number of seeds (storm.seed, storm.seed + 1, ...) or the seeds themselves.
    fractile : float
        Fractile of the maximum displacement reported [-], in (0, 1).
    n_workers : int or None
        Worker processes of the embedded Dask cluster (None → one per core); 0 → run in this
        process without Dask.
    scheduler : str or None
        Address of a running Dask scheduler (``tcp://host:8786``); wins over ``n_workers``.
    client : distributed.Client or None
        An open client to use.
    progress : bool
        tqdm progress bar over seeds.
    store : path or None
        Folder keeping each finished seed (one JSON file per seed, written as it finishes);
        seeds found there with this run's identity are not run again. None → nothing kept.
    restart : bool
        Empty ``store`` first (start afresh).
    identity : any
        JSON-able description of the inputs for the run identity of the stored seeds
        (default: the text of pipe, soil, storm and kwargs).
    **kwargs
        depth, current, z0, sample_interval, force_model, reductions, settings (the
        ``record_interval`` is forced to None: summaries only).
    """
    if not 0.0 < float(fractile) < 1.0:
        raise InputError(f"fractile = {fractile!r} is invalid: must lie in (0, 1)")
    if isinstance(seeds, (int, np.integer)):
        seed_values = seed_list(storm.seed, int(seeds))
    else:
        seed_values = [int(s) for s in seeds]
        if not seed_values:
            raise InputError("seeds = [] is invalid: give at least one seed")
    s = kwargs.pop("settings", None) or StormSolverSettings()
    kwargs["settings"] = replace(s, record_interval=None)
    job = _SeedJob(pipe=pipe, soil=soil, storm=storm, kwargs=kwargs)
    attrs = {
        "scheduler": scheduler or ("in-process" if n_workers == 0 else "local"),
        "soil_model": soil.name,
    }
    ts = None
    done: dict[int, dict[str, Any]] = {}
    if store is not None:
        ident = identity if identity is not None else _inputs_digest((pipe, soil, storm, kwargs))
        ts = TaskStore(
            store, {"study": "storm_seeds", "inputs": ident}, restart=restart, what="seed"
        )
        done = {seed_values[i]: r for i, r in ts.load([{"seed": x} for x in seed_values]).items()}
        if done:
            logger.info(
                "resuming: %d of %d seeds already done in %s", len(done), len(seed_values), store
            )
    todo = [x for x in seed_values if x not in done]
    rows_new: dict[int, dict[str, Any]] = {}

    def keep(seed: int, row: dict[str, Any]) -> None:
        rows_new[int(seed)] = row
        if ts is not None and row["status"] != STATUS_ERROR:  # an exception may be transient
            ts.put({"seed": int(seed)}, row)

    from onbottom.study.engine import run_streamed

    try:
        run_streamed(
            job,
            todo,
            keep,
            n_workers=n_workers,
            scheduler=scheduler,
            client=client,
            progress=progress,
            unit="storm",
            batch_size=1 if len(todo) < 64 else None,
        )
    except KeyboardInterrupt:
        raise RunInterrupted(
            _interrupted(
                len(done) + sum(1 for r in rows_new.values() if r["status"] != STATUS_ERROR),
                len(seed_values),
                store,
            )
        ) from None
    rows = [done[x] if x in done else rows_new[x] for x in seed_values]
    return _collect(rows, pipe.outer_diameter, fractile, attrs)


def _interrupted(kept: int, total: int, store: Any) -> str:
    """The one-line message of an interrupted run."""
    head = f"interrupted after {kept} of {total} seeds"
    if store is None:
        return head + " (nothing kept: no store)"
    if kept == 0:
        return head + "; run the same command again to start"
    return head + f"; they are kept in {store}: run the same command again to resume"


def _inputs_digest(inputs: Any) -> str:
    """SHA-256 of the pickled inputs: every number of every array counts (a storm series or a
    coefficient table read from a file enters by its content; ``repr`` would elide the middle
    of a long array). ``repr`` for inputs that cannot be pickled."""
    import hashlib
    import pickle

    try:
        blob = pickle.dumps(inputs, protocol=5)
    except Exception:  # not picklable: the text form
        return repr(inputs)
    return "sha256:" + hashlib.sha256(blob).hexdigest()
