"""``onbottom backbone``: Verley & Sotberg backbone (region limits, F_r1/F_r2/F_r3, z_i, z3).

Optionally drives the model along a cyclic displacement path to show penetration growth and
writes the backbone (and path) plots.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import click

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
)
from onbottom.errors import InputError
from onbottom.inputs import Pipe, Sand

__all__ = ["command"]

_KN = 1.0e3
_POINTS_PER_CYCLE = 400  # soil.response.cyclic_path default
_BYTES_PER_POINT = 160  # measured peak 72 B/point (tracemalloc, 1e5 points) + room for plots
MAX_PATH_BYTES = 2 * 1024**3
"""Largest memory a --cycles path may take (estimated up front; larger requests are refused)."""

_POS = Number(float, min=0.0, min_open=True)


@click.command("backbone")
@click.option(
    "--model",
    "variant",
    type=click.Choice(["silica", "calcareous", "f109"]),
    default="silica",
    show_default=True,
    help="silica: Verley & Sotberg (1994); calcareous: Youssef & Cassidy (2014); "
    "f109: silica with the DNV-RP-F109 §3.4.6 passive law.",
)
@click.option("--diameter", type=_POS, required=True, help="Pipe outer diameter D [m] (required).")
@click.option(
    "--weight-kn",
    type=_POS,
    required=True,
    help="Vertical contact load V = W_s − F_L [kN/m] (submerged weight when F_L = 0).",
)
@click.option(
    "--load-kn",
    type=_POS,
    default=None,
    help="Installation load W for z_i (Eq 7) [kN/m]; default --weight-kn.",
)
@click.option(
    "--gamma-kn",
    type=Number(float, min=1.0, max=25.0, unit="kN/m³"),
    required=True,
    help="Submerged unit weight γ' [kN/m³].",
)
@click.option(
    "--mu",
    type=Number(float, min=0.0, max=2.0, min_open=True),
    default=0.6,
    show_default=True,
    help="Friction μ [-].",
)
@click.option(
    "--A",
    "a_factor",
    type=Number(float, min=0.0, max=10.0, min_open=True),
    default=None,
    help="Factor A (default by model).",
)
@click.option(
    "--B",
    "b_factor",
    type=Number(float, min=0.0, max=10.0, min_open=True),
    default=None,
    help="Factor B (default by model).",
)
@click.option(
    "--C",
    "c_factor",
    type=Number(float, min=0.0, max=10.0, min_open=True),
    default=None,
    help="Factor C (default by model).",
)
@click.option(
    "--z2-over-d",
    type=Number(float, min=0.0, max=1.0),
    default=None,
    help="Penetration at breakout z2/D [-] for the backbone; default z_i/D.",
)
@click.option(
    "--cycles",
    type=_POS,
    default=None,
    help="Drive a sinusoidal displacement path of this many cycles (penetration path).",
)
@click.option(
    "--amplitude",
    type=_POS,
    default=None,
    help="Amplitude of the cyclic path [m]; default 0.1·D.",
)
@click.option(
    "--plot",
    "plot_path",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write the backbone plot here (PNG/PDF/SVG); the path plot gets suffix _path.",
)
@json_option
@handle_errors
def command(
    variant: str,
    diameter: float,
    weight_kn: float,
    load_kn: float | None,
    gamma_kn: float,
    mu: float,
    a_factor: float | None,
    b_factor: float | None,
    c_factor: float | None,
    z2_over_d: float | None,
    cycles: float | None,
    amplitude: float | None,
    plot_path: Path | None,
    as_json: bool,
) -> None:
    """Backbone of the Verley & Sotberg model: region limits, forces, penetrations.

    Example: onbottom backbone --model calcareous --diameter 1.0 --weight-kn 10.52
    --load-kn 42.98 --gamma-kn 7.5 --mu 0.48 --cycles 5 --plot bb.png
    """
    if cycles is not None:
        need = cycles * _POINTS_PER_CYCLE * _BYTES_PER_POINT
        if need > MAX_PATH_BYTES:
            err = InputError(
                f"--cycles = {cycles:g} is invalid: the path of {cycles * _POINTS_PER_CYCLE:.3g}"
                f" points would need about {need / 1024**3:.3g} GiB of memory, more than the"
                f" {MAX_PATH_BYTES / 1024**3:g} GiB allowed (at most"
                f" {MAX_PATH_BYTES / (_POINTS_PER_CYCLE * _BYTES_PER_POINT):.0f} cycles)"
            )
            err.field = "--cycles"  # type: ignore[attr-defined]
            raise err
    if plot_path is not None:
        check_output_path(plot_path, field="--plot")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        payload, validity = _run(
            variant,
            diameter,
            weight_kn,
            load_kn,
            gamma_kn,
            mu,
            {"A": a_factor, "B": b_factor, "C": c_factor},
            z2_over_d,
            cycles,
            amplitude,
            plot_path,
        )
    messages = list(dict.fromkeys(str(w.message) for w in caught))
    payload["warnings"] = messages
    payload["success"] = not validity
    payload["message"] = (
        "outside the model's validity: " + "; ".join(validity) if validity else "ok"
    )
    if as_json:
        emit_json(payload)
    else:
        _print_table(payload, diameter)
        for msg in messages:
            click.echo(f"warning: {msg}", err=True)
        if validity:
            click.echo(f"Error: {payload['message']}", err=True)
    if validity:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)


def _run(
    variant: str,
    diameter: float,
    weight_kn: float,
    load_kn: float | None,
    gamma_kn: float,
    mu: float,
    abc: dict[str, float | None],
    z2_over_d: float | None,
    cycles: float | None,
    amplitude: float | None,
    plot_path: Path | None,
) -> tuple[dict, list[str]]:
    """Options in kN → SI, :func:`onbottom.soil.backbone.backbone_run`, the plots; returns the
    payload and the validity notes."""
    from onbottom.soil.backbone import backbone_run

    v = weight_kn * _KN
    run = backbone_run(
        variant,
        Pipe(outer_diameter=diameter, submerged_weight=v),
        Sand(submerged_unit_weight=gamma_kn * _KN, friction_coefficient=mu),
        installation_load=None if load_kn is None else load_kn * _KN,
        factors=abc,
        penetration=None if z2_over_d is None else z2_over_d * diameter,
        cycles=cycles,
        amplitude=amplitude,
    )
    payload = run.as_dict()
    if plot_path is not None:
        from onbottom.plotting.backbone import plot_backbone, plot_path_response

        title = f"Verley & Sotberg ({variant}), V = {weight_kn:g} kN/m"
        plot_backbone(run.points, diameter=diameter, title=title).savefig(plot_path, dpi=150)
        payload["plots"] = [str(plot_path)]
        if run.path is not None:
            p2 = plot_path.with_name(plot_path.stem + "_path" + plot_path.suffix)
            plot_path_response(run.path, diameter=diameter).savefig(p2, dpi=150)
            payload["plots"].append(str(p2))
    return payload, run.validity()


def _print_table(payload: dict, d: float) -> None:
    pts = payload["backbone"]
    variant = payload["model"]
    click.echo(f"Verley & Sotberg backbone ({variant}); SI inputs converted from kN")
    rows = [
        ("K_s = γ'D²/V", f"{pts['K_s']:.6g}", "-"),
        ("y1 (elastic)", f"{pts['y1']:.6g}", f"m  ({pts['y1'] / d:.4g} D)"),
        ("y2 (accumulation)", f"{pts['y2']:.6g}", f"m  ({pts['y2'] / d:.4g} D)"),
        ("y3 (breakout)", f"{pts['y3']:.6g}", f"m  ({pts['y3'] / d:.4g} D)"),
        ("z_i (Eq 7)", f"{pts['z_i']:.6g}", f"m  ({pts['z_i'] / d:.5g} D)"),
        ("z2", f"{pts['z2']:.6g}", f"m  ({pts['z2'] / d:.5g} D)"),
        ("z3 (Eqs 9-10)", f"{pts['z3']:.6g}", f"m  ({pts['z3'] / d:.5g} D)"),
        ("F_r1 = 0.3 F_r2", f"{pts['F_r1'] / _KN:.6g}", "kN/m"),
        ("F_r2 (Eqs 3-4)", f"{pts['F_r2'] / _KN:.6g}", "kN/m"),
        ("F_r3", f"{pts['F_r3'] / _KN:.6g}", "kN/m"),
        ("F_f = μV", f"{pts['F_f'] / _KN:.6g}", "kN/m"),
    ]
    for name, val, unit in rows:
        click.echo(f"  {name:<20} {val:>12}  {unit}")
    if "path" in payload:
        p = payload["path"]
        click.echo(
            f"  cyclic path: {p['cycles']:g} cycles of ±{p['amplitude']:.4g} m →"
            f" z = {p['final_penetration']:.6g} m ({p['final_penetration'] / d:.5g} D),"
            f" max |R| = {p['max_resistance'] / _KN:.4g} kN/m"
        )
    for path in payload.get("plots", []):
        click.echo(f"  plot written: {path}")
