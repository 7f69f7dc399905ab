"""Every key of every case kind is used or refused.

The test walks every field of the ``storm``, ``stability``, ``assess`` (route),
``reliability``, ``curves`` and ``[pipeline]`` case schemas, of the ``simulate`` section case
(one schema per programme kind), of the ``sweep`` grid file (its axes as tables) and of the
``dem`` config file (JSON: the config is built and checked, no DEM is run); the case kinds
without a schema of keys are named in ``NOT_WALKED`` with the reason, and
``test_every_case_schema_is_walked`` fails on a schema of ``onbottom.cases`` no kind reaches.
For each field it changes the value (or sets it, where the base
case leaves it out) to other values the schema accepts and builds what the command computes
from (the storm setup, the F109 inputs and notes, the route, the reliability setup). The field
passes when a change reaches those objects ("used"), when every change is a named error
("refused": the error names the key), or when it is listed below as documented metadata or as
proved by another test. A field whose change is accepted and changes nothing is a key that is
parsed and never used: the failure lists them.
"""

from __future__ import annotations

import copy
import dataclasses
import enum
import functools
import hashlib
import json
import shutil
import tomllib
import types
import typing
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pydantic
import pytest

from onbottom._casefile import StrictModel
from onbottom.errors import InputError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

# ---- what a build is compared by ---------------------------------------------------------------
_DROP = {"identity", "document", "path"}  # hashes and copies of the inputs, not inputs


def canon(o: Any, depth: int = 0, seen: frozenset = frozenset()) -> Any:
    """Plain, comparable data of a built object (dataclasses, models, arrays by hash)."""
    if depth > 16:
        return "<deep>"
    if o is None or isinstance(o, (bool, int, str)):
        return o
    if isinstance(o, float):
        return round(o, 12)
    if isinstance(o, np.generic):
        return canon(o.item(), depth + 1, seen)
    if isinstance(o, np.ndarray):
        return ("array", o.shape, hashlib.sha1(np.ascontiguousarray(o).tobytes()).hexdigest())
    if isinstance(o, enum.Enum):
        return str(o)
    if isinstance(o, (types.FunctionType, types.BuiltinFunctionType, functools.partial, type)):
        return getattr(o, "__qualname__", type(o).__name__)
    if isinstance(o, Path):
        return str(o)
    if id(o) in seen:
        return "<cycle>"
    seen = seen | {id(o)}
    if isinstance(o, pydantic.BaseModel):
        return canon(o.model_dump(), depth + 1, seen)
    if dataclasses.is_dataclass(o):
        return (
            type(o).__name__,
            {
                f.name: canon(getattr(o, f.name), depth + 1, seen)
                for f in dataclasses.fields(o)
                if f.name not in _DROP
            },
        )
    if isinstance(o, dict):
        return {str(k): canon(v, depth + 1, seen) for k, v in o.items() if k not in _DROP}
    if isinstance(o, (list, tuple, set, frozenset)):
        return [canon(v, depth + 1, seen) for v in o]
    d = getattr(o, "__dict__", None)
    if d is not None:
        return (type(o).__name__, canon(d, depth + 1, seen))
    slots = getattr(type(o), "__slots__", None)
    if slots:
        return (type(o).__name__, {s: canon(getattr(o, s, None), depth + 1, seen) for s in slots})
    return type(o).__name__


