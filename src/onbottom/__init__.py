"""onbottom — subsea pipeline–seabed interaction.

Pipe–soil resistance models (Verley & Sotberg sand with the Youssef & Cassidy calcareous
calibration, Verley & Lund clay, Coulomb friction), DNVGL-RP-F114 vertical penetration,
load-controlled pipe-section simulation, calibration, and a 2D DEM of pipe penetration.
All quantities are SI (m, s, N, N/m, Pa, rad) unless a name carries a unit suffix.

The model and solver names below are loaded lazily on first use, so ``import onbottom``
stays light (numba, scipy and xarray load only when a model is used).
"""

from __future__ import annotations

from onbottom._lazy import attach
from onbottom._version import __version__
from onbottom.errors import InputError, OnbottomError, OutOfRangeWarning, SolutionError
from onbottom.inputs import Clay, Layer, Pipe, Rock, Sand

_EXPORTS: dict[str, tuple[str, ...]] = {
    "onbottom.soil": (
        "CoulombFriction",
        "VerleyLund",
        "VerleySotberg",
        "lateral_model",
        "penetration_curve",
        "solve_embedment",
    ),
    "onbottom.dynamics": (
        "LoadProgramme",
        "inclined_cyclic",
        "run_centrifuge_test",
        "simulate_section",
    ),
    "onbottom.inputs.pipe_buildup": ("PipeBuildUp",),
    "onbottom.checks": ("absolute_lateral_stability",),
    "onbottom.checks.design": ("design_concrete_thickness",),
    "onbottom.hydro.design_sea_state": ("significant_bed_velocity",),
    "onbottom.inputs.storm": (
        "SeaState",
        "Storm",
        "Current",
    ),
    "onbottom.dynamics.storm_section": ("simulate_storm_section",),
    "onbottom.study.storm_seeds": ("run_storm_seeds",),
    "onbottom.study.stability_curves": ("stability_curves",),
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
    *sorted(name for names in _EXPORTS.values() for name in names),
]


__getattr__, __dir__ = attach(__name__, _EXPORTS)
