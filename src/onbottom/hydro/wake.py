"""Wake force model: flow-history drag and lift on a pipe on the seabed (a reconstruction).

The wake model of Lambrakos, Chao, Beckmann & Brannon (1987), "Wake model of hydrodynamic
forces on pipelines", Ocean Eng. 14(2):117–136, and its "Wake II" refinement (Soedigdo,
Lambrakos & Edge 1999, Ocean Eng. 26:431–462; Sabag, Edge & Soedigdo 2000, Ocean Eng.
27:1295–1319) add to Morison's force the pipe's encounter with its own wake when the flow
reverses, and let the drag and lift coefficients vary in time after a reversal. Only the
structure of those models is public; the licensed programs' empirical parameters are not.
:class:`WakeModel` is a **reconstruction of that published structure**, with its constants
calibrated by this project against DNV-RP-F109's peak-load coefficients C*_Y, C*_Z
(Tables 3-9/3-10), which F109 derived with a wake-type model. It is not the licensed model.

Equations, symbols, defaults and the calibration: ``docs/theory/wake_model.md`` and
``docs/validation/wake_calibration.md``; kernel: :mod:`onbottom.hydro._wake_kernel`.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import in_range
from onbottom.errors import InputError
from onbottom.hydro import _wake_kernel as wk

__all__ = ["FORCE_WAKE", "WakeModel"]

FORCE_WAKE = 1
"""Kernel id of :class:`WakeModel` in ``onbottom.hydro._force_dispatch.force_step``."""

_SOURCE = (
    "Reconstruction of the public structure of the wake model (Lambrakos et al. 1987, Ocean"
    " Eng. 14(2):117-136; Wake II: Soedigdo, Lambrakos & Edge 1999, Ocean Eng. 26:431-462;"
    " Sabag, Edge & Soedigdo 2000, Ocean Eng. 27:1295-1319); constants fitted by onbottom to"
    " the peak-load coefficients C*_Y, C*_Z of DNV-RP-F109 (2017) Tables 3-9/3-10"
    " (docs/validation/wake_calibration.md); not the licensed coefficients"
)


@dataclass(frozen=True, kw_only=True)
class WakeModel:
    """Wake force model (reconstruction; see the module docstring and docs/theory/wake_model.md).

    Distances are in pipe diameters; s is the distance the total flow U + V has travelled since
    its last reversal.

    Parameters
    ----------
    cd_steady : float
        C_D∞ [-], drag coefficient far from a reversal, in [0, 5]. Default 1.0: F109's
        steady-current row (M* = 10: C*_Y = 1.00); fixed, not fitted.
    cl_steady : float
        C_L∞ [-], lift coefficient far from a reversal, in [0, 5]. Default 0.9: F109's
        steady-current row (M* = 10: C*_Z = 0.90); fixed, not fitted.
    cm : float
        C_M [-], inertia coefficient on the ambient acceleration, in [0, 10]. Default 3.29:
        potential flow on a plane wall, 1 + (π²/3 − 1); also F109's inertia-dominated column
        (C*_Y(K* = 2.5, M* = 0) = 13.0 = π² C_M / 2.5); fixed, not fitted.
    drag_excess : float
        ΔC_D [-], excess of C_D at a reversal, in [-C_D∞, 20]. Default: fitted (see below).
    lift_excess : float
        ΔC_L [-], excess of C_L at a reversal, in [-C_L∞, 20]. Default: fitted.
    drag_relaxation : float
        λ_D [-], distance (in D) over which C_D relaxes by a factor e, in (0, 1000]. Fitted.
    lift_relaxation : float
        λ_L [-], distance (in D) over which C_L relaxes by a factor e, in (0, 1000]. Fitted.
    wake_ratio : float
        α_w [-], wake velocity at a reversal divided by the peak |U + V| of the half-cycle
        that made the wake, in [0, 2]. Fitted.
    wake_decay : float
        λ_w [-], distance (in D) over which the wake velocity decays by a factor e, in
        (0, 1000]. Fitted.
    added_mass : float or None
        C_a [-] on the pipe's own acceleration (solver's mass side), >= 0; None → C_M − 1.
    lift_relative_velocity : bool
        Lift from (U_e − ẏ)² instead of U_e² (default off, as the Morison lift).
    wake : bool
        False turns the wake velocity and the coefficient relaxation off (α_w, ΔC_D, ΔC_L
        taken as 0): the model is then Morison with C_D∞, C_M, C_L∞, bit for bit.
    reversal_tolerance : float
        A sign change of U + V counts as a reversal only when |U + V| exceeds this fraction
        of the half-cycle's running peak [-], in [0, 0.1]; default 1e-9 (round-off guard).
    slack_exponent : float
        β [-], exponent of the strength g = ((r − r_0)/(1 − r_0))^β of a *slack* (a local
        minimum of |U + V| without a reversal, depth r = 1 − min/peak), in [0, 20]. Fitted.
    slack_threshold : float
        r_0 [-], slack depth below which a slack makes no wake, in [0, 0.9]. Default 0.2: a
        regular flow with a following current M = V/U has slacks of depth 2/(1 + M), so the
        wake is gone for M >= 9 (F109's M* = 10 row is steady flow); fixed, not fitted.
    wake_onset : float
        λ_o [-], distance (in D) over which a new wake and coefficient excess replace the old
        ones after an event (C¹ smoothstep), in [0, 10]; 0 gives a step. Default 0.3: short
        against the smallest tabulated stroke (K* = 2.5: 0.8 D), long enough that the solver
        does not reject steps at every reversal; fixed, not fitted.

    Defaults of ΔC_D, ΔC_L, λ_D, λ_L, α_w, λ_w: least-squares fit of the regular-flow
    protocol of :mod:`onbottom.hydro.wake_calibration` to F109 Tables 3-9/3-10 over the whole
    K*, M* grid (``tools/calibrate_wake.py``; table, RMS and worst cell in
    ``docs/validation/wake_calibration.md``).
    """

    cd_steady: float = 1.0
    cl_steady: float = 0.9
    cm: float = 3.29
    # fitted by tools/calibrate_wake.py to DNV-RP-F109 (2017) Tables 3-9/3-10 (regular
    # protocol, 4 cycles of 400 steps, 242 cells): RMS ln(model/F109) 0.1011, worst cell
    # C*_Z(K* 2.5, M* 0.8) x1.531; docs/validation/wake_calibration.md
    drag_excess: float = 0.6279
    lift_excess: float = 1.927
    drag_relaxation: float = 9.279
    lift_relaxation: float = 3.829
    wake_ratio: float = 0.354
    wake_decay: float = 9.470
    added_mass: float | None = None
    lift_relative_velocity: bool = False
    wake: bool = True
    reversal_tolerance: float = 1.0e-9
    slack_exponent: float = 1.458
    slack_threshold: float = 0.2
    wake_onset: float = 0.3
    name: str = "wake"
    model_id: int = FORCE_WAKE

    def __post_init__(self) -> None:
        in_range("WakeModel.cd_steady", self.cd_steady, 0.0, 5.0)
        in_range("WakeModel.cl_steady", self.cl_steady, 0.0, 5.0)
        in_range("WakeModel.cm", self.cm, 0.0, 10.0)
        in_range("WakeModel.drag_excess", self.drag_excess, -self.cd_steady, 20.0)
        in_range("WakeModel.lift_excess", self.lift_excess, -self.cl_steady, 20.0)
        for key in ("drag_relaxation", "lift_relaxation", "wake_decay"):
            in_range(f"WakeModel.{key}", getattr(self, key), 0.0, 1000.0, low_inclusive=False)
        in_range("WakeModel.wake_ratio", self.wake_ratio, 0.0, 2.0)
        in_range("WakeModel.reversal_tolerance", self.reversal_tolerance, 0.0, 0.1)
        in_range("WakeModel.slack_exponent", self.slack_exponent, 0.0, 20.0)
        in_range("WakeModel.slack_threshold", self.slack_threshold, 0.0, 0.9)
        in_range("WakeModel.wake_onset", self.wake_onset, 0.0, 10.0)
        if self.added_mass is not None:
            in_range("WakeModel.added_mass", self.added_mass, 0.0, 10.0)
        elif self.cm < 1.0:
            raise InputError(
                f"WakeModel.cm = {self.cm!r} is invalid without added_mass: C_a = C_M − 1"
                " must be >= 0"
            )
        for key in ("lift_relative_velocity", "wake"):
            if not isinstance(getattr(self, key), bool):
                raise InputError(
                    f"WakeModel.{key} = {getattr(self, key)!r} is invalid: expected a bool"
                )
        if self.name != "wake" or self.model_id != FORCE_WAKE:
            raise InputError(
                f"WakeModel.name/model_id = {self.name!r}/{self.model_id!r} is invalid:"
                f" must be 'wake'/{FORCE_WAKE}"
            )

    def without_wake(self) -> WakeModel:
        """The same model with the wake velocity and the coefficient relaxation off."""
        return dataclasses.replace(self, wake=False)

    @property
    def added_mass_coefficient(self) -> float:
        """C_a [-] of the added mass on the pipe's acceleration (C_M − 1 unless given)."""
        return float(self.added_mass) if self.added_mass is not None else self.cm - 1.0

    def parameters(self) -> NDArray:
        """The kernel's parameter row (layout ``P_*`` of :mod:`onbottom.hydro._wake_kernel`)."""
        p = np.zeros(wk.N_PARAMS)
        on = 1.0 if self.wake else 0.0
        p[wk.P_CD_STEADY] = self.cd_steady
        p[wk.P_CL_STEADY] = self.cl_steady
        p[wk.P_CM] = self.cm
        p[wk.P_DCD] = on * self.drag_excess
        p[wk.P_DCL] = on * self.lift_excess
        p[wk.P_LAMBDA_D] = self.drag_relaxation
        p[wk.P_LAMBDA_L] = self.lift_relaxation
        p[wk.P_WAKE_RATIO] = on * self.wake_ratio
        p[wk.P_LAMBDA_W] = self.wake_decay
        p[wk.P_LIFT_RELATIVE] = 1.0 if self.lift_relative_velocity else 0.0
        p[wk.P_REVERSAL_TOL] = self.reversal_tolerance
        p[wk.P_SLACK_EXPONENT] = self.slack_exponent
        p[wk.P_SLACK_THRESHOLD] = self.slack_threshold
        p[wk.P_ONSET] = self.wake_onset
        return p

    def parameter_table(self, keulegan_carpenter: ArrayLike, current_ratio: ArrayLike) -> NDArray:
        """Array (n_stages, N_PARAMS): one identical row per stage (constants, no K, M rule).

        The model's K- and M-dependence comes from its history (distance since reversal,
        previous half-cycle), not from the stage's K, M; those only set the number of rows and
        are checked for sign (K >= 0, M >= 0, not NaN; a calm stage's K = 0 or M = inf is
        accepted, as for a constant Morison model).
        """
        k = np.atleast_1d(np.asarray(keulegan_carpenter, dtype=float))
        m = np.atleast_1d(np.asarray(current_ratio, dtype=float))
        if k.shape != m.shape or k.ndim != 1:
            raise InputError(
                f"WakeModel.parameter_table: K shape {k.shape} and M shape {m.shape} are"
                " invalid: expected two 1-D arrays of the same length"
            )
        if np.any(np.isnan(k) | (k < 0.0)):
            raise InputError(f"keulegan_carpenter = {k!r} is invalid: must be >= 0")
        if np.any(np.isnan(m) | (m < 0.0)):
            raise InputError(f"current_ratio = {m!r} is invalid: must be >= 0")
        return np.tile(self.parameters(), (k.size, 1))

    def describe(self) -> dict[str, Any]:
        """Provenance attributes (flat, NetCDF-friendly)."""
        return {
            "force_model": self.name,
            "force_model_id": self.model_id,
            "reconstruction": 1,
            "wake": int(self.wake),
            "cd_steady": self.cd_steady,
            "cl_steady": self.cl_steady,
            "cm": self.cm,
            "drag_excess": self.drag_excess,
            "lift_excess": self.lift_excess,
            "drag_relaxation_diameters": self.drag_relaxation,
            "lift_relaxation_diameters": self.lift_relaxation,
            "wake_ratio": self.wake_ratio,
            "wake_decay_diameters": self.wake_decay,
            "added_mass_coefficient": self.added_mass_coefficient,
            "lift_relative_velocity": int(self.lift_relative_velocity),
            "reversal_tolerance": self.reversal_tolerance,
            "slack_exponent": self.slack_exponent,
            "slack_threshold": self.slack_threshold,
            "wake_onset_diameters": self.wake_onset,
            "force_model_source": _SOURCE,
        }
