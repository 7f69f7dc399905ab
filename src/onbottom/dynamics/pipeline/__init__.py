"""onbottom.dynamics.pipeline — whole-pipeline FE model in a short-crested storm.

Planform corotational beam (axial, lateral, rotation per node), soil kernels at every node,
Morison loads with relative velocity from short-crested kinematics, HHT-α with full Newton
and an O(n) banded solve. Theory: docs/theory/pipeline_fe.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.dynamics.pipeline.model import END_CONDITIONS, PipelineModel, SoilSection
    from onbottom.dynamics.pipeline.solver import (
        CRITERIA_OVER_D,
        PipelineResult,
        PipelineSettings,
        pipeline_identity,
        simulate_pipeline,
    )
    from onbottom.dynamics.pipeline.storm_run import PipelineStormRun, simulate_pipeline_storm
    from onbottom.dynamics.pipeline.user_load import (
        TableLoad,
        TravellingSineLoad,
        UserLoad,
        still_water,
    )

__all__ = [
    "CRITERIA_OVER_D",
    "END_CONDITIONS",
    "PipelineModel",
    "PipelineResult",
    "PipelineSettings",
    "PipelineStormRun",
    "SoilSection",
    "TableLoad",
    "TravellingSineLoad",
    "UserLoad",
    "pipeline_identity",
    "simulate_pipeline",
    "simulate_pipeline_storm",
    "still_water",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.dynamics.pipeline.model": (
            "END_CONDITIONS",
            "PipelineModel",
            "SoilSection",
        ),
        "onbottom.dynamics.pipeline.solver": (
            "CRITERIA_OVER_D",
            "PipelineResult",
            "PipelineSettings",
            "pipeline_identity",
            "simulate_pipeline",
        ),
        "onbottom.dynamics.pipeline.storm_run": ("PipelineStormRun", "simulate_pipeline_storm"),
        "onbottom.dynamics.pipeline.user_load": (
            "TableLoad",
            "TravellingSineLoad",
            "UserLoad",
            "still_water",
        ),
    },
)
