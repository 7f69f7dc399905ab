"""F109 design checks per load combination, and the minimum concrete (or weight) design.

:func:`run_checks` evaluates, for a pipe build-up (or a simple pipe), a seabed, the water
column and a list of :class:`~onbottom.inputs.environment.LoadCombination`:

* ``vertical_stability`` — F109 (2017) §3.3 Eq 3.1 in every condition of
  ``options.vertical_conditions`` (flotation, γ_W = 1.1);
* ``absolute_lateral`` and ``absolute_vertical`` — F109 §3.6 Eqs 3.38 and 3.39 in every load
  combination, for the pipe in the combination's condition.

The checks are the ones named in ``options.checks``, looked up in
:mod:`onbottom.checks.registry` (these two: :mod:`onbottom.checks.builtin`). Each row has a
utilisation (pass at <= 1). :func:`design_concrete_thickness` finds the
smallest thickness of one coating layer in ``[t_min, t_max]`` for which every row passes;
:func:`design_submerged_weight` does the same for the submerged weight of a simple pipe.

Method (both): the governing utilisation u(x) = max over rows is evaluated on ``n_scan``
equally spaced values; the first passing value x_i and its predecessor bracket the root of
u(x) − 1, which Brent's method (:func:`onbottom._roots.brentq`, the criterion of
``scipy.optimize.brentq`` without importing scipy) refines to ``xtol``. A thicker coat adds weight
but also diameter and load, so u(x) need not be monotone: the answer is the smallest passing
value to the resolution of the scan. If no scanned value passes, :class:`NoFeasibleDesignError`
(a :class:`~onbottom.errors.SolutionError`) names the range and the lowest utilisation found.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from onbottom import _roots
from onbottom._validate import in_range, non_negative, one_of, positive
from onbottom.checks.builtin import CheckRow
from onbottom.checks.f109_tables import REGIONS, SAFETY_CLASSES
from onbottom.checks.registry import get_check
from onbottom.checks.vertical import VERTICAL_SAFETY_FACTOR
from onbottom.errors import InputError, OutOfRangeWarning, SolutionError
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.pipe_buildup import CONDITIONS, PipeBuildUp
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.status import Status

__all__ = [
    "CheckOptions",
    "CheckRow",
    "DesignResult",
    "NoFeasibleDesignError",
    "design_concrete_thickness",
    "design_submerged_weight",
    "governing",
    "minimum_passing",
    "penetration_outside_validity",
    "run_checks",
]


class NoFeasibleDesignError(SolutionError):
    """No value in the allowed design range passes every check.

    Attributes: ``variable`` (name), ``bounds`` (low, high), ``best_value`` and
    ``best_utilisation`` (the lowest governing utilisation found in the scan).
    """

    def __init__(
        self, message: str, *, variable: str, bounds: tuple[float, float], best: tuple[float, float]
    ) -> None:
        super().__init__(message)
        self.variable = variable
        self.bounds = bounds
        self.best_value, self.best_utilisation = best


@dataclass(frozen=True, kw_only=True, slots=True)
class CheckOptions:
    """Settings of the F109 checks.

    Parameters
    ----------
    safety_class : str
        ``"low"``, ``"normal"`` or ``"high"`` (γ_SC, F109 Tables 3-5 to 3-8).
    region : str
        One of :data:`onbottom.checks.f109_tables.REGIONS`.
    vertical_conditions : tuple of str
        Conditions checked for flotation (Eq 3.1); default all four.
    vertical_safety_factor : float
        γ_W [-] (F109: 1.1).
    penetration : float or None
        z_p [m] for the absolute check; None → initial penetration under w_s.
    trench_depth : float
        z_t [m], >= 0.
    trench_angle_deg : float
        Trench wall angle [deg], in [5, 45].
    permeable : bool or None
        r_perm,z = 0.7; None → sand and rock yes, clay no.
    checks : tuple of str
        The design checks run, in order: names in :data:`onbottom.checks.registry.CHECKS`
        (default ``("vertical", "absolute")``: flotation, then the absolute checks).
    """

    safety_class: str = "normal"
    region: str = "north_sea_winter"
    vertical_conditions: tuple[str, ...] = CONDITIONS
    vertical_safety_factor: float = VERTICAL_SAFETY_FACTOR
    penetration: float | None = None
    trench_depth: float = 0.0
    trench_angle_deg: float = 45.0
    permeable: bool | None = None
    checks: tuple[str, ...] = ("vertical", "absolute")

    def __post_init__(self) -> None:
        object.__setattr__(self, "checks", tuple(self.checks))
        for name in self.checks:
            get_check(name, where="checks")
        one_of("safety_class", self.safety_class, SAFETY_CLASSES)
        one_of("region", self.region, REGIONS)
        object.__setattr__(self, "vertical_conditions", tuple(self.vertical_conditions))
        for c in self.vertical_conditions:
            one_of("vertical_conditions", c, CONDITIONS)
        in_range("vertical_safety_factor", self.vertical_safety_factor, 1.0, 2.0)
        if self.penetration is not None:
            non_negative("penetration", self.penetration)
        non_negative("trench_depth", self.trench_depth)
        in_range("trench_angle_deg", self.trench_angle_deg, 5.0, 45.0)


def _pipe_in(section: PipeBuildUp | Pipe, condition: str) -> tuple[Pipe | None, object]:
    if isinstance(section, Pipe):
        return section, section
    props = section.properties(condition)
    if props.submerged_weight <= 0.0:
        return None, props
    return section.pipe(condition), props


def run_checks(
    section: PipeBuildUp | Pipe,
    seabed: Sand | Clay | Rock,
    environment: Environment,
    combinations: Sequence[LoadCombination],
    options: CheckOptions | None = None,
) -> list[CheckRow]:
    """All F109 checks of ``section`` (see the module docstring), one :class:`CheckRow` each.

    A simple :class:`Pipe` has no conditions: its flotation check is made once (condition
    ``"as given"``) and the combinations' conditions are ignored.
    """
    if not isinstance(section, (PipeBuildUp, Pipe)):
        raise InputError(f"section = {section!r} is invalid: expected PipeBuildUp or Pipe")
    if not isinstance(environment, Environment):
        raise InputError(f"environment = {environment!r} is invalid: expected Environment")
    opts = CheckOptions() if options is None else options
    combos = tuple(combinations)
    if not combos:
        raise InputError("combinations = () is invalid: give at least one load combination")
    for combo in combos:
        if not isinstance(combo, LoadCombination):
            raise InputError(f"combinations item {combo!r} is invalid: expected LoadCombination")
    rows: list[CheckRow] = []
    conditions = ("as given",) if isinstance(section, Pipe) else opts.vertical_conditions
    for check in (get_check(name, where="checks") for name in opts.checks):
        if check.per == "condition":
            for cond in conditions:
                props = section if isinstance(section, Pipe) else section.properties(cond)
                rows.extend(check.run(props, opts, cond))
            continue
        for combo in combos:
            cond = "as given" if isinstance(section, Pipe) else combo.condition
            pipe, props = _pipe_in(section, cond)
            if pipe is None:
                details = {"submerged_weight": props.submerged_weight, "message": "the pipe floats"}
                for name in check.rows:
                    rows.append(CheckRow(name, combo.name, cond, math.inf, False, details))
                continue
            rows.extend(check.run(pipe, seabed, environment, combo, opts, cond))
    return rows


def penetration_outside_validity(rows: Sequence[CheckRow]) -> list[str]:
    """Rows of the absolute check whose embedment z_p exceeds D/2 (outside F109 Eqs
    3.19–3.22 and the soil resistance models): one line per combination, empty if none."""
    out = []
    for r in rows:
        det = r.details
        if r.name != "absolute_lateral" or "penetration" not in det or "diameter" not in det:
            continue
        ratio = det["penetration"] / det["diameter"]
        if ratio > 0.5:
            out.append(
                f"combination {r.combination!r} ({r.condition}): embedment z_p/D = {ratio:.3g}"
                " > 0.5 lies outside the validity of F109 Eqs 3.19–3.22 (check the soil"
                " strength and its unit)"
            )
    return out


def governing(rows: Sequence[CheckRow]) -> CheckRow:
    """The row with the largest utilisation."""
    return max(rows, key=lambda r: r.utilisation)


@dataclass(frozen=True, slots=True)
class DesignResult:
    """Result of a design solve.

    ``success`` (True: ``status.success``), ``status`` (a :class:`~onbottom.status.Status`:
    ``CONVERGED`` (6), the minimum found inside the range; ``AT_BOUND`` (7), the lower bound
    already passes), ``message``; ``variable`` (``"concrete_thickness"`` [m] or
    ``"submerged_weight"`` [N/m]); ``value``; ``utilisation`` (governing, at ``value``);
    ``governing_check``; ``checks`` (rows at ``value``); ``section`` (the designed PipeBuildUp
    or Pipe).
    """

    success: bool
    status: Status
    message: str
    variable: str
    value: float
    utilisation: float
    governing_check: str
    checks: tuple[CheckRow, ...]
    section: PipeBuildUp | Pipe

    def as_dict(self) -> dict:
        """JSON-ready summary (without the check rows' details)."""
        return {
            "success": self.success,
            "status": int(self.status),
            "message": self.message,
            "variable": self.variable,
            "value": self.value,
            "utilisation": self.utilisation,
            "governing_check": self.governing_check,
        }


def minimum_passing(
    build: Callable[[float], PipeBuildUp | Pipe],
    evaluate: Callable[[PipeBuildUp | Pipe], list[CheckRow]],
    lo: float,
    hi: float,
    n_scan: int,
    xtol: float,
    variable: str,
    unit: str,
) -> DesignResult:
    """Smallest design value x in [lo, hi] whose check rows all pass (utilisation <= 1).

    The solver behind :func:`design_concrete_thickness` and :func:`design_submerged_weight`,
    for any set of checks: ``build(x)`` makes the trial section, ``evaluate(section)`` returns
    its :class:`CheckRow` list (the governing row decides). ``n_scan`` (>= 2) values are
    scanned from ``lo`` to ``hi``; the first passing one and its failing neighbour bracket
    the crossing, refined by Brent's method to ``xtol`` (in the unit of x) and returned on
    the passing side. Status ``AT_BOUND``: ``lo`` already passes; ``CONVERGED``: a crossing
    found. A governing utilisation that is not monotone in x between scan points can hide a
    narrower passing window: refine ``n_scan``.

    Parameters
    ----------
    build : callable
        x → the trial :class:`PipeBuildUp` or :class:`Pipe`.
    evaluate : callable
        Section → check rows (e.g. :func:`run_checks` or a subset of its rows).
    lo, hi : float
        Range of x, in ``unit`` (m for a thickness, N/m for a submerged weight).
    n_scan : int
        Number of scanned values [-], >= 2.
    xtol : float
        Root tolerance, in ``unit``, > 0.
    variable, unit : str
        Name and unit of x, for the result and the messages.

    Raises
    ------
    NoFeasibleDesignError
        No scanned value passes.
    """
    if n_scan < 2:
        raise InputError(f"n_scan = {n_scan!r} is invalid: must be >= 2")
    positive("xtol", xtol)

    def util(x: float) -> float:
        return governing(evaluate(build(x))).utilisation

    xs = np.linspace(lo, hi, n_scan)
    with warnings.catch_warnings():
        # the scan visits values far from the answer; only the final design's warnings count
        warnings.simplefilter("ignore", OutOfRangeWarning)
        us = np.array([util(float(x)) for x in xs])
    ok = np.flatnonzero(us <= 1.0)
    if ok.size == 0:
        ib = int(np.argmin(us))
        raise NoFeasibleDesignError(
            f"{variable} = [{lo:g}, {hi:g}] {unit} is invalid: no value in the range passes every"
            f" F109 check (lowest governing utilisation {us[ib]:.4g} at {xs[ib]:.4g} {unit});"
            " widen the range or change the section",
            variable=variable,
            bounds=(lo, hi),
            best=(float(xs[ib]), float(us[ib])),
        )
    i = int(ok[0])
    if i == 0:
        x, status = float(xs[0]), Status.AT_BOUND
        msg = f"the lower bound {lo:g} {unit} already passes"
    else:
        a, b = float(xs[i - 1]), float(xs[i])
        if math.isfinite(us[i - 1]):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", OutOfRangeWarning)
                x = _roots.brentq(lambda t: util(t) - 1.0, a, b, xtol=xtol)
                # brentq's root may sit a hair on the failing side: step to the passing side
                x = min(x + xtol, b) if util(x) > 1.0 else x
        else:
            x = b
        status, msg = Status.CONVERGED, f"minimum {variable} found to ±{xtol:g} {unit}"
    section = build(x)
    rows = evaluate(section)
    g = governing(rows)
    return DesignResult(
        status.success, status, msg, variable, x, g.utilisation, f"{g.name} / {g.combination}",
        tuple(rows), section,
    )  # fmt: skip


def design_concrete_thickness(
    buildup: PipeBuildUp,
    seabed: Sand | Clay | Rock,
    environment: Environment,
    combinations: Sequence[LoadCombination],
    options: CheckOptions | None = None,
    *,
    layer: str = "concrete",
    thickness_min: float = 0.0,
    thickness_max: float = 0.25,
    n_scan: int = 51,
    xtol: float = 1.0e-5,
) -> DesignResult:
    """Minimum thickness [m] of the coating ``layer`` that passes every F109 check.

    Parameters
    ----------
    buildup : PipeBuildUp
        The section; ``layer`` must be one of its layers (its thickness is replaced).
    seabed, environment, combinations, options
        As :func:`run_checks`.
    layer : str
        Name of the layer to size (default ``"concrete"``).
    thickness_min, thickness_max : float
        Allowed range [m], 0 <= min < max <= 1.
    n_scan : int
        Number of scanned thicknesses (>= 2).
    xtol : float
        Root tolerance [m].

    Raises
    ------
    NoFeasibleDesignError
        No thickness in the range passes.
    """
    if not isinstance(buildup, PipeBuildUp):
        raise InputError(f"buildup = {buildup!r} is invalid: expected PipeBuildUp")
    buildup.layer_index(layer)
    lo = in_range("thickness_min", thickness_min, 0.0, 1.0)
    hi = in_range("thickness_max", thickness_max, 0.0, 1.0)
    if hi <= lo:
        raise InputError(f"thickness_max = {hi!r} is invalid: must be > thickness_min = {lo!r}")
    return minimum_passing(
        lambda t: buildup.with_layer_thickness(layer, t),
        lambda s: run_checks(s, seabed, environment, combinations, options),
        lo,
        hi,
        n_scan,
        xtol,
        "concrete_thickness" if layer == "concrete" else f"{layer}_thickness",
        "m",
    )


def design_submerged_weight(
    pipe: Pipe,
    seabed: Sand | Clay | Rock,
    environment: Environment,
    combinations: Sequence[LoadCombination],
    options: CheckOptions | None = None,
    *,
    weight_min: float = 1.0,
    weight_max: float = 2.0e4,
    n_scan: int = 51,
    xtol: float = 0.1,
) -> DesignResult:
    """Minimum submerged weight w_s [N/m] of a simple pipe (fixed D) passing every check.

    ``weight_min``/``weight_max`` [N/m] bound the search (0 < min < max); ``xtol`` [N/m].
    Raises :class:`NoFeasibleDesignError` when none passes.
    """
    if not isinstance(pipe, Pipe):
        raise InputError(f"pipe = {pipe!r} is invalid: expected Pipe")
    lo = positive("weight_min", weight_min)
    hi = positive("weight_max", weight_max)
    if hi <= lo:
        raise InputError(f"weight_max = {hi!r} is invalid: must be > weight_min = {lo!r}")
    return minimum_passing(
        lambda w: replace(pipe, submerged_weight=w, mass=None),
        lambda s: run_checks(s, seabed, environment, combinations, options),
        lo,
        hi,
        n_scan,
        xtol,
        "submerged_weight",
        "N/m",
    )
