"""What the storm-section solver needs, built from a storm case or by hand.

:class:`StormSetup` is a plain value type: :mod:`onbottom.cases.storm` builds it from a case
file, and the API (:func:`onbottom.dynamics.storm_section.simulate_storm_section`, the
reliability campaign, the route assessment) takes it as it is.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from onbottom.dynamics.storm_section import StormSolverSettings
from onbottom.hydro.force_model import ForceModel
from onbottom.hydro.reductions import LoadReductions
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.inputs.storm import Current, Storm
from onbottom.soil.base import LateralResistanceModel

__all__ = ["StormSetup"]


@dataclass(frozen=True)
class StormSetup:
    """Everything :func:`simulate_storm_section` needs, built from a case.

    ``storm`` is a :class:`Storm` (``[storm] kind = "spectral"``) or, for a regular wave or a
    measured record, its :class:`StormKinematics` (current included; one deterministic run).
    """

    pipe: Pipe
    soil: LateralResistanceModel
    seabed: Sand | Clay | Rock
    storm: Storm | StormKinematics
    depth: float
    current: Current
    z0: float
    force_model: ForceModel
    reductions: LoadReductions
    settings: StormSolverSettings
    sample_interval: float | None
    seeds: int
    fractile: float
    path: str | None
    compression_level: int = 0

    def kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :func:`onbottom.dynamics.storm_section.simulate_storm_section`."""
        return {
            "depth": self.depth,
            "current": self.current,
            "z0": self.z0,
            "sample_interval": self.sample_interval,
            "force_model": self.force_model,
            "reductions": self.reductions,
            "settings": self.settings,
        }
