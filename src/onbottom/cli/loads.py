"""``onbottom loads``: V–H envelope of the peak hydrodynamic loads per wave cycle.

Case file: :mod:`onbottom.cases.stability`; computation:
:func:`onbottom.checks.loads.combination_loads`; this module prints, plots or writes."""

from __future__ import annotations

import warnings
from pathlib import Path

import click

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    emit_json,
    handle_errors,
    json_option,
)

__all__ = ["command"]


def _evaluate(case_path: Path, *, seed: int | None, duration_hours: float) -> tuple[dict, list]:
    """The JSON payload of a case file and the envelopes: the cycle peak loads of every load
    combination (:func:`onbottom.checks.loads.combination_loads` on the inputs built by
    :mod:`onbottom.cases.stability`) and every :class:`OutOfRangeWarning` raised on the way."""
    from onbottom.cases.stability import build_loads_inputs, load_stability_case
    from onbottom.checks.loads import combination_loads
    from onbottom.errors import OutOfRangeWarning
    from onbottom.inputs.consistency import warnings_reported_by_case

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        inputs = build_loads_inputs(load_stability_case(case_path), case_path)
        # the absolute check's consistency warnings were issued by the case, with the line
        with warnings_reported_by_case():
            result = combination_loads(inputs, duration=duration_hours * 3600.0, seed=seed)
    h = inputs.coefficients
    payload = {
        "case": str(case_path),
        "seed": result.seed,
        "duration": duration_hours * 3600.0,
        "coefficients": {"cd": h.drag, "cm": h.inertia, "cl": h.lift},
        "combinations": [c.as_dict() for c in result.combinations],
        "success": result.success,
        "message": result.message,
        "warnings": sorted(
            {str(w.message) for w in caught if issubclass(w.category, OutOfRangeWarning)}
        ),
    }
    return payload, result.envelopes


def _check_outputs(case: Path, plot: Path | None, output: Path | None) -> None:
    """Refuse output names that would overwrite the case file or each other, or a wrong kind."""
    from onbottom.errors import InputError

    def fail(field: str, message: str) -> None:
        err = InputError(message)
        err.field = field  # type: ignore[attr-defined]
        raise err

    if plot is not None and plot.suffix.lower() not in (".png", ".pdf", ".svg"):
        fail(
            "--plot",
            f"--plot = {str(plot)!r} is invalid: the file name must end in .png, .pdf or .svg",
        )
    if output is not None and output.suffix.lower() != ".nc":
        fail("--output", f"--output = {str(output)!r} is invalid: the file name must end in .nc")
    same = [
        (name, p)
        for name, p in (("--plot", plot), ("--output", output))
        if p is not None and p.resolve() == case.resolve()
    ]
    for name, p in same:
        fail(name, f"{name} = {str(p)!r} is invalid: it would overwrite the case file")
    if plot is not None and output is not None and plot.resolve() == output.resolve():
        fail("--output", f"--output = {str(output)!r} is invalid: the same file as --plot")


@click.command("loads")
@click.argument("case", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--plot",
    "plot",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write the V–H figure to this file (png, pdf, svg).",
)
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write the cycle peaks (NetCDF, dims combination × cycle) to this file.",
)
@click.option(
    "--seed",
    type=Number(int, min=0, max=2**32 - 1),
    default=None,
    help="Random-phase seed (default: [storm] seed, else 0).",
)
@click.option(
    "--duration-hours",
    type=Number(float, min=0.1, max=100.0, unit="h"),
    default=3.0,
    show_default=True,
    help="Length of the simulated record [h] (F109 design sea state: 3 h).",
)
@json_option
@handle_errors
def command(
    case: Path,
    plot: Path | None,
    output: Path | None,
    seed: int | None,
    duration_hours: float,
    as_json: bool,
) -> None:
    """Peak hydrodynamic loads of every wave cycle of each load combination of CASE (TOML),
    in V–H space (H = |F_Y|, V = w_s − F_Z), and the fraction of cycles whose load angle from
    the V axis lies between 20° and 45° (Youssef & Cassidy 2014, Fig. 4).

    Loads: Morison drag + inertia and lift with [hydro] cd, cm, cl on the pipe at rest, with
    the F109 load reductions of the absolute check when [hydro] reductions = true.
    """
    _check_outputs(case, plot, output)
    payload, envs = _evaluate(case, seed=seed, duration_hours=duration_hours)
    if plot is not None:
        from onbottom.cli._common import check_output_path
        from onbottom.plotting.load_envelope import plot_load_envelope

        check_output_path(plot, field="--plot")
        fig = plot_load_envelope(
            envs,
            [c["combination"] for c in payload["combinations"]],
            title=f"{case.stem}: peak loads per wave cycle, seed {payload['seed']}",
        )
        from onbottom.results import save_figure

        save_figure(fig, plot, dpi=110)
        payload["plot"] = str(plot)
    if output is not None:
        from onbottom.cli._common import check_output_path
        from onbottom.hydro.load_envelope import envelopes_dataset
        from onbottom.results import save_dataset

        check_output_path(output, field="--output")
        ds = envelopes_dataset(
            envs, [c["combination"] for c in payload["combinations"]], case=str(case)
        )
        save_dataset(ds, output)
        payload["output"] = str(output)
    if as_json:
        emit_json(payload)
        if not payload["success"]:
            raise click.exceptions.Exit(EXIT_INVALID_RESULT)
        return
    for w in payload["warnings"]:
        click.echo(f"warning: {w}", err=True)
    click.echo(
        f"{'combination':<40} {'cycles':>6} {'20–45°':>7} {'max H (kN/m)':>13} {'min V (kN/m)':>13}"
    )
    for c in payload["combinations"]:
        mh = c["max_horizontal"] / 1e3 if c["max_horizontal"] is not None else float("nan")
        mv = c["min_vertical"] / 1e3 if c["min_vertical"] is not None else float("nan")
        click.echo(
            f"{c['combination'][:40]:<40} {c['n_cycles']:>6d} {100 * c['fraction_20_45']:>6.1f}%"
            f" {mh:>13.3f} {mv:>13.3f}"
        )
    click.echo(
        "note: these are Morison peaks of a 3-h record with the [hydro] coefficients (default"
        " C_D 0.7, C_L 0.9); F109's absolute check uses its peak-load coefficients C*_Y, C*_Z"
        " (Tables 3-9/3-10, derived with a wake model) at the design oscillation U*, which are"
        " about 2.5x larger at K* 50-80 (docs/theory/storm_section.md, 'Absolute check vs"
        ' dynamic storm\'); [hydro] model = "wake" gives F109-calibrated peaks in `storm`.'
    )
    if plot is not None:
        click.echo(f"figure: {plot}")
    if output is not None:
        click.echo(f"cycle peaks: {output}")
    if not payload["success"]:
        click.echo(f"NOT VALID: {payload['message']}", err=True)
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
