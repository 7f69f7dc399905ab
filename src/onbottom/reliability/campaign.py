"""A campaign of many model runs on Dask, streamed to a Zarr store, resumable after a kill.

A *model* is a picklable callable ``model(x, seed) -> dict`` of one run: ``x`` the physical
inputs of the run (a 1-D array, columns ``model.input_names``), ``seed`` an integer (the storm's
random phases); the dict holds the floats named in ``model.output_names``. ``model.identity()``
is a text that changes whenever anything that changes its results changes (case, solver
settings, version).

:class:`Campaign` evaluates blocks of rows (what an estimator asks for). Rows are grouped into
**tasks** of ``task_size`` rows; a task's identity is the BLAKE2b-128 hash of the model's
identity, the task's input bytes and its seeds — the same inputs give the same key, whatever
the process, worker or run. A task whose key the store already holds is read back, not rerun.
Missing tasks go to Dask (an embedded ``LocalCluster`` of single-threaded worker processes by
default, a remote scheduler with ``scheduler``, or this process with ``n_workers = 0``), at most
``4 × workers`` submissions in flight, each of as many tasks as fit in about
``submission_seconds`` of work at the measured rate; finished tasks are appended to the store
together, one commit every ``commit_interval`` seconds (default 2 s) and at the end of each
block.

Store (Zarr v3 group, ``zarr`` ≥ 3.1; :class:`ResultStore`):

* per row: ``inputs`` (n, d) float64, ``seed`` (n,) int64, ``outputs`` (n, k) float64 (NaN on
  failure), ``status`` (n,) int32 (the model's status; −9: the run raised), ``task`` (n,)
  int64;
* per task: ``task_key`` (m, 2) uint64 (the hash), ``task_start``, ``task_rows`` (m,) int64;
* group attributes: ``n_rows``, ``n_tasks`` (the **commit record**, written last), the model
  identity and its hash, input and output names;
* ``failures.jsonl`` beside the arrays: one line per failed run (row, seed, message).

Every object write of zarr's ``LocalStore`` is atomic (temporary file, then rename). A batch is
written as rows first, tasks second and the commit record last; after a kill at any instant the
store opens at its last commit record and rows beyond it are overwritten. So a kill loses at
most the tasks in flight and those finished since the last commit (an exception or an
interrupt loses none: they are committed first), and a rerun repeats only those.
Memory: the campaign holds the tasks in flight, those not yet committed, and the index of
finished tasks (key → start, rows: about 250 bytes a task by tracemalloc, 750 bytes of resident
memory: 75–230 MB for 10⁷ runs in tasks of 32) — flat in the number of runs otherwise.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
import traceback
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from onbottom._validate import integer
from onbottom.errors import InputError
from onbottom.status import Status

__all__ = [
    "STATUS_RAISED",
    "Campaign",
    "CampaignModel",
    "ResultStore",
    "task_key",
]

STATUS_RAISED = int(Status.RAISED)
"""Status of a run whose model raised an exception (recorded, never fatal):
:attr:`onbottom.status.Status.RAISED`."""

_FORMAT = "onbottom-campaign-1"
_ARRAYS = ("inputs", "seed", "outputs", "status", "task", "task_key", "task_start", "task_rows")


class CampaignModel(Protocol):
    """What :class:`Campaign` runs."""

    input_names: tuple[str, ...]
    output_names: tuple[str, ...]

    def identity(self) -> str: ...

    def __call__(self, x: np.ndarray, seed: int) -> dict[str, float]: ...


def task_key(identity_hash: bytes, x: np.ndarray, seeds: np.ndarray) -> tuple[int, int]:
    """BLAKE2b-128 of the model identity's hash, the inputs and the seeds, as two uint64."""
    h = hashlib.blake2b(digest_size=16)
    h.update(identity_hash)
    h.update(np.ascontiguousarray(x, dtype="<f8").tobytes())
    h.update(np.ascontiguousarray(seeds, dtype="<i8").tobytes())
    d = h.digest()
    return int.from_bytes(d[:8], "little"), int.from_bytes(d[8:], "little")


