"""Report section: Storm section: a pipe section through a design storm.

Shows the pipe-section response to a design storm (build-up, peak, decay) and its displacement against the F109 criteria. Needs :mod:`onbottom.dynamics.storm_section`; until that module is part of the build the report lists
this section as "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext
from onbottom.report.registry import section

REQUIRES = ("onbottom.dynamics.storm_section",)


@section("storm_section", "Storm section: a pipe section through a design storm", order=60, requires=REQUIRES)
def build(ctx: SectionContext) -> SectionContent:
    """The module is present but this section has not been written for its interface yet."""
    return SectionContent(
        summary="onbottom.dynamics.storm_section is present in this build, but the report section for it has not been"
        " written yet (onbottom/report/sections/storm_section.py).",
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
