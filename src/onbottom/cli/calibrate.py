"""``onbottom calibrate``: fit A, B, C, μ (and γ') of the calcareous V&S model to test records."""

from __future__ import annotations

import math
from pathlib import Path

import click

from onbottom.calibration.parameters import CALCAREOUS_BOUNDS, CALCAREOUS_START
from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
)
from onbottom.errors import InputError

DEFAULT_START = CALCAREOUS_START
"""Start values (:data:`onbottom.calibration.parameters.CALCAREOUS_START`)."""
DEFAULT_BOUNDS = CALCAREOUS_BOUNDS
"""Search bounds (:data:`onbottom.calibration.parameters.CALCAREOUS_BOUNDS`)."""


def _pairs(text: str | None, option: str) -> dict[str, str]:
    out: dict[str, str] = {}
    if not text:
        return out
    for item in text.split(","):
        if "=" not in item:
            raise InputError(f"{option} entry {item!r} is invalid: expected NAME=VALUE")
        k, v = item.split("=", 1)
        out[k.strip()] = v.strip()
    return out


def _float(option: str, name: str, text: str) -> float:
    try:
        x = float(text)
    except ValueError as exc:
        raise InputError(f"{option} {name}={text!r} is invalid: expected a number") from exc
    if not math.isfinite(x):
        raise InputError(f"{option} {name}={text!r} is invalid: expected a finite number")
    return x


def _parameters(vary: str, bounds: str | None, start: str | None, gamma: float | None):
    """Options → :func:`onbottom.calibration.parameters.calcareous_parameters` (the option
    strings are parsed and checked here, so that errors name the option)."""
    from onbottom.calibration.parameters import calcareous_parameters, check_vary

    names = [n.strip() for n in vary.split(",") if n.strip()]
    check_vary(names, option="--vary", given=vary)
    known = set(DEFAULT_BOUNDS)
    b: dict[str, tuple[float, float]] = {}
    for k, v in _pairs(bounds, "--bounds").items():
        if ":" not in v:
            raise InputError(f"--bounds {k}={v!r} is invalid: expected LOWER:UPPER")
        if k not in known:
            raise InputError(f"--bounds {k}= is invalid: must be among {sorted(known)}")
        lo, hi = v.split(":", 1)
        b[k] = (_float("--bounds", k, lo), _float("--bounds", k, hi))
        if not b[k][0] < b[k][1]:
            raise InputError(f"--bounds {k}={v} is invalid: LOWER must be below UPPER")
    s: dict[str, float] = {}
    for k, v in _pairs(start, "--start").items():
        if k not in known:
            raise InputError(f"--start {k}= is invalid: must be among {sorted(known)}")
        s[k] = _float("--start", k, v)
    return calcareous_parameters(names, bounds=b, start=s, gamma=gamma)


def _weights(text: str | None):
    from dataclasses import fields

    from onbottom.calibration.objective import MisfitWeights

    allowed = [f.name for f in fields(MisfitWeights)]
    for k in _pairs(text, "--weights"):
        if k not in allowed:
            raise InputError(f"--weights {k}= is invalid: must be among {allowed}")
    return MisfitWeights(
        **{k: _float("--weights", k, v) for k, v in _pairs(text, "--weights").items()}
    )


@click.command("calibrate")
@click.argument("records", nargs=-1, required=True, type=click.Path(exists=True, dir_okay=False))
@click.option("--vary", default="A,B,C,mu", show_default=True, help="Parameters to fit.")
@click.option("--bounds", help="Search bounds, e.g. 'A=0.1:0.6,mu=0.4:1.2'.")
@click.option("--start", help="Start/fixed values, e.g. 'A=0.3,mu=0.5'.")
@click.option(
    "--gamma",
    type=Number(float, min=1.0e3, max=2.5e4, unit="N/m³"),
    help="Submerged unit weight γ' [N/m³] (default: preset's).",
)
@click.option("--weights", help="Misfit weights, e.g. 'u_history=2,time_to_limit=0'.")
@click.option(
    "--history-only",
    is_flag=True,
    help="Fit the u and w histories only (recommended for noisy records; overrides --weights).",
)
@click.option(
    "--method", type=click.Choice(["global", "local"]), default="global", show_default=True
)
@click.option("--each", is_flag=True, help="Fit each record alone; print Table 2 and Table 3.")
@click.option(
    "--loads",
    type=click.Choice(["preset", "recorded"]),
    default="preset",
    show_default=True,
    help="Simulate the record's centrifuge preset, or drive by its recorded H and V.",
)
@click.option("--seed", type=Number(int, min=0), default=0, show_default=True)
@click.option(
    "--maxiter",
    type=Number(int, min=1, max=100_000),
    default=40,
    show_default=True,
    help="DE generations (local: iterations).",
)
@click.option(
    "--popsize",
    type=Number(int, min=5, max=1000),
    default=10,
    show_default=True,
    help="DE population factor (population = popsize × parameters; below 5 the search is"
    " too thin to trust).",
)
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write fitted TOML here.")
@click.option("--plot-dir", type=click.Path(file_okay=False), help="Write fit figures here.")
@click.option("--scheduler", help="Dask scheduler address (remote cluster).")
@click.option(
    "--workers",
    type=Number(int, min=0, max=1024),
    default=0,
    show_default=True,
    help="Local Dask workers (0 = serial).",
)
@json_option
@handle_errors
def command(
    records,
    vary,
    bounds,
    start,
    gamma,
    weights,
    history_only,
    method,
    each,
    loads,
    seed,
    maxiter,
    popsize,
    output,
    plot_dir,
    scheduler,
    workers,
    as_json,
):
    """Fit the calcareous Verley & Sotberg parameters to test RECORDS (CSV or NetCDF).

    Records fitted together share one parameter set; with --each, each record is fitted alone
    and the per-test values (Table 2) and recommended values (Table 3, rules of Youssef &
    Cassidy 2014: A lowest, B and C mean, μ range only) are printed.
    """
    from onbottom.calibration.objective import HISTORY_ONLY
    from onbottom.calibration.summary import write_fits

    # settings
    params = _parameters(vary, bounds, start, gamma)
    misfit_weights = HISTORY_ONLY if history_only else _weights(weights)
    if output:
        check_output_path(output, field="--output")
    # setup
    recs = _load_records(records)
    simulator = _simulator(loads, gamma)
    fit_options = dict(
        simulator=simulator,
        weights=misfit_weights,
        method=method,
        seed=seed,
        maxiter=maxiter,
        popsize=popsize,
        progress=not as_json,
    )
    # the fits
    results = _fit(recs, params, each, scheduler, workers, fit_options)
    # results
    if output:
        write_fits(results, output)
    if plot_dir:
        _plot_fits(results, recs, simulator, Path(plot_dir))
    _report(results, params, each, as_json)


