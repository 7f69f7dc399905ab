"""Content of a section whose module is in the build but whose report section is not written."""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent


def pending(module: str, name: str) -> SectionContent:
    """Say visibly that ``module`` is present but ``sections/<name>.py`` is still a stub."""
    return SectionContent(
        summary=f"{module} is present in this build, but the report section for it has not"
        f" been written yet (onbottom/report/sections/{name}.py).",
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
