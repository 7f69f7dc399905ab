"""``onbottom reproduce``: the seven centrifuge tests of Youssef & Cassidy (2014)."""

from __future__ import annotations

import time
from dataclasses import asdict
from pathlib import Path

import click

from onbottom.cli._common import Number, emit_json, handle_errors, json_option


@click.command("reproduce")
@click.option(
    "--out",
    "out",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("onbottom-results"),
    show_default=True,
    help="Output folder (tables, NetCDF files, plots).",
)
@click.option(
    "--gamma-kn",
    type=Number(float, min=1.0, max=25.0, unit="kN/m³"),
    default=None,
    help="Submerged unit weight of the sand [kN/m³] (default 7.5, see the docs).",
)
@click.option("--no-plots", is_flag=True, help="Do not write figures.")
@click.option("--no-netcdf", is_flag=True, help="Do not write NetCDF files.")
@click.option("--no-sensitivity", is_flag=True, help="Skip the γ' sensitivity table.")
@click.option("--quiet", is_flag=True, help="No progress bar.")
@click.option(
    "--bands",
    is_flag=True,
    help="Instead of the reproduction, compute the sensitivity bands over every unstated"
    " choice (cycle shape, time basis, γ', B placement, Eq 8 reading, work integrand, α of"
    " tests 4-5) on Dask; writes centrifuge_bands.csv/.md under --out.",
)
@click.option("--scheduler", default=None, help="Address of a running Dask scheduler (--bands).")
@click.option(
    "--band-test",
    "band_tests",
    multiple=True,
    help="With --bands: only this test (repeatable; default all seven).",
)
@click.option(
    "--workers",
    type=click.IntRange(min=0),
    default=None,
    help="Local Dask worker processes for --bands (default one per core; 0 = serial).",
)
@json_option
@handle_errors
def command(
    out: Path,
    gamma_kn: float | None,
    no_plots: bool,
    no_netcdf: bool,
    no_sensitivity: bool,
    quiet: bool,
    bands: bool,
    scheduler: str | None,
    band_tests: tuple[str, ...],
    workers: int | None,
    as_json: bool,
) -> None:
    """Reproduce the seven Youssef (2012) centrifuge tests (Youssef & Cassidy 2014).

    Runs every test with the calibrated Table 2 parameters and with the Table 3 recommended
    values, and writes table.md / table.csv (cycles to the displacement limit against
    Table 1, penetrations, final displacement), gamma_sensitivity.md/.csv, netcdf/*.nc and
    plots/*.png under --out. With --bands: the sensitivity bands of the cycle counts
    (docs/validation/bands/centrifuge_bands.md is the committed copy).
    """
    if bands:
        _bands(out, scheduler, workers, band_tests or None, quiet, as_json)
        return
    from onbottom.study.youssef_cassidy import reproduce

    figure = None
    if not no_plots:
        from onbottom.plotting.section import reproduction_figure as figure
    t0 = time.perf_counter()
    res = reproduce(
        out,
        figure=figure,
        netcdf=not no_netcdf,
        sensitivity=not no_sensitivity,
        gamma=None if gamma_kn is None else gamma_kn * 1e3,
        progress=not quiet and not as_json,
    )
    wall = time.perf_counter() - t0
    if as_json:
        emit_json(
            {
                "rows": [asdict(r) for r in res["rows"]],
                "files": [str(p) for p in res["files"]],
                "wall_time_s": wall,
            }
        )
        return
    click.echo((out / "table.md").read_text(encoding="utf-8"))
    click.echo(
        "Regular and Irregular fall outside the paper's cycle counts: why, and the sensitivity"
        " to every unstated choice, in docs/validation/youssef_cassidy_2014.md (and"
        " `onbottom reproduce --bands`)."
    )
    click.echo(f"{len(res['files'])} files written under {out} in {wall:.1f} s")


def _bands(
    out: Path,
    scheduler: str | None,
    workers: int | None,
    tests: tuple[str, ...] | None,
    quiet: bool,
    as_json: bool,
) -> None:
    from onbottom.study.centrifuge_bands import bands

    t0 = time.perf_counter()
    res = bands(
        out,
        tests=tests,
        scheduler_address=scheduler,
        n_workers=workers,
        progress=not quiet and not as_json,
    )
    wall = time.perf_counter() - t0
    if as_json:
        emit_json(
            {
                "bands": [asdict(s) for s in res["summaries"]],
                "n_runs": len(res["rows"]),
                "files": [str(p) for p in res["files"]],
                "wall_time_s": wall,
            }
        )
        return
    click.echo((out / "centrifuge_bands.md").read_text(encoding="utf-8"))
    click.echo(f"{len(res['rows'])} runs, {len(res['files'])} files under {out} in {wall:.1f} s")
