"""Force models by name: one registry for case files, the CLI, sweeps and the report.

``FORCE_MODELS`` maps the name used in a case file's ``[hydro] model = "…"`` to the class
(scipy's ``solve_ivp`` ``METHODS`` dict is the model): ``"morison"`` (:class:`MorisonLift`,
constant or per-sea-state coefficients), ``"wake"`` (:class:`~onbottom.hydro.wake.WakeModel`,
a reconstruction of the Lambrakos et al. 1987 / Wake II structure calibrated to DNV-RP-F109's
peak-load tables) and ``"fourier"`` (:class:`~onbottom.hydro.fourier.FourierModel`, the
Sørensen et al. 1986 / Bryndum et al. 1992 form with a user coefficient table). An unknown
name, an unknown option or a bad value is an :class:`~onbottom.errors.InputError` naming it and
the choices.

Options of a model come from a case file's sub-table (``[hydro.wake]``, ``[hydro.fourier]``)
and are the keyword arguments of the class; the Fourier model's ``table`` is a path (CSV or
NetCDF, resolved against ``base_dir``: the case file's folder) or ``"example"`` for the
synthetic table the package ships.
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
    base_dir: str | Path | None = None,
    where: str = "hydro",
) -> Any:
    """An instance of force model ``name`` with ``options`` (keyword arguments of its class).

    Parameters
    ----------
    name : str
        A key of :data:`FORCE_MODELS`.
    options : mapping or None
        Keyword arguments of the class; unknown keys are named errors listing the allowed ones.
        For ``"fourier"``, ``table`` is a path [-] to a CSV/NetCDF coefficient table (relative
        paths against ``base_dir``) or ``"example"``.
    base_dir : path or None
        Folder that relative paths are resolved against (the case file's folder).
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
        opts["table"] = _fourier_table(opts.get("table"), base_dir, f"{where}.{name}.table")
    try:
        return cls(**opts)
    except InputError as exc:
        raise InputError(f"[{where}.{name}] {exc}") from None
    except TypeError as exc:  # a wrong type the dataclass could not take
        raise InputError(f"[{where}.{name}] invalid options: {exc}") from None


def _fourier_table(value: Any, base_dir: str | Path | None, where: str) -> Any:
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
    return FourierTable.load(_case_file(value, base_dir, where))


def _case_file(value: str, base_dir: str | Path | None, where: str) -> Path:
    """A file named in a case file: relative to (and contained in) the case file's folder."""
    from onbottom._casefile import contained

    p = Path(value)
    if base_dir is not None:
        if not p.is_absolute():
            p = Path(base_dir) / p
        p = contained(value, p, folder=base_dir, field=where)
    if not p.is_file():
        raise InputError(f"{where} = {value!r} is invalid: no such file ({p})")
    return p


def force_model_from_case(
    hydro: Any, *, base_dir: str | Path | None = None, default: str = "morison"
) -> Any:
    """The force model of a case file's ``[hydro]`` table.

    ``model`` not given (None) → ``default`` (the command's default model). ``model =
    "morison"`` with ``coefficient_table`` (a CSV of C_D, C_M, C_L over K, M:
    :mod:`onbottom.hydro.morison_table`) is Morison per sea state; without it, it takes
    ``cd``, ``cm``, ``cl``, ``added_mass_coefficient`` of ``[hydro]``; ``"wake"`` and
    ``"fourier"`` take their options from ``[hydro.wake]`` or ``[hydro.fourier]``. Options
    given for a model that is not selected are a named error (a sub-table that silently does
    nothing would be a silent wrong result).
    """
    name = default if hydro.model is None else hydro.model
    force_model_class(name)
    for other in ("wake", "fourier"):
        if other != name and getattr(hydro, other):
            raise InputError(
                f"[hydro.{other}] is given but hydro.model = {name!r}: set model = {other!r}"
                f" or remove [hydro.{other}]"
            )
    table = getattr(hydro, "coefficient_table", None)
    if table is not None and name != "morison":
        raise InputError(
            f"hydro.coefficient_table is given but hydro.model = {name!r}: a coefficient table"
            " is for model = 'morison' (per-sea-state C_D, C_M, C_L)"
        )
    if name == "morison":
        from onbottom.hydro.force_model import MorisonLift

        if table is not None:
            from onbottom.hydro.morison_table import MorisonCoefficientTable

            rule = MorisonCoefficientTable.from_csv(
                _case_file(table, base_dir, "hydro.coefficient_table")
            )
            return MorisonLift.per_sea_state(rule, added_mass=hydro.added_mass_coefficient)
        return MorisonLift(
            cd=hydro.cd, cm=hydro.cm, cl=hydro.cl, added_mass=hydro.added_mass_coefficient
        )
    return build_force_model(name, getattr(hydro, name), base_dir=base_dir)
