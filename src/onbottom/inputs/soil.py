"""Seabed descriptions: sand, clay, rock (immutable, validated; no resistance physics here)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from onbottom._validate import (
    FRICTION_COEFFICIENT,
    SOIL_UNIT_WEIGHT_N_M3,
    in_range,
    non_negative,
    plausible,
    positive,
)

__all__ = ["Clay", "Rock", "Sand", "Seabed"]


def _unit_weight(field: str, value: float) -> None:
    err, usual = SOIL_UNIT_WEIGHT_N_M3
    plausible(
        field, value, error=err, usual=usual, unit="N/m³", what="γ' of seabed soils", stacklevel=5
    )


def _friction(field: str, value: float) -> None:
    err, usual = FRICTION_COEFFICIENT
    plausible(
        field, value, error=err, usual=usual, unit="", what="pipe–soil friction", stacklevel=5
    )


@dataclass(frozen=True, kw_only=True, slots=True)
class Sand:
    """A sandy seabed (drained behaviour).

    Parameters
    ----------
    submerged_unit_weight : float
        γ' [N/m³], in [1 000, 25 000] (an error outside; a warning outside the usual
        3 000–18 000). For dry centrifuge samples use the dry unit weight.
    friction_coefficient : float
        Pipe–soil Coulomb friction μ [-], in (0, 2]. DNV-RP-F109 default for sand: 0.6.
    friction_angle_deg : float
        Drained (peak or design) friction angle φ' [deg], in [15, 50]; used by DNVGL-RP-F114.
    d50 : float
        Median grain size [m], > 0 (0.25 mm = fine sand); used for seabed roughness.
    kind : str
        Free label, e.g. "silica" or "calcareous".
    """

    submerged_unit_weight: float
    friction_coefficient: float = 0.6
    friction_angle_deg: float = 35.0
    d50: float = 2.5e-4
    kind: str = "silica"

    def __post_init__(self) -> None:
        _unit_weight("Sand.submerged_unit_weight", self.submerged_unit_weight)
        in_range(
            "Sand.friction_coefficient", self.friction_coefficient, 0.0, 2.0, low_inclusive=False
        )
        _friction("Sand.friction_coefficient", self.friction_coefficient)
        in_range("Sand.friction_angle_deg", self.friction_angle_deg, 15.0, 50.0)
        positive("Sand.d50", self.d50)

    @property
    def friction_angle(self) -> float:
        """φ' [rad]."""
        return math.radians(self.friction_angle_deg)


@dataclass(frozen=True, kw_only=True, slots=True)
class Clay:
    """A clayey seabed (undrained behaviour).

    Parameters
    ----------
    undrained_shear_strength : float
        s_u at the mudline [Pa], > 0.
    strength_gradient : float
        ds_u/dz [Pa/m], >= 0 (ρ in DNVGL-RP-F114).
    submerged_unit_weight : float
        γ' [N/m³], in [1 000, 25 000] (warning outside 3 000–18 000).
    unit_weight : float
        Total (dry/bulk) unit weight γ_s [N/m³], > submerged; the Verley & Lund (1995)
        parameter G_c = s_u/(D·γ_s) uses it (DNV-RP-F109 §3.4.6).
    friction_coefficient : float
        μ [-], in (0, 2]. DNV-RP-F109 default for clay: 0.2.
    """

    undrained_shear_strength: float
    submerged_unit_weight: float
    unit_weight: float
    strength_gradient: float = 0.0
    friction_coefficient: float = 0.2

    def __post_init__(self) -> None:
        positive("Clay.undrained_shear_strength", self.undrained_shear_strength)
        non_negative("Clay.strength_gradient", self.strength_gradient)
        _unit_weight("Clay.submerged_unit_weight", self.submerged_unit_weight)
        in_range("Clay.unit_weight", self.unit_weight, self.submerged_unit_weight, 3.0e4)
        in_range(
            "Clay.friction_coefficient", self.friction_coefficient, 0.0, 2.0, low_inclusive=False
        )
        _friction("Clay.friction_coefficient", self.friction_coefficient)

    def strength_at(self, depth: float) -> float:
        """s_u at ``depth`` below the mudline [Pa] (linear profile)."""
        return self.undrained_shear_strength + self.strength_gradient * max(depth, 0.0)


@dataclass(frozen=True, kw_only=True, slots=True)
class Rock:
    """A rock seabed: Coulomb friction only, no penetration (DNV-RP-F109 §3.4.6).

    Parameters
    ----------
    friction_coefficient : float
        μ [-], in (0, 2]. Typical 0.5–0.7.
    """

    friction_coefficient: float = 0.6

    def __post_init__(self) -> None:
        in_range(
            "Rock.friction_coefficient", self.friction_coefficient, 0.0, 2.0, low_inclusive=False
        )


Seabed = Sand | Clay | Rock
"""Any seabed description."""
