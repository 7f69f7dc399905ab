"""``onbottom curves``: F109-style generalized-stability curves from dynamic storm analyses.

Reads the ``[curves]`` table (grid and settings) and the optional ``[hydro]`` and
``[environment]`` tables of a case file, bisects L_stable and L_10 on the grid
(:func:`onbottom.study.stability_curves.stability_curves`) on Dask, and writes a NetCDF file,
a CSV table and a figure of L/(2 + M)² against K.

Case file::

    [curves]
    K = [5.0, 10.0, 20.0, 40.0]
    M = [0.0, 0.2, 0.4, 0.8]
    N = [0.003]
    soils = ["sand", "clay"]
    seeds = 5
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path
from typing import Annotated, Any, Literal

import click
from pydantic import Field, field_validator

from onbottom._casefile import StrictModel, load_case_file, read_toml
from onbottom.cases.stability import EnvironmentTable, HydroTable
from onbottom.cli._common import (
    EXIT_INVALID_RESULT,
    Number,
    check_output_names,
    check_output_path,
    emit_json,
    handle_errors,
    json_option,
    log_to_stderr,
)
from onbottom.errors import OutOfRangeWarning

#: Grid ranges [I]: F109's generalized-stability tables (§3.5; Tables 3-9/3-10 are the
#: absolute method's peak-load coefficients, not these) span K from 5 to 160; K up to 1000 and
#: M up to 100 are accepted for exploration, and every (K, N) must give a sea state with
#: H_s <= 30 m and T_p <= 40 s (checked before running).
KValue = Annotated[float, Field(gt=0.0, le=1000.0)]
MValue = Annotated[float, Field(ge=0.0, le=100.0)]
NValue = Annotated[float, Field(gt=0.0, le=0.2)]


class CurvesTable(StrictModel):
    K: list[KValue] = Field(
        min_length=1, description="Keulegan–Carpenter numbers K [-], each in (0, 1000], distinct"
    )
    M: list[MValue] = Field(
        min_length=1, description="current ratios M = V/U_s [-], each in [0, 100], distinct"
    )
    N: list[NValue] = Field(
        default_factory=lambda: [0.003],
        min_length=1,
        description="N = U_s/(g T_u) [-], each in (0, 0.2], distinct",
    )
    soils: list[Literal["sand", "clay"]] = Field(default_factory=lambda: ["sand", "clay"])
    criteria: list[Literal["L_stable", "L_10"]] = Field(
        default_factory=lambda: ["L_stable", "L_10"]
    )
    seeds: int = Field(5, ge=1, le=1000, description="storms per evaluation [-]")
    first_seed: int = Field(0, ge=0, description="[-]")
    build_up_hours: float = Field(0.5, ge=0.0, le=100.0, description="[h]")
    peak_hours: float = Field(3.0, gt=0.0, le=100.0, description="[h]")
    tolerance: float = Field(0.02, gt=0.0, le=0.5, description="relative L bracket [-]")
    l_min: float = Field(1.0, gt=0.0, description="initial L bracket low [-]")
    l_max: float = Field(300.0, gt=0.0, description="initial L bracket high [-]")
    diameter: float = Field(0.5, ge=0.005, le=5.0, description="D [m], in [0.005, 5]")
    time_step: float = Field(0.1, gt=0.0, le=5.0, description="largest step [s]")
    gamma: float = Field(3.3, ge=1.0, le=7.0, description="JONSWAP γ [-]")
    tn_over_tp: float = Field(0.1, gt=0.0, le=1.0, description="T_n/T_p [-]")
    sand_unit_weight: float = Field(
        10.0e3, ge=1.0e3, le=2.0e4, description="γ'_s [N/m³] (not kN/m³), in [1000, 20000]"
    )
    sand_friction: float = Field(0.6, gt=0.0, le=2.0, description="μ [-]")
    clay_gc: float = Field(0.222, gt=0.0, le=10.0, description="G_c = s_u/(D γ_s) [-]")
    clay_unit_weight: float = Field(
        18.0e3, ge=1.0e4, le=3.0e4, description="γ_s [N/m³] (not kN/m³), in [10000, 30000]"
    )
    clay_submerged_unit_weight: float = Field(
        8.0e3, ge=1.0e3, le=2.0e4, description="γ' [N/m³] (not kN/m³), in [1000, 20000]"
    )
    clay_friction: float = Field(0.2, gt=0.0, le=2.0, description="μ [-]")

    @field_validator("K", "M", "N", "soils", "criteria")
    @classmethod
    def _distinct(cls, values: list[Any]) -> list[Any]:
        seen: set[Any] = set()
        for v in values:
            if v in seen:
                raise ValueError(f"the value {v!r} is repeated: give each value once")
            seen.add(v)
        return values


class CurvesCase(StrictModel):
    curves: CurvesTable
    hydro: HydroTable = HydroTable()
    environment: EnvironmentTable | None = None
    # other tables of a shared case file are accepted and not used here
    pipe: dict[str, Any] | None = None
    seabed: dict[str, Any] | None = None
    waves: dict[str, Any] | None = None
    current: dict[str, Any] | None = None
    storm: dict[str, Any] | None = None
    solver: dict[str, Any] | None = None
    run: dict[str, Any] | None = None
    pipeline: dict[str, Any] | None = None
    combinations: list[Any] | None = None
    design: dict[str, Any] | None = None


@click.command("curves")
@click.argument("case", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="NetCDF file (default CASE with suffix .nc); the CSV and PNG go beside it.",
)
@click.option("--scheduler", default=None, metavar="ADDRESS", help="Dask scheduler address.")
@click.option(
    "--workers",
    type=Number(int, min=0, max=1024),
    default=None,
    help="Local Dask worker processes (default one per core; 0 = in this process).",
)
@click.option("--quiet", is_flag=True, help="No progress bar.")
@click.option(
    "--force",
    is_flag=True,
    help="Run even when the estimated time or memory exceeds the budget"
    " (onbottom.study.budget: 12 h, 8 GB).",
)
@click.option(
    "--restart",
    is_flag=True,
    help="Discard the points an interrupted run kept (OUTPUT.tasks/) and start afresh.",
)
@json_option
@handle_errors
def command(
    case: Path,
    output: Path | None,
    scheduler: str | None,
    workers: int | None,
    quiet: bool,
    force: bool,
    restart: bool,
    as_json: bool,
) -> None:
    """Stability curves L_stable, L_10 from dynamic storms (CASE: TOML with [curves]).

    For each soil, N, M and K, bisects the weight parameter L = w_s/(½ρDU_s²) at which the
    seed-averaged maximum displacement of a storm is 0.5D and 10D; writes NetCDF, CSV and a
    figure of L/(2 + M)² against K (the form of DNV-RP-F109's tables).

    Each finished point is kept at once in OUTPUT.tasks/ (one small file per point), so an
    interrupted run (Ctrl-C, a kill) resumes without repeating it; --restart starts afresh.
    Results are written under a temporary name and renamed when complete.
    """
    with log_to_stderr(not as_json):
        _command(case, output, scheduler, workers, quiet, force, restart, as_json)


def _command(
    case: Path,
    output: Path | None,
    scheduler: str | None,
    workers: int | None,
    quiet: bool,
    force: bool,
    restart: bool,
    as_json: bool,
) -> None:
    from onbottom.results import TaskStore, save_dataset, save_figure, write_csv_atomic
    from onbottom.study.stability_curves import curves_table, stability_curves

    nc = output if output is not None else case.with_suffix(".nc")
    check_output_names(case, [("--output", nc, (".nc",))])
    check_output_names(  # the CSV and the figure go beside the NetCDF
        case,
        [("--output", nc.with_suffix(".csv"), ()), ("--output", nc.with_suffix(".png"), ())],
    )
    cfg = load_case_file(case, CurvesCase)
    c = cfg.curves
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        settings = _settings(case, cfg)
    notes_in = sorted({str(w.message) for w in caught if issubclass(w.category, OutOfRangeWarning)})
    if not as_json:
        for note in notes_in:
            click.echo(f"warning: {note}", err=True)
    check_output_path(nc, field="--output")
    _check_budget(c, workers=workers, force=force)
    store = nc.with_name(nc.name + ".tasks")
    t0 = time.perf_counter()
    ds = stability_curves(
        c.K,
        c.M,
        c.N,
        soils=c.soils,
        criteria=c.criteria,
        settings=settings,
        n_workers=workers,
        scheduler=scheduler,
        progress=not quiet and not as_json,
        store=store,
        restart=restart,
    )
    save_dataset(ds, nc)
    rows = curves_table(ds)
    csv_path = nc.with_suffix(".csv")
    write_csv_atomic(csv_path, rows, list(rows[0]))
    import matplotlib.pyplot as plt

    from onbottom.plotting.storm import plot_stability_curves

    fig = plot_stability_curves(
        ds, title=f"{case.stem}: {c.seeds} seeds, {c.build_up_hours:g} h + {c.peak_hours:g} h"
    )
    png = nc.with_suffix(".png")
    save_figure(fig, png, dpi=110)
    plt.close(fig)
    TaskStore.delete(store)  # the NetCDF, CSV and figure hold every point now
    failures = ds.attrs.get("failures", "[]")
    import json

    failures = json.loads(failures) if isinstance(failures, str) else failures
    notes = ds.attrs.get("no_crossing", "[]")
    notes = json.loads(notes) if isinstance(notes, str) else notes
    payload = {
        "points": rows,
        "total_storms": int(ds.attrs["total_storms"]),
        "wall_time_s": time.perf_counter() - t0,
        "workers": int(ds.attrs["workers"]),
        "failures": failures,
        "no_crossing": notes,
        "netcdf": str(nc),
        "csv": str(csv_path),
        "figure": str(png),
        "warnings": notes_in,
    }
    if as_json:
        emit_json(payload)
    else:
        for r in rows:
            click.echo(f"{r['soil']:>4} N={r['N']:g} M={r['M']:g} K={r['K']:g}: {_point(r)}")
        for note in notes:
            click.echo(
                f"  no L for {note['criterion']} at {note['soil']} K={note['K']:g}"
                f" M={note['M']:g}: {note['message']}"
            )
        flagged = [
            f"{r['soil']} K={r['K']:g} M={r['M']:g} N={r['N']:g}"
            for r in rows
            if any(v for k, v in r.items() if k.endswith("_out_of_range"))
        ]
        if flagged:
            click.echo(
                f"  outside the soil model's range (storms buried the pipe beyond D/2; marked"
                f" out_of_range): {', '.join(flagged)}"
            )
        click.echo(
            f"{payload['total_storms']} storms in {payload['wall_time_s']:.1f} s on"
            f" {payload['workers']} worker(s); written: {nc}, {csv_path}, {png}"
        )
    if failures:
        raise click.exceptions.Exit(EXIT_INVALID_RESULT)


def _check_budget(c: CurvesTable, *, workers: int | None, force: bool) -> None:
    """Refuse a grid whose estimated time or memory exceeds the budget (unless --force)."""
    import math

    from onbottom.constants import GRAVITY
    from onbottom.study import budget

    n_points = len(c.K) * len(c.M) * len(c.N) * len(c.soils) * len(c.criteria)
    # the shortest zero-up-crossing period T_u of the grid: the most flow samples (memory)
    tu = min(math.sqrt(k * c.diameter / (n * GRAVITY)) for k in c.K for n in c.N)
    budget.check(
        budget.curve_points(
            n_points,
            c.seeds,
            (c.build_up_hours + c.peak_hours) * 3600.0,
            c.time_step,
            tolerance=c.tolerance,
            l_min=c.l_min,
            l_max=c.l_max,
            tp=tu,
            workers=workers,
        ),
        force=force,
        field="[curves]",
    )


def _point(row: dict[str, Any]) -> str:
    """One console line of a curve point: per criterion L, its bracket, the seeds' spread of
    max |y|/D at both ends, and NOT CONVERGED where the bracket is wider than the tolerance."""
    parts = []
    for c in ("L_stable", "L_10"):
        if c not in row:
            continue
        lo, hi = row.get(f"{c}_L_low"), row.get(f"{c}_L_high")
        spread = (
            f"; seeds max|y|/D {row[f'{c}_seed_min_low']:.3g}-{row[f'{c}_seed_max_low']:.3g}"
            f" at L_low, {row[f'{c}_seed_min_high']:.3g}-{row[f'{c}_seed_max_high']:.3g} at"
            " L_high"
            if f"{c}_seed_min_low" in row
            else ""
        )
        if row.get(f"{c}_converged", True):
            parts.append(
                f"{c} = {row[c]:.3g} [{lo:.3g}, {hi:.3g}], {c}/(2+M)^2 ="
                f" {row[f'{c}/(2+M)^2']:.3g}{spread}"
            )
        else:
            parts.append(f"{c} NOT CONVERGED (bracket [{lo:.3g}, {hi:.3g}]){spread}")
    return "; ".join(parts)


def _settings(case: Path, cfg: CurvesCase) -> Any:
    """:class:`CurveSettings` of a parsed case, every (K, N) checked for a representable sea
    state up front; errors name the case-file key (``curves.K[i]``, ``curves.l_max``)."""
    import math

    from onbottom.cases.force import force_model_from_case
    from onbottom.cases.stability import Checker
    from onbottom.cases.storm import TIME_STEP_MAX_FRACTION, TIME_STEP_WARN_FRACTION
    from onbottom.constants import GRAVITY
    from onbottom.errors import InputError
    from onbottom.hydro.storm_kinematics import sea_state_for_velocity
    from onbottom.study.stability_curves import CurveSettings

    _, text = read_toml(case)
    chk = Checker(case, text)
    c = cfg.curves
    h = cfg.hydro
    try:
        settings = CurveSettings(
            diameter=c.diameter,
            seeds=c.seeds,
            first_seed=c.first_seed,
            build_up_hours=c.build_up_hours,
            peak_hours=c.peak_hours,
            tolerance=c.tolerance,
            l_min=c.l_min,
            l_max=c.l_max,
            gamma=c.gamma,
            tn_over_tp=c.tn_over_tp,
            time_step=c.time_step,
            sand_unit_weight=c.sand_unit_weight,
            sand_friction=c.sand_friction,
            clay_gc=c.clay_gc,
            clay_unit_weight=c.clay_unit_weight,
            clay_submerged_unit_weight=c.clay_submerged_unit_weight,
            clay_friction=c.clay_friction,
            water_density=cfg.environment.water_density if cfg.environment else 1025.0,
            force_model=force_model_from_case(h, base_dir=case.resolve().parent, default="wake"),
        )
    except InputError as exc:
        msg = str(exc)
        head = msg.split(" ", 1)[0]
        obj, _, attr = head.partition(".")
        if obj == "CurveSettings" and attr:
            key = "environment.water_density" if attr == "water_density" else f"curves.{attr}"
            chk.fail(key, key + msg[len(head) :])
        chk.fail("hydro", f"[hydro] is invalid: {msg}")
    d = c.diameter
    tps: list[tuple[float, float, float]] = []
    for i, k in enumerate(c.K):
        for n in c.N:
            try:
                sea, _ = sea_state_for_velocity(
                    math.sqrt(k * n * GRAVITY * d),
                    math.sqrt(k * d / (n * GRAVITY)),
                    tn_over_tp=c.tn_over_tp,
                    gamma=c.gamma,
                )
            except InputError as exc:
                chk.fail(
                    f"curves.K[{i}]",
                    f"curves.K[{i}] = {k!r} is invalid with N = {n:g}, D = {d:g} m: no storm"
                    f" represents it (needs H_s <= 30 m and T_p <= 40 s; {exc})",
                )
            tps.append((sea.tp, k, n))
    # a storm peak of a few peak periods at least (onbottom.inputs.consistency)
    from onbottom.inputs import consistency

    tp_max = max(tps)[0]
    chk.apply(consistency.peak_duration(c.peak_hours * 3600.0, tp_max, field="curves.peak_hours"))
    # the time-step rule of `onbottom storm` (docs/theory/storm_section.md)
    tp, k, n = min(tps)
    if c.time_step > TIME_STEP_MAX_FRACTION * tp:
        chk.fail(
            "curves.time_step",
            f"curves.time_step = {c.time_step!r} s is invalid: the storm of K = {k:g}, N ="
            f" {n:g} has T_p = {tp:.3g} s and the step must be <= T_p/4 ="
            f" {TIME_STEP_MAX_FRACTION * tp:.3g} s",
        )
    if c.time_step > TIME_STEP_WARN_FRACTION * tp:
        chk.warn(
            "curves.time_step",
            f"curves.time_step = {c.time_step:g} s is coarse: the storm of K = {k:g}, N ="
            f" {n:g} has T_p = {tp:.3g} s; above T_p/20 = {TIME_STEP_WARN_FRACTION * tp:.3g} s"
            " the result depends on the step",
        )
    return settings
