"""The registry of report sections.

Each section is a small function in its own module ``onbottom/report/sections/<name>.py``,
registered with :func:`section`::

    @section("f114", "DNVGL-RP-F114 penetration", order=10, requires=("onbottom.soil",))
    def build(ctx: SectionContext) -> SectionContent: ...

:data:`SECTION_MODULES` lists the modules the report imports. A section whose module, or one
of the modules named in ``requires``, is missing from this build (another part of onbottom
not merged yet, an optional extra not installed) is not an error: the report shows it with the
note "not available in this build" and the missing module's name.
"""

from __future__ import annotations

import importlib
import importlib.util
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from onbottom.errors import InputError
from onbottom.report.content import SectionContent, SectionContext

__all__ = [
    "REGISTRY",
    "SECTION_MODULES",
    "ReportSection",
    "UnavailableSection",
    "load_sections",
    "missing_requirements",
    "section",
    "section_catalogue",
]

SECTION_MODULES: tuple[str, ...] = (
    "f114",
    "centrifuge",
    "centrifuge_bands",
    "calibration",
    "checks_f109",
    "storm_section",
    "pipeline",
    "stability_curves",
    "dem",
    "metocean",
)
"""Modules of ``onbottom.report.sections``, each registering one section (add new ones at the
end; the order on the page comes from each section's ``order``)."""


@dataclass(frozen=True, slots=True)
class ReportSection:
    """A registered section.

    Attributes
    ----------
    name : str
        Identifier used by ``onbottom report --only NAME`` (lower case, no spaces).
    title : str
        Heading on the page.
    order : int
        Position on the page (ascending).
    build : callable
        ``build(ctx: SectionContext) -> SectionContent``.
    slow : bool
        True for sections that take more than a few seconds (skipped by ``--fast``).
    requires : tuple of str
        Modules that must be importable; a missing one makes the section "not available".
    module : str
        Module that defined the section.
    """

    name: str
    title: str
    order: int
    build: Callable[[SectionContext], SectionContent]
    slow: bool = False
    requires: tuple[str, ...] = ()
    module: str = ""


@dataclass(frozen=True, slots=True)
class UnavailableSection:
    """A section module that could not be imported (shown with a note, never run)."""

    name: str
    title: str
    order: int
    reason: str
    slow: bool = False
    requires: tuple[str, ...] = field(default=())


REGISTRY: dict[str, ReportSection] = {}
"""Registered sections by name (filled by importing the section modules)."""


def section(
    name: str,
    title: str,
    order: int,
    *,
    slow: bool = False,
    requires: Iterable[str] = (),
) -> Callable[[Callable[[SectionContext], SectionContent]], Callable]:
    """Register ``fn(ctx) -> SectionContent`` as the report section ``name``.

    Parameters
    ----------
    name : str
        Identifier (``[a-z0-9_]+``); unique.
    title : str
        Heading.
    order : int
        Position on the page (ascending).
    slow : bool
        The section takes more than a few seconds.
    requires : iterable of str
        Modules (``"onbottom.dynamics.storm_section"``) the section needs; when one is missing
        the section is shown as "not available in this build".
    """
    if not name or not all(c.isalnum() or c == "_" for c in name) or name != name.lower():
        raise InputError(f"name = {name!r} is invalid: expected lower-case letters, digits, _")

    def register(fn: Callable[[SectionContext], SectionContent]):
        old = REGISTRY.get(name)
        if old is not None and old.module != fn.__module__:
            raise InputError(f"name = {name!r} is invalid: already registered by {old.module}")
        REGISTRY[name] = ReportSection(
            name=name,
            title=title,
            order=int(order),
            build=fn,
            slow=bool(slow),
            requires=tuple(requires),
            module=fn.__module__,
        )
        return fn

    return register


def missing_requirements(sec: ReportSection) -> list[str]:
    """The modules in ``sec.requires`` that this build cannot import."""
    missing = []
    for mod in sec.requires:
        try:
            found = importlib.util.find_spec(mod) is not None
        except ModuleNotFoundError:  # a parent package is missing
            found = False
        if not found:
            missing.append(mod)
    return missing


def load_sections(
    modules: Iterable[str] = SECTION_MODULES,
) -> list[ReportSection | UnavailableSection]:
    """Import the section modules; return every section, ordered by ``order`` then name.

    A module that fails with :class:`ModuleNotFoundError` (a part of onbottom or an optional
    package missing from this build) becomes an :class:`UnavailableSection` carrying the
    missing module's name. Any other import error is a bug and propagates.
    """
    found: dict[str, ReportSection | UnavailableSection] = {}
    for i, mod in enumerate(modules):
        full = f"onbottom.report.sections.{mod}"
        try:
            importlib.import_module(full)
        except ModuleNotFoundError as exc:
            if exc.name == full:
                reason = f"section module {full} is not in this build"
            else:
                reason = f"module {exc.name} is not in this build"
            found[mod] = UnavailableSection(name=mod, title=mod, order=1000 + i, reason=reason)
    for sec in REGISTRY.values():
        found[sec.name] = sec
    return sorted(found.values(), key=lambda s: (s.order, s.name))


def section_catalogue(
    sections: Iterable[ReportSection | UnavailableSection] | None = None,
) -> list[dict[str, str | bool]]:
    """The report's sections as ``onbottom report --list`` shows them: ``name``, ``title``,
    ``slow`` and ``available`` (its module imported and every module it ``requires``
    importable). ``sections``: default :func:`load_sections`."""
    secs = load_sections() if sections is None else sections
    return [
        {
            "name": s.name,
            "title": s.title,
            "slow": s.slow,
            "available": isinstance(s, ReportSection) and not missing_requirements(s),
        }
        for s in secs
    ]
