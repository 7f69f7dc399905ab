"""Static dispatch from a model id to its numba kernel (private).

numba cannot cache functions that receive other jitted functions as arguments, so solvers call
:func:`lateral_step` with the integer ``model_id`` of the model class instead. The built-in
models have a branch here and an entry in ``_KERNELS``; a model added through
:func:`onbottom.soil.registry.register_soil_model` with ``kernel=`` gets an id and a
``_KERNELS`` entry from :func:`register_soil_kernel`, with no edit of this module.

Compile time: the storm, section and pipeline kernels take the model id as a
numba literal (``numba.literally``; called from Python through
:func:`onbottom._jit.call_literal`) and call :func:`lateral_step_of` /
:func:`lateral_step_node`, which compile to a direct call of that one model's kernel, so a run
compiles only the models it uses (about half the compiling of a storm case).

Speed: the kernels use ``error_model="numpy"`` (a division by zero gives inf/NaN,
which the solvers' finiteness checks catch, instead of a ZeroDivisionError test at every
division and a status check after every call); :data:`lateral_step_inline`, the same function
inlined into its caller (``inline="always"``), is for callers that loop over many nodes (the
pipeline FE): the called dispatch costs more per node call than the Coulomb kernel
itself. The one-node solvers keep the called form (less to compile).
"""

from __future__ import annotations

import numpy as np
from numba.extending import overload

from onbottom._jit import jitted_only, literal_dispatch, njit, registered_kernel_id
from onbottom.soil._coulomb_kernel import coulomb_kernel
from onbottom.soil._verley_lund_kernel import verley_lund_kernel
from onbottom.soil._verley_sotberg_kernel import verley_sotberg_kernel
from onbottom.soil._vh_parabolic_kernel import vh_parabolic_kernel

MODEL_COULOMB = 0
MODEL_VERLEY_SOTBERG = 1
MODEL_VERLEY_LUND = 2
MODEL_VH_PARABOLIC = 3  # two-DOF force-resultant test model (onbottom.soil.vh_parabolic)


@jitted_only
def lateral_step(model_id, params, state_old, y_new, v_load, state_new, out):
    """Call the kernel of model ``model_id`` (contract: :mod:`onbottom.soil.base`)."""
    if model_id == MODEL_COULOMB:
        coulomb_kernel(params, state_old, y_new, v_load, state_new, out)
    elif model_id == MODEL_VERLEY_SOTBERG:
        verley_sotberg_kernel(params, state_old, y_new, v_load, state_new, out)
    elif model_id == MODEL_VERLEY_LUND:
        verley_lund_kernel(params, state_old, y_new, v_load, state_new, out)
    elif model_id == MODEL_VH_PARABOLIC:
        vh_parabolic_kernel(params, state_old, y_new, v_load, state_new, out)
    else:
        # unknown id: signal with NaN resistance; the Python layer validates ids beforehand
        for i in range(out.shape[0]):
            out[i] = 0.0
        out[0] = np.nan


lateral_step_inline = njit(cache=True, inline="always")(lateral_step.py_func)
""":func:`lateral_step` inlined into its caller at numba-IR level (same source)."""


_KERNELS = {
    MODEL_COULOMB: coulomb_kernel,
    MODEL_VERLEY_SOTBERG: verley_sotberg_kernel,
    MODEL_VERLEY_LUND: verley_lund_kernel,
    MODEL_VH_PARABOLIC: vh_parabolic_kernel,
}


def lateral_step_of(model_id, params, state_old, y_new, v_load, state_new, out):
    """:func:`lateral_step` that compiles only the kernel of a literal ``model_id``.

    In a kernel whose ``model_id`` is a numba literal (the caller's entry point calls
    ``numba.literally(model_id)``) this is a direct call of that model's kernel
    (:func:`onbottom._jit.literal_dispatch`), so the caller compiles one soil model, not all
    of them (numba's dead-branch pruning does not resolve ``model_id == MODEL_*`` on literal
    integers). With a non-literal id it is :func:`lateral_step`; in plain Python too (this
    body).
    """
    kernel = _KERNELS.get(model_id)
    if kernel is None or model_id < FIRST_REGISTERED_ID:
        lateral_step(model_id, params, state_old, y_new, v_load, state_new, out)
    else:
        kernel(params, state_old, y_new, v_load, state_new, out)


literal_dispatch(lateral_step_of, _KERNELS, lateral_step)


FIRST_REGISTERED_ID = 1000
"""Model ids from here up belong to kernels added by :func:`register_soil_kernel`."""


def register_soil_kernel(kernel) -> int:
    """Add soil kernel ``kernel`` (an ``@njit(cache=True)`` function on the contract of
    :mod:`onbottom.soil.base`) to the dispatch table; returns its model id.

    The id is derived from the kernel's module, name and source, so that numba's on-disk
    cache of a solver specialised on it (a literal id) never serves another kernel. The
    solvers that take a literal model id (section, storm section, pipeline with one soil)
    then call it directly, with no edit of this module; the non-literal :func:`lateral_step`
    (pipeline nodes on several soil models) knows the built-in models only.
    """
    model_id = registered_kernel_id(kernel, FIRST_REGISTERED_ID)
    _KERNELS[model_id] = kernel
    return model_id


MODELS_MIXED = -1
"""``soil_id`` of :func:`lateral_step_node` when the nodes use several soil models."""


def lateral_step_node(soil_id, model_id, params, state_old, y_new, v_load, state_new, out):
    """Soil step of one node of a solver whose nodes all use the literal model ``soil_id``.

    For the pipeline FE: with ``soil_id`` a numba literal model id (all nodes on one
    soil model, the usual case) the caller compiles that model's kernel only; with
    :data:`MODELS_MIXED` (or a non-literal) it is :data:`lateral_step_inline` on the node's
    ``model_id``. In plain Python: :func:`lateral_step`.
    """
    lateral_step(model_id, params, state_old, y_new, v_load, state_new, out)


# inline="always": the one-line wrapper is inlined into the caller's numba IR, so the node loop
# calls the model's kernel directly (saving the wrapper's own call per node)
@overload(
    lateral_step_node, prefer_literal=True, inline="always", jit_options={"error_model": "numpy"}
)
def _lateral_step_node(soil_id, model_id, params, state_old, y_new, v_load, state_new, out):
    kernel = _KERNELS.get(getattr(soil_id, "literal_value", None))
    if kernel is None:

        def mixed(soil_id, model_id, params, state_old, y_new, v_load, state_new, out):
            lateral_step_inline(model_id, params, state_old, y_new, v_load, state_new, out)

        return mixed

    def one(soil_id, model_id, params, state_old, y_new, v_load, state_new, out):
        kernel(params, state_old, y_new, v_load, state_new, out)

    return one
