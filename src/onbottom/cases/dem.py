"""DEM config files (JSON): ``onbottom dem prepare|penetrate --config`` and ``onbottom dem-lammps``.

A DEM config file is :meth:`DEMConfig.to_json <onbottom.dem.config.DEMConfig.to_json>`: one
table per dataclass of :mod:`onbottom.dem.config` (``geometry``, ``psd``, ``target``,
``material``, ``contacts``, ``preparation``, ``loading``, ``numerics``) plus ``name`` and
``seed``. Its strict schema mirrors those dataclasses field by field (:func:`dem_config_schema`):
unknown keys, wrong types and missing required keys raise
:class:`~onbottom._casefile.CaseFileError` naming the key, the file and the line; tables left
out take the dataclasses' defaults, whose own checks (ranges, cross-checks) then apply.

The input files the ``dem`` commands take besides the config, a prepared specimen
(:func:`load_sample`) and a run or summary (:func:`load_run`), are read here too, so that a file
of the wrong kind is an input error naming it.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import os
from typing import Any, get_type_hints

from onbottom._casefile import CaseFileError, StrictModel, parse_case, read_json
from onbottom.dem.config import DEMConfig
from onbottom.errors import InputError

__all__ = [
    "dem_config_from_dict",
    "dem_config_from_json",
    "dem_config_schema",
    "load_dem_config",
    "load_run",
    "load_sample",
]


def load_dem_config(path: str | os.PathLike) -> DEMConfig:
    """Read a DEM config JSON file (:meth:`DEMConfig.to_json`); errors name the file, key and
    line."""
    d, text = read_json(path)
    return dem_config_from_dict(d, file=path, text=text)


def dem_config_from_json(s: str) -> DEMConfig:
    """The config of a JSON string (inverse of :meth:`DEMConfig.to_json`)."""
    try:
        d = json.loads(s)
    except json.JSONDecodeError as exc:
        raise CaseFileError(
            f"DEM config is not valid JSON: {exc.msg} (line {exc.lineno}, column {exc.colno})",
            line=exc.lineno,
        ) from None
    return dem_config_from_dict(d, text=s)


def dem_config_from_dict(
    d: Any, *, file: str | os.PathLike | None = None, text: str | None = None
) -> DEMConfig:
    """Inverse of :meth:`DEMConfig.to_dict`, checked against the strict schema of a DEM config.

    Unknown keys, wrong types and missing required keys raise
    :class:`~onbottom._casefile.CaseFileError` naming the key (and the file and line when
    ``file``/``text`` are given); sections left out take their defaults.
    """
    doc = parse_case(dem_config_schema(), d, file=file, text=text)
    return _build(DEMConfig, doc)


def dem_config_schema() -> type[StrictModel]:
    """The strict schema of a DEM config file (a mirror of :class:`DEMConfig`)."""
    return _schema_of(DEMConfig)


@functools.cache
def _schema_of(dc: type) -> type[StrictModel]:
    """A strict pydantic schema (``_casefile.StrictModel``) mirroring the dataclass ``dc``."""
    import pydantic

    hints = get_type_hints(dc)
    fields: dict[str, Any] = {}
    for f in dataclasses.fields(dc):
        t = hints[f.name]
        if dataclasses.is_dataclass(t):
            required = f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
            sub = _schema_of(t)
            fields[f.name] = (sub, ...) if required else (sub | None, None)
        elif f.default is not dataclasses.MISSING:
            fields[f.name] = (t, f.default)
        else:
            fields[f.name] = (t, ...)
    return pydantic.create_model(f"{dc.__name__}Schema", __base__=StrictModel, **fields)


def _build(dc: type, model: Any) -> Any:
    """The dataclass ``dc`` from a validated schema instance (None → the dataclass default)."""
    hints = get_type_hints(dc)
    kwargs: dict[str, Any] = {}
    for f in dataclasses.fields(dc):
        value = getattr(model, f.name)
        if dataclasses.is_dataclass(hints[f.name]):
            if value is None:
                continue
            value = _build(hints[f.name], value)
        kwargs[f.name] = value
    return dc(**kwargs)


def load_sample(path: str | os.PathLike, *, field: str = "--sample") -> Any:
    """A prepared specimen (:class:`~onbottom.dem.sample.Sample`) read from ``path``.

    A file that is not one (unreadable, truncated, another kind of file) is an
    :class:`~onbottom.errors.InputError` naming ``field`` and the file.
    """
    from onbottom.dem.sample import Sample

    try:
        return Sample.load(path)
    except Exception as exc:  # unreadable, truncated or another kind of file
        err = InputError(
            f"{field} = {str(path)!r} is invalid: not a readable specimen file"
            f" ({type(exc).__name__}: {exc}); prepare one with 'onbottom dem prepare'"
        )
        err.field = field  # type: ignore[attr-defined]
        raise err from None


def load_run(path: str | os.PathLike) -> Any:
    """A run or summary dataset of ``dem penetrate`` / ``dem summarize`` read from ``path``.

    A file that is neither is an :class:`~onbottom.errors.InputError` naming it.
    """
    from onbottom.results import load_dataset

    try:
        ds = load_dataset(path)
    except Exception as exc:  # unreadable, truncated or not NetCDF
        raise InputError(
            f"results = {str(path)!r} is invalid: not a readable NetCDF file"
            f" ({type(exc).__name__}: {exc})"
        ) from None
    if not ({"V_prototype", "V_prototype_mean"} & set(ds.data_vars)):
        raise InputError(
            f"results = {str(path)!r} is invalid: not a 'dem penetrate' run or a"
            " 'dem summarize' summary"
        )
    return ds
