"""Lazy exports for package ``__init__`` files (PEP 562 module ``__getattr__``; private).

A package lists the names it exports and the submodule that defines each; a name is imported
on first access, so ``import onbottom.soil`` (and every ``import onbottom.soil.x``, which runs
the package ``__init__`` first) costs nothing beyond the package itself. Usage::

    from typing import TYPE_CHECKING
    from onbottom._lazy import attach

    if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
        from onbottom.soil.coulomb import CoulombFriction

    __all__ = ["CoulombFriction"]
    __getattr__, __dir__ = attach(__name__, {"onbottom.soil.coulomb": ("CoulombFriction",)})

``tests/unit/test_lazy_imports.py`` checks that each table, its ``__all__`` and its
``TYPE_CHECKING`` imports name the same things and that every exported name resolves.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterable, Mapping
from typing import Any

__all__ = ["attach", "lazy_table"]


def lazy_table(package: str) -> dict[str, str]:
    """The name → defining module table of a package set up by :func:`attach`."""
    return dict(getattr(sys.modules[package], "_LAZY_TABLE", {}))


def attach(
    package: str, exports: Mapping[str, Iterable[str]]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """Module ``__getattr__`` and ``__dir__`` for ``package`` exporting ``exports`` lazily.

    Parameters
    ----------
    package
        The package's ``__name__``.
    exports
        Defining module (absolute dotted name) → the names it exports through the package.
    """
    table: dict[str, str] = {}
    for module, names in exports.items():
        for name in names:
            if name in table:
                raise ValueError(f"{package}: {name!r} exported from two modules")
            table[name] = module
    namespace = sys.modules[package].__dict__
    namespace["_LAZY_TABLE"] = table

    def __getattr__(name: str) -> Any:
        module = table.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(table))

    return __getattr__, __dir__
