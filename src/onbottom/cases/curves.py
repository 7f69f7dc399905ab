"""Curves case files (TOML) for ``onbottom curves``: F109-style generalized-stability curves.

The ``[curves]`` table (the grid K × M × N × soils × criteria and the storm, soil and bisection
settings) and the optional ``[hydro]`` and ``[environment]`` tables (strict tables of
:mod:`onbottom.cases.stability`); other tables of a shared case file are accepted and not used,
and so is ``[environment] water_depth`` (required by the shared table; the curves are given in
K, M and N, without a depth). ``[hydro] reductions = false`` is refused: every point applies
F109's permeable-seabed reduction on sand.
:func:`build_curve_settings` turns a parsed case into
:class:`~onbottom.study.stability_curves.CurveSettings` (the API of
:func:`~onbottom.study.stability_curves.stability_curves`), :func:`check_budget` refuses a grid
beyond the run budget (:mod:`onbottom.study.budget`).

Case file::

    [curves]
    K = [5.0, 10.0, 20.0, 40.0]
    M = [0.0, 0.2, 0.4, 0.8]
    N = [0.003]
    soils = ["sand", "clay"]
    seeds = 10
    statistic = "fractile"   # each seed's own L; the 0.9 fractile and the median
    fractile = 0.9
    early_stop = true        # a storm stops once |y| reaches the criterion
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, Literal

from pydantic import Field, field_validator

from onbottom._casefile import StrictModel, load_case_file, read_toml
from onbottom.cases.tables import Checker, EnvironmentTable, HydroTable
from onbottom.constants import GRAVITY
from onbottom.errors import InputError
from onbottom.inputs import consistency

if TYPE_CHECKING:
    from onbottom.study.stability_curves import CurveSettings

__all__ = [
    "CurvesCase",
    "CurvesTable",
    "build_curve_settings",
    "check_budget",
    "load_curves_case",
]

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
    seeds: int = Field(
        10,
        ge=1,
        le=1000,
        description="seeds [-]: each has its own bisection (statistic 'fractile'), or storms"
        " per evaluation (statistic 'mean_of_maxima')",
    )
    statistic: Literal["fractile", "mean_of_maxima"] = Field(
        "fractile",
        description="curve statistic: 'fractile' (each seed's own L; the point's L is the"
        " fractile, the median beside it) or 'mean_of_maxima' (the former seed-averaged"
        " maximum, for comparison)",
    )
    fractile: float = Field(
        0.9, ge=0.5, le=0.99, description="fractile of the per-seed L reported as L [-]"
    )
    early_stop: bool = Field(
        True, description="stop each storm once |y| reaches the criterion ('fractile' only)"
    )
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


def load_curves_case(path: str | os.PathLike) -> CurvesCase:
    """Read and validate a curves case file (errors: :class:`onbottom._casefile.CaseFileError`
    naming the key, the file and the line)."""
    return load_case_file(path, CurvesCase)


def build_curve_settings(cfg: CurvesCase, case: str | os.PathLike) -> CurveSettings:
    """:class:`~onbottom.study.stability_curves.CurveSettings` of a parsed case (``case``: the
    file it came from), every (K, N) checked for a representable sea state up front, the
    storm peak's length and the time-step rule (:mod:`onbottom.inputs.consistency`) against
    the grid's peak periods; errors name the case-file key (``curves.K[i]``,
    ``curves.l_max``), warnings (:class:`~onbottom.errors.OutOfRangeWarning`) the file and
    line."""
    from onbottom.cases.force import force_model_from_case
    from onbottom.cases.models import check_model_names
    from onbottom.hydro.storm_kinematics import sea_state_for_velocity
    from onbottom.study.stability_curves import CurveSettings

    case = Path(case)
    _, text = read_toml(case)
    chk = Checker(case, text)
    c = cfg.curves
    h = cfg.hydro
    check_model_names(cfg, chk)
    if not h.reductions:
        chk.fail(
            "hydro.reductions",
            "hydro.reductions = false is not used by onbottom curves: every curve point applies"
            " F109's permeable-seabed load reduction on sand (none on clay), as the generalized"
            " method's curves do; remove the key",
        )
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
            statistic=c.statistic,
            fractile=c.fractile,
            early_stop=c.early_stop,
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
        field = getattr(exc, "field", None)
        if isinstance(field, str) and field.startswith("hydro."):
            chk.fail(field, msg)
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
    # a storm peak of a few peak periods at least, and the time-step rule of `onbottom storm`
    tp_max = max(tps)[0]
    chk.apply(consistency.peak_duration(c.peak_hours * 3600.0, tp_max, field="curves.peak_hours"))
    tp, k, n = min(tps)
    chk.apply(
        consistency.time_step(
            c.time_step, tp, field="curves.time_step", source=f"the storm of K = {k:g}, N = {n:g}"
        )
    )
    return settings


def check_budget(c: CurvesTable, *, workers: int | None, force: bool) -> None:
    """Refuse a grid whose estimated time or memory exceeds the budget (unless ``force``,
    the command's ``--force``): :func:`onbottom.study.budget.check` of the grid's storms."""
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
