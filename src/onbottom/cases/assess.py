"""Route case file of ``onbottom assess``: one pipe, a route of KP sections, every F109 level.

Strict TOML tables (:class:`onbottom._casefile.StrictModel`; unknown keys are errors naming the
file, the line and the nearest valid key):

* ``[route]`` — ``name`` and ``[[route.sections]]``: each section has a ``name``, its KP range
  (``kp_start_km``/``kp_end_km`` or ``kp_start_m``/``kp_end_m``), ``water_depth`` [m],
  ``[route.sections.seabed]`` (the stability case's ``[seabed]``: soil model and parameters,
  optional trench ``trench_depth``/``trench_angle_deg``) and its metocean: either the stability
  case's ``waves``, ``current`` and ``[[...combinations]]`` tables, or ``metocean = "NAME"``
  referring to a shared ``[metocean.NAME]`` table holding them;
* ``[pipe]`` — the pipe and its build-up with its conditions (the stability case's ``[pipe]``);
* ``[environment]`` — ``water_density``, ``kinematic_viscosity`` (the depth is per section);
* ``[hydro]`` — the force model of the dynamic level (``model = "morison" | "wake" |
  "fourier"``, :mod:`onbottom.hydro.registry`; default :data:`DEFAULT_FORCE_MODEL`, the wake
  model, as for the curves — the storm documents then name it, so ``onbottom storm`` on them
  runs the same model);
* ``[design]`` — safety class, region, flotation conditions, and the design variable:
  ``solve_for = "auto"`` (concrete thickness of ``layer`` for a build-up pipe, submerged
  weight for a simple pipe), with its range;
* ``[levels]`` — ``absolute``, ``generalized`` (F109 §3.5 from F109's tables), ``dynamic``
  (booleans) and ``pipeline_fe`` (false: the pipeline FE run of the governing section,
  :mod:`onbottom.assess.pipeline`); ``dynamic_curves`` (false; true: the shipped curve sweeps;
  a path: that NetCDF file or folder of sweeps — a separate level, never F109's);
  ``allow_below_generalized`` / ``allow_below_coulomb`` (reason texts that accept a design
  below F109's generalized requirement / the Coulomb-friction bound; see
  :mod:`onbottom.assess.core`);
* ``[pipeline]`` — that run's line length, element length, end conditions, strain limit and
  optional duration;
* ``[dynamic]`` — seeds, the allowable displacement (``allowable = "0.5D" | "10D" | "user"``
  with ``allowable_displacement_m``), the storm (build-up, peak, time step) and the
  search tolerance.

Each section is turned into the case files of the single-section commands
(:meth:`RouteCase.stability_document` → ``onbottom stability``,
:meth:`RouteCase.storm_document` → ``onbottom storm``) and validated by their own loaders
before any work, so a route of one section runs exactly what those commands run; an error is
re-raised under the route key it came from (``route.sections[1].water_depth``).

:func:`build_route` turns a validated case into the plain :class:`~onbottom.assess.route.Route`
that :func:`onbottom.assess.assess` takes (each section's check inputs and the storm setups of
its load combinations, built by those same loaders, and a
:class:`~onbottom.assess.route.DesignTrials` for the trial designs of the dynamic search: built
objects varied by ``replace``, never a case document read again); :func:`load_route` reads a
file and builds it in one call; :func:`example_path` is the embedded example route
(``onbottom assess`` without a CASE).
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
import os
import re
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, NoReturn

from pydantic import Field, PrivateAttr, model_validator

from onbottom._casefile import (
    CaseFileError,
    StrictModel,
    contained,
    find_key_line,
    parse_case,
    read_toml,
)
from onbottom._version import __version__
from onbottom.assess.route import (
    ALLOWABLE_OVER_D,
    DesignRange,
    DesignTrials,
    DynamicSettings,
    Levels,
    PipelineFESettings,
    Route,
    Section,
    SoilChoice,
    StormCombination,
)
from onbottom.cases.models import SoilTable, check_model_names
from onbottom.cases.stability import (
    DesignTable,
    StabilityCase,
    _check_section,
    check_options,
)
from onbottom.cases.tables import (
    Checker,
    CombinationTable,
    CurrentTable,
    HydroTable,
    PipeTable,
    SeabedTable,
    SeawaterTable,
    WavesTable,
)
from onbottom.dynamics.storm_setup import StormSetup
from onbottom.errors import InputError

if TYPE_CHECKING:
    from onbottom.cases.storm import StormCase

__all__ = [
    "ALLOWABLE_OVER_D",
    "EXAMPLE",
    "RouteCase",
    "RouteSection",
    "build_route",
    "case_identity",
    "dynamic_curve_files",
    "example_path",
    "load_route",
    "load_route_case",
    "parse_route_case",
    "section_identity",
    "trial_pipe",
]

ALLOWABLE_MAX_OVER_D = 10.0
"""Largest user allowable displacement over D: the storms' runaway stop (``[solver]
max_displacement_over_d``, 10) and F109's largest criterion (10D, generalized method)."""

