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
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from onbottom.errors import InputError

__all__ = [
    "FORCE_MODELS",
    "build_force_model",
    "force_model_class",
    "force_model_names",
    "register_force_model",
]


def _classes() -> dict[str, type]:
    from onbottom.hydro.force_model import MorisonLift
    from onbottom.hydro.fourier import FourierModel
    from onbottom.hydro.wake import WakeModel

    return {"morison": MorisonLift, "wake": WakeModel, "fourier": FourierModel, **_REGISTERED}


FORCE_MODELS: tuple[str, ...] = ("morison", "wake", "fourier")
"""Names of the registered force models, in the order the documentation lists them."""

_NOT_OPTIONS = frozenset({"name", "model_id", "rule"})


_REGISTERED: dict[str, type] = {}
"""Force models added by :func:`register_force_model` (after the built-in ones)."""


def register_force_model(name: str, cls: type, *, replace: bool = False) -> type:
    """Register force-model class ``cls`` (a frozen dataclass on the
    :class:`~onbottom.hydro.force_model.ForceModel` protocol) under ``name``.

    Its dataclass fields are the options a case file may give (``[hydro.<name>]``). A name
    taken is an error unless ``replace`` (docs/contributing.md, "Add a force model").
    """
    if not isinstance(name, str) or not name.isidentifier():
        raise InputError(f"force model name = {name!r} is invalid: a lower-case identifier")
    if not dataclasses.is_dataclass(cls) or not isinstance(cls, type):
        raise InputError(f"force model {name!r}: cls = {cls!r} is invalid: a dataclass")
    if (name in FORCE_MODELS or name in _REGISTERED) and not replace:
        raise InputError(f"force model {name!r} is registered already (pass replace=True)")
    _REGISTERED[name] = cls
    return cls


def force_model_names() -> tuple[str, ...]:
    """The registered names."""
    return FORCE_MODELS + tuple(k for k in _REGISTERED if k not in FORCE_MODELS)


def force_model_class(name: str, *, where: str = "hydro.model") -> type:
    """The class registered under ``name``; a named error listing the choices otherwise."""
    classes = _classes()
    if not isinstance(name, str) or name not in classes:
        raise InputError(
            f"{where} = {name!r} is invalid: choose one of"
            f" {', '.join(map(repr, force_model_names()))}"
        )
    return classes[name]


def model_options(name: str) -> tuple[str, ...]:
    """The option names a case file may give for model ``name``."""
    cls = force_model_class(name)
    return tuple(f.name for f in dataclasses.fields(cls) if f.name not in _NOT_OPTIONS)


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
    opts = dict(options or {})
    allowed = model_options(name)
    for key in opts:
        if key not in allowed:
            raise InputError(
                f"{where}.{name}.{key} is not an option of the {name!r} force model: choose from"
                f" {', '.join(allowed)}"
            )
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
