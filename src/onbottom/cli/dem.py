"""``onbottom dem`` — 2D DEM of a pipe pushed vertically into sand.

Examples::

    onbottom dem prepare --preset SD-reduced --out sd.nc
    onbottom dem penetrate --preset SD-reduced --sample sd.nc --out sd_run.nc
    onbottom dem penetrate --preset SM --sample sm.nc --out sm_run.nc \\
        --checkpoint sm_ck.nc --checkpoint-every 200000      # full size, resumable
    onbottom dem plot sd_run.nc --sample sd.nc --outdir figs
    onbottom dem summarize sm_run.nc sd_run.nc --outdir summaries   # small files to keep
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import click
import numpy as np

from onbottom.cli._common import emit_json, handle_errors, json_option
from onbottom.dem.config import PRESETS, DEMConfig, get_preset

__all__ = ["command"]

# OpenMP worker threads that spin at barriers lose badly when other processes share the cores
# (measured: 2 threads slower than 1); wait passively unless the user chose otherwise. Must be
# set before the first parallel kernel starts the OpenMP runtime.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _config(preset: str, seed: int | None, config_file: Path | None) -> DEMConfig:
    if config_file is not None:
        cfg = DEMConfig.from_json(config_file.read_text())
    else:
        cfg = get_preset(preset)
    if seed is not None:
        cfg = cfg.replace(seed=seed)
    return cfg


class _Bar:
    """tqdm progress bar on the fraction done (with ETA), or nothing."""

    def __init__(self, enabled: bool, desc: str) -> None:
        self.bar = None
        if enabled:
            from tqdm import tqdm

            self.bar = tqdm(total=1000, desc=desc, unit="‰", leave=True)
        self.last = 0

    def __call__(self, *args: float | str) -> None:
        frac = float(args[-1])
        if self.bar is not None:
            now = round(1000 * min(max(frac, 0.0), 1.0))
            if now > self.last:
                self.bar.update(now - self.last)
                self.last = now

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


preset_option = click.option(
    "--preset",
    type=click.Choice(sorted(PRESETS)),
    default="SD-reduced",
    show_default=True,
    help="Experiment preset (SM/SD: the paper's full size; -reduced: minutes).",
)
seed_option = click.option("--seed", type=int, default=None, help="Override the preset seed.")
config_option = click.option(
    "--config",
    "config_file",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
    default=None,
    help="DEMConfig as JSON (DEMConfig.to_json); overrides --preset.",
)
threads_option = click.option(
    "--threads", type=int, default=None, help="Numba threads (default: automatic)."
)
progress_option = click.option(
    "--progress/--no-progress", default=True, show_default=True, help="Show a progress bar."
)


results_argument = click.argument(
    "results", nargs=-1, required=True, type=click.Path(exists=True, dir_okay=False, path_type=Path)
)
outdir_option = click.option(
    "--outdir",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("."),
    show_default=True,
)


@click.group("dem")
def command() -> None:
    """2D DEM of a pipe pushed into sand (model scale SI; prototype = ×N)."""


def _prepare(cfg: DEMConfig, out: Path, progress: bool):
    """Prepare and save the specimen; resumable per compacted layer.

    The layer checkpoint ``<out>.prep-checkpoint.nc`` is written after every layer, read when a
    previous run was interrupted, and removed once the specimen is saved.
    """
    from onbottom.dem.preparation import prepare_sample

    checkpoint = out.with_name(out.name + ".prep-checkpoint.nc")
    bar = _Bar(progress, f"prepare {cfg.name}")
    t0 = time.perf_counter()
    try:
        sample = prepare_sample(
            cfg,
            progress=lambda stage, f: bar(
                0.8 * f if stage == "compaction" else (0.8 if stage == "1g" else 0.9) + 0.1 * f
            ),
            checkpoint=checkpoint,
        )
    finally:
        bar.close()
    sample.save(out)
    checkpoint.unlink(missing_ok=True)
    return sample, time.perf_counter() - t0


@command.command("prepare")
@preset_option
@seed_option
@config_option
@click.option("--out", type=click.Path(dir_okay=False, path_type=Path), required=True)
@progress_option
@json_option
@handle_errors
def prepare_cmd(
    preset: str,
    seed: int | None,
    config_file: Path | None,
    out: Path,
    progress: bool,
    as_json: bool,
) -> None:
    """Prepare a specimen (multi-layer under-compaction, 1 g then N g equilibrium).

    Resumable: rerunning the same command after an interruption continues from the last
    compacted layer or the last checkpoint of the 1 g / N g equilibria
    (OUT.prep-checkpoint.nc, every 100,000 steps).
    """
    cfg = _config(preset, seed, config_file)
    sample, wall = _prepare(cfg, out, progress and not as_json)
    summary = {
        "preset": cfg.name,
        "file": str(out),
        "n_particles": sample.n,
        "target_void_ratio": cfg.target.void_ratio,
        "void_ratio": sample.attrs.get("void_ratio_Ng"),
        "equilibrium_Ng_converged": sample.attrs.get("equilibrium_Ng_converged"),
        "wall_time_s": wall,
    }
    if as_json:
        emit_json(summary)
    else:
        for k, v in summary.items():
            click.echo(f"{k:>26}: {v}")


@command.command("penetrate")
@preset_option
@seed_option
@config_option
@click.option(
    "--sample",
    "sample_path",
    type=click.Path(dir_okay=False, path_type=Path),
    required=True,
    help="Specimen file; prepared (and written) first if it does not exist.",
)
@click.option("--out", type=click.Path(dir_okay=False, path_type=Path), required=True)
@click.option(
    "--checkpoint",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Checkpoint file (default: <out>.checkpoint.nc).",
)
@click.option(
    "--checkpoint-every",
    type=int,
    default=200_000,
    show_default=True,
    help="Steps between checkpoints.",
)
@click.option(
    "--resume/--no-resume",
    default=True,
    show_default=True,
    help="Resume from the checkpoint if present.",
)
@click.option("--max-steps", type=int, default=None, help="Stop after this many steps (resumable).")
@threads_option
@progress_option
@json_option
@handle_errors
def penetrate_cmd(
    preset: str,
    seed: int | None,
    config_file: Path | None,
    sample_path: Path,
    out: Path,
    checkpoint: Path | None,
    checkpoint_every: int,
    resume: bool,
    max_steps: int | None,
    threads: int | None,
    progress: bool,
    as_json: bool,
) -> None:
    """Push the pipe to the final embedment; write the V–w record and field snapshots."""
    from onbottom.dem.experiment import initial_state, penetrate
    from onbottom.dem.sample import Sample
    from onbottom.results import save_dataset

    cfg = _config(preset, seed, config_file)
    show = progress and not as_json
    if sample_path.exists():
        sample = Sample.load(sample_path)
    else:
        sample, _ = _prepare(cfg, sample_path, show)
    ck = checkpoint if checkpoint is not None else out.with_suffix(".checkpoint.nc")
    bar = _Bar(show, f"penetrate {cfg.name}")
    t0 = time.perf_counter()
    try:
        ds = penetrate(
            cfg,
            sample,
            checkpoint=ck,
            checkpoint_every=checkpoint_every,
            resume=resume,
            threads=threads,
            max_steps=max_steps,
            progress=bar,
        )
    finally:
        bar.close()
    wall = time.perf_counter() - t0
    ini = initial_state(cfg, sample)
    for name, da in ini.data_vars.items():
        ds[f"initial_{name}"] = da.rename({"depth": "circle_depth"})
    ds = ds.assign_coords(circle_depth=("circle_depth", ini["depth"].values))
    ds.attrs["circle_diameter"] = ini.attrs["circle_diameter"]
    save_dataset(ds, out)
    if bool(ds.attrs["complete"]) and ck.exists():
        ck.unlink()
    from onbottom.dem.summary import summarize_run

    small = summarize_run(ds)
    summary = {
        "preset": cfg.name,
        "file": str(out),
        "complete": bool(ds.attrs["complete"]),
        "steps": int(ds.attrs["steps"]),
        "dt_s": float(ds.attrs["dt"]),
        "n_particles": int(ds.attrs["n_particles"]),
        "inertial_number": float(ds.attrs["inertial_number"]),
        "quasi_static": bool(ds.attrs["quasi_static"]),
        **_key_figures(small),
        "wall_time_s": wall,
    }
    if as_json:
        emit_json(summary)
    else:
        click.echo(json.dumps(summary, indent=2))


def _key_figures(small) -> dict[str, object]:
    """Headline numbers of a run summary (bin-mean V in kN/m prototype, heave / D)."""
    a = small.attrs
    out: dict[str, object] = {
        "V_prototype_kN_per_m (bin mean)": {
            f"{r:g}D": (
                None
                if not np.isfinite(a.get(f"V_prototype_at_{r:g}D", np.nan))
                else round(float(a[f"V_prototype_at_{r:g}D"]) / 1e3, 2)
            )
            for r in (0.05, 0.1, 0.2, 0.3, 0.4, 0.5)
        },
        "w_over_D_reached": round(float(a["w_over_D_reached"]), 4),
        "heave_peak_over_D": round(float(a["heave_peak_over_D"]), 4),
        "heave_extent_over_D": round(float(a["heave_extent_over_D"]), 3),
        "softening": a["softening"] or "none",
    }
    return out


def _f114_unit_weight(ds, gamma_kn: float | None) -> float | None:
    """γ_d [N/m³] for the F114 bounds: the option, else the preset's estimate, else None."""
    if gamma_kn is not None:
        return gamma_kn * 1e3
    from onbottom.plotting.dem_f114 import DEFAULT_DRY_UNIT_WEIGHT

    preset = str(ds.attrs.get("preset", "")).upper()
    for key, value in DEFAULT_DRY_UNIT_WEIGHT.items():
        if preset.startswith(key):
            return value
    return None


