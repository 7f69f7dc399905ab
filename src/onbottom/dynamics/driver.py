"""The one time-domain driver: chunked integration, a growing record buffer, a progress bar.

Every time-domain solver (:mod:`~onbottom.dynamics.section`, :mod:`~onbottom.dynamics.
storm_section`, :mod:`~onbottom.dynamics.pipeline.solver`) runs its numba kernel chunk by chunk
through :func:`drive`: the kernel advances to the end of a chunk (``t_stop``), an event, the
end of the run or a full record buffer, and returns a :class:`~onbottom.dynamics.status.Status`.
Between chunks the driver grows the buffer (:class:`Recorder`), moves the progress bar and
calls the solver's ``after_chunk`` (the pipeline writes its records and checkpoint there).
The loop is Python, once per chunk; the time steps stay in the kernels.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

from onbottom.dynamics.status import Status

__all__ = ["Recorder", "drive", "progress_bar"]

_CHUNK = int(Status.CHUNK)
_BUFFER_FULL = int(Status.BUFFER_FULL)


class Recorder:
    """Record rows written by a kernel: ``rows`` (capacity × width), ``n`` rows used.

    A kernel that returns :attr:`Status.BUFFER_FULL` gets the buffer doubled
    (:meth:`grow`) and is called again from where it stopped.
    """

    def __init__(self, rows: np.ndarray, n: int = 0) -> None:
        self.rows = rows
        self.n = int(n)

    def grow(self) -> None:
        """Double the capacity, keeping the rows written."""
        self.rows = np.concatenate([self.rows, np.empty_like(self.rows)])

    def records(self) -> np.ndarray:
        """The rows written (a view)."""
        return self.rows[: self.n]


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
        ``chunk_end(k)``: the end time of chunk k = 1, 2, … [s].
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
    while status == _CHUNK:
        rows = recorder.rows if recorder is not None else empty
        n = recorder.n if recorder is not None else 0
        n, status = advance(chunk_end(k), rows, n)
        if recorder is not None:
            recorder.n = n
        if status == _BUFFER_FULL:
            if recorder is None:
                raise RuntimeError("a kernel without a record buffer returned BUFFER_FULL")
            recorder.grow()
            status = _CHUNK
            continue
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
