"""``onbottom metocean``: from a hindcast to the per-sector design table of DNV-RP-F109.

Writes into ``--out``:

* ``design_table.csv`` — per sector (omni first): H_s per return period with its confidence
  interval, the T_p that goes with it (median and 5–95 % of T_p|H_s), the current speed per
  return period with its interval;
* ``case_<sector>.toml`` — for each sector with enough storms, ``[waves]`` (100-year),
  ``[current]`` (10-year) and the two F109 §3.4.2 ``[[combinations]]``, to paste over those
  tables of a ``stability`` / ``storm`` case file;
* ``metocean.nc`` — return values, intervals, thresholds, storm counts, GPD parameters,
  IFORM contours, with provenance attributes;
* ``return_levels.png``, ``contours.png``, ``threshold.png`` (mean residual life and threshold
  stability of the omnidirectional H_s) — the figures;
* ``report.html`` (+ ``tables/*.csv``) — the report page: the record, storms and return values,
  joint model and contours, the design table, assumptions and provenance
  (:mod:`onbottom.report.pages`).

``--json`` keys: ``success`` (false when the omnidirectional H_s has no return values: exit
status 3), ``hindcast`` (path), ``years``, ``step_hours``, ``sectors`` (labels),
``return_periods``, ``ci_method``, ``confidence``, ``table`` (list of rows: ``sector``,
``centre_deg``, ``hs``, ``hs_lower``, ``hs_upper``, ``tp``, ``tp_low``, ``tp_high``,
``current``, ``current_lower``, ``current_upper``, ``current_with_hs``,
``current_with_hs_p90`` (median and 90 % current given the row's H_s, from the joint model),
each a list over ``return_periods``; SI), ``joint_model`` (parameters), ``current_model``
(Weibull ``scale`` [m/s], ``shape``, copula ``rho``, ``spearman``, …; null without current),
``contour_max_hs`` (per return period, m), ``tail`` (the omnidirectional H_s fit's tail guard:
``warnings``, ``endpoint``, the exponential (ξ = 0) fit's values and intervals, the storms
censored by a data gap and the fit that treats them as censored; null without a fit),
``contour_check`` (the H_s marginal's tail against the data: empirical and fitted exceedance at
the top levels, the longest return period's contour maximum against the POT value and their
ratio, and the contour with a maximum-likelihood Weibull), ``files`` (paths written),
``notes`` (sectors without values and why).
"""

from __future__ import annotations

from pathlib import Path

import click

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    emit_json,
    handle_errors,
    json_option,
)

__all__ = ["command", "run_metocean"]


def _return_periods(text: str) -> tuple[float, ...]:
    from onbottom.errors import InputError

    try:
        vals = tuple(float(x) for x in text.split(",") if x.strip())
    except ValueError:
        vals = ()
    if not vals:
        err = InputError(
            f"--return-periods = {text!r} is invalid: expected comma-separated years, e.g. 1,10,100"
        )
        err.field = "--return-periods"  # type: ignore[attr-defined]
        raise err
    return tuple(sorted(set(vals)))


