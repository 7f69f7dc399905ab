"""Cost of the wake and Fourier force models against constant Morison (issue 30 item 8).

Goal: each flow-history model costs at most 2x constant Morison per 3.5-h section storm and per
pipeline storm. Runs are paired and alternated (model order rotated each repeat) on the same
seeds and the same machine; CPU time of the time integration only (the flow synthesis is the
same for every model and is done once per seed, outside the timing).

Run: ``PYTHONPATH=src python benchmarks/force_models.py [--repeat 5] [--pipeline-elements 50]``.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np

from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro.registry import build_force_model
from onbottom.hydro.storm_kinematics import storm_kinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.soil.verley_sotberg import VerleySotberg

MODELS = ("morison", "wake", "fourier")


def _model(name: str):
    return build_force_model(name, {"table": "example"} if name == "fourier" else {})


def section(repeat: int) -> dict[str, list[float]]:
    """CPU seconds of the time integration of one 3.5-h storm, per model, paired by seed."""
    pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm.standard(SeaState(hs=4.68, tp=10.8, gamma=1.009, spreading_s=8.0))
    current = Current(velocity=0.91, z0=5.2e-6)
    settings = StormSolverSettings(dt_max=0.1, record_interval=None)
    models = {m: _model(m) for m in MODELS}
    kin0 = storm_kinematics(storm, 13.0, diameter=0.3951, current=current)
    for fm in models.values():  # compile / load the caches
        simulate_storm_section(pipe, soil, kin0, force_model=fm, settings=settings)
    cpu: dict[str, list[float]] = {m: [] for m in MODELS}
    steps: dict[str, list[int]] = {m: [] for m in MODELS}
    for seed in range(repeat):
        kin = storm_kinematics(storm.with_seed(seed), 13.0, diameter=0.3951, current=current)
        order = MODELS[seed % 3 :] + MODELS[: seed % 3]
        for m in order:
            c0 = time.process_time()
            r = simulate_storm_section(pipe, soil, kin, force_model=models[m], settings=settings)
            cpu[m].append(time.process_time() - c0)
            steps[m].append(int(r.summary["n_steps"]))
        print(
            f"  seed {seed}: "
            + ", ".join(f"{m} {cpu[m][-1] * 1e3:.1f} ms ({steps[m][-1]} steps)" for m in MODELS)
        )
    return cpu


def pipeline(elements: int, repeat: int) -> dict[str, list[float]]:
    """CPU seconds of a 0.35-h pipeline storm per model (same kinematics), alternated."""
    from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
    from onbottom.hydro.short_crested import pipeline_kinematics
    from onbottom.inputs.pipe import Layer
    from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp

    pipe = PipeBuildUp(
        steel_outer_diameter=0.2191,
        wall_thickness=0.0127,
        layers=(Layer(name="fbe", thickness=0.0055, density=1335.0),
                Layer(name="concrete", thickness=0.03, density=3043.5)),
        contents=Contents.uniform(1025.0),
    ).pipe("operation")  # fmt: skip
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=1.0e4, friction_coefficient=0.6))
    length = 1000.0
    built = {
        m: PipelineModel(
            pipe=pipe,
            length=length,
            element_length=length / elements,
            soil=soil,
            end_conditions="fixed",
            current=0.3,
            force_model=_model(m),
        )
        for m in MODELS
    }
    sea = SeaState(hs=4.5, tp=10.0, direction_deg=80.0, spreading_s=8.0)
    storm = Storm.standard(sea, build_up_hours=0.1, peak_hours=0.25, seed=0)
    kin = pipeline_kinematics(storm, 13.0, built["morison"].x)
    settings = PipelineSettings(dt_max=0.1, record_interval=None)
    for m in MODELS:
        simulate_pipeline(built[m], kin, duration=2.0, settings=settings)  # compile / warm
    cpu: dict[str, list[float]] = {m: [] for m in MODELS}
    for rep in range(repeat):
        order = MODELS[rep % 3 :] + MODELS[: rep % 3]
        for m in order:
            c0 = time.process_time()
            simulate_pipeline(built[m], kin, settings=settings)
            cpu[m].append(time.process_time() - c0)
        print(f"  repeat {rep}: " + ", ".join(f"{m} {cpu[m][-1]:.2f} s" for m in MODELS))
    return cpu


def _report(title: str, cpu: dict[str, list[float]]) -> None:
    base = np.median(cpu["morison"])
    print(title)
    for m in MODELS:
        med = float(np.median(cpu[m]))
        ratio = med / base
        goal = "" if m == "morison" else f"  goal <= 2x: {'met' if ratio <= 2.0 else 'NOT met'}"
        print(f"  {m:8s} median CPU {med * 1e3:9.1f} ms   {ratio:5.2f}x Morison{goal}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument(
        "--pipeline-elements", type=int, default=0, help="also a pipeline of N elements"
    )
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.repeat = 1
    _report("section, one 3.5-h storm (integration CPU time):", section(args.repeat))
    if args.pipeline_elements > 0:
        _report(
            f"pipeline, {args.pipeline_elements} elements, 0.35-h storm (CPU time):",
            pipeline(args.pipeline_elements, max(2, args.repeat // 2)),
        )
    load = os.getloadavg()
    print(f"load average (1, 5, 15 min): {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")


if __name__ == "__main__":
    main()
