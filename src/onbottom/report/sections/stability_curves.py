"""Report section: Stability curves.

Shows stability curves (required submerged weight against wave height).
Needs :mod:`onbottom.study.stability_curves`; without it: "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import SectionContent, SectionContext
from onbottom.report.registry import section
from onbottom.report.sections._pending import pending

REQUIRES = ("onbottom.study.stability_curves",)


@section(
    "stability_curves",
    "Stability curves",
    order=80,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Stub until the section is written against the module's interface."""
    return pending(REQUIRES[0], "stability_curves")
