"""Throughput and parallel efficiency of the stability-curve sweep (issue 12 §9).

Goal: >= 10⁴ storms in <= 1 h on 2 cores with >= 85 % parallel efficiency of 2 workers over
1. A full sweep is far too long for a shared machine, so this runs a reduced grid (sand and
clay, K × M, both criteria, a few seeds, the full 0.5 h + 3 h storms unless ``--peak-hours``
is given) on 1 and on 2 local Dask workers, reports storms per hour and the efficiency
T₁/(2·T₂), and extrapolates the time of 10⁴ storms from the measured rate. Storms stopped as
runaways or cut short by the early decision of a bisection step are counted as storms, so the
rate is per storm as the sweep runs them. Load average printed next to the figures.

Per-storm overhead (issue 33 §6), each against the ≈ 0.1 s of physics of a storm: the pickled
task sent to a worker and the result it returns (bytes per task and per storm: a task is a
curve point, a bisection of many storms); the scheduling and transfer time, measured twice —
wall minus worker CPU per storm on 1 worker, and directly by a no-op task of the same sizes
through the same map (:class:`onbottom.study.engine.ParallelMap` on a 1-worker cluster); and
the Python time inside a worker around the storm kernel (one point run in this process: CPU
time in the point function minus the kernel calls and the storm synthesis, each timed).

Early stop (``--early-stop``): the same small grid in this process (one core, CPU time of
this process: other processes' load does not count) with the per-seed statistic and storms
stopped once |y| reaches the criterion, with the same statistic and storms run on to the
runaway stop (the results are identical: ``tests/unit/test_curve_statistic.py``), and with
the former mean-of-maxima statistic; prints storms, storms per hour (wall) and per CPU-hour,
and CPU-s per curve point, paired on the same seeds.

Run: ``PYTHONPATH=src python benchmarks/stability_curves.py [--seeds 3] [--peak-hours 3]``;
``... --early-stop [--K 10 20] [--M 0.2 0.8 2] [--soils sand]``.
"""

from __future__ import annotations

import argparse
import os
import pickle
import time
from typing import Any

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from dataclasses import replace

import onbottom.dynamics.storm_section as storm_section
import onbottom.study.stability_curves as sc
from onbottom.study.engine import ParallelMap, _apply_batch, dask_client
from onbottom.study.stability_curves import CurveSettings, curves_table, stability_curves


class _Echo:
    """A no-op point job: carries the settings as the real one and returns a stored row."""

    def __init__(self, settings: CurveSettings, row: dict[str, Any]) -> None:
        self.settings = settings
        self.row = row

    def __call__(self, item: tuple) -> dict[str, Any]:
        return dict(self.row)


def _task_bytes(job: Any, item: tuple) -> int:
    """Bytes of one task as Dask ships it: (function, job, batch) by cloudpickle."""
    import cloudpickle

    return len(cloudpickle.dumps((_apply_batch, job, [item])))


def _timed(fn: Any, total: list[float]) -> Any:
    """``fn`` adding the CPU time of each call to ``total[0]`` [s]."""

    def timed(*a: Any, **kw: Any) -> Any:
        t = time.process_time()
        try:
            return fn(*a, **kw)
        finally:
            total[0] += time.process_time() - t

    return timed


def _in_worker_split(item: tuple, s: CurveSettings) -> dict[str, Any]:
    """One point in this process: total, storm-kernel and storm-synthesis CPU time [s] (this
    process's CPU time, not wall: other processes' load does not count), storms."""
    kernel = [0.0]
    synth = [0.0]
    call0 = storm_section.call_literal
    kin0 = sc.point_kinematics
    storm_section.call_literal = _timed(call0, kernel)
    sc.point_kinematics = _timed(kin0, synth)
    try:
        t0 = time.process_time()
        row = sc._PointJob(s)(item)
        total = time.process_time() - t0
    finally:
        storm_section.call_literal = call0
        sc.point_kinematics = kin0
    return {
        "total": total,
        "kernel": kernel[0],
        "synth": synth[0],
        "storms": row["storms"],
        "row": row,
    }


