"""Throughput of the reliability campaign (issue 34 item 4): storms per second on 1 and 2 Dask
workers, parallel efficiency, memory, and the extrapolated cost of 10⁵ and 10⁷ storms.

The storms are those of ``examples/reliability_case.toml`` (1 h peak, 0.25 h build-up, a
Verley & Sotberg sand, sea states from the synthetic hindcast's storm climate), drawn by Monte
Carlo and run through :class:`onbottom.reliability.campaign.Campaign` (Zarr store, task
identity, bounded tasks in flight) — the path of ``onbottom reliability`` — in two blocks.
Each configuration starts from an empty store. The resident memory of this process (the
client side: the workers are separate processes) is read before, after the first half and
after all storms (flat: it does not grow with the storms run), and the store's size on disk
per storm.

    python benchmarks/reliability_campaign.py [--storms N] [--task-size K] [--workers 1 2]

N defaults to 10⁵ (the issue's figure); on a loaded 2-core machine use a few hundred and read
the extrapolation. Cost model: T(N, W) = N·t_storm/(W·e) with t_storm the measured seconds per
storm on one worker and e the measured efficiency (assumed to hold on a cluster of W workers,
where one task of K storms costs one scheduler round trip, ≈ 1 ms, against K·t_storm).
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

from onbottom.cases.reliability import load_reliability_setup
from onbottom.reliability.campaign import Campaign
from onbottom.reliability.climate import StormClimate
from onbottom.reliability.dynamic import seeds_from_uniform
from onbottom.reliability.storm_model import StormModel

CASE = Path(__file__).resolve().parents[1] / "examples" / "reliability_case.toml"


def rows(model: StormModel, params, n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    cols = []
    for p in params:
        if p.name.startswith("u_"):
            cols.append(rng.standard_normal(n))
        else:
            d = p.openturns()
            cols.append(np.asarray(d.getSample(n)).reshape(-1))
    return np.column_stack(cols), seeds_from_uniform(rng.uniform(size=n))


def smoke_setup(setup):
    """The case with a 0.05-h peak and no build-up (the smoke run's tiny size)."""
    from dataclasses import replace

    st = setup.storm
    peak = replace(st.storm.stages[0], duration_s=180.0)
    storm = replace(st.storm, stages=(peak,), build_up_s=0.0)
    return replace(setup, storm=replace(st, storm=storm))


def _workers_cpu(c: Campaign) -> float:
    """CPU seconds of the campaign's worker processes so far (all of their threads)."""
    return float(sum(c._ensure_client().run(time.process_time).values()))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--storms", type=int, default=100_000)
    ap.add_argument("--task-size", type=int, default=4)
    ap.add_argument(
        "--commit-interval", type=float, default=2.0, help="seconds between store commits"
    )
    ap.add_argument(
        "--workers",
        type=int,
        nargs="+",
        default=[1, 2],
        help="worker counts to run (default 1 2; the efficiency needs both 1 and 2)",
    )
    ap.add_argument(
        "--smoke", action="store_true", help="tiny run (CI): 4 storms of 0.05 h on 1 worker"
    )
    a = ap.parse_args()
    if a.smoke:
        a.storms, a.workers = 4, [1]
    from onbottom.metocean import MetoceanOptions, analyse_hindcast, read_hindcast

    setup = load_reliability_setup(CASE)
    if a.smoke:
        setup = smoke_setup(setup)
    res = analyse_hindcast(
        read_hindcast(setup.climate.hindcast),
        MetoceanOptions(sectors=setup.climate.sectors, storm_rate=setup.climate.storm_rate),
    )
    climate = StormClimate.from_result(res, current=setup.climate.current)
    user = list(setup.inputs)
    model = StormModel(
        setup.storm,
        inputs=tuple(p.name for p in user),
        climate=climate,
        pipe_heading_deg=setup.climate.pipe_heading_deg,
        soil_kind=setup.seabed_model,
    )
    params = climate.parameters() + user
    x, seeds = rows(model, params, a.storms, 0)
    warm = Campaign(model, Path(tempfile.mkdtemp()) / "w.zarr", n_workers=0)
    warm.evaluate(x[:1], seeds[:1] + 10**9)  # numba compile in this process
    import psutil

    me = psutil.Process()
    rate = {}
    cpu_total = {}
    for workers in a.workers:
        tmp = Path(tempfile.mkdtemp())
        with Campaign(
            model,
            tmp / "s.zarr",
            n_workers=workers,
            task_size=a.task_size,
            commit_interval=a.commit_interval,
        ) as c:
            c.evaluate(x[:workers], seeds[:workers] + 10**9)  # start and compile the workers
            rss0 = me.memory_info().rss
            cpu_w0 = _workers_cpu(c)
            n_w0 = c.stats.computed
            runs0 = c.stats.compute_cpu_seconds
            c0 = time.process_time()
            t0 = time.perf_counter()
            half = a.storms // 2
            for lo, hi in ((0, half), (half, a.storms)):  # blocks, as an estimator asks
                c.evaluate(x[lo:hi], seeds[lo:hi])
                if lo == 0:
                    rss_half = me.memory_info().rss
            dt = time.perf_counter() - t0
            client_cpu = (time.process_time() - c0) / a.storms
            rss1 = me.memory_info().rss
            worker_cpu = (_workers_cpu(c) - cpu_w0) / (c.stats.computed - n_w0)
            in_runs = (c.stats.compute_cpu_seconds - runs0) / (c.stats.computed - n_w0)
        size = sum(f.stat().st_size for f in (tmp / "s.zarr").rglob("*") if f.is_file())
        rate[workers] = a.storms / dt
        mib = 1024.0**2
        print(
            f"{workers} worker(s): {a.storms} storms in {dt:.1f} s = {rate[workers]:.2f} storms/s;"
            f" compute {c.stats.compute_seconds / c.stats.computed:.3f} s/storm in the workers;"
            f" store {size / a.storms:.0f} B/storm; RSS of this process {rss0 / mib:.0f} MiB"
            f" before, {rss_half / mib:.0f} after {half} storms, {rss1 / mib:.0f} after"
            f" {a.storms}"
        )
        print(
            f"  CPU per storm: worker processes {worker_cpu * 1e3:.2f} ms (of which the runs"
            f" {in_runs * 1e3:.2f} ms), this"
            f" process (client, scheduler, store) {client_cpu * 1e3:.2f} ms ="
            f" {client_cpu / worker_cpu:.1%} of a storm"
        )
        cpu_total[workers] = (worker_cpu, client_cpu)
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"load average (1, 5, 15 min) at the end: {os.getloadavg()}")
    if 1 in cpu_total and 2 in cpu_total:
        w1, _ = cpu_total[1]
        w2, k2 = cpu_total[2]
        # 2 workers on 2 cores share them with this process: 2 storms cost 2·w2 + 2·k2 CPU
        eff_cpu = w1 / (w2 + k2)
        t_1e5 = 1e5 * (w2 + k2) / 2.0
        print(
            f"CPU efficiency 1 -> 2 workers (CPU per storm of 1 worker / CPU per storm of 2"
            f" workers and this process; idle 2 cores): {eff_cpu:.2f}; target >= 0.9:"
            f" {'met' if eff_cpu >= 0.9 else 'NOT met'}"
        )
        print(
            f"10^5 storms on 2 idle cores from the CPU per storm: {t_1e5 / 60:.1f} min;"
            f" target <= 10 min: {'met' if t_1e5 <= 600 else 'NOT met'}"
        )
    if 1 not in rate or 2 not in rate:
        return
    eff = rate[2] / (2.0 * rate[1])
    print(f"efficiency 1 -> 2 workers: {eff:.2f}")
    t1 = 1.0 / rate[1]
    for n, w in ((10**5, 2), (10**7, 2), (10**7, 256), (10**7, 2048)):
        hours = n * t1 / (w * eff) / 3600.0
        print(f"extrapolated: {n:.0e} storms on {w} workers ~ {hours:.3g} h")


if __name__ == "__main__":
    main()
