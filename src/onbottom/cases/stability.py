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
import warnings
from dataclasses import fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, NoReturn

from pydantic import Field, field_validator, model_validator

from onbottom._casefile import CaseFileError, StrictModel, find_key_line, load_case_file
from onbottom.cases.models import check_model_names, collect_model_tables
from onbottom.checks.design import CheckOptions
from onbottom.checks.evaluation import (
    DesignBounds,
    DesignRequest,
    StabilityInputs,
    penetration_outside_validity,
)
from onbottom.constants import KINEMATIC_VISCOSITY_SEAWATER
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.inputs import consistency
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe import Layer, Pipe
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
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

Condition = Literal["installation", "flooded", "hydrotest", "operation"]


class LayerTable(StrictModel):
    name: str = Field("coating", description="label, e.g. corrosion, concrete [-]")
    thickness: float = Field(ge=0.0, le=1.0, description="radial thickness [m]")
    density: float = Field(ge=100.0, le=2.0e4, description="density [kg/m³]")


class ContentsTable(StrictModel):
    installation: float = Field(0.0, ge=0.0, le=3.0e3, description="empty as laid [kg/m³]")
    flooded: float = Field(1025.0, ge=0.0, le=3.0e3, description="water-flooded [kg/m³]")
    hydrotest: float = Field(1025.0, ge=0.0, le=3.0e3, description="hydrotest water [kg/m³]")
    operation: float = Field(0.0, ge=0.0, le=3.0e3, description="product [kg/m³]")


class PipeTable(StrictModel):
    outer_diameter: float | None = Field(None, ge=0.005, le=5.0, description="D (simple) [m]")
    submerged_weight: float | None = Field(None, ge=1.0, description="w_s (simple) [N/m]")
    steel_outer_diameter: float | None = Field(None, ge=0.005, le=5.0, description="D_s [m]")
    wall_thickness: float | None = Field(None, gt=0.0, description="steel wall t [m]")
    steel_density: float = Field(7850.0, ge=2.0e3, le=2.0e4, description="[kg/m³]")
    youngs_modulus: float = Field(207.0e9, gt=0.0, description="steel E [Pa]")
    contents_density: float | None = Field(
        None, ge=0.0, le=3.0e3, description="contents in every condition [kg/m³]"
    )
    contents: ContentsTable | None = None
    condition: Condition = "operation"
    layers: list[LayerTable] = Field(default_factory=list)
    marine_growth: LayerTable | None = None

    @model_validator(mode="after")
    def _one_form(self) -> PipeTable:
        simple = self.outer_diameter is not None or self.submerged_weight is not None
        built = self.steel_outer_diameter is not None or self.wall_thickness is not None
        if simple and built:
            raise ValueError(
                "give either outer_diameter + submerged_weight (simple form) or"
                " steel_outer_diameter + wall_thickness (build-up form), not both"
            )
        if simple and (self.outer_diameter is None or self.submerged_weight is None):
            raise ValueError("the simple form needs both outer_diameter and submerged_weight")
        if not simple and (self.steel_outer_diameter is None or self.wall_thickness is None):
            raise ValueError(
                "give outer_diameter + submerged_weight, or steel_outer_diameter + wall_thickness"
            )
        if self.contents_density is not None and self.contents is not None:
            raise ValueError("give contents_density or [pipe.contents], not both")
        if simple:
            fields = type(self).model_fields
            unused = (
                [
                    k
                    for k in ("steel_density", "youngs_modulus")
                    if getattr(self, k) != fields[k].default
                ]
                + [
                    k
                    for k in ("contents_density", "contents", "marine_growth")
                    if getattr(self, k) is not None
                ]
                + (["layers"] if self.layers else [])
            )
            if unused:
                raise ValueError(
                    f"{', '.join(unused)} {'applies' if len(unused) == 1 else 'apply'} to the"
                    " build-up form (steel_outer_diameter + wall_thickness) only: the simple"
                    " form's outer_diameter and submerged_weight already hold them; remove"
                    f" {'it' if len(unused) == 1 else 'them'}"
                )
        return self

    @property
    def is_buildup(self) -> bool:
        return self.steel_outer_diameter is not None

    def section(self, water_density: float) -> PipeBuildUp | Pipe:
        """The :class:`PipeBuildUp` (build-up form) or :class:`Pipe` (simple form)."""
        if not self.is_buildup:
            return Pipe(
                outer_diameter=self.outer_diameter,
                submerged_weight=self.submerged_weight,
                seawater_density=water_density,
            )
        if self.contents is not None:
            contents = Contents(**self.contents.model_dump())
        elif self.contents_density is not None:
            contents = Contents.uniform(self.contents_density)
        else:
            contents = Contents()
        return PipeBuildUp(
            steel_outer_diameter=self.steel_outer_diameter,
            wall_thickness=self.wall_thickness,
            steel_density=self.steel_density,
            youngs_modulus=self.youngs_modulus,
            layers=tuple(Layer(**layer.model_dump()) for layer in self.layers),
            marine_growth=None
            if self.marine_growth is None
            else Layer(**self.marine_growth.model_dump()),
            contents=contents,
            seawater_density=water_density,
        )


