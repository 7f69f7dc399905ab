"""``onbottom curves``: F109-style generalized-stability curves from dynamic storm analyses.

Reads the ``[curves]`` table (grid and settings) and the optional ``[hydro]`` and
``[environment]`` tables of a case file (the format, an example and every key:
:mod:`onbottom.cases.curves`), bisects L_stable and L_10 on the grid
(:func:`onbottom.study.stability_curves.stability_curves`) on Dask, and writes a NetCDF file,
a CSV table and a figure of L/(2 + M)² against K.
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path

import click

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    check_output_names,
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
    log_to_stderr,
)
from onbottom.errors import OutOfRangeWarning


@click.command("curves")
@click.argument("case", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="NetCDF file (default CASE with suffix .nc); the CSV and PNG go beside it.",
)
@click.option("--scheduler", default=None, metavar="ADDRESS", help="Dask scheduler address.")
@click.option(
    "--workers",
    type=Number(int, min=0, max=1024),
    default=None,
    help="Local Dask worker processes (default one per core; 0 = in this process).",
)
@click.option("--quiet", is_flag=True, help="No progress bar.")
@click.option(
    "--force",
    is_flag=True,
    help="Run even when the estimated time or memory exceeds the budget"
    " (onbottom.study.budget: 12 h, 8 GB).",
)
@click.option(
    "--restart",
    is_flag=True,
    help="Discard the points an interrupted run kept (OUTPUT.tasks/) and start afresh.",
)
@json_option
@handle_errors
def command(
    case: Path,
    output: Path | None,
    scheduler: str | None,
    workers: int | None,
    quiet: bool,
    force: bool,
    restart: bool,
    as_json: bool,
) -> None:
    """Stability curves L_stable, L_10 from dynamic storms (CASE: TOML with [curves]).

    For each soil, N, M and K, bisects for each seed the weight parameter L = w_s/(½ρDU_s²)
    at which its storm's maximum displacement reaches 0.5D and 10D, and reports the 0.9
    fractile (the design value) and the median over the seeds (statistic = "fractile", 10
    seeds by default; "mean_of_maxima" is the former seed-averaged maximum); writes NetCDF,
    CSV and a figure of L/(2 + M)² against K (the form of DNV-RP-F109's tables).

    Each finished point is kept at once in OUTPUT.tasks/ (one small file per point), so an
    interrupted run (Ctrl-C, a kill) resumes without repeating it; --restart starts afresh.
    Results are written under a temporary name and renamed when complete.
    """
    with log_to_stderr(not as_json):
        _command(case, output, scheduler, workers, quiet, force, restart, as_json)


def _command(
    case: Path,
    output: Path | None,
    scheduler: str | None,
    workers: int | None,
    quiet: bool,
    force: bool,
    restart: bool,
    as_json: bool,
) -> None:
    """Settings (case, output names, budget), the curves, their files, the report."""
    from onbottom.cases.curves import build_curve_settings, check_budget, load_curves_case
    from onbottom.results import TaskStore, save_dataset
    from onbottom.study.stability_curves import curves_table, stability_curves

    # settings
    nc = output if output is not None else case.with_suffix(".nc")
    check_output_names(case, [("--output", nc, (".nc",))])
    check_output_names(  # the CSV and the figure go beside the NetCDF
        case,
        [("--output", nc.with_suffix(".csv"), ()), ("--output", nc.with_suffix(".png"), ())],
    )
    cfg = load_curves_case(case)
    c = cfg.curves
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        settings = build_curve_settings(cfg, case)
    notes_in = sorted({str(w.message) for w in caught if issubclass(w.category, OutOfRangeWarning)})
    seed_note = (
        f"curves.seeds = {c.seeds}: the {c.fractile:g} fractile of fewer than 10 seeds rests"
        " on the heaviest seeds (use seeds >= 10 for a design curve)"
        if c.statistic == "fractile" and c.seeds < 10
        else None
    )
    if not as_json:
        for note in notes_in:
            click.echo(f"warning: {note}", err=True)
    check_output_path(nc, field="--output")
    check_budget(c, workers=workers, force=force)
    # the curves (resumable: one task file per point)
    store = nc.with_name(nc.name + ".tasks")
    t0 = time.perf_counter()
    ds = stability_curves(
        c.K,
        c.M,
        c.N,
        soils=c.soils,
        criteria=c.criteria,
        settings=settings,
        n_workers=workers,
        scheduler=scheduler,
        progress=not quiet and not as_json,
        store=store,
        restart=restart,
    )
    # the files, then the report
    save_dataset(ds, nc)
    rows, csv_path, png, stat = _write_table_and_figure(ds, nc, case, c)
    TaskStore.delete(store)  # the NetCDF, CSV and figure hold every point now
    failures = ds.attrs.get("failures", "[]")
    import json

    failures = json.loads(failures) if isinstance(failures, str) else failures
    notes = ds.attrs.get("no_crossing", "[]")
    notes = json.loads(notes) if isinstance(notes, str) else notes
    payload = {
        "points": curves_table(ds, per_seed=True),
        "statistic": stat["statistic"],
        "statistic_description": stat["label"],
        "seeds": int(c.seeds),
        "fractile": c.fractile if c.statistic == "fractile" else None,
        "stopped_early": int(ds.attrs.get("stopped_early", 0)),
        "total_storms": int(ds.attrs["total_storms"]),
        "wall_time_s": time.perf_counter() - t0,
        "workers": int(ds.attrs["workers"]),
        "failures": failures,
        "no_crossing": notes,
        "netcdf": str(nc),
        "csv": str(csv_path),
        "figure": str(png),
        "warnings": notes_in + ([seed_note] if seed_note else []),
    }
    if as_json:
        emit_json(payload)
    else:
        _echo(payload, rows, notes, stat, seed_note, (nc, csv_path, png))
    if failures:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)


def _write_table_and_figure(ds, nc: Path, case: Path, c) -> tuple[list[dict], Path, Path, dict]:
    """The CSV table and the figure beside the NetCDF: the table's rows, the two paths and the
    curves' statistic."""
    import matplotlib.pyplot as plt

    from onbottom.plotting.storm import plot_stability_curves
    from onbottom.results import save_figure, write_csv_atomic
    from onbottom.study.stability_curves import curve_statistic, curves_table

    rows = curves_table(ds)
    csv_path = nc.with_suffix(".csv")
    write_csv_atomic(csv_path, rows, list(rows[0]))
    stat = curve_statistic(ds)
    fig = plot_stability_curves(
        ds,
        title=f"{case.stem}: {c.build_up_hours:g} h + {c.peak_hours:g} h storms; L ="
        f" {stat['label']}",
    )
    png = nc.with_suffix(".png")
    save_figure(fig, png, dpi=110)
    plt.close(fig)
    return rows, csv_path, png, stat


def _echo(payload: dict, rows: list[dict], notes: list, stat: dict, seed_note, files) -> None:
    """The text report: one line per point, the points without L and those out of range."""
    from onbottom.study.stability_curves import point_summary

    for r in payload["points"]:
        click.echo(f"{r['soil']:>4} N={r['N']:g} M={r['M']:g} K={r['K']:g}: {point_summary(r)}")
    for note in notes:
        click.echo(
            f"  no L for {note['criterion']} at {note['soil']} K={note['K']:g}"
            f" M={note['M']:g}: {note['message']}"
        )
    flagged = [
        f"{r['soil']} K={r['K']:g} M={r['M']:g} N={r['N']:g}"
        for r in rows
        if any(v for k, v in r.items() if k.endswith("_out_of_range"))
    ]
    if flagged:
        click.echo(
            f"  outside the soil model's range (storms buried the pipe beyond D/2; marked"
            f" out_of_range): {', '.join(flagged)}"
        )
    click.echo(f"L = {stat['label']}")
    if seed_note:
        click.echo(f"note: {seed_note}")
    nc, csv_path, png = files
    click.echo(
        f"{payload['total_storms']} storms ({payload['stopped_early']} stopped once their"
        f" verdict was known) in {payload['wall_time_s']:.1f} s on"
        f" {payload['workers']} worker(s); written: {nc}, {csv_path}, {png}"
    )
