"""Parametric sweeps over a grid of parameters, serially or on Dask distributed.

``sweep(fn, {"A": [...], "B": [...]})`` calls ``fn(A=a, B=b)`` at every point of the outer
product of the axes and returns an :class:`xarray.Dataset` with one dimension per swept
parameter and one variable per scalar output of ``fn``. Failed runs do not stop the sweep:
their outputs are NaN and the variables ``failed`` (bool) and ``error`` (the exception as
``"Type: message"``) say what happened.

Reproducibility: with ``seed`` given, each grid point gets its own independent stream
``np.random.SeedSequence(seed).spawn(n_points)[i]`` (points in C order of the grid) passed as
``rng=np.random.default_rng(...)`` when ``fn`` has a parameter named ``rng``, so results do not
depend on how the runs are split over workers.
"""

from __future__ import annotations

import inspect
import logging
import math
import time
from collections.abc import Callable, Mapping, Sequence
from numbers import Real
from typing import Any

import numpy as np
import xarray as xr

from onbottom.errors import InputError
from onbottom.results import provenance
from onbottom.study.engine import ParallelMap, SerialMap, dask_client

__all__ = ["sweep"]

logger = logging.getLogger(__name__)


class _PointRunner:
    """Picklable callable: runs ``fn`` at one grid point, capturing failures."""

    def __init__(self, fn: Callable[..., Any], fixed: Mapping[str, Any], pass_rng: bool):
        self.fn = fn
        self.fixed = dict(fixed)
        self.pass_rng = pass_rng

    def __call__(self, job: tuple[dict[str, Any], Any]) -> tuple[dict[str, float] | None, str]:
        point, seed_seq = job
        kwargs = {**self.fixed, **point}
        if self.pass_rng:
            kwargs["rng"] = np.random.default_rng(seed_seq)
        try:
            out = self.fn(**kwargs)
            return _as_outputs(out), ""
        except Exception as exc:  # recorded in the result, by design
            return None, f"{type(exc).__name__}: {exc}"


def _as_outputs(out: Any) -> dict[str, float]:
    if isinstance(out, Mapping):
        items = dict(out)
    else:
        items = {"value": out}
    result: dict[str, float] = {}
    for k, v in items.items():
        if isinstance(v, (bool, np.bool_)):
            result[str(k)] = float(v)
        elif isinstance(v, Real) or (isinstance(v, np.ndarray) and v.ndim == 0):
            result[str(k)] = float(v)
        else:
            raise TypeError(f"output {k!r} = {v!r} is not a scalar number")
    return result


def _accepts_rng(fn: Callable[..., Any]) -> bool:
    try:
        params = inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False
    return "rng" in params


def _axes(grid: Mapping[str, Sequence[Any]]) -> dict[str, np.ndarray]:
    if not grid:
        raise InputError("grid is invalid: give at least one parameter with its values")
    axes: dict[str, np.ndarray] = {}
    for name, values in grid.items():
        arr = np.atleast_1d(np.asarray(values))
        if arr.ndim != 1 or arr.size == 0:
            raise InputError(f"grid[{name!r}] is invalid: expected a non-empty 1-D sequence")
        if len(np.unique(arr)) != arr.size:
            raise InputError(f"grid[{name!r}] = {arr.tolist()} is invalid: values repeat")
        axes[str(name)] = arr
    return axes