def _identity_hash(identity: str) -> bytes:
    return hashlib.blake2b(identity.encode("utf-8"), digest_size=16).digest()


def run_task(model: CampaignModel, x: np.ndarray, seeds: np.ndarray) -> dict[str, Any]:
    """Run the rows of one task; a row that raises is recorded (status −9), never raised."""
    n, k = x.shape[0], len(model.output_names)
    out = np.full((n, k), np.nan)
    status = np.zeros(n, dtype=np.int32)
    messages: list[tuple[int, str]] = []
    t0 = time.perf_counter()
    c0 = time.process_time()
    for i in range(n):
        try:
            r = model(x[i], int(seeds[i]))
        except Exception as exc:  # recorded, not raised: one bad run must not sink the campaign
            status[i] = STATUS_RAISED
            tb = traceback.format_exc(limit=2).strip().splitlines()[-1]
            messages.append((i, f"{type(exc).__name__}: {exc} ({tb})"))
            continue
        out[i] = [float(r[name]) for name in model.output_names]
        status[i] = int(r.get("status", Status.END))
        if "message" in r and status[i] < 0:
            messages.append((i, str(r["message"])))
    return {
        "outputs": out,
        "status": status,
        "messages": messages,
        "seconds": time.perf_counter() - t0,
        "cpu_seconds": time.process_time() - c0,
    }


def run_tasks(model: CampaignModel, rows: list[tuple[np.ndarray, np.ndarray]]) -> list[dict]:
    """:func:`run_task` for each (inputs, seeds) of one Dask submission (several tasks: one
    scheduler round trip for all of them)."""
    return [run_task(model, x, seeds) for x, seeds in rows]


