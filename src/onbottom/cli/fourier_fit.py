"""``onbottom fourier-fit``: fit a Fourier force coefficient table from regular-wave runs.

Thin wrapper over :func:`onbottom.hydro.fourier_fit.fit_fourier_table` (procedure and the run
CSV schema: :func:`onbottom.hydro.fourier_fit.read_run_csv`, docs/theory/fourier_model.md).
"""

from __future__ import annotations

from pathlib import Path

import click

from onbottom.cli._common import Number, check_output_path, emit_json, handle_errors, json_option
from onbottom.errors import InputError
from onbottom.hydro.fourier_fit import fit_run, read_run_csv, table_from_fits

__all__ = ["command"]


@click.command("fourier-fit")
@click.argument("runs", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option(
    "--diameter",
    type=Number(float, min=0.0, min_open=True),
    required=True,
    help="Pipe outer diameter D [m] of the tests.",
)
@click.option(
    "--rho",
    type=Number(float, min=0.0, min_open=True),
    default=1025.0,
    show_default=True,
    help="Water density ρ [kg/m³] of the tests.",
)
@click.option(
    "--harmonics",
    type=Number(int, min=1, max=8),
    default=5,
    show_default=True,
    help="Harmonic order N of the table.",
)
@click.option(
    "--discard",
    type=Number(int, min=0),
    default=0,
    show_default=True,
    help="Complete half-cycles dropped at the start of each run.",
)
@click.option(
    "--source",
    default="fitted by onbottom fourier-fit",
    show_default=True,
    help="Provenance written into the table.",
)
@click.option(
    "--out",
    "out",
    type=click.Path(dir_okay=False),
    required=True,
    help="Table file to write: .csv or .nc.",
)
@json_option
@handle_errors
def command(runs, diameter, rho, harmonics, discard, source, out, as_json):
    """Fit a Fourier coefficient table from regular-wave RUNS (CSV: t,U,F_Y,F_Z).

    Each run file has a units line s,m/s,N/m,N/m and may carry '# current_m_s: V',
    '# K: …', '# M: …' (nominal values) lines. The runs must cover a full K–M grid.
    """
    suffix = Path(out).suffix.lower()
    if suffix not in (".csv", ".nc"):
        raise InputError(f"--out = {out!r} is invalid: expected a .csv or .nc file name")
    fits = []
    for path in runs:
        fits.append(
            fit_run(
                read_run_csv(path), diameter=diameter, rho=rho, harmonics=harmonics, discard=discard
            )
        )
    table = table_from_fits(fits, source=source)
    check_output_path(out, field="--out")
    if suffix == ".csv":
        table.to_csv(out)
    else:
        table.to_netcdf(out)
    payload = {
        "table": str(out),
        "harmonics": table.harmonics,
        "K": table.k_grid.tolist(),
        "M": table.m_grid.tolist(),
        "runs": [{"run": str(r), **f.summary()} for r, f in zip(runs, fits, strict=True)],
    }
    if as_json:
        emit_json(payload)
        return
    click.echo(f"{'run':40s} {'K':>8s} {'M':>6s} {'U_m':>8s} {'T':>8s} {'n':>4s} {'rms':>9s}")
    for row in payload["runs"]:
        click.echo(
            f"{row['run'][-40:]:40s} {row['K']:8.4g} {row['M']:6.3g} {row['U_m']:8.4g}"
            f" {row['T']:8.4g} {row['half_cycles']:4d} {row['rms']:9.2e}"
        )
    click.echo(f"wrote {out}: {table.k_grid.size} K x {table.m_grid.size} M, N = {table.harmonics}")
