"""Build a lateral pipe–soil resistance model by name (through :mod:`onbottom.soil.registry`).

Names: "coulomb" (any seabed; rock: friction only, DNV-RP-F109 §3.4.6),
"verley_sotberg_silica", "verley_sotberg_calcareous", "verley_sotberg_f109" (sand) and
"verley_lund" (clay).
"""

from __future__ import annotations

from typing import Any

from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.soil.base import LateralResistanceModel
from onbottom.soil.registry import SOIL_MODELS, build_soil_model

__all__ = ["LATERAL_MODELS", "lateral_model"]

LATERAL_MODELS: dict[str, tuple[type, ...]] = {
    name: entry.seabeds for name, entry in SOIL_MODELS.items()
}
"""Model names and the seabed types each accepts (a view of :data:`.registry.SOIL_MODELS` at
import; the registry is the one list)."""


def lateral_model(
    name: str, pipe: Pipe, seabed: Sand | Clay | Rock, **options: Any
) -> LateralResistanceModel:
    """Lateral resistance model ``name`` for ``pipe`` on ``seabed``.

    Parameters
    ----------
    name : str
        A registered soil model (:data:`onbottom.soil.registry.SOIL_MODELS`).
    pipe : Pipe
        Pipe section (D, W_s).
    seabed : Sand, Clay or Rock
        Seabed; must suit the model (sand for Verley & Sotberg, clay for Verley & Lund).
    **options
        Passed to the model constructor (e.g. ``installation_load``, ``A``, ``passive_law``,
        ``penetration_form``, ``mobilisation_displacement``).

    Raises
    ------
    InputError
        Unknown name (the choices listed), or a seabed type the model does not accept.
    """
    return build_soil_model(name, pipe, seabed, where="lateral_model.name", **options)
