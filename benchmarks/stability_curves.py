"""Throughput and parallel efficiency of the stability-curve sweep (issue 12 §9).

Goal: >= 10⁴ storms in <= 1 h on 2 cores with >= 85 % parallel efficiency of 2 workers over
1. A full sweep is far too long for a shared machine, so this runs a reduced grid (sand and
clay, K × M, both criteria, a few seeds, the full 0.5 h + 3 h storms unless ``--peak-hours``
is given) on 1 and on 2 local Dask workers, reports storms per hour and the efficiency
T₁/(2·T₂), and extrapolates the time of 10⁴ storms from the measured rate. Storms stopped as
runaways or cut short by the early decision of a bisection step are counted as storms, so the
rate is per storm as the sweep runs them. Load average printed next to the figures.

Run: ``PYTHONPATH=src python benchmarks/stability_curves.py [--seeds 3] [--peak-hours 3]``.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from onbottom.study.stability_curves import CurveSettings, curves_table, stability_curves


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--peak-hours", type=float, default=3.0)
    ap.add_argument("--build-up-hours", type=float, default=0.5)
    ap.add_argument("--K", type=float, nargs="+", default=[5.0, 10.0, 20.0, 40.0])
    ap.add_argument("--M", type=float, nargs="+", default=[0.0, 0.4])
    ap.add_argument("--soils", nargs="+", default=["sand", "clay"])
    ap.add_argument("--tolerance", type=float, default=0.05)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    args = ap.parse_args()
    s = CurveSettings(
        seeds=args.seeds,
        peak_hours=args.peak_hours,
        build_up_hours=args.build_up_hours,
        tolerance=args.tolerance,
    )
    # compile/cache-load once in this process so that no timing includes it
    stability_curves(
        [10.0],
        [0.2],
        soils=["sand"],
        criteria=["L_10"],
        n_workers=0,
        settings=CurveSettings(seeds=1, peak_hours=0.02, build_up_hours=0.0),
    )
    times = {}
    cpus = {}
    for w in args.workers:
        load0 = os.getloadavg()[0]
        t0 = time.perf_counter()
        ds = stability_curves(args.K, args.M, soils=args.soils, settings=s, n_workers=w)
        wall = time.perf_counter() - t0  # includes the cluster start
        storms = int(ds.attrs["total_storms"])
        compute = float(ds.attrs["wall_time_s"])
        times[w] = wall
        cpu = float(ds.attrs["cpu_time_s"])
        cpus[w] = cpu / storms
        print(
            f"{w} worker(s): {storms} storms in {wall:.1f} s ({compute:.1f} s in the map),"
            f" {storms / wall * 3600:,.0f} storms/h, {wall / storms:.3f} s/storm;"
            f" load {load0:.2f} -> {os.getloadavg()[0]:.2f}"
        )
        print(f"  CPU time of the workers: {cpu:.1f} s = {cpu / storms:.3f} s/storm")
        if w == max(args.workers):
            t_1e4 = 1e4 * wall / storms
            print(f"  extrapolated: 10^4 storms in {t_1e4 / 60:.1f} min on {w} worker(s)")
            for row in curves_table(ds):
                print(
                    "  "
                    + ", ".join(
                        f"{k}={v:.3g}" if isinstance(v, float) else str(v) for k, v in row.items()
                    )
                )
    if 1 in times and 2 in times:
        eff = times[1] / (2.0 * times[2])
        print(f"parallel efficiency of 2 workers over 1: {eff:.0%} (goal >= 85 %)")
        ceff = cpus[1] / cpus[2]
        print(
            f"CPU-time efficiency (CPU s/storm on 1 worker / on 2 workers): {ceff:.0%}"
            " (the overhead of distribution alone, independent of other processes' load)"
        )
    la = os.getloadavg()
    cores = os.cpu_count()
    print(f"load average (1, 5, 15 min): {la[0]:.2f} {la[1]:.2f} {la[2]:.2f} on {cores} cores")


if __name__ == "__main__":
    main()