def sweep(
    fn: Callable[..., Any],
    grid: Mapping[str, Sequence[Any]],
    *,
    fixed: Mapping[str, Any] | None = None,
    client: Any = None,
    scheduler_address: str | None = None,
    n_workers: int | None = None,
    threads_per_worker: int = 1,
    seed: int | None = None,
    batch_size: int | None = None,
    progress: bool = True,
    dashboard: bool = False,
) -> xr.Dataset:
    """Evaluate ``fn`` over the outer product of ``grid``.

    Parameters
    ----------
    fn : callable
        ``fn(**fixed, **point[, rng=Generator]) -> float | Mapping[str, float]``. Must be
        picklable (module-level function, or a closure cloudpickle can send) for Dask.
    grid : mapping of str to sequence
        Values of each swept parameter (one dimension each, in this order).
    fixed : mapping or None
        Keyword arguments passed unchanged to every call.
    client : distributed.Client or None
        Use an existing client.
    scheduler_address : str or None
        Connect to a remote scheduler at this address.
    n_workers : int or None
        Worker processes of the embedded ``LocalCluster`` (default: one per core). ``0`` runs
        serially in this process without Dask.
    threads_per_worker : int
        Threads per worker process (default 1).
    seed : int or None
        Root seed of the per-point random streams (see module docstring). ``None`` gives
        fresh entropy (recorded in the result attributes).
    batch_size : int or None
        Runs per Dask task (default: about four tasks per worker thread).
    progress : bool
        Show a progress bar.
    dashboard : bool
        Serve the dashboard of an embedded cluster on 127.0.0.1.

    Returns
    -------
    xarray.Dataset
        Dimensions = grid names; one variable per output; ``failed`` (bool) and ``error``
        (str, empty where the run succeeded); attributes: provenance, ``seed``,
        ``n_points``, ``n_failed``, ``wall_time`` [s], ``engine``.
    """
    axes = _axes(grid)
    fixed = dict(fixed or {})
    overlap = set(fixed) & set(axes)
    if overlap:
        raise InputError(f"fixed and grid both give {sorted(overlap)}: give each once")
    names = list(axes)
    shape = tuple(a.size for a in axes.values())
    n_points = math.prod(shape)
    root = np.random.SeedSequence(seed)
    seeds = root.spawn(n_points)
    jobs = []
    for flat, idx in enumerate(np.ndindex(*shape)):
        point = {n: axes[n][i].item() for n, i in zip(names, idx, strict=True)}
        jobs.append((point, seeds[flat]))
    runner = _PointRunner(fn, fixed, _accepts_rng(fn))

    t0 = time.perf_counter()
    results, engine = _run_points(
        runner, jobs, client, scheduler_address, n_workers, threads_per_worker, batch_size,
        progress, dashboard,
    )  # fmt: skip
    wall = time.perf_counter() - t0
    ds = _dataset(results, axes, shape)
    ds.attrs = provenance(
        "sweep",
        function=getattr(fn, "__qualname__", type(fn).__name__),
        fixed={k: v for k, v in fixed.items() if isinstance(v, (str, int, float, bool))},
        seed=int(root.entropy) if seed is None else int(seed),
        n_points=n_points,
        n_failed=int(ds["failed"].values.sum()),
        wall_time=float(wall),
        engine=engine,
    )
    # JSON-encode the seed entropy (it can exceed 64 bits)
    ds.attrs["seed"] = str(ds.attrs["seed"])
    return ds


def _run_points(runner, jobs, client, scheduler_address, n_workers, threads_per_worker,
                batch_size, progress, dashboard):  # fmt: skip
    """Stage of :func:`sweep`: every point's (result, error), in this process or on Dask;
    (results, engine)."""
    if client is None and scheduler_address is None and n_workers == 0:
        if progress:
            from tqdm.auto import tqdm

            return [runner(j) for j in tqdm(jobs, unit="run")], "serial"
        return SerialMap()(runner, jobs), "serial"
    with dask_client(
        client,
        scheduler_address=scheduler_address,
        n_workers=n_workers,
        threads_per_worker=threads_per_worker,
        dashboard=dashboard,
    ) as c:
        pmap = ParallelMap(c, batch_size=batch_size, progress=progress)
        return pmap(runner, jobs), "dask"


def _dataset(results, axes, shape) -> xr.Dataset:
    """Stage of :func:`sweep`: the outputs on the grid, ``failed`` and ``error``."""
    names = list(axes)
    n_points = math.prod(shape)
    out_names: list[str] = []
    for res, _ in results:
        if res is not None:
            out_names.extend(k for k in res if k not in out_names)
    failed = np.zeros(n_points, dtype=bool)
    errors = np.empty(n_points, dtype=object)
    values = {k: np.full(n_points, np.nan) for k in out_names}
    for i, (res, err) in enumerate(results):
        errors[i] = err
        if res is None:
            failed[i] = True
            continue
        for k, v in res.items():
            values[k][i] = v
    if failed.any():
        logger.warning("sweep: %d of %d runs failed", int(failed.sum()), n_points)

    coords = {n: (n, axes[n]) for n in names}
    ds = xr.Dataset(coords=coords)
    for k in out_names:
        ds[k] = (names, values[k].reshape(shape))
    ds["failed"] = (names, failed.reshape(shape))
    ds["failed"].attrs["long_name"] = "the run raised an exception"
    ds["error"] = (names, errors.reshape(shape).astype(str))
    ds["error"].attrs["long_name"] = "exception of a failed run (empty if it succeeded)"
    return ds