class ResultStore:
    """The Zarr store of a campaign (layout and commit protocol: module docstring).

    Parameters
    ----------
    path : path
        Folder of the store (created if absent).
    identity : str
        The model's identity; a store made by another model is refused (InputError).
    input_names, output_names : sequence of str
        Column names.
    chunk_rows : int
        Rows per Zarr chunk, in [64, 10⁶].
    """

    def __init__(
        self,
        path: str | os.PathLike,
        identity: str,
        input_names: Sequence[str],
        output_names: Sequence[str],
        *,
        chunk_rows: int = 4096,
    ) -> None:
        import zarr

        self.path = Path(path)
        self.identity = identity
        self.identity_hash = _identity_hash(identity)
        self.input_names = tuple(input_names)
        self.output_names = tuple(output_names)
        chunk = integer("chunk_rows", chunk_rows, 64, 10**6)
        d, k = len(self.input_names), len(self.output_names)
        fresh = not (self.path / "zarr.json").exists()
        if not fresh:  # a kill while this store was being created: no attributes yet, and
            # only (some of) its arrays — anything else is not overwritten
            g0 = zarr.open_group(str(self.path), mode="r")
            fresh = not dict(g0.attrs) and set(g0.keys()) <= set(_ARRAYS)
        if fresh:
            self.path.mkdir(parents=True, exist_ok=True)
            g = zarr.open_group(str(self.path), mode="w")
            spec = {
                "inputs": ((0, d), (chunk, d), "float64", np.nan),
                "seed": ((0,), (chunk,), "int64", 0),
                "outputs": ((0, k), (chunk, k), "float64", np.nan),
                "status": ((0,), (chunk,), "int32", 0),
                "task": ((0,), (chunk,), "int64", -1),
                "task_key": ((0, 2), (chunk, 2), "uint64", 0),
                "task_start": ((0,), (chunk,), "int64", -1),
                "task_rows": ((0,), (chunk,), "int64", 0),
            }
            for name, (shape, chunks, dtype, fill) in spec.items():
                g.create_array(name, shape=shape, chunks=chunks, dtype=dtype, fill_value=fill)
            g.attrs.update(
                {
                    "format": _FORMAT,
                    "identity": identity,
                    "identity_hash": self.identity_hash.hex(),
                    "input_names": list(self.input_names),
                    "output_names": list(self.output_names),
                    "n_rows": 0,
                    "n_tasks": 0,
                }
            )
        else:
            g = zarr.open_group(str(self.path), mode="r+")
            a = dict(g.attrs)
            if a.get("format") != _FORMAT:
                raise InputError(
                    f"store = {str(self.path)!r} is invalid: not an onbottom campaign store"
                )
            if a.get("identity_hash") != self.identity_hash.hex():
                raise InputError(
                    f"store = {str(self.path)!r} is invalid: it holds runs of another model or"
                    " case (its identity differs); use another --out folder or delete it"
                )
        self.group = g
        self.n_rows = int(g.attrs["n_rows"])
        self.n_tasks = int(g.attrs["n_tasks"])
        self._index: dict[tuple[int, int], tuple[int, int]] = {}
        if self.n_tasks:
            keys = np.asarray(g["task_key"][: self.n_tasks])
            starts = np.asarray(g["task_start"][: self.n_tasks])
            rows = np.asarray(g["task_rows"][: self.n_tasks])
            for (a, b), s, r in zip(keys.tolist(), starts.tolist(), rows.tolist(), strict=True):
                self._index[(a, b)] = (s, r)

    def __len__(self) -> int:
        return self.n_rows

    def lookup(self, key: tuple[int, int]) -> tuple[int, int] | None:
        """(first row, rows) of a finished task, or None."""
        return self._index.get(key)

    def read(self, start: int, rows: int) -> tuple[np.ndarray, np.ndarray]:
        """Outputs and status of rows [start, start + rows)."""
        g = self.group
        return (
            np.asarray(g["outputs"][start : start + rows]),
            np.asarray(g["status"][start : start + rows]),
        )

    def _grow(self, name: str, need: int) -> None:
        arr = self.group[name]
        if arr.shape[0] < need:
            cap = max(need, 2 * arr.shape[0], arr.chunks[0])
            arr.resize((cap, *arr.shape[1:]))

    def append(self, batch: Sequence[tuple[tuple[int, int], np.ndarray, np.ndarray, dict]]) -> None:
        """Write finished tasks (key, inputs, seeds, run_task result): rows, tasks, commit.

        A write that fails (a full disk) raises ``OSError`` naming the store; the rows of
        this batch are not committed (a rerun computes them again)."""
        try:
            self._append(batch)
        except OSError as exc:
            errno_ = exc.errno if isinstance(exc.errno, int) else None
            reason = os.strerror(errno_) if errno_ else str(exc).splitlines()[0]
            raise OSError(
                errno_, f"cannot write the campaign store: {reason}", str(self.path)
            ) from None

    def _append(self, batch: Sequence[tuple[tuple[int, int], np.ndarray, np.ndarray, dict]]):
        if not batch:
            return
        g = self.group
        n0, m0 = self.n_rows, self.n_tasks
        x = np.concatenate([b[1] for b in batch])
        seeds = np.concatenate([b[2] for b in batch])
        out = np.concatenate([b[3]["outputs"] for b in batch])
        status = np.concatenate([b[3]["status"] for b in batch])
        sizes = np.array([b[1].shape[0] for b in batch], dtype=np.int64)
        starts = n0 + np.concatenate(([0], np.cumsum(sizes)[:-1]))
        task = np.repeat(np.arange(m0, m0 + len(batch), dtype=np.int64), sizes)
        n1, m1 = n0 + x.shape[0], m0 + len(batch)
        for name in ("inputs", "seed", "outputs", "status", "task"):
            self._grow(name, n1)
        for name in ("task_key", "task_start", "task_rows"):
            self._grow(name, m1)
        g["inputs"][n0:n1] = x
        g["seed"][n0:n1] = seeds
        g["outputs"][n0:n1] = out
        g["status"][n0:n1] = status
        g["task"][n0:n1] = task
        g["task_key"][m0:m1] = np.array([b[0] for b in batch], dtype=np.uint64)
        g["task_start"][m0:m1] = starts
        g["task_rows"][m0:m1] = sizes
        failures = [
            {"row": int(s + i), "seed": int(b[2][i]), "message": msg}
            for b, s in zip(batch, starts.tolist(), strict=True)
            for i, msg in b[3]["messages"]
        ]
        if failures:  # before the commit: a line for an uncommitted row is ignored on read
            with open(self.path / "failures.jsonl", "a", encoding="utf-8") as f:
                f.write("".join(json.dumps(r) + "\n" for r in failures))
                f.flush()
                os.fsync(f.fileno())
        g.attrs.update({"n_rows": n1, "n_tasks": m1})  # the commit record, last
        self.n_rows, self.n_tasks = n1, m1
        for b, s in zip(batch, starts.tolist(), strict=True):
            self._index[b[0]] = (s, b[1].shape[0])

    def failures(self) -> list[dict[str, Any]]:
        """The failed runs of committed rows (row, seed, message)."""
        p = self.path / "failures.jsonl"
        if not p.exists():
            return []
        out, seen = [], set()
        for line in p.read_text(encoding="utf-8").splitlines():
            try:
                r = json.loads(line)
            except json.JSONDecodeError:  # a line torn by a kill
                continue
            if r.get("row", 1 << 62) < self.n_rows and r["row"] not in seen:
                seen.add(r["row"])
                out.append(r)
        return out

    def iter_rows(self, block: int = 65536) -> Iterator[dict[str, np.ndarray]]:
        """Committed rows in blocks (inputs, seed, outputs, status) — memory bounded."""
        g = self.group
        for a in range(0, self.n_rows, block):
            b = min(self.n_rows, a + block)
            yield {
                "inputs": np.asarray(g["inputs"][a:b]),
                "seed": np.asarray(g["seed"][a:b]),
                "outputs": np.asarray(g["outputs"][a:b]),
                "status": np.asarray(g["status"][a:b]),
            }


