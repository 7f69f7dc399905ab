"""Wake force model: Morison limit, steady current, twin, derivative, mirror symmetry, Δt."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.hydro import _morison_kernel as mk
from onbottom.hydro import _wake_kernel as wk
from onbottom.hydro._force_contract import (
    FO_DFY_DYD,
    FO_DFZ_DYD,
    FO_FY,
    FO_FZ,
    FO_SIZE,
    N_FORCE_STATE,
)
from onbottom.hydro._wake_twin import wake_kernel_py
from onbottom.hydro.wake import WakeModel
from onbottom.hydro.wake_calibration import regular_peak_coefficients

pytestmark = pytest.mark.verification

RHO = 1025.0
D = 0.8


def _record(seed: int, n: int = 1500, current: float = 0.2):
    """An irregular flow with many reversals, a current and a random pipe velocity."""
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.02, 0.12, n))
    w = rng.uniform(0.3, 1.5, 6)
    a = rng.uniform(0.1, 0.5, 6)
    ph = rng.uniform(0.0, 2.0 * math.pi, 6)
    u = (a * np.sin(np.outer(t, w) + ph)).sum(axis=1)
    dudt = (a * w * np.cos(np.outer(t, w) + ph)).sum(axis=1)
    ydot = 0.05 * rng.standard_normal(n)
    return t, u, dudt, np.full(n, current), ydot


def _run(kernel, params, t, u, dudt, vc, ydot, state0=None):
    s_old = np.zeros(N_FORCE_STATE) if state0 is None else state0.copy()
    s_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    outs = np.empty((t.size, FO_SIZE))
    states = np.empty((t.size, N_FORCE_STATE))
    for i in range(t.size):
        kernel(params, s_old, t[i], u[i], dudt[i], vc[i], ydot[i], D, RHO, s_new, out)
        outs[i] = out
        states[i] = s_new
        s_old[:] = s_new
    return outs, states


@pytest.mark.parametrize("lift_relative", [False, True])
def test_wake_off_equals_morison_bit_for_bit(lift_relative):
    """α_w = ΔC_D = ΔC_L = 0: out[0:4] identical to the Morison kernel's, step by step."""
    m = WakeModel(
        cd_steady=0.7, cl_steady=0.9, cm=3.29, lift_relative_velocity=lift_relative
    ).without_wake()
    t, u, dudt, vc, ydot = _record(1)
    outs, states = _run(wk.wake_kernel, m.parameters(), t, u, dudt, vc, ydot)
    assert states[-1, wk.S_N_REVERSALS] >= 10  # the history did run
    p = np.zeros(mk.N_PARAMS)
    p[mk.P_CD], p[mk.P_CM], p[mk.P_CL] = 0.7, 3.29, 0.9
    p[mk.P_LIFT_REL] = 1.0 if lift_relative else 0.0
    ref, _ = _run(mk.morison_kernel, p, t, u, dudt, vc, ydot)
    np.testing.assert_array_equal(outs, ref)


def test_steady_current_gives_steady_drag_and_lift_only():
    m = WakeModel()
    n = 400
    t = np.linspace(0.0, 200.0, n)
    vc = 0.7
    outs, states = _run(
        wk.wake_kernel, m.parameters(), t, np.zeros(n), np.zeros(n), np.full(n, vc), np.zeros(n)
    )
    assert np.all(outs[:, FO_FY] == 0.5 * RHO * D * m.cd_steady * vc * vc)
    assert np.all(outs[:, FO_FZ] == 0.5 * RHO * D * m.cl_steady * vc * vc)
    assert np.all(states[:, wk.S_N_REVERSALS] == 0.0)
    assert states[-1, wk.S_DIST] == pytest.approx(vc * 200.0, rel=1e-12)


