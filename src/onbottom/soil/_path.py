"""Generic numba driver: push a lateral-resistance model along a displacement path (private)."""

from __future__ import annotations

import numpy as np

from onbottom._jit import njit
from onbottom.soil._dispatch import lateral_step


@njit(cache=True)
def drive_path(model_id, params, state0, y_path, v_path, history):
    """Drive model ``model_id`` along prescribed displacements, committing every point.

    history: float64[n, OUT_SIZE], written with the kernel output at each point.
    Returns the final committed state.
    """
    state = state0.copy()
    trial = np.empty_like(state)
    out = np.empty(history.shape[1])
    for i in range(y_path.shape[0]):
        lateral_step(model_id, params, state, y_path[i], v_path[i], trial, out)
        state[:] = trial
        history[i, :] = out
    return state


def drive_path_py(kernel, params, state0, y_path, v_path, history):
    """Plain-Python twin of :func:`drive_path` taking a (Python) kernel function."""
    state = np.array(state0, dtype=float)
    trial = np.empty_like(state)
    out = np.empty(history.shape[1])
    for i in range(len(y_path)):
        kernel(params, state, float(y_path[i]), float(v_path[i]), trial, out)
        state[:] = trial
        history[i, :] = out
    return state
