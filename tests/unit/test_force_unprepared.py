"""force_step_unprepared_of (hydro.kernel_contract): the one-call slot of a solver that prepares
models with the two-stage form (rule 7) compiles no one-call kernel for them."""

from __future__ import annotations

import numpy as np
from numba import literally

from onbottom._jit import call_literal, njit
from onbottom.hydro.force_model import MorisonLift
from onbottom.hydro.kernel_contract import (
    FO_SIZE,
    FORCE_MORISON,
    FORCE_WAKE,
    N_FORCE_PREP,
    N_FORCE_STATE,
    force_evaluate_of,
    force_prepare_of,
    force_step_of,
    force_step_unprepared_of,
)
from onbottom.hydro.wake import WakeModel

ARGS = (2.0, 0.8, -0.3, 0.2, -0.1, 0.4, 1025.0)  # t, u, dudt, vc, ydot, d, rho


@njit(cache=False)
def _unprepared(force_id, params, state_old, state_new, out):
    literally(force_id)
    t, u, dudt, vc, ydot, d, rho = 2.0, 0.8, -0.3, 0.2, -0.1, 0.4, 1025.0
    force_step_unprepared_of(force_id, params, state_old, t, u, dudt, vc, ydot, d, rho,
                             state_new, out)  # fmt: skip


@njit(cache=False)
def _staged(force_id, params, state_old, state_new, prep, out):
    literally(force_id)
    t, u, dudt, vc, ydot, d, rho = 2.0, 0.8, -0.3, 0.2, -0.1, 0.4, 1025.0
    if force_prepare_of(force_id, params, state_old, t, u, dudt, vc, d, rho, state_new, prep):
        force_evaluate_of(force_id, params, prep, u, vc, ydot, d, rho, out)
        return True
    return False


def _state(model, params):
    """The committed state after an evaluation at t = 1 s in the opposite flow (the step to
    t = 2 s is then a flow reversal: the wake model's event branch)."""
    new, out = np.zeros(N_FORCE_STATE), np.zeros(FO_SIZE)
    force_step_of(model, params, np.zeros(N_FORCE_STATE), 1.0, -0.9, 0.5, 0.2, 0.0, 0.4,
                  1025.0, new, out)  # fmt: skip
    return new


def _one_call(model, params):
    out, new = np.zeros(FO_SIZE), np.zeros(N_FORCE_STATE)
    t, u, dudt, vc, ydot, d, rho = ARGS
    force_step_of(model, params, _state(model, params), t, u, dudt, vc, ydot, d, rho, new, out)
    return out, new


def test_model_without_stages_compiles_its_kernel():
    params = np.ascontiguousarray(MorisonLift().parameter_table(1.0, 0.0)[0])
    out, new = np.zeros(FO_SIZE), np.zeros(N_FORCE_STATE)
    call_literal(_unprepared, 1, FORCE_MORISON, params, _state(FORCE_MORISON, params), new, out)
    ref_out, ref_new = _one_call(FORCE_MORISON, params)
    assert np.isfinite(out).all()
    np.testing.assert_array_equal(out, ref_out)
    np.testing.assert_array_equal(new, ref_new)
    prep = np.zeros(N_FORCE_PREP)
    assert not call_literal(
        _staged, 1, FORCE_MORISON, params, _state(FORCE_MORISON, params), new, prep, out
    )


def test_model_with_stages_compiles_the_stub_and_its_stages_give_the_kernel():
    params = np.ascontiguousarray(WakeModel().parameter_table(1.0, 0.0)[0])
    out, new = np.zeros(FO_SIZE), np.zeros(N_FORCE_STATE)
    call_literal(_unprepared, 1, FORCE_WAKE, params, _state(FORCE_WAKE, params), new, out)
    assert np.isnan(out).all()  # the stub: never called where force_prepare_of returns True
    ref_out, ref_new = _one_call(FORCE_WAKE, params)
    assert np.isfinite(ref_out).all()
    prep, out2, new2 = np.zeros(N_FORCE_PREP), np.zeros(FO_SIZE), np.zeros(N_FORCE_STATE)
    assert call_literal(
        _staged, 1, FORCE_WAKE, params, _state(FORCE_WAKE, params), new2, prep, out2
    )
    np.testing.assert_array_equal(out2, ref_out)  # rule 7: bit for bit the one-call kernel
    np.testing.assert_array_equal(new2, ref_new)


def test_plain_python_is_the_one_call_kernel_of_every_model():
    params = np.ascontiguousarray(WakeModel().parameter_table(1.0, 0.0)[0])
    out, new = np.zeros(FO_SIZE), np.zeros(N_FORCE_STATE)
    t, u, dudt, vc, ydot, d, rho = ARGS
    force_step_unprepared_of(
        FORCE_WAKE, params, _state(FORCE_WAKE, params), t, u, dudt, vc, ydot, d, rho, new, out
    )
    ref_out, ref_new = _one_call(FORCE_WAKE, params)
    np.testing.assert_array_equal(out, ref_out)
    np.testing.assert_array_equal(new, ref_new)
