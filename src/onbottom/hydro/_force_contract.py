"""Slots of the stateful force-model kernel contract (private; no numba code here).

The contract itself is written as numbered rules in :mod:`onbottom.hydro._force_dispatch`.
Every force-model kernel module imports its output slots and the state length from here.

``out`` slots written by a kernel (forces per unit length, *before* the DNV-RP-F109 load
reductions, which the solver applies):

- ``FO_FY`` lateral force F_Y [N/m], positive in +y (drag, Froude–Krylov and added-mass
  inertia on U̇; not the added mass on the pipe's own acceleration);
- ``FO_DFY_DYD`` ∂F_Y/∂ẏ [N·s/m²] (<= 0 for a drag law);
- ``FO_FZ`` vertical (lift) force F_Z [N/m], positive upward;
- ``FO_DFZ_DYD`` ∂F_Z/∂ẏ [N·s/m²].
"""

from __future__ import annotations

FO_FY = 0
FO_DFY_DYD = 1
FO_FZ = 2
FO_DFZ_DYD = 3
FO_SIZE = 4

N_FORCE_STATE = 16
"""Length of a force model's state vector (zeros at the start of a run)."""

N_FORCE_PREP = 8
"""Length of the scratch ``prep`` of a model's once-per-step stage (``force_prepare``)."""
