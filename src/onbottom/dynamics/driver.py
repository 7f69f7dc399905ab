"""The one time-domain driver: chunked integration, a growing record buffer, a progress bar.

Every time-domain solver (:mod:`~onbottom.dynamics.section`, :mod:`~onbottom.dynamics.
storm_section`, :mod:`~onbottom.dynamics.pipeline.solver`) runs its numba kernel chunk by chunk
through :func:`drive`: the kernel advances to the end of a chunk (``t_stop``), an event, the
end of the run or a full record buffer, and returns a :class:`~onbottom.dynamics.status.Status`.
Between chunks the driver makes room in the record buffer — a :class:`Recorder` doubles it
(the sections keep every row in memory), a :class:`SpillRecorder` hands its rows on and reuses
it (the pipeline: rows per node, streamed to chunk files or lists) —, moves the progress bar and
calls the solver's ``after_chunk`` (the pipeline writes its checkpoint there). The loop is
Python, once per chunk; the time steps stay in the kernels.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

from onbottom.dynamics.status import Status

__all__ = ["Recorder", "SpillRecorder", "drive", "progress_bar"]

_CHUNK = int(Status.CHUNK)
_BUFFER_FULL = int(Status.BUFFER_FULL)


class Recorder:
    """Record rows written by a kernel: ``rows`` (capacity × width), ``n`` rows used.

    A kernel that returns :attr:`Status.BUFFER_FULL` gets room (:meth:`full`: the buffer
    doubled) and is called again from where it stopped; at the end of each chunk the driver
    calls :meth:`end_chunk` (nothing here).
    """

    def __init__(self, rows: np.ndarray, n: int = 0) -> None:
        self.rows = rows
        self.n = int(n)

    def full(self) -> None:
        """Make room after :attr:`Status.BUFFER_FULL`: :meth:`grow`."""
        self.grow()

    def end_chunk(self) -> None:
        """Called by :func:`drive` after each chunk, before ``after_chunk``."""

    def grow(self) -> None:
        """Double the capacity, keeping the rows written."""
        self.rows = np.concatenate([self.rows, np.empty_like(self.rows)])

    def records(self) -> np.ndarray:
        """The rows written (a view)."""
        return self.rows[: self.n]


class SpillRecorder(Recorder):
    """A fixed record buffer that the kernel fills from row 0: when it is full and at the end
    of each chunk, ``sink(*views)`` gets the rows written (views of ``buffers[i][:n]``: copy
    what is kept) and the buffer is used again.

    ``buffers``: arrays whose first axis is the row (e.g. times and values per node); the first
    is :attr:`rows`.
    """

    def __init__(self, sink: Callable[..., None], *buffers: np.ndarray) -> None:
        super().__init__(buffers[0], 0)
        self.buffers = buffers
        self.sink = sink

    def full(self) -> None:
        """Hand the rows on (:meth:`spill`)."""
        self.spill()

    def end_chunk(self) -> None:
        """Hand the rows on (:meth:`spill`)."""
        self.spill()

    def spill(self) -> None:
        """``sink`` the rows written, if any, and start again at row 0."""
        if self.n:
            self.sink(*(b[: self.n] for b in self.buffers))
        self.n = 0

    def grow(self) -> None:
        raise RuntimeError("a SpillRecorder does not grow: it spills")


@contextmanager
def progress_bar(enabled: bool, total: int, desc: str, unit: str) -> Iterator[Any]:
    """A tqdm bar (``tqdm.auto``) when ``enabled``, else None; filled and closed at the end."""
    if not enabled:
        yield None
        return
    from tqdm.auto import tqdm

    bar = tqdm(total=total, desc=desc, unit=unit, leave=False)
    try:
        yield bar
    finally:
        bar.close()


def drive(
    advance: Callable[[float, np.ndarray, int], tuple[int, int]],
    chunk_end: Callable[[int], float],
    *,
    recorder: Recorder | None = None,
    status: int = _CHUNK,
    bar: Any = None,
    position: Callable[[], int] | None = None,
    after_chunk: Callable[[int], None] | None = None,
) -> int:
    """Run a kernel chunk by chunk until it returns a final status; return that status.

    Parameters
    ----------
    advance : callable
        ``advance(t_stop, rows, n) -> (n, status)``: the kernel call from the committed state
        to ``t_stop`` [s], appending records to ``rows`` from row ``n``.
    chunk_end : callable
        ``chunk_end(k)``: the end time of chunk k = 1, 2, … [s], asked once per chunk (a
        kernel called again after a full buffer goes on to the same end).
    recorder : Recorder or None
        The record buffer (None: the kernel records elsewhere; ``rows`` is then an empty array).
    status : int
        The status to start from (a final one runs nothing: e.g. lift-off at the start, or a
        resumed run that had ended).
    bar : tqdm or None
        Progress bar (:func:`progress_bar`): one step per chunk, or ``position()`` when given.
    after_chunk : callable or None
        ``after_chunk(status)``, called after every chunk (the last one included).
    """
    empty = np.empty((0, 0))
    k = 1
    t_stop = None
    while status == _CHUNK:
        rows = recorder.rows if recorder is not None else empty
        n = recorder.n if recorder is not None else 0
        if t_stop is None:
            t_stop = chunk_end(k)
        n, status = advance(t_stop, rows, n)
        if recorder is not None:
            recorder.n = n
        if status == _BUFFER_FULL:
            if recorder is None:
                raise RuntimeError("a kernel without a record buffer returned BUFFER_FULL")
            recorder.full()
            status = _CHUNK
            continue
        t_stop = None
        if recorder is not None:
            recorder.end_chunk()
        if after_chunk is not None:
            after_chunk(status)
        if status == _CHUNK:
            k += 1
            if bar is not None and position is None:
                bar.update(1)
        if bar is not None and position is not None:
            bar.update(position() - bar.n)
    if bar is not None and position is None:
        bar.update(bar.total - bar.n)
    return status
