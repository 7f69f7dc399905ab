"""Unit test: the one time-domain driver (chunks, a growing record buffer, the progress bar)."""

from __future__ import annotations

import numpy as np

from onbottom.dynamics.driver import Recorder, SpillRecorder, drive, progress_bar
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


def test_spill_recorder_hands_on_every_row_once_and_asks_each_chunk_end_once():
    advance, clock = _fake_kernel(t_end=1.0, dt=0.01)
    spilled = []
    seen = []
    rec = SpillRecorder(lambda rows: spilled.append(rows.copy()), np.zeros((8, 1)))

    def after(status):
        seen.append((status, sum(len(x) for x in spilled)))

    ends = []

    def chunk_end(k):
        ends.append(k)
        return 0.25 * k

    status = drive(advance, chunk_end, recorder=rec, after_chunk=after)
    assert status == Status.END and ends == [1, 2, 3, 4]
    # a full buffer calls the kernel again towards the same chunk end
    assert len(clock["calls"]) > 4 and {c[0] for c in clock["calls"]} == {0.25, 0.5, 0.75, 1.0}
    rows = np.concatenate(spilled)[:, 0]
    np.testing.assert_allclose(rows, 0.01 * np.arange(1, 101), rtol=1e-12)
    assert rec.rows.shape[0] == 8 and max(len(x) for x in spilled) == 8  # reused, not grown
    # every row of a chunk is handed on before after_chunk sees the chunk's end
    assert [n for _, n in seen] == [25, 50, 75, 100]