def run_metocean(
    hindcast_path: Path,
    out: Path,
    *,
    sectors: int | None = None,
    return_periods: tuple[float, ...] = (1.0, 10.0, 100.0),
    storm_rate: float = 3.0,
    r_hours: float = 48.0,
    confidence: float = 0.95,
    ci_method: str = "profile",
    n_bootstrap: int = 200,
    seed: int = 0,
    pipe_heading_deg: float | None = None,
    current_height: float = 1.0,
    figures: bool = True,
    report: bool = True,
) -> dict:
    """Run the analysis (:func:`onbottom.metocean.run.run_metocean_analysis`), write its files
    (:func:`onbottom.metocean.run.write_metocean_outputs`), the figures and the report page;
    returns the JSON payload. ``sectors`` None: 8 when the hindcast has a wave direction column,
    else 1 (omnidirectional) with a note."""
    import importlib.util
    import time

    t0 = time.perf_counter()

    from onbottom.errors import InputError

    missing = [m for m in ("pyextremes", "virocon") if importlib.util.find_spec(m) is None]
    if missing:
        raise InputError(
            f"onbottom metocean needs the optional package(s) {', '.join(missing)}:"
            " pip install 'onbottom[metocean]'"
        )
    from onbottom.metocean.analysis import MetoceanOptions
    from onbottom.metocean.hindcast import read_hindcast
    from onbottom.metocean.run import run_metocean_analysis, write_metocean_outputs
    from onbottom.results import OutputSet, save_figure

    if out.exists() and not out.is_dir():
        err = InputError(f"--out = {str(out)!r} is invalid: it is a file, expected a folder")
        err.field = "--out"  # type: ignore[attr-defined]
        raise err
    hindcast = read_hindcast(hindcast_path)
    chosen = []
    if sectors is None:
        sectors = 8 if hindcast.has_direction else 1
        if not hindcast.has_direction:
            chosen.append(
                "the hindcast has no wave direction column: omnidirectional statistics only"
                " (--sectors 1); give a wave_direction_deg column for direction sectors"
            )
    options = MetoceanOptions(
        sectors=sectors,
        return_periods=return_periods,
        storm_rate=storm_rate,
        r_hours=r_hours,
        confidence=confidence,
        ci_method=ci_method,
        n_bootstrap=n_bootstrap,
        seed=seed,
    )
    run = run_metocean_analysis(
        hindcast,
        options,
        source=str(hindcast_path),
        pipe_heading_deg=pipe_heading_deg,
        current_height=current_height,
    )
    if chosen:
        run.notes[:0] = chosen
    figs: dict[str, str] = {}
    with OutputSet() as group:  # renamed together: a full disk leaves no complete-looking file
        files = [str(f) for f in write_metocean_outputs(run, out, group=group)]
        if figures:
            import matplotlib.pyplot as plt

            from onbottom.plotting.metocean import (
                plot_contours,
                plot_return_levels,
                plot_threshold_choice,
            )

            for name, fig in (
                ("return_levels.png", plot_return_levels(run.result, title=hindcast_path.name)),
                ("contours.png", plot_contours(run.result)),
                ("threshold.png", plot_threshold_choice(run.result)),
            ):
                try:
                    save_figure(fig, out / name, group=group, dpi=110)
                finally:
                    plt.close(fig)
                files.append(str(out / name))
                figs[name.removesuffix(".png")] = name
    if report:
        from onbottom.report.pages import metocean_sections, write_page

        sections, prov = metocean_sections(
            run.result, run.rows, source=hindcast_path, figures=figs, notes=run.notes
        )
        page = write_page(
            out,
            f"Metocean statistics — {hindcast_path.name}",
            sections,
            command=f"onbottom metocean {hindcast_path} --out {out} --sectors {sectors}"
            f" --return-periods {','.join(f'{r:g}' for r in options.return_periods)}",
            inputs=prov,
            run_time=time.perf_counter() - t0,
        )
        files.append(str(page))
    return run.as_dict(files)