@dataclass
class CampaignStats:
    """Counters of a campaign: rows asked for, run here, read back, failed; compute seconds
    (wall time of the runs in the workers) and compute CPU seconds (their CPU time: the
    measured rate of a storm, independent of other processes' load)."""

    requested: int = 0
    computed: int = 0
    reused: int = 0
    failed: int = 0
    compute_seconds: float = 0.0
    compute_cpu_seconds: float = 0.0
    task_rates: deque = field(default_factory=lambda: deque(maxlen=512), repr=False)
    """CPU seconds per run of the last 512 tasks computed (the rate without the first tasks'
    compilation: :meth:`cpu_seconds_per_run`)."""

    def cpu_seconds_per_run(self) -> float:
        """Median CPU seconds of a run over the recent tasks (NaN before any): robust to the
        compilation that the first task of each worker pays."""
        return float(np.median(self.task_rates)) if self.task_rates else math.nan


class Campaign:
    """Evaluate rows of a model on Dask, through a :class:`ResultStore` (module docstring).

    Use as a context manager (the Dask client opens on the first rows that need computing and
    closes on exit).

    Parameters
    ----------
    model : CampaignModel
        The model.
    store : path
        Folder of the Zarr store (resumed if it exists).
    task_size : int
        Rows per task, in [1, 10⁴].
    n_workers : int or None
        Worker processes of the embedded Dask cluster (None: one per core); 0: this process.
    scheduler : str or None
        Address of a running Dask scheduler; wins over ``n_workers``.
    client : distributed.Client or None
        An open client to use.
    progress : callable or None
        Called with the number of rows finished (computed or read back) after each task.
    commit_interval : float
        Seconds between two commits of finished tasks to the store [s], >= 0 (0: a commit
        per batch of finished tasks). Finished tasks are queued and written together, so that
        small tasks do not cost a store commit each (the client's CPU, which competes with
        the workers on a small machine); a kill loses the tasks in flight and those finished
        within the last interval, an exception or interrupt none (they are committed first).
    submission_seconds : float
        Work per Dask submission [s] (0: one task per submission): consecutive tasks go to a
        worker together, as many as the measured rate fits in this time (the first ones one
        by one, to measure it), fewer at the end of a block so that every worker has work.
        Tasks, their identities and the store are those of ``task_size``: only the
        scheduler's round trips (per submission) are fewer.
    """

    def __init__(
        self,
        model: CampaignModel,
        store: str | os.PathLike,
        *,
        task_size: int = 8,
        n_workers: int | None = None,
        scheduler: str | None = None,
        client: Any = None,
        progress: Callable[[int], None] | None = None,
        commit_interval: float = 2.0,
        submission_seconds: float = 0.5,
    ) -> None:
        self.model = model
        self.submission_seconds = float(submission_seconds)
        self.commit_interval = float(commit_interval)
        if not (self.commit_interval >= 0.0 and math.isfinite(self.commit_interval)):
            raise InputError(
                f"commit_interval = {commit_interval!r} is invalid: a finite number of seconds >= 0"
            )
        self.store = ResultStore(store, model.identity(), model.input_names, model.output_names)
        self.task_size = integer("task_size", task_size, 1, 10**4)
        self.n_workers = n_workers
        self.scheduler = scheduler
        self._client = client
        self._given_client = client
        self._stack = ExitStack()
        self._model_future: Any = None
        self.progress = progress
        self.stats = CampaignStats()

    def __enter__(self) -> Campaign:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def close(self) -> None:
        """Close the Dask client (if this campaign opened it)."""
        self._model_future = None
        self._stack.close()
        self._client = self._given_client

    @property
    def serial(self) -> bool:
        """True when runs execute in this process."""
        return self.n_workers == 0 and self.scheduler is None and self._given_client is None

    def _ensure_client(self) -> Any:
        if self._model_future is None:
            from onbottom.study.engine import dask_client

            c = self._stack.enter_context(
                dask_client(
                    self._given_client,
                    scheduler_address=self.scheduler,
                    n_workers=self.n_workers,
                )
            )
            self._client = c
            self._model_future = c.scatter(self.model, broadcast=True, hash=False)
        return self._client

    def slots(self) -> int:
        """Concurrent runs available (1 in this process)."""
        if self.serial:
            return 1
        c = self._ensure_client()
        try:
            return max(1, sum(c.nthreads().values()))
        except Exception:  # pragma: no cover - remote scheduler without info
            return 1

    def evaluate(self, x: np.ndarray, seeds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Outputs (n, k) and status (n,) of the rows ``x`` (n, d) with ``seeds`` (n,)."""
        x = np.ascontiguousarray(np.atleast_2d(np.asarray(x, dtype=float)))
        seeds = np.ascontiguousarray(np.asarray(seeds, dtype=np.int64).reshape(-1))
        n = x.shape[0]
        if x.shape[1] != len(self.model.input_names) or seeds.shape[0] != n:
            raise InputError(
                f"rows of shape {x.shape} with {seeds.shape[0]} seeds are invalid: expected"
                f" (n, {len(self.model.input_names)}) and n seeds"
            )
        out = np.full((n, len(self.model.output_names)), np.nan)
        status = np.zeros(n, dtype=np.int32)
        self.stats.requested += n
        todo: list[tuple[tuple[int, int], int, int]] = []
        reused = 0
        for a in range(0, n, self.task_size):
            b = min(n, a + self.task_size)
            key = task_key(self.store.identity_hash, x[a:b], seeds[a:b])
            hit = self.store.lookup(key)
            if hit is not None and hit[1] == b - a:
                out[a:b], status[a:b] = self.store.read(*hit)
                reused += b - a
            else:
                todo.append((key, a, b))
        self.stats.reused += reused
        if reused and self.progress:
            self.progress(reused)
        if todo:
            self._compute(todo, x, seeds, out, status)
        return out, status

    def _finish(self, done, x, seeds, out, status, unwritten) -> None:
        """Take finished tasks into ``out``/``status`` and the counters; queue their rows in
        ``unwritten`` for the next store commit."""
        for (key, a, b), res in done:
            out[a:b], status[a:b] = res["outputs"], res["status"]
            self.stats.computed += b - a
            self.stats.failed += int(np.count_nonzero(res["status"] == STATUS_RAISED))
            self.stats.compute_seconds += res["seconds"]
            cpu = res.get("cpu_seconds", res["seconds"])
            self.stats.compute_cpu_seconds += cpu
            self.stats.task_rates.append(cpu / max(b - a, 1))
            unwritten.append((key, x[a:b], seeds[a:b], res))
        if self.progress:
            self.progress(sum(b - a for (_, a, b), _ in done))

    def _commit(self, unwritten: list, last: list[float], force: bool = False) -> None:
        """Append the queued tasks to the store when ``commit_interval`` has passed since
        the last commit (or ``force``): one commit for many small tasks."""
        now = time.perf_counter()
        if unwritten and (force or now - last[0] >= self.commit_interval):
            self.store.append(unwritten)
            unwritten.clear()
            last[0] = now

    def _compute(self, todo, x, seeds, out, status) -> None:
        unwritten: list = []
        last = [time.perf_counter()]
        try:
            if self.serial:
                for t in todo:
                    _, a, b = t
                    res = run_task(self.model, x[a:b], seeds[a:b])
                    self._finish([(t, res)], x, seeds, out, status, unwritten)
                    self._commit(unwritten, last)
            else:
                self._compute_on_dask(todo, x, seeds, out, status, unwritten, last)
        finally:  # also on an interrupt: what finished is kept
            self._commit(unwritten, last, force=True)

    def _compute_on_dask(self, todo, x, seeds, out, status, unwritten, last) -> None:
        from distributed import as_completed

        client = self._ensure_client()
        slots = self.slots()
        window = 4 * slots
        meta: dict[str, list] = {}
        nxt = 0  # the next task of todo to submit
        measured = [0.0, 0]  # worker seconds and tasks finished in this call

        def group() -> int:
            """Tasks per Dask submission: about ``submission_seconds`` of work by the rate
            measured so far (1 until a task has finished), and few enough that every worker
            still gets work at the end of the block."""
            if not measured[1] or self.submission_seconds <= 0.0:
                return 1
            per_task = measured[0] / measured[1]
            g = int(self.submission_seconds / per_task) if per_task > 0.0 else len(todo)
            return max(1, min(g, (len(todo) - nxt) // (2 * slots)))

        def submit():
            nonlocal nxt
            ts = todo[nxt : nxt + group()]
            nxt += len(ts)
            rows = [(x[a:b], seeds[a:b]) for _, a, b in ts]
            f = client.submit(run_tasks, self._model_future, rows, pure=False)
            meta[f.key] = ts
            return f

        first = [submit() for _ in range(min(window, len(todo)))]
        # results come with the completions (no round trip per task to fetch each)
        ac = as_completed(first, with_results=True)
        try:
            for batch in ac.batches():
                done = []
                for f, results in batch:
                    done.extend(zip(meta.pop(f.key), results, strict=True))
                    measured[0] += sum(r["seconds"] for r in results)
                    measured[1] += len(results)
                    if nxt < len(todo):
                        ac.add(submit())
                self._finish(done, x, seeds, out, status, unwritten)
                self._commit(unwritten, last)
        except BaseException:  # do not leave the rest running on the cluster
            client.cancel([f for f in getattr(ac, "futures", ())])
            raise


def _take(it: Iterator, n: int) -> list:
    out = []
    for _ in range(n):
        v = next(it, None)
        if v is None:
            break
        out.append(v)
    return out


def seconds_per_row(stats: CampaignStats) -> float:
    """Mean compute time of a run [s] (NaN before any)."""
    return stats.compute_seconds / stats.computed if stats.computed else math.nan
