"""Design checks by name: one registry for case files, the CLI, sweeps and the report.

``CHECKS`` maps a check's name to a :class:`DesignCheck` (scipy's ``solve_ivp`` ``METHODS``
dict is the model). :func:`onbottom.checks.design.run_checks` runs the checks named in
``CheckOptions.checks`` (default ``("vertical", "absolute")``) in that order:

* ``vertical`` (per condition): row ``vertical_stability``, flotation with γ_W (DNV-RP-F109
  (2017) §3.3, Eq 3.1);
* ``absolute`` (per load combination): rows ``absolute_lateral`` and ``absolute_vertical``
  (F109 §3.6, Eqs 3.38–3.41).

A check ``per="condition"`` is called once per pipe condition of the options
(``run(props, options, condition)``, ``props`` the :class:`~onbottom.inputs.pipe.Pipe` or the
build-up's properties in that condition); ``per="combination"`` once per load combination
(``run(pipe, seabed, environment, combination, options, condition)``). Each returns a list of
:class:`~onbottom.checks.design.CheckRow`. An unknown name is an
:class:`~onbottom.errors.InputError` naming the field and listing the choices. A new check
registers with :func:`register_check` (docs/contributing.md, "Add a design check").
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

from pydantic import BaseModel

from onbottom.errors import InputError
from onbottom.registry import Registry

__all__ = ["CHECKS", "DesignCheck", "check_names", "get_check", "register_check"]


@dataclass(frozen=True)
class DesignCheck:
    """One registered design check.

    ``name`` (the case-file name), ``per`` (``"condition"`` or ``"combination"``), ``run``
    (the function, signature in the module docstring), ``rows`` (the names of the rows it
    returns; a floating pipe gets these rows with an infinite utilisation), ``reference`` (the
    source: standard, edition, equations), ``options`` (a pydantic schema of the check's own
    options; None: it reads :class:`~onbottom.checks.design.CheckOptions` only). An entry of
    :class:`onbottom.registry.Registry`, like the soil and force models.
    """

    name: str
    per: Literal["condition", "combination"]
    run: Callable[..., list[Any]]
    rows: tuple[str, ...]
    reference: str
    options: type[BaseModel] | None = None

    @property
    def description(self) -> str:
        """One line: the reference."""
        return self.reference


def _register_builtin() -> None:
    from onbottom.checks.builtin import _absolute_rows, _vertical_rows

    for check in (
        DesignCheck(
            "vertical",
            "condition",
            _vertical_rows,
            ("vertical_stability",),
            "DNV-RP-F109 (2017) §3.3, Eq 3.1",
        ),
        DesignCheck(
            "absolute",
            "combination",
            _absolute_rows,
            ("absolute_lateral", "absolute_vertical"),
            "DNV-RP-F109 (2017) §3.6, Eqs 3.38-3.41",
        ),
    ):
        register_check(check)


CHECKS: Registry[DesignCheck] = Registry("design check", "checks", loader=_register_builtin)
"""Registered design checks by name (the F109 ones of :mod:`onbottom.checks.builtin`,
registered on first look-up or registration)."""


def register_check(check: DesignCheck, *, replace: bool = False) -> DesignCheck:
    """Register ``check`` under ``check.name``; a name taken is an error unless ``replace``."""
    if not isinstance(check, DesignCheck):
        raise InputError(f"check = {check!r} is invalid: expected DesignCheck")
    if check.per not in ("condition", "combination"):
        raise InputError(
            f"DesignCheck.per = {check.per!r} is invalid: choose 'condition' or 'combination'"
        )
    if not check.rows:
        raise InputError(f"DesignCheck.rows = () is invalid for {check.name!r}: name its rows")
    CHECKS.load()  # the built-in checks first: a new check may replace one of them
    return CHECKS.add(check, replace=replace)


def check_names() -> tuple[str, ...]:
    """The registered names, in registration order."""
    return CHECKS.names()


def get_check(name: str, *, where: str = "checks") -> DesignCheck:
    """The check registered under ``name``; an :class:`InputError` listing the choices."""
    return CHECKS.entry(name, where=where)