def overhead(args: argparse.Namespace, s: CurveSettings, one: dict[str, float]) -> None:
    """Print the per-storm overhead figures against the physics (module docstring)."""
    soil, k, m = args.soils[0], args.K[0], args.M[0]
    item = (soil, k, m, 0.003, "L_10")
    split = _in_worker_split(item, s)
    storms = max(int(split["storms"]), 1)
    row = split.pop("row")
    job = sc._PointJob(s)
    task_b = _task_bytes(job, item)
    result_b = len(pickle.dumps([row]))
    kernel = split["kernel"] / storms  # CPU s per storm in the kernel (the physics)
    cpu1 = one["cpu"] / one["storms"]  # worker CPU s per storm in the 1-worker sweep
    per_point = one["storms"] / one["points"]  # storms per task in the measured sweep
    print(f"per-storm overhead (1 point in this process: {soil}, K={k:g}, M={m:g}, L_10):")
    print(
        f"  physics: storm kernel {kernel * 1e3:.1f} ms CPU/storm ({storms} storms), storm"
        f" synthesis {split['synth'] / storms * 1e3:.1f} ms CPU/storm; the sweep's workers"
        f" {cpu1 * 1e3:.1f} ms CPU/storm"
    )
    py = split["total"] - split["kernel"] - split["synth"]
    print(
        f"  in-worker Python around the kernel: {py / storms * 1e3:.2f} ms CPU/storm"
        f" = {py / split['kernel']:.1%} of the kernel time"
    )
    print(
        f"  task sent to a worker: {task_b:,} B/point = {task_b / per_point:,.0f} B/storm;"
        f" result returned: {result_b:,} B/point = {result_b / per_point:,.0f} B/storm"
        f" ({per_point:.1f} storms per point in the sweep)"
    )
    gap = one["wall"] / one["storms"] - cpu1
    print(
        f"  wall - worker CPU on 1 worker: {gap * 1e3:.2f} ms/storm = {gap / cpu1:.1%} of the"
        " worker CPU per storm (an upper bound of scheduling + transfer: the cluster start and"
        " any wait for a core under other processes' load count here too)"
    )
    n_tasks = int(one["points"])
    t0 = time.perf_counter()
    with dask_client(n_workers=1) as c:
        pm = ParallelMap(c, batch_size=1)
        echo = _Echo(s, row)
        pm(echo, [item])  # warm: the worker imports onbottom once
        start = time.perf_counter() - t0
        t0 = time.perf_counter()
        pm(echo, [item] * n_tasks)
        noop = time.perf_counter() - t0
    per_task = noop / n_tasks
    print(
        f"  scheduling + transfer, no-op tasks of the same sizes through ParallelMap:"
        f" {per_task * 1e3:.2f} ms/task wall = {per_task / per_point * 1e3:.3f} ms/storm"
        f" = {per_task / per_point / cpu1:.2%} of the worker CPU per storm ({n_tasks} tasks)"
    )
    print(
        f"  cluster start and first task (once per sweep): {start:.2f} s ="
        f" {start / one['storms'] * 1e3:.2f} ms/storm over the {one['storms']:.0f} storms above"
    )


BASELINE_STORMS_PER_CPU_H = 77_296
"""The sweep's storms per CPU-hour before the early stop and the faster kernels (code of
f759cfd, mean-of-maxima statistic, run on; the default grid, one core, measured on the 2-core
development machine in a paired session, 2026-11-29). The aim: at least twice this."""