EXAMPLE = "assess_example.toml"
"""The embedded example route (package data ``onbottom/data/``)."""

DEFAULT_FORCE_MODEL = "wake"
"""Force model of the dynamic level when ``[hydro] model`` is unset: the wake model, as for
the curves (``onbottom curves``; constant Morison coefficients give peak loads about
2.5 times below F109's C*_Y, C*_Z, so a design weight from them would be unconservative)."""


class MetoceanTable(StrictModel):
    """Sea states and currents of a section: the stability case's ``[waves]``, ``[current]``
    and ``[[combinations]]`` (return-period combinations with directions)."""

    waves: WavesTable
    current: CurrentTable = CurrentTable()
    combinations: list[CombinationTable] = Field(default_factory=list)


class RouteSection(StrictModel):
    """One KP section of the route."""

    name: str = Field(min_length=1, description="label, e.g. shore approach [-]")
    kp_start_km: float | None = Field(None, ge=0.0, le=1.0e4, description="KP start [km]")
    kp_end_km: float | None = Field(None, ge=0.0, le=1.0e4, description="KP end [km]")
    kp_start_m: float | None = Field(None, ge=0.0, le=1.0e7, description="KP start [m]")
    kp_end_m: float | None = Field(None, ge=0.0, le=1.0e7, description="KP end [m]")
    water_depth: float = Field(gt=0.0, le=5000.0, description="d [m]")
    seabed: SeabedTable
    metocean: str | None = Field(None, min_length=1, description="name of a [metocean.NAME] [-]")
    waves: WavesTable | None = None
    current: CurrentTable | None = None
    combinations: list[CombinationTable] = Field(default_factory=list)
    gap_reason: str | None = Field(
        None,
        min_length=1,
        description="why the KP range between the section before and this one is not assessed"
        " (a crossing, a landfall by HDD); required for a gap, printed in the report [-]",
    )

    @model_validator(mode="after")
    def _kp_and_metocean(self) -> RouteSection:
        km = self.kp_start_km is not None or self.kp_end_km is not None
        m = self.kp_start_m is not None or self.kp_end_m is not None
        if km and m:
            raise ValueError("give kp_start_km/kp_end_km or kp_start_m/kp_end_m, not both")
        if not km and not m:
            raise ValueError("give the KP range: kp_start_km and kp_end_km (or _m)")
        lo, hi = self.kp_start, self.kp_end
        if math.isnan(lo) or math.isnan(hi):
            raise ValueError("give both ends of the KP range (start and end)")
        if hi <= lo:
            raise ValueError(f"the KP end ({hi:g} m) must lie after the KP start ({lo:g} m)")
        own = self.waves is not None or self.current is not None or bool(self.combinations)
        if self.metocean is not None and own:
            raise ValueError(
                "give metocean = NAME (a shared [metocean.NAME] table) or the section's own"
                " waves/current/combinations, not both"
            )
        if self.metocean is None and self.waves is None:
            raise ValueError("give the section's [waves] (and [current]) or metocean = NAME")
        return self

    @property
    def kp_start(self) -> float:
        """KP start [m]."""
        if self.kp_start_m is not None:
            return self.kp_start_m
        return math.nan if self.kp_start_km is None else self.kp_start_km * 1.0e3

    @property
    def kp_end(self) -> float:
        """KP end [m]."""
        if self.kp_end_m is not None:
            return self.kp_end_m
        return math.nan if self.kp_end_km is None else self.kp_end_km * 1.0e3


class RouteTable(StrictModel):
    name: str = Field("route", min_length=1, description="label of the route [-]")
    sections: list[RouteSection] = Field(min_length=1)


class RouteEnvironmentTable(SeawaterTable):
    """A route's ``[environment]``: the sea water (depths are per section)."""


class RouteDesignTable(DesignTable):
    solve_for: Literal["auto", "concrete_thickness", "submerged_weight", "none"] = "auto"


class LevelsTable(StrictModel):
    absolute: bool = True
    generalized: bool = True
    dynamic: bool = True
    pipeline_fe: bool = False
    dynamic_curves: bool | str = Field(
        False,
        description="the tool's own curve sweeps as a separate level: true (the shipped"
        " sweeps) or a NetCDF file or folder of `onbottom curves` sweeps (relative to the case)",
    )
    allow_below_generalized: str | None = Field(
        None,
        min_length=1,
        description="reason text: accept a design below F109's generalized requirement",
    )
    allow_below_coulomb: str | None = Field(
        None,
        min_length=1,
        description="reason text: accept a dynamic design below the Coulomb-friction bound"
        " where F109's tables leave a current-dominated point uncovered",
    )


