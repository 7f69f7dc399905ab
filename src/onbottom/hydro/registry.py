"""Force models by name: one registry for case files, the CLI, sweeps and the report.

``FORCE_MODELS`` maps the name used in a case file's ``[hydro] model = "…"`` to the class
(scipy's ``solve_ivp`` ``METHODS`` dict is the model): ``"morison"`` (:class:`MorisonLift`,
constant or per-sea-state coefficients), ``"wake"`` (:class:`~onbottom.hydro.wake.WakeModel`,
a reconstruction of the Lambrakos et al. 1987 / Wake II structure calibrated to DNV-RP-F109's
peak-load tables) and ``"fourier"`` (:class:`~onbottom.hydro.fourier.FourierModel`, the
Sørensen et al. 1986 / Bryndum et al. 1992 form with a user coefficient table). An unknown
name, an unknown option or a bad value is an :class:`~onbottom.errors.InputError` naming it and
the choices.

Options of a model are the keyword arguments of the class (in a case file, its sub-table
``[hydro.wake]``, ``[hydro.fourier]``); the Fourier model's ``table`` is a coefficient table, a
path (CSV or NetCDF) or ``"example"`` for the synthetic table the package ships. A case file's
``[hydro]`` table (paths relative to the case file's folder) is built into a model by
:func:`onbottom.cases.force.force_model_from_case`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import BaseModel

from onbottom.errors import InputError
from onbottom.registry import Registry, options_schema

__all__ = [
    "FORCE_MODELS",
    "FORCE_REGISTRY",
    "ForceModelEntry",
    "build_force_model",
    "force_model_class",
    "force_model_names",
    "register_force_model",
]

_NOT_OPTIONS = ("name", "model_id", "rule")


@dataclass(frozen=True)
class ForceModelEntry:
    """One registered force model (an entry of :class:`onbottom.registry.Registry`):
    ``name``, ``cls`` (a frozen dataclass on the
    :class:`~onbottom.hydro.force_model.ForceModel` protocol), ``description`` (one line),
    ``options`` (the pydantic schema of ``[hydro.<name>]``), ``example`` (options that build
    a model for the conformance tests when the class needs some)."""

    name: str
    cls: type
    description: str = ""
    options: type[BaseModel] | None = None
    example: Mapping[str, Any] = field(default_factory=dict)


def _register_builtin() -> None:
    from onbottom.hydro.force_model import MorisonLift
    from onbottom.hydro.fourier import FourierModel
    from onbottom.hydro.wake import WakeModel

    for name, cls, text, example in (
        ("morison", MorisonLift, "Morison drag and inertia with a lift force", {}),
        ("wake", WakeModel, "wake model (Lambrakos et al. 1987 / Wake II structure)", {}),
        (
            "fourier",
            FourierModel,
            "Fourier force model (Sørensen et al. 1986, Bryndum et al. 1992)",
            {"table": "example"},
        ),
    ):
        register_force_model(name, cls, description=text, example=example)


FORCE_REGISTRY: Registry[ForceModelEntry] = Registry(
    "force model", "hydro.model", loader=_register_builtin
)
"""Registered force models by name (the built-in ones registered on first look-up)."""

FORCE_MODELS: tuple[str, ...] = ("morison", "wake", "fourier")
"""The built-in force models, in the order the documentation lists them (all registered ones:
:func:`force_model_names`)."""


def register_force_model(
    name: str,
    cls: type,
    *,
    description: str = "",
    options: type[BaseModel] | None = None,
    kernel: Callable[..., None] | None = None,
    example: Mapping[str, Any] | None = None,
    replace: bool = False,
) -> type:
    """Register force-model class ``cls`` (a frozen dataclass on the
    :class:`~onbottom.hydro.force_model.ForceModel` protocol) under ``name``.

    Its dataclass fields (less ``name``, ``model_id``, ``rule``) are the options a case file
    may give (``[hydro.<name>]``) unless ``options`` gives the schema. ``kernel``: the model's
    own numba kernel, added to the solvers' dispatch
    (:func:`onbottom.hydro._force_dispatch.register_force_kernel`); the class's ``model_id``
    (then a class attribute, not a field) is set to its id. A name taken is an error unless
    ``replace`` (docs/contributing.md, "Add a force model").
    """
    if not dataclasses.is_dataclass(cls) or not isinstance(cls, type):
        raise InputError(f"force model {name!r}: cls = {cls!r} is invalid: a dataclass")
    if name in FORCE_REGISTRY and not replace:
        raise InputError(f"force model {name!r} is registered already (pass replace=True)")
    if options is None:
        options = options_schema(cls, exclude=_NOT_OPTIONS, name=f"{cls.__name__}Options")
    if kernel is not None:
        from onbottom.hydro._force_dispatch import register_force_kernel

        if any(f.name == "model_id" for f in dataclasses.fields(cls)):
            raise InputError(
                f"force model {name!r}: model_id is a field of {cls.__name__}: leave it out"
                " when the kernel is registered (the registry sets the class's model_id)"
            )
        cls.model_id = register_force_kernel(kernel)
    else:
        from onbottom.hydro._force_dispatch import _KERNELS

        if getattr(cls, "model_id", None) not in _KERNELS:
            raise InputError(
                f"force model {name!r}: {cls.__name__}.model_id ="
                f" {getattr(cls, 'model_id', None)!r} names no kernel of the solvers'"
                " dispatch: pass kernel=<the model's numba kernel>"
            )
    FORCE_REGISTRY.add(
        ForceModelEntry(name, cls, description, options, dict(example or {})), replace=replace
    )
    return cls


def force_model_names() -> tuple[str, ...]:
    """The registered names."""
    return FORCE_REGISTRY.names()


def force_model_class(name: str, *, where: str = "hydro.model") -> type:
    """The class registered under ``name``; a named error listing the choices otherwise."""
    return FORCE_REGISTRY.entry(name, where=where).cls


def model_options(name: str) -> tuple[str, ...]:
    """The option names a case file may give for model ``name``."""
    schema = FORCE_REGISTRY.entry(name).options
    return tuple(schema.model_fields) if schema is not None else ()


def build_force_model(
    name: str,
    options: Mapping[str, Any] | None = None,
    *,
    where: str = "hydro",
) -> Any:
    """An instance of force model ``name`` with ``options`` (keyword arguments of its class).

    Parameters
    ----------
    name : str
        A key of :data:`FORCE_MODELS`.
    options : mapping or None
        Keyword arguments of the class; unknown keys are named errors listing the allowed ones.
        For ``"fourier"``, ``table`` is a :class:`~onbottom.hydro.fourier_table.FourierTable`,
        the path [-] of a CSV/NetCDF coefficient table, or ``"example"``. (A case file's
        ``[hydro]`` table, with paths relative to its folder, is built by
        :func:`onbottom.cases.force.force_model_from_case`.)
    where : str
        Prefix of the error messages (the case-file table).
    """
    cls = force_model_class(name, where=f"{where}.model")
    opts = FORCE_REGISTRY.check_options(name, options, where=f"{where}.{name}")
    if name == "fourier":
        opts["table"] = _fourier_table(opts.get("table"), f"{where}.{name}.table")
    try:
        return cls(**opts)
    except InputError as exc:
        raise InputError(f"[{where}.{name}] {exc}") from None
    except TypeError as exc:  # a wrong type the dataclass could not take
        raise InputError(f"[{where}.{name}] invalid options: {exc}") from None


def _fourier_table(value: Any, where: str) -> Any:
    from onbottom.hydro.fourier_table import FourierTable

    if isinstance(value, FourierTable):
        return value
    if value is None:
        raise InputError(
            f"{where} is missing: give the path of a coefficient table (CSV or NetCDF,"
            " docs/theory/fourier_model.md) or 'example' for the synthetic one"
        )
    if not isinstance(value, str) or not value:
        raise InputError(f"{where} = {value!r} is invalid: expected a path or 'example'")
    if value == "example":
        return FourierTable.example()
    p = Path(value)
    if not p.is_file():
        raise InputError(f"{where} = {value!r} is invalid: no such file ({p})")
    return FourierTable.load(p)
