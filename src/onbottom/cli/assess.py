"""``onbottom assess``: every F109 level on every KP section of a route, and its design report.

With no CASE the embedded example route runs (package data ``data/assess_example.toml``:
shore approach, mid-route, deep end). Writes into ``--out``: ``report.html`` (and
``report.pdf`` with WeasyPrint), ``results.json``, ``dynamic.nc`` and ``sections/*.json``
(the per-section results a rerun resumes from).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    emit_json,
    handle_errors,
    json_option,
)

__all__ = ["command"]


def _refuse_case_in_out(case: Path, out: Path) -> None:
    from onbottom.errors import InputError

    names = {"report.html", "report.pdf", "results.json", "dynamic.nc"}
    if case.resolve().parent == out.resolve() and case.name in names:
        err = InputError(f"--out = {str(out)!r} is invalid: it would overwrite the case {case}")
        err.field = "--out"  # type: ignore[attr-defined]
        raise err
    if out.exists() and not out.is_dir():
        err = InputError(f"--out = {str(out)!r} is invalid: it is a file, expected a folder")
        err.field = "--out"  # type: ignore[attr-defined]
        raise err


@click.command("assess")
@click.argument(
    "case", required=False, type=click.Path(exists=True, dir_okay=False, path_type=Path)
)
@click.option(
    "--out",
    "out",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("assess_results"),
    show_default=True,
    help="Output folder (report.html/.pdf, results.json, dynamic.nc, sections/).",
)
@click.option(
    "--seeds",
    type=Number(int, min=1, max=1000),
    default=None,
    help="Storms per evaluation of the dynamic level (default [dynamic] seeds).",
)
@click.option(
    "--workers",
    type=Number(int, min=0, max=1024),
    default=None,
    help="Local Dask worker processes (default one per core; 0 = in this process).",
)
@click.option("--scheduler", default=None, metavar="ADDRESS", help="Dask scheduler address.")
@click.option("--no-pdf", is_flag=True, help="Do not write report.pdf.")
@click.option("--example", is_flag=True, help="Print the embedded example route and exit.")
@click.option("--quiet", is_flag=True, help="No progress bar.")
@json_option
@handle_errors
def command(
    case: Path | None,
    out: Path,
    seeds: int | None,
    workers: int | None,
    scheduler: str | None,
    no_pdf: bool,
    example: bool,
    quiet: bool,
    as_json: bool,
) -> None:
    """On-bottom stability of a whole route (CASE: route TOML; none: the embedded example).

    Per KP section, condition and load combination: flotation (F109 Eq 3.1), the absolute
    lateral check (Eqs 3.38/3.39), the generalized level where the tool's own curves cover
    the point, and storms on the section over seeds; per section the minimum concrete (or
    submerged weight) per level — the dynamic one by a search with every seed within the
    allowable displacement — and the governing design. A killed run resumes from the
    sections already done (same inputs). See examples/assess_route.toml.

    --json prints the results.json document (keys: schema, provenance, route, summary,
    sections, comparison, validity, clauses, pipeline) plus "files" and "pdf". A section with no
    passing design at any level run (the range is too narrow) exits 3 after writing the
    outputs; failing checks at the given design are a result (exit 0); input errors exit 1.
    """
    from onbottom.assess.core import assess
    from onbottom.assess.output import write_outputs
    from onbottom.cases.assess import example_path, load_route

    path = example_path() if case is None else case
    if example:
        click.echo(path.read_text(encoding="utf-8"), nl=False)
        return
    _refuse_case_in_out(path, out)
    route = load_route(path, seeds=seeds)  # every bad input raises here, before any work
    text = path.read_text(encoding="utf-8")
    source = "embedded example" if case is None else str(case)
    a = assess(
        route,
        out=out,
        n_workers=workers,
        scheduler=scheduler,
        progress=not quiet and not as_json,
        source=source,
    )
    written = write_outputs(a, out, case_text=text, pdf=not no_pdf)
    if as_json:
        from onbottom.assess.output import results_payload

        payload: dict[str, Any] = results_payload(a, text) | written
        emit_json(payload)
    else:
        _print(a, out, written)
    if route.variable != "none" and any(s["governing_level"] is None for s in a.sections):
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)


def _print(a: Any, out: Path, written: dict[str, Any]) -> None:
    click.echo(_table(a))
    click.echo(f"wrote {', '.join(written['files'])}")
    if written["pdf"]:
        click.echo(written["pdf"])
    if a.reused:
        click.echo(f"resumed: {len(a.reused)} section(s) reused from {out / 'sections'}")
    for name, why in a.recomputed:
        click.echo(f"recomputed: section {name!r} (its saved result is stale: {why})")


def _table(a: Any) -> str:
    from onbottom.assess.output import format_value as fv

    var = a.route.variable
    lines = [
        f"{a.route.name}: {len(a.sections)} sections, {a.wall_time_s:.1f} s",
        f"{'section':<20} {'KP [km]':<12} {'util.':>7}  {'absolute':>12} {'dynamic':>12}  design",
    ]
    for s in a.sections:
        lv = s["levels"]
        u = s["max_utilisation"]
        lines.append(
            f"{s['name'][:20]:<20} {s['kp_start_m'] / 1e3:g}–{s['kp_end_m'] / 1e3:g}".ljust(33)
            + f" {u:>7.3f}  "
            + f"{fv((lv.get('absolute') or {}).get('value'), var):>12} "
            + f"{fv((lv.get('dynamic') or {}).get('value'), var):>12}  "
            + (
                f"{fv(s['design_value'], var)} ({s['governing_level']})"
                if s["governing_level"]
                else "no solution"
            )
        )
    return "\n".join(lines)
