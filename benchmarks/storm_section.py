"""Speed of one 3.5-h storm on a pipe section (0.5 h build-up + 3 h peak), one core.

Goal (issue 12 §9): <= 0.5 s after compilation (>= 25,000 times faster than real time).
Measures the flow synthesis (FFT) and the time integration separately, best and median of
``--repeat`` runs, wall clock and process CPU time (CPU time is not inflated by time slices
lost to other processes on a shared machine); prints the load average next to the figures.

Output (issue 33 item 4, "writing a storm's records costs no more than its integration"): the
same storm recorded every ``--record-interval`` seconds (the storm case's default 0.5 s) and
written to NetCDF with ``SolverResult.save`` (plain and at compression level 4), the CPU time
of each write against the integration's, and the file sizes.

Run: ``PYTHONPATH=src python benchmarks/storm_section.py [--repeat 7] [--dt 0.1]``.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np

from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro.storm_kinematics import storm_kinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.soil.verley_sotberg import VerleySotberg


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--dt", type=float, default=0.1, help="largest solver step [s]")
    ap.add_argument("--record-interval", type=float, default=0.5, help="output rows [s]")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.repeat = 1
    pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm.standard(SeaState(hs=4.68, tp=10.8, gamma=1.009, spreading_s=8.0))
    current = Current(velocity=0.91, z0=5.2e-6)
    settings = StormSolverSettings(dt_max=args.dt, record_interval=None)

    t0 = time.perf_counter()
    kin = storm_kinematics(storm, 13.0, diameter=0.3951, current=current)
    r = simulate_storm_section(pipe, soil, kin, settings=settings)
    first = time.perf_counter() - t0

    syn, solve, cpu, full, nsteps = [], [], [], [], []
    for seed in range(args.repeat):
        c0 = time.process_time()
        t0 = time.perf_counter()
        kin = storm_kinematics(storm.with_seed(seed), 13.0, diameter=0.3951, current=current)
        t1 = time.perf_counter()
        r = simulate_storm_section(pipe, soil, kin, settings=settings)
        t2 = time.perf_counter()
        cpu.append(time.process_time() - c0)
        syn.append(t1 - t0)
        solve.append(t2 - t1)
        full.append(r.status == 1)
        nsteps.append(r.summary["n_steps"])
        print(f"  seed {seed}: {r.message}, {r.summary['n_steps']} steps, {t2 - t0:.3f} s")
    keep = np.array(full)
    if not keep.any():
        raise SystemExit("no seed ran the whole storm: choose a heavier pipe")
    syn = list(np.array(syn)[keep])
    solve = list(np.array(solve)[keep])
    cpu = list(np.array(cpu)[keep])
    total = np.array(syn) + np.array(solve)
    print(f"figures over the {keep.sum()} seeds that ran the whole storm (no runaway stop):")
    load = os.getloadavg()
    steps = int(np.median([n for n, ok in zip(nsteps, full, strict=True) if ok]))
    print(f"storm: {storm.duration_s / 3600:.1f} h, dt_max = {args.dt} s, {steps} steps")
    print(f"first call (numba compilation or cache load): {first:.2f} s")
    print(f"flow synthesis (FFT)  best {min(syn):.3f} s   median {np.median(syn):.3f} s")
    print(f"time integration      best {min(solve):.3f} s   median {np.median(solve):.3f} s")
    print(f"one storm, total      best {total.min():.3f} s   median {np.median(total):.3f} s")
    print(f"one storm, CPU time   best {min(cpu):.3f} s   median {np.median(cpu):.3f} s")
    print(f"faster than real time: {storm.duration_s / np.median(total):,.0f}x (median wall)")
    print(f"goal <= 0.5 s: {'met' if np.median(total) <= 0.5 else 'NOT met'} (median wall)")
    _output_figures(pipe, soil, storm, current, args, float(np.median(cpu)))
    cores = os.cpu_count()
    print(
        f"load average (1, 5, 15 min): {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} on {cores} cores"
    )


def _output_figures(pipe, soil, storm, current, args, integration_cpu: float) -> None:
    """CPU time of writing one storm's records (NetCDF) against its integration."""
    settings = StormSolverSettings(dt_max=args.dt, record_interval=args.record_interval)
    kin = storm_kinematics(storm.with_seed(0), 13.0, diameter=0.3951, current=current)
    simulate_storm_section(pipe, soil, kin, settings=settings)  # the recording path loaded
    c0 = time.process_time()
    r = simulate_storm_section(pipe, soil, kin, settings=settings)
    run_cpu = time.process_time() - c0
    rows = r.data.sizes.get("time", 0)
    print(
        f"output: records every {args.record_interval:g} s ({rows} rows); the run with"
        f" recording {run_cpu:.3f} CPU-s"
    )
    with tempfile.TemporaryDirectory(prefix="onbottom-out-") as tmp:
        for level in (0, 4):
            path = Path(tmp) / f"storm_{level}.nc"
            times = []
            for _ in range(3):
                path.unlink(missing_ok=True)
                c0 = time.process_time()
                r.save(path, compression_level=level)
                times.append(time.process_time() - c0)
            w = min(times)
            verdict = "met" if w <= run_cpu else "NOT met"
            print(
                f"  NetCDF write, compression level {level}: {w:.3f} CPU-s (best of 3),"
                f" {path.stat().st_size / 1e6:.2f} MB; target <= the integration"
                f" ({run_cpu:.3f} CPU-s): {verdict}"
            )
            ratio = w / run_cpu
            print(
                f"    write / integration = {ratio:.2f}; aim <= 0.5:"
                f" {'met' if ratio <= 0.5 else 'NOT met'}"
            )
    print(f"  (integration without recording: {integration_cpu:.3f} CPU-s, median)")


if __name__ == "__main__":
    main()
