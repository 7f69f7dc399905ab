"""onbottom — subsea pipeline–seabed interaction.

Pipe–soil resistance models (Verley & Sotberg sand with the Youssef & Cassidy calcareous
calibration, Verley & Lund clay, Coulomb friction), DNVGL-RP-F114 vertical penetration,
load-controlled pipe-section simulation, calibration, and a 2D DEM of pipe penetration.
All quantities are SI (m, s, N, N/m, Pa, rad) unless a name carries a unit suffix.
"""

from onbottom._version import __version__
from onbottom.errors import InputError, OnbottomError, OutOfRangeWarning, SolutionError
from onbottom.inputs import Clay, Layer, Pipe, Rock, Sand

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
]
