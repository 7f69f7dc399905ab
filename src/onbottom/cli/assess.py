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


def _pipeline_estimate(route: Any, *, workers: int | None) -> Any:
    """The :class:`~onbottom.study.budget.Estimate` of the pipeline FE level: one complete FE
    storm per section with ``[pipeline] sections = "every"``, else one (the governing
    section's, costed at the dearest section), each by the pipeline cost model
    (:func:`onbottom.dynamics.pipeline.storm_run.run_cost`: nodes × steps at the largest time
    step, kinematics per node-hour); None without ``[levels] pipeline_fe``. The design raised
    above a failing FE run adds trials stopped at the allowable, not counted."""
    from onbottom.assess.pipeline import section_fe_nodes
    from onbottom.dynamics.pipeline.storm_run import run_cost
    from onbottom.study import budget

    if not route.levels.pipeline_fe:
        return None
    costs = [
        max(
            (
                run_cost(nodes, c.setup.storm, route.pipeline.duration, c.setup.settings.dt_max)
                for c in sec.storms
            ),
            key=lambda c: c.cpu_s,
        )
        for sec in route.sections
        if sec.storms
        for nodes in [section_fe_nodes(route, sec)]
    ]
    if not costs:
        return None
    if route.pipeline.sections != "every":
        costs = [max(costs, key=lambda c: c.cpu_s)]
    return budget.pipeline_storms(
        len(costs),
        max(c.cpu_s for c in costs),
        max(c.memory_bytes for c in costs),
        workers=workers,
    )


def estimate(route: Any, *, workers: int | None) -> Any:
    """The :class:`~onbottom.study.budget.Estimate` of a route's dynamic level: per section
    and load combination, the seeds at the given design and, with a design variable, the
    search's trials (about 3 + log2(range / tolerance), as the curves' bisection), each
    a storm of ``[dynamic]`` build-up + peak at its time step; plus the pipeline FE storms of
    :func:`_pipeline_estimate` (:func:`onbottom.study.budget.combined`); None without the
    dynamic level."""
    import math

    from onbottom.study import budget

    if not route.levels.dynamic:
        return None
    d = route.dynamic
    trials = 0
    if route.variable == "concrete_thickness":
        span, tol = route.design.thickness_max - route.design.thickness_min, d.thickness_tolerance_m
    elif route.variable == "submerged_weight":
        span, tol = route.design.weight_max - route.design.weight_min, d.weight_tolerance_n_per_m
    else:
        span, tol = 0.0, 1.0
    if span > 0.0:
        trials = 3 + math.ceil(math.log2(max(span / tol, 1.0)))
    setups = [c.setup for s in route.sections for c in s.storms]
    if not setups:
        return None
    n = len(setups) * d.seeds * (1 + trials)
    st = setups[0]
    tp = max((x.tp for c in setups for x in getattr(c.storm, "stages", ())), default=10.0)
    est = budget.section_storms(
        n, float(st.storm.duration_s), st.settings.dt_max, tp=tp, workers=workers
    )
    fe = _pipeline_estimate(route, workers=workers)
    return est if fe is None else budget.combined(est, fe)


def check_budget(route: Any, *, workers: int | None, force: bool) -> None:
    """Refuse a route whose dynamic level is estimated above the budget (unless ``force``,
    the command's ``--force``): :func:`onbottom.study.budget.check`, as ``storm --seeds``
    and ``curves``."""
    from onbottom.study import budget

    est = estimate(route, workers=workers)
    if est is not None:
        budget.check(est, force=force, field="[dynamic]")


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
@click.option(
    "--force",
    is_flag=True,
    help="Run even when the estimated time or memory of the storms exceeds the budget"
    " (onbottom.study.budget: 12 h, 8 GB), and write into an --out holding files onbottom did"
    " not write.",
)
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
    force: bool,
    no_pdf: bool,
    example: bool,
    quiet: bool,
    as_json: bool,
) -> None:
    """On-bottom stability of a whole route (CASE: route TOML; none: the embedded example).

    Per KP section, condition and load combination: flotation (F109 Eq 3.1), the absolute
    lateral check (Eqs 3.38/3.39), the generalized level from F109's tables (§3.5) where they
    cover the point, and storms on the section over seeds; per section the minimum concrete
    (or submerged weight) per level — the dynamic one by a search with every seed within the
    allowable displacement — and the governing design, never below F109's generalized
    requirement unless [levels] allow_below_generalized says why. A killed run resumes from the
    sections already done (same inputs). See examples/assess_route.toml.

    --json prints the results.json document (keys: schema, provenance, route, summary,
    sections, comparison, validity, clauses, pipeline) plus "files" and "pdf". A section with no
    passing design at any level run (the range is too narrow) exits 3 after writing the
    outputs; failing checks at the given design are a result (exit 0); input errors exit 1.
    """
    from onbottom.assess.core import assess
    from onbottom.assess.output import claim_output_folder, write_outputs
    from onbottom.cases.assess import example_path, load_route

    path = example_path() if case is None else case
    if example:
        click.echo(path.read_text(encoding="utf-8"), nl=False)
        return
    _refuse_case_in_out(path, out)
    import warnings

    with warnings.catch_warnings(record=True) as caught:  # printed once each, as notes
        warnings.simplefilter("always")
        route = load_route(path, seeds=seeds)  # every bad input raises here, before any work
        check_budget(route, workers=workers, force=force)
        text = path.read_text(encoding="utf-8")
        source = "embedded example" if case is None else str(case)
        with claim_output_folder(out, force=force) as held:
            for note in held.notes:
                click.echo(f"note: {note}", err=True)
            a = assess(
                route,
                out=out,
                n_workers=workers,
                scheduler=scheduler,
                progress=not quiet and not as_json,
                source=source,
            )
            raised = _once([str(w.message) for w in caught])
            written = write_outputs(a, out, case_text=text, pdf=not no_pdf, notes=raised)
    if as_json:
        from onbottom.assess.output import results_payload

        payload: dict[str, Any] = results_payload(a, text) | written
        emit_json(payload)
    else:
        _print(a, out, written, raised)
    if route.variable != "none" and any(s["governing_level"] is None for s in a.sections):
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)


