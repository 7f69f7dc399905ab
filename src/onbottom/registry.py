"""One registry type for every pluggable family: soil models, force models, design checks.

A :class:`Registry` maps a name (the one a case file writes, ``[soil] model = "<name>"``) to an
entry; every entry carries ``name``, ``description`` (one line) and ``options`` (a pydantic
model of the options a case file may give in ``[<table>.<name>]``, units and ranges in the field
descriptions; ``None``: no options). The family adds its own fields (the class, the builder,
the kernel, the seabeds). scipy's ``solve_ivp`` ``METHODS`` dict is the model; the registry is
a ``dict`` so that code and tests that read it as one keep working.

An unknown name is an :class:`~onbottom.errors.InputError` naming the key and listing the
registered names (:meth:`Registry.entry`); options not in the schema are named errors listing
the allowed ones (:meth:`Registry.check_options`). Built-in entries may register lazily
(``loader``, run once before the first look-up), so that a registry module imports nothing
heavy. :func:`options_schema` derives a schema from a dataclass and its numpy-style docstring
(the ``Parameters`` section gives each field's description, unit and range).
"""

from __future__ import annotations

import dataclasses
import inspect
import re
from collections.abc import Callable, Iterable, Mapping
from typing import Any, Generic, Protocol, TypeVar

from pydantic import BaseModel, ConfigDict, Field, ValidationError, create_model

from onbottom.errors import InputError

__all__ = ["Registry", "RegistryEntry", "options_schema"]


class RegistryEntry(Protocol):
    """What every entry of a :class:`Registry` has."""

    name: str
    description: str
    options: type[BaseModel] | None


E = TypeVar("E", bound=RegistryEntry)


class Registry(dict[str, E], Generic[E]):
    """Entries of one family by name (a ``dict``: name → entry, in registration order).

    Parameters
    ----------
    family : str
        What the entries are, for messages ("soil model", "force model", "design check").
    key : str
        The case-file key that names an entry (``"soil.model"``): default ``where`` of errors.
    loader : callable or None
        Registers the built-in entries; called once, before the first look-up.
    """

    def __init__(self, family: str, key: str, loader: Callable[[], None] | None = None) -> None:
        super().__init__()
        self.family, self.key = family, key
        self._loader = loader

    def load(self) -> Registry[E]:
        """Register the built-in entries (once); returns the registry."""
        loader, self._loader = self._loader, None
        if loader is not None:
            loader()
        return self

    def snapshot(self) -> dict[str, E]:
        """A copy of the entries, the built-in ones included (they are registered first)."""
        return dict(self.load())

    def restore(self, saved: Mapping[str, E]) -> None:
        """Make the entries those of ``saved`` (a :meth:`snapshot`), in its order."""
        self.load()
        self.clear()
        self.update(saved)

    def add(self, entry: E, *, replace: bool = False) -> E:
        """Register ``entry`` under ``entry.name``; a name taken is an error unless
        ``replace``."""
        name = entry.name
        if not isinstance(name, str) or not name.isidentifier():
            raise InputError(f"{self.family} name = {name!r} is invalid: a lower-case identifier")
        if name in self and not replace:
            raise InputError(f"{self.family} {name!r} is registered already (pass replace=True)")
        self[name] = entry
        return entry

    def names(self) -> tuple[str, ...]:
        """The registered names, in registration order."""
        return tuple(self.load())

    def entry(self, name: Any, *, where: str | None = None) -> E:
        """The entry of ``name``; an :class:`InputError` naming ``where`` (default: the
        registry's key) and listing the registered names otherwise."""
        self.load()
        if not isinstance(name, str) or name not in self:
            raise InputError(
                f"{where or self.key} = {name!r} is invalid: choose one of"
                f" {', '.join(map(repr, self))} (registered {self.family}s)"
            )
        return self[name]

    def check_options(
        self, name: str, options: Mapping[str, Any] | None, *, where: str
    ) -> dict[str, Any]:
        """``options`` of entry ``name`` checked against its schema: an unknown key or a value
        the schema refuses is an :class:`InputError` naming ``where.<key>``. Returns the
        options as given (the class validates ranges and builds)."""
        opts = dict(options or {})
        schema = self.entry(name).options
        if schema is None:
            if opts:
                raise InputError(
                    f"{where}.{next(iter(opts))} is invalid: the {self.family} {name!r} takes no"
                    " options"
                )
            return opts
        allowed = tuple(schema.model_fields)
        for key in opts:
            if key not in allowed:
                raise InputError(
                    f"{where}.{key} is not an option of the {name!r} {self.family}: choose from"
                    f" {', '.join(allowed) or '(none)'}"
                )
        try:
            schema.model_validate(opts)
        except ValidationError as exc:
            err = exc.errors()[0]
            loc = ".".join(str(p) for p in err["loc"])
            raise InputError(
                f"{where}.{loc} = {err.get('input')!r} is invalid: {err['msg']}"
            ) from None
        return opts

    def table(self) -> str:
        """The registered entries as a Markdown table (name, description, options)."""
        rows = [f"| name | {self.family} | options |", "|---|---|---|"]
        for name, e in self.load().items():
            opts = ", ".join(f"`{k}`" for k in (e.options.model_fields if e.options else ()))
            rows.append(f"| `{name}` | {e.description} | {opts or '—'} |")
        return "\n".join(rows)


_PARAM = re.compile(r"^(\w+)\s*:\s*[^\n]*\n((?:[ \t]+[^\n]*\n?)*)", re.MULTILINE)


def _docstring_fields(cls: type) -> dict[str, str]:
    doc = inspect.getdoc(cls) or ""
    if "Parameters" not in doc:
        return {}
    section = doc.split("Parameters", 1)[1].split("\n\n", 1)[0] + "\n"
    return {m[1]: " ".join(m[2].split()) for m in _PARAM.finditer(section)}


def options_schema(
    cls: type, *, exclude: Iterable[str] = (), name: str | None = None
) -> type[BaseModel]:
    """A pydantic model of the options of dataclass ``cls``: its init fields less ``exclude``,
    each described by the ``Parameters`` section of the class docstring (unit and range are
    the docstring's: the class validates the values, and which are required, when it is
    built; a builder may set some from the pipe or the seabed). Types are not re-checked here
    (the class does), so the schema accepts what the class accepts."""
    if not dataclasses.is_dataclass(cls):
        raise InputError(f"options_schema: cls = {cls!r} is invalid: a dataclass")
    docs = _docstring_fields(cls)
    skip = set(exclude)
    spec: dict[str, Any] = {}
    for f in dataclasses.fields(cls):
        if not f.init or f.name in skip or f.name.startswith("_"):
            continue
        spec[f.name] = (Any, Field(None, description=docs.get(f.name, "")))
    return create_model(
        name or f"{cls.__name__}Options",
        __config__=ConfigDict(extra="forbid", arbitrary_types_allowed=True),
        **spec,
    )
