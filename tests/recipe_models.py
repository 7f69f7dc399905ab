"""Two models added as docs/contributing.md says, each with its own numba kernel, in this one
file: a soil model (``adhesive_coulomb``) and a force model (``quadratic_drag``).

Importing the module registers both (``register_soil_model(..., kernel=...)``,
``register_force_model(..., kernel=...)``): no source file of the package is edited, and the
solvers that take a literal model id call these kernels directly. The conformance suites
(``tests/conformance``) import it, so the two models also run every conformance test.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from onbottom._jit import njit, pure_python
from onbottom._validate import in_range, positive
from onbottom.hydro.kernel_contract import FO_DFY_DYD, FO_DFZ_DYD, FO_FY, FO_FZ
from onbottom.hydro.registry import register_force_model
from onbottom.soil.base import (
    N_COMMON_STATE,
    OUT_DISSIPATED,
    OUT_FRICTION,
    OUT_R,
    OUT_STORED,
    OUT_TANGENT,
    OUT_WORK,
    S_FRICTION,
    S_SOIL_WORK,
    S_WORK,
    S_Y,
    LateralResistanceModel,
)
from onbottom.soil.registry import SOIL_MODELS, register_soil_model

# ---- soil: Coulomb friction plus a constant adhesion a, R = μV + a once mobilised ------------
P_MU, P_ADHESION, P_DELTA = 0, 1, 2


@njit(cache=True)
def adhesive_coulomb_kernel(params, state_old, y_new, v_load, state_new, out):
    """Elastic–plastic friction with capacity μV + a (V > 0), stiffness capacity/δ; zero at
    lift-off (V <= 0). Soil work ∫R dy by the trapezoid of the increment."""
    for i in range(state_old.shape[0]):
        state_new[i] = state_old[i]
    for i in range(out.shape[0]):
        out[i] = 0.0
    dy = y_new - state_old[S_Y]
    state_new[S_Y] = y_new
    f0 = state_old[S_FRICTION]
    f = 0.0
    k = 0.0
    stored = 0.0
    if not v_load <= 0.0:  # V > 0, or NaN (which then gives NaN resistance)
        cap = params[P_MU] * v_load + params[P_ADHESION]
        k = cap / params[P_DELTA]
        f0 = min(max(f0, -cap), cap)
        f = f0 + k * dy
        if f > cap:
            f, k = cap, 0.0
        elif f < -cap:
            f, k = -cap, 0.0
        stored = 0.5 * f * f * params[P_DELTA] / cap
    else:
        f0 = 0.0
    w = 0.5 * (f + f0) * dy
    state_new[S_FRICTION] = f
    state_new[S_WORK] = state_old[S_WORK] + abs(w)
    state_new[S_SOIL_WORK] = state_old[S_SOIL_WORK] + w
    out[OUT_R] = f
    out[OUT_FRICTION] = f
    out[OUT_TANGENT] = k
    out[OUT_WORK] = state_new[S_WORK]
    out[OUT_STORED] = stored
    out[OUT_DISSIPATED] = state_new[S_SOIL_WORK] - stored


@dataclass(frozen=True, kw_only=True)
class AdhesiveCoulomb(LateralResistanceModel):
    """Coulomb friction with adhesion: R = μV + a once mobilised (recipe example).

    Parameters
    ----------
    friction_coefficient : float
        μ [-], in (0, 2].
    adhesion : float
        a [N/m], in [0, 1e5].
    mobilisation_displacement : float
        δ [m], > 0 (default 1 mm).
    """

    name: ClassVar[str] = "adhesive_coulomb"
    reference: ClassVar[str] = "Coulomb friction with adhesion (recipe example)"
    state_size: ClassVar[int] = N_COMMON_STATE

    friction_coefficient: float
    adhesion: float = 0.0
    mobilisation_displacement: float = 1.0e-3

    def __post_init__(self) -> None:
        in_range("AdhesiveCoulomb.friction_coefficient", self.friction_coefficient, 0.0, 2.0)
        in_range("AdhesiveCoulomb.adhesion", self.adhesion, 0.0, 1.0e5)
        positive("AdhesiveCoulomb.mobilisation_displacement", self.mobilisation_displacement)

    @property
    def kernel(self):
        return adhesive_coulomb_kernel

    @property
    def python_kernel(self):
        return pure_python(adhesive_coulomb_kernel)

    def packed_parameters(self) -> np.ndarray:
        return np.array([self.friction_coefficient, self.adhesion, self.mobilisation_displacement])

    def initial_state(self) -> np.ndarray:
        return np.zeros(self.state_size)

    def parameters(self) -> Mapping[str, Any]:
        return {
            "friction_coefficient": self.friction_coefficient,
            "adhesion": self.adhesion,
            "mobilisation_displacement": self.mobilisation_displacement,
        }


# ---- force: quadratic drag alone, F_Y = ½ρD C_D |u + vc − ẏ|(u + vc − ẏ), F_Z = 0 -------------
@njit(cache=True)
def quadratic_drag_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Drag on the relative velocity; no inertia, no lift, no state."""
    for i in range(state_old.shape[0]):
        state_new[i] = state_old[i]
    ur = u + vc - ydot
    c = 0.5 * rho * d * params[0]
    out[FO_FY] = c * abs(ur) * ur
    out[FO_DFY_DYD] = -2.0 * c * abs(ur)
    out[FO_FZ] = 0.0
    out[FO_DFZ_DYD] = 0.0


@dataclass(frozen=True, kw_only=True)
class QuadraticDrag:
    """Drag alone on the relative velocity (recipe example).

    Parameters
    ----------
    cd : float
        Drag coefficient C_D [-], in [0, 10].
    added_mass : float
        C_a [-] of the pipe's added mass, in [0, 10] (default 2.29).
    """

    name: ClassVar[str] = "quadratic_drag"

    cd: float = 0.7
    added_mass: float = 2.29

    def __post_init__(self) -> None:
        in_range("QuadraticDrag.cd", self.cd, 0.0, 10.0)
        in_range("QuadraticDrag.added_mass", self.added_mass, 0.0, 10.0)

    @property
    def added_mass_coefficient(self) -> float:
        return self.added_mass

    def parameter_table(self, keulegan_carpenter, current_ratio) -> np.ndarray:
        return np.full((np.size(keulegan_carpenter), 1), self.cd)

    def describe(self) -> dict[str, Any]:
        return {"force_model": self.name, "cd": self.cd, "source": "recipe example"}


# ---- registration: one call each ------------------------------------------------------------
if "adhesive_coulomb" not in SOIL_MODELS:
    register_soil_model(
        "adhesive_coulomb",
        AdhesiveCoulomb,
        lambda pipe, seabed, **o: AdhesiveCoulomb(
            **{"friction_coefficient": seabed.friction_coefficient, **o}
        ),
        kernel=adhesive_coulomb_kernel,
        description="Coulomb friction with adhesion (recipe example)",
    )
    register_force_model(
        "quadratic_drag",
        QuadraticDrag,
        kernel=quadratic_drag_kernel,
        description="drag alone on the relative velocity (recipe example)",
    )
