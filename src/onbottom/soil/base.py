"""The lateral pipe–soil resistance model interface and its numba kernel contract.

A lateral resistance model is a *thin Python class* (validated parameters, references,
calibration range) in front of a *numba kernel* that later solvers call increment by increment.
The pattern follows openpile (numba spring laws behind model classes) and scipy's ``OdeSolver``
(an explicit implementer contract).

Kernel contract
---------------
Every model provides ``model_id`` (its branch in :mod:`onbottom.soil._dispatch`; solvers call
``lateral_step(model_id, ...)`` because numba cannot cache jitted functions passed as
arguments, and import it from the public :mod:`onbottom.soil.kernel_contract`), ``kernel``
(an ``@njit(cache=True)`` function) and ``python_kernel`` (its plain-Python twin, used by the
tests), both with the signature::

    kernel(params, state_old, y_new, v_load, state_new, out) -> None

1. ``params`` — float64 array from :meth:`LateralResistanceModel.packed_parameters`; read only.
2. ``state_old`` — float64 array of length ``model.state_size``: the last *committed* state;
   read only. The first slots are common to all models (indices below); the rest are the
   model's own.
3. ``y_new`` — trial total lateral displacement of the pipe y [m] (any sign).
4. ``v_load`` — vertical contact load V = W_s − F_L [N/m]. V <= 0 means lift-off: the kernel
   must then return zero resistance, not NaN.
5. ``state_new`` — float64 array, same length as the state; the kernel writes the trial state
   reached by moving from ``state_old`` to ``y_new`` under ``v_load``. The caller *commits* it
   (copies it into ``state_old``) once the time step is accepted, so a kernel may be called
   many times from the same ``state_old`` (Newton iterations) without side effects.
6. ``out`` — float64 array of length :data:`OUT_SIZE`; the kernel writes
   ``out[OUT_R]`` resistance R [N/m], ``out[OUT_FRICTION]`` Coulomb part, ``out[OUT_PASSIVE]``
   passive part, ``out[OUT_TANGENT]`` dR/dy [N/m²], ``out[OUT_Z]`` penetration z [m],
   ``out[OUT_WORK]`` accumulated work [N], ``out[OUT_REGION]`` region code,
   ``out[OUT_STORED]`` elastic energy stored in the soil (friction and passive springs) [N·m/m]
   and ``out[OUT_DISSIPATED]`` energy dissipated by the soil since the start [N·m/m]: the
   soil work ∫R dy (trapezoidal per committed increment, common slot ``S_SOIL_WORK``) minus the
   stored energy. A physically admissible law never lets the dissipated energy decrease on a
   path at constant V (``tests/verification/test_energy_balance.py``).
7. Sign: R is the soil force *resisting* positive pipe motion, so the equation of lateral motion
   of a pipe section is ``m·ü = H − R``; R > 0 pushes the pipe towards −y.
8. No allocation, no Python objects, no printing inside the kernel; float64 only.

Common state slots: ``S_Y`` committed displacement y [m]; ``S_FRICTION`` friction force
[N/m] (elastic–plastic, see :mod:`onbottom.soil.coulomb`); ``S_Z`` penetration z [m];
``S_WORK`` accumulated work E [N]; ``S_REGION`` region code; ``S_SOIL_WORK`` work done on the
soil ∫R dy since the start [N·m/m] (energy bookkeeping). Model-specific slots follow
``N_COMMON_STATE``; never hard-code state lengths (use ``model.state_size`` or the kernels'
``N_STATE``).

Second form: two degrees of freedom (vertical + lateral)
--------------------------------------------------------
A *force-resultant* model (a yield surface in V–H space, a flow rule, hardening; the test model
is :class:`onbottom.soil.vh_parabolic.ParabolicVH`) couples the two directions: the vertical
load changes the lateral capacity and the lateral slip moves the pipe vertically. It is a
:class:`ForceResultantModel` (``degrees_of_freedom = 2``) and its kernel keeps the signature
and slots above (so the same :func:`~onbottom.soil._dispatch.lateral_step` serves both forms
and the section, storm and pipeline solvers take it unchanged), under these further rules:

2.1 *Mixed control.* The pipe's degrees of freedom are the lateral displacement y (``y_new``)
    and the vertical displacement z, positive downward (penetration). The section, storm and
    pipeline solvers have no vertical degree of freedom: they prescribe the vertical load V
    (rule 4) and the kernel returns the lateral reaction H (``out[OUT_R]``) and the vertical
    displacement z (``out[OUT_Z]``, also ``state_new[S_Z]``) that the soil allows under V.
    z is a plastic (or elastic) *displacement*, free to move both ways — penetration or heave —
    not a penetration law; the solvers feed it back into the DNV-RP-F109 penetration
    reductions of the loads (storm section, pipeline), as they do for the 1-DOF models.
2.2 *Coupling tangent.* When ``out`` has :data:`OUT2_SIZE` slots (or more) the kernel also
    writes the other three entries of the hybrid 2×2 tangent of (H, z) with respect to
    (y, V): ``out[OUT_TANGENT]`` = ∂H/∂y, ``out[OUT2_DH_DV]`` = ∂H/∂V [-],
    ``out[OUT2_DZ_DY]`` = ∂z/∂y [-], ``out[OUT2_DZ_DV]`` = ∂z/∂V [m²/N], all consistent with
    the return mapping of the increment (checked against finite differences in the tests).
    With ``OUT_SIZE`` slots it writes only those (the load-controlled solvers, which need
    ∂H/∂y alone: their V does not depend on y within a step). A caller with a vertical degree
    of freedom obtains the displacement-controlled stiffness ∂(H, V)/∂(y, z) by partial
    inversion (:func:`onbottom.soil._two_dof.stiffness_from_hybrid`), which needs
    ∂z/∂V > 0 (a model with vertical compliance at that state).
2.3 *Plastic flow.* Plastic increments follow a flow rule from a plastic potential g(V, H):
    (Δz_p, Δy_p) = Δλ·(∂g/∂V, ∂g/∂H), Δλ >= 0; the plastic work V·Δz_p + H·Δy_p must be
    >= 0 (rule 6's dissipation includes the vertical work V·Δz: the soil-work slot
    ``S_SOIL_WORK`` accumulates ∫H dy + ∫V dz).
2.4 *Hardening* variables live in the model's own state slots (after ``N_COMMON_STATE``)
    and are committed with the rest of the state (rule 5).
2.5 *Lift-off.* V <= 0: H = 0, all tangents 0, z and the hardening state frozen.
2.6 *No equilibrium.* A vertical load the soil cannot carry (V above the capacity with no
    hardening) returns ``out[OUT_R]`` = NaN; the solvers stop with their soil-NaN status.
2.7 *Reduction to the first form.* A 2-DOF model whose yield surface does not depend on V
    beyond Coulomb's |H| = μV and whose flow has no vertical part is the 1-DOF Coulomb model:
    it must then give Coulomb's lateral history to round-off in every solver
    (``tests/verification/test_vh_soil_in_solvers.py``).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from typing import Any, ClassVar

import numpy as np

__all__ = [
    "N_COMMON_STATE",
    "OUT2_DH_DV",
    "OUT2_DZ_DV",
    "OUT2_DZ_DY",
    "OUT2_SIZE",
    "OUT_DISSIPATED",
    "OUT_FRICTION",
    "OUT_PASSIVE",
    "OUT_R",
    "OUT_REGION",
    "OUT_SIZE",
    "OUT_STORED",
    "OUT_TANGENT",
    "OUT_WORK",
    "OUT_Z",
    "S_FRICTION",
    "S_REGION",
    "S_SOIL_WORK",
    "S_WORK",
    "S_Y",
    "S_Z",
    "ForceResultantModel",
    "LateralResistanceModel",
]

# common state slots
S_Y = 0
S_FRICTION = 1
S_Z = 2
S_WORK = 3
S_REGION = 4
S_SOIL_WORK = 5
N_COMMON_STATE = 6

# output slots
OUT_R = 0
OUT_FRICTION = 1
OUT_PASSIVE = 2
OUT_TANGENT = 3
OUT_Z = 4
OUT_WORK = 5
OUT_REGION = 6
OUT_STORED = 7
OUT_DISSIPATED = 8
OUT_SIZE = 9
# second form (two degrees of freedom): the coupling entries of the hybrid tangent (rule 2.2)
OUT2_DH_DV = 9
OUT2_DZ_DY = 10
OUT2_DZ_DV = 11
OUT2_SIZE = 12

KernelFn = Callable[[np.ndarray, np.ndarray, float, float, np.ndarray, np.ndarray], None]


class LateralResistanceModel(ABC):
    """Base class of lateral pipe–soil resistance models (see the module docstring)."""

    name: ClassVar[str]
    """Short model name used in results and case files."""
    reference: ClassVar[str]
    """Source of the model (authors, year, journal/standard, edition)."""
    state_size: ClassVar[int]
    """Length of the state vector."""
    model_id: ClassVar[int]
    """Integer id used by :func:`onbottom.soil._dispatch.lateral_step` (cacheable dispatch)."""
    degrees_of_freedom: ClassVar[int] = 1
    """1: lateral kernel (rules 1–8); 2: force-resultant kernel (rules 2.1–2.7)."""

    @property
    @abstractmethod
    def kernel(self) -> KernelFn:
        """The numba kernel (see contract)."""

    @property
    @abstractmethod
    def python_kernel(self) -> KernelFn:
        """Plain-Python twin of :attr:`kernel` (same signature, same results)."""

    @abstractmethod
    def packed_parameters(self) -> np.ndarray:
        """Model parameters packed as a float64 array for the kernel."""

    @abstractmethod
    def initial_state(self) -> np.ndarray:
        """State of the pipe at the start of lateral loading (y = 0)."""

    @abstractmethod
    def parameters(self) -> Mapping[str, Any]:
        """Model parameters as a name → value mapping (SI) for provenance and calibration."""


class ForceResultantModel(LateralResistanceModel):
    """Base class of two-degree-of-freedom (V–H force-resultant) models (second form, rules
    2.1–2.7 of the module docstring)."""

    degrees_of_freedom: ClassVar[int] = 2
    """Vertical and lateral."""
