"""onbottom.soil — pipe–soil resistance models.

Lateral (stateful, behind the kernel contract of :mod:`onbottom.soil.base`): Coulomb friction,
Verley & Sotberg sand (silica, calcareous, DNV-RP-F109 variant), Verley & Lund clay; the
two-DOF V–H force-resultant test model (second form of the contract).
Vertical: DNVGL-RP-F114 penetration resistance and the embedment solver. The backbone of
``onbottom backbone`` (:mod:`.backbone`) and the table and embedment of ``onbottom penetration``
(:mod:`.penetration_table`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from onbottom._lazy import attach

if TYPE_CHECKING:  # the same names, for type checkers, mkdocstrings and the layering test
    from onbottom.soil.backbone import backbone_run
    from onbottom.soil.coulomb import CoulombFriction
    from onbottom.soil.factory import lateral_model
    from onbottom.soil.penetration_f114 import (
        DrainedBounds,
        DrainedPenetration,
        UndrainedModel1,
        UndrainedModel2,
        lay_factor,
        penetration_curve,
        resistance_model,
        solve_embedment,
    )
    from onbottom.soil.penetration_table import penetration_run
    from onbottom.soil.response import path_response
    from onbottom.soil.verley_lund import VerleyLund
    from onbottom.soil.verley_sotberg import VerleySotberg
    from onbottom.soil.vh_parabolic import ParabolicVH

__all__ = [
    "CoulombFriction",
    "DrainedBounds",
    "DrainedPenetration",
    "ParabolicVH",
    "UndrainedModel1",
    "UndrainedModel2",
    "VerleyLund",
    "VerleySotberg",
    "backbone_run",
    "lateral_model",
    "lay_factor",
    "path_response",
    "penetration_curve",
    "penetration_run",
    "resistance_model",
    "solve_embedment",
]

__getattr__, __dir__ = attach(
    __name__,
    {
        "onbottom.soil.backbone": ("backbone_run",),
        "onbottom.soil.coulomb": ("CoulombFriction",),
        "onbottom.soil.factory": ("lateral_model",),
        "onbottom.soil.penetration_f114": (
            "DrainedBounds",
            "DrainedPenetration",
            "UndrainedModel1",
            "UndrainedModel2",
            "lay_factor",
            "penetration_curve",
            "resistance_model",
            "solve_embedment",
        ),
        "onbottom.soil.penetration_table": ("penetration_run",),
        "onbottom.soil.response": ("path_response",),
        "onbottom.soil.verley_lund": ("VerleyLund",),
        "onbottom.soil.verley_sotberg": ("VerleySotberg",),
        "onbottom.soil.vh_parabolic": ("ParabolicVH",),
    },
)
