"""Report section: Storm section: a pipe section through a design storm.

Shows the pipe-section response to a design storm and its displacement against the
F109 criteria.
Needs :mod:`onbottom.dynamics.storm_section`; without it: "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import SectionContent, SectionContext
from onbottom.report.registry import section
from onbottom.report.sections._pending import pending

REQUIRES = ("onbottom.dynamics.storm_section",)


@section(
    "storm_section",
    "Storm section: a pipe section through a design storm",
    order=60,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Stub until the section is written against the module's interface."""
    return pending(REQUIRES[0], "storm_section")
