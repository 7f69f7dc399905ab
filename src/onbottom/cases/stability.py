"""Case-file schema of the F109 design commands (``onbottom stability``, ``onbottom loads``).

Strict TOML tables (:class:`onbottom._casefile.StrictModel`: unknown keys are errors with file,
line and did-you-mean), laid out as in the common case layout: ``[pipe]`` (simple or
build-up form), ``[seabed]``, ``[environment]``, ``[waves]``, ``[current]``, ``[hydro]``, plus

* ``[[combinations]]`` — load combinations; each has a ``name`` and may override ``hs``,
  ``tp``, ``gamma`` and ``current_velocity`` of ``[waves]``/``[current]`` and set the pipe
  ``condition``. Without it the single combination ``"design"`` is ``[waves]`` + ``[current]``
  in ``pipe.condition``.
* ``[design]`` — safety class, region, conditions for flotation, and the design solve
  (``solve_for = "concrete_thickness" | "submerged_weight" | "none"`` with its range).

Tables used by other commands (``[storm]``, ``[solver]``, ``[run]``, ``[pipeline]``) are
accepted here and validated by the commands that read them.

Builders: :func:`build_stability_inputs` (the inputs of
:func:`onbottom.checks.evaluation.evaluate_stability`) and :func:`build_loads_inputs` (those of
:func:`onbottom.checks.loads.combination_loads`).
"""

from __future__ import annotations

import math
import os
from dataclasses import fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from pydantic import Field, model_validator

from onbottom._casefile import CaseFileError, StrictModel, load_case_file
from onbottom.cases.models import check_model_names
from onbottom.cases.tables import (
    Checker,
    CombinationTable,
    Condition,
    CurrentTable,
    EnvironmentTable,
    HydroTable,
    PipeTable,
    SeabedTable,
    WavesTable,
)
from onbottom.checks.design import CheckOptions
from onbottom.checks.evaluation import (
    DesignBounds,
    DesignRequest,
    StabilityInputs,
    penetration_outside_validity,
)
from onbottom.errors import InputError
from onbottom.inputs import consistency
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.pipe_buildup import PipeBuildUp
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.inputs.storm import Current, SeaState

__all__ = [
    "Checker",
    "StabilityCase",
    "build_loads_inputs",
    "build_stability_inputs",
    "check_common_tables",
    "check_options",
    "check_reference_height",
    "load_stability_case",
    "penetration_outside_validity",
    "unused_table_notes",
]

if TYPE_CHECKING:
    from onbottom.checks.loads import LoadsInputs


class DesignTable(StrictModel):
    safety_class: Literal["low", "normal", "high"] = "normal"
    region: Literal[
        "north_sea_winter", "north_sea_cyclonic", "gulf_of_mexico_winter", "gulf_of_mexico_cyclonic"
    ] = "north_sea_winter"
    vertical_conditions: list[Condition] = Field(
        default_factory=lambda: ["installation", "flooded", "hydrotest", "operation"]
    )
    vertical_safety_factor: float = Field(1.1, ge=1.0, le=2.0, description="γ_W [-]")
    checks: list[str] = Field(
        default_factory=lambda: ["vertical", "absolute"],
        description="design checks run, by name (checks/registry.py: vertical, absolute)",
    )
    permeable: bool | None = None
    solve_for: Literal["concrete_thickness", "submerged_weight", "none"] = "none"
    layer: str = Field("concrete", min_length=1, description="layer sized by the solve [-]")
    thickness_min: float = Field(0.0, ge=0.0, le=1.0, description="[m]")
    thickness_max: float = Field(0.25, gt=0.0, le=1.0, description="[m]")
    weight_min: float = Field(1.0, gt=0.0, description="[N/m]")
    weight_max: float = Field(2.0e4, gt=0.0, description="[N/m]")

    @model_validator(mode="after")
    def _ranges(self) -> DesignTable:
        if self.thickness_max <= self.thickness_min:
            raise ValueError("thickness_max must be > thickness_min")
        if self.weight_max <= self.weight_min:
            raise ValueError("weight_max must be > weight_min")
        return self

    def bounds(self) -> dict[str, Any]:
        """The design search range: the fields of
        :class:`~onbottom.checks.evaluation.DesignBounds` (layer, thickness and weight
        ranges) as keyword arguments."""
        return {f.name: getattr(self, f.name) for f in fields(DesignBounds)}


