"""A pipe-section simulation, built (``onbottom simulate``): :class:`SectionRun`.

A plain value type holding what :func:`onbottom.dynamics.section.simulate_section` takes: the
load programme, the soil model, the section's mass, the displacement limit and the solver
settings. :func:`onbottom.dynamics.centrifuge.centrifuge_run` builds it for a centrifuge test
of Youssef & Cassidy (2014); :func:`onbottom.cases.section.load_section_run` from a case file.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from onbottom.dynamics.programmes import LoadProgramme
from onbottom.dynamics.section import SectionResult, SolverSettings, simulate_section
from onbottom.soil.base import LateralResistanceModel

__all__ = ["SectionRun"]


@dataclass(frozen=True)
class SectionRun:
    """A section simulation, built (arguments of :func:`simulate_section`).

    Parameters
    ----------
    programme : LoadProgramme
        H(t), V(t) [N/m].
    soil : LateralResistanceModel
        Lateral soil model (its initial state starts the run).
    mass : float
        Mass per unit length of the moving section [kg/m], > 0.
    displacement_limit : float or None
        |u| at which the run stops [m], > 0; None = no limit.
    after_limit : {"stop", "runaway_end", "continue"}
        What happens at the limit (see :func:`simulate_section`).
    settings : SolverSettings or None
        Integrator settings (defaults if None).
    attrs : mapping
        Provenance attributes of the result (e.g. ``case_file``, ``test``).
    """

    programme: LoadProgramme
    soil: LateralResistanceModel
    mass: float
    displacement_limit: float | None = None
    after_limit: str = "stop"
    settings: SolverSettings | None = None
    attrs: Mapping[str, Any] = field(default_factory=dict)

    def simulate(self, *, progress: bool = False) -> SectionResult:
        """Run :func:`simulate_section` (``progress``: a progress bar)."""
        return simulate_section(
            self.programme,
            self.soil,
            mass=self.mass,
            displacement_limit=self.displacement_limit,
            after_limit=self.after_limit,
            settings=self.settings,
            progress=progress,
            attrs=dict(self.attrs),
        )
