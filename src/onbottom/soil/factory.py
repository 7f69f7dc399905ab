"""Build a lateral pipe–soil resistance model by name.

Names: "coulomb" (any seabed; rock: friction only, DNV-RP-F109 §3.4.6),
"verley_sotberg_silica", "verley_sotberg_calcareous", "verley_sotberg_f109" (sand) and
"verley_lund" (clay); "vh_parabolic" (any seabed: the two-DOF V–H test model of
:mod:`onbottom.soil.vh_parabolic`, μ from the seabed; ``bearing_capacity`` required).
"""

from __future__ import annotations

from typing import Any

from onbottom._validate import one_of
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.soil.base import LateralResistanceModel
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.verley_lund import VerleyLund
from onbottom.soil.verley_sotberg import VerleySotberg
from onbottom.soil.vh_parabolic import ParabolicVH

__all__ = ["LATERAL_MODELS", "lateral_model"]

LATERAL_MODELS: dict[str, tuple[type, ...]] = {
    "coulomb": (Sand, Clay, Rock),
    "verley_sotberg_silica": (Sand,),
    "verley_sotberg_calcareous": (Sand,),
    "verley_sotberg_f109": (Sand,),
    "verley_lund": (Clay,),
    "vh_parabolic": (Sand, Clay, Rock),
}
"""Model names and the seabed types each accepts."""


def lateral_model(
    name: str, pipe: Pipe, seabed: Sand | Clay | Rock, **options: Any
) -> LateralResistanceModel:
    """Lateral resistance model ``name`` for ``pipe`` on ``seabed``.

    Parameters
    ----------
    name : str
        One of :data:`LATERAL_MODELS`.
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
        Unknown name, or a seabed type the model does not accept.
    """
    one_of("lateral_model.name", name, LATERAL_MODELS)
    allowed = LATERAL_MODELS[name]
    if not isinstance(seabed, allowed):
        kinds = ", ".join(t.__name__ for t in allowed)
        raise InputError(
            f"lateral_model.seabed = {type(seabed).__name__} is invalid for model {name!r}:"
            f" must be one of {kinds}"
        )
    if name == "coulomb":
        return CoulombFriction.from_seabed(seabed, **options)
    if name == "verley_sotberg_silica":
        return VerleySotberg.silica(pipe, seabed, **options)
    if name == "verley_sotberg_calcareous":
        return VerleySotberg.calcareous(pipe, seabed, **options)
    if name == "vh_parabolic":
        if "bearing_capacity" not in options:
            raise InputError(
                "lateral_model.bearing_capacity is missing: model 'vh_parabolic' needs the"
                " vertical capacity V_p [N/m], in (0, inf]"
            )
        return ParabolicVH.from_seabed(seabed, **options)
    if name == "verley_sotberg_f109":
        return VerleySotberg.f109(pipe, seabed, **options)
    return VerleyLund.from_seabed(pipe, seabed, **options)