class StabilityCase(StrictModel):
    """Top level of a case file read by the F109 design commands."""

    pipe: PipeTable
    seabed: SeabedTable
    environment: EnvironmentTable
    waves: WavesTable
    current: CurrentTable = CurrentTable()
    hydro: HydroTable = HydroTable()
    combinations: list[CombinationTable] = Field(default_factory=list)
    design: DesignTable = DesignTable()
    # tables of other commands: accepted, validated where they are used
    storm: dict[str, Any] | None = None
    solver: dict[str, Any] | None = None
    run: dict[str, Any] | None = None
    pipeline: dict[str, Any] | None = None

    # ---- builders -----------------------------------------------------------------------
    def environment_object(self) -> Environment:
        e = self.environment
        return Environment(
            water_depth=e.water_depth,
            water_density=e.water_density,
            kinematic_viscosity=e.kinematic_viscosity,
        )

    def section(self) -> PipeBuildUp | Pipe:
        return self.pipe.section(self.environment.water_density)

    def sea_state(self, combo: CombinationTable | None = None) -> SeaState:
        if combo is None:
            return self.waves.sea_state()
        return self.waves.sea_state(hs=combo.hs, tp=combo.tp, gamma=combo.gamma)

    def current_object(self, combo: CombinationTable | None = None) -> Current:
        return self.current.current(None if combo is None else combo.current_velocity)

    def load_combinations(self) -> tuple[LoadCombination, ...]:
        if not self.combinations:
            return (
                LoadCombination(
                    name="design",
                    sea_state=self.sea_state(),
                    current=self.current_object(),
                    condition=self.pipe.condition,
                ),
            )
        return tuple(
            LoadCombination(
                name=c.name,
                sea_state=self.sea_state(c),
                current=self.current_object(c),
                condition=c.condition or self.pipe.condition,
            )
            for c in self.combinations
        )


# ---- checks across tables and plausibility (after the schema) -------------------------------
# limits shared with the API (kept here under their old names)
MAX_WAVE_STEEPNESS = consistency.MAX_WAVE_STEEPNESS
MAX_HS_OVER_DEPTH = consistency.MAX_HS_OVER_DEPTH
USUAL_HS_OVER_DEPTH = consistency.USUAL_HS_OVER_DEPTH


def outer_diameter(pipe: PipeTable) -> float:
    """Outer diameter D [m] of a [pipe] table: given (simple form) or the steel plus twice
    every layer and the marine growth (build-up form)."""
    if not pipe.is_buildup:
        return float(pipe.outer_diameter)
    d = float(pipe.steel_outer_diameter) + 2.0 * sum(layer.thickness for layer in pipe.layers)
    if pipe.marine_growth is not None:
        d += 2.0 * pipe.marine_growth.thickness
    return d


