"""The F109 design checks of one pipe section and the design solve, from built inputs.

What ``onbottom stability`` computes (:mod:`onbottom.cases.stability` builds the inputs from a
case file): :func:`evaluate_stability` runs :func:`~onbottom.checks.design.run_checks` on every
load combination and, when asked (:class:`DesignRequest`), the minimum concrete thickness
(:func:`~onbottom.checks.design.design_concrete_thickness`) or submerged weight
(:func:`~onbottom.checks.design.design_submerged_weight`); a design range with no passing value
is a result (``success`` false), not an error. :func:`penetration_outside_validity` names the
combinations whose embedment z_p/D exceeds 0.5 (outside F109 Eqs 3.19–3.22: the result is not
valid). The same inputs serve ``onbottom loads`` (:mod:`onbottom.checks.loads`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from onbottom._validate import non_negative, one_of, positive
from onbottom.checks.design import (
    CheckOptions,
    CheckRow,
    DesignResult,
    NoFeasibleDesignError,
    design_concrete_thickness,
    design_submerged_weight,
    penetration_outside_validity,
    run_checks,
)
from onbottom.checks.f109_generalized import generalized_table
from onbottom.errors import InputError
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.pipe_buildup import PipeBuildUp
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.status import Status

__all__ = [
    "SOLVE_FOR",
    "DesignBounds",
    "DesignRequest",
    "StabilityEvaluation",
    "StabilityInputs",
    "evaluate_stability",
    "f109_soil",
    "penetration_outside_validity",
    "section_summary",
    "solve_design",
]

SOLVE_FOR = ("none", "concrete_thickness", "submerged_weight")
"""What a design solve sizes: nothing, a coating layer's thickness or the submerged weight."""


@dataclass(frozen=True, kw_only=True)
class DesignBounds:
    """The search range of a design solve (:func:`solve_design`).

    Parameters
    ----------
    layer : str
        The coating layer sized by ``"concrete_thickness"`` (default ``"concrete"``).
    thickness_min, thickness_max : float
        Range of the layer thickness [m] (see
        :func:`~onbottom.checks.design.design_concrete_thickness`).
    weight_min, weight_max : float
        Range of the submerged weight [N/m] (see
        :func:`~onbottom.checks.design.design_submerged_weight`).
    """

    layer: str = "concrete"
    thickness_min: float = 0.0
    thickness_max: float = 0.25
    weight_min: float = 1.0
    weight_max: float = 2.0e4

    def __post_init__(self) -> None:
        name = type(self).__name__
        non_negative(f"{name}.thickness_min", self.thickness_min)
        if positive(f"{name}.thickness_max", self.thickness_max) <= self.thickness_min:
            raise InputError(
                f"{name}.thickness_max = {self.thickness_max!r} is invalid: must be >"
                f" thickness_min = {self.thickness_min!r} m"
            )
        if positive(f"{name}.weight_max", self.weight_max) <= positive(
            f"{name}.weight_min", self.weight_min
        ):
            raise InputError(
                f"{name}.weight_max = {self.weight_max!r} is invalid: must be >"
                f" weight_min = {self.weight_min!r} N/m"
            )


@dataclass(frozen=True, kw_only=True)
class DesignRequest(DesignBounds):
    """The design solve of :func:`evaluate_stability`: ``solve_for``, one of
    :data:`SOLVE_FOR` (default ``"none"``: checks only), and the search range of
    :class:`DesignBounds` (``layer``, ``thickness_min``/``thickness_max`` [m],
    ``weight_min``/``weight_max`` [N/m])."""

    solve_for: str = "none"

    def __post_init__(self) -> None:
        one_of("solve_for", self.solve_for, SOLVE_FOR)
        super().__post_init__()


def solve_design(
    variable: str,
    section: PipeBuildUp | Pipe,
    seabed: Sand | Clay | Rock,
    environment: Environment,
    combinations: Sequence[LoadCombination],
    options: CheckOptions,
    bounds: DesignBounds,
) -> DesignResult:
    """The minimum ``variable`` (``"concrete_thickness"`` of ``bounds.layer`` [m], else the
    submerged weight [N/m]) in the range of ``bounds`` passing every check of ``options``
    (:func:`~onbottom.checks.design.design_concrete_thickness` or
    :func:`~onbottom.checks.design.design_submerged_weight`; no passing value:
    :class:`~onbottom.checks.design.NoFeasibleDesignError`)."""
    args = (section, seabed, environment, combinations, options)
    if variable == "concrete_thickness":
        return design_concrete_thickness(
            *args,
            layer=bounds.layer,
            thickness_min=bounds.thickness_min,
            thickness_max=bounds.thickness_max,
        )
    return design_submerged_weight(
        *args, weight_min=bounds.weight_min, weight_max=bounds.weight_max
    )


