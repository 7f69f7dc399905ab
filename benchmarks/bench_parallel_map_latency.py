"""Latency of one ParallelMap call on a local 2-worker cluster (issue 31).

ParallelMap waits for finished tasks with a done-callback wake-up and a Ctrl-C flag (polled
at most every 0.1 s) instead of blocking in distributed's ``as_completed`` iterator; this
prints the time per call of both for many small calls (as a differential-evolution
generation makes), so that the interrupt handling can be seen to cost nothing.

    PYTHONPATH=src python3 benchmarks/bench_parallel_map_latency.py
"""

from __future__ import annotations

import sys
import time

SMOKE = "--smoke" in sys.argv[1:]
"""Tiny size (CI: the script finishes and prints its figures)."""


def _double(x: int) -> int:
    return 2 * x


def _blocking_map(client, func, items):
    """The former loop: ``for fut in as_completed(futures)``."""
    from distributed import as_completed

    futures = client.map(func, items, pure=False)
    index = {f.key: i for i, f in enumerate(futures)}
    out = [None] * len(items)
    for fut in as_completed(futures):
        out[index[fut.key]] = fut.result()
    return out


def main(calls: int = 40, items: int = 8) -> None:
    from onbottom.study.engine import ParallelMap, dask_client

    with dask_client(n_workers=2) as client:
        pm = ParallelMap(client, batch_size=1)
        for rnd in range(2):
            t0 = time.perf_counter()
            for _ in range(calls):
                pm(_double, range(items))
            t1 = time.perf_counter()
            for _ in range(calls):
                _blocking_map(client, _double, list(range(items)))
            t2 = time.perf_counter()
            print(
                f"round {rnd}: ParallelMap {1e3 * (t1 - t0) / calls:.1f} ms/call,"
                f" blocking as_completed {1e3 * (t2 - t1) / calls:.1f} ms/call"
                f" ({items} one-item tasks per call)"
            )


if __name__ == "__main__":
    main(calls=2, items=2) if SMOKE else main()
