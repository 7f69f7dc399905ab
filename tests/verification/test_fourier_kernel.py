"""Verification of the Fourier force kernel (issue 30 items 2 and 7) against known answers.

* a Fourier table of a pure Morison force reproduces Morison in regular flow (at the table's
  nodes to the fit's accuracy; between nodes within the interpolation error stated below);
* the plain-Python twin (same source, interpreted) to round-off;
* mirror symmetry, bit for bit, from the mirrored state;
* a zero state is valid (quasi-steady law), a steady current gives the steady drag and lift;
* ∂F_Y/∂ẏ equals a finite difference; the memory weight converges as w^k after a change.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from onbottom._jit import pure_python
from onbottom.hydro import _fourier_kernel as FK
from onbottom.hydro._force_contract import FO_DFY_DYD, FO_DFZ_DYD, FO_FY, FO_FZ, N_FORCE_STATE
from onbottom.hydro.fourier import FourierModel
from onbottom.hydro.fourier_fit import synthetic_morison_table

pytestmark = pytest.mark.verification

RHO, D, UM = 1025.0, 0.5, 1.2
CD, CM, CL = 0.7, 3.29, 0.9


@pytest.fixture(scope="module")
def morison_model():
    tab = synthetic_morison_table([5.0, 10.0, 20.0], [0.0, 0.4], cd=CD, cm=CM, cl=CL, harmonics=5)
    return FourierModel(table=tab, drag_coefficient=CD, lift_coefficient=CL)


def morison(u, dudt, vc, ydot):
    w = u + vc
    wr = w - ydot
    fy = 0.5 * RHO * D * CD * wr * abs(wr) + 0.25 * math.pi * RHO * D * D * CM * dudt
    return fy, 0.5 * RHO * D * CL * w * w


def run(kernel, params, t, u, dudt, vc, ydot):
    """Drive the kernel over a record; return out (n, 4) and states (n, 16)."""
    st = np.zeros(N_FORCE_STATE)
    sn = np.zeros(N_FORCE_STATE)
    out = np.zeros(4)
    outs = np.empty((t.size, 4))
    states = np.empty((t.size, N_FORCE_STATE))
    for i in range(t.size):
        kernel(params, st, t[i], u[i], dudt[i], vc[i], ydot[i], D, RHO, sn, out)
        outs[i] = out
        states[i] = sn
        st[:] = sn
    return outs, states


def regular(kc, m, cycles=8, spc=400):
    period = kc * D / UM
    omega = 2.0 * math.pi / period
    t = np.arange(1, cycles * spc) * (period / spc)
    u = UM * np.sin(omega * t)
    dudt = UM * omega * np.cos(omega * t)
    return t, u, dudt, np.full_like(t, m * UM), period


def irregular(seed=3, n=6000, dt=0.02, current=0.25):
    rng = np.random.default_rng(seed)
    om = np.linspace(0.3, 1.6, 40)
    amp = rng.uniform(0.02, 0.09, om.size)
    ph = rng.uniform(0.0, 2.0 * math.pi, om.size)
    t = np.arange(1, n + 1) * dt
    u = (amp * np.cos(np.outer(t, om) + ph)).sum(axis=1)
    dudt = -(amp * om * np.sin(np.outer(t, om) + ph)).sum(axis=1)
    ydot = 0.2 * np.sin(0.37 * t) * np.exp(-((t - 60.0) ** 2) / 400.0)
    return t, u, dudt, np.full_like(t, current), ydot


PHASES = ("time", "flow")


@pytest.mark.parametrize("phase", PHASES)
@pytest.mark.parametrize(("m", "tol"), [(0.0, 1e-12), (0.4, 2e-4)])
def test_morison_table_reproduces_morison_at_a_node(morison_model, m, tol, phase):
    """At a node (K = 10) the only errors are the fit's truncation at N = 5 (M = 0: none,
    W|W| and U̇ are exact in two harmonics) and the O(Δt²) crossing and peak estimates of the
    kernel at Δt = T/400: stated tolerance 2e-4 of the peak |F_Y| with current."""
    params = replace(morison_model, phase=phase).params()
    t, u, dudt, vc, period = regular(10.0, m)
    out, states = run(FK.fourier_kernel, params, t, u, dudt, vc, 0 * t)
    fy, fz = morison(u, dudt, vc, 0.0)
    late = t > 3.0 * period
    assert np.all(states[late, FK.S_MODE] == 1.0)  # the Fourier series, not the fallback
    assert states[-1, FK.S_K] == pytest.approx(10.0, rel=1e-5)
    scale = np.abs(fy).max()
    assert np.abs(out[late, FO_FY] - fy[late]).max() <= tol * scale
    assert np.abs(out[late, FO_FZ] - fz[late]).max() <= tol * scale
    # pipe motion: the relative-velocity correction is Morison's drag difference exactly
    yd = 0.3 * np.cos(0.5 * t)
    out2, _ = run(FK.fourier_kernel, params, t, u, dudt, vc, yd)
    fy2, _ = morison(u, dudt, vc, yd)
    np.testing.assert_allclose(out2[:, FO_FY] - out[:, FO_FY], fy2 - fy, rtol=0, atol=1e-9)


@pytest.mark.parametrize("phase", PHASES)
def test_morison_table_between_nodes_within_interpolation_error(phase):
    """Between nodes the bilinear interpolation is the error: the inertia coefficient
    A₁ = π² C_M / K is linear in 1/K, not K, and lift is quadratic in M. On a grid with
    K ratio 1.1 and M step 0.1 both stay below 0.5 %: stated tolerance 0.5 % of peak F_Y."""
    tab = synthetic_morison_table(
        [8.0, 8.8, 9.68, 10.648], [0.0, 0.1, 0.2, 0.3], cd=CD, cm=CM, cl=CL, harmonics=5
    )
    params = FourierModel(table=tab, phase=phase).params()
    t, u, dudt, vc, period = regular(9.3, 0.15)
    out, _ = run(FK.fourier_kernel, params, t, u, dudt, vc, 0 * t)
    fy, fz = morison(u, dudt, vc, 0.0)
    late = t > 3.0 * period
    scale = np.abs(fy).max()
    assert np.abs(out[late, FO_FY] - fy[late]).max() <= 5e-3 * scale
    assert np.abs(out[late, FO_FZ] - fz[late]).max() <= 5e-3 * scale


@pytest.mark.parametrize("phase", PHASES)
def test_twin_to_round_off(phase):
    params = FourierModel.example(phase=phase).params()
    t, u, dudt, vc, ydot = irregular(n=2500)
    out, st = run(FK.fourier_kernel, params, t, u, dudt, vc, ydot)
    out_py, st_py = run(pure_python(FK.fourier_kernel), params, t, u, dudt, vc, ydot)
    assert st[-1, FK.S_NCROSS] > 10 and np.any(st[:, FK.S_MODE] == 1.0)
    np.testing.assert_allclose(out_py, out, rtol=1e-13, atol=1e-10)
    np.testing.assert_allclose(st_py, st, rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("phase", PHASES)
def test_mirror_symmetry_bit_for_bit(phase):
    params = FourierModel.example(phase=phase).params()
    t, u, dudt, vc, ydot = irregular(seed=5)
    out, st = run(FK.fourier_kernel, params, t, u, dudt, vc, ydot)
    outm, stm = run(FK.fourier_kernel, params, t, -u, -dudt, -vc, -ydot)
    assert st[-1, FK.S_NCROSS] > 20 and np.any(st[:, FK.S_MODE] == 1.0)
    np.testing.assert_array_equal(outm[:, FO_FY], -out[:, FO_FY])
    np.testing.assert_array_equal(outm[:, FO_FZ], out[:, FO_FZ])
    np.testing.assert_array_equal(outm[:, FO_DFY_DYD], out[:, FO_DFY_DYD])
    mirrored = st.copy()
    mirrored[:, [FK.S_SIGN, FK.S_W]] *= -1.0
    np.testing.assert_array_equal(stm, mirrored)


def test_zero_state_is_valid_and_state_old_untouched():
    params = FourierModel.example().params()
    st = np.zeros(N_FORCE_STATE)
    sn = np.full(N_FORCE_STATE, np.nan)
    out = np.full(4, np.nan)
    for u, dudt, vc, yd in [(0.0, 0.0, 0.0, 0.0), (0.7, -0.3, 0.2, 0.1), (-1.0, 2.0, 0.0, -0.5)]:
        FK.fourier_kernel(params, st, 1.0, u, dudt, vc, yd, D, RHO, sn, out)
        assert np.all(np.isfinite(sn)) and np.all(np.isfinite(out))
        assert np.all(st == 0.0)
        fy, fz = morison(u, dudt, vc, yd)  # the quasi-steady law with default coefficients
        assert out[FO_FY] == pytest.approx(fy, rel=1e-14, abs=1e-12)
        assert out[FO_FZ] == pytest.approx(fz, rel=1e-14, abs=1e-12)
        assert out[FO_DFZ_DYD] == 0.0 and sn[FK.S_MODE] == 0.0


def test_steady_current_gives_the_steady_force():
    params = FourierModel.example().params()
    t = np.arange(1, 2001) * 0.05
    v = 0.8
    out, st = run(FK.fourier_kernel, params, t, 0 * t, 0 * t, np.full_like(t, v), 0 * t)
    assert np.all(st[:, FK.S_NCROSS] == 0.0) and np.all(st[:, FK.S_MODE] == 0.0)
    np.testing.assert_allclose(out[:, FO_FY], 0.5 * RHO * D * CD * v * v, rtol=1e-14)
    np.testing.assert_allclose(out[:, FO_FZ], 0.5 * RHO * D * CL * v * v, rtol=1e-14)
    # waves on a current stronger than them (M = 1.5: no reversal): finite and quasi-steady
    tt, u, dudt, vc, _ = regular(10.0, 1.5)
    out, st = run(FK.fourier_kernel, params, tt, u, dudt, vc, 0 * tt)
    fy, fz = morison(u, dudt, vc, 0.0)
    np.testing.assert_allclose(out[:, FO_FY], fy, rtol=1e-13, atol=1e-10)
    np.testing.assert_allclose(out[:, FO_FZ], fz, rtol=1e-13, atol=1e-10)


@pytest.mark.parametrize("phase", PHASES)
def test_derivative_matches_finite_difference(phase):
    params = FourierModel.example(phase=phase).params()
    t, u, dudt, vc, ydot = irregular(n=3000)
    _, st = run(FK.fourier_kernel, params, t, u, dudt, vc, ydot)
    sn = np.zeros(N_FORCE_STATE)
    op, om, o = np.zeros(4), np.zeros(4), np.zeros(4)
    h = 1e-6
    modes = set()
    for i in range(100, t.size, 97):
        s_old = st[i - 1]
        for yd in (-0.4, 0.05, 0.3):
            FK.fourier_kernel(params, s_old, t[i], u[i], dudt[i], vc[i], yd, D, RHO, sn, o)
            modes.add(sn[FK.S_MODE])
            FK.fourier_kernel(params, s_old, t[i], u[i], dudt[i], vc[i], yd + h, D, RHO, sn, op)
            FK.fourier_kernel(params, s_old, t[i], u[i], dudt[i], vc[i], yd - h, D, RHO, sn, om)
            fd = (op[FO_FY] - om[FO_FY]) / (2 * h)
            assert o[FO_DFY_DYD] == pytest.approx(fd, rel=1e-6, abs=1e-6)
            assert o[FO_DFY_DYD] <= 0.0
            assert op[FO_FZ] == om[FO_FZ] and o[FO_DFZ_DYD] == 0.0
    assert modes == {0.0, 1.0}


@pytest.mark.parametrize("w", [0.0, 0.25, 0.6])
def test_memory_weight_converges_geometrically(w):
    """Regular flow whose amplitude steps from U₁ to U₂: each completed half-cycle gives
    a_k = U₂ exactly, so Û_k = U₂ + (Û_0 − U₂) w^k (to the O(Δt²) peak sampling)."""
    params = FourierModel.example(memory_weight=w).params()
    period = 4.0
    spc = 400  # samples land on the peaks: P_k exact
    t = np.arange(1, 12 * spc) * (period / spc)
    amp = np.where(t < 4.0 * period, 1.0, 0.6)
    u = amp * np.sin(2.0 * math.pi * t / period)
    dudt = amp * 2.0 * math.pi / period * np.cos(2.0 * math.pi * t / period)
    _, st = run(FK.fourier_kernel, params, t, u, dudt, 0 * t, 0 * t)
    starts = np.nonzero(np.diff(st[:, FK.S_NCROSS]) > 0)[0] + 1
    um = st[starts, FK.S_UM]
    k_change = int(np.argmax(t[starts] > 4.0 * period + 0.25 * period))
    # the first half-cycle wholly at U₂ ends at the crossing k_change + 1
    u0 = um[k_change]
    for k in range(1, 6):
        expect = 0.6 + (u0 - 0.6) * w**k
        assert um[k_change + k] == pytest.approx(expect, abs=1e-12)
    np.testing.assert_allclose(st[starts[2:], FK.S_TW], period, rtol=1e-9)


def test_blend_of_equal_rows_keeps_the_integer_header():
    """A solver blending two stage rows, (1 − a) r + a r, may move N, n_K, n_M by an ulp; the
    kernel reads them rounded, so the force is unchanged to round-off."""
    row = FourierModel.example().params()
    blended = (1.0 - 0.3) * row + 0.3 * row
    blended[FK.P_NHARM] = np.nextafter(5.0, 0.0)  # the worst case: just below the integer
    t, u, dudt, vc, ydot = irregular(n=1500)
    out, _ = run(FK.fourier_kernel, row, t, u, dudt, vc, ydot)
    out_b, _ = run(FK.fourier_kernel, blended, t, u, dudt, vc, ydot)
    np.testing.assert_allclose(out_b, out, rtol=1e-12, atol=1e-9)
