"""Static dispatch from a force-model id to its numba kernel, and the force-model contract.

numba cannot cache functions that receive other jitted functions as arguments, so the storm
section (:mod:`onbottom.dynamics._storm_kernel`) and the pipeline FE
(:mod:`onbottom.dynamics.pipeline._pipeline_kernel`) call :func:`force_step` with the integer
``model_id`` of the force-model class, as they call ``soil._dispatch.lateral_step`` for soil.
They import it, the ``FO_*`` slots and the F109 penetration reductions from the public
:mod:`onbottom.hydro.kernel_contract` (and ``lateral_step`` from
:mod:`onbottom.soil.kernel_contract`).

Kernel contract
---------------
A hydrodynamic force model is a frozen dataclass (``name``, ``model_id``,
``added_mass_coefficient``, ``parameter_table(K, M)``, ``describe()``; see
:class:`onbottom.hydro.force_model.ForceModel`) in front of a numba kernel in its own private
module (``hydro/_<name>_kernel.py``) with the signature::

    kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out) -> None

Arguments (float64 scalars unless said): ``params`` the model's parameters for the current sea
state (1-D contiguous; one row of the table the solver built from ``parameter_table``, its
layout given by the kernel module's ``P_*`` constants); ``state_old`` the committed state,
:data:`~onbottom.hydro._force_contract.N_FORCE_STATE` slots (meaning: the module's ``S_*``
constants); ``t`` time of the evaluation [s] (the trial step end); ``u``, ``dudt`` the
wave-induced velocity normal to the pipe [m/s] and its time derivative [m/s²], without
current; ``vc`` the steady current normal to the pipe [m/s], signed; ``ydot`` the pipe's
lateral velocity [m/s] (0.0 when the solver's relative velocity is off); ``d`` outer diameter
[m]; ``rho`` water density [kg/m³]; ``state_new`` the state after this evaluation;
``out`` the :data:`~onbottom.hydro._force_contract.FO_SIZE` outputs F_Y, ∂F_Y/∂ẏ, F_Z, ∂F_Z/∂ẏ
(slots ``FO_*`` in :mod:`onbottom.hydro._force_contract`), per unit length, **before** any
reduction factor.

1. A kernel is a pure function of its arguments: deterministic, no global state, no
   allocation, no Python objects, no printing; float64 only.
2. It never writes ``state_old``; it writes every slot of ``state_new`` it uses and all of
   ``out[0:4]``. The solver copies ``state_new`` into the committed state only when the time
   step is accepted, so the same ``state_old`` may be evaluated at several ``t`` and ``ydot``
   (Newton iterations, halved steps) without side effects. ``t`` is strictly increasing
   between committed states.
3. A zero ``state_old`` is a valid initial state (the flow at rest before the record).
4. Finite inputs give finite outputs; ``out[FO_DFY_DYD]`` and ``out[FO_DFZ_DYD]`` are
   consistent with a finite difference of F_Y and F_Z in ``ydot`` (the Newton tangent);
   ∂F_Y/∂ẏ <= 0 for a drag law.
5. Mirror symmetry: (u, dudt, vc, ydot) → −(u, dudt, vc, ydot) from the mirrored state gives
   F_Y → −F_Y and F_Z unchanged.
6. The kernel has a plain-Python twin with the same arithmetic, tested to round-off, and
   tests of rules 2–5 (``tests/unit/test_force_kernels.py``).
7. Optional two-stage form, for a model whose state update and most of its arithmetic do not
   depend on ``ydot`` (the wake model's history and its ``exp`` terms). A solver that
   evaluates one trial step at several ``ydot`` (its Newton iterations and the commit) may
   call, once per trial step (each new ``t`` or ``state_old``, a halved step included),
   ``prepared = force_prepare(model_id, params, state_old, t, u, dudt, vc, d, rho, state_new,
   prep)`` and then, per ``ydot``, ``force_evaluate(model_id, params, prep, u, vc, ydot, d,
   rho, out)`` in place of the kernel; ``prep`` is a scratch of
   :data:`~onbottom.hydro._force_contract.N_FORCE_PREP` float64 slots owned by the solver.
   ``force_prepare`` writes ``state_new`` as the kernel would (it does not depend on
   ``ydot``) and returns True; ``force_evaluate`` writes ``out`` only and gives **bit for
   bit** the kernel's ``out`` (same operations in the same order). A model without this
   form returns False from ``force_prepare`` (a no-op) and the solver calls the kernel
   per evaluation, as before; the one-call kernel stays valid for every model (the pipeline
   FE uses it). Models with the two-stage form: the wake model
   (:func:`~onbottom.hydro._wake_kernel.wake_prepare`,
   :func:`~onbottom.hydro._wake_kernel.wake_evaluate`); registered models use the one-call
   form. Tested: ``tests/unit/test_force_kernels.py`` (two-stage = one-call, bitwise, and
   the twin) and ``tests/conformance/test_force_models.py``.

What the solver does, not the kernel: the added mass on the pipe's own acceleration
(ρ_w π D²/4 · ``added_mass_coefficient``, on the mass side); the DNV-RP-F109 reductions
(F_Y·r_y, F_Z·r_z, ∂F_Y/∂ẏ·r_y; :mod:`onbottom.hydro.reductions`); the choice of the
``params`` row (per kinematics sample when the model's parameters change with the sea state,
blended with the stage weights; see :func:`onbottom.hydro.force_model.parameter_rows`).

Adding a model: a kernel and a class, registered with
:func:`onbottom.hydro.registry.register_force_model` (``kernel=``), which gives the kernel an id
and a ``_KERNELS`` entry (:func:`register_force_kernel`) with no edit of this module
(docs/contributing.md, "Add a force model"). The storm and pipeline
kernels call :func:`force_step_of` with a literal id: they compile the model used only.
"""

