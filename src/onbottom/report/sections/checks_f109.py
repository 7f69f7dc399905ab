"""Report section: DNV-RP-F109 design checks of the design-sheet case.

Shows the DNV-RP-F109 absolute and vertical stability checks of the design-sheet case against the hand calculation. Needs :mod:`onbottom.checks.f109`; until that module is part of the build the report lists
this section as "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext
from onbottom.report.registry import section

REQUIRES = ("onbottom.checks.f109",)


@section("checks_f109", "DNV-RP-F109 design checks of the design-sheet case", order=50, requires=REQUIRES)
def build(ctx: SectionContext) -> SectionContent:
    """The module is present but this section has not been written for its interface yet."""
    return SectionContent(
        summary="onbottom.checks.f109 is present in this build, but the report section for it has not been"
        " written yet (onbottom/report/sections/checks_f109.py).",
        checks=[
            Check(
                name="section written",
                value="no",
                reference="yes",
                tolerance="—",
                status="info",
            )
        ],
    )
