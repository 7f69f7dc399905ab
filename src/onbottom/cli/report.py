"""``onbottom report`` — build the HTML validation report."""

from __future__ import annotations

import click

from onbottom.cli._common import emit_json, handle_errors, json_option

__all__ = ["command"]


@click.command("report")
@click.option(
    "--out",
    "out",
    type=click.Path(file_okay=False),
    default="onbottom-report",
    show_default=True,
    help="Output folder: index.html, report.json, figures/, tables/.",
)
@click.option(
    "--only",
    "only",
    multiple=True,
    metavar="SECTION",
    help="Run only this section (repeatable); --list shows the names.",
)
@click.option("--fast", is_flag=True, help="Leave out the slow sections (calibration recovery, …).")
@click.option("--list", "list_", is_flag=True, help="List the sections and exit.")
@click.option(
    "--force",
    is_flag=True,
    help="Overwrite an index.html in --out that onbottom did not write.",
)
@json_option
@handle_errors
def command(
    out: str, only: tuple[str, ...], fast: bool, list_: bool, force: bool, as_json: bool
) -> None:
    """Validation report: every comparison with the papers and the standards on one page.

    Runs the fast comparisons (F114 against the reference values and the penetration tests,
    the seven centrifuge tests, calibration recovery, …) and reads the committed DEM
    summaries; writes a self-contained HTML page with figures and CSV tables beside it, pass/
    fail against the stated tolerances and provenance (version, git commit, date, machine,
    run time). Sections whose part of onbottom is missing from this build are listed as "not
    available". Exit status 0 even when checks fail (the page says which); 1 on bad input.
    --out is refused when it is the filesystem root or the home folder, or when it holds an
    index.html that onbottom did not write (unless --force); an earlier report is replaced.
    """
    from onbottom.report.build import build_report
    from onbottom.report.registry import section_catalogue

    if list_:
        rows = section_catalogue()
        if as_json:
            emit_json({"sections": rows})
        else:
            for r in rows:
                flags = ("slow " if r["slow"] else "") + ("" if r["available"] else "unavailable")
                click.echo(f"{r['name']:<18} {r['title']}  {flags}".rstrip())
        return
    res = build_report(out, only=only or None, fast=fast, force=force)
    if as_json:
        emit_json(res.summary())
        return
    for s in res.sections:
        if s.state == "ok" and not (s.n_pass or s.n_fail):
            state = f"for information  ({s.run_time:.1f} s)"
        elif s.state == "ok":
            state = f"{s.n_pass} pass, {s.n_fail} fail  ({s.run_time:.1f} s)"
        elif s.state == "error":
            state = f"ERROR: {s.reason.strip().splitlines()[-1]}"
        else:
            state = f"{s.state}: {s.reason}"
        click.echo(f"{s.name:<18} {state}")
    click.echo(
        f"{res.n_pass} checks pass, {res.n_fail} fail; {res.provenance['run_time']} s → {res.index}"
    )
