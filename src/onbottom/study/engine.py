"""Execution engine for many independent runs: serial, or Dask distributed.

:func:`dask_client` opens (and closes) a Dask client: an embedded ``LocalCluster`` of worker
*processes* on the loopback interface by default, or a connection to a remote scheduler.
:class:`ParallelMap` is a ``map``-like callable over that client that submits work in batches,
so that 10⁴ runs of a few milliseconds become a few hundred tasks instead of drowning the
scheduler; it can be passed to :func:`scipy.optimize.differential_evolution` as ``workers``.

Numba and BLAS threads inside the workers are capped to one (``NUMBA_NUM_THREADS``,
``OMP_NUM_THREADS``, ``MKL_NUM_THREADS``, ``OPENBLAS_NUM_THREADS`` = 1): the parallelism comes
from the processes, and a 16-core machine running 16 workers each with 16 numba threads would
be oversubscribed 16 times. The dashboard, when asked for, binds to 127.0.0.1 only.
"""

from __future__ import annotations

import logging
import math
import os
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from onbottom.errors import InputError

__all__ = ["WORKER_ENV", "ParallelMap", "SerialMap", "dask_client", "default_n_workers"]

logger = logging.getLogger(__name__)

WORKER_ENV: dict[str, str] = {
    "NUMBA_NUM_THREADS": "1",
    "OMP_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "OPENBLAS_NUM_THREADS": "1",
}
"""Environment set in every embedded worker process (one compute thread per process)."""


def default_n_workers() -> int:
    """One worker process per available core (CPU affinity respected)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


@contextmanager
def dask_client(
    client: Any = None,
    *,
    scheduler_address: str | None = None,
    n_workers: int | None = None,
    threads_per_worker: int = 1,
    dashboard: bool = False,
) -> Iterator[Any]:
    """Yield a ``distributed.Client``; close what this function opened on exit.

    Parameters
    ----------
    client : distributed.Client or None
        Use this client as is (not closed on exit).
    scheduler_address : str or None
        Address of a running scheduler (``"tcp://10.0.0.5:8786"``) to connect to.
    n_workers : int or None
        Worker processes of the embedded cluster (default: one per core), >= 1.
    threads_per_worker : int
        Threads per worker process (default 1; numba kernels are single-threaded).
    dashboard : bool
        Serve the Dask dashboard on ``127.0.0.1`` (random free port) — never on all
        interfaces.
    """
    if client is not None:
        yield client
        return
    from distributed import Client, LocalCluster

    if scheduler_address is not None:
        c = Client(scheduler_address)
        try:
            yield c
        finally:
            c.close()
        return
    n = default_n_workers() if n_workers is None else int(n_workers)
    if n < 1:
        raise InputError(f"n_workers = {n_workers!r} is invalid: must be >= 1 for a Dask cluster")
    if threads_per_worker < 1:
        raise InputError(f"threads_per_worker = {threads_per_worker!r} is invalid: must be >= 1")
    cluster = LocalCluster(
        n_workers=n,
        threads_per_worker=threads_per_worker,
        processes=True,
        host="127.0.0.1",
        dashboard_address="127.0.0.1:0" if dashboard else None,
        silence_logs=logging.WARNING,
        env=dict(WORKER_ENV),
    )
    c = Client(cluster)
    if dashboard:
        logger.info("Dask dashboard at %s", c.dashboard_link)
    try:
        yield c
    finally:
        c.close()
        cluster.close()


def _apply_batch(func: Callable[[Any], Any], items: Sequence[Any]) -> list[Any]:
    return [func(x) for x in items]


def _chunks(items: Sequence[Any], size: int) -> list[Sequence[Any]]:
    return [items[i : i + size] for i in range(0, len(items), size)]


class SerialMap:
    """``map``-like callable that runs in this process (same interface as ParallelMap)."""

    def __call__(self, func: Callable[[Any], Any], iterable: Iterable[Any]) -> list[Any]:
        return [func(x) for x in iterable]


class ParallelMap:
    """``map``-like callable that evaluates ``func`` over items on a Dask client in batches.

    Parameters
    ----------
    client : distributed.Client
        Where to run.
    batch_size : int or None
        Items per task. Default: enough items that each worker thread gets about four
        tasks per call (at least 1).
    progress : bool
        Show a tqdm bar per call.

    Notes
    -----
    Results come back in input order. An exception in ``func`` propagates (the sweep wraps its
    function so that failures are recorded instead).
    """

    def __init__(self, client: Any, *, batch_size: int | None = None, progress: bool = False):
        self.client = client
        self.batch_size = batch_size
        self.progress = progress

    def _slots(self) -> int:
        try:
            return max(1, sum(self.client.nthreads().values()))
        except Exception:  # pragma: no cover - remote scheduler without info
            return 1

    def __call__(self, func: Callable[[Any], Any], iterable: Iterable[Any]) -> list[Any]:
        from distributed import as_completed
        from tqdm.auto import tqdm

        items = list(iterable)
        if not items:
            return []
        size = self.batch_size or max(1, math.ceil(len(items) / (4 * self._slots())))
        batches = _chunks(items, size)
        futures = self.client.map(
            _apply_batch, [func] * len(batches), batches, pure=False, key=None
        )
        index = {f.key: i for i, f in enumerate(futures)}
        out: list[list[Any] | None] = [None] * len(batches)
        try:
            with tqdm(total=len(items), disable=not self.progress, unit="run") as bar:
                for fut in as_completed(futures):
                    out[index[fut.key]] = fut.result()
                    bar.update(len(batches[index[fut.key]]))
        except BaseException:
            self.client.cancel(futures)  # do not leave the rest running on the cluster
            raise
        return [x for batch in out for x in (batch or [])]
