"""The case tables every case kind shares, and the :class:`Checker` that reports their errors.

``[pipe]`` (simple or build-up form), ``[seabed]``, ``[environment]``, ``[waves]``,
``[current]``, ``[[combinations]]``, ``[hydro]`` and ``[storm]`` (with its stages) are read by
several commands (``stability``, ``loads``, ``storm``, ``curves``, ``assess``, ...); each case
module builds its own case from these tables. They live here, below the case modules, so that no
case module imports another for its tables.
"""

from __future__ import annotations

import os
import re
import warnings
from pathlib import Path
from typing import Any, Literal, NoReturn

from pydantic import Field, field_validator, model_validator

from onbottom._casefile import CaseFileError, StrictModel, find_key_line
from onbottom.cases.models import collect_model_tables
from onbottom.constants import KINEMATIC_VISCOSITY_SEAWATER
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.inputs import consistency
from onbottom.inputs.pipe import Layer, Pipe
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.inputs.storm import Current, SeaState

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
        if k not in used.split(", ")
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


class SeawaterTable(StrictModel):
    """Sea-water properties shared by ``[environment]`` and a route's ``[environment]``."""

    water_density: float = Field(1025.0, ge=900.0, le=1100.0, description="ρ_w [kg/m³]")
    kinematic_viscosity: float = Field(
        KINEMATIC_VISCOSITY_SEAWATER,
        ge=1.0e-7,
        le=1.0e-4,
        description="ν [m²/s] (not used: default only)",
    )

    _nu = field_validator("kinematic_viscosity")(viscosity_not_used)


class EnvironmentTable(SeawaterTable):
    water_depth: float = Field(gt=0.0, le=5000.0, description="d [m]")


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
    return re.sub(r"np\.(?:float|int|uint|bool_?|str_)\d*\(([^()]*)\)", r"\1", text)


class StageTable(StrictModel):
    hs: float = Field(gt=0.0, le=30.0, description="H_s [m]")
    tp: float = Field(gt=0.0, le=40.0, description="T_p [s]")
    duration_hours: float = Field(gt=0.0, le=100.0, description="stage duration [h]")
    gamma: float | None = Field(None, ge=1.0, le=7.0, description="JONSWAP γ [-]")
    spectrum: Literal["jonswap", "pierson-moskowitz"] | None = None
    direction_deg: float | None = Field(None, ge=0.0, le=360.0, description="[deg]")
    spreading_s: float | None = Field(None, ge=0.0, le=100.0, description="cos^s exponent [-]")


class StormTable(StrictModel):
    kind: Literal["spectral", "regular", "measured"] = Field(
        "spectral",
        description="spectral (random-phase JONSWAP storm), regular (Airy wave height/period)"
        " or measured (velocity series CSV)",
    )
    height: float | None = Field(None, gt=0.0, le=40.0, description="regular wave H [m]")
    period: float | None = Field(None, gt=0.0, le=40.0, description="regular wave T [s]")
    direction_deg: float | None = Field(
        None, ge=0.0, le=360.0, description="regular wave direction to the pipe axis [deg]"
    )
    series: str | None = Field(
        None, min_length=1, description="measured: CSV t [s], U [m/s][, dU/dt [m/s^2]]"
    )
    sampling_tolerance: float | None = Field(
        None, gt=0.0, le=0.5, description="measured: relative sampling-interval tolerance [-]"
    )
    seed: int = Field(0, ge=0, description="random-phase seed of the first storm [-]")
    build_up_hours: float | None = Field(None, ge=0.0, le=100.0, description="[h]")
    peak_hours: float | None = Field(None, gt=0.0, le=100.0, description="[h]")
    decay_hours: float = Field(0.0, ge=0.0, le=100.0, description="[h]")
    transition_s: float = Field(60.0, ge=0.0, description="blend between stages [s]")
    time_step: float = Field(0.1, gt=0.0, le=5.0, description="initial/largest step [s]")
    sample_interval: float | None = Field(
        None, gt=0.0, le=5.0, description="flow sample interval [s] (default T_p/50)"
    )
    stages: list[StageTable] = Field(default_factory=list)

    @model_validator(mode="after")
    def _stages_or_peak(self) -> StormTable:
        if self.stages and self.peak_hours is not None:
            raise ValueError(
                "give peak_hours (one peak from [waves]) or [[storm.stages]], not both"
            )
        own = {
            "spectral": (),
            "regular": ("height", "period", "direction_deg"),
            "measured": ("series", "sampling_tolerance"),
        }
        for kind, keys in own.items():
            if kind == self.kind:
                continue
            for key in keys:
                if getattr(self, key) is not None:
                    raise ValueError(f"{key} is for kind = {kind!r}, not {self.kind!r}")
        if self.kind != "spectral" and self.stages:
            raise ValueError(f"[[storm.stages]] are for kind = 'spectral', not {self.kind!r}")
        if self.kind == "regular" and (self.height is None or self.period is None):
            raise ValueError("kind = 'regular' needs height [m] and period [s]")
        if self.kind == "measured":
            if self.series is None:
                raise ValueError("kind = 'measured' needs series (a CSV file)")
            for key in ("build_up_hours", "peak_hours"):
                if getattr(self, key) is not None:
                    raise ValueError(
                        f"{key} is not used with kind = 'measured': the record sets the time"
                    )
        if self.kind != "spectral" and self.decay_hours:
            raise ValueError(f"decay_hours is for kind = 'spectral', not {self.kind!r}")
        return self
