"""Do the speed levers change the V–w curve beyond the seed scatter? (reduced preset)

For each seed the specimen is prepared once (plain engine) and penetrated twice, plain and
with the lever (``--lever subcycle``: wall/pipe contacts sub-cycled at the soil time step;
``--lever sort``: disks renumbered in cell order), so the paired difference isolates the
lever. With ``--lever fire`` (or ``subcycle-prep``) the *preparation* changes, so each seed is
prepared twice and the specimens (void ratios, steps) are compared as well;
``--lever subcycle-all`` sub-cycles both the preparation (its 1 g, ramp and N g stages) and
the penetration: the whole case as the presets run it. The baseline is always the plain engine
(``Numerics.subcycle = False``), whatever the preset's default, except for ``--lever
lidpause`` (the whole case as the preset runs it, against the same with the lid's pressure
pauses ended as soon as the pressure falls, ``Preparation.lid_pause = "adaptive"``) and for
``--lever fire-1g`` (the whole case as the preset runs it, against the same with its 1 g stage
relaxed by FIRE at the plain step, ``Preparation.relaxation = "fire-1g"``) and for
``--lever mass`` (each specimen of the preset, penetrated as the preset runs it and again
with inertial mass scaling, ``Numerics.penetration_mass_floor`` = ``--mass-floor``, default
1.0: every disk as heavy as the largest in inertia, its weight its own) and for
``--lever compaction-step`` (the whole case as the preset runs it, against the same with the
compaction at the step ``--compaction-dt-safety``, ``Numerics.compaction_dt_safety``) and for
``--lever random``: there the baseline is the whole case as the presets ran it before that
lever (sub-cycled engine, layers laid out on the square lattice,
``Preparation.layer_generation = "lattice"``) and the lever lays the layers out by random
sequential addition (opt-in), prepared and penetrated sub-cycled. ``--lever step
--dt-safety F`` penetrates each plain specimen with the plain engine at another time step
(``Numerics.dt_safety``): the step's own effect, the control for a lever whose error shrinks
with the step.

Run (in a worktree prefix ``PYTHONPATH=src``)::

    python benchmarks/dem_lever_check.py --preset SM-reduced --seeds 1 2 3 --lever subcycle

``--merge A.json B.json …`` prints the table and verdict of rows written by several calls
(for instance one seed per process on a machine with more cores) and, with ``--json``,
writes them as one record.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np

from onbottom.dem.config import PRESETS, DEMConfig
from onbottom.dem.experiment import penetrate
from onbottom.dem.preparation import prepare_sample
from onbottom.dem.sample import Sample

EDGES = np.arange(0.0, 0.5001, 0.05)


def lever(cfg: DEMConfig, name: str) -> DEMConfig:
    """``cfg`` with one lever on."""
    if name == "subcycle":  # the penetration (the specimens are the plain ones)
        return cfg.replace(numerics=dataclasses.replace(cfg.numerics, subcycle=True))
    if name in ("subcycle-prep", "subcycle-all"):
        num = dataclasses.replace(cfg.numerics, subcycle=True, subcycle_preparation=True)
        return cfg.replace(numerics=num)
    if name == "sort":
        return cfg.replace(numerics=dataclasses.replace(cfg.numerics, sort_disks=True))
    if name in ("fire", "fire-1g"):
        return cfg.replace(preparation=dataclasses.replace(cfg.preparation, relaxation=name))
    if name == "mass":  # the floor comes from --mass-floor
        return cfg
    if name == "step":  # the time step comes from --dt-safety
        return cfg
    if name == "lidspeed":  # the speed comes from --lid-speed
        return cfg
    if name == "compaction-step":  # the step comes from --compaction-dt-safety
        return cfg
    if name == "lidpause":
        return cfg.replace(preparation=dataclasses.replace(cfg.preparation, lid_pause="adaptive"))
    if name == "random":
        return cfg.replace(
            preparation=dataclasses.replace(cfg.preparation, layer_generation="random")
        )
    raise ValueError(name)


def binned(ds) -> np.ndarray:
    """Mean prototype V [kN/m] per bin of w/D (``EDGES``)."""
    w = ds["w_over_D"].values
    v = ds["V_prototype"].values / 1e3
    idx = np.digitize(w, EDGES) - 1
    return np.array([v[idx == b].mean() if np.any(idx == b) else np.nan for b in range(10)])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--preset", default="SM-reduced", choices=sorted(PRESETS))
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument(
        "--lever",
        default="subcycle",
        choices=(
            "subcycle",
            "subcycle-prep",
            "subcycle-all",
            "sort",
            "fire",
            "fire-1g",
            "random",
            "step",
            "lidpause",
            "lidspeed",
            "mass",
            "compaction-step",
        ),
    )
    ap.add_argument(
        "--preset-engine",
        action="store_true",
        help="baseline: the preset as it is (its own engine) instead of the plain engine",
    )
    ap.add_argument(
        "--lid-speed", type=float, default=1.0, help="lid speed of --lever lidspeed [m/s]"
    )
    ap.add_argument(
        "--mass-floor",
        type=float,
        default=1.0,
        help="Numerics.penetration_mass_floor of --lever mass (fraction of the largest mass)",
    )
    ap.add_argument(
        "--pipe-velocity",
        type=float,
        default=None,
        help="override Loading.pipe_velocity of both runs [m/s] (for instance to match the"
        " full-size inertial number on a reduced preset)",
    )
    ap.add_argument(
        "--compaction-dt-safety",
        type=float,
        default=0.8,
        help="Numerics.compaction_dt_safety of --lever compaction-step",
    )
    ap.add_argument(
        "--merge", nargs="+", default=None, help="rows of earlier calls (their --json files)"
    )
    ap.add_argument("--json", default=None)
    ap.add_argument("--dt-safety", type=float, default=None, help="dt_safety of the lever run")
    ap.add_argument(
        "--cache", default=None, help="folder keeping the specimens and plain curves between calls"
    )
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.seeds = args.seeds[:1]
    if args.merge is not None:
        rows = [r for f in args.merge for r in json.loads(Path(f).read_text())]
        report(rows, args.lever, args.preset, args.json)
        return
    if args.lever == "step" and args.dt_safety is None:
        ap.error("--lever step needs --dt-safety")
    cache = Path(args.cache) if args.cache else None
    if cache is not None:
        cache.mkdir(parents=True, exist_ok=True)
    # the baseline is the plain engine (one time step for all, Numerics.subcycle = False)
    preset = PRESETS[args.preset]
    if args.smoke:
        from _smoke import tiny_dem_config

        preset = tiny_dem_config()
    base = preset.replace(numerics=dataclasses.replace(preset.numerics, subcycle=False))
    if args.lever == "random":  # the whole case as run before the random layers
        base = preset.replace(
            numerics=dataclasses.replace(preset.numerics, subcycle=True),
            preparation=dataclasses.replace(preset.preparation, layer_generation="lattice"),
        )
    if (
        args.lever in ("lidpause", "lidspeed", "fire-1g", "mass", "compaction-step")
        or args.preset_engine
    ):  # the preset as it is
        base = preset
    prep_changes = args.lever in (
        "fire",
        "fire-1g",
        "subcycle-prep",
        "subcycle-all",
        "random",
        "lidpause",
        "lidspeed",
        "compaction-step",
    )
    if args.pipe_velocity is not None:
        base = base.replace(
            loading=dataclasses.replace(base.loading, pipe_velocity=args.pipe_velocity)
        )
    vtag = "" if args.pipe_velocity is None else f"_v{args.pipe_velocity:g}"
    rows = []
    for seed in args.seeds:
        cfg = base.replace(seed=seed)
        lcfg = lever(cfg, args.lever)
        if args.lever == "lidspeed":
            prep = dataclasses.replace(cfg.preparation, lid_speed=args.lid_speed)
            lcfg = lcfg.replace(preparation=prep)
        if args.lever == "compaction-step":
            num = dataclasses.replace(cfg.numerics, compaction_dt_safety=args.compaction_dt_safety)
            lcfg = lcfg.replace(numerics=num)
        if args.lever == "mass":
            num = dataclasses.replace(cfg.numerics, penetration_mass_floor=args.mass_floor)
            lcfg = lcfg.replace(numerics=num)
        if args.dt_safety is not None:
            lcfg = lcfg.replace(
                numerics=dataclasses.replace(
                    lcfg.numerics, dt_safety=args.dt_safety, subcycle_dt_safety=None
                )
            )
        t_base: dict[str, float] = {}
        t_lever: dict[str, float] = {}
        t0 = time.perf_counter()
        spath = cache / f"{cfg.name}_seed{seed}.nc" if cache is not None else None
        if spath is not None and spath.exists():
            sample = Sample.load(spath)
        else:
            sample = prepare_sample(cfg, timings=t_base)
            if spath is not None:
                sample.save(spath)
        tp = time.perf_counter() - t0
        lsample = sample.permuted(sample.cell_order()) if args.lever == "sort" else sample
        tpl = tp
        if prep_changes:
            t0 = time.perf_counter()
            lsample = prepare_sample(lcfg, timings=t_lever)
            tpl = time.perf_counter() - t0
        t0 = time.perf_counter()
        cpath = cache / f"{cfg.name}_seed{seed}{vtag}_plain.json" if cache is not None else None
        if cpath is not None and cpath.exists():
            plain_curve, ta, plain_steps = json.loads(cpath.read_text())
        else:
            a = penetrate(cfg, sample, snapshots=())
            ta = time.perf_counter() - t0
            plain_curve, plain_steps = binned(a).tolist(), int(a.attrs["steps"])
            if cpath is not None:
                cpath.write_text(json.dumps([plain_curve, ta, plain_steps]))
        t0 = time.perf_counter()
        pen_cfg = cfg if args.lever in ("fire", "subcycle-prep") else lcfg
        b = penetrate(pen_cfg, lsample, snapshots=())
        tb = time.perf_counter() - t0
        row = {
            "seed": seed,
            "plain": plain_curve,
            "lever": binned(b).tolist(),
            "wall_prep": (tp, tpl),
            "wall_pen": (ta, tb),
            "e_Ng": (sample.attrs["void_ratio_Ng"], lsample.attrs["void_ratio_Ng"]),
            "steps": (plain_steps, int(b.attrs["steps"])),
            "prep_steps": (
                {k[:-6]: int(v) for k, v in t_base.items() if k.endswith("_steps")},
                {k[:-6]: int(v) for k, v in t_lever.items() if k.endswith("_steps")},
            ),
            "inertial_number": (
                float(b.attrs["inertial_number"]),
                float(b.attrs["inertial_number_scaled"]),
            ),
            "load": os.getloadavg()[0],
        }
        rows.append(row)
        print(json.dumps(row), flush=True)
    report(rows, args.lever, args.preset, args.json, args.seeds)


def report(rows: list[dict], lever_name: str, preset: str, out: str | None, seeds=None) -> None:
    """Print the binned comparison and the verdict; write ``rows`` to ``out``."""
    if seeds is None:
        seeds = [r["seed"] for r in rows]
    pa = np.array([r["plain"] for r in rows])
    pb = np.array([r["lever"] for r in rows])
    scatter = pa.std(axis=0, ddof=1)
    diff = (pb - pa).mean(axis=0)
    print(f"lever {lever_name}, preset {preset}, seeds {seeds}")
    print("w/D bin    plain  lever  scatter  mean diff  |diff|/scatter")
    for k in range(10):
        print(
            f"{EDGES[k]:.2f}-{EDGES[k + 1]:.2f} {pa[:, k].mean():7.1f} {pb[:, k].mean():6.1f} "
            f"{scatter[k]:8.1f} {diff[k]:10.1f} {abs(diff[k]) / scatter[k]:10.2f}"
        )
    ratio = np.abs(diff) / scatter
    print(
        "mean V over the curve per seed, plain:",
        np.round(pa.mean(axis=1), 1),
        "lever:",
        np.round(pb.mean(axis=1), 1),
    )
    verdict = "PASS" if np.nanmax(ratio) < 1 else "FAIL"
    print(f"max |diff|/scatter = {np.nanmax(ratio):.2f} -> {verdict}")
    if out:
        with open(out, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
