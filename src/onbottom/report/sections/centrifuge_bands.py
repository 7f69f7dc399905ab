"""Report section: Centrifuge tests: sensitivity bands.

Shows the cycles to the limit of the seven centrifuge tests over the uncertain inputs
(γ', α, cycle shape, time axis) against Table 1.
Needs :mod:`onbottom.study.centrifuge_bands`; without it: "not available in this build".
"""

from __future__ import annotations

from onbottom.report.content import SectionContent, SectionContext
from onbottom.report.registry import section
from onbottom.report.sections._pending import pending

REQUIRES = ("onbottom.study.centrifuge_bands",)


@section(
    "centrifuge_bands",
    "Centrifuge tests: sensitivity bands",
    order=25,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Stub until the section is written against the module's interface."""
    return pending(REQUIRES[0], "centrifuge_bands")
