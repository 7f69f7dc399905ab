"""Constants of the stateful hydrodynamic force-model kernel contract (no numba code).

Every force-model kernel (``hydro/_morison_kernel.py``, ``hydro/_wake_kernel.py``,
``hydro/_fourier_kernel.py``) has the signature

    kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)

and is dispatched on an integer ``model_id`` by ``onbottom.hydro._force_dispatch.force_step``
(the contract's numbered rules are in that module's docstring). ``state_old``/``state_new`` hold
:data:`N_FORCE_STATE` slots; ``out`` holds :data:`FO_SIZE` values:

* ``out[FO_FY]``: lateral force per unit length before reduction factors [N/m], positive in +y;
* ``out[FO_DFY_DYD]``: ∂F_Y/∂ẏ [N·s/m²];
* ``out[FO_FZ]``: vertical (lift) force per unit length before reductions [N/m], upward;
* ``out[FO_DFZ_DYD]``: ∂F_Z/∂ẏ [N·s/m²].
"""

from __future__ import annotations

__all__ = ["FO_DFY_DYD", "FO_DFZ_DYD", "FO_FY", "FO_FZ", "FO_SIZE", "N_FORCE_STATE"]

N_FORCE_STATE = 16
"""Number of history slots of a force model's state (zeros at the start of a run)."""

FO_FY = 0
"""Index of the lateral force F_Y [N/m] in ``out``."""
FO_DFY_DYD = 1
"""Index of ∂F_Y/∂ẏ [N·s/m²] in ``out``."""
FO_FZ = 2
"""Index of the vertical force F_Z [N/m] in ``out``."""
FO_DFZ_DYD = 3
"""Index of ∂F_Z/∂ẏ [N·s/m²] in ``out``."""
FO_SIZE = 4
"""Length of ``out``."""
