"""Static dispatch from a model id to its numba kernel (private).

numba cannot cache functions that receive other jitted functions as arguments, so solvers call
:func:`lateral_step` with the integer ``model_id`` of the model class instead. Adding a model:
give its class a new ``model_id`` and add one branch here.

Speed (issue 33): the kernels use ``error_model="numpy"`` (a division by zero gives inf/NaN,
which the solvers' finiteness checks catch, instead of a ZeroDivisionError test at every
division and a status check after every call); :data:`lateral_step_inline`, the same function
inlined into its caller (``inline="always"``), is for callers that loop over many nodes (the
pipeline FE): the called dispatch cost about 40 ns per node call, more than the Coulomb
kernel itself. The one-node solvers keep the called form (less to compile).
"""

from __future__ import annotations

import numpy as np

from onbottom._jit import njit
from onbottom.soil._coulomb_kernel import coulomb_kernel
from onbottom.soil._verley_lund_kernel import verley_lund_kernel
from onbottom.soil._verley_sotberg_kernel import verley_sotberg_kernel
from onbottom.soil._vh_parabolic_kernel import vh_parabolic_kernel

MODEL_COULOMB = 0
MODEL_VERLEY_SOTBERG = 1
MODEL_VERLEY_LUND = 2
MODEL_VH_PARABOLIC = 3  # two-DOF force-resultant test model (onbottom.soil.vh_parabolic)


@njit(cache=True)
def lateral_step(model_id, params, state_old, u_new, v_load, state_new, out):
    """Call the kernel of model ``model_id`` (contract: :mod:`onbottom.soil.base`)."""
    if model_id == MODEL_COULOMB:
        coulomb_kernel(params, state_old, u_new, v_load, state_new, out)
    elif model_id == MODEL_VERLEY_SOTBERG:
        verley_sotberg_kernel(params, state_old, u_new, v_load, state_new, out)
    elif model_id == MODEL_VERLEY_LUND:
        verley_lund_kernel(params, state_old, u_new, v_load, state_new, out)
    elif model_id == MODEL_VH_PARABOLIC:
        vh_parabolic_kernel(params, state_old, u_new, v_load, state_new, out)
    else:
        # unknown id: signal with NaN resistance; the Python layer validates ids beforehand
        for i in range(out.shape[0]):
            out[i] = 0.0
        out[0] = np.nan


lateral_step_inline = njit(cache=True, inline="always")(lateral_step.py_func)
""":func:`lateral_step` inlined into its caller at numba-IR level (same source)."""