@dataclass(frozen=True, kw_only=True)
class StabilityInputs:
    """Built inputs of the F109 checks of one section.

    ``section`` (a :class:`~onbottom.inputs.pipe_buildup.PipeBuildUp` or a simple
    :class:`~onbottom.inputs.pipe.Pipe`), ``seabed``, ``environment``, the load
    ``combinations``, the check ``options``, the pipe ``condition`` the section is reported in
    (``"operation"``…; a simple pipe has one) and the ``design`` solve.
    """

    section: PipeBuildUp | Pipe
    seabed: Sand | Clay | Rock
    environment: Environment
    combinations: tuple[LoadCombination, ...]
    options: CheckOptions = field(default_factory=CheckOptions)
    condition: str = "operation"
    design: DesignRequest = field(default_factory=DesignRequest)


@dataclass(frozen=True)
class StabilityEvaluation:
    """Result of :func:`evaluate_stability`: the reported ``section`` (see
    :func:`section_summary`), the check ``rows``, the ``design`` solve (a dict:
    ``solve_for`` and, when solved, :meth:`~onbottom.checks.design.DesignResult.as_dict` and
    the designed ``section``, or ``success`` false with the best value found) and the
    ``invalid`` notes of :func:`penetration_outside_validity`; ``generalized``: F109's
    generalized method at the given design per combination, L_stable and L_10 from F109's
    tables (:func:`onbottom.checks.f109_generalized.generalized_table`; shown, not a pass/fail
    row)."""

    section: dict[str, Any]
    rows: tuple[CheckRow, ...]
    design: dict[str, Any]
    invalid: tuple[str, ...] = ()
    generalized: tuple[dict[str, Any], ...] = ()

    @property
    def success(self) -> bool:
        """A valid result: the design solve (if any) found a value and no embedment is
        outside F109's validity. Failing checks are a result: they do not clear it."""
        return bool(self.design.get("success", True)) and not self.invalid

    @property
    def message(self) -> str:
        if self.invalid:
            return "; ".join(self.invalid)
        return "" if self.design.get("success", True) else "the design solve has no solution"

    @property
    def all_pass(self) -> bool:
        return all(r.passes for r in self.rows)

    def as_dict(self) -> dict[str, Any]:
        """``{section, checks, success, message, all_pass, design}`` (JSON-ready)."""
        return {
            "section": self.section,
            "checks": [
                {k: v for k, v in r.as_dict().items() if k != "details"} | {"details": r.details}
                for r in self.rows
            ],
            "success": self.success,
            "message": self.message,
            "all_pass": self.all_pass,
            "design": self.design,
            "generalized": list(self.generalized),
        }


def section_summary(section: PipeBuildUp | Pipe, condition: str) -> dict[str, Any]:
    """The section's properties in ``condition`` (a build-up:
    :meth:`~onbottom.inputs.pipe_buildup.PipeBuildUp.properties`; a simple pipe: ``"as given"``
    with D [m], w_s [N/m], s_g [-] and the buoyancy [N/m])."""
    if isinstance(section, PipeBuildUp):
        return section.properties(condition).as_dict()
    return {
        "condition": "as given",
        "outer_diameter": section.outer_diameter,
        "submerged_weight": section.submerged_weight,
        "specific_gravity": section.specific_gravity,
        "buoyancy": section.buoyancy,
    }


def evaluate_stability(inputs: StabilityInputs) -> StabilityEvaluation:
    """The F109 checks of ``inputs`` (:func:`~onbottom.checks.design.run_checks`) and its
    design solve; a design range where nothing passes gives ``design["success"]`` false with
    the best value and utilisation found (not an error)."""
    i = inputs
    rows = run_checks(i.section, i.seabed, i.environment, i.combinations, i.options)
    d = i.design
    design: dict[str, Any] = {"solve_for": d.solve_for}
    if d.solve_for != "none":
        try:
            res = solve_design(
                d.solve_for, i.section, i.seabed, i.environment, i.combinations, i.options, d
            )
            design.update(res.as_dict())
            design["section"] = section_summary(res.section, i.condition)
        except NoFeasibleDesignError as exc:
            design.update(
                {
                    "success": False,
                    "status": int(Status.NO_SOLUTION),
                    "message": str(exc),
                    "variable": exc.variable,
                    "value": None,
                    "best_value": exc.best_value,
                    "best_utilisation": exc.best_utilisation,
                }
            )
    return StabilityEvaluation(
        section=section_summary(i.section, i.condition),
        rows=tuple(rows),
        design=design,
        invalid=tuple(penetration_outside_validity(rows)),
        generalized=tuple(
            generalized_table(rows, f109_soil(i.seabed), i.environment.water_density)
        ),
    )


def f109_soil(seabed: Sand | Clay | Rock) -> str | None:
    """The soil of F109's generalized tables for a seabed: ``"sand"`` (silica sand),
    ``"clay"``, or None (calcareous sand, rock: not covered by F109 §3.5)."""
    if isinstance(seabed, Sand):
        return "sand" if seabed.kind == "silica" else None
    return "clay" if isinstance(seabed, Clay) else None
