"""Coulomb friction resistance (rock seabed, or friction-only analyses).

R = μ·V once mobilised (DNV-RP-F109 §3.4.6: rock has no passive resistance and no
penetration). Rigid-plastic friction is integrated as elastic–perfectly-plastic with a small
mobilisation displacement δ (return mapping), so a sub-critical load |H| < μV produces a
bounded elastic displacement |y| <= δ and never creep.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from onbottom._validate import in_range, positive
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.soil._coulomb_kernel import P_DELTA, P_MU, coulomb_kernel, coulomb_kernel_py
from onbottom.soil._dispatch import MODEL_COULOMB
from onbottom.soil.base import N_COMMON_STATE, LateralResistanceModel

__all__ = ["CoulombFriction"]


@dataclass(frozen=True, kw_only=True)
class CoulombFriction(LateralResistanceModel):
    """Pure Coulomb friction.

    Parameters
    ----------
    friction_coefficient : float
        μ [-], in (0, 2].
    mobilisation_displacement : float
        δ [m], > 0: displacement from rest at which μV is fully mobilised. Keep it small
        compared with the motions of interest (default 1 mm).
    """

    name: ClassVar[str] = "coulomb"
    reference: ClassVar[str] = "Coulomb friction; DNV-RP-F109 (2010/2017) §3.4.6 for rock"
    state_size: ClassVar[int] = N_COMMON_STATE
    model_id: ClassVar[int] = MODEL_COULOMB

    friction_coefficient: float
    mobilisation_displacement: float = 1.0e-3

    def __post_init__(self) -> None:
        in_range(
            "CoulombFriction.friction_coefficient",
            self.friction_coefficient,
            0.0,
            2.0,
            low_inclusive=False,
        )
        positive("CoulombFriction.mobilisation_displacement", self.mobilisation_displacement)

    @classmethod
    def from_seabed(cls, seabed: Sand | Clay | Rock, **kwargs: Any) -> CoulombFriction:
        """Friction-only model using the seabed's friction coefficient."""
        return cls(friction_coefficient=seabed.friction_coefficient, **kwargs)

    @property
    def kernel(self):
        return coulomb_kernel

    @property
    def python_kernel(self):
        return coulomb_kernel_py

    def packed_parameters(self) -> np.ndarray:
        p = np.zeros(2)
        p[P_MU] = self.friction_coefficient
        p[P_DELTA] = self.mobilisation_displacement
        return p

    def initial_state(self) -> np.ndarray:
        return np.zeros(self.state_size)

    def parameters(self) -> Mapping[str, Any]:
        return {
            "friction_coefficient": self.friction_coefficient,
            "mobilisation_displacement": self.mobilisation_displacement,
        }