def _check_case(case: StabilityCase, chk: Checker) -> None:
    """Cross-table rules and engineering plausibility of a parsed case."""

    # -- combinations and design against the pipe form ------------------------------------
    if case.waves.spectrum != "jonswap":
        for i, c in enumerate(case.combinations):
            if c.gamma is not None:
                chk.fail(
                    f"combinations[{i}].gamma",
                    f"combinations[{i}].gamma = {c.gamma!r} is invalid: γ applies to the JONSWAP"
                    f" spectrum only (waves.spectrum = {case.waves.spectrum!r}); remove it",
                )
    seen: set[str] = set()
    for i, c in enumerate(case.combinations):
        if c.name in seen:
            chk.fail(
                f"combinations[{i}].name",
                f"combinations[{i}].name = {c.name!r} is invalid: combination names must be unique",
            )
        seen.add(c.name)
    d = case.design
    names = [layer.name for layer in case.pipe.layers]
    if d.solve_for == "concrete_thickness":
        if not case.pipe.is_buildup:
            chk.fail(
                "design.solve_for",
                "design.solve_for = 'concrete_thickness' is invalid: it needs the build-up"
                " [pipe] form (steel_outer_diameter, wall_thickness, [[pipe.layers]])",
            )
        if d.layer not in names:
            chk.fail(
                "design.layer",
                f"design.layer = {d.layer!r} is invalid: not one of the [[pipe.layers]] names"
                f" ({', '.join(map(repr, names)) or 'no layers given'})",
            )
        i = names.index(d.layer)
        rho = case.pipe.layers[i].density
        if rho <= case.environment.water_density:
            chk.fail(
                f"pipe.layers[{i}].density",
                f"pipe.layers[{i}].density = {rho!r} kg/m³ is invalid for the design solve: the"
                f" layer {d.layer!r} is not heavier than the water"
                f" ({case.environment.water_density:g} kg/m³), so more of it makes the pipe"
                " lighter (check the unit: kg/m³)",
            )
    if d.solve_for == "submerged_weight" and case.pipe.is_buildup:
        chk.fail(
            "design.solve_for",
            "design.solve_for = 'submerged_weight' is invalid: it needs the simple [pipe] form"
            " (outer_diameter, submerged_weight)",
        )
    states = []
    for i, c in enumerate(case.combinations):
        key = f"combinations[{i}]"
        states.append(
            (
                f"combination {c.name!r}",
                case.waves.hs if c.hs is None else c.hs,
                case.waves.tp if c.tp is None else c.tp,
                key if c.hs is not None else "waves",
                key if c.tp is not None else "waves",
            )
        )
    _check_common(case, chk, states)


