"""The ``[hydro]`` table of a case file → a force model (``storm``, ``curves``, ``sweep``...).

:func:`force_model_from_case` turns the parsed ``[hydro]`` table of a storm-type case file
(``model``, ``cd``/``cm``/``cl``/``added_mass_coefficient``, ``coefficient_table``, the
sub-table ``[hydro.<model>]`` of the model's options) into a model of :mod:`onbottom.hydro`
by its registry name (:mod:`onbottom.hydro.registry`). Files the table names (a Morison
coefficient table, a Fourier coefficient table) are relative to the case file's folder and must
stay inside it (:func:`onbottom._casefile.contained`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from onbottom._casefile import contained
from onbottom.cases.models import model_tables
from onbottom.errors import InputError
from onbottom.hydro.registry import build_force_model, force_model_class, model_options

__all__ = ["case_file", "force_model_from_case"]


def case_file(value: str, base_dir: str | Path | None, where: str) -> Path:
    """A file named in a case file: relative to (and contained in) the case file's folder
    ``base_dir`` (None: taken as given); a file that does not exist is an error naming
    ``where``."""
    p = Path(value)
    if base_dir is not None:
        if not p.is_absolute():
            p = Path(base_dir) / p
        p = contained(value, p, folder=base_dir, field=where)
    if not p.is_file():
        raise _named(f"{where} = {value!r} is invalid: no such file ({p})", where)
    return p


def force_model_from_case(
    hydro: Any, *, base_dir: str | Path | None = None, default: str = "morison"
) -> Any:
    """The force model of a case file's ``[hydro]`` table.

    ``model`` not given (None) → ``default`` (the command's default model). ``model =
    "morison"`` with ``coefficient_table`` (a CSV of C_D, C_M, C_L over K, M:
    :mod:`onbottom.hydro.morison_table`) is Morison per sea state; without it, it takes
    ``cd``, ``cm``, ``cl``, ``added_mass_coefficient`` of ``[hydro]``; every other registered
    model takes its options from ``[hydro.<name>]``. Options
    given for a model that is not selected are a named error (a sub-table that silently does
    nothing would be a silent wrong result). ``base_dir`` is the case file's folder: the
    files the table names are relative to it and must stay inside it.
    """
    name = default if hydro.model is None else hydro.model
    force_model_class(name)
    tables = model_tables(hydro)
    for other in tables:
        if other != name:
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
    _check_coefficients(hydro, name, table)
    if name == "morison":
        from onbottom.hydro.force_model import MorisonLift

        if table is not None:
            from onbottom.hydro.morison_table import MorisonCoefficientTable

            where = "hydro.coefficient_table"
            path = case_file(table, base_dir, where)
            try:
                rule = MorisonCoefficientTable.from_csv(path)
            except InputError as exc:
                raise _named(f"{where} = {table!r} is invalid: {exc}", where) from None
            return MorisonLift.per_sea_state(rule, added_mass=hydro.added_mass_coefficient)
        return MorisonLift(
            cd=hydro.cd, cm=hydro.cm, cl=hydro.cl, added_mass=hydro.added_mass_coefficient
        )
    return build_force_model(name, _options(name, tables.get(name), base_dir))


_COEFFICIENTS = ("cd", "cm", "cl", "added_mass_coefficient")


def _named(message: str, field: str) -> InputError:
    err = InputError(message)
    err.field = field  # type: ignore[attr-defined]
    return err


def _check_coefficients(hydro: Any, name: str, table: Any) -> None:
    """Constant Morison coefficients that no model reads, or that make no force, are errors:
    ``cd``, ``cm``, ``cl`` other than their defaults with ``model`` other than morison or with
    a ``coefficient_table`` (which gives them per sea state), and all three zero."""
    fields = getattr(type(hydro), "model_fields", None)
    if not fields:
        return
    defaults = {k: fields[k].default for k in _COEFFICIENTS if k in fields}
    changed = [k for k, v in defaults.items() if getattr(hydro, k) != v]
    if name != "morison":
        if changed:
            k = changed[0]
            raise _named(
                f"hydro.{k} = {getattr(hydro, k)!r} is not used by hydro.model = {name!r} (the"
                f" constant Morison coefficients are for model = 'morison'); remove"
                f" {', '.join(f'hydro.{c}' for c in changed)} or set model = 'morison'",
                f"hydro.{k}",
            )
        return
    if table is not None:
        given = [k for k in changed if k != "added_mass_coefficient"]
        if given:
            raise _named(
                f"hydro.{given[0]} = {getattr(hydro, given[0])!r} is not used with"
                " hydro.coefficient_table (the table gives C_D, C_M, C_L per sea state); remove"
                f" {', '.join(f'hydro.{c}' for c in given)}",
                f"hydro.{given[0]}",
            )
        return
    if hydro.cd == 0.0 and hydro.cm == 0.0 and hydro.cl == 0.0:
        raise _named(
            "hydro.cd = hydro.cm = hydro.cl = 0 is invalid: no wave or current force at all"
            " (F109 §3.4.3: C_D, C_M, C_L > 0); give the coefficients or remove the keys for"
            " the defaults",
            "hydro.cd",
        )


def _options(name: str, options: Any, base_dir: str | Path | None) -> Any:
    """``options`` of model ``name`` with the Fourier ``table`` path read (case-file rules)."""
    if name != "fourier" or not options:
        return options
    value = options.get("table")
    if not isinstance(value, str) or not value or value == "example":
        return options  # missing or invalid: the registry names it
    if set(options) - set(model_options(name)):
        return options  # an unknown option: the registry names it first
    from onbottom.hydro.fourier_table import FourierTable

    where = f"hydro.{name}.table"
    path = case_file(value, base_dir, where)
    try:
        return {**options, "table": FourierTable.load(path)}
    except InputError as exc:
        raise _named(f"{where} = {value!r} is invalid: {exc}", where) from None