_SOIL_KEYS_USED = {
    "sand": "submerged_unit_weight, friction_coefficient, d50",
    "calcareous": "submerged_unit_weight, friction_coefficient, d50",
    "clay": "undrained_shear_strength, submerged_unit_weight, unit_weight, friction_coefficient",
    "rock": "friction_coefficient",
    "coulomb": "friction_coefficient",
}
"""The soil keys each seabed model reads (besides initial_penetration and the trench)."""

_SOIL_KEYS_NOT_USED = {
    model: tuple(
        k
        for k in ("submerged_unit_weight", "unit_weight", "undrained_shear_strength", "d50")
        if k not in used
    )
    for model, used in _SOIL_KEYS_USED.items()
}
"""Keys given for a model that does not read them: refused (a key that silently does nothing,
such as a sand's γ' and d50 on rock, would hide a wrong seabed model)."""


class SeabedTable(StrictModel):
    model: Literal["sand", "calcareous", "clay", "rock", "coulomb"] = "sand"
    submerged_unit_weight: float | None = Field(None, gt=0.0, le=2.0e4, description="γ' [N/m³]")
    unit_weight: float | None = Field(
        None, gt=0.0, le=3.0e4, description="clay total unit weight γ_s [N/m³]"
    )
    friction_coefficient: float | None = Field(None, ge=0.01, le=2.0, description="μ [-]")
    undrained_shear_strength: float | None = Field(
        None, ge=100.0, le=1.0e6, description="s_u [Pa] (not kPa)"
    )
    d50: float | None = Field(None, gt=0.0, le=1.0, description="median grain size [m]")
    initial_penetration: float | None = Field(None, ge=0.0, description="z_p [m]")
    trench_depth: float = Field(0.0, ge=0.0, description="z_t [m]")
    trench_angle_deg: float = Field(45.0, ge=5.0, le=45.0, description="trench wall angle [deg]")

    @model_validator(mode="after")
    def _needs(self) -> SeabedTable:
        if self.model in ("sand", "calcareous") and self.submerged_unit_weight is None:
            raise ValueError(f"model = {self.model!r} needs submerged_unit_weight [N/m³]")
        if self.model == "clay":
            missing = [
                k
                for k in ("undrained_shear_strength", "submerged_unit_weight", "unit_weight")
                if getattr(self, k) is None
            ]
            if missing:
                raise ValueError(f"model = 'clay' needs {', '.join(missing)}")
        unused = [k for k in _SOIL_KEYS_NOT_USED[self.model] if getattr(self, k) is not None]
        if unused:
            raise ValueError(
                f"{', '.join(unused)} {'does' if len(unused) == 1 else 'do'} not apply to"
                f" model = {self.model!r} (its keys: {_SOIL_KEYS_USED[self.model]}); remove"
                f" {'it' if len(unused) == 1 else 'them'} or choose the model they belong to"
            )
        return self

    def seabed(self) -> Sand | Clay | Rock:
        """The soil object of the F109 checks (calcareous → sand law; coulomb → rock)."""
        mu = (
            {}
            if self.friction_coefficient is None
            else {"friction_coefficient": self.friction_coefficient}
        )
        if self.model in ("sand", "calcareous"):
            extra = {} if self.d50 is None else {"d50": self.d50}
            return Sand(
                submerged_unit_weight=self.submerged_unit_weight, kind=self.model, **mu, **extra
            )
        if self.model == "clay":
            return Clay(
                undrained_shear_strength=self.undrained_shear_strength,
                submerged_unit_weight=self.submerged_unit_weight,
                unit_weight=self.unit_weight,
                **mu,
            )
        return Rock(**mu)


