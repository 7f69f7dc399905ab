"""Pluggable time-domain hydrodynamic force models for the storm solvers.

A force model tells the numba time loop *which* force law to evaluate (an integer
``model_id``, the branch in :func:`onbottom.dynamics._storm_kernel.hydro_forces`) and *with which
coefficients*, as a float64 array ``coefficients[k, j]`` (row k = coefficient, column j = time
sample of the storm, or a single column when constant). A wake model or a Fourier-expansion
model (PRCI Level 3) can be added later as a new class with a new ``model_id`` and a new kernel
branch, without touching the solvers.

:class:`MorisonLift` (``model_id`` 0) is the Morison form with relative velocity used by
CORUS-3D (Youssef & Cassidy 2014) and written in ``shared/spec/on-bottom-stability.md``:

    F_Y = r_y · [ ½ ρ_w D C_D (U + V − ẏ)|U + V − ẏ| + ρ_w (π D²/4) C_M U̇ ]
    F_Z = r_z · ½ ρ_w D C_L (U + V)²        (or (U + V − ẏ)² with ``lift_relative_velocity``)

with the added mass ρ_w (π D²/4) C_a on the pipe's acceleration (left-hand side).

Default coefficients: C_D = 0.7, C_L = 0.9, C_M = 3.29 (C_a = 2.29). C_M = 1 + C_a with
C_a = π²/3 − 1 is the potential-flow value for a cylinder on a plane wall (textbook, e.g.
Sarpkaya & Isaacson 1981); C_D = 0.7 and C_L = 0.9 are the constant values of common practice
for a pipe resting on the seabed (the former DNV RP-E305 (1988) simplified method) — they are
**not** DNV-RP-F109 prescriptions (``shared/spec/dnv-reference.md`` §2.2, [B]). F109 recommends
coefficients depending on K, M, roughness and embedment, or a wake model, for dynamic analysis;
supply them per sea state with :meth:`MorisonLift.per_sea_state`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from onbottom._validate import non_negative
from onbottom.errors import InputError

__all__ = [
    "COEF_CD",
    "COEF_CL",
    "COEF_CM",
    "FORCE_MODEL_MORISON_LIFT",
    "ForceModel",
    "MorisonLift",
]

FORCE_MODEL_MORISON_LIFT = 0
"""Kernel branch of :class:`MorisonLift`."""

COEF_CD = 0
COEF_CM = 1
COEF_CL = 2
N_COEF = 3

CoefficientRule = Callable[[float, float], tuple[float, float, float]]
"""(K, M) → (C_D, C_M, C_L) for one sea state."""


@runtime_checkable
class ForceModel(Protocol):
    """What a storm solver needs from a hydrodynamic force model."""

    name: str
    model_id: int

    def coefficient_table(
        self, keulegan_carpenter: np.ndarray, current_ratio: np.ndarray
    ) -> np.ndarray:
        """Coefficients per sea state: array (N_COEF, n_stages) from each stage's K and M."""
        ...

    @property
    def added_mass_coefficient(self) -> float:
        """C_a [-] of the added mass on the pipe's acceleration."""
        ...

    @property
    def lift_relative_velocity(self) -> bool:
        """Whether lift uses the relative velocity U + V − ẏ."""
        ...

    def describe(self) -> dict[str, Any]:
        """Provenance: name, coefficients or rule, source."""
        ...