def test_strong_following_current_recovers_steady_coefficients():
    """M = 10: slacks of depth 2/(1 + M) = 0.18 < r_0 make no wake: Morison, bit for bit."""
    m = WakeModel()
    t = np.linspace(0.0, 100.0, 2001)
    u = np.sin(2.0 * math.pi * t / 8.0)
    dudt = 2.0 * math.pi / 8.0 * np.cos(2.0 * math.pi * t / 8.0)
    vc = np.full(t.size, 10.0)
    outs, states = _run(wk.wake_kernel, m.parameters(), t, u, dudt, vc, np.zeros(t.size))
    ref, _ = _run(wk.wake_kernel, m.without_wake().parameters(), t, u, dudt, vc, np.zeros(t.size))
    assert np.all(states[:, wk.S_N_REVERSALS] == 0.0)
    assert np.all(states[:, wk.S_STRENGTH] == 0.0)
    np.testing.assert_array_equal(outs, ref)


def test_following_current_wake_fades_with_m():
    """M >= 1: no reversal, but one slack per period makes a wake; its share falls with M.

    Peak C_Y of the regular protocol over the steady-coefficient value at K* = 20: above 1
    for M* = 1, 2, 5, decreasing, and exactly the steady value from 2/(1 + M*) <= r_0 on.
    """
    m = WakeModel()
    k = np.full(5, 20.0)
    mm = np.array([1.0, 2.0, 5.0, 9.5, 20.0])
    cy, _ = regular_peak_coefficients(m, k, mm)
    cy0, _ = regular_peak_coefficients(m.without_wake(), k, mm)
    excess = cy / cy0
    assert excess[0] > excess[1] > excess[2] > 1.0
    assert excess[3] == 1.0 and excess[4] == 1.0