@command.command("plot")
@results_argument
@outdir_option
@click.option(
    "--chain-threshold",
    type=float,
    default=200.0,
    show_default=True,
    help="Force-chain threshold [N].",
)
@click.option(
    "--rotation-threshold",
    type=float,
    default=20.0,
    show_default=True,
    help="Rotation highlight [deg].",
)
@click.option(
    "--gamma-kn",
    type=float,
    default=None,
    help="Prototype dry unit weight of the sand for the F114 bounds [kN/m³]; default by "
    "preset (SM 15.9, SD 16.7: estimates, see onbottom.plotting.dem_f114).",
)
@click.option(
    "--phi-lower-deg",
    type=float,
    default=33.0,
    show_default=True,
    help="φ' of the F114 lower bound [deg] (φ_c of the test sand).",
)
@click.option(
    "--phi-upper-deg",
    type=float,
    default=40.0,
    show_default=True,
    help="φ' of the F114 upper bound [deg] (peak angle implied by the paper).",
)
@json_option
@handle_errors
def plot_cmd(
    results: tuple[Path, ...],
    outdir: Path,
    chain_threshold: float,
    rotation_threshold: float,
    gamma_kn: float | None,
    phi_lower_deg: float,
    phi_upper_deg: float,
    as_json: bool,
) -> None:
    """Plot V–w, initial profiles, heave, velocity, rotation and force-chain fields.

    RESULTS are run files or summaries (``dem summarize``; V–w, heave and initial profiles
    only). The full-size SM and SD presets carry the paper's centrifuge points as markers.
    """
    import matplotlib.pyplot as plt
    import xarray as xr

    from onbottom.plotting import dem as P
    from onbottom.results import load_dataset

    outdir.mkdir(parents=True, exist_ok=True)
    runs = [load_dataset(p) for p in results]
    written: list[str] = []

    def save(fig, name):
        path = outdir / name
        fig.savefig(path, dpi=150, bbox_inches="tight")
        plt.close(fig)
        written.append(str(path))

    from onbottom.dem.published import PUBLISHED

    paper = {name: case.resistance for name, case in PUBLISHED.items()}
    save(P.plot_resistance(runs, prototype=True, reference=paper), "dem_V_w_prototype.png")
    save(P.plot_resistance(runs, prototype=False), "dem_V_w_model.png")
    gamma = _f114_unit_weight(runs[0], gamma_kn)
    if gamma is not None:
        from onbottom.plotting.dem_f114 import plot_dem_against_f114

        fig = plot_dem_against_f114(
            runs,
            unit_weight=gamma,
            phi_lower_deg=phi_lower_deg,
            phi_upper_deg=phi_upper_deg,
            reference=paper,
        )
        save(fig, "dem_V_w_f114.png")
    save(P.plot_surface(runs), "dem_heave.png")
    inis = []
    for ds in runs:
        if "initial_porosity" in ds:
            ini = xr.Dataset(
                {
                    k[8:]: ds[k].rename({"circle_depth": "depth"})
                    for k in ds.data_vars
                    if str(k).startswith("initial_")
                }
            )
            ini.attrs["preset"] = ds.attrs.get("preset", "")
            inis.append(ini)
    if inis:
        save(
            P.plot_initial_state(inis, float(runs[0].attrs["pipe_diameter"])),
            "dem_initial_state.png",
        )
    for ds in runs:
        name = str(ds.attrs.get("preset", "run"))
        if "snapshot" not in ds.coords:
            continue
        for r in ds["snapshot"].values:
            tag = f"{name}_{r:.1f}D"
            save(P.plot_rotation_field(ds, r, rotation_threshold), f"dem_rotation_{tag}.png")
            save(P.plot_force_chains(ds, r, chain_threshold), f"dem_chains_{tag}.png")
        save(
            P.plot_velocity_field(ds, float(ds["snapshot"].values[-1])), f"dem_velocity_{name}.png"
        )
    if as_json:
        emit_json({"figures": written})
    else:
        for w in written:
            click.echo(w)


