"""Pipeline case files (TOML): ``onbottom storm CASE`` with a ``[pipeline]`` table.

The shared tables ([pipe], [seabed], [environment], [waves], [current], [hydro], [storm],
[solver], [run]) are read and built by :mod:`onbottom.cases.storm` (:func:`build_setup`: its
rules, the time-step rule among them, hold here unchanged); this module validates the strict
``[pipeline]`` table and its ``[[pipeline.sections]]`` (unknown keys are errors with their
line), checks the mesh, chunks, structure and animation file, and builds the
:class:`~onbottom.dynamics.pipeline.storm_run.PipelineStormRun` that
:func:`onbottom.study.pipeline_seeds.run_pipeline_seeds` runs.

From the shared tables the pipeline uses: the pipe (D, w_s, mass; EI and EA from the build-up
form, or ``[pipeline] bending_stiffness / axial_stiffness / mass`` with the simple form), the soil
model of [seabed] (or ``[[pipeline.sections]]`` along the route), the storm and its seed,
current (normal component, mean over D), [hydro] coefficients and reductions, the storm
solver's largest and smallest steps (``[storm] time_step``, ``[solver] dt_min``),
``sample_interval``, ``[solver] max_displacement_over_d`` (runaway stop) and
``max_displacement_increment_over_d``, ``compression_level``, ``[run] seeds``.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any, Literal

from pydantic import Field, model_validator

from onbottom._casefile import CaseFileError, StrictModel, parse_case, read_json, read_toml
from onbottom.dynamics.pipeline.storm_run import (
    BYTES_PER_NODE_HOUR,
    SECONDS_PER_NODE_STEP,
    PipelineStormRun,
    run_cost,
)
from onbottom.dynamics.storm_setup import StormSetup
from onbottom.errors import InputError

__all__ = [
    "MAX_CHUNKS",
    "MAX_KINEMATICS_BYTES",
    "MAX_RUN_SECONDS",
    "PipelineTable",
    "RouteSectionTable",
    "is_pipeline_case",
    "load_pipeline_run",
]

EndName = Literal["fixed", "pinned", "free", "spring"]


class RouteSectionTable(StrictModel):
    """``[[pipeline.sections]]``: a stretch of the route with its own seabed."""

    start: float = Field(ge=0.0, description="start of the section along the pipe [m]")
    end: float = Field(gt=0.0, description="end of the section along the pipe [m]")
    model: Literal["sand", "calcareous", "clay", "rock", "coulomb"] | None = None
    submerged_unit_weight: float | None = Field(None, gt=0.0, le=2.0e4, description="[N/m³]")
    unit_weight: float | None = Field(None, gt=0.0, le=3.0e4, description="[N/m³]")
    friction_coefficient: float | None = Field(None, ge=0.01, le=2.0, description="μ [-]")
    undrained_shear_strength: float | None = Field(
        None, ge=100.0, le=1.0e6, description="s_u [Pa] (not kPa), as [seabed]"
    )
    axial_friction_coefficient: float | None = Field(
        None, gt=0.0, le=2.0, description="μ_ax [-] (default: μ)"
    )

    @model_validator(mode="after")
    def _order(self) -> RouteSectionTable:
        if not self.end > self.start:
            raise ValueError("end must exceed start")
        return self


class PipelineTable(StrictModel):
    """``[pipeline]``: presence selects the pipeline FE."""

    length: float = Field(gt=0.0, le=1.0e5, description="pipeline length L [m]")
    element_length: float = Field(gt=0.0, description="element length [m]")
    end_conditions: EndName | list[EndName] = "fixed"
    end_springs: list[float] = Field(
        default_factory=lambda: [0.0, 0.0, 0.0],
        description="axial [N/m], lateral [N/m], rotational [N·m/rad] springs at 'spring' ends",
    )
    effective_axial_force: float = Field(
        0.0,
        description="initial N₀ [N], tension +; |N₀| <= 2 % of EA (an axial strain far beyond"
        " the yield of line-pipe steel), a warning above 0.3 %",
    )
    bending_stiffness: float | None = Field(
        None, ge=1.0e2, le=1.0e11, description="EI [N·m²], in [1e2, 1e11]"
    )
    axial_stiffness: float | None = Field(
        None, ge=1.0e5, le=1.0e12, description="EA [N], in [1e5, 1e12]"
    )
    mass: float | None = Field(
        None, gt=0.0, description="structural mass incl. contents [kg/m] (simple pipe form)"
    )
    axial_friction_coefficient: float | None = Field(None, gt=0.0, le=2.0, description="[-]")
    axial_mobilisation: float = Field(5.0e-3, gt=0.0, le=1.0, description="δ_ax [m]")
    strain_limit: float | None = Field(
        None,
        gt=0.0,
        le=0.05,
        description="user limit [-] (a fraction, not %), in (0, 0.05]; a warning above 0.01",
    )
    strain_fibre_distance: float | None = Field(
        None, gt=0.0, description="c [m], in (0, D/2] (outer diameter D)"
    )
    hht_alpha: float = Field(-0.1, ge=-1.0 / 3.0, le=0.0, description="HHT-α [-]")
    force_tolerance: float = Field(1.0e-6, gt=0.0, le=1.0e-2, description="relative [-]")
    max_iterations: int = Field(8, ge=3, le=200, description="Newton iterations [-]")
    record_interval: float | None = Field(
        1.0, gt=0.0, description="time between records [s]; absent/None → envelopes only"
    )
    chunk_duration: float = Field(600.0, gt=0.0, description="NetCDF/checkpoint interval [s]")
    duration: float | None = Field(None, gt=0.0, description="simulate only [0, duration] [s]")
    animation: str | None = Field(None, description="GIF file of the line in the storm")
    relative_velocity: bool = True
    sections: list[RouteSectionTable] = Field(default_factory=list)

    @model_validator(mode="after")
    def _checks(self) -> PipelineTable:
        if self.element_length > self.length:
            raise ValueError("element_length must not exceed length")
        if isinstance(self.end_conditions, list) and len(self.end_conditions) != 2:
            raise ValueError("end_conditions: one name, or [start, end]")
        if len(self.end_springs) != 3 or any(k < 0 for k in self.end_springs):
            raise ValueError("end_springs: three values >= 0 (axial, lateral, rotational)")
        ends = (
            [self.end_conditions] if isinstance(self.end_conditions, str) else self.end_conditions
        )
        default = type(self).model_fields["end_springs"].get_default(call_default_factory=True)
        if "spring" not in ends and list(self.end_springs) != list(default):
            raise ValueError(
                "end_springs is used by end_conditions = 'spring' only (no end is a spring"
                " here): remove end_springs or set a spring end"
            )
        return self


def _soil_for(
    section: RouteSectionTable | None,
    case: Any,
    pipe: Any,
    *,
    index: int = 0,
    file: str | os.PathLike | None = None,
    text: str | None = None,
):
    from onbottom.cases.models import soil_from_case

    sb = case.seabed
    root = f"pipeline.sections[{index}]"
    if section is not None:
        upd = {
            k: getattr(section, k)
            for k in (
                "model",
                "submerged_unit_weight",
                "unit_weight",
                "friction_coefficient",
                "undrained_shear_strength",
            )
            if getattr(section, k) is not None
        }
        base = sb.model_dump(exclude_defaults=True)
        if upd.get("model", sb.model) != sb.model:
            # another soil model: the [seabed] keys it does not read are not inherited
            from onbottom.cases.tables import _SOIL_KEYS_NOT_USED

            for k in _SOIL_KEYS_NOT_USED[upd["model"]]:
                base.pop(k, None)
        sb = parse_case(
            type(sb),
            {**base, **upd},
            file=file,
            text=text,
            root=root,
        )
    try:
        return soil_from_case(getattr(case, "soil", None), sb.model, pipe, sb.seabed())
    except InputError as exc:
        if section is None:
            raise
        raise CaseFileError(
            f"{file}: {root} is invalid: {exc}",
            field=root,
            file=None if file is None else str(file),
        ) from None


#: Largest pipeline mesh accepted, as limits of one storm run: its kinematics [bytes] and its
#: computing time [s], estimated by :func:`onbottom.dynamics.pipeline.storm_run.run_cost`.
MAX_KINEMATICS_BYTES = 4 * 1024**3
MAX_RUN_SECONDS = 24 * 3600.0


def _fail(p: Path, text: str | None, field: str, message: str) -> None:
    from onbottom.cases.tables import Checker

    Checker(p, text).fail(field, message)


def _check_sections(p: Path, text: str | None, table: PipelineTable) -> None:
    """``[[pipeline.sections]]`` cover [0, length], one after the other (errors name the key
    and its line, not the model's internals)."""
    secs = table.sections
    if not secs:
        return
    if abs(secs[0].start) > 1e-9:
        _fail(p, text, "pipeline.sections[0].start",
              f"pipeline.sections[0].start = {secs[0].start:g} m is invalid: the sections cover"
              f" the line from 0 to pipeline.length = {table.length:g} m; start at 0")  # fmt: skip
    for i in range(1, len(secs)):
        if abs(secs[i].start - secs[i - 1].end) > 1e-6:
            _fail(p, text, f"pipeline.sections[{i}].start",
                  f"pipeline.sections[{i}].start = {secs[i].start:g} m is invalid: the section"
                  f" before ends at {secs[i - 1].end:g} m (sections follow each other, no gap"
                  " or overlap)")  # fmt: skip
    last = len(secs) - 1
    if abs(secs[-1].end - table.length) > 1e-6:
        _fail(p, text, f"pipeline.sections[{last}].end",
              f"pipeline.sections[{last}].end = {secs[-1].end:g} m is invalid: the sections"
              f" cover the line to pipeline.length = {table.length:g} m; end there")  # fmt: skip


def _check_mesh(p: Path, text: str | None, table: PipelineTable, setup: StormSetup) -> None:
    """Refuse a mesh whose memory or run time is excessive, with the estimate."""
    nodes = round(table.length / table.element_length) + 1
    cost = run_cost(nodes, setup.storm, table.duration, setup.settings.dt_max)
    storm_s, steps, mem, cpu = cost.storm_s, cost.steps, cost.memory_bytes, cost.cpu_s
    if mem > MAX_KINEMATICS_BYTES or cpu > MAX_RUN_SECONDS:
        max_nodes = min(
            MAX_KINEMATICS_BYTES / (BYTES_PER_NODE_HOUR * storm_s / 3600.0),
            MAX_RUN_SECONDS / (SECONDS_PER_NODE_STEP * steps),
        )
        shortest = table.length / max(max_nodes - 1.0, 1.0)
        _fail(
            p,
            text,
            "pipeline.element_length",
            f"pipeline.element_length = {table.element_length!r} m is invalid: {nodes} nodes"
            f" on {table.length:g} m need about {mem / 1e9:.3g} GB of storm kinematics"
            f" ({storm_s / 3600:.3g} h storm, ~0.5 MB per node-hour) and about"
            f" {cpu / 3600:.3g} h of computing ({steps:.3g} steps, ~1 µs per node-step);"
            f" the limits are {MAX_KINEMATICS_BYTES / 1e9:.3g} GB and"
            f" {MAX_RUN_SECONDS / 3600:.3g} h: element_length must be >= {shortest:.3g} m"
            " for this storm",
        )


def _check_structure(p: Path, text: str | None, table: PipelineTable, model: Any) -> None:
    """Plausibility of the stiffnesses, axial force and strain inputs against the section."""
    import warnings

    from onbottom.errors import OutOfRangeWarning

    d = float(model.pipe.outer_diameter)
    ea, ei = model.ea, model.ei
    c = table.strain_fibre_distance
    if c is not None and c > 0.5 * d:
        _fail(
            p,
            text,
            "pipeline.strain_fibre_distance",
            f"pipeline.strain_fibre_distance = {c!r} m is invalid: it must lie in (0, D/2] ="
            f" (0, {0.5 * d:.4g}] m for the outer diameter D = {d:.4g} m (check the unit: m,"
            " not mm)",
        )
    n0 = table.effective_axial_force
    if ea > 0.0:
        r2 = ei / ea  # radius of gyration² of the section: D²/16 (bar) to D²/8 (thin tube)
        key = (
            "pipeline.bending_stiffness"
            if table.bending_stiffness is not None
            else "pipeline.axial_stiffness"
        )
        if r2 > 0.25 * d * d:
            _fail(
                p,
                text,
                key,
                f"{key} is invalid: EI/EA = {r2:.4g} m² (EI = {ei:.4g} N·m², EA = {ea:.4g} N)"
                f" exceeds D²/4 = {0.25 * d * d:.4g} m²; no section of outer diameter"
                f" {d:.4g} m has a radius of gyration above D/2",
            )
        if r2 < d * d / 1.0e4:
            _fail(
                p,
                text,
                key,
                f"{key} is invalid: EI/EA = {r2:.4g} m² (EI = {ei:.4g} N·m², EA = {ea:.4g} N)"
                f" is below D²/10⁴ = {d * d / 1.0e4:.4g} m²: the radius of gyration of a pipe"
                f" wall lies between D/4 and D/√8 (check the units: N·m² and N)",
            )
        eps = abs(n0) / ea
        if eps > 0.02:
            _fail(
                p,
                text,
                "pipeline.effective_axial_force",
                f"pipeline.effective_axial_force = {n0!r} N is invalid: |N₀|/EA = {eps:.3g} is"
                f" an axial strain far beyond yield; |N₀| must be <= 0.02 EA = {0.02 * ea:.4g}"
                f" N (EA = {ea:.4g} N)",
            )
        if eps > 0.003:
            warnings.warn(
                f"{p}: pipeline.effective_axial_force = {n0:g} N is unusual: |N₀|/EA ="
                f" {eps:.3g} exceeds 0.3 % (about the yield strain of line-pipe steel)",
                OutOfRangeWarning,
                stacklevel=3,
            )
    if table.strain_limit is not None and table.strain_limit > 0.01:
        warnings.warn(
            f"{p}: pipeline.strain_limit = {table.strain_limit:g} is unusual: a strain (a"
            " fraction, not %) above 1 %",
            OutOfRangeWarning,
            stacklevel=3,
        )


def _check_free_nodes(p: Path, text: str | None, table: PipelineTable, ends: Any) -> None:
    """At least three nodes free to move laterally (fixed and pinned ends hold theirs)."""
    from onbottom.cases.tables import Checker
    from onbottom.inputs import consistency

    nodes = round(table.length / table.element_length) + 1
    pair = (ends, ends) if isinstance(ends, str) else tuple(ends)
    held = sum(1 for e in pair if e in ("fixed", "pinned"))
    Checker(p, text).apply(
        consistency.free_nodes(
            nodes - held,
            field="pipeline.element_length",
            detail=f" ({nodes} nodes on length = {table.length:g} m, {held} held by"
            f" end_conditions = {table.end_conditions!r})",
        )
    )


MAX_CHUNKS = 10_000
"""Most NetCDF/checkpoint chunks of one run: each chunk costs a file write and a checkpoint
(~0.1 s), so 10⁴ chunks add ~20 min of writing; ``chunk_duration`` must not be shorter."""


def _check_chunks(p: Path, text: str | None, table: PipelineTable, setup: StormSetup) -> None:
    """Refuse a ``chunk_duration`` that splits the run into more than :data:`MAX_CHUNKS`."""
    run_s = run_cost(0, setup.storm, table.duration, setup.settings.dt_max).run_s
    n = math.ceil(run_s / table.chunk_duration)
    if n > MAX_CHUNKS:
        _fail(
            p,
            text,
            "pipeline.chunk_duration",
            f"pipeline.chunk_duration = {table.chunk_duration!r} s is invalid: it splits the"
            f" {run_s:.4g} s run into {n:.3g} chunks (each a NetCDF write and a checkpoint,"
            f" about {n * 0.1 / 3600:.3g} h of writing); the limit is {MAX_CHUNKS} chunks:"
            f" chunk_duration must be >= {run_s / MAX_CHUNKS:.3g} s",
        )


def _check_animation(p: Path, text: str | None, table: PipelineTable) -> None:
    if table.animation is None:
        return
    from onbottom._casefile import contained

    ap = Path(table.animation)
    if not ap.is_absolute():
        ap = p.parent / ap
    try:  # a case file writes only inside its own folder
        contained(table.animation, ap, folder=p.parent, field="pipeline.animation")
    except CaseFileError as exc:
        _fail(p, text, "pipeline.animation", str(exc))
    if ap.suffix.lower() != ".gif":
        _fail(
            p,
            text,
            "pipeline.animation",
            f"pipeline.animation = {table.animation!r} is invalid: the file name must end in .gif",
        )
    if ap.resolve() == p.resolve():
        _fail(
            p,
            text,
            "pipeline.animation",
            f"pipeline.animation = {table.animation!r} is invalid: it would overwrite the case"
            " file",
        )


def load_pipeline_run(path: str | os.PathLike) -> PipelineStormRun:
    """Read, validate and build a pipeline case file (errors: :class:`CaseFileError`).

    Returns the built run: the pipeline model, the storm setup of the shared tables
    (:func:`onbottom.cases.storm.build_setup`), the pipeline settings, ``duration``, the
    ``animation`` file (relative names: in the case's folder), ``attrs`` (``case_file``) and
    ``identity`` (``case``: the file's text, so a changed case never resumes an old run).
    """
    from onbottom._casefile import load_case_file
    from onbottom.cases.storm import StormCase, build_setup
    from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, SoilSection
    from onbottom.hydro.storm_kinematics import current_normal_to_pipe

    p = Path(path)
    case = load_case_file(p, StormCase)
    doc, text = read_toml(p)
    table = parse_case(PipelineTable, doc.get("pipeline") or {}, file=p, text=text, root="pipeline")
    setup = build_setup(case, p)
    _check_mesh(p, text, table, setup)
    _check_sections(p, text, table)
    _check_chunks(p, text, table, setup)
    _check_animation(p, text, table)
    pipe = setup.pipe
    if table.mass is not None:
        from dataclasses import replace

        try:
            pipe = replace(pipe, mass=table.mass)
        except InputError as exc:
            raise CaseFileError(
                f"{p}: pipeline.mass = {table.mass!r} is invalid: {exc}",
                field="pipeline.mass",
                file=str(p),
            ) from None
    d = pipe.outer_diameter
    if table.sections:
        soil: Any = tuple(
            SoilSection(
                start=s.start,
                end=s.end,
                model=_soil_for(s, case, pipe, index=i, file=p, text=text),
                axial_friction_coefficient=s.axial_friction_coefficient
                or table.axial_friction_coefficient,
            )
            for i, s in enumerate(table.sections)
        )
    elif table.axial_friction_coefficient is not None:
        soil = (
            SoilSection(
                start=0.0,
                end=table.length,
                model=setup.soil,
                axial_friction_coefficient=table.axial_friction_coefficient,
            ),
        )
    else:
        soil = setup.soil
    fibre = table.strain_fibre_distance
    if fibre is None and case.pipe.steel_outer_diameter is not None:
        fibre = 0.5 * case.pipe.steel_outer_diameter
    ends = (
        table.end_conditions
        if isinstance(table.end_conditions, str)
        else tuple(table.end_conditions)
    )
    try:
        model = PipelineModel(
            pipe=pipe,
            length=table.length,
            element_length=table.element_length,
            soil=soil,
            bending_stiffness=table.bending_stiffness,
            axial_stiffness=table.axial_stiffness,
            effective_axial_force=table.effective_axial_force,
            end_conditions=ends,
            end_springs=tuple(table.end_springs),
            axial_mobilisation=table.axial_mobilisation,
            force_model=setup.force_model,
            reductions=setup.reductions,
            current=current_normal_to_pipe(setup.current, d, setup.z0),
            relative_velocity=table.relative_velocity,
            strain_fibre_distance=fibre,
        )
    except InputError as exc:
        raise CaseFileError(
            f"{p}: [pipeline] is invalid: {exc}", field="pipeline", file=str(p)
        ) from None
    _check_structure(p, text, table, model)
    _check_free_nodes(p, text, table, ends)
    solver = setup.settings  # [storm] time_step and [solver], as built for the storm section
    settings = PipelineSettings(
        alpha=table.hht_alpha,
        dt_max=solver.dt_max,
        dt_min=solver.dt_min,
        max_iterations=table.max_iterations,
        force_tolerance=table.force_tolerance,
        max_displacement_increment_over_d=solver.max_displacement_increment_over_d,
        stop_displacement_over_d=solver.stop_displacement_over_d,
        record_interval=table.record_interval,
        chunk_duration=table.chunk_duration,
        strain_limit=table.strain_limit,
        compression_level=setup.compression_level,
    )
    animation = None
    if table.animation is not None:
        animation = Path(table.animation)
        if not animation.is_absolute():
            animation = p.parent / animation
    return PipelineStormRun(
        model=model,
        setup=setup,
        settings=settings,
        duration=table.duration,
        animation=animation,
        attrs={"case_file": str(p)},
        identity={"case": text},
    )


def is_pipeline_case(path: str | os.PathLike) -> bool:
    """True when the storm case file ``path`` has a ``[pipeline]`` table: ``onbottom storm``
    then runs the pipeline FE (:func:`load_pipeline_run`), else the rigid section
    (:func:`onbottom.cases.storm.load_storm_case`).

    Read with the size- and nesting-limited readers (a device or a huge file is refused at
    once); a file that cannot be read is not a pipeline case: the storm loader then reports the
    problem with its line.
    """
    p = Path(path)
    try:
        doc, _ = read_json(p) if p.suffix.lower() == ".json" else read_toml(p)
    except CaseFileError:
        return False
    return isinstance(doc, dict) and "pipeline" in doc
