"""Pipe build-up: steel wall, coatings, marine growth and contents per condition.

A :class:`PipeBuildUp` describes the cross-section once; :meth:`PipeBuildUp.properties` gives
the derived section properties for one condition (outer diameter, mass, weight in air,
buoyancy, submerged weight w_s, specific gravity s_g, EI, EA) and :meth:`PipeBuildUp.pipe`
the simple :class:`~onbottom.inputs.pipe.Pipe` the soil, hydro and dynamics models use.

Conditions (DNV-RP-F109 (2010/2017) §3.1 and §3.3 list the temporary and operational
phases): ``installation`` (empty / as laid), ``flooded``, ``hydrotest`` and ``operation``.
Geometry only: pure area × density sums, no physics beyond weight and stiffness.

* outer diameter D = D_s + 2 Σ t_i (+ 2 t_mg)
* mass m = Σ ρ_i A_i + ρ_c π D_i²/4, weight in air m g, buoyancy b = ρ_w g π D²/4
* w_s = m g − b, s_g = (w_s + b)/b = m g / b
* EI = E π (D_s⁴ − D_i⁴)/64, EA = E π (D_s² − D_i²)/4 (steel wall only: coatings are
  assumed not to contribute; concrete cracks and slips at field joints — a conservative choice
  for on-bottom stability, where only the lateral deflection of long spans depends on EI).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from onbottom._validate import in_range, non_negative, one_of, positive
from onbottom.constants import GRAVITY, RHO_SEAWATER, RHO_STEEL
from onbottom.errors import InputError
from onbottom.inputs import consistency
from onbottom.inputs.pipe import Layer, Pipe

__all__ = ["CONDITIONS", "Contents", "PipeBuildUp", "PipeProperties"]

CONDITIONS: tuple[str, ...] = ("installation", "flooded", "hydrotest", "operation")
"""Pipe conditions: empty as laid, water-flooded, hydrotest, operation."""


@dataclass(frozen=True, kw_only=True, slots=True)
class Contents:
    """Density of the bore contents per condition [kg/m³], each >= 0 (0 = empty/gas).

    Defaults: installation empty (0), flooded and hydrotest filled with sea water
    (1025 kg/m³), operation empty (give the product density).
    """

    installation: float = 0.0
    flooded: float = RHO_SEAWATER
    hydrotest: float = RHO_SEAWATER
    operation: float = 0.0

    def __post_init__(self) -> None:
        for name in CONDITIONS:
            in_range(f"Contents.{name}", getattr(self, name), 0.0, 2.0e4)

    def density(self, condition: str) -> float:
        """Contents density [kg/m³] in ``condition`` (one of :data:`CONDITIONS`)."""
        one_of("condition", condition, CONDITIONS)
        return float(getattr(self, condition))

    @classmethod
    def uniform(cls, density: float) -> Contents:
        """The same contents density [kg/m³] in every condition."""
        return cls(**{name: density for name in CONDITIONS})


@dataclass(frozen=True, kw_only=True, slots=True)
class PipeProperties:
    """Section properties of a :class:`PipeBuildUp` in one condition (all SI).

    Attributes: ``condition``; ``outer_diameter`` D [m] (hydrodynamic and soil diameter,
    marine growth included); ``steel_inner_diameter`` [m]; ``steel_mass``, ``coating_mass``,
    ``contents_mass``, ``mass`` (total) [kg/m]; ``weight_in_air`` [N/m]; ``buoyancy`` b [N/m];
    ``submerged_weight`` w_s [N/m]; ``specific_gravity`` s_g [-]; ``bending_stiffness`` EI
    [N·m²]; ``axial_stiffness`` EA [N]; ``seawater_density`` [kg/m³].
    """

    condition: str
    outer_diameter: float
    steel_inner_diameter: float
    steel_mass: float
    coating_mass: float
    contents_mass: float
    mass: float
    weight_in_air: float
    buoyancy: float
    submerged_weight: float
    specific_gravity: float
    bending_stiffness: float
    axial_stiffness: float
    seawater_density: float

    def as_dict(self) -> dict[str, float | str]:
        """Plain dict of the properties (for JSON output)."""
        return {name: getattr(self, name) for name in self.__slots__}


@dataclass(frozen=True, kw_only=True, slots=True)
class PipeBuildUp:
    """A pipe cross-section built from steel, coating layers, marine growth and contents.

    Parameters
    ----------
    steel_outer_diameter : float
        Steel outer diameter D_s [m], > 0.
    wall_thickness : float
        Steel wall thickness t [m], 0 < t < D_s/2.
    steel_density : float
        [kg/m³], > 0 (default 7850).
    youngs_modulus : float
        Steel Young's modulus E [Pa], in [1e10, 3e11] (default 207 GPa; 207000 is MPa typed
        as Pa: an error).
    layers : tuple of Layer
        Coatings from the steel outwards (corrosion coat, insulation, concrete), any number.
    marine_growth : Layer or None
        Marine growth, outermost; adds to D and to the mass.
    contents : Contents
        Contents density per condition.
    seawater_density : float
        ρ_w [kg/m³], > 0.
    """

    steel_outer_diameter: float
    wall_thickness: float
    steel_density: float = RHO_STEEL
    youngs_modulus: float = 207.0e9
    layers: tuple[Layer, ...] = field(default=())
    marine_growth: Layer | None = None
    contents: Contents = field(default_factory=Contents)
    seawater_density: float = RHO_SEAWATER

    def __post_init__(self) -> None:
        ds = positive("PipeBuildUp.steel_outer_diameter", self.steel_outer_diameter)
        in_range(
            "PipeBuildUp.wall_thickness",
            self.wall_thickness,
            0.0,
            ds / 2.0,
            low_inclusive=False,
            high_inclusive=False,
        )
        positive("PipeBuildUp.steel_density", self.steel_density)
        positive("PipeBuildUp.youngs_modulus", self.youngs_modulus)
        consistency.raise_first(
            consistency.youngs_modulus(self.youngs_modulus, field="PipeBuildUp.youngs_modulus")
        )
        positive("PipeBuildUp.seawater_density", self.seawater_density)
        object.__setattr__(self, "layers", tuple(self.layers))
        for i, layer in enumerate(self.layers):
            if not isinstance(layer, Layer):
                raise InputError(
                    f"PipeBuildUp.layers[{i}] = {layer!r} is invalid: expected a Layer"
                )
        if self.marine_growth is not None and not isinstance(self.marine_growth, Layer):
            raise InputError(
                f"PipeBuildUp.marine_growth = {self.marine_growth!r} is invalid: expected a Layer"
            )
        if not isinstance(self.contents, Contents):
            raise InputError(
                f"PipeBuildUp.contents = {self.contents!r} is invalid: expected a Contents"
            )

    # ---- derived ------------------------------------------------------------------------
    @property
    def steel_inner_diameter(self) -> float:
        """D_i = D_s − 2t [m]."""
        return self.steel_outer_diameter - 2.0 * self.wall_thickness

    @property
    def outer_diameter(self) -> float:
        """Total outer diameter D including coatings and marine growth [m]."""
        d = self.steel_outer_diameter + 2.0 * sum(layer.thickness for layer in self.layers)
        if self.marine_growth is not None:
            d += 2.0 * self.marine_growth.thickness
        return d

    @property
    def bending_stiffness(self) -> float:
        """EI of the steel wall [N·m²]."""
        ds, di = self.steel_outer_diameter, self.steel_inner_diameter
        return self.youngs_modulus * math.pi * (ds**4 - di**4) / 64.0

    @property
    def axial_stiffness(self) -> float:
        """EA of the steel wall [N]."""
        ds, di = self.steel_outer_diameter, self.steel_inner_diameter
        return self.youngs_modulus * math.pi * (ds**2 - di**2) / 4.0

    def properties(self, condition: str = "operation") -> PipeProperties:
        """Section properties in ``condition`` (one of :data:`CONDITIONS`).

        Raises :class:`~onbottom.errors.InputError` if the condition is unknown; a floating
        pipe (w_s <= 0) is reported through ``submerged_weight`` <= 0, not an error, so that
        the vertical stability check can grade it.
        """
        rho_c = self.contents.density(condition)
        ds, di = self.steel_outer_diameter, self.steel_inner_diameter
        steel = self.steel_density * math.pi * (ds**2 - di**2) / 4.0
        coat = 0.0
        d = ds
        outer = list(self.layers)
        if self.marine_growth is not None:
            outer.append(self.marine_growth)
        for layer in outer:
            d_out = d + 2.0 * layer.thickness
            coat += layer.density * math.pi * (d_out**2 - d**2) / 4.0
            d = d_out
        contents = rho_c * math.pi * di**2 / 4.0
        mass = steel + coat + contents
        b = self.seawater_density * GRAVITY * math.pi * d**2 / 4.0
        w_air = mass * GRAVITY
        return PipeProperties(
            condition=condition,
            outer_diameter=d,
            steel_inner_diameter=di,
            steel_mass=steel,
            coating_mass=coat,
            contents_mass=contents,
            mass=mass,
            weight_in_air=w_air,
            buoyancy=b,
            submerged_weight=w_air - b,
            specific_gravity=w_air / b,
            bending_stiffness=self.bending_stiffness,
            axial_stiffness=self.axial_stiffness,
            seawater_density=self.seawater_density,
        )

    def pipe(self, condition: str = "operation") -> Pipe:
        """The simple :class:`Pipe` (D, w_s, mass, EI, EA) in ``condition``.

        Raises :class:`~onbottom.errors.InputError` if the pipe floats (w_s <= 0) in it.
        """
        p = self.properties(condition)
        if p.submerged_weight <= 0.0:
            raise InputError(
                f"Pipe.submerged_weight = {p.submerged_weight:.6g} N/m in condition"
                f" {condition!r} is invalid: the pipe floats (must be > 0); add weight coating"
            )
        return Pipe(
            outer_diameter=p.outer_diameter,
            submerged_weight=p.submerged_weight,
            mass=p.mass,
            bending_stiffness=p.bending_stiffness,
            axial_stiffness=p.axial_stiffness,
            seawater_density=self.seawater_density,
            layers=self.layers,
        )

    def layer_index(self, name: str) -> int:
        """Index of the coating layer called ``name`` (InputError if absent)."""
        names = [layer.name for layer in self.layers]
        if name not in names:
            raise InputError(
                f"layer = {name!r} is invalid: must be one of the pipe's layers {names}"
            )
        return names.index(name)

    def with_layer_thickness(self, name: str, thickness: float) -> PipeBuildUp:
        """A copy with the layer ``name`` set to ``thickness`` [m] (>= 0)."""
        non_negative(f"{name}.thickness", thickness)
        i = self.layer_index(name)
        layers = list(self.layers)
        layers[i] = replace(layers[i], thickness=thickness)
        return replace(self, layers=tuple(layers))
