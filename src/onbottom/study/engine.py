"""Execution engine for many independent runs: serial, or Dask distributed.

:func:`dask_client` opens (and closes) a Dask client: an embedded ``LocalCluster`` of worker
*processes* on the loopback interface by default, or a connection to a remote scheduler.
:class:`ParallelMap` is a ``map``-like callable over that client that submits work in batches,
so that 10⁴ runs of a few milliseconds become a few hundred tasks instead of drowning the
scheduler; it can be passed to :func:`scipy.optimize.differential_evolution` as ``workers``.

Numba and BLAS threads inside the workers are capped to one (``NUMBA_NUM_THREADS``,
``OMP_NUM_THREADS``, ``MKL_NUM_THREADS``, ``OPENBLAS_NUM_THREADS`` = 1): the parallelism comes
from the processes, and a 16-core machine running 16 workers each with 16 numba threads would
be oversubscribed 16 times. glibc's allocator keeps its defaults in the workers (Dask's
``MALLOC_TRIM_THRESHOLD_`` is not set: :data:`_NANNY_ENV`). The dashboard, when asked for,
binds to 127.0.0.1 only.

Interrupts and kills: the embedded workers are started with SIGINT ignored, so a
Ctrl-C in a terminal (sent to the whole process group) reaches this process only, which
cancels the futures and closes the cluster quietly (:class:`ParallelMap`, :func:`dask_client`);
each worker asks the kernel for SIGKILL when its parent dies (``PR_SET_PDEATHSIG``, Linux;
elsewhere a parent-PID watchdog thread), so a kill -9 of the parent never leaves workers
computing — distributed's own parent-pipe check needs the GIL, which a long numba kernel
holds. ``ParallelMap(on_result=...)`` hands each finished item to the caller as it comes,
so a study can stream its results to disk (:class:`onbottom.results.TaskStore`).
"""

from __future__ import annotations

import logging
import math
import os
import signal
import sys
import threading
import time
import warnings
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from onbottom.errors import InputError

__all__ = [
    "WORKER_ENV",
    "ParallelMap",
    "SerialMap",
    "dask_client",
    "default_n_workers",
    "die_with_parent",
]

logger = logging.getLogger(__name__)

WORKER_ENV: dict[str, str] = {
    "NUMBA_NUM_THREADS": "1",
    "OMP_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "OPENBLAS_NUM_THREADS": "1",
}
"""Environment set in every embedded worker process (one compute thread per process)."""

_NANNY_ENV = {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}
"""Dask's nannies start their workers with ``MALLOC_TRIM_THRESHOLD_=65536`` (to give memory
back to the system), which also turns off glibc's adaptive mmap threshold: every array of
128 kB or more (a storm's flow series) is then mapped and unmapped, its pages faulted in
afresh each time. The embedded workers keep glibc's defaults (a variable set in this
process's environment still reaches them)."""


PARENT_PID_ENV = "ONBOTTOM_PARENT_PID"
"""Environment variable holding the PID of the process that started the embedded cluster."""


def die_with_parent(parent_pid: int | None = None) -> None:
    """Make this process die when ``parent_pid`` (default: the current parent) dies.

    Linux: ``prctl(PR_SET_PDEATHSIG, SIGKILL)``, acted on by the kernel even while a numba
    kernel holds the GIL. Elsewhere (or if prctl fails): a daemon thread polling the parent
    PID each second. Either way, a parent already gone means an immediate exit.
    """
    pid = os.getppid() if parent_pid is None else int(parent_pid)
    armed = False
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            armed = libc.prctl(1, int(signal.SIGKILL), 0, 0, 0) == 0  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):  # pragma: no cover - no libc prctl
            armed = False
    if os.getppid() != pid:
        os._exit(1)
    if armed:
        return

    def watch() -> None:  # pragma: no cover - non-Linux fallback
        while True:
            if os.getppid() != pid:
                os._exit(1)
            time.sleep(1.0)

    threading.Thread(target=watch, name="onbottom-parent-watchdog", daemon=True).start()


def dask_setup(worker: Any = None) -> None:
    """Preload hook of the embedded workers: die with the process that started the cluster,
    and ignore Ctrl-C (also in a worker the nanny restarts later)."""
    pid = os.environ.get(PARENT_PID_ENV)
    if pid and pid.isdigit():
        die_with_parent(int(pid))
        try:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        except ValueError:  # pragma: no cover - preload outside the main thread
            pass


@contextmanager
def _sigint_ignored() -> Iterator[None]:
    """SIGINT ignored (main thread only): child processes started inside inherit SIG_IGN."""
    try:
        old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


_POLL_S = 0.1
"""Longest wait of :class:`ParallelMap` between looks for finished tasks and a Ctrl-C [s]
(a finished task or a Ctrl-C wakes it at once)."""


@contextmanager
def _sigint_sets(*flags: threading.Event) -> Iterator[None]:
    """SIGINT sets ``flags`` instead of raising (main thread only; elsewhere nothing changes)."""

    def handler(signum: int, frame: Any) -> None:
        for f in flags:
            f.set()

    try:
        old = signal.signal(signal.SIGINT, handler)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


