"""Report section: Stability curves.

Shows stability curves (required submerged weight against wave height) from the section model and F109. Needs :mod:`onbottom.study.stability_curves`; until that module is part of the build the report lists
this section as "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext
from onbottom.report.registry import section

REQUIRES = ("onbottom.study.stability_curves",)


@section("stability_curves", "Stability curves", order=80, requires=REQUIRES)
def build(ctx: SectionContext) -> SectionContent:
    """The module is present but this section has not been written for its interface yet."""
    return SectionContent(
        summary="onbottom.study.stability_curves is present in this build, but the report section for it has not been"
        " written yet (onbottom/report/sections/stability_curves.py).",
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
