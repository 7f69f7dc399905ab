"""The force-model kernel contract for solvers: what a solver kernel of another package calls.

The storm section and the pipeline FE (:mod:`onbottom.dynamics`) call the hydrodynamic force
model's numba kernel from inside their own kernels. numba cannot cache a kernel that receives
another jitted function as an argument, so they dispatch statically on the force-model class's
integer ``model_id``; this module is the public home of that dispatch, of the output and state
slots, and of the DNV-RP-F109 penetration reductions the solvers apply to the kernel's output.
The kernels stay in their private modules (``hydro/_*_kernel.py``, ``hydro/_force_dispatch.py``,
``hydro/_force_contract.py``, ``hydro/_load_kernels.py``); the names here are the same objects
(numba's on-disk cache is keyed by the file that defines a function, so importing them from
here changes nothing compiled).

The rules every force-model kernel obeys (signature ``kernel(params, state_old, t, u, dudt, vc,
ydot, d, rho, state_new, out)``, read-only ``state_old``, a zero state a valid start, the
Newton tangent, mirror symmetry, forces before the F109 reductions) are the numbered rules in
the docstring of ``onbottom/hydro/_force_dispatch.py``, with the model classes' protocol
:class:`onbottom.hydro.force_model.ForceModel`.

Exports
-------
:func:`force_step`
    ``force_step(model_id, params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)``:
    the kernel of force model ``model_id`` (a ``FORCE_*`` id; an unknown id gives NaN forces).
:data:`force_step_inline`
    The same, inlined into its caller (for loops over many nodes).
:func:`force_step_of`
    Same arguments; with a numba-literal ``model_id`` (``numba.literally`` at the caller's
    entry point) it compiles to a direct call of that one model's kernel.
``FORCE_MORISON``, ``FORCE_WAKE``, ``FORCE_FOURIER``
    The model ids (each force-model class's ``model_id``).
``FO_FY``, ``FO_DFY_DYD``, ``FO_FZ``, ``FO_DFZ_DYD``, ``FO_SIZE``
    The slots of ``out``: F_Y [N/m], ∂F_Y/∂ẏ [N·s/m²], F_Z [N/m], ∂F_Z/∂ẏ [N·s/m²], per unit
    length before the reductions; ``FO_SIZE`` the length of ``out``.
``N_FORCE_STATE``
    Length of a force model's state vector (zeros at the start of a run).
:func:`force_prepare_of`, :func:`force_evaluate_of`
    The optional two-stage form of rule 7 (non-literal ids: :func:`force_prepare`,
    :func:`force_evaluate`): ``force_prepare_of(model_id, params, state_old, t,
    u, dudt, vc, d, rho, state_new, prep) -> bool`` once per trial step, then
    ``force_evaluate_of(model_id, params, prep, u, vc, ydot, d, rho, out)`` per ``ydot``, bit
    for bit the kernel's ``out``; False from the first: call the kernel instead.
:func:`force_step_unprepared_of`
    As :func:`force_step_of`, for a solver that calls the kernel only where
    :func:`force_prepare_of` returned False: with a literal id of a model with the two-stage
    form it compiles to a NaN stub (:func:`prepared_only`, never called) instead of that
    model's one-call kernel.
``N_FORCE_PREP``
    Length of the ``prep`` scratch of the two-stage form.
:func:`penetration_reduction_y`, :func:`penetration_reduction_z`
    r_pen,y(z/D) and r_pen,z(z/D), DNV-RP-F109 (2017) Eqs 3.19–3.20 (numba; plain-Python twin
    :func:`onbottom.hydro.reductions.penetration_reduction`).
"""

from __future__ import annotations

from onbottom.hydro._force_contract import (
    FO_DFY_DYD,
    FO_DFZ_DYD,
    FO_FY,
    FO_FZ,
    FO_SIZE,
    N_FORCE_PREP,
    N_FORCE_STATE,
)
from onbottom.hydro._force_dispatch import (
    FORCE_FOURIER,
    FORCE_MORISON,
    FORCE_WAKE,
    force_evaluate,
    force_evaluate_of,
    force_prepare,
    force_prepare_of,
    force_step,
    force_step_inline,
    force_step_of,
    force_step_unprepared_of,
)
from onbottom.hydro._load_kernels import penetration_reduction_y, penetration_reduction_z

__all__ = [
    "FORCE_FOURIER",
    "FORCE_MORISON",
    "FORCE_WAKE",
    "FO_DFY_DYD",
    "FO_DFZ_DYD",
    "FO_FY",
    "FO_FZ",
    "FO_SIZE",
    "N_FORCE_PREP",
    "N_FORCE_STATE",
    "force_evaluate",
    "force_evaluate_of",
    "force_prepare",
    "force_prepare_of",
    "force_step",
    "force_step_inline",
    "force_step_of",
    "force_step_unprepared_of",
    "penetration_reduction_y",
    "penetration_reduction_z",
]
