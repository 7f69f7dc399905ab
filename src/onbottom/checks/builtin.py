"""The built-in F109 design checks' rows, registered by :mod:`onbottom.checks.registry`.

``vertical`` (per condition): the flotation check, DNV-RP-F109 (2017) §3.3, Eq 3.1;
``absolute`` (per load combination): the absolute lateral and vertical checks, F109 §3.6,
Eqs 3.38–3.41. ``opts`` is a :class:`onbottom.checks.design.CheckOptions` (typed ``Any`` here so
that this module imports neither the registry nor the driver that runs the checks).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from onbottom.checks.absolute import absolute_lateral_stability
from onbottom.checks.vertical import vertical_stability
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand

__all__ = ["CheckRow"]


@dataclass(frozen=True, slots=True)
class CheckRow:
    """One check: ``name``, ``combination`` (load combination, or the condition for the
    flotation check), ``condition``, ``utilisation`` [-], ``passes``, ``details`` (dict of
    intermediate values, SI)."""

    name: str
    combination: str
    condition: str
    utilisation: float
    passes: bool
    details: dict

    def as_dict(self) -> dict:
        """``{name, combination, condition, utilisation, pass, details}``."""
        return {
            "name": self.name,
            "combination": self.combination,
            "condition": self.condition,
            "utilisation": self.utilisation,
            "pass": self.passes,
            "details": self.details,
        }


def _vertical_rows(props: Any, opts: Any, cond: str) -> list[CheckRow]:
    """The flotation check (F109 §3.3 Eq 3.1) in condition ``cond``: one row, none when the
    pipe has no buoyancy."""
    if not props.buoyancy > 0.0:
        return []
    v = vertical_stability(props, opts.vertical_safety_factor)
    details = {"specific_gravity": v.specific_gravity, "gamma_w": v.safety_factor}
    return [CheckRow("vertical_stability", cond, cond, v.utilisation, v.passes, details)]


def _absolute_rows(
    pipe: Pipe,
    seabed: Sand | Clay | Rock,
    environment: Environment,
    combo: LoadCombination,
    opts: Any,
    cond: str,
) -> list[CheckRow]:
    """The absolute lateral and vertical checks (F109 §3.6 Eqs 3.38, 3.39) of one load
    combination: two rows."""
    ss, cur = combo.sea_state, combo.current
    r = absolute_lateral_stability(
        pipe,
        seabed,
        hs=ss.hs,
        tp=ss.tp,
        depth=environment.water_depth,
        current_velocity=cur.velocity,
        current_reference_height=cur.reference_height,
        roughness=cur.z0,
        gamma=ss.gamma,
        spectrum=ss.spectrum,
        wave_direction_deg=ss.direction_deg,
        current_direction_deg=_to_half_turn(cur.direction_deg),
        spreading_s=ss.spreading_s or None,
        safety_class=opts.safety_class,
        region=opts.region,
        penetration=opts.penetration,
        trench_depth=opts.trench_depth,
        trench_angle_deg=opts.trench_angle_deg,
        permeable=opts.permeable,
        duration=ss.duration_s,
    )
    details = r.as_dict()
    return [
        CheckRow(
            "absolute_lateral",
            combo.name,
            cond,
            r.utilisation_lateral,
            r.utilisation_lateral <= 1.0,
            details,
        ),
        CheckRow(
            "absolute_vertical",
            combo.name,
            cond,
            r.utilisation_vertical,
            r.utilisation_vertical <= 1.0,
            details,
        ),
    ]


def _to_half_turn(angle_deg: float) -> float:
    """Map a direction in [0, 360] to [0, 180] with the same |sin| (current normal part)."""
    a = angle_deg % 360.0
    return a if a <= 180.0 else 360.0 - a
