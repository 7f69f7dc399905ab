"""Vertical stability in water (DNVGL-RP-F109 (2017) §3.3, Eq 3.1).

    γ_W · b / (w_s + b) <= 1.0,   γ_W = 1.1

b buoyancy per unit length, w_s submerged weight; equivalently s_g >= γ_W with the specific
gravity s_g = (w_s + b)/b. The utilisation is γ_W/s_g. F109 §3.3 requires it for pipes on
or in the seabed in every condition where the pipe should not float (installation empty,
flooded, hydrotest, operation); for buried pipes in soils liable to liquefy it adds a check
against the soil's density, not implemented here.
"""

from __future__ import annotations

from dataclasses import dataclass

from onbottom._validate import in_range, positive
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.pipe_buildup import PipeProperties

__all__ = ["VERTICAL_SAFETY_FACTOR", "VerticalStabilityResult", "vertical_stability"]

VERTICAL_SAFETY_FACTOR = 1.1
"""γ_W [-] of DNV-RP-F109 (2017) Eq 3.1."""


@dataclass(frozen=True, slots=True)
class VerticalStabilityResult:
    """``utilisation`` = γ_W b/(w_s + b) [-], ``passes`` (<= 1), ``specific_gravity`` s_g [-],
    ``safety_factor`` γ_W [-]."""

    utilisation: float
    passes: bool
    specific_gravity: float
    safety_factor: float


def vertical_stability(
    section: Pipe | PipeProperties, safety_factor: float = VERTICAL_SAFETY_FACTOR
) -> VerticalStabilityResult:
    """F109 vertical stability (Eq 3.1) of a :class:`Pipe` or a build-up's properties.

    Parameters
    ----------
    section : Pipe or PipeProperties
        Provides the buoyancy b [N/m] and the submerged weight w_s [N/m] (may be <= 0 for
        :class:`PipeProperties`: a floating pipe fails with utilisation > 1).
    safety_factor : float
        γ_W [-], in [1, 2] (F109: 1.1).
    """
    in_range("safety_factor", safety_factor, 1.0, 2.0)
    if not isinstance(section, (Pipe, PipeProperties)):
        raise InputError(f"section = {section!r} is invalid: expected Pipe or PipeProperties")
    b = positive("buoyancy", section.buoyancy)
    sg = (section.submerged_weight + b) / b
    util = safety_factor * b / (section.submerged_weight + b) if sg > 0.0 else float("inf")
    return VerticalStabilityResult(
        utilisation=util, passes=bool(util <= 1.0), specific_gravity=sg, safety_factor=safety_factor
    )
