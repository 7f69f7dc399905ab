"""Build a lateral pipe–soil resistance model by name (through :mod:`onbottom.soil.registry`).

The names are those of :data:`onbottom.soil.registry.SOIL_MODELS` (the one list).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.soil.base import LateralResistanceModel
from onbottom.soil.registry import SOIL_MODELS, build_soil_model

__all__ = ["LATERAL_MODELS", "lateral_model"]


class _SeabedsView(Mapping[str, tuple[type, ...]]):
    """Live view of :data:`SOIL_MODELS`: name → the seabed types the model accepts."""

    def __getitem__(self, name: str) -> tuple[type, ...]:
        return SOIL_MODELS[name].seabeds

    def __iter__(self) -> Iterator[str]:
        return iter(SOIL_MODELS.names())

    def __len__(self) -> int:
        return len(SOIL_MODELS.names())


LATERAL_MODELS: Mapping[str, tuple[type, ...]] = _SeabedsView()
"""Model names and the seabed types each accepts (a live view of
:data:`.registry.SOIL_MODELS`, the one list: a model registered later is in it)."""


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
