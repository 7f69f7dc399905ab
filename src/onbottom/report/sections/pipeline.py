"""Report section: Pipeline finite-element model.

Shows the pipeline finite-element example (beam on the pipe–soil springs) against its analytic limit cases. Needs :mod:`onbottom.dynamics.pipeline`; until that module is part of the build the report lists
this section as "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext
from onbottom.report.registry import section

REQUIRES = ("onbottom.dynamics.pipeline",)


@section("pipeline", "Pipeline finite-element model", order=70, requires=REQUIRES)
def build(ctx: SectionContext) -> SectionContent:
    """The module is present but this section has not been written for its interface yet."""
    return SectionContent(
        summary="onbottom.dynamics.pipeline is present in this build, but the report section for it has not been"
        " written yet (onbottom/report/sections/pipeline.py).",
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
