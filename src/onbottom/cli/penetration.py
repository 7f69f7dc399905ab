"""``onbottom penetration`` — DNVGL-RP-F114 vertical penetration resistance and embedment."""

from __future__ import annotations

import warnings
from typing import Any

import click
import numpy as np

from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
)
from onbottom.errors import InputError, OutOfRangeWarning, SolutionError
from onbottom.soil.penetration_clay import DEFAULT_ROUGHNESS
from onbottom.soil.penetration_f114 import LayConditions
from onbottom.soil.penetration_sand import DEPTH_FACTOR_COEFFICIENT, N_GAMMA_METHODS, DrainedBounds
from onbottom.soil.penetration_table import drained_estimates, penetration_run, undrained_model

__all__ = ["command"]

_KN = 1.0e3
_POS = Number(float, min=0.0, min_open=True)


def _parse_levels(text: str) -> np.ndarray:
    try:
        levels = np.array([float(t) for t in text.split(",") if t.strip()], dtype=float)
    except ValueError as exc:
        raise InputError(
            f"--at = {text!r} is invalid: expected comma-separated z/D values in (0, 1]"
        ) from exc
    if levels.size == 0 or np.any(levels < 0.0) or np.any(levels > 1.0):
        raise InputError(f"--at = {text!r} is invalid: z/D values must lie in [0, 1]")
    return levels


def _build_models(opts: dict[str, Any]) -> tuple[Any, DrainedBounds | None]:
    """Options (kN, kPa) → SI → :func:`onbottom.soil.penetration_table.drained_estimates` or
    :func:`~onbottom.soil.penetration_table.undrained_model`."""
    d = opts["diameter"]
    gamma = opts["gamma_kn"] * _KN
    if opts["soil"] == "sand":
        if opts["phi_deg"] is None:
            raise InputError(
                "--phi-deg is required with --soil sand: best-estimate friction angle φ' [deg],"
                " allowed 15–50"
            )
        return drained_estimates(
            diameter=d,
            unit_weight=gamma,
            friction_angle_deg=opts["phi_deg"],
            lower_friction_angle_deg=opts["phi_lower_deg"],
            upper_friction_angle_deg=opts["phi_upper_deg"],
            n_gamma=opts["n_gamma"],
            lower_n_gamma=opts["lower_n_gamma"],
            upper_n_gamma=opts["upper_n_gamma"],
            depth_factor_coefficient=opts["depth_coefficient"],
        )
    if opts["su_kpa"] is None:
        raise InputError("--su-kpa = None is invalid: required for --soil clay [kPa]")
    model = undrained_model(
        opts["model"],
        diameter=d,
        su_mudline=opts["su_kpa"] * _KN,
        su_gradient=opts["su_gradient_kpa"] * _KN,
        unit_weight=gamma,
        roughness=opts["roughness"],
    )
    return model, None