from __future__ import annotations

import numpy as np

from onbottom._jit import jitted_only, literal_dispatch, njit, registered_kernel_id
from onbottom.hydro._force_contract import FO_SIZE
from onbottom.hydro._fourier_kernel import fourier_kernel
from onbottom.hydro._morison_kernel import morison_kernel
from onbottom.hydro._wake_kernel import wake_evaluate, wake_kernel, wake_prepare

FORCE_MORISON = 0
FORCE_WAKE = 1  # hydro/_wake_kernel.py, hydro/wake.py
FORCE_FOURIER = 2  # hydro/_fourier_kernel.py, hydro/fourier.py


@jitted_only
def force_step(model_id, params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """Call the kernel of force model ``model_id`` (contract: the module docstring)."""
    if model_id == FORCE_MORISON:
        morison_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)
    elif model_id == FORCE_WAKE:
        wake_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)
    elif model_id == FORCE_FOURIER:
        fourier_kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)
    else:
        # unknown id: NaN forces (the step fails); the Python layer validates ids beforehand
        for i in range(FO_SIZE):
            out[i] = np.nan


force_step_inline = njit(cache=True, inline="always")(force_step.py_func)
""":func:`force_step` inlined into its caller at numba-IR level (same source), for callers that
loop over many nodes (the pipeline FE; a called dispatch costs a call per node,
saved by inlining). The one-node storm kernel keeps the called form (less to compile)."""


_KERNELS = {FORCE_MORISON: morison_kernel, FORCE_WAKE: wake_kernel, FORCE_FOURIER: fourier_kernel}


