"""Storm case files (TOML/JSON) for ``onbottom storm`` and ``onbottom curves``.

Common layout (see CASE_LAYOUT in the docs and ``examples/storm_case.toml``): ``[pipe]``,
``[seabed]``, ``[environment]``, ``[waves]`` (the peak sea state), ``[current]``, ``[hydro]``
share the strict tables of :mod:`onbottom.cases.stability`; this module adds the strict
``[storm]``, ``[solver]`` and ``[run]`` tables. A ``[pipeline]`` table selects the pipeline FE;
it is accepted here and validated by that command.

``[storm] kind`` selects the flow: ``"spectral"`` (default: ``[waves]`` or ``[[storm.stages]]``,
random phases), ``"regular"`` (``height`` [m], ``period`` [s], ``direction_deg``; linear Airy
wave in ``[environment].water_depth``, ``build_up_hours`` ramp, ``peak_hours`` at full
amplitude) or ``"measured"`` (``series``: CSV ``t [s], U [m/s][, dU/dt [m/s^2]]``, a path
relative to the case file's folder; ``sampling_tolerance``). The last two are deterministic
(``run.seeds`` = 1) and give :class:`~onbottom.hydro.storm_kinematics.StormKinematics`.

Soil model from ``[soil] model`` (a registry name, options in ``[soil.<name>]``:
:mod:`onbottom.cases.models`), else the default of the seabed kind ``[seabed].model``
(:data:`onbottom.soil.registry.SEABED_MODELS`: sand → Verley & Sotberg silica, calcareous →
Verley & Sotberg calcareous, clay → Verley & Lund, rock → Coulomb friction). Seabed roughness
z_0 (when ``[current].z0`` is absent): DNV-RP-F109 Table 3-1 from ``d50`` (log–log
interpolation; fine sand 0.25 mm if absent), silt and clay for clay, gravel for rock.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any, Literal

from pydantic import Field, model_validator

from onbottom._casefile import CaseFileError, StrictModel, contained, load_case_file
from onbottom.cases.force import force_model_from_case
from onbottom.cases.models import SoilTable, check_model_names, soil_from_case
from onbottom.cases.stability import check_common_tables, check_reference_height
from onbottom.cases.tables import (
    Checker,
    CurrentTable,
    EnvironmentTable,
    HydroTable,
    PipeTable,
    SeabedTable,
    StormTable,
    WavesTable,
)
from onbottom.checks.absolute import seabed_roughness
from onbottom.dynamics.storm_section import StormSolverSettings
from onbottom.dynamics.storm_setup import StormSetup
from onbottom.errors import InputError
from onbottom.hydro.reductions import LoadReductions
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs import consistency
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.inputs.storm import Current, SeaState, Storm

__all__ = [
    "StormCase",
    "StormSetup",
    "case_relative",
    "load_storm_setup",
]


class SolverTable(StrictModel):
    max_displacement_over_d: float = Field(
        10.0, gt=0.0, le=1000.0, description="runaway stop |y|/D [-]"
    )
    liftoff: Literal["free", "stop"] = "free"
    record_interval: float = Field(
        0.5, ge=0.0, description="time between records [s], 0 = every step"
    )
    compression_level: int = Field(
        0, ge=0, le=9, description="zlib level of the NetCDF records [-], 0 = none"
    )
    dt_min: float | None = Field(None, gt=0.0, description="smallest step [s]")
    max_displacement_increment_over_d: float = Field(0.05, gt=0.0, le=1.0, description="[-]")
    force_tolerance: float = Field(1e-9, gt=0.0, le=1e-3, description="relative [-]")
    max_iterations: int = Field(60, ge=5, le=1000, description="[-]")
    newmark_gamma: float = Field(0.5, ge=0.5, le=1.0, description="[-]")
    newmark_beta: float = Field(0.25, ge=0.25, le=0.5, description="[-]")


class RunTable(StrictModel):
    seeds: int = Field(1, ge=1, le=100000, description="number of storms (seeds) [-]")
    fractile: float = Field(0.9, gt=0.0, lt=1.0, description="fractile of max displacement [-]")


class StormCase(StrictModel):
    """Top level of a storm case file."""

    pipe: PipeTable
    seabed: SeabedTable
    environment: EnvironmentTable
    waves: WavesTable | None = None
    current: CurrentTable = CurrentTable()
    hydro: HydroTable = HydroTable()
    soil: SoilTable | None = None
    storm: StormTable = StormTable()
    solver: SolverTable = SolverTable()
    run: RunTable = RunTable()
    pipeline: dict[str, Any] | None = None
    # accepted so that one file serves the design commands too
    combinations: list[Any] | None = None
    design: dict[str, Any] | None = None
    curves: dict[str, Any] | None = None

    @model_validator(mode="after")
    def _waves(self) -> StormCase:
        if self.storm.kind != "spectral":
            return self
        if self.waves is None and not self.storm.stages:
            raise ValueError("give [waves] (the peak sea state) or [[storm.stages]]")
        return self


#: Fields of the input objects built here → the case-file keys they come from.
_FIELD_KEYS = {
    "LoadReductions.trench_depth_over_d": "seabed.trench_depth",
    "LoadReductions.trench_angle_deg": "seabed.trench_angle_deg",
    "StormSolverSettings.dt_max": "storm.time_step",
    "StormSolverSettings.dt_min": "solver.dt_min",
    "StormSolverSettings.record_interval": "solver.record_interval",
    "StormSolverSettings.stop_displacement_over_d": "solver.max_displacement_over_d",
    "StormSolverSettings.max_displacement_increment_over_d": (
        "solver.max_displacement_increment_over_d"
    ),
    "StormSolverSettings.force_tolerance": "solver.force_tolerance",
    "StormSolverSettings.max_iterations": "solver.max_iterations",
    "StormSolverSettings.newmark_gamma": "solver.newmark_gamma",
    "StormSolverSettings.newmark_beta": "solver.newmark_beta",
    "Storm.transition_s": "storm.transition_s",
    "Storm.build_up_s": "storm.build_up_hours",
    "Storm.decay_s": "storm.decay_hours",
    "Current.reference_height": "current.reference_height",
    "Current.velocity": "current.velocity",
    "Current.z0": "current.z0",
    "MorisonLift.cd": "hydro.cd",
    "MorisonLift.cm": "hydro.cm",
    "MorisonLift.cl": "hydro.cl",
    "MorisonLift.added_mass": "hydro.added_mass_coefficient",
}


class _Keys:
    """Re-raise errors of the input objects under the case-file keys they came from."""

    def __init__(self, chk: Checker) -> None:
        self.chk = chk

    def __enter__(self) -> _Keys:
        return self

    def __exit__(self, kind: Any, exc: BaseException | None, tb: Any) -> bool:
        if isinstance(exc, CaseFileError) and exc.file is None and exc.field:
            self.chk.fail(exc.field, str(exc))  # a key's error: now with the file and line
        if exc is None or isinstance(exc, CaseFileError) or not isinstance(exc, InputError):
            return False
        text = str(exc)
        head = text.split(" ", 1)[0]
        key = _FIELD_KEYS.get(head)
        if key is None:
            field = getattr(exc, "field", None)
            key = _FIELD_KEYS.get(str(field)) if field else None
        if key is not None:
            body = f"{key}{text[len(head) :]}" if head in _FIELD_KEYS else text
            self.chk.fail(key, re.sub(r"\bdt_max\b", "storm.time_step", body))
        self.chk.rename(exc)
        return False  # pragma: no cover - rename raises


def _check_time_step(case: StormCase, chk: Checker) -> None:
    """The largest step against the shortest peak period of the storm
    (:func:`onbottom.inputs.consistency.time_step`)."""
    periods = [(s.tp, f"storm.stages[{i}].tp") for i, s in enumerate(case.storm.stages)]
    if case.storm.kind == "regular":
        periods = [(case.storm.period, "storm.period")]
    elif case.storm.kind == "measured":
        return  # the record's own sampling sets the flow resolution
    if not periods and case.waves is not None:
        periods = [(case.waves.tp, "waves.tp")]
    if not periods:
        return
    tp, where = min(periods)
    chk.apply(
        consistency.time_step(case.storm.time_step, tp, field="storm.time_step", source=where)
    )


def _check_durations_and_stop(case: StormCase, chk: Checker) -> None:
    """A storm peak of at least a few peak periods and a runaway stop at or above the largest
    F109 criterion (:mod:`onbottom.inputs.consistency`)."""
    from onbottom.dynamics.storm_section import CRITERIA_OVER_D

    found: list[consistency.Finding] = []
    st = case.storm
    if st.stages:
        for i, s in enumerate(st.stages):
            found += consistency.peak_duration(
                s.duration_hours * 3600.0, s.tp, field=f"storm.stages[{i}].duration_hours"
            )
    elif case.waves is not None:
        peak = 3.0 if st.peak_hours is None else st.peak_hours
        found += consistency.peak_duration(peak * 3600.0, case.waves.tp, field="storm.peak_hours")
    found += consistency.stop_limit(
        case.solver.max_displacement_over_d,
        CRITERIA_OVER_D.values(),
        field="solver.max_displacement_over_d",
    )
    chk.apply(found)


def build_setup(case: StormCase, path: str | os.PathLike | None = None) -> StormSetup:
    """Objects of a validated :class:`StormCase`.

    Engineering plausibility first (:func:`onbottom.cases.stability.check_common_tables`
    on the shared tables and every sea state, the time-step rule, the current's reference
    height above the seabed roughness, a trench no deeper than D);
    every error is a :class:`CaseFileError` naming the case-file key, its value and range.
    """
    where = "<case>" if path is None else path
    chk = Checker(where, None) if path is None else Checker.of_file(path)
    stages = [
        (f"stage {i}", s.hs, s.tp, f"storm.stages[{i}]", f"storm.stages[{i}]")
        for i, s in enumerate(case.storm.stages)
    ]
    check_model_names(case, chk)
    check_common_tables(case, where, sea_states=stages)
    _check_time_step(case, chk)
    if case.storm.kind != "spectral" and case.run.seeds > 1:
        chk.fail(
            "run.seeds",
            f"run.seeds = {case.run.seeds!r} is invalid with storm.kind = {case.storm.kind!r}:"
            " the flow is deterministic, give seeds = 1",
        )
    _check_durations_and_stop(case, chk)
    rho = case.environment.water_density
    with _Keys(chk):
        section = case.pipe.section(rho)
        pipe = section if isinstance(section, Pipe) else section.pipe(case.pipe.condition)
        seabed = case.seabed.seabed()
    check_reference_height(case, where, seabed)  # z_0 of F109 Table 3-1 when not given
    if case.seabed.trench_depth and case.seabed.trench_depth > pipe.outer_diameter:
        chk.fail(
            "seabed.trench_depth",
            f"seabed.trench_depth = {case.seabed.trench_depth!r} m is invalid: deeper than the"
            f" pipe's outer diameter {pipe.outer_diameter:.4g} m (must lie in [0, D])",
        )
    with _Keys(chk):
        return _build_objects(case, path, pipe, seabed)


def _build_objects(
    case: StormCase, path: str | os.PathLike | None, pipe: Pipe, seabed: Sand | Clay | Rock
) -> StormSetup:
    if case.seabed.initial_penetration is not None:
        raise CaseFileError(
            "seabed.initial_penetration is not used by the storm solver: the soil model sets"
            " the as-laid penetration from the submerged weight (remove the key)",
            field="seabed.initial_penetration",
            file=None if path is None else str(path),
        )
    soil = soil_from_case(case.soil, case.seabed.model, pipe, seabed)
    st = case.storm
    c = case.current
    current = c.current()
    z0 = c.z0 if c.z0 is not None else seabed_roughness(seabed)
    storm: Storm | StormKinematics
    if st.kind != "spectral":
        storm = _flow_input(case, path, pipe, current, z0)
    elif st.stages:
        w = case.waves
        stages = tuple(
            SeaState(
                hs=s.hs,
                tp=s.tp,
                gamma=s.gamma,
                spectrum=s.spectrum or (w.spectrum if w else "jonswap"),
                duration_s=s.duration_hours * 3600.0,
                direction_deg=s.direction_deg
                if s.direction_deg is not None
                else (w.direction_deg if w else 90.0),
                spreading_s=s.spreading_s
                if s.spreading_s is not None
                else (w.spreading_s if w else 0.0),
            )
            for s in st.stages
        )
        storm = Storm(
            stages=stages,
            seed=st.seed,
            build_up_s=(st.build_up_hours or 0.0) * 3600.0,
            decay_s=st.decay_hours * 3600.0,
            transition_s=st.transition_s,
        )
    else:
        storm = Storm.standard(
            case.waves.sea_state(),
            build_up_hours=0.5 if st.build_up_hours is None else st.build_up_hours,
            peak_hours=3.0 if st.peak_hours is None else st.peak_hours,
            decay_hours=st.decay_hours,
            seed=st.seed,
        )
    h = case.hydro
    fm = force_model_from_case(h, base_dir=None if path is None else Path(path).resolve().parent)
    if h.reductions:
        red = LoadReductions(
            permeable_seabed=case.seabed.model != "clay",
            penetration=True,
            trench_depth_over_d=case.seabed.trench_depth / pipe.outer_diameter,
            trench_angle_deg=case.seabed.trench_angle_deg,
        )
    else:
        red = LoadReductions(permeable_seabed=False, penetration=False)
    sv = case.solver
    settings = StormSolverSettings(
        dt_max=st.time_step,
        dt_min=sv.dt_min,
        max_displacement_increment_over_d=sv.max_displacement_increment_over_d,
        force_tolerance=sv.force_tolerance,
        max_iterations=sv.max_iterations,
        newmark_gamma=sv.newmark_gamma,
        newmark_beta=sv.newmark_beta,
        stop_displacement_over_d=sv.max_displacement_over_d,
        liftoff=sv.liftoff,
        record_interval=sv.record_interval,
    )
    return StormSetup(
        pipe=pipe,
        soil=soil,
        seabed=seabed,
        storm=storm,
        depth=case.environment.water_depth,
        current=current,
        z0=z0,
        force_model=fm,
        reductions=red,
        settings=settings,
        sample_interval=st.sample_interval,
        seeds=case.run.seeds,
        fractile=case.run.fractile,
        path=None if path is None else os.fspath(path),
        compression_level=sv.compression_level,
    )


def case_relative(path: str | os.PathLike | None, name: str, *, field: str) -> Path:
    """A path named in a case file at key ``field``: relative to the case's folder, and inside
    its folder tree (absolute or relative: :func:`onbottom._casefile.contained`); ``path``
    None (a case built in memory): as given."""
    p = Path(name).expanduser()
    if path is None:
        return p
    base = Path(path).resolve().parent
    return contained(name, p if p.is_absolute() else base / p, folder=base, field=field)


def _flow_input(
    case: StormCase, path: str | os.PathLike | None, pipe: Pipe, current: Current, z0: float
) -> StormKinematics:
    """The flow of ``[storm] kind = "regular"`` or ``"measured"`` (errors under their keys)."""
    st = case.storm
    file = None if path is None else str(path)
    d = pipe.outer_diameter
    if st.kind == "regular":
        w = case.waves
        direction = st.direction_deg
        if direction is None:
            direction = w.direction_deg if w is not None else 90.0
        build = (st.build_up_hours or 0.0) * 3600.0
        peak = (3.0 if st.peak_hours is None else st.peak_hours) * 3600.0
        try:
            return StormKinematics.regular(
                st.height,
                st.period,
                case.environment.water_depth,
                duration=build + peak,
                diameter=d,
                direction_deg=direction,
                build_up_s=build,
                current=current,
                z0=z0,
                sample_interval=st.sample_interval,
            )
        except InputError as exc:
            raise _flow_error(file, "storm.height", f"storm.height/storm.period: {exc}") from None
    series = case_relative(path, st.series, field="storm.series")
    if not series.is_file():
        raise _flow_error(
            file,
            "storm.series",
            f"storm.series = {st.series!r} is invalid: no file {series}"
            " (a path relative to the case file's folder)",
        )
    if st.sample_interval is not None:
        raise _flow_error(
            file,
            "storm.sample_interval",
            "storm.sample_interval is not used with kind = 'measured':"
            " the record's own sampling is used (remove the key)",
        )
    try:
        return StormKinematics.from_series(
            series,
            diameter=d,
            current=current,
            z0=z0,
            sampling_tolerance=st.sampling_tolerance,
        )
    except InputError as exc:
        raise _flow_error(file, "storm.series", f"storm.series: {exc}") from None


def _flow_error(file: str | None, field: str, message: str) -> CaseFileError:
    """An error of the flow keys of ``[storm]`` naming ``field`` (the file and the key's line
    are added where it is raised, by ``_Keys``)."""
    del file
    return CaseFileError(message, field=field)


def load_storm_setup(path: str | os.PathLike) -> StormSetup:
    """Read, validate and build a storm case file (errors: :class:`CaseFileError`)."""
    return build_setup(load_case_file(path, StormCase), path)
