"""Throughput of the 2D DEM engine: particle-steps per second on 1 and 2 threads.

The bed: ~60,000 equal disks (d = 0.74 mm, the paper's SM count in its 13D × 5.5D box) on a
triangular lattice, each touching its six neighbours with a 1e-4·r overlap, under 25 g with the
paper's contact parameters — a settled bed with the contact density of a dense packing (three
half-list neighbours per disk), built without minutes of settling. ``--sample FILE`` measures
a prepared specimen instead (``onbottom dem prepare``).

Run: ``python benchmarks/bench_dem.py [--steps 400] [--repeat 3] [--sample sm.nc]`` (in a git
worktree prefix ``PYTHONPATH=src`` so that the worktree's package is measured). Other processes on
a shared machine lower the figures; the script prints the load average next to them, the best of
``--repeat`` timings, and for one thread also the rate per CPU-second of the process (not
lowered by time slices lost to other processes, still by their use of the shared caches).
"""

from __future__ import annotations

import argparse
import os
import time

# OpenMP threads that spin at barriers lose badly when other processes share the cores;
# passive waiting must be chosen before the OpenMP runtime starts (override by exporting it).
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numba
import numpy as np

from onbottom.constants import GRAVITY
from onbottom.dem.config import SM
from onbottom.dem.engine import Simulation
from onbottom.dem.sample import Sample


def lattice_bed(width: float = 0.26, height: float = 0.11, d: float = 0.74e-3) -> Sample:
    a = d
    h = a * np.sqrt(3.0) / 2.0
    rows = int((height - a) / h)
    cols = int((width - a) / a)
    pts = [
        ((c + 0.5 + 0.5 * (r % 2)) * a, 0.5 * a + r * h)
        for r in range(rows)
        for c in range(cols - (r % 2))
    ]
    pos = np.array(pts)
    return Sample(pos, np.full(len(pos), 0.5 * a * (1 + 1e-4)), (0.0, width, 0.0, height))


def measure(
    sample: Sample, threads: int, steps: int, repeat: int = 1, nsub: int = 1
) -> tuple[float, float]:
    """Best (wall-clock, CPU-time) particle-steps per second of ``repeat`` runs of ``steps``.

    ``nsub`` = 4: zonal sub-cycling (the default engine; the disks next to the walls take 4
    sub-steps): the rate per step, which is 3.65× longer than the plain one."""
    sim = Simulation(
        sample,
        SM.contacts,
        damping=0.7,
        gravity=(0.0, -25 * GRAVITY),
        threads=threads,
        nsub=nsub,
    )
    sim.run(50)  # compile + warm caches
    wall = cpu = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        c0 = time.process_time()
        sim.run(steps)
        cpu = min(cpu, time.process_time() - c0)
        wall = min(wall, time.perf_counter() - t0)
    return sim.n * steps / wall, sim.n * steps / cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--steps", type=int, default=400)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--sample", default=None)
    ap.add_argument(
        "--subcycle", action="store_true", help="also measure the zonally sub-cycled step"
    )
    ap.add_argument(
        "--cell-order",
        action="store_true",
        help="measure the specimen renumbered in cell order too (Numerics.sort_disks)",
    )
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.steps, args.repeat = 5, 1
    sample = Sample.load(args.sample) if args.sample else lattice_bed()
    if args.smoke and not args.sample:
        sample = lattice_bed(width=0.02, height=0.01)
    if args.cell_order:
        for label, s in (("as numbered", sample), ("cell order", None)):
            s = s if s is not None else sample.permuted(sample.cell_order())
            _, per_cpu = measure(s, 1, args.steps, args.repeat)
            print(
                f"{label}: {per_cpu:.3e} particle-steps per CPU-second, one thread "
                f"(load average {os.getloadavg()[0]:.2f})"
            )
        return
    print(
        f"disks: {sample.n}, steps: {args.steps}, numba threads available: "
        f"{numba.config.NUMBA_NUM_THREADS}, load average: {os.getloadavg()[0]:.2f}"
    )
    for nsub in (1, 4) if args.subcycle else (1,):
        for threads in (1, 2):
            if threads > numba.config.NUMBA_NUM_THREADS:
                break
            rate, per_cpu = measure(sample, threads, args.steps, args.repeat, nsub)
            extra = f", {per_cpu:.3e} per CPU-second" if threads == 1 else ""
            label = "sub-cycled, " if nsub > 1 else ""
            print(
                f"{label}threads={threads}: {rate:.3e} particle-steps/s{extra} "
                f"(load average {os.getloadavg()[0]:.2f})"
            )


if __name__ == "__main__":
    main()