@click.command("metocean")
@click.argument("hindcast", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--out",
    "out",
    type=click.Path(file_okay=False, path_type=Path),
    required=True,
    help="Folder for the table, the case fragments, metocean.nc and the figures.",
)
@click.option(
    "--sectors",
    type=Number(int, min=1, max=36),
    default=None,
    help="Equal direction sectors, the first centred on north (1: omnidirectional only)."
    " Default 8, or 1 (with a note) when the hindcast has no wave direction column.",
)
@click.option(
    "--return-periods",
    "return_periods",
    default="1,10,100",
    show_default=True,
    help="Return periods [years], comma-separated (F109's table needs 10 and 100).",
)
@click.option(
    "--storm-rate",
    type=Number(float, min=0.5, max=50.0, unit="1/year"),
    default=3.0,
    show_default=True,
    help="Storms per year above each series' POT threshold (sets the threshold).",
)
@click.option(
    "--r-hours",
    type=Number(float, min=3.0, max=720.0, unit="h"),
    default=48.0,
    show_default=True,
    help="Declustering time [h]: exceedances closer than this are one storm.",
)
@click.option(
    "--confidence",
    type=Number(float, min=0.5, max=1.0, min_open=True, max_open=True),
    default=0.95,
    show_default=True,
    help="Level of the confidence intervals.",
)
@click.option(
    "--ci",
    "ci_method",
    type=click.Choice(["profile", "bootstrap"]),
    default="profile",
    show_default=True,
    help="Confidence intervals: profile likelihood (Coles 2001) or pyextremes' bootstrap.",
)
@click.option(
    "--bootstrap",
    "n_bootstrap",
    type=Number(int, min=20, max=5000),
    default=200,
    show_default=True,
    help="Bootstrap samples per fit (with --ci bootstrap).",
)
@click.option(
    "--seed",
    type=Number(int, min=0, max=2**32 - 1),
    default=0,
    show_default=True,
    help="Seed of the bootstrap.",
)
@click.option(
    "--pipe-heading-deg",
    type=Number(float, min=0.0, max=360.0, unit="deg"),
    default=None,
    help="Pipe axis heading [deg from north]: sets direction_deg of the case fragments.",
)
@click.option(
    "--current-height",
    type=Number(float, min=0.01, max=1000.0, min_open=False, unit="m"),
    default=1.0,
    show_default=True,
    help="Height above the seabed of the hindcast's current [m] (reference_height).",
)
@click.option("--no-figures", is_flag=True, help="Skip the figures.")
@click.option("--no-report", is_flag=True, help="Skip the report page (report.html).")
@json_option
@handle_errors
def command(
    hindcast: Path,
    out: Path,
    sectors: int | None,
    return_periods: str,
    storm_rate: float,
    r_hours: float,
    confidence: float,
    ci_method: str,
    n_bootstrap: int,
    seed: int,
    pipe_heading_deg: float | None,
    current_height: float,
    no_figures: bool,
    no_report: bool,
    as_json: bool,
) -> None:
    """Metocean statistics of HINDCAST (CSV or NetCDF: time, hs, tp, wave_direction_deg,
    current_speed, current_direction_deg; see docs/theory/metocean.md): declustered storms,
    return values per direction sector with confidence intervals (POT/GPD, pyextremes), the
    DNV-RP-C205 H_s–T_p model and IFORM contours (virocon), and the DNV-RP-F109 design table
    per sector.
    """
    payload = run_metocean(
        hindcast,
        out,
        sectors=sectors,
        return_periods=_return_periods(return_periods),
        storm_rate=storm_rate,
        r_hours=r_hours,
        confidence=confidence,
        ci_method=ci_method,
        n_bootstrap=n_bootstrap,
        seed=seed,
        pipe_heading_deg=pipe_heading_deg,
        current_height=current_height,
        figures=not no_figures,
        report=not no_report,
    )
    if as_json:
        emit_json(payload)
        if not payload["success"]:
            raise click.exceptions.Exit(EXIT_INVALID_RESULT)
        return
    rps = payload["return_periods"]
    click.echo(
        f"{payload['hindcast']}: {payload['years']:.1f} years, step {payload['step_hours']:g} h"
    )
    head = "".join(f" {'Hs ' + format(r, 'g') + 'y':>9} {'Tp':>6}" for r in rps)
    has_cur = payload["table"][0]["current"] is not None
    if has_cur:
        head += "".join(f" {'U ' + format(r, 'g') + 'y':>8}" for r in rps)
    click.echo(f"{'sector':<7}{head}")

    def g(x, nd):
        return f"{x:.{nd}f}" if x is not None else "–"

    for r in payload["table"]:
        line = "".join(f" {g(h, 2):>9} {g(t, 1):>6}" for h, t in zip(r["hs"], r["tp"], strict=True))
        if has_cur:
            line += "".join(f" {g(u, 3):>8}" for u in r["current"])
        click.echo(f"{r['sector']:<7}{line}")
    t = payload.get("tail")
    if t:
        ex = t["exponential"]
        vals = ", ".join(
            f"{r:g}y {g(v, 2)} [{g(a, 2)}, {g(b, 2)}]"
            for r, v, a, b in zip(rps, ex["value"], ex["lower"], ex["upper"], strict=True)
        )
        click.echo(f"omni H_s, exponential tail (xi = 0) beside the GPD: {vals}")
        c = t["censored_fit"]
        if c:
            vals = ", ".join(
                f"{r:g}y {g(v, 2)} [{g(a, 2)}, {g(b, 2)}]"
                for r, v, a, b in zip(rps, c["value"], c["lower"], c["upper"], strict=True)
            )
            click.echo(f"omni H_s, censored storms as censored (xi = {c['shape']:.2f}): {vals}")
    cc = payload.get("contour_check")
    if cc:
        lv = ", ".join(
            f"{r['hs']:.2f} m {r['empirical']:.1e}/{r['fitted']:.1e}" for r in cc["levels"]
        )
        click.echo(
            f"{cc['return_period']:g}-year contour max H_s {cc['contour_max_hs']:.2f} m ="
            f" {cc['ratio']:.2f} x POT {cc['pot_value']:.2f} m (alpha {cc['alpha']:.1e} per"
            f" state; MLE Weibull: {cc['mle_contour_max_hs']:.2f} m); H_s exceedance"
            f" empirical/fitted: {lv}"
        )
        tz = cc["tp_at_peaks"]
        click.echo(
            f"T_p | H_s at the {tz['n']} storm peaks: mean z {tz['mean_z']:+.2f} SD (< 0: the"
            f" model's T_p too long), KS {tz['ks']:.2f} (p = {tz['ks_p']:.2g})"
        )
    for n in payload["notes"]:
        click.echo(f"note: {n}", err=True)
    click.echo(f"written to {out}: {len(payload['files'])} files")
    if not payload["success"]:
        click.echo("NOT VALID: no return values for the whole record (too few storms)", err=True)
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
