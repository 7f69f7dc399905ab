"""Report section: DNV-RP-F109 design checks of the design-sheet case.

Shows the DNV-RP-F109 absolute and vertical stability checks of the design-sheet case.
Needs :mod:`onbottom.checks.f109`; without it: "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import SectionContent, SectionContext
from onbottom.report.registry import section
from onbottom.report.sections._pending import pending

REQUIRES = ("onbottom.checks.f109",)


@section(
    "checks_f109",
    "DNV-RP-F109 design checks of the design-sheet case",
    order=50,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Stub until the section is written against the module's interface."""
    return pending(REQUIRES[0], "checks_f109")
