"""onbottom.dem — 2D discrete-element model of a pipe pushed vertically into sand.

Depends only on the base modules (errors, constants, _validate, results); see
``docs/theory/dem.md``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.dem.config import (
        PRESETS,
        SD,
        SD_REDUCED,
        SM,
        SM_REDUCED,
        ContactParameters,
        ContactSet,
        DEMConfig,
        Geometry,
        Loading,
        Material,
        Numerics,
        ParticleSizeDistribution,
        Preparation,
        Target,
        get_preset,
    )
    from onbottom.dem.engine import PipeState, Simulation, critical_time_step
    from onbottom.dem.experiment import initial_state, penetrate
    from onbottom.dem.preparation import prepare_sample
    from onbottom.dem.sample import Sample

__all__ = [
    "PRESETS",
    "SD",
    "SD_REDUCED",
    "SM",
    "SM_REDUCED",
    "ContactParameters",
    "ContactSet",
    "DEMConfig",
    "Geometry",
    "Loading",
    "Material",
    "Numerics",
    "ParticleSizeDistribution",
    "PipeState",
    "Preparation",
    "Sample",
    "Simulation",
    "Target",
    "critical_time_step",
    "get_preset",
    "initial_state",
    "penetrate",
    "prepare_sample",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.dem.config": (
            "PRESETS",
            "SD",
            "SD_REDUCED",
            "SM",
            "SM_REDUCED",
            "ContactParameters",
            "ContactSet",
            "DEMConfig",
            "Geometry",
            "Loading",
            "Material",
            "Numerics",
            "ParticleSizeDistribution",
            "Preparation",
            "Target",
            "get_preset",
        ),
        "onbottom.dem.engine": (
            "PipeState",
            "Simulation",
            "critical_time_step",
        ),
        "onbottom.dem.experiment": (
            "initial_state",
            "penetrate",
        ),
        "onbottom.dem.preparation": ("prepare_sample",),
        "onbottom.dem.sample": ("Sample",),
    },
)