class DynamicTable(StrictModel):
    seeds: int = Field(5, ge=1, le=1000, description="storms per evaluation [-]")
    first_seed: int = Field(0, ge=0, description="first random-phase seed [-]")
    allowable: Literal["0.5D", "10D", "user"] = "0.5D"
    allowable_displacement_m: float | None = Field(
        None, gt=0.0, le=1000.0, description="user allowable displacement [m]"
    )
    build_up_hours: float = Field(0.5, ge=0.0, le=100.0, description="storm build-up [h]")
    peak_hours: float = Field(3.0, gt=0.0, le=100.0, description="storm peak duration [h]")
    time_step: float = Field(0.1, gt=0.0, le=5.0, description="largest solver step [s]")
    thickness_tolerance_m: float = Field(
        1.0e-3, gt=0.0, le=0.05, description="search tolerance on the thickness [m]"
    )
    weight_tolerance_n_per_m: float = Field(
        5.0, gt=0.0, le=1.0e3, description="search tolerance on the submerged weight [N/m]"
    )

    @model_validator(mode="after")
    def _user(self) -> DynamicTable:
        if self.allowable == "user" and self.allowable_displacement_m is None:
            raise ValueError("allowable = 'user' needs allowable_displacement_m [m]")
        if self.allowable != "user" and self.allowable_displacement_m is not None:
            raise ValueError(
                f"allowable_displacement_m is for allowable = 'user', not {self.allowable!r}"
            )
        return self

    def settings(self) -> DynamicSettings:
        """The built settings of the dynamic level (its allowable displacement:
        :meth:`~onbottom.assess.route.DynamicSettings.allowable_for`)."""
        return DynamicSettings(
            seeds=self.seeds,
            first_seed=self.first_seed,
            allowable=self.allowable,
            allowable_displacement_m=self.allowable_displacement_m,
            build_up_hours=self.build_up_hours,
            peak_hours=self.peak_hours,
            thickness_tolerance_m=self.thickness_tolerance_m,
            weight_tolerance_n_per_m=self.weight_tolerance_n_per_m,
        )


class RoutePipelineTable(StrictModel):
    """``[pipeline]``: the pipeline FE run of the governing section
    (``[levels] pipeline_fe = true``; :mod:`onbottom.assess.pipeline`)."""

    length: float = Field(200.0, gt=0.0, le=5000.0, description="modelled line length L [m]")
    element_length: float = Field(5.0, gt=0.0, le=100.0, description="element length [m]")
    end_conditions: Literal["fixed", "pinned", "free"] = "fixed"
    strain_limit: float = Field(
        2.0e-3,
        gt=0.0,
        le=0.05,
        description="strain limit [-] (a fraction, not %); default 0.2 %, a screening value"
        " below the yield strain of X65 (0.22 %)",
    )
    duration: float | None = Field(
        None, gt=0.0, description="simulate only [0, duration] of the storm [s] (None: all)"
    )
    sections: Literal["governing", "every"] = Field(
        "governing",
        description="the FE checks the governing section only, or every section's design",
    )
    mesh: Literal["given", "rule"] = Field(
        "given",
        description="length and element_length as given, or from the section by the stated"
        " rule (onbottom.assess.pipeline.fe_mesh)",
    )

    @model_validator(mode="after")
    def _mesh(self) -> RoutePipelineTable:
        if self.element_length > 0.5 * self.length:
            raise ValueError(
                f"element_length = {self.element_length:g} m must be at most half the length"
                f" ({0.5 * self.length:g} m): the line needs free nodes between its ends"
            )
        if self.length / self.element_length > 2000:
            raise ValueError(
                f"length / element_length = {self.length / self.element_length:.0f} elements"
                " is too many for a route study (at most 2000)"
            )
        return self