@pytest.mark.parametrize("lift_relative", [False, True])
def test_twin_to_round_off(lift_relative):
    m = WakeModel(lift_relative_velocity=lift_relative)
    t, u, dudt, vc, ydot = _record(2)
    o1, s1 = _run(wk.wake_kernel, m.parameters(), t, u, dudt, vc, ydot)
    o2, s2 = _run(wake_kernel_py, m.parameters(), t, u, dudt, vc, ydot)
    assert s1[-1, wk.S_N_REVERSALS] >= 10
    np.testing.assert_allclose(o1, o2, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(s1, s2, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("lift_relative", [False, True])
def test_derivative_matches_finite_difference(lift_relative):
    """∂F_Y/∂ẏ, ∂F_Z/∂ẏ from the same state_old against central differences in ẏ."""
    m = WakeModel(lift_relative_velocity=lift_relative)
    p = m.parameters()
    t, u, dudt, vc, ydot = _record(3, n=600)
    _, states = _run(wk.wake_kernel, p, t, u, dudt, vc, ydot)
    s_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    h = 1e-6
    checked = 0
    for i in range(100, 600, 7):
        s_old = states[i - 1]
        f = []
        for yd in (ydot[i] + h, ydot[i] - h):
            wk.wake_kernel(p, s_old, t[i], u[i], dudt[i], vc[i], yd, D, RHO, s_new, out)
            f.append(out.copy())
        wk.wake_kernel(p, s_old, t[i], u[i], dudt[i], vc[i], ydot[i], D, RHO, s_new, out)
        dfy = (f[0][FO_FY] - f[1][FO_FY]) / (2 * h)
        dfz = (f[0][FO_FZ] - f[1][FO_FZ]) / (2 * h)
        assert out[FO_DFY_DYD] <= 0.0
        assert out[FO_DFY_DYD] == pytest.approx(dfy, rel=1e-6, abs=1e-3)
        assert out[FO_DFZ_DYD] == pytest.approx(dfz, rel=1e-6, abs=1e-3)
        checked += 1
    assert checked > 50


def test_mirror_symmetry():
    """(u, U̇, V, ẏ) → −(…): F_Y → −F_Y, F_Z unchanged, odd state slots negated."""
    m = WakeModel(lift_relative_velocity=True)
    t, u, dudt, vc, ydot = _record(4)
    o1, s1 = _run(wk.wake_kernel, m.parameters(), t, u, dudt, vc, ydot)
    o2, s2 = _run(wk.wake_kernel, m.parameters(), t, -u, -dudt, -vc, -ydot)
    np.testing.assert_array_equal(o2[:, FO_FY], -o1[:, FO_FY])
    np.testing.assert_array_equal(o2[:, FO_DFY_DYD], o1[:, FO_DFY_DYD])
    np.testing.assert_array_equal(o2[:, FO_FZ], o1[:, FO_FZ])
    np.testing.assert_array_equal(o2[:, FO_DFZ_DYD], -o1[:, FO_DFZ_DYD])
    odd = [wk.S_Q, wk.S_SIGN, wk.S_W_END]
    even = [i for i in range(N_FORCE_STATE) if i not in odd]
    np.testing.assert_array_equal(s2[:, odd], -s1[:, odd])
    np.testing.assert_array_equal(s2[:, even], s1[:, even])


def test_zero_state_and_finite_outputs():
    """A zero state is valid at any start time; finite inputs give finite outputs."""
    m = WakeModel()
    rng = np.random.default_rng(5)
    s_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    for _ in range(200):
        u, dudt, vc, ydot = rng.uniform(-3, 3, 4)
        t0 = rng.uniform(0.0, 1e4)
        wk.wake_kernel(m.parameters(), np.zeros(N_FORCE_STATE), t0, u, dudt, vc, ydot, D, RHO,
                       s_new, out)  # fmt: skip
        assert np.all(np.isfinite(out)) and np.all(np.isfinite(s_new))
        assert s_new[wk.S_DIST] == 0.0 and s_new[wk.S_WAKE0] == 0.0
    t, u, dudt, vc, ydot = _record(6, current=0.0)
    outs, states = _run(wk.wake_kernel, m.parameters(), t, 10 * u, dudt, vc, ydot)
    assert np.all(np.isfinite(outs)) and np.all(np.isfinite(states))


def test_repeated_evaluation_from_one_state_is_pure():
    """The solver may evaluate the same state_old at several t, ẏ: same inputs, same bits."""
    m = WakeModel()
    t, u, dudt, vc, ydot = _record(7, n=300)
    _, states = _run(wk.wake_kernel, m.parameters(), t, u, dudt, vc, ydot)
    s_old = states[150].copy()
    keep = s_old.copy()
    a_s, a_o = np.zeros(N_FORCE_STATE), np.zeros(FO_SIZE)
    b_s, b_o = np.zeros(N_FORCE_STATE), np.zeros(FO_SIZE)
    p = m.parameters()
    wk.wake_kernel(p, s_old, t[151], u[151], dudt[151], vc[151], 0.3, D, RHO, a_s, a_o)
    wk.wake_kernel(p, s_old, t[151] + 0.01, u[151], dudt[151], vc[151], -0.2, D, RHO, b_s, b_o)
    wk.wake_kernel(p, s_old, t[151], u[151], dudt[151], vc[151], 0.3, D, RHO, b_s, b_o)
    np.testing.assert_array_equal(a_s, b_s)
    np.testing.assert_array_equal(a_o, b_o)
    np.testing.assert_array_equal(s_old, keep)


@pytest.mark.parametrize("m_star", [0.0, 0.3, 0.8, 2.0])
def test_peak_converges_with_sample_interval(m_star):
    """Per-cycle peaks of the calibration protocol: error falls at least as fast as Δt.

    Reference: 25 600 samples per period. Over each two fourfold refinements the largest
    relative error over K* = 2.5–100 must fall by more than 16 (first order overall). One
    fourfold step alone is not monotone: the maximum of a sampled curve depends on where the
    samples fall on it (with the wake's onset the peak can sit near the start of a segment),
    so the error of one refinement can stall while the next one drops by a hundred.
    A slack is placed at the sample of the minimum of |U + V|: first order too.
    """
    m = WakeModel()
    k = np.array([2.5, 5.0, 10.0, 20.0, 40.0, 100.0])
    ref = np.array(regular_peak_coefficients(m, k, m_star, steps_per_cycle=25600))
    errs = [
        np.abs(np.array(regular_peak_coefficients(m, k, m_star, steps_per_cycle=n)) / ref - 1).max()
        for n in (100, 400, 1600, 6400)
    ]
    assert errs[2] < errs[0] / 16.0
    assert errs[3] < errs[1] / 16.0
    assert errs[3] < 1e-5


def test_fit_recovers_known_constants():
    """Tables made by the model itself are fitted back to the constants that made them."""
    from onbottom.hydro.wake_calibration import fit_wake_model

    truth = WakeModel(wake_ratio=0.35, lift_excess=2.2, drag_relaxation=8.0)
    k = np.array([2.5, 5.0, 10.0, 20.0, 40.0, 100.0])
    m = np.array([0.0, 0.2, 0.5, 0.8])
    kk, mm = np.meshgrid(k, m)
    cy, cz = regular_peak_coefficients(truth, kk, mm, steps_per_cycle=200)
    fit = fit_wake_model(
        k,
        m,
        cy,
        cz,
        start=WakeModel(wake_ratio=0.6, lift_excess=1.0, drag_relaxation=3.0),
        free=("wake_ratio", "lift_excess", "drag_relaxation"),
        steps_per_cycle=200,
    )
    assert fit.model.wake_ratio == pytest.approx(0.35, rel=1e-4)
    assert fit.model.lift_excess == pytest.approx(2.2, rel=1e-4)
    assert fit.model.drag_relaxation == pytest.approx(8.0, rel=1e-4)
    assert fit.rms_log < 1e-8


@pytest.mark.parametrize("lift_relative", [False, True])
def test_two_stage_form_equals_one_call_bit_for_bit(lift_relative):
    """Contract rule 7: wake_prepare once per step, then wake_evaluate at several ẏ, gives the
    state and the outputs of wake_kernel at each ẏ bit for bit; the twins' two stages equal
    the kernel to round-off."""
    from onbottom.hydro._force_contract import N_FORCE_PREP
    from onbottom.hydro._wake_twin import wake_evaluate_py, wake_prepare_py

    m = WakeModel(lift_relative_velocity=lift_relative)
    p = m.parameters()
    t, u, dudt, vc, ydot = _record(4, n=800)
    _, states = _run(wk.wake_kernel, p, t, u, dudt, vc, ydot)
    assert states[-1, wk.S_N_REVERSALS] >= 10
    prep, prep_py = np.zeros(N_FORCE_PREP), np.zeros(N_FORCE_PREP)
    s1, s2, s3 = (np.zeros(N_FORCE_STATE) for _ in range(3))
    o1, o2, o3 = (np.zeros(FO_SIZE) for _ in range(3))
    for i in range(1, t.size):
        s_old = states[i - 1]
        assert wk.wake_prepare(p, s_old, t[i], u[i], dudt[i], vc[i], D, RHO, s2, prep)
        wake_prepare_py(p, s_old, t[i], u[i], dudt[i], vc[i], D, RHO, s3, prep_py)
        for yd in (ydot[i], ydot[i] + 0.3, -0.7):
            wk.wake_kernel(p, s_old, t[i], u[i], dudt[i], vc[i], yd, D, RHO, s1, o1)
            wk.wake_evaluate(p, prep, u[i], vc[i], yd, D, RHO, o2)
            wake_evaluate_py(p, prep_py, u[i], vc[i], yd, D, RHO, o3)
            assert np.array_equal(o1, o2)
            np.testing.assert_allclose(o3, o1, rtol=1e-12, atol=1e-9)
        assert np.array_equal(s1, s2)
        np.testing.assert_allclose(s3, s1, rtol=1e-12, atol=1e-12)