def viscosity_not_used(value: float) -> float:
    """``environment.kinematic_viscosity``: only its default is accepted. No model of onbottom
    reads ν (DNV-RP-F109's load coefficients and the time-domain force models are given for
    the flow's K and M, without a Reynolds number): another value would be silently unused."""
    if value != KINEMATIC_VISCOSITY_SEAWATER:
        raise ValueError(
            f"is not used by any model of onbottom (F109's coefficients and the force models"
            f" take no Reynolds number): remove the key (default {KINEMATIC_VISCOSITY_SEAWATER:g}"
            " m²/s)"
        )
    return value


class EnvironmentTable(StrictModel):
    water_depth: float = Field(gt=0.0, le=5000.0, description="d [m]")
    water_density: float = Field(1025.0, ge=900.0, le=1100.0, description="ρ_w [kg/m³]")
    kinematic_viscosity: float = Field(
        KINEMATIC_VISCOSITY_SEAWATER,
        ge=1.0e-7,
        le=1.0e-4,
        description="ν [m²/s] (not used: default only)",
    )

    _nu = field_validator("kinematic_viscosity")(viscosity_not_used)


class WavesTable(StrictModel):
    hs: float = Field(gt=0.0, le=30.0, description="H_s [m]")
    tp: float = Field(gt=0.0, le=40.0, description="T_p [s]")
    gamma: float | None = Field(None, ge=1.0, le=7.0, description="JONSWAP γ [-]")
    spectrum: Literal["jonswap", "pierson-moskowitz"] = "jonswap"
    direction_deg: float = Field(90.0, ge=0.0, le=360.0, description="to the pipe axis [deg]")
    spreading_s: float = Field(0.0, ge=0.0, le=100.0, description="cos^s exponent [-]")

    @model_validator(mode="after")
    def _gamma_only_for_jonswap(self) -> WavesTable:
        if self.gamma is not None and self.spectrum != "jonswap":
            raise ValueError("gamma applies to the JONSWAP spectrum only; remove it")
        return self

    def sea_state(
        self, *, hs: float | None = None, tp: float | None = None, gamma: float | None = None
    ) -> SeaState:
        """The sea state of the table; ``hs`` [m], ``tp`` [s], ``gamma`` [-] replace the
        table's where given (a load combination's)."""
        return SeaState(
            hs=self.hs if hs is None else hs,
            tp=self.tp if tp is None else tp,
            gamma=self.gamma if gamma is None else gamma,
            spectrum=self.spectrum,
            direction_deg=self.direction_deg,
            spreading_s=self.spreading_s,
        )


class CurrentTable(StrictModel):
    velocity: float = Field(0.0, ge=0.0, le=10.0, description="V(z_r) [m/s]")
    reference_height: float = Field(1.0, gt=0.0, description="z_r [m]")
    direction_deg: float = Field(90.0, ge=0.0, le=360.0, description="to the pipe axis [deg]")
    z0: float | None = Field(None, gt=0.0, le=1.0, description="roughness z_0 [m]")

    def current(self, velocity: float | None = None) -> Current:
        """The current of the table; ``velocity`` [m/s] replaces the table's where given."""
        return Current(
            velocity=self.velocity if velocity is None else velocity,
            reference_height=self.reference_height,
            direction_deg=self.direction_deg,
            z0=self.z0,
        )


class CombinationTable(StrictModel):
    name: str = Field(min_length=1, description="label [-]")
    hs: float | None = Field(None, gt=0.0, le=30.0, description="H_s [m]")
    tp: float | None = Field(None, gt=0.0, le=40.0, description="T_p [s]")
    gamma: float | None = Field(None, ge=1.0, le=7.0, description="JONSWAP γ [-]")
    current_velocity: float | None = Field(None, ge=0.0, le=10.0, description="V(z_r) [m/s]")
    condition: Condition | None = None


