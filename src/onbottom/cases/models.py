"""Models chosen by name in a case file: ``[soil] model`` and ``[hydro] model`` through the
registries.

Every case kind that chooses a soil or a force model reads the name and its options here:

* ``[soil] model = "<name>"`` with options in ``[soil.<name>]``: a soil model of
  :data:`onbottom.soil.registry.SOIL_MODELS`. Without ``[soil]`` the seabed kind chooses, as
  before (``[seabed] model``, :data:`~onbottom.soil.registry.SEABED_MODELS`).
* ``[hydro] model = "<name>"`` with options in ``[hydro.<name>]``: a force model of
  :data:`onbottom.hydro.registry.FORCE_REGISTRY` (built by
  :func:`onbottom.cases.force.force_model_from_case`).

An unknown name, an option the model's schema does not have, or options given for a model that
is not selected, is a :class:`~onbottom.errors.CaseFileError` naming the key, the file and the
line and listing the registered names (:func:`check_model_names`). No list of names is written
here: the registries are the one list.
"""

from __future__ import annotations

from typing import Any

from pydantic import Field, model_validator

from onbottom._casefile import StrictModel
from onbottom.errors import InputError
from onbottom.hydro.registry import FORCE_REGISTRY
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.soil.base import LateralResistanceModel
from onbottom.soil.registry import SOIL_MODELS, build_soil_model, soil_model_for_seabed

__all__ = [
    "SoilTable",
    "check_model_names",
    "collect_model_tables",
    "model_tables",
    "soil_from_case",
]


def collect_model_tables(data: Any, fields: set[str]) -> Any:
    """``data`` of a ``[soil]``/``[hydro]`` table with its sub-tables that are not fields of
    the table (``[soil.<name>]``) moved under ``models`` (checked against the registry by
    :func:`check_model_names`); other unknown keys stay (the strict schema names them)."""
    if not isinstance(data, dict):
        return data
    extra = {k: v for k, v in data.items() if k not in fields and isinstance(v, dict)}
    if not extra:
        return data
    rest = {k: v for k, v in data.items() if k not in extra}
    return {**rest, "models": {**dict(rest.get("models") or {}), **extra}}


class SoilTable(StrictModel):
    """``[soil]``: the soil model by registry name, its options in ``[soil.<name>]``."""

    model: str | None = Field(
        None,
        min_length=1,
        description="soil model by name (onbottom.soil.registry.SOIL_MODELS; the docs'"
        " api/models.md lists them); default: the seabed kind's model [-]",
    )
    models: dict[str, dict[str, Any]] = Field(
        default_factory=dict, description="options of each model: the [soil.<name>] tables"
    )

    @model_validator(mode="before")
    @classmethod
    def _sub_tables(cls, data: Any) -> Any:
        return collect_model_tables(data, {"model", "models"})


def model_tables(hydro: Any) -> dict[str, dict[str, Any]]:
    """The non-empty ``[hydro.<name>]`` option tables of a ``[hydro]`` table: its ``models``
    and the fields of the table that are named after a registered force model."""
    tables = dict(getattr(hydro, "models", None) or {})
    for field in getattr(type(hydro), "model_fields", None) or vars(hydro):
        value = getattr(hydro, field)
        if field in FORCE_REGISTRY.load() and isinstance(value, dict) and value:
            tables[field] = value
    return tables


def check_model_names(case: Any, chk: Any) -> None:
    """The ``[soil]`` and ``[hydro]`` model names and option tables of ``case`` against the
    registries; the first problem is a :class:`CaseFileError` through ``chk`` (a
    :class:`~onbottom.cases.tables.Checker`: key, file, line)."""
    soil = getattr(case, "soil", None)
    if soil is not None:
        _check_table(chk, "soil", soil.model, soil.models, SOIL_MODELS)
    hydro = getattr(case, "hydro", None)
    if hydro is not None and hydro.model is not None:
        _check_table(chk, "hydro", hydro.model, model_tables(hydro), FORCE_REGISTRY)
    elif hydro is not None:
        for name in getattr(hydro, "models", {}) or {}:
            if name not in FORCE_REGISTRY.load():
                _unknown(chk, f"hydro.{name}", name, FORCE_REGISTRY)


def _unknown(chk: Any, key: str, name: str, registry: Any) -> None:
    chk.fail(
        key,
        f"{key} = {name!r} is invalid: no {registry.family} of that name; choose one of"
        f" {', '.join(map(repr, registry.load()))}",
    )


def _check_table(
    chk: Any,
    table: str,
    name: str | None,
    options: dict[str, dict[str, Any]],
    registry: Any,
) -> None:
    registry.load()
    if name is not None and name not in registry:
        _unknown(chk, f"{table}.model", name, registry)
    for other, opts in options.items():
        if other not in registry:
            chk.fail(
                f"{table}.{other}",
                f"[{table}.{other}] is invalid: no {registry.family} {other!r}; choose one of"
                f" {', '.join(map(repr, registry))}",
            )
        if other != name:
            chk.fail(
                f"{table}.{other}",
                f"[{table}.{other}] is given but {table}.model = {name!r}: set model ="
                f" {other!r} or remove [{table}.{other}]",
            )
        try:
            registry.check_options(other, opts, where=f"{table}.{other}")
        except InputError as exc:
            key = str(exc).split(" ", 1)[0]
            chk.fail(key, str(exc))


def soil_from_case(
    soil: SoilTable | None, kind: str, pipe: Pipe, seabed: Sand | Clay | Rock
) -> LateralResistanceModel:
    """The soil model of a case: ``[soil] model`` with its ``[soil.<name>]`` options when
    given, else the default of the seabed kind ``kind`` (``[seabed] model``)."""
    if soil is None or soil.model is None:
        return soil_model_for_seabed(kind, pipe, seabed)
    opts = SOIL_MODELS.check_options(
        soil.model, soil.models.get(soil.model), where=f"soil.{soil.model}"
    )
    try:
        return build_soil_model(soil.model, pipe, seabed, where="soil.model", **opts)
    except TypeError as exc:  # an option the builder sets itself, or a wrong type
        raise InputError(f"[soil.{soil.model}] invalid options: {exc}") from None
