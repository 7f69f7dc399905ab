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

from onbottom.cli._common import EXIT_INVALID_RESULT, Number, emit_json, handle_errors, json_option
from onbottom.dem.config import PRESETS, DEMConfig, get_preset
from onbottom.errors import InputError

__all__ = ["command"]

# OpenMP worker threads that spin at barriers lose badly when other processes share the cores
# (measured: 2 threads slower than 1); wait passively unless the user chose otherwise. Must be
# set before the first parallel kernel starts the OpenMP runtime.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _config(preset: str, seed: int | None, config_file: Path | None) -> DEMConfig:
    if config_file is not None:
        from onbottom.cases.dem import load_dem_config

        cfg = load_dem_config(config_file)
    else:
        cfg = get_preset(preset)
    if seed is not None:
        cfg = cfg.replace(seed=seed)
    return cfg


def _check_out(path: Path, field: str) -> None:
    from onbottom.cli._common import check_output_path

    check_output_path(path, field=field)


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
seed_option = click.option(
    "--seed", type=Number(int, min=0), default=None, help="Override the preset seed."
)
config_option = click.option(
    "--config",
    "config_file",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
    default=None,
    help="DEMConfig as JSON (DEMConfig.to_json); overrides --preset.",
)
threads_option = click.option(
    "--threads", type=Number(int, min=1), default=None, help="Numba threads (default: automatic)."
)
restart_option = click.option(
    "--restart",
    is_flag=True,
    help="Start afresh: discard an existing checkpoint of this output and replace an output "
    "of another run (a checkpoint or output of another run, or a corrupt checkpoint, is "
    "otherwise an error).",
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


def _prepare(cfg: DEMConfig, out: Path, progress: bool, restart: bool = False):
    """Prepare and save the specimen (resumable per compacted layer: ``prepare_to_file``)."""
    from onbottom.dem.preparation import prepare_to_file

    _check_out(out, "--out")
    bar = _Bar(progress, f"prepare {cfg.name}")
    t0 = time.perf_counter()
    try:
        sample = prepare_to_file(cfg, out, progress=bar, restart=restart, field="--out")
    finally:
        bar.close()
    return sample, time.perf_counter() - t0


@command.command("prepare")
@preset_option
@seed_option
@config_option
@click.option("--out", type=click.Path(dir_okay=False, path_type=Path), required=True)
@restart_option
@progress_option
@json_option
@handle_errors
def prepare_cmd(
    preset: str,
    seed: int | None,
    config_file: Path | None,
    out: Path,
    restart: bool,
    progress: bool,
    as_json: bool,
) -> None:
    """Prepare a specimen (multi-layer under-compaction, 1 g then N g equilibrium).

    Resumable: rerunning the same command after an interruption continues from the last
    compacted layer or the last checkpoint of the 1 g / N g equilibria
    (OUT.prep-checkpoint.nc, every 100,000 steps).
    """
    cfg = _config(preset, seed, config_file)
    sample, wall = _prepare(cfg, out, progress and not as_json, restart)
    summary = {
        "preset": cfg.name,
        "file": str(out),
        "n_particles": sample.n,
        "target_void_ratio": cfg.target.void_ratio,
        "void_ratio": sample.attrs.get("void_ratio_Ng"),
        "equilibrium_Ng_converged": sample.attrs.get("equilibrium_Ng_converged"),
        "run_fingerprint": sample.attrs.get("run_fingerprint"),
        "wall_time_s": wall,
    }
    # a specimen whose final (N g) equilibrium stopped at its time cap is written (it can be
    # inspected) but is not a valid result: exit 3, never 0. The 1 g stage is intermediate:
    # its state is recorded in the file's attributes.
    settled = sample.attrs.get("equilibrium_Ng_converged")
    unsettled = settled is not None and not bool(settled)
    summary["success"] = not unsettled
    summary["message"] = (
        "the N g equilibrium did not reach the unbalanced-force criterion within"
        " preparation.max_settle_time: the specimen is not at rest"
        if unsettled
        else "specimen at N g equilibrium"
    )
    if as_json:
        emit_json(summary)
    else:
        for k, v in summary.items():
            click.echo(f"{k:>26}: {v}")
    if unsettled:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)


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
    type=Number(int, min=1),
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
@click.option(
    "--max-steps",
    type=Number(int, min=1),
    default=None,
    help="Stop after this many steps (resumable).",
)
@click.option(
    "--event-snapshots/--no-event-snapshots",
    default=True,
    show_default=True,
    help="Also store field snapshots at the peak and trough of each softening episode.",
)
@click.option(
    "--event-drop-fraction",
    type=Number(float, min=0.0, max=1.0, min_open=True, max_open=True),
    default=0.05,
    show_default=True,
    help="Drop of the bin-mean V below its running peak that makes an episode [-] (as "
    "'dem summarize --drop-fraction').",
)
@click.option(
    "--max-event-snapshots",
    type=Number(int, min=2, max=10_000),
    default=64,
    show_default=True,
    help="Cap on the event snapshots (about 2.5 MB each at full size).",
)
@restart_option
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
    event_snapshots: bool,
    event_drop_fraction: float,
    max_event_snapshots: int,
    restart: bool,
    threads: int | None,
    progress: bool,
    as_json: bool,
) -> None:
    """Push the pipe to the final embedment; write the V–w record and field snapshots.

    Field snapshots (positions, velocities, rotations, force chains) are stored at w/D = 0.1,
    0.2, … 0.5 and, unless --no-event-snapshots, at the peak and at the trough of each
    softening episode found while the pipe goes down (the episode rule of 'dem summarize').

    Resumable: rerunning the same command continues from the checkpoint, if it belongs to the
    same run (configuration, seed, velocity, specimen, engine); otherwise the command stops
    and names the differing fields (--restart discards the checkpoint).
    """
    from onbottom.cases.dem import load_sample
    from onbottom.dem.experiment import penetrate, with_initial_state
    from onbottom.dem.identity import check_sample_config, dem_identity, guard_output
    from onbottom.results import clean_stale_temporaries, save_dataset

    cfg = _config(preset, seed, config_file)
    show = progress and not as_json
    _check_out(out, "--out")
    if sample_path.exists():
        sample = load_sample(sample_path)
        check_sample_config(sample, cfg, sample_path)
    else:
        sample, _ = _prepare(cfg, sample_path, show)
    ck = checkpoint if checkpoint is not None else out.with_suffix(".checkpoint.nc")
    if not ck.exists():  # else the checkpoint's own identity check decides (in penetrate)
        guard_output(
            out,
            dem_identity(cfg, "penetration", sample=sample).fields,
            restart=restart,
            field="--out",
        )
    if ck.resolve() in (out.resolve(), sample_path.resolve()):
        raise InputError(
            f"--checkpoint = {str(ck)!r} is invalid: it must differ from --out and --sample"
        )
    clean_stale_temporaries(out)
    clean_stale_temporaries(ck)
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
            restart=restart,
            event_snapshots=event_snapshots,
            event_drop_fraction=event_drop_fraction,
            max_event_snapshots=max_event_snapshots,
        )
    finally:
        bar.close()
    wall = time.perf_counter() - t0
    ds = with_initial_state(ds, cfg, sample)
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
        "run_fingerprint": ds.attrs.get("run_fingerprint"),
        **_key_figures(small),
        "event_snapshots": int(
            np.count_nonzero(ds["snapshot_kind"].values != "fixed") if "snapshot_kind" in ds else 0
        ),
        "event_snapshots_capped": bool(ds.attrs.get("event_snapshots_capped", 0)),
        "wall_time_s": wall,
    }
    if as_json:
        emit_json(summary)
    else:
        click.echo(json.dumps(summary, indent=2))


