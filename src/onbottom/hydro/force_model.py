"""Pluggable time-domain hydrodynamic force models of the storm section and the pipeline FE.

A force model is a frozen dataclass in front of a numba kernel. It tells the solvers' time loops
*which* force law to evaluate (an integer ``model_id``, the branch in
:func:`onbottom.hydro._force_dispatch.force_step`) and *with which parameters*: a float64 table
``parameter_table(K, M)`` of shape (n_stages, n_params), one row per storm stage from its
Keulegan–Carpenter number K and current ratio M (identical rows for a constant model). The
solvers turn it into rows per kinematics sample with :func:`parameter_rows` (blended with the
stage weights) and pass one row per evaluation, with the model's state slots (committed on
accepted steps). The kernel contract is written as numbered rules in
:mod:`onbottom.hydro._force_dispatch`; docs/contributing.md has the recipe for a new model.

:class:`MorisonLift` (``model_id`` 0, :mod:`onbottom.hydro._morison_kernel`) is the Morison form
with relative velocity used by CORUS-3D (Youssef & Cassidy 2014):

    F_Y = r_y · [ ½ ρ_w D C_D (U + V − ẏ)|U + V − ẏ| + ρ_w (π D²/4) C_M U̇ ]
    F_Z = r_z · ½ ρ_w D C_L (U + V)²        (or (U + V − ẏ)² with ``lift_relative_velocity``)

with the added mass ρ_w (π D²/4) C_a on the pipe's acceleration (left-hand side); the solver
applies the reductions r_y, r_z (:mod:`onbottom.hydro.reductions`).

Default coefficients: C_D = 0.7, C_L = 0.9, C_M = 3.29 (C_a = 2.29). C_M = 1 + C_a with
C_a = π²/3 − 1 is the potential-flow value for a cylinder on a plane wall (textbook, e.g.
Sarpkaya & Isaacson 1981); C_D = 0.7 and C_L = 0.9 are the constant values of common practice
for a pipe resting on the seabed (the former DNV RP-E305 (1988) simplified method) — they are
**not** DNV-RP-F109 prescriptions. F109 recommends
coefficients depending on K, M, roughness and embedment, or a wake model, for dynamic analysis;
supply them per sea state with :meth:`MorisonLift.per_sea_state`.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from onbottom._validate import non_negative
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro._force_contract import N_FORCE_STATE
from onbottom.hydro._force_dispatch import FORCE_MORISON
from onbottom.hydro._morison_kernel import N_PARAMS, P_CD, P_CL, P_CM, P_LIFT_REL

__all__ = [
    "FORCE_MODEL_MORISON_LIFT",
    "N_FORCE_STATE",
    "ForceModel",
    "MorisonLift",
    "parameter_rows",
]

FORCE_MODEL_MORISON_LIFT = FORCE_MORISON
"""Kernel branch of :class:`MorisonLift`."""

CoefficientRule = Callable[[float, float], tuple[float, float, float]]
"""(K, M) → (C_D, C_M, C_L) for one sea state."""


@runtime_checkable
class ForceModel(Protocol):
    """What the storm-section and pipeline solvers need from a hydrodynamic force model.

    The kernel contract (numbered rules) is in :mod:`onbottom.hydro._force_dispatch`.
    """

    name: str
    model_id: int

    @property
    def added_mass_coefficient(self) -> float:
        """C_a [-] of the added mass on the pipe's acceleration (the solver's mass side)."""
        ...

    def parameter_table(
        self, keulegan_carpenter: np.ndarray, current_ratio: np.ndarray
    ) -> np.ndarray:
        """Kernel parameters per storm stage: float64 array (n_stages, n_params) from each
        stage's K = U_s T_u / D [-] and M = |V| / U_s [-] (identical rows when constant)."""
        ...

    def describe(self) -> dict[str, Any]:
        """Provenance: name, parameters or rule, source (and "reconstruction" where relevant)."""
        ...


