"""One full DEM case from a fresh start: preparation + penetration, timed per stage.

The issue-#15 measurement: a full-size case (``--preset SM``, ``SD`` or ``SM-Dr48``) prepared
from nothing and penetrated to 0.5D, with the wall-clock time, steps and particle-steps per
second of every stage and the 1-minute load average around it (the machine is shared: a load
above the number of cores makes a figure not comparable with a quiet one). Unlike
``dem_stages.py`` it keeps what it makes: the specimen (``<out>/<name>_sample.nc``), the run
(``<out>/<name>_run.nc``, the input of ``onbottom dem summarize``), the stage figures
(``<out>/<name>_stages.json``) and, with ``--keep-checkpoints``, a copy of every penetration
checkpoint (``<out>/checkpoints/``), from which any stretch of the run can be replayed
bitwise (for instance to take field snapshots at w/D values only known afterwards).

``--from-compaction CHECKPOINT STAGES`` starts a lever that acts after the compaction
(``--relaxation fire-1g``) from another run's compacted specimen: CHECKPOINT is that run's
preparation checkpoint written after its last layer (copy it before its 1 g stage overwrites
it), STAGES its ``_stages.json``. The compaction is the same for both configurations (checked:
the identities may differ only in ``preparation.relaxation`` and the inertial mass floors
of the later stages, and both relax the layers alike), so the checkpoint is re-labelled with
this run's identity and resumed; the compaction's wall time and steps are taken from STAGES
and added to the total.

``--stage prepare`` and ``--stage penetrate`` run the two halves in separate calls (the
second reads the specimen and the first's figures); the total is the sum of the two.
Before and after the case (and before a separate penetration) it records the machine's own
rate, ``machine_rate.reference()`` (a frozen reference workload, ns per disk-step on 2 and 1
threads), so that cases timed on different days can be told apart from a machine that ran
faster or slower. A
penetration resumed from its checkpoint reports this call's wall time, ``steps_this_call``
and the rate over those steps (``steps`` is the run's total).

Run::

    python benchmarks/dem_full_case.py --preset SM-Dr48 --out /tmp/smdr48
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import dataclasses

import machine_rate
import numba
import xarray as xr

from onbottom.dem.config import PRESETS, RELAXATIONS, DEMConfig
from onbottom.dem.experiment import penetrate
from onbottom.dem.identity import dem_identity, differences
from onbottom.dem.preparation import prepare_sample
from onbottom.dem.sample import Sample
from onbottom.results import save_dataset

STAGES = ("generation", "compaction", "1g", "ramp", "Ng")


def load() -> float:
    """1-minute load average."""
    return os.getloadavg()[0]


def adopt_compaction(cfg: DEMConfig, source: Path, target: Path) -> None:
    """Copy the compacted specimen in ``source`` to ``target`` under ``cfg``'s identity."""
    saved = Sample.load(source)
    meta = saved.attrs["_checkpoint"]
    if meta["layers_done"] != cfg.preparation.n_layers or meta.get("stage", "compaction") != (
        "compaction"
    ):
        raise SystemExit(
            f"{source}: not a checkpoint of a finished compaction (layers_done"
            f" {meta['layers_done']}, stage {meta.get('stage')})"
        )
    ident = dem_identity(cfg, "preparation").fields
    diff = differences(meta["identity"], ident)
    after_compaction = (
        "config.preparation.relaxation:",
        "config.numerics.equilibrium_mass_floor:",
        "config.numerics.penetration_mass_floor:",
    )
    if any(not d.startswith(after_compaction) for d in diff):
        raise SystemExit(
            f"{source}: another case, not only a lever that acts after the compaction: {diff}"
        )
    old = cfg.preparation.__class__(
        **{**dataclasses.asdict(cfg.preparation), **meta["identity"]["config"]["preparation"]}
    )
    if old.stage_relaxation("layer") != cfg.preparation.stage_relaxation("layer"):
        raise SystemExit(f"{source}: its layers were relaxed otherwise ({diff})")
    meta["identity"] = ident
    saved.attrs["_checkpoint"] = meta
    saved.save(target)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--preset", default="SM-Dr48", choices=sorted(PRESETS))
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--out", help="folder for the specimen, run and figures (required)")
    ap.add_argument("--checkpoint-every", type=int, default=100_000)
    ap.add_argument(
        "--keep-checkpoints", action="store_true", help="copy every penetration checkpoint"
    )
    ap.add_argument("--stage", default="both", choices=("both", "prepare", "penetrate"))
    ap.add_argument(
        "--subcycle", default=None, choices=("on", "off"), help="override Numerics.subcycle"
    )
    ap.add_argument(
        "--sort-disks",
        default=None,
        choices=("on", "off"),
        help="override Numerics.sort_disks (off: resume a run started before it was on)",
    )
    ap.add_argument(
        "--relaxation",
        default=None,
        choices=RELAXATIONS,
        help="override Preparation.relaxation (fire-1g: FIRE for the 1 g stage only)",
    )
    ap.add_argument(
        "--penetration-mass-floor",
        type=float,
        default=None,
        help="override Numerics.penetration_mass_floor (inertial mass scaling, penetration)",
    )
    ap.add_argument(
        "--equilibrium-mass-floor",
        type=float,
        default=None,
        help="override Numerics.equilibrium_mass_floor (the same in the 1 g, ramp, N g stages)",
    )
    ap.add_argument(
        "--compaction-dt-safety",
        type=float,
        default=None,
        help="override Numerics.compaction_dt_safety (the compaction's own step)",
    )
    ap.add_argument(
        "--from-compaction",
        nargs=2,
        metavar=("CHECKPOINT", "STAGES"),
        default=None,
        help="start from another run's compacted specimen (see the module docstring)",
    )
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    cfg = PRESETS[args.preset]
    if args.smoke:
        import functools
        import tempfile

        from _smoke import tiny_dem_config

        cfg = tiny_dem_config()
        args.out = args.out or tempfile.mkdtemp(prefix="dem_full_case_smoke_")
        args.checkpoint_every = min(args.checkpoint_every, 2000)
        machine_rate.reference = functools.partial(machine_rate.reference, steps=20, repeat=1)
    elif args.out is None:
        ap.error("--out is required")
    if args.relaxation is not None:
        cfg = cfg.replace(
            preparation=dataclasses.replace(cfg.preparation, relaxation=args.relaxation)
        )
    if args.sort_disks is not None:
        num = dataclasses.replace(cfg.numerics, sort_disks=args.sort_disks == "on")
        cfg = cfg.replace(numerics=num)
    for fld in ("penetration_mass_floor", "equilibrium_mass_floor", "compaction_dt_safety"):
        if getattr(args, fld) is not None:
            num = dataclasses.replace(cfg.numerics, **{fld: getattr(args, fld)})
            cfg = cfg.replace(numerics=num)
    if args.seed is not None:
        cfg = cfg.replace(seed=args.seed)
    if args.subcycle is not None:
        num = dataclasses.replace(cfg.numerics, subcycle=args.subcycle == "on")
        cfg = cfg.replace(numerics=num)
    out = Path(args.out)
    (out / "checkpoints").mkdir(parents=True, exist_ok=True)
    name = f"{cfg.name}_seed{cfg.seed}"
    figfile = out / f"{name}_stages.json"
    if args.stage == "penetrate":
        fig = json.loads(figfile.read_text())
        sample = Sample.load(out / f"{name}_sample.nc")
        fig["load_start_penetration"] = load()
        fig["machine_reference_penetration_start"] = machine_rate.reference()
        penetration(cfg, sample, out, name, fig, args.checkpoint_every, args.keep_checkpoints)
        return
    fig: dict = {
        "preset": cfg.name,
        "seed": cfg.seed,
        "subcycle": cfg.numerics.subcycle,
        "numerics": dataclasses.asdict(cfg.numerics),
        "relaxation": cfg.preparation.relaxation,
        "threads": numba.config.NUMBA_NUM_THREADS,
        "cores": os.cpu_count(),
        "load_start": load(),
        "machine_reference_start": machine_rate.reference(),
    }
    if args.from_compaction is not None:
        ck_src, stages_src = (Path(p) for p in args.from_compaction)
        adopt_compaction(cfg, ck_src, out / f"{name}_prep.checkpoint.nc")
        src_fig = json.loads(stages_src.read_text())
        fig["compaction_from"] = {
            "stages_file": str(stages_src),
            "compaction": src_fig["preparation"]["stages"]["compaction"],
        }
    print(json.dumps(fig), flush=True)
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    last = [0.0]

    def prep_progress(stage: str, frac: float) -> None:
        now = time.perf_counter()
        if now - last[0] > 60.0:
            last[0] = now
            print(f"  prep {stage} {frac:.2f} t={now - t0:.0f}s load={load():.2f}", flush=True)

    sample = prepare_sample(
        cfg, progress=prep_progress, checkpoint=out / f"{name}_prep.checkpoint.nc",
        timings=timings,
    )  # fmt: skip
    prep_wall = time.perf_counter() - t0
    if "compaction_from" in fig:  # the adopted compaction's time belongs to this case
        prep_wall += fig["compaction_from"]["compaction"]["wall_s"]
    sample.save(out / f"{name}_sample.nc")
    stages = {}
    for st in STAGES:
        if f"{st}_wall" in timings:
            w = timings[f"{st}_wall"]
            stages[st] = {
                "wall_s": w,
                "steps": int(timings[f"{st}_steps"]),
                "disks": int(timings[f"{st}_disks"]),
                "particle_steps_per_s": timings[f"{st}_disk_steps"] / w if w else 0.0,
            }
    fig["preparation"] = {"wall_s": prep_wall, "stages": stages, "load_end": load()}
    fig["sample"] = {
        k: (float(v) if isinstance(v, (int, float)) else str(v))
        for k, v in sample.attrs.items()
        if k.startswith(("void_ratio", "equilibrium", "ratio", "n_"))
    }
    print(json.dumps(fig["preparation"]), flush=True)
    figfile.write_text(json.dumps(fig, indent=1, default=float))
    if args.stage == "both":
        penetration(cfg, sample, out, name, fig, args.checkpoint_every, args.keep_checkpoints)


