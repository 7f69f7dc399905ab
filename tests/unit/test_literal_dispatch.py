"""Model dispatch on numba literal ids (issue 33 item 2): the kernels compile only the soil and
force models a run uses, with results identical to the general dispatch."""

from __future__ import annotations

import multiprocessing
import sys

import numpy as np
import pytest
from numba import literally

from onbottom._jit import _compile_lock, call_literal, compile_lock_path, njit
from onbottom.hydro._force_contract import FO_SIZE
from onbottom.hydro._force_dispatch import FORCE_MORISON, force_step, force_step_of
from onbottom.hydro.force_model import N_FORCE_STATE, MorisonLift
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil._dispatch import MODELS_MIXED, lateral_step, lateral_step_node, lateral_step_of
from onbottom.soil.base import OUT_SIZE
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.verley_sotberg import VerleySotberg

PIPE = Pipe(outer_diameter=0.4, submerged_weight=600.0)


@njit(cache=False)  # inspect_llvm: empty for a function loaded from the cache
def _soil_path(model_id, params, state, u, v, out_all):
    """Soil steps along ``u`` through :func:`lateral_step_of` with a literal ``model_id``."""
    literally(model_id)
    trial = np.empty_like(state)
    out = np.empty(OUT_SIZE)
    for k in range(u.shape[0]):
        lateral_step_of(model_id, params, state, u[k], v, trial, out)
        state[:] = trial
        out_all[k] = out


@njit(cache=True)
def _soil_path_node(soil_id, model_id, params, state, u, v, out_all):
    """As :func:`_soil_path` through :func:`lateral_step_node` (pipeline form)."""
    literally(soil_id)
    trial = np.empty_like(state)
    out = np.empty(OUT_SIZE)
    for k in range(u.shape[0]):
        lateral_step_node(soil_id, model_id, params, state, u[k], v, trial, out)
        state[:] = trial
        out_all[k] = out


@njit(cache=False)  # inspect_llvm: empty for a function loaded from the cache
def _force(model_id, params, state, u, out):
    literally(model_id)
    s_new = np.empty_like(state)
    force_step_of(model_id, params, state, 12.5, u, 0.3, 0.2, 0.1, 0.4, 1025.0, s_new, out)


@njit(cache=False)  # inspect_llvm: empty for a function loaded from the cache
def _force_any(model_id, params, state, u, out):
    """:func:`force_step_of` with a non-literal ``model_id`` (the general dispatch)."""
    s_new = np.empty_like(state)
    force_step_of(model_id, params, state, 12.5, u, 0.3, 0.2, 0.1, 0.4, 1025.0, s_new, out)


def _reference(model_id, params, state, u, v):
    """The same path through the general dispatch :func:`lateral_step`."""
    state = state.copy()
    trial = np.empty_like(state)
    ref = np.empty((u.size, OUT_SIZE))
    for k in range(u.size):
        out = np.empty(OUT_SIZE)
        lateral_step(model_id, params, state, u[k], v, trial, out)
        state[:] = trial
        ref[k] = out
    return ref


def _models():
    return [
        CoulombFriction(friction_coefficient=0.4),
        VerleySotberg.silica(PIPE, Sand(submerged_unit_weight=10e3, friction_coefficient=0.6)),
    ]


def test_literal_soil_dispatch_is_bitwise_the_general_one():
    u = 0.02 * np.sin(np.linspace(0.0, 12.0, 40))
    for soil in _models():
        mid = int(soil.model_id)
        params = np.ascontiguousarray(soil.packed_parameters(), dtype=float)
        state0 = np.array(soil.initial_state(), dtype=float)
        ref = _reference(mid, params, state0, u, 500.0)
        for soil_id in (mid, MODELS_MIXED):
            got = np.empty_like(ref)
            call_literal(_soil_path_node, 1, soil_id, mid, params, state0.copy(), u, 500.0, got)
            assert np.array_equal(got, ref, equal_nan=True)
        got = np.empty_like(ref)
        call_literal(_soil_path, 1, mid, params, state0.copy(), u, 500.0, got)
        assert np.array_equal(got, ref, equal_nan=True)