def _check_common(case: Any, chk: Checker, extra_states: list[tuple]) -> None:
    """Plausibility of the tables every on-bottom command shares ([pipe], [seabed],
    [environment], [waves], [current]) and of extra sea states
    ``(label, hs, tp, hs_table, tp_table)``."""
    from onbottom.constants import GRAVITY

    for i, layer in enumerate(case.pipe.layers):
        if "concrete" in layer.name.lower() and not 1800.0 <= layer.density <= 3600.0:
            chk.warn(
                f"pipe.layers[{i}].density",
                f"pipe.layers[{i}].density = {layer.density:g} kg/m³ is unusual: weight-coating"
                " concrete lies in [1800, 3600] kg/m³",
            )
    if case.pipe.is_buildup and not 7000.0 <= case.pipe.steel_density <= 8100.0:
        chk.warn(
            "pipe.steel_density",
            f"pipe.steel_density = {case.pipe.steel_density:g} kg/m³ is unusual: line-pipe"
            " steels lie in [7000, 8100] kg/m³",
        )

    if not case.pipe.is_buildup:
        buoyancy = (
            case.environment.water_density * GRAVITY * math.pi * case.pipe.outer_diameter**2 / 4.0
        )
        sg = 1.0 + case.pipe.submerged_weight / buoyancy
        if sg < 1.05:
            chk.warn(
                "pipe.submerged_weight",
                f"pipe.submerged_weight = {case.pipe.submerged_weight:g} N/m is unusual: the"
                f" specific gravity is only {sg:.4g} (check the unit: N/m, not kN/m)",
            )
    if case.seabed.model == "clay" and case.seabed.undrained_shear_strength is not None:
        su = case.seabed.undrained_shear_strength
        if not 500.0 <= su <= 2.0e5:
            chk.warn(
                "seabed.undrained_shear_strength",
                f"seabed.undrained_shear_strength = {su:g} Pa is unusual: seabed clays lie in"
                " [500, 200000] Pa (check the unit: Pa, not kPa)",
            )

    # -- physical consistency (onbottom.inputs.consistency: shared with the API) -----------
    depth = case.environment.water_depth
    rho_w = case.environment.water_density
    found: list[consistency.Finding] = []
    found += consistency.depth_and_diameter(
        depth, outer_diameter(case.pipe), depth_field="environment.water_depth"
    )
    states = [] if case.waves is None else [("", case.waves.hs, case.waves.tp, "waves", "waves")]
    states += list(extra_states)
    for label, hs, tp, hs_at, tp_at in states:
        found += consistency.sea_state(
            hs,
            tp,
            depth,
            hs_field=f"{hs_at}.hs",
            tp_field=f"{tp_at}.tp",
            depth_field="environment.water_depth",
            label=label,
        )
    if case.pipe.is_buildup:
        found += consistency.youngs_modulus(case.pipe.youngs_modulus, field="pipe.youngs_modulus")
    for i, layer in enumerate(case.pipe.layers):
        found += consistency.layer_density(
            layer.density, rho_w, field=f"pipe.layers[{i}].density", name=layer.name
        )
    if case.pipe.marine_growth is not None:
        found += consistency.layer_density(
            case.pipe.marine_growth.density,
            rho_w,
            field="pipe.marine_growth.density",
            name=case.pipe.marine_growth.name,
        )
    found += consistency.current_speed(case.current.velocity, field="current.velocity")
    for i, c in enumerate(getattr(case, "combinations", None) or []):
        v = getattr(c, "current_velocity", None)
        if v is not None:
            found += consistency.current_speed(v, field=f"combinations[{i}].current_velocity")
    angles = [("current.direction_deg", case.current.direction_deg)]
    if case.waves is not None:
        angles.append(("waves.direction_deg", case.waves.direction_deg))
    for i, s in enumerate(getattr(getattr(case, "storm", None), "stages", None) or []):
        if getattr(s, "direction_deg", None) is not None:
            angles.append((f"storm.stages[{i}].direction_deg", s.direction_deg))
    for name, value in angles:
        found += consistency.angle_deg(value, field=name)
    chk.apply(found)

    # -- current ----------------------------------------------------------------------------
    cur = case.current
    if cur.reference_height > depth:
        chk.fail(
            "current.reference_height",
            f"current.reference_height = {cur.reference_height!r} m is invalid: above the"
            f" water depth {depth:g} m (must lie in (z_0, water_depth])",
        )
    z0 = cur.z0  # (z_0 from d50 is checked where F109 Table 3-1 is applied: hydro layer)
    if z0 is not None and cur.reference_height <= z0:
        chk.fail(
            "current.reference_height",
            f"current.reference_height = {cur.reference_height!r} m is invalid: not above the"
            f" seabed roughness z_0 = {z0:g} m, where the logarithmic profile (F109 Eq 3.3)"
            " is undefined",
        )

    # -- seabed (μ: the soil objects warn) ---------------------------------------------------
    sb = case.seabed
    if sb.model in ("sand", "calcareous") and sb.d50 is not None:
        if not 6.0e-5 <= sb.d50 <= 2.0e-3:
            chk.warn(
                "seabed.d50",
                f"seabed.d50 = {sb.d50:g} m is unusual for model = {sb.model!r}: sand grains"
                " lie in [6e-05, 0.002] m (check the unit: m, not mm)",
            )


