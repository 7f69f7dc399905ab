"""onbottom.dem — 2D discrete-element model of a pipe pushed vertically into sand.

Depends only on the base modules (errors, constants, _validate, results); see
``docs/theory/dem.md``.
"""

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