def _summary_names(results: tuple[Path, ...], runs: list, outdir: Path) -> list[str]:
    """File stems of the summaries: the preset name, unless that would overwrite the summary
    of another run (two runs of one preset in this call, or an existing summary written from
    another file); then ``<preset>_<run file stem>``."""
    import xarray as xr

    base = [
        str(ds.attrs.get("preset", "")) or Path(p).stem for p, ds in zip(results, runs, strict=True)
    ]
    names = []
    for p, name in zip(results, base, strict=True):
        clash = base.count(name) > 1
        existing = outdir / f"{name}_summary.nc"
        if not clash and existing.exists():
            try:
                with xr.open_dataset(existing, engine="h5netcdf") as old:
                    src = old.attrs.get("source_file")
            except Exception:  # unreadable old summary: do not overwrite it silently either
                src = None
            clash = src != str(Path(p).resolve())
        names.append(f"{name}_{Path(p).stem}" if clash else name)
    if len(set(names)) != len(names):
        raise InputError(
            "results are invalid: two run files would write the same summary names"
            f" ({', '.join(names)}); give each run file a different name"
        )
    return names


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
    if int(a.get("band_episodes", 0)):
        out["bands_reaching_surface"] = (
            f"{int(a['band_episodes_reaching_surface'])} of {int(a['band_episodes'])} episodes"
        )
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
    type=Number(float, min=0.0),
    default=200.0,
    show_default=True,
    help="Force-chain threshold [N].",
)
@click.option(
    "--rotation-threshold",
    type=Number(float, min=0.0, max=360.0),
    default=20.0,
    show_default=True,
    help="Rotation highlight [deg].",
)
@click.option(
    "--band-threshold-deg",
    "band_threshold",
    type=Number(float, min=0.0, max=180.0, min_open=True, unit="deg"),
    default=10.0,
    show_default=True,
    help="Rotation peak→trough marking a shear band in the band figures [deg].",
)
@click.option(
    "--gamma-kn",
    type=Number(float, min=1.0, max=25.0, unit="kN/m³"),
    default=None,
    help="Prototype dry unit weight of the sand for the F114 bounds [kN/m³]; default by "
    "preset (SM 15.9, SD 16.7: estimates, see onbottom.plotting.dem_f114).",
)
@click.option(
    "--phi-lower-deg",
    type=Number(float, min=15.0, max=50.0, unit="deg"),
    default=33.0,
    show_default=True,
    help="φ' of the F114 lower bound [deg] (φ_c of the test sand).",
)
@click.option(
    "--phi-upper-deg",
    type=Number(float, min=15.0, max=50.0, unit="deg"),
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
    band_threshold: float,
    gamma_kn: float | None,
    phi_lower_deg: float,
    phi_upper_deg: float,
    as_json: bool,
) -> None:
    """Plot V–w, initial profiles, heave, velocity, rotation and force-chain fields.

    Runs with event snapshots also get one figure per softening episode: the incremental
    rotation of every disk from the episode's peak to its trough, the band that joins the
    pipe to the surface (if any) outlined.

    RESULTS are run files or summaries (``dem summarize``; V–w, heave and initial profiles
    only). The full-size SM and SD presets carry the paper's centrifuge points as markers.
    Per-run figures are named after the preset, or ``<preset>_<file stem>`` when two runs of
    one preset are plotted together.
    """
    import matplotlib.pyplot as plt

    from onbottom.cases.dem import load_run
    from onbottom.dem.experiment import initial_state_of
    from onbottom.plotting import dem as P

    if phi_lower_deg > phi_upper_deg:
        raise InputError(
            f"--phi-lower-deg = {phi_lower_deg:g} is invalid: must not exceed --phi-upper-deg"
            f" = {phi_upper_deg:g}"
        )
    runs = [load_run(p) for p in results]
    outdir.mkdir(parents=True, exist_ok=True)
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
    inis = [ini for ini in map(initial_state_of, runs) if ini is not None]
    if inis:
        save(
            P.plot_initial_state(inis, float(runs[0].attrs["pipe_diameter"])),
            "dem_initial_state.png",
        )
    base = [str(ds.attrs.get("preset", "")) or "run" for ds in runs]
    for path, ds, name in zip(results, runs, base, strict=True):
        if base.count(name) > 1:  # two runs of one preset (seeds): one set of figures each
            name = f"{name}_{Path(path).stem}"
        if "snapshot" not in ds.coords:
            continue
        kinds = (
            ds["snapshot_kind"].values.astype(str)
            if "snapshot_kind" in ds
            else np.full(ds.sizes["snapshot"], "fixed")
        )
        fixed = ds["snapshot"].values[kinds == "fixed"]
        for r in fixed:
            tag = f"{name}_{r:.1f}D"
            save(P.plot_rotation_field(ds, r, rotation_threshold), f"dem_rotation_{tag}.png")
            save(P.plot_force_chains(ds, r, chain_threshold), f"dem_chains_{tag}.png")
        if fixed.size:
            save(P.plot_velocity_field(ds, float(fixed[-1])), f"dem_velocity_{name}.png")
        from onbottom.dem.summary import band_episodes

        for band in band_episodes(ds, threshold_deg=band_threshold):
            save(
                P.plot_rotation_increment(ds, band, band_threshold),
                f"dem_band_{name}_episode{band['episode']}.png",
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
    type=Number(float, min=0.0, max=0.5, min_open=True),
    default=0.005,
    show_default=True,
    help="Bin width of the V–w curve in w/D [-].",
)
@click.option(
    "--drop-fraction",
    type=Number(float, min=0.0, max=1.0, min_open=True, max_open=True),
    default=0.05,
    show_default=True,
    help="Smallest drop below the running peak counted as softening [-].",
)
@click.option(
    "--band-threshold-deg",
    type=Number(float, min=0.0, max=180.0, min_open=True, unit="deg"),
    default=10.0,
    show_default=True,
    help="Rotation peak→trough above which a disk belongs to a shear band [deg].",
)
@json_option
@handle_errors
def summarize_cmd(
    results: tuple[Path, ...],
    outdir: Path,
    step: float,
    drop_fraction: float,
    band_threshold_deg: float,
    as_json: bool,
) -> None:
    """Write small summaries of penetration runs: binned V–w, surfaces, heave, softening.

    For each RESULT: OUTDIR/<preset>_summary.nc (NetCDF, all of it), <preset>_V_w.csv
    (w/D, prototype V mean/min/max in kN/m) and <preset>_surface.csv (x/D, surfaces and
    smoothed heave in mm, model scale) — kilobytes, fit to commit, where a run file holds
    every disk. A run with event snapshots also gets <preset>_bands.csv: per softening
    episode the w/D of its peak and trough snapshots, the drop, whether a band of disks
    rotated by more than --band-threshold-deg joins the pipe to the surface, and where.
    """
    from onbottom.cases.dem import load_run
    from onbottom.dem.summary import summarize_run
    from onbottom.results import save_dataset, write_text_atomic

    runs = [load_run(p) for p in results]
    for path, ds in zip(results, runs, strict=True):
        if "V_prototype" not in ds:
            raise InputError(f"results = {str(path)!r} is invalid: already a summary")
    names = _summary_names(results, runs, outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    report = []
    for path, ds, name in zip(results, runs, names, strict=True):
        small = summarize_run(
            ds, step=step, drop_fraction=drop_fraction, band_threshold_deg=band_threshold_deg
        )
        small.attrs["source_file"] = str(Path(path).resolve())
        save_dataset(small, outdir / f"{name}_summary.nc")
        curve = small[["V_prototype_mean", "V_prototype_min", "V_prototype_max"]] / 1e3
        write_text_atomic(
            outdir / f"{name}_V_w.csv",
            curve.to_dataframe()
            .rename(columns=lambda c: c + "_kN_per_m")
            .to_csv(float_format="%.4f"),
        )
        surf = small[["surface0", "surface", "heave"]] * 1e3
        write_text_atomic(
            outdir / f"{name}_surface.csv",
            surf.to_dataframe().rename(columns=lambda c: c + "_mm").to_csv(float_format="%.4f"),
        )
        bands = [k for k in small.data_vars if str(k).startswith("band_")]
        if small.sizes.get("band_episode", 0):
            write_text_atomic(
                outdir / f"{name}_bands.csv",
                small[bands]
                .to_dataframe()
                .rename(columns=lambda c: c[5:])
                .to_csv(float_format="%.4f"),
            )
        report.append(
            {
                "preset": str(ds.attrs.get("preset", "")),
                "summary": str(outdir / f"{name}_summary.nc"),
                "file": str(path),
                "complete": bool(ds.attrs.get("complete", 0)),
                **_key_figures(small),
            }
        )
    if as_json:
        emit_json(report)
    else:
        click.echo(json.dumps(report, indent=2))
