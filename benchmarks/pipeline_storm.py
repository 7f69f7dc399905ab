"""Benchmark of the pipeline FE in a short-crested storm (issue 13 §8, issues 33 and 45 item 3).

Targets (issue 45 item 3): 1 km pipe, 2 m elements (501 nodes), Verley & Sotberg sand,
Morison + lift (the model's default force model), 0.5 h build-up + 3 h peak short-crested storm
in **<= 13 s of solver CPU on one core (1000x real time)**; cost linear in the node count up to
4000 elements; peak memory **<= 1 GB at 4000 elements**. The full benchmark storm:

    NUMBA_NUM_THREADS=1 python benchmarks/pipeline_storm.py --elements 500 \
        --build-up-hours 0.5 --peak-hours 3

On a shared machine a shorter storm (``--peak-hours``) gives the cost per node-step (steady once
the storm is at its peak) and the linearity in nodes (the default meshes: 500, 1000, 2000 and
4000 elements). ``--repeat`` runs each mesh that many times and keeps the least CPU time (the
figure a loaded machine distorts least).

Prints, per mesh: kinematics time and memory, solver CPU time of this process (``run``, the
figure that a shared, loaded machine distorts least) and wall time, steps, rejected steps,
Newton iterations per step, µs per node-step, simulated/real time ratio, the 3.5-h storm's
CPU time (measured when the run is the full storm, else scaled from the short storm and not
judged against the target: a storm's first minutes take more Newton iterations per step), max
|y|/D and max z/D, and the process's peak resident memory so far (``resource.getrusage``; the
meshes run in the order given, so the figure of the largest, last, is its peak). Then the
500-element storm's CPU time against 13 s, the µs per node-step of every mesh relative to the
first (linear in nodes when they stay near 1) and the peak resident memory against 1 GB.
``--envelopes out.npz`` saves the envelopes of the last mesh (to compare two versions of the
code: same storm, same mesh).
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


def model_of(n_el: int, length: float = 1000.0) -> PipelineModel:
    """The benchmark pipe of ``n_el`` elements over ``length`` [m] on Verley & Sotberg sand."""
    pipe = PipeBuildUp(
        steel_outer_diameter=0.2191,
        wall_thickness=0.0127,
        layers=(Layer(name="fbe", thickness=0.0055, density=1335.0),
                Layer(name="concrete", thickness=0.03, density=3043.5)),
        contents=Contents.uniform(1025.0),
    ).pipe("operation")  # fmt: skip
    sand = Sand(submerged_unit_weight=1.0e4, friction_coefficient=0.6)
    return PipelineModel(
        pipe=pipe,
        length=length,
        element_length=length / n_el,
        soil=VerleySotberg.silica(pipe, sand),
        end_conditions="fixed",
        current=0.3,
    )


def run(
    n_el: int,
    build_up_h: float,
    peak_h: float,
    dt: float,
    length: float = 1000.0,
    kin_limit: int | None = None,
    simulate_s: float | None = None,
) -> dict:
    model = model_of(n_el, length)
    sea = SeaState(hs=4.5, tp=10.0, direction_deg=80.0, spreading_s=8.0)
    storm = Storm.standard(sea, build_up_hours=build_up_h, peak_hours=peak_h, seed=0)
    t0 = time.perf_counter()
    kin = pipeline_kinematics(storm, 13.0, model.x, memory_limit=kin_limit)
    t_kin = time.perf_counter() - t0
    st = PipelineSettings(dt_max=dt, record_interval=None)
    # compile / warm the cache on a short slice first
    simulate_pipeline(model, kin, duration=2.0, settings=st)
    t0 = time.perf_counter()
    c0 = time.process_time()
    r = simulate_pipeline(model, kin, settings=st, duration=simulate_s)
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
        "max_z_over_D": float(r.envelopes["max_z"].max()) / r.diameter,
        "envelopes": r.envelopes,
        "status": r.message,
    }


TARGET_S = 13.0  # the 3.5-h storm of 500 elements in <= 13 s of CPU on one core (1000x)
MEMORY_MB = 1024.0  # peak memory <= 1 GB at 4000 elements
KIN_MEMORY_MB = 256.0  # storm_run.KINEMATICS_MEMORY_LIMIT: windowed above
STORM_S = 3.5 * 3600.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, nargs="+", default=[500, 1000, 2000, 4000])
    ap.add_argument("--repeat", type=int, default=1, help="runs per mesh (least CPU kept)")
    ap.add_argument("--build-up-hours", type=float, default=0.0)
    ap.add_argument("--peak-hours", type=float, default=0.1)
    ap.add_argument("--dt", type=float, default=0.1)
    ap.add_argument("--envelopes", default=None, help="save the last mesh's envelopes (npz)")
    ap.add_argument(
        "--kin-memory-mb",
        type=float,
        default=KIN_MEMORY_MB,
        help="kinematics above this are windowed from a temporary file (<= 0: never)",
    )
    ap.add_argument(
        "--simulate-s",
        type=float,
        default=None,
        help="simulate only this long [s] of the storm (its kinematics drawn whole)",
    )
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    a = ap.parse_args()
    if a.smoke:
        a.elements, a.build_up_hours, a.peak_hours = [20], 0.0, 0.01
    print(f"load average: {os.getloadavg()}")
    print(
        f"{'elem':>5} {'nodes':>5} {'sim[s]':>7} {'kin[s]':>6} {'kinMB':>6} {'run[s]':>7}"
        f" {'wall[s]':>7} {'steps':>6} {'rej':>4} {'it':>4} {'us/nd-st':>8} {'x real':>7}"
        f" {'3.5h[s]':>8}"
        f" {'ymax/D':>7} {'zmax/D':>7} {'RSS MB':>6}"
    )
    rows = []
    for n in a.elements:
        limit = None if a.kin_memory_mb <= 0 else int(a.kin_memory_mb * 2**20)
        runs = [
            run(n, a.build_up_hours, a.peak_hours, a.dt, kin_limit=limit, simulate_s=a.simulate_s)
            for _ in range(max(a.repeat, 1))
        ]
        r = min(runs, key=lambda q: q["run_s"])
        r["rss_MB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        rows.append(r)
        print(
            f"{r['elements']:5d} {r['nodes']:5d} {r['sim_s']:7.0f} {r['kin_s']:6.2f}"
            f" {r['kin_MB']:6.1f} {r['run_s']:7.2f} {r['wall_s']:7.2f} {r['steps']:6.0f}"
            f" {r['rejected']:4.0f}"
            f" {r['iters']:4.2f} {r['us_node_step']:8.3f} {r['speed']:7.1f}"
            f" {r['full_storm_s']:8.1f} {r['max_y_over_D']:7.4f} {r['max_z_over_D']:7.4f}"
            f" {r['rss_MB']:6.0f}  {r['status']}"
        )
    for r in rows:
        if r["elements"] != 500:
            continue
        full = abs(r["sim_s"] - STORM_S) < 1.0
        t = r["full_storm_s"]
        if full:
            verdict = "met" if t <= TARGET_S else "NOT met"
            how = "measured"
        else:
            # a short storm is its first minutes: more Newton iterations per step than the
            # storm's average, so the scaled figure is not the storm's and is not judged
            verdict = "not judged (run the storm: --build-up-hours 0.5 --peak-hours 3)"
            how = "scaled from a shorter storm, indicative only"
        print(
            f"500 elements, 3.5-h storm ({how}): {t:.1f} s CPU"
            f" ({STORM_S / t:.0f}x real time); target <= {TARGET_S:.0f} s (1000x): {verdict}"
        )
    if len(rows) > 1:
        us0 = rows[0]["us_node_step"]
        rel = ", ".join(f"{r['elements']}: {r['us_node_step'] / us0:.2f}" for r in rows)
        us = [r["us_node_step"] for r in rows]
        print(
            f"µs per node-step from {rows[0]['elements']} to {rows[-1]['elements']} elements:"
            f" {min(us):.3f}–{max(us):.3f}; relative to {rows[0]['elements']} elements: {rel}"
            " (linear in nodes when near 1)"
        )
    if a.envelopes:
        env = rows[-1]["envelopes"]
        np.savez(a.envelopes, **{k: env[k].values for k in env.data_vars})
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    largest = max(r["elements"] for r in rows)
    print(
        f"peak resident memory: {peak:.0f} MB with {largest} elements the largest mesh"
        f" (target <= {MEMORY_MB:.0f} MB at 4000 elements:"
        f" {'met' if peak <= MEMORY_MB else 'NOT met'}); load average: {os.getloadavg()}"
    )


if __name__ == "__main__":
    main()
