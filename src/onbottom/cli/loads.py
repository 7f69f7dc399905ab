"""``onbottom loads``: V–H envelope of the peak hydrodynamic loads per wave cycle."""

from __future__ import annotations

import warnings
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

__all__ = ["command", "evaluate_loads"]


def evaluate_loads(
    case_path: Path, *, seed: int | None, duration_hours: float
) -> tuple[dict, list]:
    """Envelopes of every load combination of a case file: (JSON payload, envelopes)."""
    from onbottom.cases.stability import load_stability_case, penetration_outside_validity
    from onbottom.checks.design import CheckOptions, run_checks
    from onbottom.cli.stability import check_reference_height
    from onbottom.errors import InputError, OutOfRangeWarning
    from onbottom.hydro.forces import MorisonCoefficients
    from onbottom.hydro.load_envelope import load_envelope

    caught: list[warnings.WarningMessage] = []
    with warnings.catch_warnings(record=True) as loading:
        warnings.simplefilter("always", OutOfRangeWarning)
        case = load_stability_case(case_path)
        section = case.section()
        seabed = case.seabed.seabed()
        env = case.environment_object()
        combos = case.load_combinations()
    check_reference_height(case, case_path, seabed)
    caught.extend(loading)
    storm_seed = 0
    if case.storm is not None:  # the [storm] table of a shared file: strict, as for `storm`
        from onbottom._casefile import parse_case
        from onbottom.cases.storm import StormTable

        storm_seed = parse_case(
            StormTable,
            case.storm,
            file=case_path,
            text=Path(case_path).read_text(encoding="utf-8"),
            root="storm",
        ).seed
    if seed is None:
        seed = storm_seed
    h = case.hydro
    coef = MorisonCoefficients(drag=h.cd, inertia=h.cm, lift=h.cl)
    options = CheckOptions(
        vertical_conditions=(),
        penetration=case.seabed.initial_penetration,
        trench_depth=case.seabed.trench_depth,
        trench_angle_deg=case.seabed.trench_angle_deg,
        permeable=case.design.permeable,
    )
    out: list[dict[str, Any]] = []
    envs = []
    from onbottom.inputs.consistency import warnings_reported_by_case

    with warnings.catch_warnings(record=True) as checking, warnings_reported_by_case():
        warnings.simplefilter("always", OutOfRangeWarning)
        rows = run_checks(section, seabed, env, combos, options)
    caught.extend(checking)
    invalid = penetration_outside_validity(rows)
    by_combo = {r.combination: r.details for r in rows if r.name == "absolute_lateral"}
    for combo in combos:
        det = by_combo[combo.name]
        if "diameter" not in det:
            err = InputError(
                f"pipe = (condition {combo.condition!r}) is invalid for combination"
                f" {combo.name!r}: the pipe floats (submerged weight"
                f" {det.get('submerged_weight', float('nan')):.4g} N/m <= 0); check the densities"
                " and the contents of that condition"
            )
            err.field = "pipe"  # type: ignore[attr-defined]
            raise err
        r_y, r_z = (det["r_y"], det["r_z"]) if h.reductions else (1.0, 1.0)
        ss = combo.sea_state
        with warnings.catch_warnings(record=True) as enveloping:
            warnings.simplefilter("always", OutOfRangeWarning)
            e = load_envelope(
                hs=ss.hs,
                tp=ss.tp,
                depth=env.water_depth,
                diameter=det["diameter"],
                submerged_weight=det["submerged_weight"],
                current=det["v_star"],
                gamma=ss.gamma,
                spectrum=ss.spectrum,
                wave_direction_deg=ss.direction_deg,
                spreading_s=ss.spreading_s or None,
                coefficients=coef,
                r_y=r_y,
                r_z=r_z,
                density=env.water_density,
                duration=duration_hours * 3600.0,
                seed=seed,
            )
        caught.extend(enveloping)
        envs.append(e)
        out.append(
            {
                "combination": combo.name,
                "condition": combo.condition,
                "hs": ss.hs,
                "tp": ss.tp,
                "n_cycles": e.n_cycles,
                "fraction_20_45": e.fraction_between(20.0, 45.0),
                "max_horizontal": float(e.horizontal.max()) if e.n_cycles else None,
                "min_vertical": float(e.vertical.min()) if e.n_cycles else None,
                "max_angle_deg": float(e.angle_deg.max()) if e.n_cycles else None,
                "submerged_weight": e.submerged_weight,
                "r_y": r_y,
                "r_z": r_z,
            }
        )
    payload = {
        "case": str(case_path),
        "seed": seed,
        "duration": duration_hours * 3600.0,
        "coefficients": {"cd": h.cd, "cm": h.cm, "cl": h.cl},
        "combinations": out,
        "success": not invalid,
        "message": "; ".join(invalid),
        "warnings": sorted(
            {str(w.message) for w in caught if issubclass(w.category, OutOfRangeWarning)}
        ),
    }
    return payload, envs


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
    payload, envs = evaluate_loads(case, seed=seed, duration_hours=duration_hours)
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
