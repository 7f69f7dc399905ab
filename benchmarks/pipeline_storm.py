"""Benchmark of the pipeline FE in a short-crested storm (issue 13 §8).

Goal: 1 km pipe, 2 m elements (501 nodes), Verley & Sotberg sand, 0.5 h build-up + 3 h peak
short-crested storm in <= 60 s on one core after compilation, peak memory <= 2 GB, cost linear
in the node count. On a shared machine run a shorter storm (``--peak-hours``) and extrapolate
(the cost per simulated second is steady once the storm is at its peak).

    NUMBA_NUM_THREADS=1 python benchmarks/pipeline_storm.py --peak-hours 0.1 --elements 250 500

Prints, per mesh: kinematics time and memory, solver CPU time of this process (``run``, the
figure that a shared, loaded machine distorts least) and wall time, steps, Newton iterations, µs per
node-step, simulated/real time ratio, the extrapolated time of the full 3.5-h storm, and the
process's peak resident memory (``resource.getrusage``). Report ``uptime`` with the figures.
"""

from __future__ import annotations

import argparse
import os
import resource
import time

import numpy as np

from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.hydro.short_crested import pipeline_kinematics
from onbottom.inputs.pipe import Layer
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import SeaState, Storm
from onbottom.soil.verley_sotberg import VerleySotberg


def run(n_el: int, build_up_h: float, peak_h: float, dt: float, length: float = 1000.0) -> dict:
    pipe = PipeBuildUp(
        steel_outer_diameter=0.2191,
        wall_thickness=0.0127,
        layers=(Layer(name="fbe", thickness=0.0055, density=1335.0),
                Layer(name="concrete", thickness=0.03, density=3043.5)),
        contents=Contents.uniform(1025.0),
    ).pipe("operation")  # fmt: skip
    sand = Sand(submerged_unit_weight=1.0e4, friction_coefficient=0.6)
    model = PipelineModel(
        pipe=pipe,
        length=length,
        element_length=length / n_el,
        soil=VerleySotberg.silica(pipe, sand),
        end_conditions="fixed",
        current=0.3,
    )
    sea = SeaState(hs=4.5, tp=10.0, direction_deg=80.0, spreading_s=8.0)
    storm = Storm.standard(sea, build_up_hours=build_up_h, peak_hours=peak_h, seed=0)
    t0 = time.perf_counter()
    kin = pipeline_kinematics(storm, 13.0, model.x)
    t_kin = time.perf_counter() - t0
    st = PipelineSettings(dt_max=dt, record_interval=None)
    # compile / warm the cache on a short slice first
    simulate_pipeline(model, kin, duration=2.0, settings=st)
    t0 = time.perf_counter()
    c0 = time.process_time()
    r = simulate_pipeline(model, kin, settings=st)
    t_wall = time.perf_counter() - t0
    t_run = time.process_time() - c0
    s = r.summary
    sim = s["final_time"]
    node_steps = s["n_steps"] * model.x.size
    return {
        "elements": n_el,
        "nodes": model.x.size,
        "sim_s": sim,
        "kin_s": t_kin,
        "kin_MB": kin.nbytes / 2**20,
        "run_s": t_run,
        "wall_s": t_wall,
        "steps": s["n_steps"],
        "rejected": s["n_rejected"],
        "iters": s["mean_newton_iterations"],
        "us_node_step": 1e6 * t_run / max(node_steps, 1),
        "speed": sim / t_run,
        "full_storm_s": t_run * 3.5 * 3600.0 / sim,
        "max_y_over_D": r.max_displacement / r.diameter,
        "status": r.message,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, nargs="+", default=[250, 500, 1000, 2000])
    ap.add_argument("--build-up-hours", type=float, default=0.0)
    ap.add_argument("--peak-hours", type=float, default=0.1)
    ap.add_argument("--dt", type=float, default=0.1)
    a = ap.parse_args()
    print(f"load average: {os.getloadavg()}")
    print(
        f"{'elem':>5} {'nodes':>5} {'sim[s]':>7} {'kin[s]':>6} {'kinMB':>6} {'run[s]':>7}"
        f" {'wall[s]':>7} {'steps':>6} {'rej':>4} {'it':>4} {'us/nd-st':>8} {'x real':>7}"
        f" {'3.5h[s]':>8}"
        f" {'ymax/D':>7}"
    )
    for n in a.elements:
        r = run(n, a.build_up_hours, a.peak_hours, a.dt)
        print(
            f"{r['elements']:5d} {r['nodes']:5d} {r['sim_s']:7.0f} {r['kin_s']:6.2f}"
            f" {r['kin_MB']:6.1f} {r['run_s']:7.2f} {r['wall_s']:7.2f} {r['steps']:6.0f}"
            f" {r['rejected']:4.0f}"
            f" {r['iters']:4.2f} {r['us_node_step']:8.3f} {r['speed']:7.1f}"
            f" {r['full_storm_s']:8.1f} {r['max_y_over_D']:7.3f}  {r['status']}"
        )
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"peak resident memory: {peak:.0f} MB; load average: {os.getloadavg()}")
    _ = np


if __name__ == "__main__":
    main()
