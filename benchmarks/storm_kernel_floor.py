"""The section storm kernel beside its floor: CPU time per 3.5-h storm and the ratio.

The floor (``benchmarks/_floor.py``) is a minimal numba loop doing only the arithmetic the
storm's equations need per step — flow interpolation, the Morison + lift formula, the
Verley & Sotberg soil kernel, the Newton residual and the Newmark update — through the same
flow samples, with as many fixed steps as the kernel's accepted steps and Newton iterations to
the same tolerance. The storm kernel (:func:`onbottom.dynamics.storm_section
.simulate_storm_section`, no records: the path of seeds, sweeps and the reliability campaign)
adds step control, the safeguarded Newton bracket, the force model's state, energy
accounting, events and the running summary.

Paired runs: each repeat runs the kernel and the floor on the same storm back to back and
the ratio is taken per pair (CPU time of this process: other processes' load does not count
but slows both alike). Prints the medians, the ratio against the aim of <= 1.5, the soil
evaluations per step of each, and the load average.

Run: ``PYTHONPATH=src python benchmarks/storm_kernel_floor.py [--repeat 7] [--seeds 3]``.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _floor import floor_storm

from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro.force_model import MorisonLift, parameter_rows
from onbottom.hydro.reductions import LoadReductions
from onbottom.hydro.storm_kinematics import storm_kinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.soil.verley_sotberg import VerleySotberg


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7, help="paired runs per seed")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--dt", type=float, default=0.1, help="largest solver step [s]")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    storm = Storm.standard(SeaState(hs=4.68, tp=10.8, gamma=1.009, spreading_s=8.0))
    if args.smoke:
        args.repeat, args.seeds = 1, 1
        storm = Storm.standard(
            SeaState(hs=4.68, tp=10.8, gamma=1.009, spreading_s=8.0), peak_hours=0.05,
            build_up_hours=0.0,
        )  # fmt: skip
    d = 0.3951
    pipe = Pipe(outer_diameter=d, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    current = Current(velocity=0.91, z0=5.2e-6)
    settings = StormSolverSettings(dt_max=args.dt, record_interval=None)
    fm = MorisonLift()
    red = LoadReductions()
    ry_c, rz_c = red.constant_factors()
    rho = pipe.seawater_density
    mass = pipe.structural_mass + fm.added_mass_coefficient * rho * np.pi * d * d / 4
    params = np.ascontiguousarray(soil.packed_parameters(), dtype=float)
    state0 = np.array(soil.initial_state(), dtype=float)

    kernel_cpu, floor_cpu, ratio, per_step = [], [], [], []
    for seed in range(args.seeds):
        kin = storm_kinematics(storm.with_seed(seed), 13.0, diameter=d, current=current)
        ku = np.ascontiguousarray(kin.velocity, dtype=float)
        ka = np.ascontiguousarray(kin.acceleration, dtype=float)
        prows = parameter_rows(fm, kin.weights, kin.stage_parameters, kin.current, d)
        r = simulate_storm_section(pipe, soil, kin, settings=settings)  # compiled/loaded
        n_steps = int(r.summary["n_steps"])
        if r.status != 1 or r.summary["n_rejected"] > 0.01 * n_steps:
            print(f"  seed {seed}: {r.message}; skipped (the floor runs whole storms only)")
            continue
        fargs = (params, state0, ku, ka, kin.sample_interval, prows, kin.current, d,
                 pipe.seawater_density, pipe.submerged_weight, mass, ry_c, rz_c, args.dt,
                 n_steps, settings.force_tolerance, settings.max_iterations)  # fmt: skip
        _, evals = floor_storm(*fargs)
        for _ in range(args.repeat):
            c0 = time.process_time()
            simulate_storm_section(pipe, soil, kin, settings=settings)
            c1 = time.process_time()
            floor_storm(*fargs)
            c2 = time.process_time()
            kernel_cpu.append(c1 - c0)
            floor_cpu.append(c2 - c1)
            ratio.append((c1 - c0) / (c2 - c1))
        per_step.append((r.summary["mean_newton_iterations"], evals / n_steps))
        print(
            f"  seed {seed}: {n_steps} steps; soil evaluations per step: kernel"
            f" {per_step[-1][0]:.2f}, floor {per_step[-1][1]:.2f}"
        )
    if not ratio:
        raise SystemExit("no seed ran the whole storm: choose a heavier pipe")
    load = os.getloadavg()
    print(f"storm: {storm.duration_s / 3600:.2f} h, dt_max = {args.dt} s, {len(ratio)} pairs")
    k, f = np.median(kernel_cpu), np.median(floor_cpu)
    print(f"storm kernel (simulate_storm_section, no records): median {k:.4f} CPU-s/storm")
    print(f"floor (_floor.floor_storm): median {f:.4f} CPU-s/storm")
    med = float(np.median(ratio))
    verdict = "met" if med <= 1.5 else "NOT met"
    print(f"kernel / floor: median {med:.2f} (paired), aim <= 1.5: {verdict}")
    la = " ".join(f"{v:.2f}" for v in load)
    print(f"load average (1, 5, 15 min): {la} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
