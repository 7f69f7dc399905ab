"""Unit test: :func:`onbottom.report.registry.section_catalogue`, the list of
``onbottom report --list``, called directly."""

from __future__ import annotations

from onbottom.report.registry import ReportSection, UnavailableSection, section_catalogue


def _build(ctx):  # pragma: no cover - never run
    raise AssertionError("a catalogue runs no section")


def test_available_means_imported_and_requirements_importable():
    secs = [
        ReportSection(name="plain", title="Plain", order=1, build=_build),
        ReportSection(
            name="needs", title="Needs", order=2, build=_build, requires=("no_such_mod",)
        ),
        ReportSection(
            name="has", title="Has", order=3, build=_build, slow=True, requires=("json",)
        ),
        UnavailableSection(name="gone", title="gone", order=1000, reason="not in this build"),
    ]
    assert section_catalogue(secs) == [
        {"name": "plain", "title": "Plain", "slow": False, "available": True},
        {"name": "needs", "title": "Needs", "slow": False, "available": False},
        {"name": "has", "title": "Has", "slow": True, "available": True},
        {"name": "gone", "title": "gone", "slow": False, "available": False},
    ]


def test_default_is_every_registered_section():
    names = [row["name"] for row in section_catalogue()]
    assert {"f114", "centrifuge", "calibration", "dem"} <= set(names)
    assert len(names) == len(set(names))