@command.command("summarize")
@results_argument
@outdir_option
@click.option(
    "--step",
    type=float,
    default=0.005,
    show_default=True,
    help="Bin width of the V–w curve in w/D [-].",
)
@click.option(
    "--drop-fraction",
    type=float,
    default=0.05,
    show_default=True,
    help="Smallest drop below the running peak counted as softening [-].",
)
@json_option
@handle_errors
def summarize_cmd(
    results: tuple[Path, ...], outdir: Path, step: float, drop_fraction: float, as_json: bool
) -> None:
    """Write small summaries of penetration runs: binned V–w, surfaces, heave, softening.

    For each RESULT: OUTDIR/<preset>_summary.nc (NetCDF, all of it), <preset>_V_w.csv
    (w/D, prototype V mean/min/max in kN/m) and <preset>_surface.csv (x/D, surfaces and
    smoothed heave in mm, model scale) — kilobytes, fit to commit, where a run file holds
    every disk.
    """
    from onbottom.dem.summary import summarize_run
    from onbottom.results import load_dataset, save_dataset

    outdir.mkdir(parents=True, exist_ok=True)
    report = []
    for path in results:
        ds = load_dataset(path)
        small = summarize_run(ds, step=step, drop_fraction=drop_fraction)
        name = str(ds.attrs.get("preset", path.stem))
        save_dataset(small, outdir / f"{name}_summary.nc")
        curve = small[["V_prototype_mean", "V_prototype_min", "V_prototype_max"]] / 1e3
        curve.to_dataframe().rename(columns=lambda c: c + "_kN_per_m").to_csv(
            outdir / f"{name}_V_w.csv", float_format="%.4f"
        )
        surf = small[["surface0", "surface", "heave"]] * 1e3
        surf.to_dataframe().rename(columns=lambda c: c + "_mm").to_csv(
            outdir / f"{name}_surface.csv", float_format="%.4f"
        )
        report.append(
            {
                "preset": name,
                "file": str(path),
                "complete": bool(ds.attrs.get("complete", 0)),
                **_key_figures(small),
            }
        )
    if as_json:
        emit_json(report)
    else:
        click.echo(json.dumps(report, indent=2))