# ---- TOML out ----------------------------------------------------------------------------------
def _val(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_val(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_val(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def dump_toml(doc: dict) -> str:
    lines: list[str] = []

    def table(prefix: str, d: dict, array: bool) -> None:
        if prefix:
            lines.append(f"[[{prefix}]]" if array else f"[{prefix}]")
        subs = []
        for k, v in d.items():
            if isinstance(v, dict) and v and prefix.count(".") < 3:
                subs.append((k, [v], False))
            elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
                subs.append((k, v, True))
            else:
                lines.append(f"{json.dumps(k)} = {_val(v)}")
        for k, vs, arr in subs:
            for item in vs:
                table(f"{prefix}.{k}" if prefix else k, item, arr)

    table("", doc, False)
    return "\n".join(lines) + "\n"


# ---- the schema's leaves -------------------------------------------------------------------------
def _model_in(ann: Any) -> type[StrictModel] | None:
    if isinstance(ann, type) and issubclass(ann, StrictModel):
        return ann
    for a in typing.get_args(ann):
        m = _model_in(a)
        if m is not None:
            return m
    return None


def _is_list_of_models(ann: Any) -> bool:
    if typing.get_origin(ann) is list:
        return _model_in(ann) is not None
    return any(_is_list_of_models(a) for a in typing.get_args(ann))


def leaves(model: type[StrictModel], prefix: tuple = ()) -> list[tuple[tuple, Any]]:
    """(path, FieldInfo) of every leaf; a list of tables is entered at its element 0."""
    out = []
    for name, info in model.model_fields.items():
        sub = _model_in(info.annotation)
        if sub is None or typing.get_origin(info.annotation) is dict:
            out.append(((*prefix, name), info))
        elif _is_list_of_models(info.annotation):
            out += leaves(sub, (*prefix, name, 0))
        else:
            out += leaves(sub, (*prefix, name))
    return out


def _get(doc: Any, path: tuple) -> Any:
    for p in path:
        doc = doc[p]
    return doc


def _has_parent(doc: Any, path: tuple) -> bool:
    try:
        parent = _get(doc, path[:-1])
    except (KeyError, IndexError, TypeError):
        return False
    return isinstance(parent, dict)


def _types(ann: Any) -> set[Any]:
    """The types of an annotation, through unions and ``Annotated``."""
    if typing.get_origin(ann) is typing.Annotated:
        return _types(typing.get_args(ann)[0])
    out = {ann}
    if typing.get_origin(ann) in (typing.Union, types.UnionType):
        for a in typing.get_args(ann):
            out |= _types(a)
    return out


def _metadata(info: Any) -> list[Any]:
    """The constraints of a field, its own and those of an ``Annotated`` in its union."""
    out = list(info.metadata)

    def visit(ann: Any) -> None:
        if typing.get_origin(ann) is typing.Annotated:
            for m in ann.__metadata__:  # a pydantic Field holds its constraints in .metadata
                out.extend(getattr(m, "metadata", None) or [m])
        elif typing.get_origin(ann) in (typing.Union, types.UnionType):
            for a in typing.get_args(ann):
                visit(a)

    visit(info.annotation)
    return out


def _bounds(info: Any) -> tuple[float, float]:
    lo, hi = -1e300, 1e300
    for m in _metadata(info):
        for attr in ("ge", "gt"):
            if getattr(m, attr, None) is not None:
                lo = float(getattr(m, attr))
        for attr in ("le", "lt"):
            if getattr(m, attr, None) is not None:
                hi = float(getattr(m, attr))
    return lo, hi


def _candidates(info: Any, current: Any) -> list[Any]:
    if current is None and not info.is_required():
        current = info.get_default(call_default_factory=True)
    if isinstance(current, (list, dict)):
        nums = (
            isinstance(current, list)
            and current
            and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in current)
        )
        return [[x * 1.1 for x in current], current[:1]] if nums else []
    args = _types(info.annotation)
    lits = [a for a in args if typing.get_origin(a) is typing.Literal]
    if lits:
        return [c for c in typing.get_args(lits[0]) if c != current]
    if bool in args:
        return [not current] if current is not None else [True, False]
    if str in args and float not in args:
        return [f"{current or 'walk'}-changed"]
    lo, hi = _bounds(info)
    if int in args and float not in args:
        if current is None:
            start = int(lo) if lo > -1e299 else 0
            base = [start + 1, start + 2, 2 * start + 3]
        else:
            base = [int(current) + 1, int(current) - 1, int(current) * 2]
        return [v for v in base if lo <= v <= hi and v != current]
    if float in args:
        if current is None:
            mid = [x for x in ((lo + hi) / 2 if hi < 1e299 and lo > -1e299 else 1.0,) if x]
            return [float(x) for x in (*mid, lo * 1.5 if lo > 0 else 0.5, 2.0) if lo <= x <= hi]
        v = float(current)
        out = [v * 1.1, v * 0.9, v + 0.1, v - 0.1, (v + hi) / 2 if hi < 1e299 else v + 1]
        return [x for x in out if lo <= x <= hi and x != v]
    return []


# ---- the case kinds ------------------------------------------------------------------------------
@dataclasses.dataclass
class Kind:
    schema: type[StrictModel]
    bases: list[Callable[[], dict]]
    build: Callable[[Path], Any]
    special: dict[str, list[Any]]
    metadata: dict[str, str]
    root: tuple = ()
    pairs: dict[str, dict[str, Any]] = dataclasses.field(default_factory=dict)
    prepare: Callable[[Path], None] | None = None
    write: Callable[[dict], str] = dump_toml
    filename: str = "case.toml"


def _toml(path: Path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _storm_base() -> dict:
    return _toml(EXAMPLES / "storm_case.toml")


def _storm_soil() -> dict:
    doc = _storm_base()
    doc["soil"] = {"model": "verley_sotberg_silica"}
    return doc


def _storm_buildup() -> dict:
    d = _storm_base()
    d["pipe"] = {
        "steel_outer_diameter": 0.3239,
        "wall_thickness": 0.0143,
        "steel_density": 7850.0,
        "youngs_modulus": 2.07e11,
        "condition": "operation",
        "contents": {
            "installation": 0.0,
            "flooded": 1025.0,
            "hydrotest": 1025.0,
            "operation": 180.0,
        },
        "layers": [{"name": "concrete", "thickness": 0.05, "density": 3040.0}],
        "marine_growth": {"name": "growth", "thickness": 0.02, "density": 1300.0},
    }
    d["seabed"] = {
        "model": "clay",
        "undrained_shear_strength": 5.0e3,
        "submerged_unit_weight": 6.0e3,
        "unit_weight": 16.0e3,
        "friction_coefficient": 0.3,
        "trench_depth": 0.1,
    }
    d["storm"] = {
        "seed": 1,
        "time_step": 0.1,
        "build_up_hours": 0.2,
        "decay_hours": 0.2,
        "stages": [
            {"hs": 4.0, "tp": 10.0, "duration_hours": 1.0},
            {"hs": 4.5, "tp": 10.5, "duration_hours": 1.0},
        ],
    }
    return d


def _in_condition(make: Callable[[], dict], condition: str) -> dict:
    d = make()
    d["pipe"]["condition"] = condition
    return d


def _storm_regular() -> dict:
    return _toml(EXAMPLES / "storm_regular_case.toml")


def _storm_build(path: Path) -> Any:
    from onbottom.cases.storm import load_storm_setup

    return load_storm_setup(path)


_SHARED = "a table of other commands in a shared case file (documented: ignored by this command)"

STORM = Kind(
    schema=__import__("onbottom.cases.storm", fromlist=["StormCase"]).StormCase,
    bases=[
        _storm_base,
        _storm_soil,
        _storm_buildup,
        _storm_regular,
        *(
            functools.partial(_in_condition, _storm_buildup, c)
            for c in ("installation", "flooded", "hydrotest")
        ),
    ],
    build=_storm_build,
    pairs={"solver.newmark_gamma": {"solver.newmark_beta": 0.31}},
    special={
        "pipe.contents_density": [500.0],
        "pipe.layers.0.name": ["concrete2"],
        "pipe.marine_growth.name": ["growth2"],
        "hydro.model": ["wake", "fourier"],
        "hydro.wake": [{"drag_excess": 0.5}],
        "hydro.fourier": [{"table": "example"}],
        "storm.kind": ["regular", "measured"],
        "storm.series": ["flow.csv"],
        "solver.newmark_gamma": [0.6],
    },
    metadata={
        "soil.models": "the [soil.<name>] option tables of the soil models: each is walked by"
        " tests/unit/test_recipes_end_to_end.py (options change the result)",
        "hydro.models": "the [hydro.<name>] option tables of registered force models: each is"
        " walked by tests/unit/test_recipes_end_to_end.py (options change the result)",
        "pipe.marine_growth.name": "the growth layer's label",
        "pipeline": "the pipeline FE's table (onbottom storm with [pipeline]: cases/pipeline)",
        "combinations": _SHARED,
        "design": _SHARED,
        "curves": _SHARED,
    },
)


def _stability_base() -> dict:
    return _toml(EXAMPLES / "stability_case.toml")


def _stability_simple() -> dict:
    d = _stability_base()
    d["pipe"] = {"outer_diameter": 0.4, "submerged_weight": 1500.0}
    d["seabed"] = {
        "model": "clay",
        "undrained_shear_strength": 5.0e3,
        "submerged_unit_weight": 6.0e3,
        "unit_weight": 16.0e3,
        "friction_coefficient": 0.3,
    }
    d["design"] = {"solve_for": "submerged_weight"}
    return d


def _stability_build(path: Path) -> Any:
    from onbottom.cases.stability import (
        build_stability_inputs,
        load_stability_case,
        unused_table_notes,
    )

    sc = load_stability_case(path)
    return build_stability_inputs(sc, path), unused_table_notes(sc)


STABILITY = Kind(
    schema=__import__("onbottom.cases.stability", fromlist=["StabilityCase"]).StabilityCase,
    bases=[_stability_base, _stability_simple, lambda: _storm_buildup() | {"design": {}}],
    build=_stability_build,
    special={
        "pipe.layers.0.name": ["concrete2"],
        "hydro.wake": [{"drag_excess": 0.5}],
        "hydro.fourier": [{"table": "example"}],
        "design.vertical_conditions": [["operation"]],
        "design.checks": [["vertical"]],
        "hydro.model": ["wake"],
        "design.layer": ["corrosion"],
    },
    metadata={
        "soil.models": "the [soil.<name>] option tables of the soil models: each is walked by"
        " tests/unit/test_recipes_end_to_end.py (options change the result)",
        "hydro.models": "the [hydro.<name>] option tables of registered force models: each is"
        " walked by tests/unit/test_recipes_end_to_end.py (options change the result)",
        "storm": _SHARED,
        "solver": _SHARED,
        "run": _SHARED,
        "pipeline": _SHARED,
    },
)


def _route_base() -> dict:
    return _toml(EXAMPLES / "assess_route.toml")


def _route_soil() -> dict:
    doc = _route_base()
    doc["soil"] = {"model": "coulomb"}
    return doc


def _route_growth() -> dict:
    d = _route_base()
    d["pipe"]["marine_growth"] = {"name": "growth", "thickness": 0.02, "density": 1300.0}
    return d


def _route_build(path: Path) -> Any:
    from onbottom.cases.assess import build_route, load_route_case

    return build_route(load_route_case(path))


ROUTE = Kind(
    schema=__import__("onbottom.cases.assess", fromlist=["RouteCase"]).RouteCase,
    bases=[_route_base, _route_soil, _route_growth],
    build=_route_build,
    special={
        "route.sections.0.name": ["landfall"],
        "pipe.layers.0.name": ["concrete2"],
        "hydro.model": ["morison", "fourier"],
        "hydro.wake": [{"drag_excess": 0.5}],
        "design.layer": ["corrosion"],
        "design.checks": [["vertical"]],
        "route.sections.0.gap_reason": ["a crossing"],
        "design.vertical_conditions": [["operation"]],
        "route.sections.0.kp_end_km": [2.0],
        "route.sections.0.metocean": ["open_sea"],
        "route.sections.0.combinations.0.name": ["storm A"],
        "hydro.fourier": [{"table": "example"}],
    },
    pairs={
        "route.sections.0.kp_end_km": {"route.sections.1.kp_start_km": 2.0},
        "hydro.fourier": {"hydro.model": "fourier"},
    },
    metadata={
        "soil.models": "the [soil.<name>] option tables of the soil models: each is walked by"
        " tests/unit/test_recipes_end_to_end.py (options change the result)",
        "hydro.models": "the [hydro.<name>] option tables of registered force models: each is"
        " walked by tests/unit/test_recipes_end_to_end.py (options change the result)",
        "metocean": "named metocean tables: the same tables as a section's own, walked there",
    },
)


def _reliability_base() -> dict:
    return _toml(EXAMPLES / "reliability_case.toml")


def _reliability_build(path: Path) -> Any:
    from onbottom.cases.reliability import load_reliability_setup

    return load_reliability_setup(path)


def _reliability_prepare(folder: Path) -> None:
    shutil.copy(EXAMPLES / "hindcast_synthetic.csv", folder)
    shutil.copy(EXAMPLES / "hindcast_synthetic.csv", folder / "other.csv")


RELIABILITY = Kind(
    schema=__import__("onbottom.cases.reliability", fromlist=["ReliabilityCase"]).ReliabilityCase,
    bases=[_reliability_base],
    build=_reliability_build,
    root=("reliability",),
    prepare=_reliability_prepare,
    special={
        "reliability.limits": [["0.5D"], ["1D", "10D"]],
        "reliability.climate.hindcast": ["other.csv"],
        "reliability.inputs": [{"friction_coefficient": 0.5}],
    },
    metadata={
        "soil.models": "the [soil.<name>] option tables of the soil models: each is walked by"
        " tests/unit/test_recipes_end_to_end.py (options change the result)",
        "hydro.models": "the [hydro.<name>] option tables of registered force models: each is"
        " walked by tests/unit/test_recipes_end_to_end.py (options change the result)",
    },
)


def _curves_build(path: Path) -> Any:
    from onbottom.cases.curves import build_curve_settings, load_curves_case

    cfg = load_curves_case(path)
    c = cfg.curves
    return build_curve_settings(cfg, path), c.K, c.M, c.N, c.soils, c.criteria, c.seeds


CURVES = Kind(
    schema=__import__("onbottom.cases.curves", fromlist=["CurvesCase"]).CurvesCase,
    bases=[
        lambda: _toml(EXAMPLES / "curves_case.toml"),
        lambda: _toml(EXAMPLES / "curves_case.toml") | {"environment": {"water_depth": 30.0}},
    ],
    build=_curves_build,
    special={
        "curves.K": [[5.0, 10.0]],
        "curves.M": [[0.0]],
        "curves.N": [[0.004]],
        "curves.soils": [["sand"]],
        "curves.criteria": [["L_10"]],
        "hydro.model": ["morison"],
        "hydro.wake": [{"drag_excess": 0.5}],
        "hydro.fourier": [{"table": "example"}],
    },
    pairs={"hydro.fourier": {"hydro.model": "fourier"}},
    metadata={
        "soil.models": "the [soil.<name>] option tables of the soil models: each is walked by"
        " tests/unit/test_recipes_end_to_end.py (options change the result)",
        "hydro.models": "the [hydro.<name>] option tables of registered force models: each is"
        " walked by tests/unit/test_recipes_end_to_end.py (options change the result)",
        **{
            k: _SHARED
            for k in (
                "pipe",
                "seabed",
                "waves",
                "current",
                "storm",
                "solver",
                "run",
                "pipeline",
                "combinations",
                "design",
            )
        },
        "environment.water_depth": "required by the shared [environment] table; the curves"
        " are in K, M, N (no depth): documented in cases/curves.py",
    },
)


class _PipelineOnly(StrictModel):
    pipeline: __import__("onbottom.cases.pipeline", fromlist=["PipelineTable"]).PipelineTable


def _pipeline_build(path: Path) -> Any:
    from onbottom.cases.pipeline import load_pipeline_run

    return load_pipeline_run(path)


def _pipeline_sections(clay: bool) -> dict:
    d = _toml(EXAMPLES / "pipeline_case.toml")
    soil = (
        {"model": "clay", "undrained_shear_strength": 5.0e3, "submerged_unit_weight": 6.0e3,
         "unit_weight": 16.0e3, "friction_coefficient": 0.3}
        if clay
        else {"model": "sand", "submerged_unit_weight": 9.0e3, "friction_coefficient": 0.5}
    )  # fmt: skip
    d["pipeline"]["sections"] = [
        {"start": 0.0, "end": 80.0, **soil, "axial_friction_coefficient": 0.4},
        {"start": 80.0, "end": 200.0},
    ]
    return d


PIPELINE = Kind(
    schema=_PipelineOnly,
    bases=[
        lambda: _toml(EXAMPLES / "pipeline_case.toml"),
        functools.partial(_pipeline_sections, False),
        functools.partial(_pipeline_sections, True),
    ],
    build=_pipeline_build,
    root=("pipeline",),
    special={"pipeline.sections.0.end": [100.0]},
    pairs={
        "pipeline.end_springs": {"pipeline.end_conditions": "spring"},
        "pipeline.sections.0.end": {"pipeline.sections.1.start": 100.0},
    },
    metadata={
        "soil.models": "the [soil.<name>] option tables of the soil models: each is walked by"
        " tests/unit/test_recipes_end_to_end.py (options change the result)",
        "hydro.models": "the [hydro.<name>] option tables of registered force models: each is"
        " walked by tests/unit/test_recipes_end_to_end.py (options change the result)",
    },
)


# ---- onbottom simulate: the section case, one schema per programme kind --------------------------
from onbottom.cases import section as _section  # noqa: E402


class _SectionInclined(_section.SectionCase):
    programme: _section.InclinedCyclicTable | None = None


class _SectionWaves(_section.SectionCase):
    programme: _section.WaveGroupsTable | None = None


class _SectionArrays(_section.SectionCase):
    programme: _section.ArraysTable | None = None


class _SectionCsv(_section.SectionCase):
    programme: _section.CsvTable | None = None


def _section_base() -> dict:
    return _toml(EXAMPLES / "section_case.toml")


def _section_soil(model: str) -> dict:
    d = _section_base()
    for k in ("A", "B", "C"):
        del d["soil"][k]
    d["soil"]["model"] = model
    if model == "coulomb":
        del d["soil"]["submerged_unit_weight_kn"]
        d["soil"]["mobilisation_displacement"] = 0.01
    else:
        d["soil"] |= {"passive_law": "verley_sotberg", "work_law": "reconstruction"}
        d["soil"] |= {"max_penetration_law": "reconstruction", "work_integrand": "total"}
    return d


def _section_programme(programme: dict) -> Callable[[], dict]:
    def make() -> dict:
        d = _section_base()
        d["programme"] = dict(programme)
        return d

    return make


_WAVES = {"vertical_load_kn": 10.52, "n_groups": 2, "installation_load_kn": 42.98, "name": "w"}


def _section_build(path: Path) -> Any:
    from onbottom.cases.section import load_section_run

    return load_section_run(path)


def _section_prepare(folder: Path) -> None:
    (folder / "loads.csv").write_text("t,H,V\n0,0,10\n10,1,9\n20,0,10\n", encoding="utf-8")
    (folder / "other.csv").write_text("t,H,V\n0,0,10\n10,2,9\n20,0,10\n", encoding="utf-8")


_SECTION_SPECIAL = {
    "soil.model": ["verley_sotberg_silica", "verley_sotberg_calcareous"],
    "soil.passive_law": ["dnv_f109"],
    "soil.work_law": ["none"],
    "soil.max_penetration_law": ["reconstruction_no_half"],
    "soil.work_integrand": ["passive"],
    "preset.test": ["Inclined 2", "Regular"],
    "programme.file": ["other.csv"],
    "pipe.mass": [1878.0, 2500.0],
    "solver.dt_min": [1.0e-3],
    "solver.force_tolerance": [1.0e-6],
}
_SECTION_METADATA = {
    "soil.models": "the [soil.<name>] option tables of the soil models: each is walked by"
    " tests/unit/test_recipes_end_to_end.py (options change the result)",
}
_KIND_BY_SCHEMA = (
    "selects the programme's schema: each kind is walked as a case kind of its own here"
    " (section, section-waves, section-arrays, section-csv)"
)
SECTION = Kind(
    schema=_SectionInclined,
    bases=[
        _section_base,
        functools.partial(_section_soil, "verley_sotberg_silica"),
        functools.partial(_section_soil, "coulomb"),
        lambda: _toml(EXAMPLES / "section_preset.toml"),
    ],
    build=_section_build,
    special=_SECTION_SPECIAL,
    metadata=_SECTION_METADATA | {"programme.kind": _KIND_BY_SCHEMA},
)
SECTION_WAVES = Kind(
    schema=_SectionWaves,
    bases=[
        _section_programme(
            _WAVES
            | {
                "kind": "regular",
                "group_period": 60.0,
                "sub_cycles": 6,
                "h_peak_kn": 0.3,
                "h_trough_kn": -0.2,
                "v_peak_kn": 0.3,
                "increment": 1.0,
            }
        ),
        _section_programme(
            _WAVES
            | {
                "kind": "irregular",
                "group_period": 50.0,
                "hs": 6.0,
                "tp": 12.0,
                "depth": 60.0,
                "waves_per_group": 5.0,
                "seed": 3,
                "h_peak_kn": 3.0,
                "h_trough_kn": -2.0,
                "v_peak_kn": 3.0,
                "increment": 0.1,
            }
        ),
    ],
    build=_section_build,
    root=("programme",),
    special=_SECTION_SPECIAL,
    metadata=_SECTION_METADATA,
)
SECTION_ARRAYS = Kind(
    schema=_SectionArrays,
    bases=[
        _section_programme(
            {
                "kind": "arrays",
                "time": [0.0, 10.0, 20.0],
                "horizontal_load_kn": [0.0, 1.0, 0.0],
                "vertical_load_kn": [10.0, 9.0, 10.0],
                "cycle_period": 20.0,
                "installation_load_kn": 40.0,
                "name": "a",
            }
        )
    ],
    build=_section_build,
    root=("programme",),
    special=_SECTION_SPECIAL,
    metadata=_SECTION_METADATA | {"programme.kind": _KIND_BY_SCHEMA},
)
SECTION_CSV = Kind(
    schema=_SectionCsv,
    bases=[
        _section_programme(
            {
                "kind": "csv",
                "file": "loads.csv",
                "cycle_period": 20.0,
                "installation_load_kn": 40.0,
                "name": "c",
            }
        )
    ],
    build=_section_build,
    root=("programme",),
    prepare=_section_prepare,
    special=_SECTION_SPECIAL,
    metadata=_SECTION_METADATA | {"programme.kind": _KIND_BY_SCHEMA},
)


# ---- onbottom sweep: the grid file (its [grid] axes as one table each) ---------------------------
from onbottom.cases import sweep as _sweep  # noqa: E402


class _GridAxes(StrictModel):
    A: _sweep.LinspaceAxis
    mu: _sweep.ValuesAxis


class _GridWalk(_sweep.GridFile):
    grid: _GridAxes  # type: ignore[assignment]
    fixed: dict[str, Any]


def _sweep_base() -> dict:
    d = _toml(EXAMPLES / "sweep_grid.toml")
    d["grid"]["mu"] = {"values": d["grid"]["mu"]}
    return d


def _sweep_build(path: Path) -> Any:
    return _sweep.read_grid(path)


SWEEP = Kind(
    schema=_GridWalk,
    bases=[_sweep_base],
    build=_sweep_build,
    special={
        "sweep.function": ["misfit"],
        "grid.mu.values": [[0.5, 0.6]],
        "fixed": [{"test": "Inclined 2", "B": 0.35, "C": 0.79}],
    },
    metadata={},
)


# ---- onbottom dem: the config file (JSON; built and checked, never run) --------------------------
def _dem_base(preset: str = "SM") -> dict:
    from onbottom.dem import config

    return json.loads(getattr(config, preset).to_json())


def _dem_build(path: Path) -> Any:
    from onbottom.cases.dem import load_dem_config

    return load_dem_config(path)


DEM = Kind(
    schema=__import__("onbottom.cases.dem", fromlist=["x"]).dem_config_schema(),
    bases=[_dem_base, functools.partial(_dem_base, "SD")],
    build=_dem_build,
    special={
        "preparation.relaxation": ["fire", "damped"],
        "preparation.layer_generation": ["random"],
        "preparation.lid_pause": ["adaptive"],
        "psd.basis": ["mass"],
    },
    metadata={},
    write=lambda d: json.dumps(d, indent=1),
    filename="config.json",
)

KINDS = {
    "storm": STORM,
    "stability": STABILITY,
    "assess": ROUTE,
    "reliability": RELIABILITY,
    "curves": CURVES,
    "pipeline": PIPELINE,
    "section": SECTION,
    "section-waves": SECTION_WAVES,
    "section-arrays": SECTION_ARRAYS,
    "section-csv": SECTION_CSV,
    "sweep": SWEEP,
    "dem": DEM,
}


def _walk(kind: Kind, tmp_path: Path) -> dict[str, list[str]]:
    if kind.prepare is not None:
        kind.prepare(tmp_path)
    (tmp_path / "flow.csv").write_text(
        "t [s],U [m/s]\n"
        + "\n".join(f"{0.2 * i:.1f},{0.5 * np.sin(i / 5):.6f}" for i in range(400))
    )
    path = tmp_path / kind.filename
    cache: dict[int, Any] = {}

    def build(doc: dict) -> Any:
        path.write_text(kind.write(doc), encoding="utf-8")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return canon(kind.build(path))

    found: dict[str, list[str]] = {"unused": [], "not walked": []}
    for rel, info in leaves(kind.schema):
        key = ".".join(map(str, rel))
        if key in kind.metadata or key.split(".")[0] in kind.metadata:
            continue
        if kind.root and rel[: len(kind.root)] != kind.root:
            continue
        outcomes = []
        for b, make in enumerate(kind.bases):
            doc = make()
            if not _has_parent(doc, rel):
                continue
            if b not in cache:
                cache[b] = build(make())
            outcomes.append(_try(kind, key, rel, info, doc, cache[b], build))
            if outcomes[-1] == "used":
                break
        if not outcomes:
            found["not walked"].append(key)
        elif "used" not in outcomes and "refused" not in outcomes:
            found["unused"].append(f"{key} ({outcomes[0][:160]})")
    return found


def _try(kind: Kind, key: str, rel: tuple, info: Any, doc: dict, base: Any, build: Any) -> str:
    """ "used", "refused" (every change a named error), "same" or "error: ..." of one key."""
    current = _get(doc, rel[:-1]).get(rel[-1])
    values = kind.special.get(key) or _candidates(info, current)
    outcome = "no candidate"
    for v in values:
        changed = copy.deepcopy(doc)
        _get(changed, rel[:-1])[rel[-1]] = v
        for other, value in kind.pairs.get(key, {}).items():
            where = tuple(int(x) if x.isdigit() else x for x in other.split("."))
            _get(changed, where[:-1])[where[-1]] = value
        try:
            got = build(changed)
        except InputError as exc:
            field = str(getattr(exc, "field", "") or "")
            named = rel[-1] in str(exc) or rel[-1] in field or key in str(exc)
            if outcome != "same":
                outcome = "refused" if named else f"error: {exc}"
            continue
        if got != base:
            return "used"
        outcome = "same"
    return outcome


@pytest.mark.parametrize("name", list(KINDS))
def test_every_key_is_used_or_refused(name, tmp_path):
    found = _walk(KINDS[name], tmp_path)
    assert not found["unused"], "keys parsed and never used:\n" + "\n".join(found["unused"])
    assert not found["not walked"], "keys no base case holds:\n" + "\n".join(found["not walked"])


def _extremes(info: Any) -> list[Any]:
    """The ends of a numeric field's range the schema accepts (finite ends only)."""
    args = _types(info.annotation)
    if bool in args or not (int in args or float in args):
        return []
    out = []
    for m in _metadata(info):
        for attr, step in (("ge", 0.0), ("gt", 1e-9), ("le", 0.0), ("lt", -1e-9)):
            v = getattr(m, attr, None)
            if v is not None and abs(float(v)) < 1e12:
                x = float(v) + step * max(abs(float(v)), 1.0)
                out.append(round(x) if int in args and float not in args else x)
    return out


@pytest.mark.parametrize("name", list(KINDS))
def test_schema_extremes_are_built_or_named_errors(name, tmp_path):
    """Every numeric key at the ends of its schema range: the command's loader builds it or
    names a key; never another exception (a value the schema accepts that the code after it
    cannot take)."""
    kind = KINDS[name]
    if kind.prepare is not None:
        kind.prepare(tmp_path)
    path = tmp_path / kind.filename
    bad = []
    for rel, info in leaves(kind.schema):
        key = ".".join(map(str, rel))
        if kind.root and rel[: len(kind.root)] != kind.root:
            continue
        doc = next((m() for m in kind.bases if _has_parent(m(), rel)), None)
        if doc is None:
            continue
        for v in _extremes(info):
            changed = copy.deepcopy(doc)
            _get(changed, rel[:-1])[rel[-1]] = v
            path.write_text(kind.write(changed), encoding="utf-8")
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    kind.build(path)
            except InputError:
                pass
            except Exception as exc:  # the failure under test
                bad.append(f"{key} = {v!r}: {type(exc).__name__}: {exc}"[:200])
    assert not bad, "schema-accepted values the loader cannot take:\n" + "\n".join(bad)


# ---- every case kind is walked, or named here with the reason ------------------------------------
NOT_WALKED = {
    "calibrate": "onbottom calibrate reads test records (CSV or NetCDF columns, no case schema):"
    " its options are command-line options (tests/unit/test_cli_calibration.py)",
    "dem specimen and run files": "onbottom dem's --sample and results inputs are NetCDF/NPZ"
    " datasets onbottom wrote (cases.dem.load_sample, load_run): no keys a user types",
    "programme TOML of its own": "cases.programme.programme_from_toml on a file reads its"
    " [programme] table: the same tables as the section case's, walked there",
    "hydrodynamic coefficient tables": "cases.force reads CSV tables named by [hydro] keys:"
    " columns, not keys; the naming keys are walked with storm, stability and assess",
}


def _models_of(model: type, seen: set[type]) -> None:
    for cls in model.__mro__:
        if isinstance(cls, type) and issubclass(cls, StrictModel) and cls is not StrictModel:
            seen.add(cls)
    for info in model.model_fields.values():
        stack = [info.annotation]
        while stack:
            a = stack.pop()
            if isinstance(a, type) and issubclass(a, StrictModel) and a not in seen:
                _models_of(a, seen)
            stack.extend(typing.get_args(a))


def test_every_case_schema_is_walked():
    """Every strict schema under onbottom.cases is reached by a walked kind (the section's
    programme tables, the sweep's axes included)."""
    import importlib
    import pkgutil

    import onbottom.cases

    for m in pkgutil.iter_modules(onbottom.cases.__path__):
        importlib.import_module(f"onbottom.cases.{m.name}")
    walked: set[type] = set()
    for kind in KINDS.values():
        _models_of(kind.schema, walked)
    todo, schemas = [StrictModel], set()
    while todo:
        for sub in todo.pop().__subclasses__():
            todo.append(sub)
            if sub.__module__.startswith("onbottom.cases."):
                schemas.add(sub)
    missing = sorted(
        f"{c.__module__}.{c.__qualname__}"
        for c in schemas
        if c not in walked and not c.__name__.startswith("_")
    )
    assert not missing, "case schemas no kind walks:\n" + "\n".join(missing)
    assert all(reason for reason in NOT_WALKED.values())