class RouteCase(StrictModel):
    """Top level of a route case file."""

    route: RouteTable
    pipe: PipeTable
    environment: RouteEnvironmentTable = RouteEnvironmentTable()
    hydro: HydroTable = HydroTable()
    soil: SoilTable | None = None
    design: RouteDesignTable = RouteDesignTable()
    levels: LevelsTable = LevelsTable()
    dynamic: DynamicTable = DynamicTable()
    pipeline: RoutePipelineTable = RoutePipelineTable()
    metocean: dict[str, MetoceanTable] = Field(default_factory=dict)
    _storms: dict[str, tuple[StormCase, StormSetup]] = PrivateAttr(default_factory=dict)
    """The storm cases and setups built when the case was validated, by their storm document
    (:func:`_built_storm`): :func:`build_route` takes them as they are."""

    # ---- per-section metocean ---------------------------------------------------------------
    def section_metocean(self, i: int) -> MetoceanTable:
        s = self.route.sections[i]
        if s.metocean is not None:
            return self.metocean[s.metocean]
        return MetoceanTable(
            waves=s.waves, current=s.current or CurrentTable(), combinations=s.combinations
        )

    @property
    def solve_for(self) -> str:
        """The design variable: concrete_thickness, submerged_weight or none."""
        if self.design.solve_for != "auto":
            return self.design.solve_for
        return "concrete_thickness" if self.pipe.is_buildup else "submerged_weight"

    # ---- the single-section case files ------------------------------------------------------
    def stability_document(self, i: int) -> dict[str, Any]:
        """Section ``i`` as an ``onbottom stability`` case document (JSON-ready)."""
        s = self.route.sections[i]
        met = self.section_metocean(i)
        design = _dump(self.design)
        design["solve_for"] = self.solve_for
        doc = {
            "pipe": _dump(self.pipe),
            "seabed": _dump(s.seabed),
            "environment": {"water_depth": s.water_depth, **_dump(self.environment)},
            "waves": _dump(met.waves),
            "current": _dump(met.current),
            "design": design,
        }
        if met.combinations:
            doc["combinations"] = [_dump(c) for c in met.combinations]
        return doc

    def combination_names(self, i: int) -> list[str]:
        met = self.section_metocean(i)
        return [c.name for c in met.combinations] or ["design"]

    def storm_document(
        self, i: int, combination: str, *, seeds: int | None = None, pipe: dict | None = None
    ) -> dict[str, Any]:
        """Section ``i`` in ``combination`` as an ``onbottom storm`` case document: the
        combination's sea state as the storm peak, its current, the pipe in its condition;
        ``pipe`` replaces the ``[pipe]`` table (a trial design)."""
        s = self.route.sections[i]
        met = self.section_metocean(i)
        combo = next((c for c in met.combinations if c.name == combination), None)
        if combo is None and combination != "design":
            raise InputError(f"combination = {combination!r} is invalid: not in section {i}")
        waves = _dump(met.waves)
        current = _dump(met.current)
        p = dict(_dump(self.pipe) if pipe is None else pipe)
        if combo is not None:
            for key in ("hs", "tp", "gamma"):
                if getattr(combo, key) is not None:
                    waves[key] = getattr(combo, key)
            if combo.current_velocity is not None:
                current["velocity"] = combo.current_velocity
            if combo.condition is not None:
                p["condition"] = combo.condition
        seabed = _dump(s.seabed)
        seabed.pop("initial_penetration", None)  # the storm's soil model sets it from w_s
        d = self.dynamic
        doc = {
            "pipe": p,
            "seabed": seabed,
            "environment": {"water_depth": s.water_depth, **_dump(self.environment)},
            "waves": waves,
            "current": current,
            "hydro": _dump(self.hydro),
            "storm": {
                "seed": d.first_seed,
                "build_up_hours": d.build_up_hours,
                "peak_hours": d.peak_hours,
                "time_step": d.time_step,
            },
            "solver": {"record_interval": 0.0},
            "run": {"seeds": d.seeds if seeds is None else seeds},
        }
        if self.soil is not None:
            doc["soil"] = _dump(self.soil)
        doc["hydro"].setdefault("model", DEFAULT_FORCE_MODEL)
        if not doc["hydro"].get("wake"):
            doc["hydro"].pop("wake", None)
        if not doc["hydro"].get("fourier"):
            doc["hydro"].pop("fourier", None)
        if not doc["hydro"].get("models"):
            doc["hydro"].pop("models", None)
        return doc


def _dump(model: StrictModel) -> dict[str, Any]:
    """A table as plain data without unset optional keys (a valid case-file table)."""
    return json.loads(model.model_dump_json(exclude_none=True))


# ---- loading and checks ----------------------------------------------------------------------
def _fail(file: str, text: str | None, field: str, message: str) -> NoReturn:
    Checker(file, text).fail(field, message)


def _check_route(case: RouteCase, file: str, text: str | None) -> None:
    """Rules across tables; then each section through the single-section loaders."""
    sections = case.route.sections
    names = [s.name for s in sections]
    for i, name in enumerate(names):
        if names.index(name) != i:
            _fail(file, text, f"route.sections[{i}].name", f"route.sections[{i}].name ="
                  f" {name!r} is invalid: section names must be unique")  # fmt: skip
    order = sorted(range(len(sections)), key=lambda k: sections[k].kp_start)
    for a, b in itertools.pairwise(order):
        if sections[b].kp_start < sections[a].kp_end - 1e-9:
            _fail(
                file,
                text,
                _kp_key(sections[b], b, "start"),
                f"route.sections[{b}] ({sections[b].name!r}) is invalid: its KP range"
                f" [{sections[b].kp_start:g}, {sections[b].kp_end:g}] m overlaps section"
                f" {sections[a].name!r} [{sections[a].kp_start:g}, {sections[a].kp_end:g}] m",
            )
    _check_kp(sections, file, text)
    for i, s in enumerate(sections):
        if s.metocean is not None and s.metocean not in case.metocean:
            _fail(
                file,
                text,
                f"route.sections[{i}].metocean",
                f"route.sections[{i}].metocean = {s.metocean!r} is invalid: no [metocean."
                f"{s.metocean}] table (tables: {', '.join(map(repr, case.metocean)) or 'none'})",
            )
    if case.levels.pipeline_fe and not case.levels.dynamic:
        _fail(
            file,
            text,
            "levels.pipeline_fe",
            "levels.pipeline_fe = true is invalid without levels.dynamic = true: the pipeline"
            " FE runs the governing section in the governing storm of the dynamic level",
        )
    dynamic_curve_files(case, file, text)
    if not (case.levels.absolute or case.levels.generalized or case.levels.dynamic):
        _fail(file, text, "levels", "levels: every level is switched off; nothing to run")
    _check_allowable(case, file, text)
    default_checks = RouteDesignTable.model_fields["checks"].default_factory()
    if list(case.design.checks) != list(default_checks):
        _fail(file, text, "design.checks",
              f"design.checks = {list(case.design.checks)!r} is not used by onbottom assess: it"
              f" runs the design checks {', '.join(default_checks)} at every level; remove the"
              " key (it selects the checks of onbottom stability)")  # fmt: skip
    if case.levels.dynamic and case.solve_for == "none":
        pass  # dynamic runs at the given weight only
    # each section through the stability and storm loaders (their checks, their messages)
    for i, s in enumerate(sections):
        key = f"route.sections[{i}]"
        label = f"<{key}>"
        try:
            doc = case.stability_document(i)
            sc = parse_case(StabilityCase, doc, file=label)
            _check_section(sc, Checker(label, None))
            if case.levels.dynamic:
                for name in case.combination_names(i):
                    _built_storm(case, case.storm_document(i, name), label)
        except CaseFileError as exc:
            route_key = _route_key(case, i, getattr(exc, "field", None) or "")
            inner = re.sub(r"^(?:<[^>]*>|" + re.escape(str(file)) + r")(?:, line \d+)?: ", "",
                           str(exc))  # fmt: skip
            for inner_key, outer_key in _STORM_KEYS.items():
                inner = re.sub(rf"\b{re.escape(inner_key)}\b", outer_key, inner)
            line = find_key_line(text, route_key)
            where = f"{file}{f', line {line}' if line else ''}"
            raise CaseFileError(
                f"{where}: {key} ({s.name!r}) -> {route_key}: {inner}",
                field=route_key,
                file=file,
                line=line,
            ) from None
        except InputError as exc:
            raise CaseFileError(
                f"{file}: {key} ({s.name!r}): {exc}", field=key, file=file
            ) from None


