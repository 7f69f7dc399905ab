"""Numba kernel: a force model's loads on a fixed pipe along a sampled flow record (private).

The public entry is :func:`onbottom.hydro.fixed_pipe.fixed_pipe_loads`. The loop evaluates the
force model (a literal model id: only that model is compiled) at every flow sample with the
pipe at rest (ẏ = 0), from a zero state, committing the state after each sample as a solver
does after an accepted step. A model with the two-stage form (rule 7 of
:mod:`onbottom.hydro._force_dispatch`: the wake model) is evaluated through its two stages,
bit for bit its one-call kernel, so that this kernel and the storm kernel share the compiled
stages; any other model through its one-call kernel.
Plain-Python twin: ``fixed_pipe_record.py_func`` with ``onbottom._jit.pure_python``; the
Morison model is checked against the closed form in ``tests/unit/test_fixed_pipe.py``.
"""

from __future__ import annotations

import numpy as np
from numba import literally

from onbottom._jit import njit
from onbottom.hydro._force_contract import FO_FY, FO_FZ, FO_SIZE, N_FORCE_PREP, N_FORCE_STATE
from onbottom.hydro.kernel_contract import (
    force_evaluate_of,
    force_prepare_of,
    force_step_unprepared_of,
)


@njit(cache=True)
def fixed_pipe_record(force_id, rows, dt, u, dudt, vc, d, rho, fy, fz):
    """F_Y, F_Z [N/m] (before reductions) of force model ``force_id`` at every sample.

    ``rows``: the model's parameter rows (one, or one per sample); ``dt`` the sample interval
    [s] (sample j at t = j·dt); ``u``, ``dudt`` wave velocity [m/s] and acceleration [m/s²]
    normal to the pipe; ``vc`` the current [m/s], signed; ``d`` [m]; ``rho`` [kg/m³]. Writes
    ``fy`` and ``fz``.
    """
    literally(force_id)  # compile only the force model used
    state_old = np.zeros(N_FORCE_STATE)
    state_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    prep = np.zeros(N_FORCE_PREP)
    nr = rows.shape[0]
    for i in range(u.shape[0]):
        r = i if nr > 1 else 0
        if r >= nr:
            r = nr - 1
        t = i * dt
        if force_prepare_of(force_id, rows[r], state_old, t, u[i], dudt[i], vc, d, rho,
                            state_new, prep):  # fmt: skip
            force_evaluate_of(force_id, rows[r], prep, u[i], vc, 0.0, d, rho, out)
        else:
            force_step_unprepared_of(
                force_id, rows[r], state_old, t, u[i], dudt[i], vc, 0.0, d, rho, state_new, out
            )
        fy[i] = out[FO_FY]
        fz[i] = out[FO_FZ]
        for k in range(N_FORCE_STATE):
            state_old[k] = state_new[k]