def early_stop_pair(args: argparse.Namespace, s: CurveSettings) -> None:
    """Storms per hour and per CPU-hour with and without the early stop (module docstring)."""
    runs = (
        ("per-seed 0.9 fractile, early stop", replace(s, statistic="fractile", early_stop=True)),
        ("per-seed 0.9 fractile, run on", replace(s, statistic="fractile", early_stop=False)),
        ("mean of maxima (former)", replace(s, statistic="mean_of_maxima")),
    )
    results = {}
    for label, settings in runs:
        load0 = os.getloadavg()[0]
        c0 = time.process_time()
        t0 = time.perf_counter()
        ds = stability_curves(
            args.K, args.M, soils=args.soils, settings=settings, n_workers=0, progress=False
        )
        cpu = time.process_time() - c0
        wall = time.perf_counter() - t0
        storms = int(ds.attrs["total_storms"])
        points = ds.sizes["soil"] * ds.sizes["N"] * ds.sizes["M"] * ds.sizes["K"] * 2
        stopped = int(ds.attrs.get("stopped_early", 0))
        results[label] = (ds, storms, cpu)
        print(
            f"{label}: {storms} storms ({stopped} stopped early), {storms / wall * 3600:,.0f}"
            f" storms/h wall, {storms / cpu * 3600:,.0f} storms/CPU-h, {cpu / points:.2f} CPU-s"
            f" per point ({points} points), {cpu:.1f} CPU-s, {wall:.1f} s wall;"
            f" load {load0:.2f} -> {os.getloadavg()[0]:.2f}"
        )
    (a, sa, ca), (b, sb, cb) = (results[runs[0][0]], results[runs[1][0]])
    same = all(
        bool(((a[v] == b[v]) | (a[v].isnull() & b[v].isnull())).all())
        for v in a.data_vars
        if v.startswith(("L_stable", "L_10")) and not v.endswith(("runtime", "stopped_early"))
        and "seed_m" not in v
    )  # fmt: skip
    print(
        f"early stop against run on: {cb / ca:.2f}x less CPU per point, storms per CPU-hour"
        f" x{(sa / ca) / (sb / cb):.2f}; L, medians and per-seed L identical: {same}"
    )
    rate = sa / ca * 3600
    ratio = rate / BASELINE_STORMS_PER_CPU_H
    verdict = "met" if ratio >= 2.0 else "NOT met"
    if args.smoke:
        verdict = "not judged at the smoke size (another grid and storm length)"
    print(
        f"storms per CPU-hour with early stop: {rate:,.0f} = x{ratio:.2f} the baseline"
        f" {BASELINE_STORMS_PER_CPU_H:,} (before the early stop and the faster kernels);"
        f" aim >= x2: {verdict} (the baseline is this machine's: compare on the same machine)"
    )
    for c in ("L_stable", "L_10"):
        mom = results[runs[2][0]][0][c].values.ravel()
        print(
            f"  {c}: 0.9 fractile {' '.join(f'{x:.3g}' for x in a[c].values.ravel())};"
            f" median {' '.join(f'{x:.3g}' for x in a[c + '_median'].values.ravel())};"
            f" mean of maxima {' '.join(f'{x:.3g}' for x in mom)}"
        )


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
    ap.add_argument(
        "--early-stop",
        action="store_true",
        help="only the paired early-stop figures, in this process (module docstring)",
    )
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.seeds, args.peak_hours, args.build_up_hours = 1, 0.02, 0.0
        args.K, args.M, args.soils, args.workers = [10.0], [0.2], ["sand"], [1]
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
    if args.early_stop:
        early_stop_pair(args, s)
        la = os.getloadavg()
        print(f"load average (1, 5, 15 min): {la[0]:.2f} {la[1]:.2f} {la[2]:.2f}")
        return
    times = {}
    cpus = {}
    one: dict[str, float] = {}
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
        if w == 1:
            points = (
                ds.sizes["soil"] * ds.sizes["N"] * ds.sizes["M"] * ds.sizes["K"] * len(sc.CRITERIA)
            )
            one = {"wall": wall, "cpu": cpu, "storms": storms, "points": points}
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
    if one:
        overhead(args, s, one)
    la = os.getloadavg()
    cores = os.cpu_count()
    print(f"load average (1, 5, 15 min): {la[0]:.2f} {la[1]:.2f} {la[2]:.2f} on {cores} cores")


if __name__ == "__main__":
    main()
