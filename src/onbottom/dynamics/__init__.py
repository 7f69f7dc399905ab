"""onbottom.dynamics — load programmes, the pipe-section time-domain solver, centrifuge presets.

See docs/theory/section_dynamics.md and docs/validation/youssef_cassidy_2014.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.dynamics.centrifuge import (
        RECOMMENDED,
        TESTS,
        CentrifugeTest,
        ParameterSet,
        build_programme,
        build_soil,
        get_test,
        run_centrifuge_test,
    )
    from onbottom.dynamics.programmes import (
        LoadProgramme,
        from_arrays,
        inclined_cyclic,
        irregular_wave_current_groups,
        regular_wave_current_groups,
    )
    from onbottom.dynamics.result import SolverResult
    from onbottom.dynamics.section import (
        SectionResult,
        SolverSettings,
        section_mass,
        simulate_section,
    )
    from onbottom.dynamics.status import Status

__all__ = [
    "RECOMMENDED",
    "TESTS",
    "CentrifugeTest",
    "LoadProgramme",
    "ParameterSet",
    "SectionResult",
    "SolverResult",
    "SolverSettings",
    "Status",
    "build_programme",
    "build_soil",
    "from_arrays",
    "get_test",
    "inclined_cyclic",
    "irregular_wave_current_groups",
    "regular_wave_current_groups",
    "run_centrifuge_test",
    "section_mass",
    "simulate_section",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.dynamics.centrifuge": (
            "RECOMMENDED",
            "TESTS",
            "CentrifugeTest",
            "ParameterSet",
            "build_programme",
            "build_soil",
            "get_test",
            "run_centrifuge_test",
        ),
        "onbottom.dynamics.programmes": (
            "LoadProgramme",
            "from_arrays",
            "inclined_cyclic",
            "irregular_wave_current_groups",
            "regular_wave_current_groups",
        ),
        "onbottom.dynamics.result": ("SolverResult",),
        "onbottom.dynamics.status": ("Status",),
        "onbottom.dynamics.section": (
            "SectionResult",
            "SolverSettings",
            "section_mass",
            "simulate_section",
        ),
    },
)
