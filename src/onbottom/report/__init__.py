"""onbottom.report — the validation report.

:func:`build_report` runs the registered sections (one module each in
``onbottom/report/sections/``, registered with :func:`section`) and writes a self-contained
HTML page with its figures and tables beside it (``onbottom report --out DIR``).
"""

from onbottom.report.build import ReportResult, build_report, provenance
from onbottom.report.content import Check, FigureRef, SectionContent, SectionContext, Table, within
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
