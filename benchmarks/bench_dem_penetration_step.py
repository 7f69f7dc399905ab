"""Plain against zonally sub-cycled penetration step on a penetration checkpoint, paired.

The SD question of issue #15: the sub-cycled step is longer (``Numerics.subcycle_dt_safety``)
but costs more per disk (its sub-step pass over the disks near the pipe is serial), so what it
buys is the simulated time per wall-clock second, not the step count. This loads one
checkpoint of a full-size run (``dem_full_case.py --keep-checkpoints``) with the preset's
numerics, plain and sub-cycled in turn (``--repeat`` times, alternated, so that a change of
the machine's rate hits both), steps ``--steps`` from it and prints particle-steps/s and
simulated seconds per wall-clock second with the load average.

Run::

    python benchmarks/bench_dem_penetration_step.py --preset SD \\
        --checkpoint runs/sd_s5f/checkpoints/SD_seed5_0.6060.nc
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import time
from pathlib import Path

import numba

from onbottom.dem import _kernels as K
from onbottom.dem.config import PRESETS
from onbottom.dem.engine import step_sizes
from onbottom.dem.experiment import _load_checkpoint


def tiny_checkpoint(cfg) -> Path:
    """A penetration checkpoint of ``cfg`` (prepared and penetrated here; the smoke run)."""
    import shutil
    import tempfile

    from onbottom.dem.experiment import penetrate
    from onbottom.dem.preparation import prepare_sample

    tmp = Path(tempfile.mkdtemp(prefix="bench_dem_penetration_step_"))
    ck, kept = tmp / "run.checkpoint.nc", tmp / "kept.nc"

    def keep(frac: float) -> None:
        if ck.exists():
            shutil.copy2(ck, kept)

    penetrate(cfg, prepare_sample(cfg), checkpoint=ck, checkpoint_every=200, progress=keep)
    if not kept.exists():
        raise SystemExit("the tiny penetration wrote no checkpoint")
    return kept


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--preset", default="SD", choices=sorted(PRESETS))
    ap.add_argument("--checkpoint", type=Path, help="a penetration checkpoint (required)")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=numba.config.NUMBA_NUM_THREADS)
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    base = PRESETS[args.preset]
    if args.smoke:
        from _smoke import tiny_dem_config

        base = tiny_dem_config()
        args.steps, args.repeat = 5, 1
        args.checkpoint = args.checkpoint or tiny_checkpoint(base)
    elif args.checkpoint is None:
        ap.error("--checkpoint is required")
    sub = dataclasses.replace(base.numerics, subcycle=True)
    modes = {"plain": dataclasses.replace(base.numerics, subcycle=False), "sub-cycled": sub}
    best: dict[str, tuple[float, float]] = {}
    print(f"{args.checkpoint.name}, {args.threads} threads, {os.cpu_count()} cores")
    for rep in range(args.repeat):
        for mode, num in modes.items():
            cfg = base.replace(numerics=num)
            sim, *_ = _load_checkpoint(args.checkpoint, cfg, args.threads)
            m_min = cfg.material.density * math.pi * float(sim.rad.min()) ** 2
            safety = num.subcycled_dt_safety if num.subcycle else num.dt_safety
            dt, _ = step_sizes(cfg.contacts, m_min, safety, num.subcycle)
            sim.prm[K.P_DT] = dt  # the checkpoint carries the step it was written with
            sim.run(50)
            t0 = time.perf_counter()
            sim.run(args.steps)
            wall = time.perf_counter() - t0
            rate, sim_rate = args.steps * sim.n / wall, args.steps * dt / wall
            b = best.get(mode, (0.0, 0.0))
            best[mode] = (max(b[0], rate), max(b[1], sim_rate))
            print(
                f"{rep} {mode:10s} dt {dt:.3g} s nsub {sim.nsub}: {rate:.3g} particle-steps/s,"
                f" {sim_rate:.3g} simulated s per s, load {os.getloadavg()[0]:.2f}",
                flush=True,
            )
    for mode, (rate, sim_rate) in best.items():
        print(f"best {mode:10s} {rate:.3g} particle-steps/s, {sim_rate:.3g} simulated s per s")


if __name__ == "__main__":
    main()
