"""onbottom.hydro — wave spectra, seabed kinematics, current and Morison loads (pure numpy).

References: DNV-RP-F109 (2010, re-issued 2017) §3.3–3.4; DNV-RP-C205 (2010) §3.5.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.hydro.current import SEABED_ROUGHNESS, mean_current_over_pipe
    from onbottom.hydro.design_sea_state import design_oscillation, significant_bed_velocity
    from onbottom.hydro.flow_synthesis import (
        near_bed_velocity_series,
        random_phase_series,
        regular_velocity_series,
    )
    from onbottom.hydro.force_model import ForceModel, MorisonLift
    from onbottom.hydro.forces import MorisonCoefficients, horizontal_force, lift_force
    from onbottom.hydro.fourier import FourierModel
    from onbottom.hydro.fourier_table import FourierTable
    from onbottom.hydro.kinematics import (
        near_bed_velocity_spectrum,
        regular_wave_bed_velocity,
        seabed_transfer,
        significant_velocity,
        wave_number,
        zero_upcrossing_period,
    )
    from onbottom.hydro.reductions import LoadReductions
    from onbottom.hydro.registry import FORCE_MODELS, build_force_model
    from onbottom.hydro.spectra import (
        jonswap,
        jonswap_peak_enhancement,
        pierson_moskowitz,
        spectral_moment,
    )
    from onbottom.hydro.wake import WakeModel

__all__ = [
    "FORCE_MODELS",
    "SEABED_ROUGHNESS",
    "ForceModel",
    "FourierModel",
    "FourierTable",
    "LoadReductions",
    "MorisonCoefficients",
    "MorisonLift",
    "WakeModel",
    "build_force_model",
    "design_oscillation",
    "horizontal_force",
    "jonswap",
    "jonswap_peak_enhancement",
    "lift_force",
    "mean_current_over_pipe",
    "near_bed_velocity_series",
    "near_bed_velocity_spectrum",
    "pierson_moskowitz",
    "random_phase_series",
    "regular_velocity_series",
    "regular_wave_bed_velocity",
    "seabed_transfer",
    "significant_bed_velocity",
    "significant_velocity",
    "spectral_moment",
    "wave_number",
    "zero_upcrossing_period",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.hydro.current": (
            "SEABED_ROUGHNESS",
            "mean_current_over_pipe",
        ),
        "onbottom.hydro.design_sea_state": (
            "design_oscillation",
            "significant_bed_velocity",
        ),
        "onbottom.hydro.force_model": ("ForceModel", "MorisonLift"),
        "onbottom.hydro.fourier": ("FourierModel",),
        "onbottom.hydro.fourier_table": ("FourierTable",),
        "onbottom.hydro.reductions": ("LoadReductions",),
        "onbottom.hydro.registry": ("FORCE_MODELS", "build_force_model"),
        "onbottom.hydro.wake": ("WakeModel",),
        "onbottom.hydro.forces": (
            "MorisonCoefficients",
            "horizontal_force",
            "lift_force",
        ),
        "onbottom.hydro.kinematics": (
            "near_bed_velocity_spectrum",
            "regular_wave_bed_velocity",
            "seabed_transfer",
            "significant_velocity",
            "wave_number",
            "zero_upcrossing_period",
        ),
        "onbottom.hydro.spectra": (
            "jonswap",
            "jonswap_peak_enhancement",
            "pierson_moskowitz",
            "spectral_moment",
        ),
        "onbottom.hydro.flow_synthesis": (
            "near_bed_velocity_series",
            "random_phase_series",
            "regular_velocity_series",
        ),
    },
)
