"""``onbottom simulate``: one pipe-section simulation from a TOML case file."""

from __future__ import annotations

import warnings
from pathlib import Path

import click

from onbottom.cli._common import (
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
)
from onbottom.errors import OutOfRangeWarning


@click.command("simulate")
@click.argument("case", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="NetCDF file for the time series (default: CASE with suffix .nc).",
)
@click.option(
    "--plot",
    "plot",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write the w–u / H–u / V–H figure to this file (png, pdf, svg).",
)
@click.option("--quiet", is_flag=True, help="No progress bar.")
@json_option
@handle_errors
def command(case: Path, output: Path | None, plot: Path | None, quiet: bool, as_json: bool) -> None:
    """Simulate a pipe section under a load programme (CASE: TOML file).

    CASE holds either a [preset] table (one of the seven centrifuge tests) or [pipe], [soil],
    [programme] and optional [solver] tables; see examples/section_case.toml. Loads in the
    file are in kN/m.
    """
    from onbottom.cases.section import load_section_run

    nc = output if output is not None else case.with_suffix(".nc")
    check_output_path(nc, field="--output")
    if plot is not None:
        check_output_path(plot, field="--plot")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        run = load_section_run(case)  # the whole file is checked before any work
        res = run.simulate(progress=not quiet and not as_json)
    messages = list(dict.fromkeys(str(w.message) for w in caught))
    res.save(nc)
    if plot is not None:
        import matplotlib.pyplot as plt

        from onbottom.plotting.section import plot_section_result

        cp = res.data.attrs.get("cycle_period")
        lim = res.data.attrs.get("displacement_limit")
        fig = plot_section_result(
            res,
            title=f"{case.stem}: {res.message}",
            installation_load=float(res.data.attrs["installation_load"]),
            cycle_period=cp if isinstance(cp, float) else None,
            displacement_limit=lim if isinstance(lim, float) else None,
        )
        from onbottom.results import save_figure

        save_figure(fig, plot, dpi=110)
        plt.close(fig)
    payload = {
        "success": res.success,
        "status": res.status,
        "message": res.message,
        "n_steps": res.n_steps,
        "cycles_to_limit": res.cycles_to_limit,
        "time_to_limit_s": res.time_to_limit,
        **{f"{k}": v for k, v in res.summary.items()},
        "netcdf": str(nc),
        "plot": None if plot is None else str(plot),
        "warnings": messages,
    }
    if as_json:
        emit_json(payload)
        if res.exit_code:
            raise click.exceptions.Exit(res.exit_code)
        return
    for msg in messages:
        click.echo(f"warning: {msg}", err=True)
    click.echo(f"{res.message} after {res.n_steps} steps")
    if res.cycles_to_limit is not None:
        click.echo(f"  load cycles to the displacement limit: {res.cycles_to_limit:.2f}")
    s = res.summary
    click.echo(f"  initial penetration  {s['initial_penetration']:.4f} m")
    click.echo(f"  largest penetration  {s['max_penetration']:.4f} m")
    click.echo(f"  final displacement   {s['final_displacement']:.3f} m")
    click.echo(f"  written: {nc}" + (f", {plot}" if plot else ""))
    if res.exit_code:
        raise click.exceptions.Exit(res.exit_code)
