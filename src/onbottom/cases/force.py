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
        raise InputError(f"{where} = {value!r} is invalid: no such file ({p})")
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
    if name == "morison":
        from onbottom.hydro.force_model import MorisonLift

        if table is not None:
            from onbottom.hydro.morison_table import MorisonCoefficientTable

            rule = MorisonCoefficientTable.from_csv(
                case_file(table, base_dir, "hydro.coefficient_table")
            )
            return MorisonLift.per_sea_state(rule, added_mass=hydro.added_mass_coefficient)
        return MorisonLift(
            cd=hydro.cd, cm=hydro.cm, cl=hydro.cl, added_mass=hydro.added_mass_coefficient
        )
    return build_force_model(name, _options(name, tables.get(name), base_dir))


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
    return {**options, "table": FourierTable.load(case_file(value, base_dir, where))}