MAX_ROUTE_KM = 2000.0
"""Longest route accepted [km]: the longest subsea pipelines are about 1200 km (Nord Stream,
1224 km); a longer route is KP typed in metres under a ``_km`` key."""

MIN_SECTION_M = 10.0
"""Shortest section accepted [m]: a route's KP sections are hundreds of metres to kilometres;
a shorter one is KP typed in km under a ``_m`` key."""

KP_TOLERANCE_M = 1.0e-3
"""Largest gap or misfit between one section's KP end and the next one's start [m]."""


def _kp_key(s: RouteSection, i: int, end: str) -> str:
    unit = "m" if s.kp_start_m is not None else "km"
    return f"route.sections[{i}].kp_{end}_{unit}"


def _check_kp(sections: list[RouteSection], file: str, text: str | None) -> None:
    """KP sections in order, one after the other (a gap needs ``gap_reason`` on the section
    after it), and lengths that can be a route's (metres typed as km, or km as metres)."""
    for i, s in enumerate(sections):
        if s.kp_end - s.kp_start < MIN_SECTION_M:
            _fail(file, text, _kp_key(s, i, "end"),
                  f"route.sections[{i}] ({s.name!r}) is invalid: it is"
                  f" {s.kp_end - s.kp_start:.4g} m long, shorter than {MIN_SECTION_M:g} m (KP in"
                  " km given under kp_start_m/kp_end_m?)")  # fmt: skip
    total = sections[-1].kp_end - sections[0].kp_start
    if max(s.kp_end for s in sections) - min(s.kp_start for s in sections) > MAX_ROUTE_KM * 1e3:
        i = max(range(len(sections)), key=lambda k: sections[k].kp_end)
        s = sections[i]
        _fail(file, text, _kp_key(s, i, "end"),
              f"route.sections[{i}] ({s.name!r}) is invalid: the route would be"
              f" {total / 1e3:.4g} km long, more than {MAX_ROUTE_KM:g} km (the longest subsea"
              " pipelines are about 1200 km): KP in metres given under kp_start_km/kp_end_km?"
              " Use kp_start_m/kp_end_m for metres")  # fmt: skip
    for i in range(1, len(sections)):
        a, b = sections[i - 1], sections[i]
        if b.kp_start < a.kp_start:
            _fail(file, text, _kp_key(b, i, "start"),
                  f"route.sections[{i}] ({b.name!r}) is invalid: KP {b.kp_start:g} m comes"
                  f" before section {a.name!r} (KP {a.kp_start:g} m) listed above it: list"
                  " the sections in KP order")  # fmt: skip
    for i in range(1, len(sections)):
        a, b = sections[i - 1], sections[i]
        gap = b.kp_start - a.kp_end
        if gap > KP_TOLERANCE_M and b.gap_reason is None:
            _fail(file, text, _kp_key(b, i, "start"),
                  f"route.sections[{i}] ({b.name!r}) is invalid: it starts at KP"
                  f" {b.kp_start:g} m, {gap:.4g} m after section {a.name!r} ends (KP"
                  f" {a.kp_end:g} m): the route has a hole. Make the sections meet, or say"
                  f" why the KP range is not assessed with route.sections[{i}].gap_reason ="
                  ' "..." (a crossing, a landfall by HDD)')  # fmt: skip
        if b.gap_reason is not None and gap <= KP_TOLERANCE_M:
            _fail(file, text, f"route.sections[{i}].gap_reason",
                  f"route.sections[{i}].gap_reason is given but there is no gap before"
                  f" section {b.name!r}: remove it")  # fmt: skip
    if sections[0].gap_reason is not None:
        _fail(file, text, "route.sections[0].gap_reason",
              "route.sections[0].gap_reason is invalid on the first section (no section before"
              " it): remove it")  # fmt: skip