@contextmanager
def _quiet_distributed() -> Iterator[None]:
    """Silence the distributed/tornado loggers (closing a cluster after an interrupt)."""
    names = ("distributed", "tornado", "asyncio")
    levels = {n: logging.getLogger(n).level for n in names}
    for n in names:
        logging.getLogger(n).setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for n, lv in levels.items():
            logging.getLogger(n).setLevel(lv)


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
    # the workers ignore Ctrl-C (only this process handles it); distributed's internal HTTP
    # server moving off a busy default port is not worth a warning
    import dask

    with _sigint_ignored(), warnings.catch_warnings(), dask.config.set(_NANNY_ENV):
        warnings.filterwarnings("ignore", message="Port .* is already in use")
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=threads_per_worker,
            processes=True,
            host="127.0.0.1",
            dashboard_address="127.0.0.1:0" if dashboard else None,
            silence_logs=logging.ERROR,  # no worker chatter on Ctrl-C
            env={**WORKER_ENV, PARENT_PID_ENV: str(os.getpid())},
            preload=["onbottom.study.engine"],
        )
        c = Client(cluster)
    if dashboard:
        logger.info("Dask dashboard at %s", c.dashboard_link)
    interrupted = False
    try:
        yield c
    except KeyboardInterrupt:
        interrupted = True
        raise
    finally:
        with _sigint_ignored(), _quiet_distributed() if interrupted else _nothing():
            c.close()
            cluster.close(timeout=10 if interrupted else None)


@contextmanager
def _nothing() -> Iterator[None]:
    yield


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
    on_result : callable or None
        ``on_result(item, value)`` called in this process for each item as soon as its batch
        finishes (stream results to disk); an exception in it cancels the rest and propagates.

    Notes
    -----
    Results come back in input order. An exception in ``func`` propagates (the sweep wraps its
    function so that failures are recorded instead).
    """

    def __init__(
        self,
        client: Any,
        *,
        batch_size: int | None = None,
        progress: bool = False,
        on_result: Callable[[Any, Any], None] | None = None,
    ):
        self.client = client
        self.batch_size = batch_size
        self.progress = progress
        self.on_result = on_result

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
        stop = threading.Event()  # Ctrl-C
        wake = threading.Event()  # a task finished, or Ctrl-C
        futures: list[Any] = []
        try:
            # Ctrl-C sets a flag checked between polls: a KeyboardInterrupt raised inside
            # distributed's own waiting (its sync()) logs a traceback from its event loop
            with _sigint_sets(stop, wake):
                futures = self.client.map(
                    _apply_batch, [func] * len(batches), batches, pure=False, key=None
                )
                for f in futures:
                    f.add_done_callback(lambda _f: wake.set())
                index = {f.key: i for i, f in enumerate(futures)}
                out: list[list[Any] | None] = [None] * len(batches)
                left = len(batches)
                with tqdm(total=len(items), disable=not self.progress, unit="run") as bar:
                    ac = as_completed(futures)
                    while left:
                        if stop.is_set():
                            raise KeyboardInterrupt
                        done = ac.next_batch(block=False)
                        if not done:
                            wake.wait(_POLL_S)
                            wake.clear()
                            continue
                        for fut in done:
                            i = index[fut.key]
                            out[i] = fut.result()
                            left -= 1
                            if self.on_result is not None:
                                for item, value in zip(batches[i], out[i] or [], strict=True):
                                    self.on_result(item, value)
                            bar.update(len(batches[i]))
        except BaseException as exc:
            # do not leave the rest running on the cluster
            with (
                _sigint_ignored(),
                _quiet_distributed() if isinstance(exc, KeyboardInterrupt) else _nothing(),
            ):
                self.client.cancel(futures)
            raise
        return [x for batch in out for x in (batch or [])]


def run_streamed(
    job: Callable[[Any], Any],
    todo: Sequence[Any],
    keep: Callable[[Any, Any], None],
    *,
    n_workers: int | None = None,
    scheduler: str | None = None,
    client: Any = None,
    progress: bool = False,
    unit: str = "task",
    batch_size: int | None = 1,
) -> int:
    """Run ``job`` on every item of ``todo`` and hand each result to ``keep(item, result)`` as
    it finishes (so a caller can stream it to disk); returns the number of worker threads.

    ``n_workers == 0`` without a scheduler or client runs in this process (with a tqdm bar when
    ``progress``); otherwise on Dask (:func:`dask_client`, :class:`ParallelMap`). A
    :class:`KeyboardInterrupt` propagates: the caller says what was kept.
    """
    if not todo:
        return 1
    if n_workers == 0 and scheduler is None and client is None:
        it: Any = todo
        if progress:
            from tqdm.auto import tqdm

            it = tqdm(todo, unit=unit)
        for x in it:
            keep(x, job(x))
        return 1
    with dask_client(client, scheduler_address=scheduler, n_workers=n_workers) as c:
        workers = max(1, sum(c.nthreads().values()))
        ParallelMap(c, batch_size=batch_size, progress=progress, on_result=keep)(job, todo)
    return workers