def penetration(
    cfg, sample, out: Path, name: str, fig: dict, checkpoint_every: int, keep: bool
) -> None:
    """Penetrate ``sample`` to the final embedment; add the figures to ``fig`` and save."""
    ck = out / f"{name}_run.checkpoint.nc"
    steps_before = 0  # steps a checkpoint this call resumes from had already taken
    if ck.exists():
        with xr.open_dataset(ck) as saved:
            steps_before = int(json.loads(saved.attrs["checkpoint_meta"])["step_count"])
    seen = [0.0]
    t1 = time.perf_counter()

    def pen_progress(frac: float) -> None:
        if ck.exists() and ck.stat().st_mtime != seen[0]:
            seen[0] = ck.stat().st_mtime
            if keep:
                shutil.copy2(ck, out / "checkpoints" / f"{name}_{frac:.4f}.nc")
            print(f"  pen {frac:.3f} t={time.perf_counter() - t1:.0f}s load={load():.2f}",
                  flush=True)  # fmt: skip

    ds = penetrate(
        cfg, sample, checkpoint=ck, checkpoint_every=checkpoint_every, progress=pen_progress
    )
    pen_wall = time.perf_counter() - t1
    save_dataset(ds, out / f"{name}_run.nc")
    steps = int(ds.attrs["steps"])
    fig["penetration"] = {
        "wall_s": pen_wall,
        "steps": steps,
        "steps_this_call": steps - steps_before,
        "disks": sample.n,
        "particle_steps_per_s": sample.n * (steps - steps_before) / pen_wall,
        "dt": float(ds.attrs["dt"]),
        "inertial_number": float(ds.attrs["inertial_number"]),
        "inertial_number_scaled": float(ds.attrs["inertial_number_scaled"]),
        "numerics": dataclasses.asdict(cfg.numerics),
        "load_end": load(),
    }
    fig["machine_reference_end"] = machine_rate.reference()
    prep_wall = fig["preparation"]["wall_s"]
    fig["total_wall_s"] = prep_wall + pen_wall
    (out / f"{name}_stages.json").write_text(json.dumps(fig, indent=1, default=float))
    print(json.dumps(fig["penetration"]), flush=True)
    print(f"total {fig['total_wall_s'] / 60:.1f} min (preparation {prep_wall / 60:.1f}, "
          f"penetration {pen_wall / 60:.1f})", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
