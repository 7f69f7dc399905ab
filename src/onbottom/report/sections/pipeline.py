"""Report section: Pipeline finite-element model.

Shows the pipeline finite-element example against its limit cases.
Needs :mod:`onbottom.dynamics.pipeline`; without it: "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import SectionContent, SectionContext
from onbottom.report.registry import section
from onbottom.report.sections._pending import pending

REQUIRES = ("onbottom.dynamics.pipeline",)


@section(
    "pipeline",
    "Pipeline finite-element model",
    order=70,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Stub until the section is written against the module's interface."""
    return pending(REQUIRES[0], "pipeline")