class HydroTable(StrictModel):
    cd: float = Field(0.7, ge=0.0, le=10.0, description="drag coefficient C_D [-]")
    cm: float = Field(3.29, ge=0.0, le=10.0, description="inertia coefficient C_M [-]")
    cl: float = Field(0.9, ge=0.0, le=10.0, description="lift coefficient C_L [-]")
    added_mass_coefficient: float = Field(2.29, ge=0.0, le=10.0, description="C_a [-]")
    reductions: bool = True
    model: str | None = Field(
        None,
        min_length=1,
        description="time-domain force model by name (onbottom.hydro.registry; the docs'"
        " api/models.md lists them), options in [hydro.<name>]; default: the command's [-]",
    )
    coefficient_table: str | None = Field(
        None,
        min_length=1,
        description="CSV of C_D, C_M, C_L over (K, M) for Morison per sea state"
        " (hydro/morison_table.py), relative to the case file [-]",
    )
    wake: dict[str, Any] = Field(
        default_factory=dict, description="options of the wake model (WakeModel fields)"
    )
    fourier: dict[str, Any] = Field(
        default_factory=dict,
        description="options of the Fourier model (FourierModel fields; table = path)",
    )
    models: dict[str, dict[str, Any]] = Field(
        default_factory=dict,
        description="options of the other registered force models: the [hydro.<name>] tables",
    )

    @model_validator(mode="before")
    @classmethod
    def _model_tables(cls, data: Any) -> Any:
        return collect_model_tables(data, set(cls.model_fields))


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


_OBJECT_TABLES = {
    "PipeBuildUp": "pipe",
    "Pipe": "pipe",
    "Layer": "pipe.layers",
    "Contents": "pipe.contents",
    "Sand": "seabed",
    "Clay": "seabed",
    "Rock": "seabed",
    "Environment": "environment",
    "SeaState": "waves",
    "Current": "current",
    "LoadCombination": "combinations",
}


class Checker:
    """Raise :class:`CaseFileError` naming field, value, range, file and line; collect warnings."""

    def __init__(self, file: str | os.PathLike, text: str | None) -> None:
        self.file, self.text = str(file), text

    @classmethod
    def of_file(cls, path: str | os.PathLike) -> Checker:
        """A checker of the case file ``path``, its text read for the line numbers (none
        where it cannot be read)."""
        try:
            text: str | None = Path(path).read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            text = None
        return cls(path, text)

    def _line(self, field: str) -> int | None:
        return find_key_line(self.text, field)

    def fail(self, field: str, message: str) -> NoReturn:
        line = self._line(field)
        where = f"{self.file}{f', line {line}' if line else ''}: "
        raise CaseFileError(where + _plain(message), field=field or None, file=self.file, line=line)

    def warn(self, field: str, message: str, category: type[Warning] = OutOfRangeWarning) -> None:
        line = self._line(field)
        where = f"{self.file}{f', line {line}' if line else ''}: "
        warnings.warn(where + _plain(message), category, stacklevel=3)

    def apply(self, findings: list[consistency.Finding]) -> None:
        """Report :mod:`onbottom.inputs.consistency` findings under their case-file keys:
        the first error raises, then every warning is issued."""
        for f in findings:
            if f.error:
                self.fail(f.field, f.message)
        for f in findings:
            self.warn(f.field, f.message, f.category)

    def rename(self, exc: InputError) -> NoReturn:
        """Re-raise an error of an input object under the case-file key it came from."""
        text = _plain(str(exc))
        field = getattr(exc, "field", None)
        head = text.split(" ", 1)[0]
        obj, _, attr = head.partition(".")
        if (field is None or field == head) and obj in _OBJECT_TABLES and attr:
            field = f"{_OBJECT_TABLES[obj]}.{attr}"
            text = f"{field}{text[len(head) :]}"
        self.fail(field or "", text)


def _plain(text: str) -> str:
    """Messages with plain numbers (``np.float64(7.0)`` → ``7.0``)."""
    import re

    return re.sub(r"np\.(?:float|int|uint|bool_?|str_)\d*\(([^()]*)\)", r"\1", text)


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
        from onbottom.cases.storm import StormTable

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