def _check_allowable(case: RouteCase, file: str, text: str | None) -> None:
    """A user allowable displacement within (0, :data:`ALLOWABLE_MAX_OVER_D`·D] of the given
    pipe: the storms of the dynamic level stop at that runaway displacement, so a larger
    allowable would pass every design."""
    d = case.dynamic
    if not case.levels.dynamic or d.allowable != "user" or d.allowable_displacement_m is None:
        return
    sc = parse_case(StabilityCase, case.stability_document(0))
    section = sc.section()
    pipe = section if hasattr(section, "outer_diameter") else section.pipe(case.pipe.condition)
    diameter = float(pipe.outer_diameter)
    top = ALLOWABLE_MAX_OVER_D * diameter
    if d.allowable_displacement_m > top:
        _fail(file, text, "dynamic.allowable_displacement_m",
              f"dynamic.allowable_displacement_m = {d.allowable_displacement_m:g} m is invalid:"
              f" {d.allowable_displacement_m / diameter:.4g} D of the pipe (D ="
              f" {diameter:.4g} m), above {ALLOWABLE_MAX_OVER_D:g}D = {top:.4g} m. The storms"
              f" stop at a runaway displacement of {ALLOWABLE_MAX_OVER_D:g}D, and F109's"
              " criteria run from 0.5D (virtually stable, §3.5) to 10D (generalized"
              " method, §3.6): give an allowable in (0, 10D]")  # fmt: skip


def _route_key(case: RouteCase, i: int, field: str) -> str:
    """The route-file key of a key of section ``i``'s single-section case."""
    key = f"route.sections[{i}]"
    if not field:
        return key
    top = field.split(".", 1)[0].split("[", 1)[0]
    if field == "environment.water_depth":
        return f"{key}.water_depth"
    if top in ("pipe", "environment", "design", "hydro"):
        return field  # shared tables of the route file
    name = case.route.sections[i].metocean
    if top in ("waves", "current", "combinations") and name is not None:
        return f"metocean.{name}.{field}"
    if field in _STORM_KEYS:  # the storm document's keys come from [dynamic]
        return _STORM_KEYS[field]
    if top in ("storm", "run", "solver"):
        return "dynamic"
    return f"{key}.{field}"


_STORM_KEYS = {
    "storm.peak_hours": "dynamic.peak_hours",
    "storm.build_up_hours": "dynamic.build_up_hours",
    "storm.time_step": "dynamic.time_step",
    "storm.seed": "dynamic.first_seed",
    "run.seeds": "dynamic.seeds",
}
"""Keys of a section's storm document → the route file's keys they are taken from."""


def parse_route_case(
    doc: dict[str, Any], *, file: str | os.PathLike = "<route>", text: str | None = None
) -> RouteCase:
    """Validate a parsed route document (schema, cross-table rules, every section).

    The files that ``[hydro]`` names (``coefficient_table``, ``[hydro.fourier] table``) are
    resolved against the case file's folder and must lie in its folder tree (the one rule of
    :func:`onbottom._casefile.contained`); without a file (``file`` in angle brackets) they
    are taken as given."""
    doc = _resolve_files(doc, str(file), text)
    case = parse_case(RouteCase, doc, file=file, text=text)
    check_model_names(case, Checker(str(file), text))
    _check_route(case, str(file), text)
    return case


_FILE_KEYS = (("coefficient_table",), ("fourier", "table"))
"""Keys of ``[hydro]`` naming a file (the storm documents carry them resolved)."""


def _resolve_files(doc: dict[str, Any], file: str, text: str | None) -> dict[str, Any]:
    """``doc`` with the files of :data:`_FILE_KEYS` made absolute and checked to lie in the
    case file's folder tree (an error names the key and its line)."""
    hydro = doc.get("hydro") if isinstance(doc, dict) else None
    if file.startswith("<") or not isinstance(hydro, dict):
        return doc
    base = Path(file).resolve().parent
    doc = copy.deepcopy(doc)
    for keys in _FILE_KEYS:
        table = doc["hydro"]
        for k in keys[:-1]:
            table = table.get(k) if isinstance(table, dict) else None
        value = table.get(keys[-1]) if isinstance(table, dict) else None
        if not isinstance(value, str) or not value or value == "example":
            continue  # absent, the built-in table or a wrong type (the schema names it)
        field = "hydro." + ".".join(keys)
        try:
            p = Path(value).expanduser()
            table[keys[-1]] = str(contained(value, p if p.is_absolute() else base / p,
                                            folder=base, field=field))  # fmt: skip
        except CaseFileError as exc:
            _fail(file, text, field, str(exc))
    return doc


