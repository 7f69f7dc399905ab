"""Paths added for kernel speed (issue 33): the project's njit error model, the V&S memo, and
the views without a reference count (``row_view``, ``borrow``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom._jit import borrow, njit, pure_python, row_view
from onbottom.soil import _verley_sotberg_kernel as VK
from onbottom.soil._path import drive_path
from onbottom.soil.base import OUT_SIZE
from onbottom.soil.verley_sotberg import VerleySotberg


def _divide(a, b):
    return a / b


def test_project_njit_divides_by_zero_as_ieee_not_by_exception():
    f = njit(_divide)
    assert f(1.0, 0.0) == math.inf and f(-1.0, 0.0) == -math.inf
    assert math.isnan(f(0.0, 0.0))
    assert f(3.0, 4.0) == 0.75


def test_project_njit_keeps_an_explicit_error_model():
    g = njit(error_model="python")(_divide)
    with pytest.raises(ZeroDivisionError):
        g(1.0, 0.0)


@pytest.fixture
def calc_model(centrifuge_pipe, calcareous_sand):
    return VerleySotberg.calcareous(centrifuge_pipe, calcareous_sand)


def test_vs_memo_holds_the_power_of_the_penetration_it_was_used_at(calc_model):
    """After any step the memo pair (z, (z/D)^1.25) is consistent, and a state whose memo was
    wiped gives bitwise the same next step (the memo changes no result)."""
    m = calc_model
    p = m.packed_parameters()
    d = p[VK.P_D]
    rng = np.random.default_rng(3)
    n = 400
    u = np.cumsum(rng.normal(0.0, 0.02, n) + 0.05 * (rng.random(n) < 0.03))
    v = np.full(n, 10.5e3)
    hist = np.zeros((n, OUT_SIZE))
    state = drive_path(m.model_id, p, m.initial_state(), u, v, hist)
    assert state[VK.S_MEMO_Z] > 0.0  # the memo was used
    for key, val in ((VK.S_MEMO_Z, VK.S_MEMO_P), (VK.S_MEMO_Z3, VK.S_MEMO_P3)):
        z = state[key]
        assert state[val] == pytest.approx(0.0 if z <= 0.0 else (z / d) ** 1.25, rel=1e-14)
    wiped = state.copy()
    wiped[VK.S_MEMO_Z : VK.S_MEMO_P3 + 1] = 0.0
    a, b = np.zeros_like(state), np.zeros_like(state)
    oa, ob = np.zeros(OUT_SIZE), np.zeros(OUT_SIZE)
    for du in (0.01, -0.2, 0.4):
        m.kernel(p, state, u[-1] + du, 10.5e3, a, oa)
        m.kernel(p, wiped, u[-1] + du, 10.5e3, b, ob)
        np.testing.assert_array_equal(oa, ob)
        np.testing.assert_array_equal(a[: VK.S_MEMO_Z], b[: VK.S_MEMO_Z])
        np.testing.assert_array_equal(a[VK.S_MEMO_P3 + 1 :], b[VK.S_MEMO_P3 + 1 :])


@njit
def _scale(row, w, i):
    for k in range(row.shape[0]):
        row[k] *= w[i]


@njit
def _scale_rows(a, w):
    """Row i of ``a`` times w[i], through row_view rows and a borrowed callee argument."""
    for i in range(a.shape[0]):
        _scale(row_view(a, i), borrow(w), i)
    return row_view(a, a.shape[0] - 1).sum()


_scale_rows_py = pure_python(_scale_rows)


def test_row_view_and_borrow_alias_the_array_in_a_kernel_and_in_python():
    """row_view(a, i) is a[i] and borrow(a) is a (same memory: writes reach the parent), in a
    kernel (views without a reference count) and in plain Python (the twins)."""
    a0 = np.arange(12.0).reshape(4, 3)
    w = np.array([1.0, 2.0, 3.0, 4.0])
    expected = a0 * w[:, None]
    # C-contiguous (the views without a count) and Fortran order (the ordinary view)
    for a in (a0.copy(), np.asfortranarray(a0)):
        assert _scale_rows(a, w) == expected[-1].sum()
        np.testing.assert_array_equal(a, expected)
    a = a0.copy()
    assert _scale_rows_py(a, w) == expected[-1].sum()
    np.testing.assert_array_equal(a, expected)
    assert np.shares_memory(row_view(a0, 2), a0)
    assert borrow(w) is w


def test_vs_kernel_compiles_without_reference_counting():
    """The V&S kernel's compiled function makes no reference-count call (NRT_incref/decref)
    and calls no helper (every helper inlined): the pipeline FE calls it once per node and
    Newton iteration, where those calls cost about a third of it. A helper that takes an
    array, or a called (not inlined) helper whose status check adds an exit, brings them back.
    """
    import re

    f = njit(VK.verley_sotberg_kernel.py_func)  # uncached: numba inspects only fresh code
    p = np.zeros(VK.N_PARAMS)
    s, t, out = np.zeros(VK.N_STATE), np.zeros(VK.N_STATE), np.zeros(OUT_SIZE)
    f(p, s, 0.0, 1.0, t, out)
    ir = f.inspect_llvm(f.signatures[0])
    bodies = {
        re.match(r"define[^@]*@([\w.$]+)", x).group(1): x
        for x in re.split(r"\n(?=define )", ir)
        if x.startswith("define")
    }
    kernel = "21verley_sotberg_kernel"  # the mangled name of the function, not of its module
    (body,) = (x for name, x in bodies.items() if kernel in name and "cpython" not in name)
    calls = set(re.findall(r"call [^@]*@([\w.$]+)", body))
    assert not {c for c in calls if c.startswith("NRT_")}, calls
    assert calls <= {"llvm.fabs.f64", "llvm.pow.f64", "sqrt"} | {
        c for c in calls if c.startswith("llvm.masked.")
    }, calls


def test_vs_kernel_keeps_the_slots_of_a_longer_state_row(calc_model):
    """A state row longer than the model's (the pipeline's nodes on several soil models)
    gives the same step in the model's slots and keeps its other slots."""
    m = calc_model
    p = m.packed_parameters()
    n = VK.N_STATE
    long_old = np.concatenate([m.initial_state(), [7.5, -2.0, np.pi]])
    short_new, out_a = np.zeros(n), np.zeros(OUT_SIZE)
    long_new, out_b = np.full(n + 3, np.nan), np.zeros(OUT_SIZE)
    for du, v in ((0.01, 10.5e3), (0.3, 9e3), (-0.2, -1.0)):
        short_old = long_old[:n].copy()
        VK.verley_sotberg_kernel(p, short_old, short_old[0] + du, v, short_new, out_a)
        VK.verley_sotberg_kernel(p, long_old, long_old[0] + du, v, long_new, out_b)
        np.testing.assert_array_equal(long_new[:n], short_new)
        np.testing.assert_array_equal(long_new[n:], [7.5, -2.0, np.pi])
        np.testing.assert_array_equal(out_a, out_b)
        long_old = long_new.copy()