def _once(messages: list[str]) -> list[str]:
    """Each warning once: messages that differ only by their ``<where>: `` prefix (one per
    section or condition) are one note, with the places listed after it."""
    import re

    where: dict[str, list[str]] = {}
    for m in messages:
        k = re.match(r"<([^>]+)>: (.*)", m, re.S)
        text, place = (k.group(2), k.group(1)) if k else (m, None)
        places = where.setdefault(text, [])
        if place and place not in places:
            places.append(place)
    return [t + (f" (in {', '.join(p)})" if len(p) > 1 else (f" ({p[0]})" if p else ""))
            for t, p in where.items()]  # fmt: skip


def _print(a: Any, out: Path, written: dict[str, Any], raised: list[str] = ()) -> None:
    click.echo(_table(a))
    files = [f for f in written["files"] if Path(f).parent.name != "tables"]
    n_csv = len(written["files"]) - len(files)
    click.echo(
        f"wrote {', '.join(files)}" + (f" and {n_csv} CSV tables in tables/" if n_csv else "")
    )
    notes = list(dict.fromkeys([*raised, *(n for s in a.sections for n in s.get("notes", []))]))
    for n in notes:
        click.echo(f"note: {n}")
    if written["pdf"]:
        click.echo(written["pdf"])
    if a.reused:
        click.echo(f"resumed: {len(a.reused)} section(s) reused from {out / 'sections'}")
    for name, why in a.recomputed:
        click.echo(f"recomputed: section {name!r} (its saved result is stale: {why})")


def _table(a: Any) -> str:
    from onbottom.assess.output import format_value as fv
    from onbottom.assess.output import level_name

    var = a.route.variable
    fe = a.route.levels.pipeline_fe
    lines = [
        f"{a.route.name}: {len(a.sections)} sections, {a.wall_time_s:.1f} s",
        f"{'section':<20} {'KP [km]':<12} {'util.':>7}  {'absolute':>12} {'dynamic':>12}"
        + (f" {'pipeline FE':>12}" if fe else "")
        + "  design",
    ]
    reasons = []
    for s in a.sections:
        lv = s["levels"]
        u = s["max_utilisation"]
        pf = lv.get("pipeline_fe")
        lines.append(
            f"{s['name'][:20]:<20} {s['kp_start_m'] / 1e3:g}–{s['kp_end_m'] / 1e3:g}".ljust(33)
            + f" {u:>7.3f}  "
            + f"{fv((lv.get('absolute') or {}).get('value'), var):>12} "
            + f"{fv((lv.get('dynamic') or {}).get('value'), var):>12}"
            + ((f" {fv(pf.get('value'), var) if pf else 'not run':>12}") if fe else "")
            + "  "
            + (
                f"{fv(s['design_value'], var)} ({level_name(s['governing_level'])})"
                if s["governing_level"]
                else "NO DESIGN"
            )
        )
        if not s["governing_level"] and var != "none":
            reasons.append(f"  {s['name']}: " + (s.get("no_design_reason")
                           or "no level run finds a passing design in the range"))  # fmt: skip
    if fe:
        lines.append("pipeline FE: run on the governing section only (the heaviest design)")
    if reasons:
        lines.append("no design:")
        lines += reasons
    return "\n".join(lines)
