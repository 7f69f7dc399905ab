"""Unit test: the one time-domain driver (chunks, a growing record buffer, the progress bar)."""

from __future__ import annotations

import numpy as np

from onbottom.dynamics.driver import Recorder, drive, progress_bar
from onbottom.dynamics.status import Status


def _fake_kernel(t_end: float, dt: float):
    """A kernel advancing t by dt per row: chunk end, full buffer and run end as the kernels."""
    clock = {"t": 0.0, "calls": []}

    def advance(t_stop, rows, n):
        clock["calls"].append((t_stop, rows.shape[0], n))
        while True:
            if clock["t"] >= t_end - 1e-12:
                return n, int(Status.END)
            if clock["t"] >= t_stop:
                return n, int(Status.CHUNK)
            if n >= rows.shape[0]:
                return n, int(Status.BUFFER_FULL)
            clock["t"] += dt
            rows[n, 0] = clock["t"]
            n += 1

    return advance, clock


def test_chunks_buffer_and_end():
    advance, _ = _fake_kernel(t_end=1.0, dt=0.01)
    rec = Recorder(np.zeros((8, 1)), 0)
    seen = []
    status = drive(advance, lambda k: 0.25 * k, recorder=rec, after_chunk=seen.append)
    assert status == Status.END
    assert rec.n == 100 and rec.rows.shape[0] >= 100  # doubled from 8 to 128
    np.testing.assert_allclose(rec.records()[:, 0], 0.01 * np.arange(1, 101), rtol=1e-12)
    # after_chunk once per chunk (never for a full buffer): 3 chunk ends and the end
    assert seen == [Status.CHUNK] * 3 + [Status.END]


def test_a_final_status_runs_nothing_and_bar_fills():
    advance, clock = _fake_kernel(t_end=1.0, dt=0.1)
    status = drive(advance, lambda k: k, status=int(Status.LIFTOFF))
    assert status == Status.LIFTOFF and clock["calls"] == []

    class Bar:
        total, n = 4, 0

        def update(self, k):
            self.n += k

    bar = Bar()
    drive(advance, lambda k: 0.25 * k, recorder=Recorder(np.zeros((100, 1))), bar=bar)
    assert bar.n == bar.total
    with progress_bar(False, 10, "x", "chunk") as none:
        assert none is None
