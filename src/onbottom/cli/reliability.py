"""``onbottom reliability CASE.toml``: the probability that a pipe section's lateral
displacement in a storm exceeds a limit, per storm, year and design life, from a campaign of
storm runs on Dask (:mod:`onbottom.reliability`); with ``[reliability.design]``, the
response-based design displacement on an IFORM contour against F109's return-period storm.

Writes into ``--out`` (default: ``<case stem>_reliability`` beside the case):
``campaign.zarr`` and ``design.zarr`` (every storm run; a rerun after a kill resumes from
them), ``reliability.json`` (the ``--json`` payload), ``exceedance.png``, ``convergence.png``,
``importance.png`` and ``design.png``, and ``report.html`` (+ ``tables/*.csv``): the report
page — climate and inputs, exceedance probabilities, importance, design, campaign,
assumptions and provenance (:mod:`onbottom.report.pages`).

``--json`` keys: ``success`` (false when a storm run failed numerically: exit status 3),
``case``, ``out``, ``diameter`` [m], ``storms_per_year``, ``inputs`` (names of the random
inputs, the storm seed last), ``climate`` (hindcast, rate, threshold, gpd_scale, gpd_shape,
sectors, sector_frequencies, current_model (null: the current is a case input), joint_model;
empty without a hindcast), ``estimates`` (per limit: ``label``, ``limit`` [m],
``probability`` (per storm), ``cv``, ``method``, ``storms``, ``computed``, ``failed_runs``,
``annual``, ``lifetime``, ``reliability_index``, ``history`` ([storms, probability, cv]),
``curve`` ([displacement m, probability]), ``importance``, ``importance_kind``,
``design_point``, ``upper_bound``, ``interval``, ``annual_interval``, ``lifetime_interval``,
``interval_kind``, ``confidence``, ``failures``, ``failure_mean`` (E[u | failure] per input),
``failure_mean_kind``, ``pilot_storms``, ``stopped_early``, ``notes``), ``design``
(``return_period``, ``fractile``, ``points``, ``governing``, ``design_displacement`` [m],
``f109``) or null,
``campaign`` (``requested``, ``computed``, ``reused``, ``failed``, ``seconds_per_storm``),
``target`` (the annual probabilities against DNV-OS-F101's target for the safety class: pass,
fail or undecided by the 95 % interval), ``plan`` (per limit: the storms and CPU time its
estimator needs for the case's ``target_cv`` at the measured rate,
:func:`onbottom.reliability.run.storm_plan`; also printed on stderr as each limit finishes),
``files``, ``notes``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

from onbottom.cli._common import EXIT_INVALID_RESULT, Number, emit_json, handle_errors, json_option

__all__ = ["command"]


def _write_run(
    case: Path,
    out: Path | None,
    *,
    n_workers: int | None,
    scheduler: str | None,
    progress: bool,
    figures: bool = True,
    report: bool = True,
    force: bool = False,
) -> dict:
    """Read the case, run it (:func:`onbottom.reliability.run.run_reliability`) and write the
    outputs; returns the JSON payload."""
    import time

    from onbottom.cases.reliability import load_reliability_setup
    from onbottom.errors import InputError
    from onbottom.reliability.run import (
        require_packages,
    )

    t0 = time.perf_counter()
    require_packages()
    setup = load_reliability_setup(case)
    check_budget(setup, workers=n_workers, force=force)
    out = out if out is not None else case.resolve().parent / f"{case.stem}_reliability"
    if out.exists() and not out.is_dir():
        err = InputError(f"--out = {str(out)!r} is invalid: it is a file, expected a folder")
        err.field = "--out"  # type: ignore[attr-defined]
        raise err
    from onbottom.assess.output import RELIABILITY_NAMES, claim_output_folder

    with claim_output_folder(
        out, force=force, command="reliability", own=RELIABILITY_NAMES
    ) as held:
        for note in held.notes:
            click.echo(f"note: {note}", err=True)
        return _run_in(setup, case, out, t0, n_workers, scheduler, progress, figures, report)


def _run_in(
    setup: Any,
    case: Path,
    out: Path,
    t0: float,
    n_workers: int | None,
    scheduler: str | None,
    progress: bool,
    figures: bool,
    report: bool,
) -> dict:
    """The run of :func:`_write_run` in its held ``--out`` folder."""
    import json
    import sys
    import time

    from onbottom.reliability.run import planned_storms, run_payload, run_reliability
    from onbottom.results import write_text_atomic

    bar = None
    if progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=planned_storms(setup), unit="storm", desc="reliability")

    def on_estimate(e: Any, plan: dict) -> None:
        line = plan_line(plan, n_workers)
        if bar is not None:
            bar.write(line, file=sys.stderr)
        else:
            click.echo(line, err=True)

    try:
        r = run_reliability(
            setup,
            out,
            n_workers=n_workers,
            scheduler=scheduler,
            progress=bar.update if bar else None,
            on_estimate=on_estimate,
        )
    finally:
        if bar is not None:
            bar.close()
    files = [str(out / "campaign.zarr")] + ([str(out / "design.zarr")] if r.design else [])
    fig_files = _figures(r, out, case.name, files) if figures else {}
    res = run_payload(r)
    payload = (
        {"success": res["success"], "case": str(case), "out": str(out)}
        | {k: v for k, v in res.items() if k not in ("success", "notes")}
        | {
            "files": [*files, str(out / "reliability.json")]
            + ([str(out / "report.html")] if report else []),
            "notes": res["notes"],
        }
    )
    from onbottom.cli._common import _jsonable

    write_text_atomic(out / "reliability.json", json.dumps(_jsonable(payload), indent=1))
    if report:
        from onbottom.report.pages import reliability_sections, write_page

        sections, prov = reliability_sections(_jsonable(payload), figures=fig_files, case=case)
        write_page(
            out,
            f"Long-term reliability — {case.name}",
            sections,
            command=f"onbottom reliability {case} --out {out}",
            inputs=prov,
            run_time=time.perf_counter() - t0,
            json_name="reliability.json",
        )
    return payload


def plan_line(plan: dict, workers: int | None) -> str:
    """One line: the storms and CPU time the estimator needs for the case's target CV
    (:func:`onbottom.reliability.run.storm_plan`), and the wall time on the workers."""
    import math
    import os

    n, cpu = plan["storms"], plan["cpu_seconds"]
    cv = plan["target_cv"]
    head = f"  plan {plan['label']}: CV {cv:g} (95 % interval about ±{1.96 * cv:.2g}·P)"
    if not math.isfinite(n):
        return f"{head}: storms needed unknown (P estimated as 0 or 1 from this sample)"
    if plan["lower_bound"]:
        need = f"at least {n:,.0f} storms by Monte Carlo (no failing storm yet: P at its bound)"
    else:
        need = f"{n:,.0f} storms ({plan['method']})"
    if not math.isfinite(cpu):
        return f"{head} needs {need}; rate unknown (every storm was read back from the store)"
    w = max(1, workers if workers is not None else (os.cpu_count() or 1))
    return (
        f"{head} needs {need} = {cpu / 3600:.3g} CPU-h at the measured"
        f" {plan['cpu_seconds_per_storm'] * 1e3:.3g} CPU-ms/storm (~{cpu / w / 60:.3g} min on"
        f" {w} worker(s)); this run used {plan['storms_used']:,}"
    )


def check_budget(setup: Any, *, workers: int | None, force: bool) -> None:
    """Refuse a campaign whose estimated time or memory exceeds the budget (unless ``force``,
    the command's ``--force``): :func:`onbottom.study.budget.check` of the storms it may run
    (:func:`onbottom.reliability.run.planned_storms`: every limit's ``max_storms``, the FORM
    search and the contour design), each a storm of the case's duration and time step."""
    from onbottom.reliability.run import planned_storms
    from onbottom.study import budget

    s = setup.storm
    stages = getattr(s.storm, "stages", ())
    tp = max((st.tp for st in stages), default=10.0)
    budget.check(
        budget.section_storms(
            planned_storms(setup),
            float(s.storm.duration_s),
            s.settings.dt_max,
            tp=tp,
            workers=workers,
        ),
        force=force,
        field="reliability.max_storms",
    )


def _figures(r: Any, out: Path, title: str, files: list[str]) -> dict[str, str]:
    """Write the figures of a run into ``out`` (appended to ``files``); name -> file."""
    import matplotlib.pyplot as plt

    from onbottom.plotting.reliability import (
        plot_convergence,
        plot_design,
        plot_exceedance,
        plot_importance,
    )

    figs = [
        ("exceedance.png", plot_exceedance(r.estimates, r.diameter, title=title)),
        ("convergence.png", plot_convergence(r.estimates)),
        ("importance.png", plot_importance(r.estimates)),
    ]
    if r.design is not None:
        figs.append(("design.png", plot_design(r.design, r.diameter)))
    names = {}
    for name, fig in figs:
        fig.savefig(out / name, dpi=110)
        plt.close(fig)
        files.append(str(out / name))
        names[name.removesuffix(".png")] = name
    return names


def _fmt_interval(iv: list) -> str:
    lo, hi = (float("nan") if v is None else v for v in iv)
    return f"[{lo:.2g}, {hi:.2g}]"


def _estimate_lines(e: dict) -> str:
    """The text lines of one estimate: probabilities with their intervals, what drives failure."""
    pct = f"{100 * e['confidence']:g} %"
    if e["upper_bound"]:
        head = f"<= {e['probability']:.3g} (an upper bound: {e['interval_kind']})"
    else:
        cv = "-" if e["cv"] is None else f"{e['cv']:.2f}"
        head = f"{e['probability']:.3g} {_fmt_interval(e['interval'])} (CV {cv})"
    lines = [
        f"  P[Y > {e['label']}] per storm {head}, {e['method']}, {e['storms']} storms,"
        f" {e['failures']} failing",
        f"    per year {e['annual']:.3g} {_fmt_interval(e['annual_interval'])};"
        f" life {e['lifetime']:.3g} {_fmt_interval(e['lifetime_interval'])} ({pct} intervals)",
    ]
    if e.get("stopped_early"):
        lines.append(
            f"    {e['stopped_early']} storms stopped early, beyond the largest limit (their"
            " verdict is the whole storm's)"
        )
    if e["failure_mean"]:
        fm = ", ".join(f"{k} {v:+.2f}" for k, v in e["failure_mean"].items())
        lines.append(f"    given failure, mean standardized input (SDs from median): {fm}")
    imp = ", ".join(f"{k} {v:.2f}" for k, v in e["importance"].items())
    lines.append(f"    SRRC^2 shares of R^2 over all storms (the bulk of the response): {imp}")
    return "\n".join(lines)


@click.command("reliability")
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--out",
    "out",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="Folder for the stores, figures and reliability.json (resumed if it holds a store).",
)
@click.option(
    "--workers",
    type=Number(int, min=0, max=4096),
    default=None,
    help="Worker processes of the local Dask cluster (default: one per core; 0: this process).",
)
@click.option(
    "--scheduler",
    default=None,
    help="Address of a running Dask scheduler (tcp://host:8786) instead of a local cluster.",
)
@click.option(
    "--force",
    is_flag=True,
    help="Run even when the estimated time or memory of the campaign exceeds the budget"
    " (onbottom.study.budget: 12 h, 8 GB), and write into an --out holding files onbottom did"
    " not write.",
)
@click.option("--no-figures", is_flag=True, help="Skip the figures.")
@click.option("--no-progress", is_flag=True, help="No progress bar.")
@click.option("--no-report", is_flag=True, help="Skip the report page (report.html).")
@json_option
@handle_errors
def command(
    case: Path,
    out: Path | None,
    workers: int | None,
    scheduler: str | None,
    force: bool,
    no_figures: bool,
    no_progress: bool,
    no_report: bool,
    as_json: bool,
) -> None:
    """Long-term reliability of CASE (a storm case with a [reliability] table; see
    examples/reliability_case.toml and docs/theory/reliability.md): P[max lateral displacement
    in a storm > limit] per storm, year and design life, with its CV and the importance of the
    inputs; the response-based design on an environmental contour.
    """
    payload = _write_run(
        case,
        out,
        n_workers=workers,
        scheduler=scheduler,
        progress=not no_progress,
        figures=not no_figures,
        report=not no_report,
        force=force,
    )
    if as_json:
        emit_json(payload)
    else:
        click.echo(f"{payload['case']}: {payload['storms_per_year']:.3g} storms/year")
        for e in payload["estimates"]:
            click.echo(_estimate_lines(e))
        t = payload["target"]
        for row in t["limits"]:
            click.echo(
                f"  {row['label']}: annual {row['annual']:.3g} (95 % upper {row['upper']:.3g})"
                f" against {t['annual_target']:.0e} ({t['safety_class']} safety class,"
                f" {t['source']}): {row['verdict']}"
            )
        d = payload["design"]
        if d is not None:
            g, f = d["governing"], d["f109"]
            click.echo(
                f"  design ({d['return_period']:g} years, {d['fractile']:g} fractile):"
                f" {d['design_displacement']:.3g} m at H_s {g['hs']:.2f} m, T_p {g['tp']:.1f} s;"
                f" F109 storm (H_s {f['hs']:.2f} m, T_p {f['tp']:.1f} s): {f['fractile']:.3g} m"
            )
        for n in payload["notes"]:
            click.echo(f"  note: {n}")
        click.echo(f"  wrote {payload['out']}")
    if not payload["success"]:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
