"""Verification of the pipe-section solver: closed-form stick–slip, time-step convergence,
mirror symmetry (docs/theory/section_dynamics.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics.centrifuge import build_programme, build_soil, get_test
from onbottom.dynamics.programmes import from_arrays
from onbottom.dynamics.section import SolverSettings, simulate_section
from onbottom.soil.coulomb import CoulombFriction

pytestmark = pytest.mark.verification

MU, V, DELTA, M = 0.5, 1000.0, 1.0e-3, 1000.0  # μV = 500 N/m, k = μV/δ = 5e5 N/m²


def _coulomb():
    return CoulombFriction(friction_coefficient=MU, mobilisation_displacement=DELTA)


def test_stick_below_friction_no_creep():
    # H ramps slowly to 0.8 μV and is held for a long time: the pipe stays on its elastic
    # mobilisation branch u = H/k (<= δ) and does not creep.
    k = MU * V / DELTA
    prog = from_arrays([0.0, 20.0, 2000.0], [0.0, 400.0, 400.0], [V, V, V])
    res = simulate_section(prog, _coulomb(), mass=M, settings=SolverSettings(dt_max=0.5))
    u = res.data["y"].values
    t = res.data["time"].values
    assert res.success and res.status == 1
    assert np.max(np.abs(u)) <= DELTA
    assert u[-1] == pytest.approx(400.0 / k, rel=1e-9)
    # no creep over the hold: u at t = 100 s and at t = 2000 s agree to round-off
    assert abs(np.interp(100.0, t, u) - u[-1]) < 1e-12


@pytest.mark.parametrize("integrator", ["newmark", "backward_euler"])
def test_slip_above_friction_matches_closed_form(integrator):
    # Constant H = 800 > μV from t = 0. Mobilisation (elastic) phase: u = (H/k)(1 − cos ωt)
    # until u = δ at t_m; then sliding at constant friction: ü = (H − μV)/m, i.e.
    # u = δ + v_m (t − t_m) + ½ (H − μV)/m (t − t_m)².
    h = 800.0
    k = MU * V / DELTA
    om = math.sqrt(k / M)
    t_m = math.acos(1.0 - k * DELTA / h) / om
    v_m = h / k * om * math.sin(om * t_m)
    a = (h - MU * V) / M
    prog = from_arrays([0.0, 10.0], [h, h], [V, V])
    dt = 2e-4 if integrator == "newmark" else 2e-5
    s = SolverSettings(integrator=integrator, dt_max=dt, max_displacement_increment=0.05)
    res = simulate_section(prog, _coulomb(), mass=M, settings=s)
    t = res.data["time"].values
    u = res.data["y"].values
    exact = DELTA + v_m * (t - t_m) + 0.5 * a * (t - t_m) ** 2
    late = t > 1.0
    np.testing.assert_allclose(u[late], exact[late], rtol=2e-4)
    # after mobilisation the pipe accelerates at (H − μV)/m = 0.3 m/s²
    udot = res.data["y_dot"].values
    i1 = np.searchsorted(t, 1.0)
    assert (udot[-1] - udot[i1]) / (t[-1] - t[i1]) == pytest.approx(a, rel=1e-3)
    # the friction force is exactly μV while sliding
    np.testing.assert_allclose(res.data["F_friction"].values[late], MU * V, rtol=1e-12)


def _constant_slip_error(dt, integrator):
    h = 800.0
    k = MU * V / DELTA
    om = math.sqrt(k / M)
    t_m = math.acos(1.0 - k * DELTA / h) / om
    v_m = h / k * om * math.sin(om * t_m)
    exact = DELTA + v_m * (10.0 - t_m) + 0.5 * (h - MU * V) / M * (10.0 - t_m) ** 2
    prog = from_arrays([0.0, 10.0], [h, h], [V, V])
    s = SolverSettings(integrator=integrator, dt_max=dt, max_displacement_increment=1.0)
    res = simulate_section(prog, _coulomb(), mass=M, settings=s)
    return abs(float(res.data["y"].values[-1]) - exact)


def test_time_step_convergence_against_closed_form():
    dts = [4e-3, 2e-3, 1e-3, 5e-4]
    be = [_constant_slip_error(dt, "backward_euler") for dt in dts]
    ratios = [be[i] / be[i + 1] for i in range(len(be) - 1)]
    # backward Euler is first order: the error halves with the step
    assert all(1.8 < r < 2.2 for r in ratios), (be, ratios)
    # average acceleration (second order away from the stick–slip kink) is far more accurate
    nm = [_constant_slip_error(dt, "newmark") for dt in dts[:2]]
    assert nm[1] < nm[0] and nm[1] < be[1] / 50.0


def _sine_run(dt):
    # H = 700 sin(2πt/10) with μV = 500: stick–slip in both directions, 2 cycles
    t = np.linspace(0.0, 20.0, 2001)
    prog = from_arrays(t, 700.0 * np.sin(2 * np.pi * t / 10.0), np.full(t.size, V))
    s = SolverSettings(dt_max=dt, max_displacement_increment=1.0)
    res = simulate_section(prog, _coulomb(), mass=M, settings=s)
    assert res.success
    return float(res.data["y"].values[-1])


def test_time_step_convergence_stick_slip_cycles():
    ref = _sine_run(1.5625e-5)
    errs = [abs(_sine_run(dt) - ref) for dt in (1e-3, 5e-4, 2.5e-4)]
    assert errs[0] > errs[1] > errs[2]
    assert errs[0] / errs[2] > 3.0, errs


def test_mirror_symmetry_verley_sotberg():
    # reversing the horizontal load mirrors the response: u → −u, w unchanged
    test = get_test("Inclined 1")
    prog = build_programme(test)
    soil = build_soil(test)
    mirrored = from_arrays(
        prog.time,
        -prog.horizontal_load,
        prog.vertical_load,
        installation_load=prog.installation_load,
        cycle_period=prog.cycle_period,
    )
    kw = {"mass": 3700.0, "displacement_limit": 3.0}
    a = simulate_section(prog, soil, **kw)
    b = simulate_section(mirrored, soil, **kw)
    assert a.n_steps == b.n_steps
    np.testing.assert_allclose(b.data["y"].values, -a.data["y"].values, atol=1e-9)
    np.testing.assert_allclose(b.data["z"].values, a.data["z"].values, atol=1e-12)
    np.testing.assert_allclose(b.data["F_soil"].values, -a.data["F_soil"].values, atol=1e-6)
    assert a.cycles_to_limit == pytest.approx(b.cycles_to_limit, abs=1e-12)