def check_common_tables(
    case: Any,
    path: str | os.PathLike,
    *,
    sea_states: list[tuple[str, float, float, str, str]] | None = None,
) -> None:
    """Engineering plausibility of the shared tables of any parsed case file.

    For the case files of other commands that reuse these tables (``onbottom storm``: section
    and pipeline): ``case`` has ``pipe``, ``seabed``, ``environment``, ``waves`` (may be None)
    and ``current`` attributes as in :class:`StabilityCase`; ``sea_states`` adds sea states
    ``(label, hs [m], tp [s], table of hs, table of tp)``, e.g. ``("stage 0", 3.0, 9.0,
    "storm.stages[0]", "storm.stages[0]")``. Raises :class:`CaseFileError` (key, value, range,
    file, line) for a sea state steeper than breaking or higher than 0.78 × depth, a current
    reference height outside (z_0, depth], densities and strengths in the wrong unit; warns
    (:class:`OutOfRangeWarning`) for unusual values. See :func:`load_stability_case`.
    """
    _check_common(case, Checker.of_file(Path(path)), list(sea_states or []))


def _check_section(case: StabilityCase, chk: Checker) -> None:
    """Build every input object once (errors under their case-file keys), the cross-table and
    plausibility rules (:func:`_check_case`), and the embedment against D."""
    try:
        section = case.section()
        case.seabed.seabed()
        case.environment_object()
    except CaseFileError:
        raise
    except InputError as exc:
        chk.rename(exc)
    _check_case(case, chk)  # sea states and cross-table rules before the combinations
    try:
        case.load_combinations()
    except InputError as exc:
        chk.rename(exc)
    diameter = (
        section.properties(case.pipe.condition).outer_diameter
        if isinstance(section, PipeBuildUp)
        else section.outer_diameter
    )
    sb = case.seabed
    for key in ("initial_penetration", "trench_depth"):
        z = getattr(sb, key)
        if z is not None and z > diameter:
            chk.fail(
                f"seabed.{key}",
                f"seabed.{key} = {z!r} m is invalid: deeper than the pipe's outer diameter"
                f" {diameter:.4g} m (must lie in [0, D]; F109 §3.6 covers an on-bottom pipe)",
            )


def load_stability_case(path: str | os.PathLike) -> StabilityCase:
    """Read and validate a TOML/JSON case file.

    Raises :class:`onbottom._casefile.CaseFileError` (an :class:`~onbottom.errors.InputError`)
    naming the key, its value and allowed range, the file and the line: schema errors
    (unknown/missing keys, wrong types, ranges), rules across tables (design layer, unique
    combination names), and implausible inputs (a sea state steeper than the breaking limit
    or higher than 0.78 × the depth, a current reference height outside (z_0, depth], an
    embedment or trench deeper than D, a design layer lighter than water). Unusual inputs give
    :class:`~onbottom.errors.OutOfRangeWarning`.
    """
    p = Path(path)
    case = load_case_file(p, StabilityCase)
    check_model_names(case, Checker.of_file(p))
    _check_section(case, Checker.of_file(p))
    return case


def check_reference_height(
    case: StabilityCase, case_path: str | os.PathLike, seabed: Sand | Clay | Rock
) -> None:
    """[current] reference_height must lie above the seabed roughness z_0 (given, or F109
    Table 3-1 from the seabed) — a case-file error naming the key (F109 Eq 3.3 log profile)."""
    from onbottom.checks.absolute import seabed_roughness

    c = case.current
    z0 = c.z0 if c.z0 is not None else seabed_roughness(seabed)
    if c.reference_height <= z0:
        raise CaseFileError(
            f"{case_path}: current.reference_height = {c.reference_height!r} m is invalid: not"
            f" above the seabed roughness z_0 = {z0:g} m (F109 Table 3-1), where the"
            " logarithmic current profile (F109 Eq 3.3) is undefined",
            field="current.reference_height",
            file=str(case_path),
        )


def check_options(case: StabilityCase, *, checks: bool = True) -> CheckOptions:
    """The F109 check settings of a case: ``[design]`` (safety class, region, flotation
    conditions, permeability) and the embedment and trench of ``[seabed]``; ``checks=False``
    runs the default design checks (``onbottom assess``) instead of ``[design] checks``."""
    d = case.design
    return CheckOptions(
        safety_class=d.safety_class,
        region=d.region,
        vertical_conditions=tuple(d.vertical_conditions),
        vertical_safety_factor=d.vertical_safety_factor,
        **_seabed_options(case),
        **({"checks": tuple(d.checks)} if checks else {}),
    )