def test_literal_specialisation_compiles_only_the_model_used():
    coulomb = CoulombFriction(friction_coefficient=0.4)
    params = np.ascontiguousarray(coulomb.packed_parameters(), dtype=float)
    state = np.array(coulomb.initial_state(), dtype=float)
    u = np.array([0.0, 0.01])
    out = np.empty((2, OUT_SIZE))
    call_literal(_soil_path, 1, int(coulomb.model_id), params, state, u, 500.0, out)
    (sig,) = [s for s in _soil_path.overloads if getattr(s[0], "literal_value", None) == 0]
    ir = _soil_path.inspect_llvm(sig)
    assert "coulomb_kernel" in ir
    for other in ("verley_sotberg_kernel", "verley_lund_kernel", "vh_parabolic_kernel"):
        assert other not in ir
    # called again: the same specialisation, no new one
    n = len(_soil_path.overloads)
    call_literal(_soil_path, 1, int(coulomb.model_id), params, state, u, 500.0, out)
    assert len(_soil_path.overloads) == n


def test_literal_force_dispatch_is_bitwise_the_general_one():
    fm = MorisonLift()
    params = fm.parameter_table(1.0, 0.0)[0]
    state = np.zeros(N_FORCE_STATE)
    for u in (-1.2, 0.0, 0.7):
        got = np.empty(FO_SIZE)
        call_literal(_force, 1, FORCE_MORISON, params, state, u, got)
        ref = np.empty(FO_SIZE)
        s_new = np.empty_like(state)
        force_step(FORCE_MORISON, params, state, 12.5, u, 0.3, 0.2, 0.1, 0.4, 1025.0, s_new, ref)
        assert np.array_equal(got, ref)
    sig = next(iter(_force.overloads))
    ir = _force.inspect_llvm(sig)
    assert "morison_kernel" in ir and "wake_kernel" not in ir and "fourier_kernel" not in ir


def test_call_literal_calls_a_plain_function():
    def f(a, b, c):
        return a + b * c

    assert call_literal(f, 2, 1, 2, 3) == 7


def test_non_literal_id_takes_the_general_dispatch():
    fm = MorisonLift()
    params = fm.parameter_table(1.0, 0.0)[0]
    state = np.zeros(N_FORCE_STATE)
    got = np.empty(FO_SIZE)
    _force_any(FORCE_MORISON, params, state, 0.7, got)
    ref = np.empty(FO_SIZE)
    force_step(
        FORCE_MORISON, params, state, 12.5, 0.7, 0.3, 0.2, 0.1, 0.4, 1025.0, state.copy(), ref
    )
    assert np.array_equal(got, ref)
    sig = next(iter(_force_any.overloads))
    assert getattr(sig[0], "literal_value", None) is None  # typed as a plain int
    # the general dispatch holds every force model's kernel
    assert "wake_kernel" in _force_any.inspect_llvm(sig)


def _try_lock(path, conn):
    import fcntl

    with open(path, "a") as f:
        try:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            conn.send("blocked")
        else:
            conn.send("acquired")


@pytest.mark.skipif(sys.platform == "win32", reason="fcntl locks: POSIX only")
def test_compile_lock_excludes_other_processes_while_held():
    sig = ("a signature",)
    path = compile_lock_path(_soil_path_node, sig)  # a cached kernel (an uncached one: no lock)
    ctx = multiprocessing.get_context("fork")  # the child only locks a file

    def other():
        a, b = ctx.Pipe()
        p = ctx.Process(target=_try_lock, args=(path, b))
        p.start()
        answer = a.recv()
        p.join()
        return answer

    with _compile_lock(_soil_path_node, sig):
        assert other() == "blocked"
    assert other() == "acquired"


@pytest.mark.skipif(sys.platform == "win32", reason="fcntl locks: POSIX only")
def test_an_uncached_kernel_is_compiled_without_the_lock():
    sig = ("a signature",)
    path = compile_lock_path(_force, sig)
    with _compile_lock(_force, sig):  # _force: cache=False, nothing for others to load
        import fcntl

        with open(path, "a") as f:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)  # free: not held
            fcntl.flock(f, fcntl.LOCK_UN)