def load_route_case(path: str | os.PathLike) -> RouteCase:
    """Read and validate a route case file (TOML).

    Every bad input is a :class:`~onbottom._casefile.CaseFileError` (an
    :class:`~onbottom.errors.InputError`) naming the key, its value and range, before any
    work: the schema, unique section names, KP ranges that do not overlap, metocean
    references, and each section through the ``onbottom stability`` and ``onbottom storm``
    loaders (physical consistency of :mod:`onbottom.inputs.consistency`).
    """
    doc, text = read_toml(path)
    return parse_route_case(doc, file=Path(path), text=text)


def case_identity(case: RouteCase) -> str:
    """SHA-256 of the validated case (canonical JSON): the run identity of a study."""
    data = json.loads(case.model_dump_json())
    if data.get("soil") is None:  # the tables of model selection count only when given
        data.pop("soil", None)
    if not data["hydro"].get("models"):
        data["hydro"].pop("models", None)
    blob = json.dumps(data, sort_keys=True).encode()
    return hashlib.sha256(blob).hexdigest()


def section_identity(case: RouteCase, i: int) -> str:
    """SHA-256 of everything section ``i``'s results depend on (its case documents, the
    levels, the dynamic settings and the onbottom version): the resume key of
    ``sections/*.json``."""
    blob = {
        "stability": case.stability_document(i),
        "storms": {
            n: case.storm_document(i, n) for n in case.combination_names(i)
        },  # the dynamic inputs
        "levels": json.loads(case.levels.model_dump_json()),
        "dynamic": json.loads(case.dynamic.model_dump_json()),
        "version": __version__,
    }
    return hashlib.sha256(json.dumps(blob, sort_keys=True).encode()).hexdigest()


def example_path() -> Path:
    """The embedded example route (package data ``data/assess_example.toml``: shore
    approach, mid-route, deep end)."""
    from importlib.resources import files

    return Path(str(files("onbottom") / "data" / EXAMPLE))


# ---- the built route -------------------------------------------------------------------------
def trial_pipe(pipe: dict[str, Any], variable: str, layer: str, x: float) -> dict[str, Any]:
    """A ``[pipe]`` table at design value ``x``: the submerged weight [N/m] of a simple pipe,
    or the thickness [m] of the build-up's layer ``layer`` (``variable``). A case document
    for writing out a design (the assessment itself varies the built pipe,
    :class:`~onbottom.assess.route.DesignTrials`)."""
    p = copy.deepcopy(pipe)
    if variable == "submerged_weight":
        p["submerged_weight"] = float(x)
    else:
        for lay in p["layers"]:
            if lay["name"] == layer:
                lay["thickness"] = float(x)
    return p


def _built_storm(
    case: RouteCase, doc: dict[str, Any], file: str | None = None
) -> tuple[StormCase, StormSetup]:
    """A section's storm document parsed as an ``onbottom storm`` case and built by its loader
    (:func:`onbottom.cases.storm.build_setup`: its checks, its errors; ``file`` names the place
    of an error): once per document and case, the validation's build kept on ``case`` for
    :func:`build_route`. The loader's warnings are the route's, reported when it was read."""
    from onbottom.cases.storm import StormCase, build_setup

    key = json.dumps(doc, sort_keys=True)
    hit = case._storms.get(key)
    if hit is None:
        storm_case = parse_case(StormCase, doc, file=file)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            hit = (storm_case, build_setup(storm_case, None))
        case._storms[key] = hit
    return hit


def _soil_choice(case: StormCase) -> SoilChoice:
    """The soil model a storm case builds (:func:`onbottom.cases.models.soil_from_case`): ``[soil]
    model`` with its checked options, else the default of the seabed kind."""
    from onbottom.soil.registry import SEABED_MODELS, SOIL_MODELS

    soil = case.soil
    if soil is None or soil.model is None:
        return SoilChoice(SEABED_MODELS[case.seabed.model], {}, where="seabed.model")
    opts = SOIL_MODELS.check_options(
        soil.model, soil.models.get(soil.model), where=f"soil.{soil.model}"
    )
    return SoilChoice(soil.model, dict(opts), where="soil.model")


def _design_trials(
    case: RouteCase, cases: list[StormCase], setups: tuple[StormSetup, ...]
) -> DesignTrials:
    """The trial designs of a section's storms: the built pipe section, soil choice and
    trench of its storm cases (read once), varied by :class:`DesignTrials`."""
    first = cases[0]
    return DesignTrials(
        section=first.pipe.section(first.environment.water_density),
        variable=case.solve_for,
        layer=case.design.layer,
        conditions=tuple(c.pipe.condition for c in cases),
        setups=setups,
        soil=_soil_choice(first),
        trench_depth=first.seabed.trench_depth if first.hydro.reductions else None,
    )


def _given_value(case: RouteCase) -> float | None:
    """The design variable of the case's ``[pipe]`` (the given design), if it has one."""
    if case.solve_for == "concrete_thickness":
        for lay in case.pipe.layers or ():
            if lay.name == case.design.layer:
                return float(lay.thickness)
        return None
    w = getattr(case.pipe, "submerged_weight", None)
    return None if w is None else float(w)


