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
"""

from __future__ import annotations

import os
from typing import Any, Literal

from pydantic import Field, model_validator

from onbottom._casefile import StrictModel, load_case_file
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe import Layer, Pipe
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.inputs.storm import Current, SeaState

__all__ = ["StabilityCase", "load_stability_case"]

Condition = Literal["installation", "flooded", "hydrotest", "operation"]


class LayerTable(StrictModel):
    name: str = Field("coating", description="label, e.g. corrosion, concrete [-]")
    thickness: float = Field(ge=0.0, le=1.0, description="radial thickness [m]")
    density: float = Field(gt=0.0, le=2.0e4, description="density [kg/m³]")


class ContentsTable(StrictModel):
    installation: float = Field(0.0, ge=0.0, le=2.0e4, description="empty as laid [kg/m³]")
    flooded: float = Field(1025.0, ge=0.0, le=2.0e4, description="water-flooded [kg/m³]")
    hydrotest: float = Field(1025.0, ge=0.0, le=2.0e4, description="hydrotest water [kg/m³]")
    operation: float = Field(0.0, ge=0.0, le=2.0e4, description="product [kg/m³]")


class PipeTable(StrictModel):
    outer_diameter: float | None = Field(None, gt=0.0, le=5.0, description="D (simple) [m]")
    submerged_weight: float | None = Field(None, gt=0.0, description="w_s (simple) [N/m]")
    steel_outer_diameter: float | None = Field(None, gt=0.0, le=5.0, description="D_s [m]")
    wall_thickness: float | None = Field(None, gt=0.0, description="steel wall t [m]")
    steel_density: float = Field(7850.0, gt=0.0, le=2.0e4, description="[kg/m³]")
    youngs_modulus: float = Field(207.0e9, gt=0.0, description="steel E [Pa]")
    contents_density: float | None = Field(
        None, ge=0.0, le=2.0e4, description="contents in every condition [kg/m³]"
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


class SeabedTable(StrictModel):
    model: Literal["sand", "calcareous", "clay", "rock", "coulomb"] = "sand"
    submerged_unit_weight: float | None = Field(None, gt=0.0, le=2.0e4, description="γ' [N/m³]")
    unit_weight: float | None = Field(
        None, gt=0.0, le=3.0e4, description="clay total unit weight γ_s [N/m³]"
    )
    friction_coefficient: float | None = Field(None, gt=0.0, le=2.0, description="μ [-]")
    undrained_shear_strength: float | None = Field(None, gt=0.0, description="s_u [Pa]")
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


class EnvironmentTable(StrictModel):
    water_depth: float = Field(gt=0.0, le=5000.0, description="d [m]")
    water_density: float = Field(1025.0, ge=900.0, le=1100.0, description="ρ_w [kg/m³]")
    kinematic_viscosity: float = Field(1.19e-6, gt=0.0, description="ν [m²/s]")


class WavesTable(StrictModel):
    hs: float = Field(gt=0.0, le=30.0, description="H_s [m]")
    tp: float = Field(gt=0.0, le=40.0, description="T_p [s]")
    gamma: float | None = Field(None, ge=1.0, le=7.0, description="JONSWAP γ [-]")
    spectrum: Literal["jonswap", "pierson-moskowitz"] = "jonswap"
    direction_deg: float = Field(90.0, ge=0.0, le=360.0, description="to the pipe axis [deg]")
    spreading_s: float = Field(0.0, ge=0.0, le=100.0, description="cos^s exponent [-]")


class CurrentTable(StrictModel):
    velocity: float = Field(0.0, ge=0.0, le=10.0, description="V(z_r) [m/s]")
    reference_height: float = Field(1.0, gt=0.0, description="z_r [m]")
    direction_deg: float = Field(90.0, ge=0.0, le=360.0, description="to the pipe axis [deg]")
    z0: float | None = Field(None, gt=0.0, le=1.0, description="roughness z_0 [m]")


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


class DesignTable(StrictModel):
    safety_class: Literal["low", "normal", "high"] = "normal"
    region: Literal[
        "north_sea_winter", "north_sea_cyclonic", "gulf_of_mexico_winter", "gulf_of_mexico_cyclonic"
    ] = "north_sea_winter"
    vertical_conditions: list[Condition] = Field(
        default_factory=lambda: ["installation", "flooded", "hydrotest", "operation"]
    )
    vertical_safety_factor: float = Field(1.1, ge=1.0, le=2.0, description="γ_W [-]")
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

    @model_validator(mode="after")
    def _checks(self) -> StabilityCase:
        names = [c.name for c in self.combinations]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise ValueError(f"combination names must be unique (repeated: {sorted(dup)})")
        if self.design.solve_for == "concrete_thickness":
            if not self.pipe.is_buildup:
                raise ValueError("solve_for = 'concrete_thickness' needs the build-up [pipe] form")
            if self.design.layer not in [layer.name for layer in self.pipe.layers]:
                raise ValueError(
                    f"design.layer = {self.design.layer!r} is not one of the [[pipe.layers]] names"
                )
        if self.design.solve_for == "submerged_weight" and self.pipe.is_buildup:
            raise ValueError("solve_for = 'submerged_weight' needs the simple [pipe] form")
        return self

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
        w = self.waves
        hs = w.hs if combo is None or combo.hs is None else combo.hs
        tp = w.tp if combo is None or combo.tp is None else combo.tp
        gamma = w.gamma if combo is None or combo.gamma is None else combo.gamma
        return SeaState(
            hs=hs,
            tp=tp,
            gamma=None if w.spectrum != "jonswap" else gamma,
            spectrum=w.spectrum,
            direction_deg=w.direction_deg,
            spreading_s=w.spreading_s,
        )

    def current_object(self, combo: CombinationTable | None = None) -> Current:
        c = self.current
        v = (
            c.velocity
            if combo is None or combo.current_velocity is None
            else combo.current_velocity
        )
        return Current(
            velocity=v, reference_height=c.reference_height, direction_deg=c.direction_deg, z0=c.z0
        )

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


def load_stability_case(path: str | os.PathLike) -> StabilityCase:
    """Read and validate a TOML/JSON case file (:class:`onbottom._casefile.CaseFileError`)."""
    return load_case_file(path, StabilityCase)
