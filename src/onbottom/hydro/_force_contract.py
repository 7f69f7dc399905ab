"""Shared constants of the stateful force-model kernel contract (private; no numba code).

Every force kernel (``hydro/_morison_kernel.py``, ``hydro/_wake_kernel.py``,
``hydro/_fourier_kernel.py``) has the signature

    kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)

and is dispatched on an integer model id by ``onbottom.hydro._force_dispatch.force_step``;
the contract's rules are written there. This module holds the sizes and output slots that
every kernel and solver share.
"""

from __future__ import annotations

FO_FY = 0
"""``out`` slot: lateral force per unit length before reductions [N/m], positive in +y."""
FO_DFY_DYD = 1
"""``out`` slot: ∂F_Y/∂ẏ [N·s/m²] (<= 0 for a drag law)."""
FO_FZ = 2
"""``out`` slot: vertical (lift) force per unit length before reductions [N/m], upward."""
FO_DFZ_DYD = 3
"""``out`` slot: ∂F_Z/∂ẏ [N·s/m²]."""
FO_SIZE = 4
"""Length of ``out``."""
N_FORCE_STATE = 16
"""Slots of a force model's state vector (zeros at the start of a run)."""
