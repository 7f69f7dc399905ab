"""Unit tests: Verley & Sotberg formulas (spec worked numbers, kN and m) and kernel behaviour."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from onbottom import InputError, OutOfRangeWarning, Pipe, Sand
from onbottom.soil import _verley_sotberg_kernel as k
from onbottom.soil._path import drive_path, drive_path_py
from onbottom.soil.base import (
    OUT_FRICTION,
    OUT_PASSIVE,
    OUT_R,
    OUT_REGION,
    OUT_SIZE,
    OUT_TANGENT,
    OUT_WORK,
    OUT_Z,
    S_Z,
)
from onbottom.soil.verley_sotberg import (
    WORK_COUNTINGS,
    VerleySotberg,
    initial_penetration,
    max_cyclic_penetration,
    peak_passive_resistance,
    residual_penetration_ratio,
    stiffness_parameter,
    work_penetration,
)

KN = 1.0e3
RTOL = 1e-4


def _drive(model, u, v):
    u = np.asarray(u, dtype=float)
    v = np.broadcast_to(np.asarray(v, dtype=float), u.shape).copy()
    h = np.zeros((u.size, OUT_SIZE))
    state = drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h, state


# ---- worked numbers of the spec (calcareous, D = 1.0, γ' = 7.5 kN/m³, V = W = 10.52 kN/m) -----
def test_calcareous_worked_numbers():
    g, d, v = 7.5 * KN, 1.0, 10.52 * KN
    assert stiffness_parameter(g, d, v) == pytest.approx(0.712928, rel=RTOL)
    zi = initial_penetration(g, d, v, C=0.98)
    assert zi / d == pytest.approx(0.045487, rel=RTOL)
    fr2 = peak_passive_resistance(g, d, v, 0.10 * d, A=0.25)
    assert fr2 / KN == pytest.approx(0.51592, rel=RTOL)
    assert 0.3 * fr2 / KN == pytest.approx(0.15478, rel=RTOL)
    assert residual_penetration_ratio(0.10) == pytest.approx(0.5, rel=RTOL)
    fr3 = peak_passive_resistance(g, d, v, 0.05 * d, A=0.25)
    assert fr3 / KN == pytest.approx(0.21692, rel=RTOL)
    # z2 = z_i
    assert peak_passive_resistance(g, d, v, zi, A=0.25) / KN == pytest.approx(0.19273, rel=RTOL)
    ratio = residual_penetration_ratio(zi / d)
    assert ratio == pytest.approx(0.674442, rel=RTOL)
    fr3_i = peak_passive_resistance(g, d, v, ratio * zi, A=0.25)
    assert fr3_i / KN == pytest.approx(0.11779, rel=RTOL)


def test_silica_worked_numbers():
    g, d, w = 10.0 * KN, 0.5, 2.0 * KN
    assert stiffness_parameter(g, d, w) == pytest.approx(1.25, rel=RTOL)
    assert initial_penetration(g, d, w) / d == pytest.approx(0.031862, rel=RTOL)
    assert peak_passive_resistance(g, d, w, 0.15 * d) / KN == pytest.approx(1.12312, rel=RTOL)
    assert peak_passive_resistance(g, d, w, 0.075 * d) / KN == pytest.approx(0.47221, rel=RTOL)
    # with lift F_L = 1.0 kN/m: V = 1.0 kN/m
    v = 1.0 * KN
    assert stiffness_parameter(g, d, v) == pytest.approx(2.5, rel=RTOL)
    assert peak_passive_resistance(g, d, v, 0.15 * d) / KN == pytest.approx(1.07936, rel=RTOL)
    assert peak_passive_resistance(g, d, v, 0.075 * d) / KN == pytest.approx(0.45381, rel=RTOL)


def test_passive_law_switch_points():
    g, d = 10.0 * KN, 1.0
    z = 0.1
    # K_s = 25: V&S above 20 → 2γ'D²(z/D)^1.25; F109 below 26.7 → quadratic (5 − 3.75)
    v = g * d * d / 25.0
    base = g * d * d * 0.1**1.25
    assert peak_passive_resistance(g, d, v, z) == pytest.approx(2.0 * base, rel=1e-12)
    f109 = peak_passive_resistance(g, d, v, z, law="dnv_f109")
    assert f109 == pytest.approx(1.25 * base, rel=1e-12)
    # K_s = 28 (outside assumed range warns nothing: 28 < 30); F109 above 26.7 → γ'D²(z/D)^1.25
    v = g * d * d / 28.0
    assert peak_passive_resistance(g, d, v, z, law="dnv_f109") == pytest.approx(base, rel=1e-12)


def test_reconstructed_penetration_laws_hand_calc():
    g, d, v = 7.5 * KN, 1.0, 10.52 * KN
    ks = g * d * d / v
    zi = 0.045487
    e, s = 2.0 * KN, 0.1
    z6 = work_penetration(zi, e, g, d, v, s, B=0.35)
    assert z6 == pytest.approx(zi + 0.35 * 0.23 * (e / g) ** 0.5 * (ks * s) ** -0.31, rel=1e-12)
    z8 = max_cyclic_penetration(zi, g, d, v, s, B=0.35)
    assert z8 == pytest.approx(zi + 0.35 * 0.5 * (s / ks) ** 0.5, rel=1e-12)
    z8b = max_cyclic_penetration(zi, g, d, v, s, B=0.35, law="reconstruction_no_half")
    assert z8b - zi == pytest.approx(2.0 * (z8 - zi), rel=1e-12)


# ---- model and kernel ------------------------------------------------------------------------
@pytest.fixture
def calc_model(centrifuge_pipe, calcareous_sand):
    return VerleySotberg.calcareous(centrifuge_pipe, calcareous_sand)


def test_elastic_region_no_work_and_linear_passive(calc_model):
    m = calc_model
    v = 10.52 * KN
    u = np.linspace(0.0, 0.9 * m.y1, 10)[1:]
    h, _ = _drive(m, u, v)
    fr2 = m.peak_passive(v, m.initial_penetration)
    np.testing.assert_allclose(h[:, OUT_PASSIVE], 0.3 * fr2 * u / m.y1, rtol=1e-12)
    assert np.all(h[:, OUT_WORK] == 0.0)
    np.testing.assert_allclose(h[:, OUT_Z], m.initial_penetration, rtol=1e-14)
    assert np.all(h[:, OUT_REGION] == 1.0)
    # friction: δ = 1 mm; full μV after 1 mm
    assert h[-1, OUT_FRICTION] == pytest.approx(0.48 * v)
    np.testing.assert_allclose(h[:, OUT_R], h[:, OUT_FRICTION] + h[:, OUT_PASSIVE])


def test_monotonic_breakout_follows_backbone(calc_model):
    # the first reading of Eq 6 (every region-2 increment counts): a one-way push grows z
    m = dataclasses.replace(calc_model, work_counting="any_region2")
    v = 10.52 * KN
    u = np.linspace(0.0, 1.2 * m.outer_diameter, 2401)[1:]
    h, state = _drive(m, u, v)
    reg = h[:, OUT_REGION]
    assert set(np.unique(reg)) == {1.0, 2.0, 3.0, 4.0}
    # penetration grows in region 2, then falls to z3 = ratio(z2)·z2 in region 3
    z = h[:, OUT_Z]
    i2 = np.flatnonzero(reg == 2.0)
    assert np.all(np.diff(z[i2]) >= 0.0) and z[i2[-1]] > m.initial_penetration
    z2 = state[k.S_Z2]
    assert z[i2[-1]] == pytest.approx(z2, rel=1e-12)
    z3 = residual_penetration_ratio(z2 / m.outer_diameter) * z2
    np.testing.assert_allclose(z[reg == 4.0], z3, rtol=1e-12)
    np.testing.assert_allclose(h[reg == 4.0, OUT_PASSIVE], m.peak_passive(v, z3), rtol=1e-12)
    assert h[-1, OUT_TANGENT] == 0.0
    assert state[k.S_PHASE] == k.PHASE_OUT


def test_new_trough_after_reversal_beyond_y3(calc_model):
    m = calc_model
    v = 10.52 * KN
    u_out = np.linspace(0.0, 1.0, 1001)[1:]
    u_back = 1.0 - np.linspace(0.0, 0.005, 6)[1:]
    h, state = _drive(m, np.concatenate([u_out, u_back]), v)
    assert state[k.S_PHASE] == k.PHASE_TROUGH
    assert state[k.S_Y0] == pytest.approx(1.0)
    z3 = h[len(u_out) - 1, OUT_Z]
    assert state[k.S_ZI] == pytest.approx(z3)
    # passive restores towards the new centre: −, elastic slope 0.3 F_r2(z3)/y1
    fr2 = m.peak_passive(v, z3)
    assert h[-1, OUT_PASSIVE] == pytest.approx(-0.3 * fr2 * 0.005 / m.y1, rel=1e-9)


def test_lift_off_gives_zero_resistance_not_nan(calc_model):
    h, _ = _drive(calc_model, [0.01, 0.3, 0.5], [0.0, -5.0 * KN, 0.0])
    assert np.all(h[:, OUT_R] == 0.0) and np.all(np.isfinite(h))


def test_trial_evaluation_has_no_side_effects(calc_model):
    m = calc_model
    p = m.packed_parameters()
    s0 = m.initial_state()
    s0_copy = s0.copy()
    out1, out2 = np.zeros(OUT_SIZE), np.zeros(OUT_SIZE)
    t1, t2 = np.zeros_like(s0), np.zeros_like(s0)
    m.kernel(p, s0, 0.1, 10.0 * KN, t1, out1)
    m.kernel(p, s0, -0.05, 10.0 * KN, t2, out2)
    m.kernel(p, s0, 0.1, 10.0 * KN, t2, out2)
    np.testing.assert_array_equal(s0, s0_copy)
    np.testing.assert_array_equal(out1, out2)
    np.testing.assert_array_equal(t1, t2)


@pytest.mark.parametrize(
    "options",
    [
        {},
        {"passive_rule": "legacy_elastic"},
        {"b_placement": "inside"},
        *({"work_counting": c} for c in WORK_COUNTINGS if c != "load_reversal"),
    ],
    ids=[
        "default",
        "legacy_elastic",
        "b_inside",
        *(c for c in WORK_COUNTINGS if c != "load_reversal"),
    ],
)
def test_numba_kernel_equals_python_twin_on_random_path(calc_model, options):
    rng = np.random.default_rng(11)
    m = dataclasses.replace(calc_model, **options)
    n = 3000
    # random walk with occasional large excursions: visits all regions and new troughs
    u = np.cumsum(rng.normal(0.0, 0.02, n) + 0.05 * (rng.random(n) < 0.02))
    v = 10.52 * KN * (1.0 + 0.3 * rng.standard_normal(n))
    h1, s1 = _drive(m, u, v)
    h2 = np.zeros_like(h1)
    s2 = drive_path_py(m.python_kernel, m.packed_parameters(), m.initial_state(), u, v, h2)
    assert len(np.unique(h1[:, OUT_REGION])) == 4
    np.testing.assert_allclose(h1, h2, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(s1, s2, rtol=1e-12, atol=1e-12)


def test_initial_state_and_variants(centrifuge_pipe):
    sand = Sand(submerged_unit_weight=10.0 * KN)
    pipe = Pipe(outer_diameter=0.5, submerged_weight=2.0 * KN)
    m = VerleySotberg.silica(pipe, sand)
    assert (m.y1, m.y2, m.y3) == pytest.approx((0.01, 0.25, 0.5))
    assert m.initial_state()[S_Z] / 0.5 == pytest.approx(0.031862, rel=RTOL)
    f = VerleySotberg.f109(pipe, sand)
    assert f.passive_law == "dnv_f109" and f.variant == "f109"
    c = VerleySotberg.calcareous(pipe, sand, A=0.3)
    assert (c.A, c.B, c.C) == (0.3, 0.35, 0.98)
    assert c.region_limits_over_d == (0.01, 0.25, 0.75)


@pytest.mark.parametrize(
    ("field", "kwargs"),
    [
        ("outer_diameter", {"outer_diameter": -1.0}),
        ("friction_coefficient", {"friction_coefficient": 0.0}),
        ("installation_load", {"installation_load": 0.0}),
        ("region_limits_over_d", {"region_limits_over_d": (0.5, 0.2, 1.0)}),
        ("passive_law", {"passive_law": "brinch_hansen"}),
        ("work_integrand", {"work_integrand": "half"}),
        ("mobilisation_displacement", {"mobilisation_displacement": 0.5}),
        ("B", {"B": -0.35}),
    ],
)
def test_bad_input_names_the_field(field, kwargs):
    base = {
        "outer_diameter": 1.0,
        "submerged_unit_weight": 7.5e3,
        "friction_coefficient": 0.5,
        "installation_load": 1.0e4,
    }
    with pytest.raises(InputError, match=field):
        VerleySotberg(**{**base, **kwargs})


def test_out_of_range_warning():
    with pytest.warns(OutOfRangeWarning, match="K_s"):
        initial_penetration(10.0e3, 1.0, 10.0, C=1.0)
    with pytest.warns(OutOfRangeWarning, match="z/D"):
        peak_passive_resistance(10.0e3, 1.0, 1.0e4, 0.8)


# ---- kernel against the pure functions -----------------------------------------------------
def _silica_model(**kw):
    pipe = Pipe(outer_diameter=0.5, submerged_weight=2.0 * KN)
    return VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10.0 * KN), **kw)


def test_kernel_penetration_equals_eq6_eq8_with_its_own_work():
    m = _silica_model(work_counting="any_region2")
    v = 2.0 * KN
    u = np.linspace(0.0, 0.9 * m.y2, 4001)[1:]
    h, _ = _drive(m, u, v)
    zi = m.initial_penetration
    in2 = u > m.y1
    for ui, zk, ek in zip(
        u[in2][::200], h[in2, OUT_Z][::200], h[in2, OUT_WORK][::200], strict=True
    ):
        z6 = work_penetration(zi, ek, 10.0 * KN, 0.5, v, ui)
        z8 = max_cyclic_penetration(zi, 10.0 * KN, 0.5, v, ui)
        assert zk == pytest.approx(max(min(z6, z8), zi), rel=1e-12)
    # the work is the integral of |R| over the region-2 part of the path (trapezoid rule)
    r = np.abs(h[:, OUT_R])
    e_trap = np.trapezoid(r[in2], u[in2]) + r[in2][0] * (u[in2][0] - m.y1)
    assert h[-1, OUT_WORK] == pytest.approx(e_trap, rel=2e-3)


@pytest.mark.parametrize(
    ("law", "factor"), [("reconstruction", 0.5), ("reconstruction_no_half", 1.0)]
)
def test_cyclic_motion_converges_to_eq8_cap(law, factor):
    m = _silica_model(max_penetration_law=law)
    v = 2.0 * KN
    amp = 0.2 * 0.5
    t = np.linspace(0.0, 20.0, 20 * 400 + 1)[1:]
    h, state = _drive(m, amp * np.sin(2 * np.pi * t), v)
    ks = 10.0 * KN * 0.25 / v
    cap = m.initial_penetration + factor * 0.5 * (amp / (ks * 0.5)) ** 0.5
    assert h[-1, OUT_Z] == pytest.approx(cap, rel=1e-9)
    assert state[k.S_SMAX] == pytest.approx(amp, rel=1e-6)


def test_work_law_none_and_passive_integrand():
    v = 2.0 * KN
    t = np.linspace(0.0, 3.0, 1201)[1:]
    u = 0.05 * np.sin(2 * np.pi * t)
    h_none, _ = _drive(_silica_model(work_law="none"), u, v)
    np.testing.assert_allclose(h_none[:, OUT_Z], h_none[0, OUT_Z], rtol=0, atol=0)
    h_tot, _ = _drive(_silica_model(), u, v)
    h_pas, _ = _drive(_silica_model(work_integrand="passive"), u, v)
    assert 0.0 < h_pas[-1, OUT_WORK] < 0.5 * h_tot[-1, OUT_WORK]
    # less work → slower growth (both reach the Eq 8 cap eventually)
    assert np.all(h_pas[:, OUT_Z] <= h_tot[:, OUT_Z])
    assert np.any(h_pas[:, OUT_Z] < h_tot[:, OUT_Z])


@pytest.mark.parametrize("rule", ["elastoplastic", "legacy_elastic"])
def test_return_from_breakout_keeps_penetration_and_frozen_envelope(calc_model, rule):
    m = dataclasses.replace(calc_model, passive_rule=rule)
    v = 10.52 * KN
    u = np.concatenate([np.linspace(0.0, 0.5, 2001)[1:], np.linspace(0.5, 0.1, 801)[1:]])
    h, state = _drive(m, u, v)
    assert state[k.S_PHASE] == k.PHASE_BREAKOUT
    z2 = state[k.S_Z2]
    z3 = residual_penetration_ratio(z2) * z2
    z_reached = z2 + (z3 - z2) * (0.5 - m.y2) / (m.y3 - m.y2)
    assert h[-1, OUT_Z] == pytest.approx(z_reached, rel=1e-12)
    fr2 = m.peak_passive(v, z2)
    if rule == "legacy_elastic":
        # restoring force on the frozen envelope
        expected = 0.3 * fr2 + 0.7 * fr2 * (0.1 - m.y1) / (m.y2 - m.y1)
        assert h[-1, OUT_PASSIVE] == pytest.approx(expected, rel=1e-9)
    else:
        # push-only: the force unloads along k_u = 0.3 F_r2/y1 and never pulls
        p_top = h[1999, OUT_PASSIVE]
        k_u = 0.3 * fr2 / m.y1
        back = 0.5 - u[2000:]
        np.testing.assert_allclose(
            h[2000:, OUT_PASSIVE], np.maximum(p_top - k_u * back, 0.0), atol=1e-9 * fr2
        )
        assert h[-1, OUT_PASSIVE] == 0.0


def test_check_validity_warns_after_a_run(calc_model):
    calc_model.check_validity([10.0e3, -1.0], [0.1])  # inside: silent
    with pytest.warns(OutOfRangeWarning, match="K_s"):
        calc_model.check_validity([10.0], [0.1])
    with pytest.warns(OutOfRangeWarning, match="z/D"):
        calc_model.check_validity([10.0e3], [0.7])


def test_model_warns_once_outside_the_ks_range():
    with pytest.warns(OutOfRangeWarning, match="K_s") as rec:
        m = VerleySotberg(
            outer_diameter=1.0,
            submerged_unit_weight=1.0e4,
            friction_coefficient=0.5,
            installation_load=100.0,
        )
        m.packed_parameters()
        m.initial_state()
    assert len(rec) == 1


def test_f109_sand_passive_in_the_standard_form():
    # DNV-RP-F109 §3.4.6: F_R/F_C = (5κ_s − 0.15κ_s²)(z/D)^1.25 for κ_s <= 26.7,
    # F_R/F_C = κ_s(z/D)^1.25 above; κ_s = γ'D²/F_C. D = 0.5 m, γ' = 10 kN/m³, z/D = 0.1.
    g, d, zd = 10.0 * KN, 0.5, 0.1
    # F_C = 0.2 kN/m: κ_s = 12.5 → F_R = 0.2·(62.5 − 23.4375)·0.1^1.25 = 0.439329 kN/m
    f = peak_passive_resistance(g, d, 0.2 * KN, zd * d, law="dnv_f109")
    assert f / KN == pytest.approx(0.439329, rel=1e-5)
    # F_C = 0.09 kN/m: κ_s = 27.78 → F_R = 0.09·27.78·0.1^1.25 = γ'D²·0.1^1.25 = 0.140585 kN/m
    f = peak_passive_resistance(g, d, 0.09 * KN, zd * d, law="dnv_f109")
    assert f / KN == pytest.approx(0.140585, rel=1e-5)
