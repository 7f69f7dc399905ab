"""Report section: Centrifuge tests: sensitivity bands.

Shows the centrifuge sensitivity bands (cycles to the limit over the uncertain inputs γ', α, cycle shape, time axis) against Table 1. Needs :mod:`onbottom.study.centrifuge_bands`; until that module is part of the build the report lists
this section as "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext
from onbottom.report.registry import section

REQUIRES = ("onbottom.study.centrifuge_bands",)


@section("centrifuge_bands", "Centrifuge tests: sensitivity bands", order=25, requires=REQUIRES)
def build(ctx: SectionContext) -> SectionContent:
    """The module is present but this section has not been written for its interface yet."""
    return SectionContent(
        summary="onbottom.study.centrifuge_bands is present in this build, but the report section for it has not been"
        " written yet (onbottom/report/sections/centrifuge_bands.py).",
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