def force_step_of(model_id, params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """:func:`force_step` that compiles only the kernel of a literal ``model_id``.

    In a kernel whose ``model_id`` is a numba literal (``numba.literally`` at the caller's entry
    point) this is a direct call of that model's kernel (:func:`onbottom._jit.literal_dispatch`),
    so the caller compiles one force model, not all of them. With a non-literal id it is
    :func:`force_step`; in plain Python too.
    """
    kernel = _KERNELS.get(model_id)
    if kernel is None or model_id < FIRST_REGISTERED_ID:
        force_step(model_id, params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)
    else:
        kernel(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)


literal_dispatch(force_step_of, _KERNELS, force_step)


@jitted_only
def no_prepare(params, state_old, t, u, dudt, vc, d, rho, state_new, prep):
    """The once-per-step stage of a model without one (rule 7): nothing; returns False."""
    return False


@jitted_only
def no_evaluate(params, prep, u, vc, ydot, d, rho, out):
    """The per-iterate stage of a model without one (never called: rule 7): NaN forces."""
    for i in range(FO_SIZE):
        out[i] = np.nan


@jitted_only
def force_prepare(model_id, params, state_old, t, u, dudt, vc, d, rho, state_new, prep):
    """Once-per-step stage of force model ``model_id`` (rule 7); False when it has none."""
    if model_id == FORCE_WAKE:
        return wake_prepare(params, state_old, t, u, dudt, vc, d, rho, state_new, prep)
    return False


@jitted_only
def force_evaluate(model_id, params, prep, u, vc, ydot, d, rho, out):
    """Per-iterate stage of force model ``model_id`` after :func:`force_prepare` (rule 7)."""
    if model_id == FORCE_WAKE:
        wake_evaluate(params, prep, u, vc, ydot, d, rho, out)
    else:
        no_evaluate(params, prep, u, vc, ydot, d, rho, out)


_PREPARE = {FORCE_MORISON: no_prepare, FORCE_WAKE: wake_prepare, FORCE_FOURIER: no_prepare}
_EVALUATE = {FORCE_MORISON: no_evaluate, FORCE_WAKE: wake_evaluate, FORCE_FOURIER: no_evaluate}


def force_prepare_of(model_id, params, state_old, t, u, dudt, vc, d, rho, state_new, prep):
    """:func:`force_prepare` compiling only the stage of a literal ``model_id`` (as
    :func:`force_step_of`); in plain Python too (False for a model without the stage)."""
    stage = _PREPARE.get(model_id, no_prepare)
    return stage(params, state_old, t, u, dudt, vc, d, rho, state_new, prep)


def force_evaluate_of(model_id, params, prep, u, vc, ydot, d, rho, out):
    """:func:`force_evaluate` compiling only the stage of a literal ``model_id``."""
    _EVALUATE.get(model_id, no_evaluate)(params, prep, u, vc, ydot, d, rho, out)


literal_dispatch(force_prepare_of, _PREPARE, force_prepare)
literal_dispatch(force_evaluate_of, _EVALUATE, force_evaluate)


FIRST_REGISTERED_ID = 1000
"""Force-model ids from here up belong to kernels added by :func:`register_force_kernel`."""


def register_force_kernel(kernel) -> int:
    """Add force kernel ``kernel`` (contract: the module docstring) to the dispatch table;
    returns its model id.

    The id is derived from the kernel's module, name and source, so that numba's on-disk cache
    of a solver specialised on it (a literal id) never serves another kernel. The storm and
    pipeline kernels (literal ids) then call it directly, with no edit of this module; the
    non-literal :func:`force_step` knows the built-in models only.
    """
    model_id = registered_kernel_id(kernel, FIRST_REGISTERED_ID)
    _KERNELS[model_id] = kernel
    _PREPARE[model_id] = no_prepare  # the one-call form (rule 7)
    _EVALUATE[model_id] = no_evaluate
    return model_id


@jitted_only
def prepared_only(params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out):
    """The one-call slot of a model with the two-stage form in a solver that prepares it
    (:func:`force_step_unprepared_of`): never called there; NaN forces (the step fails)."""
    for i in range(FO_SIZE):
        out[i] = np.nan


class _UnpreparedKernels:
    """The one-call kernels of the models without the two-stage form (rule 7), and
    :func:`prepared_only` for those with it (a ``get`` view of the dispatch tables, so that
    models registered later are included)."""

    def get(self, model_id, default=None):
        kernel = _KERNELS.get(model_id)
        if kernel is None:
            return default
        if _PREPARE.get(model_id, no_prepare) is not no_prepare:
            return prepared_only
        return kernel


def force_step_unprepared_of(
    model_id, params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out
):
    """:func:`force_step_of` for a solver that calls the kernel only where
    :func:`force_prepare_of` returned False (rule 7: a model without the two-stage form).

    With a numba-literal ``model_id`` of a model that has the two-stage form this compiles to
    :func:`prepared_only` (never called: its ``force_prepare_of`` returns True), so such a
    solver does not compile that model's one-call kernel beside its two stages; for any other
    model it is the model's kernel. In plain Python, and with a non-literal id, it is
    :func:`force_step_of` (the one-call kernel of every model).
    """
    force_step_of(model_id, params, state_old, t, u, dudt, vc, ydot, d, rho, state_new, out)


literal_dispatch(force_step_unprepared_of, _UnpreparedKernels(), force_step)