def parameter_rows(
    force_model: ForceModel,
    weights: np.ndarray,
    stage_parameters: Sequence[dict[str, float]],
    current: float,
    diameter: float,
) -> np.ndarray:
    """The solvers' parameter table: one row when constant, else one row per flow sample.

    K = U_s T_u / D and M = |V| / U_s of every stage (``stage_parameters``: significant
    velocity U_s [m/s] and mean period T_u [s] of each stage, as in
    :class:`~onbottom.hydro.storm_kinematics.StormKinematics`) give the stage rows of
    ``force_model.parameter_table``; during the build-up and the blends between stages the rows
    are blended with the normalised stage weights ``weights`` (n_stages, n_samples) — the same
    weights as the spectra. Without stages (flow not synthesised from sea states) a constant
    model gives its one row and a sea-state dependent one is an
    :class:`~onbottom.errors.InputError`. Returns a C-contiguous float64 array (1 or n_samples,
    n_params).
    """
    if len(stage_parameters) == 0:
        # flow given without sea states (regular waves, hand-made kinematics): only a model
        # whose parameters do not depend on K and M can run
        with warnings.catch_warnings():  # a probe, not a sea state: no range warnings
            warnings.simplefilter("ignore", OutOfRangeWarning)
            probe = np.asarray(
                force_model.parameter_table(np.array([5.0, 40.0]), np.array([0.0, 2.0])),
                dtype=float,
            )
        if probe.ndim != 2 or not np.all(np.isfinite(probe)) or not np.all(probe == probe[:1]):
            raise InputError(
                f"stage_parameters = [] is invalid for the sea-state dependent"
                f" {type(force_model).__name__}: the kinematics carry no stage (U_s, T_u) to"
                " give K and M; synthesise them from a Storm"
            )
        return np.ascontiguousarray(probe[:1])
    us = np.array([max(p["significant_velocity"], 1e-12) for p in stage_parameters])
    tu = np.array([p["mean_period"] for p in stage_parameters])
    table = np.asarray(
        force_model.parameter_table(us * tu / diameter, abs(current) / us), dtype=float
    )
    if table.ndim != 2 or table.shape[0] != us.size or not np.all(np.isfinite(table)):
        raise InputError(
            f"{type(force_model).__name__}.parameter_table is invalid: expected a finite"
            f" array ({us.size}, n_params), got shape {table.shape}"
        )
    if np.all(table == table[:1]):
        return np.ascontiguousarray(table[:1])
    w = np.asarray(weights, dtype=float)
    if w.ndim != 2 or w.shape[0] != us.size:
        raise InputError(f"weights of shape {w.shape} are invalid: expected ({us.size}, n_samples)")
    wsum = np.sum(w, axis=0)
    wn = np.where(wsum > 0.0, w / np.where(wsum > 0.0, wsum, 1.0), 1.0 / w.shape[0])
    return np.ascontiguousarray((np.ascontiguousarray(table.T) @ wn).T)


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
        if self.model_id != FORCE_MODEL_MORISON_LIFT:
            raise InputError(
                f"MorisonLift.model_id = {self.model_id!r} is invalid: must be"
                f" {FORCE_MODEL_MORISON_LIFT} (the Morison kernel)"
            )

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

    def parameter_table(
        self, keulegan_carpenter: np.ndarray, current_ratio: np.ndarray
    ) -> np.ndarray:
        """Array (n_stages, 4) of C_D, C_M, C_L [-] and the relative-velocity-lift flag for
        each stage's K and M (layout ``P_*`` of :mod:`onbottom.hydro._morison_kernel`)."""
        k = np.atleast_1d(np.asarray(keulegan_carpenter, dtype=float))
        m = np.atleast_1d(np.asarray(current_ratio, dtype=float))
        out = np.empty((k.size, N_PARAMS))
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
            out[j, P_CD], out[j, P_CM], out[j, P_CL] = c
            out[j, P_LIFT_REL] = 1.0 if self.lift_relative_velocity else 0.0
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
