"""Unit tests: the parabolic V–H test model of the two-DOF soil contract (hand calculations,
twin, consistent coupling tangent, reduction to Coulomb, inputs)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Rock, Sand
from onbottom.soil._path import drive_path, drive_path_py
from onbottom.soil._vh_parabolic_kernel import (
    S_VP,
    flow_direction,
    flow_direction_py,
    yield_function,
    yield_function_py,
)
from onbottom.soil.base import (
    OUT2_DH_DV,
    OUT2_DZ_DV,
    OUT2_DZ_DY,
    OUT2_SIZE,
    OUT_DISSIPATED,
    OUT_R,
    OUT_REGION,
    OUT_SIZE,
    OUT_STORED,
    OUT_TANGENT,
    OUT_Z,
    S_FRICTION,
    S_Z,
    ForceResultantModel,
)
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.factory import lateral_model
from onbottom.soil.vh_parabolic import ParabolicVH


def _drive(model, u, v, width=OUT2_SIZE):
    h = np.zeros((len(u), width))
    s = drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h, s


def test_yield_surface_and_flow_direction_by_hand():
    # μ = 0.6, V_p = 4000: at V = 1000, C = 0.6·1000·(1 − 0.25) = 450 N/m
    for f, g in ((yield_function, flow_direction), (yield_function_py, flow_direction_py)):
        assert f(450.0, 1000.0, 4000.0, 0.6) == pytest.approx(0.0, abs=1e-12)
        assert f(-500.0, 1000.0, 4000.0, 0.6) == pytest.approx(50.0)
        assert f(0.0, 2000.0, 4000.0, 0.6) == pytest.approx(-600.0)  # peak H = μV_p/4
        # ∂g/∂V = −μ′(1 − 2V/V_p): heave below V_p/2, none at V_p/2, penetration above
        assert g(1000.0, 4000.0, 0.3) == pytest.approx(-0.15)
        assert g(2000.0, 4000.0, 0.3) == pytest.approx(0.0)
        assert g(3000.0, 4000.0, 0.3) == pytest.approx(0.15)
        assert g(1000.0, math.inf, 0.3) == pytest.approx(-0.3)


def test_elastic_then_plastic_flow_by_hand():
    # μ = 0.6, μ′ = 0.3, V_p = 4000, k_p = 1e5, δ = 1 mm, V = 1000: C = 450, k = μV/δ = 6e5
    m = ParabolicVH(
        friction_coefficient=0.6,
        bearing_capacity=4000.0,
        flow_coefficient=0.3,
        hardening_stiffness=1.0e5,
    )
    h, s = _drive(m, np.array([0.0005, 0.002]), np.full(2, 1000.0))
    # elastic: H = kΔy = 300, z = 0
    assert h[0, OUT_R] == pytest.approx(300.0)
    assert h[0, OUT_TANGENT] == pytest.approx(6.0e5)
    assert h[0, OUT_Z] == 0.0
    # plastic: H_tr = 300 + 6e5·0.0015 = 1200 > C: H = 450, Δλ = 750/6e5 = 1.25e-3,
    # Δz = Δλ·(−0.3·(1 − 0.5)) = −1.875e-4 (heave), V_p = 4000 − 1e5·1.875e-4 = 3981.25
    assert h[1, OUT_R] == pytest.approx(450.0)
    assert h[1, OUT_TANGENT] == 0.0
    assert h[1, OUT_Z] == pytest.approx(-1.875e-4)
    assert h[1, OUT_REGION] == 1.0
    assert s[S_VP] == pytest.approx(3981.25)
    # coupling entries: ∂H/∂V = dC/dV = μ(1 − 2V/V_p) = 0.3; ∂z/∂y = ∂g/∂V = −0.15
    assert h[1, OUT2_DH_DV] == pytest.approx(0.3)
    assert h[1, OUT2_DZ_DY] == pytest.approx(-0.15)
    # dissipation: lateral C·Δλ = 0.5625 minus the vertical heave V·|Δz| = 0.1875 → 0.375
    assert h[1, OUT_DISSIPATED] == pytest.approx(0.375)


def test_bearing_failure_penetrates_to_the_hardened_capacity():
    # V = 5000 > V_p = 4000 with k_p = 1e6: z = (5000 − 4000)/1e6 = 1 mm, V_p = V, C = 0
    m = ParabolicVH(friction_coefficient=0.6, bearing_capacity=4000.0, hardening_stiffness=1e6)
    h, s = _drive(m, np.array([0.0]), np.array([5000.0]))
    assert h[0, OUT_Z] == pytest.approx(1.0e-3)
    assert s[S_VP] == pytest.approx(5000.0)
    assert h[0, OUT_R] == 0.0
    assert h[0, OUT2_DZ_DV] == pytest.approx(1.0e-6)
    # without hardening no equilibrium: NaN (contract rule 2.6)
    m0 = ParabolicVH(friction_coefficient=0.6, bearing_capacity=4000.0)
    h0, _ = _drive(m0, np.array([0.0]), np.array([5000.0]))
    assert math.isnan(h0[0, OUT_R])


def test_lift_off_freezes_the_vertical_state():
    m = ParabolicVH(friction_coefficient=0.6, bearing_capacity=4000.0, initial_penetration=0.01)
    h, s = _drive(m, np.array([0.01, 0.05]), np.array([-10.0, 0.0]))
    assert np.all(h[:, OUT_R] == 0.0) and np.all(h[:, OUT_TANGENT] == 0.0)
    assert np.all(h[:, OUT_Z] == 0.01) and s[S_VP] == 4000.0


def _random_path(n=400, seed=3):
    rng = np.random.default_rng(seed)
    u = np.cumsum(rng.normal(0, 0.0015, n))
    v = 1500.0 + 900.0 * rng.standard_normal(n)  # some lift-off and some bearing steps
    return u, v


@pytest.mark.parametrize("width", [OUT_SIZE, OUT2_SIZE])
def test_numba_kernel_equals_python_twin_on_random_path(width):
    m = ParabolicVH(
        friction_coefficient=0.6,
        bearing_capacity=3000.0,
        flow_coefficient=0.4,
        hardening_stiffness=2.0e5,
    )
    u, v = _random_path()
    a, sa = _drive(m, u, v, width)
    b = np.zeros_like(a)
    sb = drive_path_py(m.python_kernel, m.packed_parameters(), m.initial_state(), u, v, b)
    np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(sa, sb, rtol=1e-13, atol=1e-12)
    assert np.any(a[:, OUT_REGION] == 2.0) and np.any(a[:, OUT_REGION] == 3.0)


@pytest.mark.parametrize("v", [1000.0, 3000.0])  # heave (V < V_p/2), penetration (> V_p/2)
def test_dissipation_never_decreases_at_constant_v(v):
    # plastic work C·Δλ + V·Δz = Δλ·V(μ(1 − V/V_p) − μ′(1 − 2V/V_p)) >= 0 for μ′ <= μ
    # (base.py rule 6 with rule 2.3), also for associated flow μ′ = μ
    m = ParabolicVH(friction_coefficient=0.6, bearing_capacity=4000.0, hardening_stiffness=2e5)
    u, _ = _random_path(seed=5)
    a, _ = _drive(m, u, np.full(u.size, v))
    assert np.ptp(a[:, OUT_Z]) > 0.0
    assert np.all(np.diff(a[:, OUT_DISSIPATED]) > -1e-9)


@pytest.mark.parametrize(
    "h0, dy, v, vp",
    [
        (100.0, 3e-4, 1000.0, 4000.0),  # elastic
        (300.0, 2e-3, 1000.0, 4000.0),  # plastic, heave (V < V_p/2)
        (-300.0, -2e-3, 3000.0, 4000.0),  # plastic, penetration (V > V_p/2), negative side
        (500.0, 1e-4, 1000.0, 4000.0),  # committed H above the capacity: clamped predictor
        (100.0, 2e-3, 4500.0, 4000.0),  # bearing + plastic
    ],
)
def test_coupling_tangent_matches_finite_differences(h0, dy, v, vp):
    m = ParabolicVH(
        friction_coefficient=0.6,
        bearing_capacity=vp,
        flow_coefficient=0.4,
        hardening_stiffness=3.0e5,
    )
    p = m.packed_parameters()
    st = m.initial_state()
    st[S_FRICTION] = h0
    st[S_Z] = 0.02
    trial = np.empty_like(st)

    def run(y, vv):
        out = np.zeros(OUT2_SIZE)
        m.kernel(p, st, y, vv, trial, out)
        return out

    o = run(dy, v)
    ey, ev = 1e-9, 1e-4
    fy = (run(dy + ey, v) - run(dy - ey, v)) / (2 * ey)
    fv = (run(dy, v + ev) - run(dy, v - ev)) / (2 * ev)
    assert o[OUT_TANGENT] == pytest.approx(fy[OUT_R], rel=1e-6, abs=1e-3)
    assert o[OUT2_DZ_DY] == pytest.approx(fy[OUT_Z], rel=1e-6, abs=1e-9)
    assert o[OUT2_DH_DV] == pytest.approx(fv[OUT_R], rel=1e-6, abs=1e-9)
    assert o[OUT2_DZ_DV] == pytest.approx(fv[OUT_Z], rel=1e-5, abs=1e-12)


def test_infinite_capacity_and_no_flow_is_coulomb_bit_for_bit():
    u, v = _random_path(seed=11)
    c = CoulombFriction(friction_coefficient=0.55, mobilisation_displacement=2e-3)
    m = ParabolicVH(
        friction_coefficient=0.55,
        bearing_capacity=math.inf,
        flow_coefficient=0.0,
        mobilisation_displacement=2e-3,
    )
    a, _ = _drive(c, u, v, OUT_SIZE)
    b, _ = _drive(m, u, v, OUT_SIZE)
    np.testing.assert_array_equal(a[:, OUT_R], b[:, OUT_R])
    np.testing.assert_array_equal(a[:, OUT_TANGENT], b[:, OUT_TANGENT])
    assert np.all(b[:, OUT_Z] == 0.0)


def test_model_is_the_second_form_and_packs_its_state():
    m = ParabolicVH(friction_coefficient=0.6, bearing_capacity=4000.0, initial_penetration=0.02)
    assert isinstance(m, ForceResultantModel) and m.degrees_of_freedom == 2
    assert CoulombFriction(friction_coefficient=0.5).degrees_of_freedom == 1
    s = m.initial_state()
    assert s.size == m.state_size and s[S_Z] == 0.02 and s[S_VP] == 4000.0
    assert m.flow_coefficient == 0.6  # default: associated
    assert m.parameters()["bearing_capacity"] == 4000.0


@pytest.mark.parametrize(
    "kw, field",
    [
        ({"friction_coefficient": 0.0}, "friction_coefficient"),
        ({"bearing_capacity": -1.0}, "bearing_capacity"),
        ({"flow_coefficient": 0.7}, "flow_coefficient"),  # > μ: negative plastic work
        ({"hardening_stiffness": -1.0}, "hardening_stiffness"),
        ({"mobilisation_displacement": 0.0}, "mobilisation_displacement"),
        ({"initial_penetration": -0.1}, "initial_penetration"),
    ],
)
def test_bad_inputs_name_the_field(kw, field):
    base = {"friction_coefficient": 0.6, "bearing_capacity": 4000.0}
    with pytest.raises(InputError, match=field):
        ParabolicVH(**{**base, **kw})


def test_factory_builds_it_by_name():
    pipe = Pipe(outer_diameter=0.4, submerged_weight=600.0)
    m = lateral_model("vh_parabolic", pipe, Rock(friction_coefficient=0.6), bearing_capacity=3e3)
    assert isinstance(m, ParabolicVH) and m.friction_coefficient == 0.6
    with pytest.raises(InputError, match="bearing_capacity"):
        lateral_model("vh_parabolic", pipe, Sand(submerged_unit_weight=1e4))


def test_stored_plus_dissipated_is_the_lateral_plus_vertical_work():
    # rule 2.3: the soil work is ∫H dy + ∫V dz; at constant V, ∫V dz = V·(z − z₀). Against an
    # independent trapezoidal ∫H dy on a finely sampled path of 3 cycles of ±5 cm.
    m = ParabolicVH(
        friction_coefficient=0.6,
        bearing_capacity=4000.0,
        flow_coefficient=0.4,
        hardening_stiffness=1e5,
    )
    v = 2500.0  # above V_p/2: the sliding pipe penetrates and V_p hardens
    u = 0.05 * np.sin(np.linspace(0.0, 6.0 * np.pi, 20000))
    h, _ = _drive(m, u, np.full(u.size, v))
    uu = np.concatenate([[0.0], u])
    ff = np.concatenate([[0.0], h[:, OUT_R]])
    work = np.cumsum(0.5 * (ff[1:] + ff[:-1]) * np.diff(uu)) + v * h[:, OUT_Z]
    booked = h[:, OUT_STORED] + h[:, OUT_DISSIPATED]
    assert h[-1, OUT_Z] > 1e-3
    assert np.max(np.abs(work - booked)) <= 1e-4 * abs(work[-1])


def test_partial_inversion_gives_the_displacement_controlled_stiffness():
    # rule 2.2: a bearing + sliding increment (∂z/∂V > 0); the stiffness from the hybrid
    # tangent must predict the (H, V) change of a small (y, z) change made through (y, V)
    from onbottom.soil._two_dof import stiffness_from_hybrid

    m = ParabolicVH(
        friction_coefficient=0.6,
        bearing_capacity=4000.0,
        flow_coefficient=0.4,
        hardening_stiffness=3.0e5,
    )
    p, st = m.packed_parameters(), m.initial_state()
    st[S_FRICTION] = 100.0
    trial = np.empty_like(st)

    def run(y, v):
        out = np.zeros(OUT2_SIZE)
        m.kernel(p, st, y, v, trial, out)
        return out

    o = run(2e-3, 4500.0)
    k = np.zeros((2, 2))
    assert stiffness_from_hybrid(o, k)
    # move along V at fixed y: Δz = (∂z/∂V)ΔV must give ΔV = K_vz Δz, ΔH = K_hz Δz
    dv = 0.1
    o2 = run(2e-3, 4500.0 + dv)
    dz = o2[OUT_Z] - o[OUT_Z]
    assert k[1, 1] * dz == pytest.approx(dv, rel=1e-6)
    assert k[0, 1] * dz == pytest.approx(o2[OUT_R] - o[OUT_R], rel=1e-5, abs=1e-9)
    # by hand from the hybrid entries
    assert k[1, 1] == pytest.approx(1.0 / o[OUT2_DZ_DV])
    assert k[0, 0] == pytest.approx(o[OUT_TANGENT] - o[OUT2_DH_DV] * o[OUT2_DZ_DY] / o[OUT2_DZ_DV])
    # rigid vertically (elastic step): no finite stiffness
    assert not stiffness_from_hybrid(run(1e-5, 1000.0), k)