@click.command("penetration")
@click.option(
    "--soil",
    type=click.Choice(["sand", "clay"]),
    default="sand",
    show_default=True,
    help="Drained sand (F114 Eq 4.9) or undrained clay (Model 1 or 2).",
)
@click.option("--diameter", type=_POS, required=True, help="Pipe outer diameter D [m].")
@click.option(
    "--gamma-kn",
    type=Number(float, min=1.0, max=25.0, unit="kN/m³"),
    required=True,
    help="Effective (submerged; dry for dry centrifuge sand) unit weight γ' [kN/m³].",
)
@click.option(
    "--phi-deg",
    type=Number(float, min=15.0, max=50.0, unit="deg"),
    default=None,
    help="Sand: friction angle φ' [deg].",
)
@click.option(
    "--phi-lower-deg",
    type=Number(float, min=15.0, max=50.0, unit="deg"),
    default=None,
    help="Sand: φ' of the lower estimate [deg] (e.g. φ_cv); default --phi-deg.",
)
@click.option(
    "--phi-upper-deg",
    type=Number(float, min=15.0, max=50.0, unit="deg"),
    default=None,
    help="Sand: φ' of the upper estimate [deg] (e.g. peak); default --phi-deg.",
)
@click.option(
    "--n-gamma",
    "--nq-gamma",
    "n_gamma",
    type=click.Choice(N_GAMMA_METHODS),
    default="davis_booker_rough",
    show_default=True,
    help="Sand: N_γ expression of the best estimate.",
)
@click.option(
    "--lower-n-gamma",
    type=click.Choice(N_GAMMA_METHODS),
    default="davis_booker_smooth",
    show_default=True,
    help="Sand: N_γ of the lower estimate.",
)
@click.option(
    "--upper-n-gamma",
    type=click.Choice(N_GAMMA_METHODS),
    default="davis_booker_rough",
    show_default=True,
    help="Sand: N_γ of the upper estimate.",
)
@click.option(
    "--depth-coefficient",
    type=Number(float, min=0.0, max=10.0),
    default=DEPTH_FACTOR_COEFFICIENT,
    show_default=True,
    help="Sand: coefficient of the depth factor d_q (F114 1.2; Brinch Hansen 2).",
)
@click.option("--su-kpa", type=_POS, default=None, help="Clay: s_u at the mudline [kPa].")
@click.option(
    "--su-gradient-kpa",
    type=Number(float, min=0.0, max=1.0e4),
    default=0.0,
    show_default=True,
    help="Clay: s_u gradient ρ [kPa/m].",
)
@click.option(
    "--model",
    type=click.Choice(["1", "2"]),
    default="1",
    show_default=True,
    help="Clay: F114 Model 1 (bearing capacity) or 2 (empirical soft clay).",
)
@click.option(
    "--roughness",
    type=Number(float, min=0.0, max=1.0),
    default=DEFAULT_ROUGHNESS,
    show_default=True,
    help="Clay Model 1: pipe roughness r in [0, 1].",
)
@click.option(
    "--at",
    "levels",
    default="0.1,0.2,0.3,0.4,0.5",
    show_default=True,
    help="Comma-separated z/D values for the table.",
)
@click.option("--load-kn", type=_POS, default=None, help="Vertical load W [kN/m]: embedment.")
@click.option("--ei", type=_POS, default=None, help="Lay factor: bending stiffness EI [N·m²].")
@click.option("--tension-kn", type=_POS, default=None, help="Lay factor: bottom tension [kN].")
@click.option(
    "--plot", "plot_path", type=click.Path(dir_okay=False), default=None, help="Save a V–w plot."
)
@click.option(
    "--save",
    "save_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Save the Q_v(z) curve as NetCDF.",
)
@json_option
@handle_errors
def command(**opts: Any) -> None:
    """DNVGL-RP-F114 vertical penetration resistance Q_v(z) and the embedment for a load.

    Sand: Q_v from F114 Eq 4.9 with the chosen N_γ, plus lower/upper estimates (lower: φ_lower
    with Davis & Booker smooth N_γ; upper: φ_upper with Davis & Booker rough N_γ — onbottom's
    documented definition). Clay: Model 1 (Eqs 4.1–4.2) or Model 2 (Eq 4.8). With --load-kn,
    solves Q_v(z) = k_lay·W on 0 < z <= D; give --ei and --tension-kn to apply the lay factor.
    """
    levels = _parse_levels(opts["levels"])
    for key, option in (("plot_path", "--plot"), ("save_path", "--save")):
        if opts[key]:
            check_output_path(opts[key], field=option)
    lay = None
    if (opts["ei"] is None) != (opts["tension_kn"] is None):
        raise InputError("--ei and --tension-kn are invalid: give both or neither")
    if opts["ei"] is not None:
        lay = LayConditions(bending_stiffness=opts["ei"], bottom_tension=opts["tension_kn"] * _KN)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        model, bounds = _build_models(opts)
        d = model.diameter
        try:
            run = penetration_run(
                model,
                levels,
                bounds=bounds,
                load=None if opts["load_kn"] is None else opts["load_kn"] * _KN,
                lay=lay,
                curve=bool(opts["plot_path"] or opts["save_path"]),
            )
        except SolutionError as exc:
            exc.field = "--load-kn"  # type: ignore[attr-defined]
            raise
    messages = list(dict.fromkeys(str(w.message) for w in caught))
    embedment, validity, curve = run.embedment, run.validity, run.curve
    emb = run.embedment_dict()

    if curve is not None and opts["save_path"]:
        from onbottom.results import save_dataset

        save_dataset(curve, opts["save_path"])
    if curve is not None and opts["plot_path"]:
        from onbottom.plotting.penetration import plot_penetration_curve

        fig, _ = plot_penetration_curve(curve)
        fig.savefig(opts["plot_path"], dpi=150)

    rows = run.rows()

    if opts["as_json"]:
        payload: dict[str, Any] = {
            "model": model.name,
            "parameters": model.parameters(),
            "units": {"z": "m", "B": "m", "Q_v": "N/m", "load": "N/m"},
            "table": rows,
            "embedment": emb,
            "warnings": messages,
        }
        if bounds is not None:
            payload["bounds"] = bounds.parameters()
        emit_json(payload)
        if validity:
            raise click.exceptions.Exit(EXIT_INVALID_RESULT)
        return

    for msg in messages:
        click.echo(f"warning: {msg}", err=True)
    click.echo(f"DNVGL-RP-F114 vertical penetration — {model.name}, D = {d:g} m")
    if bounds is not None:
        click.echo(
            f"  estimate: φ' = {model.friction_angle_deg:g}°, N_γ = {model.n_gamma}"
            f" ({model.n_gamma_value:.1f})"
        )
        click.echo(
            f"  lower:    φ' = {bounds.lower.friction_angle_deg:g}°, N_γ = "
            f"{bounds.lower.n_gamma} ({bounds.lower.n_gamma_value:.1f})"
        )
        click.echo(
            f"  upper:    φ' = {bounds.upper.friction_angle_deg:g}°, N_γ = "
            f"{bounds.upper.n_gamma} ({bounds.upper.n_gamma_value:.1f})"
        )
    header = f"{'z/D':>6} {'z (m)':>9} {'B (m)':>8} {'Q_v (kN/m)':>11}"
    if "Q_v_lower" in rows:
        header += f" {'lower':>9} {'upper':>9}"
    click.echo(header)
    for i in range(levels.size):
        line = (
            f"{rows['z_over_D'][i]:6.3f} {rows['z'][i]:9.4f} {rows['B'][i]:8.4f} "
            f"{rows['Q_v'][i] / _KN:11.2f}"
        )
        if "Q_v_lower" in rows:
            line += f" {rows['Q_v_lower'][i] / _KN:9.2f} {rows['Q_v_upper'][i] / _KN:9.2f}"
        click.echo(line)
    if embedment is not None:
        click.echo(
            f"embedment: z = {embedment.z:.4f} m (z/D = {embedment.z_over_d:.4f}) for "
            f"W = {embedment.load / _KN:g} kN/m, k_lay = {embedment.lay_factor:.3f}, "
            f"Q_v = {embedment.resistance / _KN:.3f} kN/m; {emb['message']}"
        )
    if validity:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)
