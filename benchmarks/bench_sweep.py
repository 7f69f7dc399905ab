"""Benchmark of the sweep engine and of one calibration.

Prints

* runs per second of a sweep of the Inclined 1 centrifuge test over an (A, μ) grid: serial
  in-process, and on an embedded Dask LocalCluster with 1 and 2 worker processes (start-up
  excluded, numba compiled in the workers by a warm-up sweep), and the scaling efficiency
  (rate with 2 workers / (2 × rate with 1 worker));
* the wall time of one full calibration (differential evolution + least-squares polish, A, B,
  C, μ) of a virtual Inclined 1 record, serial.

    python benchmarks/bench_sweep.py [--points 256]

Figures depend on the machine and on its load; say which machine and how loaded it was when
you quote them.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numpy as np

from onbottom.calibration.fit import calibrate
from onbottom.calibration.objective import HISTORY_ONLY
from onbottom.calibration.paper import PAPER_TABLE2, default_parameters, virtual_record
from onbottom.calibration.simulators import CentrifugeSimulator
from onbottom.study.engine import dask_client
from onbottom.study.functions import centrifuge_response
from onbottom.study.sweep import sweep


def _grid(n_points: int) -> dict[str, np.ndarray]:
    n = max(2, round(float(np.sqrt(n_points))))
    return {"A": np.linspace(0.15, 0.5, n), "mu": np.linspace(0.45, 0.9, n)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=256, help="grid points per sweep")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.points = 4
    grid = _grid(args.points)
    n = grid["A"].size * grid["mu"].size
    fixed = {"test": "Inclined 1"}
    print(f"cores visible: {os.cpu_count()}, grid: {n} runs of Inclined 1")

    sweep(centrifuge_response, {"A": [0.25]}, fixed=fixed, n_workers=0, progress=False)
    t0 = time.perf_counter()
    ds = sweep(centrifuge_response, grid, fixed=fixed, n_workers=0, progress=False)
    serial = n / (time.perf_counter() - t0)
    print(f"serial (in-process):  {serial:8.1f} runs/s  ({int(ds.attrs['n_failed'])} failed)")

    rates = {}
    for workers in (1, 2):
        t_start = time.perf_counter()
        with dask_client(n_workers=workers) as client:
            startup = time.perf_counter() - t_start
            sweep(
                centrifuge_response,
                {"A": [0.25, 0.3]},
                fixed=fixed,
                client=client,
                progress=False,
                batch_size=1,
            )  # compile in every worker
            t0 = time.perf_counter()
            sweep(centrifuge_response, grid, fixed=fixed, client=client, progress=False)
            rates[workers] = n / (time.perf_counter() - t0)
        print(
            f"dask, {workers} worker(s):   {rates[workers]:8.1f} runs/s"
            f"  (cluster start-up {startup:.1f} s)"
        )
    print(f"scaling efficiency 2 vs 1 worker: {rates[2] / (2 * rates[1]):.2f}")

    sim = CentrifugeSimulator()
    truth = PAPER_TABLE2["Inclined 1"]
    rec = virtual_record("Inclined 1", truth, noise=0.01, seed=1, simulator=sim)
    start = {"A": 0.6, "B": 0.8, "C": 1.3, "mu": 1.0}
    t0 = time.perf_counter()
    res = calibrate(rec, default_parameters(start=start), simulator=sim, weights=HISTORY_ONLY)
    wall = time.perf_counter() - t0
    fitted = ", ".join(f"{k} = {v:.3f}" for k, v in res.values.items())
    print(
        f"calibration of Inclined 1 (serial): {wall:.1f} s, {res.n_evaluations} simulations"
        f" ({res.n_evaluations / wall:.0f}/s); {fitted}"
    )


if __name__ == "__main__":
    main()