def _seabed_options(case: StabilityCase) -> dict[str, Any]:
    """The :class:`CheckOptions` of the seabed: embedment, trench and permeability."""
    return {
        "penetration": case.seabed.initial_penetration,
        "trench_depth": case.seabed.trench_depth,
        "trench_angle_deg": case.seabed.trench_angle_deg,
        "permeable": case.design.permeable,
    }


def _section_inputs(case: StabilityCase, path: str | os.PathLike) -> StabilityInputs:
    """The section, seabed, water and combinations of a case (default options, no design
    solve), its current reference height checked (:func:`check_reference_height`)."""
    section, seabed = case.section(), case.seabed.seabed()
    env, combos = case.environment_object(), case.load_combinations()
    check_reference_height(case, path, seabed)
    return StabilityInputs(
        section=section,
        seabed=seabed,
        environment=env,
        combinations=combos,
        condition=case.pipe.condition,
    )


def build_stability_inputs(case: StabilityCase, path: str | os.PathLike) -> StabilityInputs:
    """The inputs of :func:`onbottom.checks.evaluation.evaluate_stability` from a case read by
    :func:`load_stability_case` from ``path``: the section, seabed, water and combinations,
    the ``[design]`` check options and solve; errors name the case-file key
    (``current.reference_height``, ``design.checks``)."""
    from onbottom.checks.registry import get_check

    inputs = _section_inputs(case, path)
    d = case.design
    for name in d.checks:  # an unknown name: an error naming the key and the choices
        get_check(name, where="design.checks")
    options = check_options(case)
    design = DesignRequest(solve_for=d.solve_for, **d.bounds())
    return replace(inputs, options=options, design=design)


def build_loads_inputs(case: StabilityCase, path: str | os.PathLike) -> LoadsInputs:
    """The inputs of :func:`onbottom.checks.loads.combination_loads` from a case read by
    :func:`load_stability_case` from ``path``: the absolute check's options (no flotation
    rows; the embedment and trench of ``[seabed]``), the ``[hydro]`` Morison coefficients and
    reductions switch, and the default seed: ``[storm] seed`` of a shared file (its
    ``[storm]`` table is checked as ``onbottom storm`` does), else 0."""
    from onbottom.checks.loads import LoadsInputs
    from onbottom.hydro.forces import MorisonCoefficients

    inputs = _section_inputs(case, path)
    seed = 0
    if case.storm is not None:  # the [storm] table of a shared file: strict, as for `storm`
        from onbottom._casefile import parse_case
        from onbottom.cases.tables import StormTable

        seed = parse_case(
            StormTable,
            case.storm,
            file=path,
            text=Path(path).read_text(encoding="utf-8"),
            root="storm",
        ).seed
    h = case.hydro
    options = CheckOptions(vertical_conditions=(), **_seabed_options(case))
    return LoadsInputs(
        checks=replace(inputs, options=options),
        coefficients=MorisonCoefficients(drag=h.cd, inertia=h.cm, lift=h.cl),
        reductions=h.reductions,
        seed=seed,
    )


def unused_table_notes(case: StabilityCase) -> list[str]:
    """Notes on tables of a case that ``onbottom stability`` reads but does not use: a
    ``[hydro]`` table other than the defaults (the F109 checks have their own coefficients)."""
    if case.hydro == HydroTable():
        return []
    return [
        "[hydro] is not used by the F109 checks (their load coefficients are Tables"
        " 3-9/3-10 and their reductions Eqs 3.17-3.22); it applies to `onbottom loads`"
        " and `onbottom storm`"
    ]