def _load_records(records: tuple[str, ...]) -> list:
    """The test records (CSV or NetCDF); an unreadable one is an error naming ``records``."""
    from onbottom.calibration.records import load_record

    recs = []
    for p in records:
        try:
            recs.append(load_record(p))
        except InputError as exc:
            exc.field = getattr(exc, "field", None) or "records"  # type: ignore[attr-defined]
            raise
    return recs


def _simulator(loads: str, gamma: float | None):
    """The record's centrifuge preset (``--loads preset``) or its recorded H and V."""
    from onbottom.calibration.simulators import CentrifugeSimulator, RecordedLoadSimulator

    if loads == "preset":
        return CentrifugeSimulator(gamma=gamma)
    return RecordedLoadSimulator(**({"gamma": gamma} if gamma is not None else {}))


def _fit(recs, params, each: bool, scheduler, workers, fit_options: dict) -> list:
    """One joint fit, or one per record (``--each``, records in parallel), on Dask when a
    scheduler or workers are given."""
    from onbottom.calibration.fit import calibrate
    from onbottom.calibration.summary import fit_each

    def run(client=None):
        if each:  # records in parallel, one task each
            return fit_each(recs, params, client=client, **fit_options)
        return [calibrate(recs, params, client=client, n_workers=0, **fit_options)]

    if scheduler or workers:
        from onbottom.study.engine import dask_client

        with dask_client(scheduler_address=scheduler, n_workers=workers or None) as client:
            return run(client)
    return run()


def _plot_fits(results, recs, simulator, pdir: Path) -> None:
    """One figure per fitted record, ``fit_<name>.png`` (a second record of one name gets
    ``_2``)."""
    from onbottom.plotting.calibration import plot_fit

    pdir.mkdir(parents=True, exist_ok=True)
    written_plots: set[str] = set()
    for res in results:
        for rec in (r for r in recs if r.name in res.record_names):
            sim = simulator(rec, res.values)
            fig = plot_fit(rec, sim, title=f"{rec.name}: fitted")
            tag = "".join(ch if ch.isalnum() else "_" for ch in rec.name)
            name = f"fit_{tag}.png"
            k = 2
            while name in written_plots:  # two records of one name: keep both figures
                name = f"fit_{tag}_{k}.png"
                k += 1
            written_plots.add(name)
            fig.savefig(pdir / name, dpi=120)


def _report(results, params, each: bool, as_json: bool) -> None:
    """The fits (JSON or text, with Tables 2 and 3 for ``--each``); exit 3 if one failed."""
    from onbottom.calibration.summary import parameter_table, recommend, to_markdown

    rows = parameter_table(results)
    names = [p.name for p in params if p.vary]
    rec_rows = recommend(rows, names=names) if each else []
    ok = all(bool(r.success) for r in results)
    if as_json:
        emit_json({"fits": [r.to_dict() for r in results], "recommended": rec_rows})
        if not ok:
            raise click.exceptions.Exit(EXIT_INVALID_RESULT)
        return
    for res in results:
        click.echo(f"{', '.join(res.record_names)}: {res.message}")
        for p in res.parameters:
            se = res.std_errors.get(p.name, math.nan)
            extra = f" ± {se:.3g} (1 s.e.)" if p.vary and math.isfinite(se) else " (fixed)"
            click.echo(f"  {p.name:6s} = {p.value:.4g}{extra}")
        click.echo(f"  misfit = {res.misfit:.4g} after {res.n_evaluations} evaluations")
    if each:
        click.echo("\nPer-test values (Table 2):\n")
        click.echo(to_markdown(rows, columns=["case", *names, "misfit"]))
        click.echo("Recommended values (Table 3):\n")
        click.echo(
            to_markdown(
                rec_rows, columns=["parameter", "min", "mean", "max", "rule", "recommended"]
            )
        )
    if not ok:
        click.echo("Error: a fit did not succeed (see its message)", err=True)
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
