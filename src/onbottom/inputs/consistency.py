"""Physical consistency of inputs, shared by every command and the public API.

One place for the rules that relate inputs to each other or to the physics, so that the case
files (``stability``, ``loads``, ``storm`` section and pipeline, ``curves``) and the Python
functions (:func:`~onbottom.checks.absolute.absolute_lateral_stability`,
:func:`~onbottom.dynamics.storm_section.simulate_storm_section`, …) refuse the same nonsense.

Each rule returns a list of :class:`Finding` (an error or a warning, with the field it is
about and a message naming the field, the value and the allowed range). The callers decide how
to report them: the API with :func:`report` (the first error raises
:class:`~onbottom.errors.InputError` naming the field; warnings are issued), the case layer with
the file and line of the key (:mod:`onbottom.cases`). The field names are parameters, so
a message names the key the user typed (``environment.water_depth`` or ``depth``).

Rules and their sources:

* water depth > D (a pipe on the seabed must be under water), warning below
  :data:`SHALLOW_DEPTH_OVER_D` × D (the free surface then interacts with the flow round the
  pipe, outside F109 §3.4's linear kinematics at the pipe);
* H_s ≤ 0.78 d (McCowan 1894 depth-limited breaking, error); H_s ≤ 0.5 d (surf zone, warning);
  steepness 2πH_s/(gT_p²) ≤ 1/7 (Miche/Stokes limiting steepness, error) and ≤ the DNV-RP-C205
  (2010) §3.5.5.4 design-sea-state limit (warning);
* current above :data:`MAX_USUAL_CURRENT` m/s near the seabed (warning: m/s typed for knots or
  cm/s);
* angles in degrees that equal a multiple of π/12 in radians (warning:
  ``direction_deg = 1.5708`` is π/2 typed in radians);
* Young's modulus of the steel in [1e10, 3e11] Pa (error: ``207000`` is MPa typed as Pa);
  layer densities lighter than the water (warning whatever the layer's name);
* a storm's peak at least :data:`MIN_PEAK_PERIODS` peak periods long (error);
* the runaway stop ``max_displacement_over_d`` at least the largest F109 criterion asked for
  (10 D: a run stopped below it gives a verdict on a criterion it never reached; error);
* a pipeline FE with at least :data:`MIN_FREE_NODES` free nodes (error);
* the storm solver's largest time step against the shortest peak period T_p
  (:func:`time_step`: above :data:`TIME_STEP_MAX_FRACTION` T_p an error, above
  :data:`TIME_STEP_WARN_FRACTION` T_p a warning; docs/theory/storm_section.md);
* scalars where scalars are expected (:func:`scalar`: an array is a named error, not numpy's
  ``TypeError``).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from numbers import Real

import numpy as np

from onbottom.constants import GRAVITY
from onbottom.errors import (
    InputError,
    OutOfRangeWarning,
    PhysicalConsistencyWarning,
    ShallowWaterWarning,
    UnitSlipWarning,
)

__all__ = [
    "MAX_HS_OVER_DEPTH",
    "MAX_USUAL_CURRENT",
    "MAX_WAVE_STEEPNESS",
    "MIN_FREE_NODES",
    "MIN_PEAK_PERIODS",
    "SHALLOW_DEPTH_OVER_D",
    "TIME_STEP_MAX_FRACTION",
    "TIME_STEP_WARN_FRACTION",
    "USUAL_HS_OVER_DEPTH",
    "YOUNGS_MODULUS_PA",
    "Finding",
    "angle_deg",
    "current_speed",
    "depth_and_diameter",
    "free_nodes",
    "layer_density",
    "peak_duration",
    "raise_first",
    "report",
    "scalar",
    "sea_state",
    "section_in_sea",
    "steepness_limit",
    "stop_limit",
    "time_step",
    "warnings_reported_by_case",
    "youngs_modulus",
]

SHALLOW_DEPTH_OVER_D = 3.0
"""Below d = 3 D the free surface and the pipe interact (the wave trough reaches the pipe's
boundary layer; F109 §3.4 transfers linear kinematics to the pipe as if it were small against
the depth): a :class:`~onbottom.errors.ShallowWaterWarning`."""

MAX_WAVE_STEEPNESS = 1.0 / 7.0
"""Limiting steepness H/L of a single wave (Miche/Stokes, deep water): a sea state with a
larger S_p = 2π H_s/(g T_p²) cannot exist — an error (T_p in the wrong unit, H_max for H_s)."""

MAX_HS_OVER_DEPTH = 0.78
"""Depth-limited breaking H/d ≈ 0.78 (McCowan 1894): a significant wave height above it is an
error."""

USUAL_HS_OVER_DEPTH = 0.5
"""Above H_s/d = 0.5 the sea is in the surf zone: linear wave kinematics (F109 §3.2) are outside
their usual range — a warning."""

MAX_USUAL_CURRENT = 3.0
"""Near-bed currents above 3 m/s are exceptional (the strongest tidal races); a faster one is
more likely a unit slip (knots, cm/s) — a warning."""

YOUNGS_MODULUS_PA = (1.0e10, 3.0e11)
"""Young's modulus of a pipe wall [Pa]: aluminium 7e10 … steels 2.1e11; outside this range the
value is in another unit (MPa, GPa) — an error."""

MIN_PEAK_PERIODS = 3.0
"""A storm peak shorter than three peak periods holds fewer than three waves: no F109 verdict
can rest on it (F109 §3.5 asks for a 3-h storm) — an error."""

MIN_FREE_NODES = 3
"""A pipeline FE with fewer free nodes bends in no mode the storm can load — an error."""

TIME_STEP_WARN_FRACTION = 1.0 / 20.0
"""Largest storm-solver step above T_p/20: the wave is resolved by fewer than 20 steps and the
result depends on the step — a warning (docs/theory/storm_section.md, time-step rule)."""

TIME_STEP_MAX_FRACTION = 1.0 / 4.0
"""Largest storm-solver step above T_p/4 — an error: the step halves only where Newton fails or
the increment exceeds 0.05 D, so a coarse step on a pipe that barely moves is never refined
(``time_step = 5`` on T_p = 10.8 s changed the maximum displacement by 74 %)."""

_ANGLE_STEP = math.pi / 12.0  # 15° in radians
_ANGLE_TOLERANCE = 2.0e-3  # rad: 1.5708 (π/2 to 4 digits) is within 4e-6


@dataclass(frozen=True)
class Finding:
    """One consistency problem: an error (``error=True``) or a warning of ``category``."""

    field: str
    message: str
    error: bool
    category: type[Warning] = PhysicalConsistencyWarning


def _err(field: str, message: str) -> Finding:
    return Finding(field, message, True)


def _warn(
    field: str, message: str, category: type[Warning] = PhysicalConsistencyWarning
) -> Finding:
    return Finding(field, message, False, category)


def raise_first(findings: Iterable[Finding]) -> None:
    """Raise :class:`InputError` (with ``.field``) for the first error among ``findings``."""
    for f in findings:
        if f.error:
            err = InputError(f.message)
            err.field = f.field  # type: ignore[attr-defined]
            raise err


_CASE_REPORTED: ContextVar[bool] = ContextVar("onbottom_case_reported", default=False)


@contextmanager
def warnings_reported_by_case() -> Iterator[None]:
    """Within this block the API functions raise the errors of these rules but leave their
    warnings to the case layer, which has already issued them with the file and the line."""
    token = _CASE_REPORTED.set(True)
    try:
        yield
    finally:
        _CASE_REPORTED.reset(token)


def report(findings: Sequence[Finding], *, stacklevel: int = 3) -> None:
    """API reporting: the first error raises :class:`InputError`; then every warning is issued
    with its category (unless within :func:`warnings_reported_by_case`)."""
    raise_first(findings)
    if _CASE_REPORTED.get():
        return
    for f in findings:
        warnings.warn(f.message, f.category, stacklevel=stacklevel)


# ---------------------------------------------------------------------------------------------
# scalars
# ---------------------------------------------------------------------------------------------
def scalar(field: str, value: object) -> object:
    """``value`` unchanged if it is a scalar (or None); :class:`InputError` naming ``field`` if it
    is an array, list or tuple (an array where the function takes one value)."""
    if value is None or isinstance(value, (str, bytes)):
        return value
    if isinstance(value, np.ndarray):
        if value.ndim == 0:
            return value.item()
        raise _array_error(field, value.shape)
    if isinstance(value, (list, tuple, set, dict)):
        raise _array_error(field, (len(value),))
    return value


def _array_error(field: str, shape: tuple[int, ...]) -> InputError:
    err = InputError(
        f"{field} = <array of shape {shape}> is invalid: expected one number (a scalar); for"
        " several values call the function once per value or use the vectorised"
        " onbottom.hydro.design_sea_state functions or a sweep"
    )
    err.field = field  # type: ignore[attr-defined]
    return err


def _num(value: object) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (Real, np.floating, np.integer)):
        return None
    x = float(value)
    return x if math.isfinite(x) else None


# ---------------------------------------------------------------------------------------------
# rules
# ---------------------------------------------------------------------------------------------
def depth_and_diameter(
    depth: float, diameter: float, *, depth_field: str = "water_depth"
) -> list[Finding]:
    """Water depth against the pipe's outer diameter D: error unless d > D; warning below
    :data:`SHALLOW_DEPTH_OVER_D` D."""
    d, dia = _num(depth), _num(diameter)
    if d is None or dia is None or dia <= 0.0:
        return []
    if d <= dia:
        return [
            _err(
                depth_field,
                f"{depth_field} = {d!r} m is invalid with the pipe's outer diameter D ="
                f" {dia:.4g} m: the water must be deeper than the pipe (must be > {dia:.4g} m;"
                " check the units: m)",
            )
        ]
    if d < SHALLOW_DEPTH_OVER_D * dia:
        return [
            _warn(
                depth_field,
                f"{depth_field} = {d:g} m is shallow for the pipe (D = {dia:.4g} m): below"
                f" {SHALLOW_DEPTH_OVER_D:g} D = {SHALLOW_DEPTH_OVER_D * dia:.3g} m the free"
                " surface interacts with the flow round the pipe, outside the linear"
                " kinematics of F109 §3.4",
                ShallowWaterWarning,
            )
        ]
    return []


def steepness_limit(tp: float) -> float:
    """DNV-RP-C205 (2010) §3.5.5.4 limiting average steepness S_p of a design sea state:
    1/15 for T_p <= 8 s, 1/25 for T_p >= 15 s, linear in between."""
    if tp <= 8.0:
        return 1.0 / 15.0
    if tp >= 15.0:
        return 1.0 / 25.0
    return 1.0 / 15.0 + (tp - 8.0) / 7.0 * (1.0 / 25.0 - 1.0 / 15.0)


def sea_state(
    hs: float,
    tp: float,
    depth: float,
    *,
    hs_field: str = "hs",
    tp_field: str = "tp",
    depth_field: str = "water_depth",
    label: str = "",
) -> list[Finding]:
    """Breaking limits of a sea state (H_s [m], T_p [s]) in water of ``depth`` [m]: errors
    above the limiting steepness 1/7 and above H_s/d = 0.78 (McCowan); warnings above the
    DNV-RP-C205 §3.5.5.4 steepness and H_s/d = 0.5."""
    h, t, d = _num(hs), _num(tp), _num(depth)
    if h is None or t is None or d is None or h <= 0.0 or t <= 0.0 or d <= 0.0:
        return []
    what = f" ({label})" if label else ""
    out: list[Finding] = []
    steep = 2.0 * math.pi * h / (GRAVITY * t * t) if t * t > 0.0 else math.inf
    if steep > MAX_WAVE_STEEPNESS:
        out.append(
            _err(
                tp_field,
                f"{tp_field} = {t!r} s is invalid with H_s = {h:g} m{what}: the steepness"
                f" 2πH_s/(gT_p²) = {steep:.3g} exceeds the breaking limit 1/7; T_p must be >="
                f" {math.sqrt(2.0 * math.pi * h / (GRAVITY * MAX_WAVE_STEEPNESS)):.3g} s"
                " (check the units: m and s)",
            )
        )
    if h > MAX_HS_OVER_DEPTH * d:
        out.append(
            _err(
                hs_field,
                f"{hs_field} = {h!r} m is invalid in water_depth = {d:g} m{what}: waves"
                f" break above H/d = {MAX_HS_OVER_DEPTH:g} (McCowan; H_s must be <="
                f" {MAX_HS_OVER_DEPTH * d:.3g} m; check {depth_field})",
            )
        )
    if steep <= MAX_WAVE_STEEPNESS and steep > steepness_limit(t):
        out.append(
            _warn(
                tp_field,
                f"{tp_field} = {t:g} s is unusual with H_s = {h:g} m{what}: the steepness"
                f" {steep:.3g} exceeds the DNV-RP-C205 §3.5.5.4 limit"
                f" {steepness_limit(t):.3g} of a design sea state",
                OutOfRangeWarning,
            )
        )
    if USUAL_HS_OVER_DEPTH * d < h <= MAX_HS_OVER_DEPTH * d:
        out.append(
            _warn(
                hs_field,
                f"{hs_field} = {h:g} m is unusual in water_depth = {d:g} m{what}: above"
                f" H_s/d = {USUAL_HS_OVER_DEPTH:g} the sea is depth-limited (surf zone, near"
                " breaking) and linear wave kinematics lose accuracy",
                OutOfRangeWarning,
            )
        )
    return out


def current_speed(velocity: float, *, field: str = "current_velocity") -> list[Finding]:
    """A warning for a near-bed current faster than :data:`MAX_USUAL_CURRENT` m/s."""
    v = _num(velocity)
    if v is None or abs(v) <= MAX_USUAL_CURRENT:
        return []
    return [
        _warn(
            field,
            f"{field} = {v:g} m/s is unusual: near-bed currents above"
            f" {MAX_USUAL_CURRENT:g} m/s are exceptional (check the unit: m/s, not knots or"
            " cm/s)",
            UnitSlipWarning,
        )
    ]


def angle_deg(value: float, *, field: str) -> list[Finding]:
    """A warning where an angle in degrees equals a multiple of π/12 in radians (0 < x ≤ 2π,
    not a whole number): ``1.5708`` is π/2 typed in radians."""
    x = _num(value)
    if x is None or x <= 0.0 or x > 2.0 * math.pi + _ANGLE_TOLERANCE or x == round(x):
        return []
    k = round(x / _ANGLE_STEP)
    if k == 0 or abs(x - k * _ANGLE_STEP) > _ANGLE_TOLERANCE:
        return []
    return [
        _warn(
            field,
            f"{field} = {x:g} looks like an angle in radians ({x:g} rad ="
            f" {math.degrees(x):.4g}°): {field} is in degrees (check the unit)",
            UnitSlipWarning,
        )
    ]


def youngs_modulus(value: float, *, field: str = "youngs_modulus") -> list[Finding]:
    """Error outside :data:`YOUNGS_MODULUS_PA` (MPa or GPa typed as Pa)."""
    e = _num(value)
    lo, hi = YOUNGS_MODULUS_PA
    if e is None or lo <= e <= hi:
        return []
    hint = ""
    if 1.0e4 <= e <= 1.0e6:
        hint = f" ({e:g} looks like MPa: {e * 1e6:g} Pa)"
    elif 10.0 <= e <= 1000.0:
        hint = f" ({e:g} looks like GPa: {e * 1e9:g} Pa)"
    return [
        _err(
            field,
            f"{field} = {e!r} Pa is invalid: must lie in the physical range [{lo:g}, {hi:g}] Pa"
            f" of pipe walls{hint} (check the unit: Pa)",
        )
    ]


def layer_density(
    density: float, water_density: float, *, field: str, name: str = ""
) -> list[Finding]:
    """A warning for a coating layer lighter than the water (whatever its name): it makes
    the pipe lighter (insulation foams are; weight coatings are not; kg/m³ slip)."""
    rho, rho_w = _num(density), _num(water_density)
    if rho is None or rho_w is None or rho >= rho_w:
        return []
    label = f" (layer {name!r})" if name else ""
    return [
        _warn(
            field,
            f"{field} = {rho:g} kg/m³{label} is lighter than the water ({rho_w:g} kg/m³): the"
            " layer makes the pipe lighter (right for insulation foam, wrong for a weight"
            " coating; check the unit: kg/m³)",
        )
    ]


def peak_duration(
    duration_s: float, tp: float, *, field: str = "peak_hours", unit_hours: bool = True
) -> list[Finding]:
    """Error where a storm peak of ``duration_s`` [s] lasts fewer than
    :data:`MIN_PEAK_PERIODS` peak periods ``tp`` [s]."""
    t, p = _num(duration_s), _num(tp)
    if t is None or p is None or p <= 0.0 or t >= MIN_PEAK_PERIODS * p:
        return []
    shown = f"{t / 3600.0!r} h" if unit_hours else f"{t!r} s"
    need = MIN_PEAK_PERIODS * p
    need_shown = f"{need / 3600.0:.3g} h" if unit_hours else f"{need:.3g} s"
    return [
        _err(
            field,
            f"{field} = {shown} is invalid: shorter than {MIN_PEAK_PERIODS:g} peak periods"
            f" (T_p = {p:g} s): must be >= {need_shown} (F109 §3.5 asks for a 3-h storm;"
            " check the unit: hours)",
        )
    ]


def stop_limit(
    stop_over_d: float,
    criteria_over_d: Iterable[float],
    *,
    field: str = "max_displacement_over_d",
) -> list[Finding]:
    """Error where the runaway stop |y|/D lies below the largest criterion asked for: a run
    stopped there would give a verdict on a criterion it never reached."""
    s = _num(stop_over_d)
    crit = [c for c in (_num(c) for c in criteria_over_d) if c is not None]
    if s is None or not crit or s >= max(crit):
        return []
    return [
        _err(
            field,
            f"{field} = {s!r} is invalid: the runaway stop must be >= the largest criterion"
            f" asked for ({max(crit):g} D; F109 §3.5 criteria"
            f" {', '.join(f'{c:g}D' for c in sorted(crit))})",
        )
    ]


def time_step(dt_max: float, tp: float, *, field: str, source: str) -> list[Finding]:
    """The storm solver's time-step rule: error where the largest step ``dt_max`` [s] exceeds
    :data:`TIME_STEP_MAX_FRACTION` × ``tp`` [s] (the shortest peak period of the storm), a
    :class:`~onbottom.errors.OutOfRangeWarning` where it exceeds
    :data:`TIME_STEP_WARN_FRACTION` × ``tp``. ``source`` says where T_p comes from (a key such
    as ``waves.tp``, or ``the storm of K = 10, N = 0.003``), shown after the period."""
    dt, p = _num(dt_max), _num(tp)
    if dt is None or p is None or p <= 0.0:
        return []
    if dt > TIME_STEP_MAX_FRACTION * p:
        return [
            _err(
                field,
                f"{field} = {dt!r} s is invalid with T_p = {p:g} s ({source}): it must be"
                f" <= T_p/4 = {TIME_STEP_MAX_FRACTION * p:.3g} s (T_p/20 ="
                f" {TIME_STEP_WARN_FRACTION * p:.3g} s or less resolves the wave)",
            )
        ]
    if dt > TIME_STEP_WARN_FRACTION * p:
        return [
            _warn(
                field,
                f"{field} = {dt:g} s is coarse for T_p = {p:g} s ({source}): above T_p/20 ="
                f" {TIME_STEP_WARN_FRACTION * p:.3g} s the result depends on the step; use"
                " <= T_p/20",
                OutOfRangeWarning,
            )
        ]
    return []


def free_nodes(n_free: int, *, field: str, detail: str = "") -> list[Finding]:
    """Error where a pipeline FE mesh has fewer than :data:`MIN_FREE_NODES` free nodes."""
    if n_free >= MIN_FREE_NODES:
        return []
    return [
        _err(
            field,
            f"{field} is invalid: the mesh has {n_free} free node(s){detail}; a pipeline needs"
            f" at least {MIN_FREE_NODES} (shorter elements or a longer line)",
        )
    ]


def section_in_sea(
    *,
    diameter: float,
    depth: float,
    hs: float | None = None,
    tp: float | None = None,
    current_velocity: float | None = None,
    angles: Sequence[tuple[str, float]] = (),
    depth_field: str = "depth",
    hs_field: str = "hs",
    tp_field: str = "tp",
    current_field: str = "current_velocity",
) -> list[Finding]:
    """Every rule of a pipe of diameter D in a sea state and current (the API functions)."""
    out = depth_and_diameter(depth, diameter, depth_field=depth_field)
    if hs is not None and tp is not None:
        out += sea_state(
            hs, tp, depth, hs_field=hs_field, tp_field=tp_field, depth_field=depth_field
        )
    if current_velocity is not None:
        out += current_speed(current_velocity, field=current_field)
    for name, value in angles:
        out += angle_deg(value, field=name)
    return out
