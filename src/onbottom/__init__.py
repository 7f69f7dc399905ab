"""onbottom — subsea pipeline–seabed interaction.

Pipe–soil resistance models (Verley & Sotberg sand with the Youssef & Cassidy calcareous
calibration, Verley & Lund clay, Coulomb friction), DNVGL-RP-F114 vertical penetration,
load-controlled pipe-section simulation, calibration, and a 2D DEM of pipe penetration.
All quantities are SI (m, s, N, N/m, Pa, rad) unless a name carries a unit suffix.

The model and solver names below are loaded lazily on first use, so ``import onbottom``
stays light (numba, scipy and xarray load only when a model is used).
"""

from __future__ import annotations

import importlib
from typing import Any

from onbottom._version import __version__
from onbottom.errors import InputError, OnbottomError, OutOfRangeWarning, SolutionError
from onbottom.inputs import Clay, Layer, Pipe, Rock, Sand

_LAZY: dict[str, str] = {
    "CoulombFriction": "onbottom.soil",
    "VerleyLund": "onbottom.soil",
    "VerleySotberg": "onbottom.soil",
    "lateral_model": "onbottom.soil",
    "penetration_curve": "onbottom.soil",
    "solve_embedment": "onbottom.soil",
    "LoadProgramme": "onbottom.dynamics",
    "inclined_cyclic": "onbottom.dynamics",
    "run_centrifuge_test": "onbottom.dynamics",
    "simulate_section": "onbottom.dynamics",
    "PipeBuildUp": "onbottom.inputs.pipe_buildup",
    "absolute_lateral_stability": "onbottom.checks",
    "design_concrete_thickness": "onbottom.checks.design",
    "significant_bed_velocity": "onbottom.hydro.design_sea_state",
    "SeaState": "onbottom.inputs.storm",
    "Storm": "onbottom.inputs.storm",
    "Current": "onbottom.inputs.storm",
    "simulate_storm_section": "onbottom.dynamics.storm_section",
    "run_storm_seeds": "onbottom.study.storm_seeds",
    "stability_curves": "onbottom.study.stability_curves",
}

__all__ = [
    "Clay",
    "InputError",
    "Layer",
    "OnbottomError",
    "OutOfRangeWarning",
    "Pipe",
    "Rock",
    "Sand",
    "SolutionError",
    "__version__",
    *sorted(_LAZY),
]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'onbottom' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
