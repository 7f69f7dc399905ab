"""The soil kernel contract for solvers: what a solver kernel of another package calls.

The section, storm and pipeline solvers (:mod:`onbottom.dynamics`) call the soil model's numba
kernel from inside their own kernels. numba cannot cache a kernel that receives another
jitted function as an argument, so they dispatch statically on the model class's integer
``model_id``; this module is the public home of that dispatch and of the other soil kernels a
solver kernel calls. The kernels stay in their private modules (``soil/_*_kernel.py``,
``soil/_dispatch.py``); the names here are the same objects (numba's on-disk cache is keyed by
the file that defines a function, so importing them from here changes nothing compiled).

The rules every soil kernel obeys (signature ``kernel(params, state_old, y_new, v_load,
state_new, out)``, read-only ``state_old``, trial ``state_new`` committed by the solver on
accepted steps, zero resistance at lift-off, the ``OUT_*`` and ``S_*`` slots, the two-DOF
form) are the numbered rules of :mod:`onbottom.soil.base`, which also holds the slot constants.

Exports
-------
:func:`lateral_step`
    ``lateral_step(model_id, params, state_old, y_new, v_load, state_new, out)``: the kernel
    of model ``model_id`` (a ``MODEL_*`` id; an unknown id gives NaN resistance).
:data:`lateral_step_inline`
    The same, inlined into its caller (for loops over many nodes).
:func:`lateral_step_of`
    Same arguments; with a numba-literal ``model_id`` (``numba.literally`` at the caller's
    entry point, called through :func:`onbottom._jit.call_literal`) it compiles to a direct
    call of that one model's kernel (one-node solvers: section, storm section).
:func:`lateral_step_node`
    ``lateral_step_node(soil_id, model_id, ...)``: one node of a multi-node solver (the
    pipeline FE); ``soil_id`` the literal model of all nodes, or :data:`MODELS_MIXED`.
:data:`MODELS_MIXED`
    The ``soil_id`` of nodes on several soil models.
``MODEL_COULOMB``, ``MODEL_VERLEY_SOTBERG``, ``MODEL_VERLEY_LUND``, ``MODEL_VH_PARABOLIC``
    The model ids (each model class's ``model_id``).
:func:`friction_return_map`
    ``friction_return_map(f_old, dy, v_load, mu, delta) -> (force, tangent)``: the
    elastic–plastic Coulomb return map (the pipeline FE's axial friction μ_ax·V).
"""

from __future__ import annotations

from onbottom.soil._coulomb_kernel import friction_return_map
from onbottom.soil._dispatch import (
    MODEL_COULOMB,
    MODEL_VERLEY_LUND,
    MODEL_VERLEY_SOTBERG,
    MODEL_VH_PARABOLIC,
    MODELS_MIXED,
    lateral_step,
    lateral_step_inline,
    lateral_step_node,
    lateral_step_of,
)

__all__ = [
    "MODELS_MIXED",
    "MODEL_COULOMB",
    "MODEL_VERLEY_LUND",
    "MODEL_VERLEY_SOTBERG",
    "MODEL_VH_PARABOLIC",
    "friction_return_map",
    "lateral_step",
    "lateral_step_inline",
    "lateral_step_node",
    "lateral_step_of",
]
