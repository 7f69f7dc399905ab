"""Parabolic V–H force-resultant model: the test model of the two-DOF soil contract.

A rigid-vertical, elastic–plastic-lateral force-resultant ("macro-element") model of a pipe
section, with the parabolic yield surface of the Zhang (2001) / Zhang, Stewart & Randolph
(2002) family at zero tension parameter (t = 0),

    f(V, H) = |H| − μ·V·(1 − V/V_p) = 0,

a non-associated flow rule from the plastic potential g = |H| − μ′·V·(1 − V/V_p) (μ′ <= μ;
μ′ = μ associated), and linear hardening of the vertical capacity with the vertical plastic
displacement, dV_p = k_p·dz_p. Lateral elasticity as in Coulomb friction
(:mod:`onbottom.soil.coulomb`): stiffness μV/δ. Derivation and the increment algorithm:
docs/theory/vh_parabolic.md; kernel contract: rules 2.1–2.7 of :mod:`onbottom.soil.base`.

Sources: Zhang, J., Stewart, D. P. & Randolph, M. F. (2002), "Modeling of shallowly embedded
offshore pipelines in calcareous sand", J. Geotech. Geoenviron. Eng. 128(5):363–371 (a
non-associated bounding-surface model whose bounding surface is of this parabolic family, with a
tension parameter t and hyperbolic hardening; calibrated on calcareous sand, shallow embedment
z/D <= 0.5, monotonic and cyclic V–H loading); the same surface is implemented by Tian &
Cassidy (2008), Int. J. Geomech. 8(4):213–229. This model keeps the surface, the form of the
flow rule and a hardening of V_p, and drops the bounding-surface interpolation and the tension
parameter: it is a *test model of the contract*, not a calibrated design model; no parameter
set of it is validated against tests.

With V_p = ∞ and μ′ = 0 the surface is |H| = μV and nothing moves vertically: the model is
Coulomb friction, bit for bit (contract rule 2.7).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from onbottom._validate import in_range, non_negative, positive
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.soil._dispatch import MODEL_VH_PARABOLIC
from onbottom.soil._vh_parabolic_kernel import (
    N_PARAMS,
    N_STATE,
    P_DELTA,
    P_KP,
    P_MU,
    P_MU_FLOW,
    S_VP,
    vh_parabolic_kernel,
    vh_parabolic_kernel_py,
)
from onbottom.soil.base import S_Z, ForceResultantModel

__all__ = ["ParabolicVH"]


@dataclass(frozen=True, kw_only=True)
class ParabolicVH(ForceResultantModel):
    """Parabolic V–H yield surface, non-associated flow, linear hardening of V_p.

    Parameters
    ----------
    friction_coefficient : float
        μ [-], in (0, 2]: slope of the yield surface at V = 0 (the Coulomb friction
        coefficient of the limit V_p → ∞).
    bearing_capacity : float
        V_p at the start [N/m], in (0, inf]: the vertical load the pipe carries at H = 0
        before it penetrates further (``math.inf``: no vertical failure, |H| = μV).
    flow_coefficient : float, optional
        μ′ [-], in [0, μ] (default μ: associated flow): vertical plastic displacement per unit
        lateral plastic slip is −μ′(1 − 2V/V_p) — heave below V_p/2, penetration above.
        μ′ <= μ keeps the plastic work >= 0. 0: no vertical plastic flow.
    hardening_stiffness : float
        k_p [N/m²], >= 0 (default 0): dV_p = k_p·dz. With k_p = 0 a vertical load above V_p
        has no equilibrium (the kernel returns NaN, the solvers stop).
    mobilisation_displacement : float
        δ [m], > 0 (default 1 mm): lateral elastic stiffness μV/δ (as Coulomb friction).
    initial_penetration : float
        z at the start [m], >= 0 (default 0).
    """

    name: ClassVar[str] = "vh_parabolic"
    reference: ClassVar[str] = (
        "Parabolic V–H surface of Zhang, Stewart & Randolph (2002), J. Geotech. Geoenviron."
        " Eng. 128(5):363–371 (t = 0, no bounding surface); test model of the two-DOF contract"
    )
    state_size: ClassVar[int] = N_STATE
    model_id: ClassVar[int] = MODEL_VH_PARABOLIC

    friction_coefficient: float
    bearing_capacity: float
    flow_coefficient: float | None = None
    hardening_stiffness: float = 0.0
    mobilisation_displacement: float = 1.0e-3
    initial_penetration: float = 0.0

    def __post_init__(self) -> None:
        mu = in_range(
            "ParabolicVH.friction_coefficient",
            self.friction_coefficient,
            0.0,
            2.0,
            low_inclusive=False,
        )
        in_range(
            "ParabolicVH.bearing_capacity",
            self.bearing_capacity,
            0.0,
            math.inf,
            low_inclusive=False,
        )
        if self.flow_coefficient is None:
            object.__setattr__(self, "flow_coefficient", mu)
        in_range("ParabolicVH.flow_coefficient", self.flow_coefficient, 0.0, mu)
        non_negative("ParabolicVH.hardening_stiffness", self.hardening_stiffness)
        positive("ParabolicVH.mobilisation_displacement", self.mobilisation_displacement)
        non_negative("ParabolicVH.initial_penetration", self.initial_penetration)

    @classmethod
    def from_seabed(cls, seabed: Sand | Clay | Rock, **kwargs: Any) -> ParabolicVH:
        """The model with μ = the seabed's friction coefficient (``bearing_capacity`` and the
        other parameters as keywords)."""
        return cls(friction_coefficient=seabed.friction_coefficient, **kwargs)

    @property
    def kernel(self):
        return vh_parabolic_kernel

    @property
    def python_kernel(self):
        return vh_parabolic_kernel_py

    def packed_parameters(self) -> np.ndarray:
        p = np.zeros(N_PARAMS)
        p[P_MU] = self.friction_coefficient
        p[P_MU_FLOW] = self.flow_coefficient
        p[P_DELTA] = self.mobilisation_displacement
        p[P_KP] = self.hardening_stiffness
        return p

    def initial_state(self) -> np.ndarray:
        s = np.zeros(self.state_size)
        s[S_Z] = self.initial_penetration
        s[S_VP] = self.bearing_capacity
        return s

    def parameters(self) -> Mapping[str, Any]:
        return {
            "friction_coefficient": self.friction_coefficient,
            "bearing_capacity": self.bearing_capacity,
            "flow_coefficient": self.flow_coefficient,
            "hardening_stiffness": self.hardening_stiffness,
            "mobilisation_displacement": self.mobilisation_displacement,
            "initial_penetration": self.initial_penetration,
        }