@dataclass(frozen=True, kw_only=True)
class MorisonLift:
    """Morison drag + inertia with relative velocity, and lift (see the module docstring).

    Parameters
    ----------
    cd : float
        Drag coefficient C_D [-], in [0, 10]; default 0.7 (common practice, not F109).
    cm : float
        Inertia coefficient C_M [-], in [0, 10]; default 3.29 (cylinder on a plane wall).
    cl : float
        Lift coefficient C_L [-], in [0, 10]; default 0.9 (common practice, not F109).
    added_mass : float or None
        Added-mass coefficient C_a [-], >= 0; None → C_M − 1 (potential flow).
    lift_relative_velocity : bool
        Lift from (U + V − ẏ)² instead of (U + V)² (spec: an option; default off).
    rule : callable or None
        (K, M) → (C_D, C_M, C_L) per sea state (see :meth:`per_sea_state`); None = constant.
    """

    cd: float = 0.7
    cm: float = 3.29
    cl: float = 0.9
    added_mass: float | None = None
    lift_relative_velocity: bool = False
    rule: CoefficientRule | None = field(default=None, compare=False)
    name: str = "morison_lift"
    model_id: int = FORCE_MODEL_MORISON_LIFT

    def __post_init__(self) -> None:
        for key in ("cd", "cm", "cl"):
            v = non_negative(f"MorisonLift.{key}", getattr(self, key))
            if v > 10.0:
                raise InputError(f"MorisonLift.{key} = {v!r} is invalid: must lie in [0, 10]")
        if self.added_mass is not None:
            non_negative("MorisonLift.added_mass", self.added_mass)
        elif self.cm < 1.0:
            raise InputError(
                f"MorisonLift.cm = {self.cm!r} is invalid without added_mass: C_a = C_M − 1"
                " must be >= 0"
            )
        if self.rule is not None and not callable(self.rule):
            raise InputError(f"MorisonLift.rule = {self.rule!r} is invalid: expected callable")

    @classmethod
    def per_sea_state(
        cls, rule: CoefficientRule, *, added_mass: float = 2.29, **kwargs: Any
    ) -> MorisonLift:
        """Coefficients chosen per sea state by ``rule(K, M) -> (C_D, C_M, C_L)``.

        K = U_s T_u / D and M = V / U_s of each stage (DNV-RP-F109 §3.5 groups). During a
        blend between stages (and the build-up), the coefficients are blended with the same
        weights as the spectra.
        """
        return cls(rule=rule, added_mass=added_mass, **kwargs)

    @property
    def added_mass_coefficient(self) -> float:
        """C_a [-]."""
        return float(self.added_mass) if self.added_mass is not None else self.cm - 1.0

    def coefficient_table(
        self, keulegan_carpenter: np.ndarray, current_ratio: np.ndarray
    ) -> np.ndarray:
        """Array (3, n_stages) of C_D, C_M, C_L for each stage's K and M."""
        k = np.atleast_1d(np.asarray(keulegan_carpenter, dtype=float))
        m = np.atleast_1d(np.asarray(current_ratio, dtype=float))
        out = np.empty((N_COEF, k.size))
        for j in range(k.size):
            if self.rule is None:
                c = (self.cd, self.cm, self.cl)
            else:
                c = tuple(float(x) for x in self.rule(float(k[j]), float(m[j])))
                if len(c) != 3 or not all(math.isfinite(x) and 0.0 <= x <= 10.0 for x in c):
                    raise InputError(
                        f"MorisonLift.rule(K={k[j]:.4g}, M={m[j]:.4g}) = {c!r} is invalid:"
                        " expected three coefficients (C_D, C_M, C_L) in [0, 10]"
                    )
            out[COEF_CD, j], out[COEF_CM, j], out[COEF_CL, j] = c
        return out

    def describe(self) -> dict[str, Any]:
        """Provenance attributes."""
        d: dict[str, Any] = {
            "force_model": self.name,
            "added_mass_coefficient": self.added_mass_coefficient,
            "lift_relative_velocity": int(self.lift_relative_velocity),
            "force_model_source": (
                "Morison with relative velocity (CORUS-3D, Youssef & Cassidy 2014); defaults"
                " C_D=0.7, C_L=0.9 common practice (former DNV RP-E305), C_M=3.29 potential"
                " flow on a plane wall; not DNV-RP-F109 prescriptions"
            ),
        }
        if self.rule is None:
            d.update(cd=self.cd, cm=self.cm, cl=self.cl)
        else:
            d["coefficient_rule"] = getattr(self.rule, "__name__", repr(self.rule))
        return d
