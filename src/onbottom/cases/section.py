"""Section-simulation case files (TOML): a preset centrifuge test or a user's own case.

Schema (loads in kN/m, unit weights in kN/m³, lengths in m, times in s; see
``examples/section_case.toml`` and ``examples/section_preset.toml``)::

    [preset]                      # EITHER a preset test ...
    test = "Inclined 1"           # Table 1 name
    parameters = "table2"         # or "recommended" (Table 3)
    # optional: A, B, C, mu, gamma_kn, alpha_deg, time_basis, shape, after_limit, dt

    [pipe]                        # ... OR pipe + soil + programme (+ solver)
    outer_diameter = 1.0
    submerged_weight_kn = 10.52
    # mass = 1878.0               # kg/m, optional (default from W_s and buoyancy)
    # added_mass_coefficient = 2.29

    [soil]
    model = "verley_sotberg_calcareous"   # or "verley_sotberg_silica", "coulomb"
    friction_coefficient = 0.48
    submerged_unit_weight_kn = 7.5        # not for coulomb
    # A = 0.25, B = 0.35, C = 0.98        # calcareous defaults (Table 3)

    [programme]                   # see onbottom.cases.programme.programme_from_toml
    kind = "inclined_cyclic"
    ...

    [solver]                      # all optional
    displacement_limit = 3.0
    after_limit = "stop"          # or "runaway_end", "continue"
    integrator = "backward_euler" # or "newmark"
    dt_max = 0.2
    max_displacement_increment = 0.002
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Annotated, Any, Literal

from pydantic import Field, model_validator

from onbottom._casefile import (
    CaseFileError,
    StrictModel,
    parse_case,
    read_toml,
    resolve_path,
)
from onbottom.cases.models import check_model_names, collect_model_tables, soil_from_case
from onbottom.cases.programme import WAVE_GROUP_ONLY, programme_from_toml
from onbottom.cases.tables import Checker
from onbottom.dynamics import centrifuge
from onbottom.dynamics.section import (
    SectionResult,
    SolverSettings,
    section_mass,
)
from onbottom.dynamics.section_run import SectionRun
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil.coulomb import CoulombFriction

__all__ = [
    "SectionCase",
    "SectionCaseFile",
    "build_section_run",
    "load_section_case",
    "load_section_run",
    "run_case",
]

_KN = 1.0e3


def _flat(model: str) -> bool:
    """Whether the flat keys of ``[soil]`` give the parameters of ``model`` (the Verley &
    Sotberg and Coulomb models; any other registered model takes its options from
    ``[soil.<name>]``)."""
    from onbottom.soil.registry import SOIL_MODELS
    from onbottom.soil.verley_sotberg import VerleySotberg

    return model in SOIL_MODELS and SOIL_MODELS[model].cls in (CoulombFriction, VerleySotberg)


_Pos = Annotated[float, Field(gt=0.0)]
_Factor = Annotated[float, Field(gt=0.0, le=10.0)]
_Mu = Annotated[float, Field(gt=0.0, le=2.0)]
_GammaKn = Annotated[float, Field(ge=1.0, le=25.0)]
_AfterLimit = Literal["stop", "runaway_end", "continue"]


class PresetTable(StrictModel):
    """``[preset]``: one of the seven centrifuge tests (Youssef & Cassidy 2014, Table 1)."""

    test: str = Field(description="Table 1 test name [-]")
    parameters: Literal["table2", "recommended"] = "table2"
    A: _Factor | None = None
    B: _Factor | None = None
    C: _Factor | None = None
    mu: _Mu | None = None
    gamma_kn: _GammaKn | None = Field(None, description="submerged unit weight [kN/m³]")
    alpha_deg: Annotated[float, Field(ge=0.0, le=90.0)] | None = None
    time_basis: Literal["paper", "prototype"] = "paper"
    shape: Literal["sine", "triangle"] = "sine"
    after_limit: _AfterLimit = "stop"
    dt: Annotated[float, Field(ge=1.0e-4, le=10.0)] | None = Field(
        None, description="largest time step [s] (1e-4 to 10 s: smaller would take days)"
    )


class SectionPipeTable(StrictModel):
    """``[pipe]``: D [m], submerged weight [kN/m], optional mass [kg/m] and C_a [-]."""

    outer_diameter: _Pos = Field(description="outer diameter D [m]")
    submerged_weight_kn: _Pos = Field(description="submerged weight W_s [kN/m]")
    mass: _Pos | None = Field(None, description="structural mass [kg/m]")
    added_mass_coefficient: Annotated[float, Field(ge=0.0, le=10.0)] = Field(
        centrifuge.ADDED_MASS_COEFFICIENT, description="added-mass coefficient C_a [-]"
    )


class SectionSoilTable(StrictModel):
    """``[soil]``: model and its parameters (μ [-], γ' [kN/m³], A, B, C [-])."""

    model: str = Field(
        min_length=1,
        description="soil model by name (onbottom.soil.registry.SOIL_MODELS; the docs'"
        " api/models.md lists them); options of other models than the Verley & Sotberg and"
        " Coulomb ones in [soil.<name>] [-]",
    )
    models: dict[str, dict[str, Any]] = Field(
        default_factory=dict, description="options of each model: the [soil.<name>] tables"
    )
    friction_coefficient: _Mu = 0.6
    submerged_unit_weight_kn: _GammaKn | None = None
    A: _Factor | None = None
    B: _Factor | None = None
    C: _Factor | None = None
    mobilisation_displacement: _Pos | None = Field(None, description="[m]")
    passive_law: str | None = None
    work_law: str | None = None
    max_penetration_law: str | None = None
    work_integrand: str | None = None

    @model_validator(mode="before")
    @classmethod
    def _sub_tables(cls, data: Any) -> Any:
        return collect_model_tables(data, set(cls.model_fields))


class SectionSolverTable(StrictModel):
    """``[solver]``: stop criterion and step control (all optional)."""

    displacement_limit: _Pos | None = Field(None, description="terminal displacement [m]")
    after_limit: _AfterLimit = "stop"
    integrator: Literal["backward_euler", "newmark"] = "backward_euler"
    dt_max: Annotated[float, Field(ge=1.0e-4, le=100.0)] | None = Field(None, description="[s]")
    dt_min: _Pos | None = Field(None, description="[s]")
    max_displacement_increment: Annotated[float, Field(ge=1.0e-6, le=1.0)] | None = Field(
        None, description="largest displacement per step [m]"
    )
    force_tolerance: Annotated[float, Field(gt=0.0, le=1.0e-3)] | None = Field(
        None, description="relative residual tolerance of the Newton iterations [-]"
    )
    max_iterations: Annotated[int, Field(ge=5, le=10_000)] | None = None
    chunks: Annotated[int, Field(ge=1, le=100_000)] | None = None


class _ProgrammeBase(StrictModel):
    name: str | None = None
    installation_load_kn: _Pos | None = Field(None, description="V_peak [kN/m]")


class InclinedCyclicTable(_ProgrammeBase):
    kind: Literal["inclined_cyclic"]
    vertical_load_kn: _Pos
    amplitude_step_kn: _Pos
    period: _Pos = Field(description="[s]")
    alpha_deg: Annotated[float, Field(ge=0.0, le=90.0)]
    n_cycles: Annotated[int, Field(ge=1, le=100_000)]
    shape: Literal["sine", "triangle"] = "sine"
    points_per_cycle: Annotated[int, Field(ge=8, le=100_000)] = 200


class WaveGroupsTable(_ProgrammeBase):
    kind: Literal["regular", "irregular"]
    vertical_load_kn: _Pos
    n_groups: Annotated[int, Field(ge=1, le=100_000)]
    group_period: _Pos | None = None
    sub_cycles: Annotated[int, Field(ge=1, le=100_000)] | None = None
    h_peak_kn: float | None = None
    h_trough_kn: float | None = None
    v_peak_kn: float | None = None
    increment: float | None = None
    hs: _Pos | None = None
    tp: _Pos | None = None
    depth: _Pos | None = None
    seed: Annotated[int, Field(ge=0)] | None = None
    waves_per_group: _Pos | None = None


class ArraysTable(_ProgrammeBase):
    kind: Literal["arrays"]
    time: list[float] = Field(min_length=2)
    horizontal_load_kn: list[float] = Field(min_length=2)
    vertical_load_kn: list[float] = Field(min_length=2)
    cycle_period: _Pos | None = None


class CsvTable(_ProgrammeBase):
    kind: Literal["csv"]
    file: str = Field(description="CSV file, relative to the case file")
    cycle_period: _Pos | None = None


_PROGRAMMES: dict[str, type[_ProgrammeBase]] = {
    "inclined_cyclic": InclinedCyclicTable,
    "regular": WaveGroupsTable,
    "irregular": WaveGroupsTable,
    "arrays": ArraysTable,
    "csv": CsvTable,
}


class SectionCase(StrictModel):
    """Schema of an ``onbottom simulate`` case file (module docstring)."""

    preset: PresetTable | None = None
    pipe: SectionPipeTable | None = None
    soil: SectionSoilTable | None = None
    programme: dict[str, Any] | None = None  # checked by kind in load_section_case
    solver: SectionSolverTable = SectionSolverTable()


@dataclass(frozen=True)
class SectionCaseFile:
    """A section case, read and validated (:func:`load_section_case`); nothing built.

    ``case``: the schema; ``programme``: its ``[programme]`` table parsed by kind (None with
    ``[preset]``); ``document``: the TOML document as read; ``path``: the file (None for a
    mapping).
    """

    case: SectionCase
    programme: Any
    document: dict[str, Any]
    path: str | None


def load_section_case(source: str | os.PathLike | Mapping[str, Any]) -> SectionCaseFile:
    """Read and check a case file (or mapping); nothing is built (:func:`build_section_run`).

    Unknown tables or keys, wrong types and missing keys raise
    :class:`~onbottom._casefile.CaseFileError` naming the key, the file and the line.
    """
    if isinstance(source, Mapping):
        doc, text, path = dict(source), None, None
    else:
        doc, text = read_toml(source)
        path = os.fspath(source)
    case = parse_case(SectionCase, doc, file=path, text=text)
    programme = None
    if case.programme is not None:
        kind = case.programme.get("kind")
        if not isinstance(kind, str) or kind not in _PROGRAMMES:
            raise CaseFileError(
                f"{path or 'case'}: programme.kind = {kind!r} is invalid: must be one of"
                f" {', '.join(map(repr, _PROGRAMMES))}",
                field="programme.kind",
                file=path,
            )
        programme = parse_case(
            _PROGRAMMES[kind], case.programme, file=path, text=text, root="programme"
        )
    if isinstance(programme, WaveGroupsTable):
        other = "irregular" if programme.kind == "regular" else "regular"
        wrong = [k for k in WAVE_GROUP_ONLY[other] if getattr(programme, k) is not None]
        if wrong:
            Checker(path or "<case>", text).fail(
                f"programme.{wrong[0]}",
                f"programme.{wrong[0]} is invalid with kind = {programme.kind!r}: it is a key"
                f" of kind = {other!r}",
            )
    if case.preset is not None:
        extra = [k for k in ("pipe", "soil", "programme") if k in doc]
        if extra:
            raise CaseFileError(
                f"{path or 'case'}: [preset] and {', '.join(f'[{k}]' for k in extra)} are"
                " invalid together: give either [preset] or [pipe], [soil] and [programme]",
                field="preset",
                file=path,
            )
        if "solver" in doc:
            raise CaseFileError(
                f"{path or 'case'}: [solver] is invalid with [preset]: set dt and after_limit"
                " in [preset]",
                field="solver",
                file=path,
            )
    else:
        for key in ("pipe", "soil", "programme"):
            if getattr(case, key) is None:  # programme: checked above
                raise CaseFileError(
                    f"{path or 'case'}: [{key}] is missing: give [pipe], [soil] and"
                    " [programme] (or a [preset] table)",
                    field=key,
                    file=path,
                )
        check_model_names(case, Checker(path or "<case>", text))
        flat = ("A", "B", "C", "mobilisation_displacement", "passive_law", "work_law")
        flat += ("max_penetration_law", "work_integrand")
        given = [k for k in flat if getattr(case.soil, k) is not None]
        if not _flat(case.soil.model) and given:
            Checker(path or "<case>", text).fail(
                f"soil.{given[0]}",
                f"soil.{given[0]} is invalid with model = {case.soil.model!r}: its options go"
                f" in [soil.{case.soil.model}]",
            )
        if case.soil.model != "coulomb" and case.soil.submerged_unit_weight_kn is None:
            raise CaseFileError(
                "soil.submerged_unit_weight_kn is missing (required for the Verley & Sotberg"
                " models) [kN/m³]",
                field="soil.submerged_unit_weight_kn",
                file=path,
            )
        if case.soil.model == "coulomb":
            used = [
                k
                for k in ("submerged_unit_weight_kn", "A", "B", "C", "passive_law", "work_law")
                if getattr(case.soil, k) is not None
            ]
            if used:
                raise CaseFileError(
                    f"soil.{used[0]} is invalid with model = 'coulomb' (it takes"
                    " friction_coefficient and mobilisation_displacement only)",
                    field=f"soil.{used[0]}",
                    file=path,
                )
        if case.soil.model == "verley_sotberg_silica":
            used = [k for k in ("A", "B", "C") if getattr(case.soil, k) is not None]
            if used:
                raise CaseFileError(
                    f"soil.{used[0]} is invalid with model = 'verley_sotberg_silica' (A, B, C"
                    " are the calcareous factors)",
                    field=f"soil.{used[0]}",
                    file=path,
                )
        if isinstance(programme, CsvTable):
            resolve_path(programme.file, relative_to=path, field="programme.file")
    return SectionCaseFile(case, programme, doc, path)


def run_case(
    source: str | os.PathLike | Mapping[str, Any], *, progress: bool = False
) -> SectionResult:
    """Run the case of a TOML file or mapping (schema in the module docstring)."""
    return load_section_run(source).simulate(progress=progress)


def load_section_run(source: str | os.PathLike | Mapping[str, Any]) -> SectionRun:
    """Read, check and build the case of a TOML file or mapping: the
    :class:`~onbottom.dynamics.section_run.SectionRun` that ``onbottom simulate`` runs
    (:func:`build_section_run` of :func:`load_section_case`)."""
    return build_section_run(load_section_case(source))


def build_section_run(loaded: SectionCaseFile) -> SectionRun:
    """The :class:`~onbottom.dynamics.section_run.SectionRun` of a validated section case
    (:func:`load_section_case`); reads no case file (a CSV programme's file is read)."""
    case = loaded.case
    if case.preset is not None:
        p = case.preset
        return centrifuge.centrifuge_run(
            p.test,
            parameters=p.parameters,
            A=p.A,
            B=p.B,
            C=p.C,
            mu=p.mu,
            gamma=None if p.gamma_kn is None else p.gamma_kn * _KN,
            alpha_deg=p.alpha_deg,
            time_basis=p.time_basis,
            shape=p.shape,
            after_limit=p.after_limit,
            dt=p.dt,
        )
    pt, st, sv = case.pipe, case.soil, case.solver
    pipe = Pipe(
        outer_diameter=pt.outer_diameter,
        submerged_weight=pt.submerged_weight_kn * _KN,
        mass=pt.mass,
    )
    table = loaded.document["programme"]
    if isinstance(loaded.programme, CsvTable):
        table = dict(table)
        table["file"] = os.fspath(
            resolve_path(loaded.programme.file, relative_to=loaded.path, field="programme.file")
        )
    prog = programme_from_toml({"programme": table})
    if not _flat(st.model):
        seabed = Sand(
            submerged_unit_weight=st.submerged_unit_weight_kn * _KN,
            friction_coefficient=st.friction_coefficient,
        )
        soil = soil_from_case(st, "sand", pipe, seabed)
    elif st.model == "coulomb":
        extra = {}
        if st.mobilisation_displacement is not None:
            extra["mobilisation_displacement"] = st.mobilisation_displacement
        soil = CoulombFriction(friction_coefficient=st.friction_coefficient, **extra)
    else:
        from onbottom.soil.registry import build_soil_model

        sand = Sand(
            submerged_unit_weight=st.submerged_unit_weight_kn * _KN,
            friction_coefficient=st.friction_coefficient,
        )
        options = {
            k: getattr(st, k)
            for k in (
                "A",
                "B",
                "C",
                "mobilisation_displacement",
                "passive_law",
                "work_law",
                "max_penetration_law",
                "work_integrand",
            )
            if getattr(st, k) is not None
        }
        soil = build_soil_model(
            st.model, pipe, sand, installation_load=prog.peak_vertical_load, **options
        )
    settings = SolverSettings(
        **{
            k: getattr(sv, k)
            for k in (
                "integrator",
                "dt_max",
                "dt_min",
                "max_displacement_increment",
                "force_tolerance",
                "max_iterations",
                "chunks",
            )
            if getattr(sv, k) is not None
        }
    )
    return SectionRun(
        programme=prog,
        soil=soil,
        mass=section_mass(pipe, pt.added_mass_coefficient),
        displacement_limit=sv.displacement_limit,
        after_limit=sv.after_limit,
        settings=settings,
        attrs={"case_file": loaded.path or "<mapping>"},
    )
