"""Hydrodynamic loads per unit length on a pipe on the seabed (pure numpy).

Morison-type horizontal load and lift (DNV-RP-F109 (2010/2017) §3.4; standard forms, see
docs/theory/section_dynamics.md):

F_Y(t) = ½ ρ_w D C_D (U+V)|U+V| + (π/4) ρ_w D² C_M dU/dt
F_Z(t) = ½ ρ_w D C_L (U+V)²

U(t) wave-induced near-bed velocity, V steady current (both normal to the pipe), ρ_w seawater
density, D outer diameter. The constant coefficients are a simple model: DNV-RP-F109
recommends coefficients depending on K, M and the embedment, or a wake model, for design.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onbottom._validate import non_negative, positive
from onbottom.constants import RHO_SEAWATER

__all__ = ["MorisonCoefficients", "horizontal_force", "lift_force"]


@dataclass(frozen=True, kw_only=True, slots=True)
class MorisonCoefficients:
    """Constant hydrodynamic coefficients of a pipe on the seabed.

    Parameters
    ----------
    drag : float
        C_D [-], >= 0. Default 0.9 (common value for a pipe on the seabed; not an F109
        prescription).
    inertia : float
        C_M [-], >= 0. Default 3.29 = 1 + C_a with C_a = π²/3 − 1, the potential-flow value
        for a cylinder on a plane wall.
    lift : float
        C_L [-], >= 0. Default 0.9 (common value; not an F109 prescription).
    """

    drag: float = 0.9
    inertia: float = 3.29
    lift: float = 0.9

    def __post_init__(self) -> None:
        non_negative("MorisonCoefficients.drag", self.drag)
        non_negative("MorisonCoefficients.inertia", self.inertia)
        non_negative("MorisonCoefficients.lift", self.lift)


def horizontal_force(
    velocity: np.ndarray,
    acceleration: np.ndarray,
    current: float,
    diameter: float,
    coefficients: MorisonCoefficients = MorisonCoefficients(),
    density: float = RHO_SEAWATER,
) -> np.ndarray:
    """Horizontal (drag + inertia) load F_Y [N/m] (Morison; DNV-RP-F109 §3.4).

    Parameters
    ----------
    velocity : array
        Wave-induced near-bed velocity U(t) [m/s].
    acceleration : array
        dU/dt [m/s²].
    current : float
        Steady current V normal to the pipe [m/s].
    diameter : float
        Outer diameter D [m], > 0.
    coefficients : MorisonCoefficients
        C_D, C_M.
    density : float
        ρ_w [kg/m³], > 0.
    """
    d = positive("diameter", diameter)
    rho = positive("density", density)
    u = np.asarray(velocity, dtype=float) + current
    du = np.asarray(acceleration, dtype=float)
    drag = 0.5 * rho * d * coefficients.drag * u * np.abs(u)
    inertia = 0.25 * math.pi * rho * d**2 * coefficients.inertia * du
    return drag + inertia


def lift_force(
    velocity: np.ndarray,
    current: float,
    diameter: float,
    coefficients: MorisonCoefficients = MorisonCoefficients(),
    density: float = RHO_SEAWATER,
) -> np.ndarray:
    """Lift F_Z = ½ ρ_w D C_L (U+V)² [N/m], positive upward (reduces V = W_s − F_Z)."""
    d = positive("diameter", diameter)
    rho = positive("density", density)
    u = np.asarray(velocity, dtype=float) + current
    return 0.5 * rho * d * coefficients.lift * u**2
