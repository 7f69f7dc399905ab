"""onbottom.report — the validation report.

:func:`build_report` runs the registered sections (one module each in
``onbottom/report/sections/``, registered with :func:`section`) and writes a self-contained
HTML page with its figures and tables beside it (``onbottom report --out DIR``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.report.build import ReportResult, build_report, provenance
    from onbottom.report.content import (
        Check,
        FigureRef,
        SectionContent,
        SectionContext,
        Table,
        within,
    )
    from onbottom.report.registry import REGISTRY, SECTION_MODULES, load_sections, section

__all__ = [
    "REGISTRY",
    "SECTION_MODULES",
    "Check",
    "FigureRef",
    "ReportResult",
    "SectionContent",
    "SectionContext",
    "Table",
    "build_report",
    "load_sections",
    "provenance",
    "section",
    "within",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.report.build": (
            "ReportResult",
            "build_report",
            "provenance",
        ),
        "onbottom.report.content": (
            "Check",
            "FigureRef",
            "SectionContent",
            "SectionContext",
            "Table",
            "within",
        ),
        "onbottom.report.registry": (
            "REGISTRY",
            "SECTION_MODULES",
            "load_sections",
            "section",
        ),
    },
)