def _build_section(case: RouteCase, i: int) -> Section:
    s = case.route.sections[i]
    doc = case.stability_document(i)
    sc = parse_case(StabilityCase, doc)
    storms: tuple[StormCombination, ...] = ()
    trials = None
    if case.levels.dynamic:
        names = case.combination_names(i)
        built = [_built_storm(case, case.storm_document(i, n)) for n in names]
        cases = [c for c, _ in built]
        setups = tuple(st for _, st in built)
        storms = tuple(
            StormCombination(n, c.pipe.condition, st)
            for n, c, st in zip(names, cases, setups, strict=True)
        )
        if case.solve_for != "none":
            trials = _design_trials(case, cases, setups)
    return Section(
        name=s.name,
        kp_start=s.kp_start,
        kp_end=s.kp_end,
        water_depth=s.water_depth,
        seabed_model=s.seabed.model,
        pipe=sc.section(),
        condition=case.pipe.condition,
        seabed=sc.seabed.seabed(),
        environment=sc.environment_object(),
        combinations=sc.load_combinations(),
        options=check_options(sc, checks=False),
        given_value=_given_value(case),
        storms=storms,
        trial_storm=trials,
        identity=section_identity(case, i),
        document=doc,
        gap=_gap(case, i),
    )


def _gap(case: RouteCase, i: int) -> str:
    """The note of the gap before section ``i`` (its ``gap_reason``), or empty."""
    s = case.route.sections[i]
    if i == 0 or s.gap_reason is None:
        return ""
    a = case.route.sections[i - 1].kp_end
    return (
        f"KP {a / 1e3:g}–{s.kp_start / 1e3:g} km before this section is not assessed:"
        f" {s.gap_reason}"
    )


def dynamic_curve_files(
    case: RouteCase, file: str | os.PathLike | None = None, text: str | None = None
) -> tuple[str, ...]:
    """The sweeps of ``[levels] dynamic_curves``: none (false), the shipped ones (true), or
    the NetCDF file or every ``*.nc`` of the folder named (relative to the case file ``file``;
    a missing file or a folder without sweeps is a named error on that key and line)."""
    from onbottom._casefile import resolve_path
    from onbottom.assess.generalized import curve_files_at, default_curve_files

    value = case.levels.dynamic_curves
    if value is False:
        return ()
    if value is True:
        return tuple(default_curve_files())
    name = "<route>" if file is None else str(file)
    real = file is not None and not name.startswith("<")
    key = "levels.dynamic_curves"
    try:
        p = resolve_path(value, relative_to=file if real else None, field=key, must_exist=False)
    except CaseFileError as exc:
        _fail(name, text, key, str(exc))
    if p.is_dir():
        found = curve_files_at(p)
        if not found:
            _fail(name, text, key, f"{key} = {value!r} is invalid: folder {p} has no *.nc sweep")
        return tuple(found)
    if not p.is_file():
        _fail(name, text, key, f"{key} = {value!r} is invalid: file {p} not found")
    return (str(p),)


def build_route(case: RouteCase, *, file: str | os.PathLike | None = None) -> Route:
    """The :class:`~onbottom.assess.route.Route` of a validated route case (from
    :func:`load_route_case` or :func:`parse_route_case`); ``file``: the case file, against
    which a relative ``[levels] dynamic_curves`` path is resolved."""
    d = case.design
    return Route(
        name=case.route.name,
        sections=tuple(_build_section(case, i) for i in range(len(case.route.sections))),
        design=DesignRange(variable=case.solve_for, **d.bounds()),
        levels=Levels(
            absolute=case.levels.absolute,
            generalized=case.levels.generalized,
            dynamic=case.levels.dynamic,
            pipeline_fe=case.levels.pipeline_fe,
            dynamic_curves=dynamic_curve_files(case, file),
            allow_below_generalized=case.levels.allow_below_generalized,
            allow_below_coulomb=case.levels.allow_below_coulomb,
        ),
        dynamic=case.dynamic.settings(),
        pipeline=PipelineFESettings(**case.pipeline.model_dump()),
        water_density=case.environment.water_density,
        force_model=case.hydro.model or DEFAULT_FORCE_MODEL,
        identity=case_identity(case),
    )


def load_route(path: str | os.PathLike, *, seeds: int | None = None) -> Route:
    """Read, validate and build a route case file (:func:`load_route_case`, then
    :func:`build_route`); ``seeds`` replaces ``[dynamic] seeds`` (storms per evaluation)
    before the case is validated, so the storm setups validated are those built."""
    doc, text = read_toml(path)
    dyn = doc.get("dynamic", {}) if isinstance(doc, dict) else None
    if seeds is not None and isinstance(dyn, dict):  # else the schema names the table
        doc = doc | {"dynamic": dyn | {"seeds": seeds}}
    case = parse_route_case(doc, file=Path(path), text=text)
    return build_route(case, file=path)
