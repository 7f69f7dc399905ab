"""Pipe cross-section description (immutable, validated, no physics beyond geometry and weight)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from onbottom._validate import PIPE_DIAMETER_M, in_range, non_negative, plausible, positive
from onbottom.constants import GRAVITY, RHO_SEAWATER, RHO_STEEL
from onbottom.errors import InputError

__all__ = ["Layer", "Pipe"]


@dataclass(frozen=True, kw_only=True, slots=True)
class Layer:
    """A concentric coating layer (corrosion coating, insulation, concrete weight coat).

    Parameters
    ----------
    thickness : float
        Radial thickness [m], >= 0.
    density : float
        Density of the layer material [kg/m³], > 0.
    name : str
        Label for reports ("FBE", "concrete", ...).
    """

    thickness: float
    density: float
    name: str = "coating"

    def __post_init__(self) -> None:
        non_negative("Layer.thickness", self.thickness)
        positive("Layer.density", self.density)


@dataclass(frozen=True, kw_only=True, slots=True)
class Pipe:
    """A pipe section for on-bottom analysis.

    Give the outer diameter and submerged weight directly, or build them from layers with
    :meth:`from_layers`.

    Parameters
    ----------
    outer_diameter : float
        Total outer diameter D including all coatings [m], > 0. This is the D of the soil and
        hydrodynamic models.
    submerged_weight : float
        Submerged weight per unit length W_s [N/m], > 0 (weight in air minus buoyancy).
    mass : float or None
        Structural mass per unit length including contents [kg/m]. If None it is derived from
        the submerged weight: ``(W_s + ρ_w g π D²/4) / g``.
    bending_stiffness : float
        EI [N·m²], >= 0 (0 = not given; needed only by lay-factor and FE models).
    axial_stiffness : float
        EA [N], >= 0 (0 = not given; needed by the pipeline FE model).
    seawater_density : float
        ρ_w [kg/m³] used for buoyancy, > 0.
    """

    outer_diameter: float
    submerged_weight: float
    mass: float | None = None
    bending_stiffness: float = 0.0
    axial_stiffness: float = 0.0
    seawater_density: float = RHO_SEAWATER
    layers: tuple[Layer, ...] = field(default=())

    def __post_init__(self) -> None:
        positive("Pipe.outer_diameter", self.outer_diameter)
        err, usual = PIPE_DIAMETER_M
        plausible(
            "Pipe.outer_diameter",
            self.outer_diameter,
            error=err,
            usual=usual,
            unit="m",
            what="the outer diameter of a pipeline",
            stacklevel=4,
        )
        positive("Pipe.submerged_weight", self.submerged_weight)
        if self.submerged_weight > 1.0e6:
            raise InputError(
                f"Pipe.submerged_weight = {float(self.submerged_weight)!r} N/m is invalid:"
                " above the plausible 1e6 N/m (check the unit: N/m, not kN/m·1000)"
            )
        positive("Pipe.seawater_density", self.seawater_density)
        non_negative("Pipe.bending_stiffness", self.bending_stiffness)
        non_negative("Pipe.axial_stiffness", self.axial_stiffness)
        if self.mass is not None:
            positive("Pipe.mass", self.mass)
            if self.mass * GRAVITY < self.submerged_weight:
                raise InputError(
                    f"Pipe.mass = {self.mass!r} kg/m is invalid: weight in air m·g must be at least"
                    f" the submerged weight {self.submerged_weight:g} N/m"
                )

    # ---- derived quantities -------------------------------------------------------------
    @property
    def buoyancy(self) -> float:
        """Buoyancy per unit length ρ_w·g·π·D²/4 [N/m]."""
        return self.seawater_density * GRAVITY * math.pi * self.outer_diameter**2 / 4.0

    @property
    def structural_mass(self) -> float:
        """Mass per unit length [kg/m] (given, or derived from W_s and buoyancy)."""
        if self.mass is not None:
            return self.mass
        return (self.submerged_weight + self.buoyancy) / GRAVITY

    @property
    def specific_gravity(self) -> float:
        """Specific gravity s_g = (W_s + b)/b [-]."""
        return (self.submerged_weight + self.buoyancy) / self.buoyancy

    def added_mass(self, coefficient: float = 2.29) -> float:
        """Hydrodynamic added mass per unit length C_a·ρ_w·π·D²/4 [kg/m].

        ``coefficient`` is C_a [-]; the default 2.29 = π²/3 − 1 is the potential-flow value
        for a cylinder resting on a plane wall (DNV-RP-F109 background; C_M = 1 + C_a = 3.29).
        """
        non_negative("added_mass.coefficient", coefficient)
        return coefficient * self.seawater_density * math.pi * self.outer_diameter**2 / 4.0

    # ---- constructors -------------------------------------------------------------------
    @classmethod
    def from_layers(
        cls,
        *,
        steel_outer_diameter: float,
        wall_thickness: float,
        layers: tuple[Layer, ...] = (),
        steel_density: float = RHO_STEEL,
        contents_density: float = 0.0,
        seawater_density: float = RHO_SEAWATER,
        youngs_modulus: float = 207e9,
    ) -> Pipe:
        """Build a pipe from steel wall, coating layers and contents.

        Parameters
        ----------
        steel_outer_diameter : float
            Steel outer diameter D_s [m], > 0.
        wall_thickness : float
            Steel wall thickness t [m], 0 < t <= D_s/2.
        layers : tuple of Layer
            Coatings from the steel outwards.
        steel_density : float
            [kg/m³], > 0.
        contents_density : float
            Density of the bore contents [kg/m³], >= 0 (0 = empty/gas-filled).
        seawater_density : float
            ρ_w [kg/m³], > 0.
        youngs_modulus : float
            Steel E [Pa], > 0; the bending and axial stiffnesses use the steel wall only.
        """
        from onbottom.inputs import consistency

        consistency.raise_first(consistency.youngs_modulus(youngs_modulus, field="youngs_modulus"))
        ds = positive("Pipe.steel_outer_diameter", steel_outer_diameter)
        t = in_range("Pipe.wall_thickness", wall_thickness, 0.0, ds / 2.0, low_inclusive=False)
        positive("Pipe.steel_density", steel_density)
        non_negative("Pipe.contents_density", contents_density)
        positive("Pipe.youngs_modulus", youngs_modulus)
        di = ds - 2.0 * t
        mass = steel_density * math.pi * (ds**2 - di**2) / 4.0
        mass += contents_density * math.pi * di**2 / 4.0
        d = ds
        for layer in layers:
            d_out = d + 2.0 * layer.thickness
            mass += layer.density * math.pi * (d_out**2 - d**2) / 4.0
            d = d_out
        buoyancy = seawater_density * GRAVITY * math.pi * d**2 / 4.0
        ws = mass * GRAVITY - buoyancy
        if ws <= 0.0:
            raise InputError(
                f"Pipe.submerged_weight = {ws:.6g} N/m (from layers) is invalid: the pipe floats;"
                " add weight coating or contents (must be > 0)"
            )
        ei = youngs_modulus * math.pi * (ds**4 - di**4) / 64.0
        ea = youngs_modulus * math.pi * (ds**2 - di**2) / 4.0
        return cls(
            outer_diameter=d,
            submerged_weight=ws,
            mass=mass,
            bending_stiffness=ei,
            axial_stiffness=ea,
            seawater_density=seawater_density,
            layers=tuple(layers),
        )
