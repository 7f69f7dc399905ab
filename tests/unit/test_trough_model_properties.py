"""Property tests (hypothesis) of the Verley & Sotberg and Verley & Lund kernels.

Continuity of the backbone at every region boundary, mirror symmetry y → −y, penetration that
never decreases inside a trough, and finite forces for every valid input (V → 0, V < 0).
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from onbottom.soil import _verley_sotberg_kernel as vk
from onbottom.soil._path import drive_path
from onbottom.soil.base import OUT_PASSIVE, OUT_R, OUT_SIZE, OUT_Z, S_Z
from onbottom.soil.verley_lund import VerleyLund
from onbottom.soil.verley_sotberg import VerleySotberg

SETTINGS = settings(max_examples=30, deadline=None)


@st.composite
def vs_models(draw):
    """Valid V&S models with K_s (installation) inside the assumed calibration range."""
    d = draw(st.floats(0.05, 2.0))
    gamma = draw(st.floats(5.0e3, 12.0e3))
    ks = draw(st.floats(0.3, 25.0))
    y1 = draw(st.floats(0.005, 0.05))
    y2 = y1 + draw(st.floats(0.05, 0.6))
    y3 = y2 + draw(st.floats(0.1, 0.8))
    return VerleySotberg(
        outer_diameter=d,
        submerged_unit_weight=gamma,
        friction_coefficient=draw(st.floats(0.2, 1.2)),
        installation_load=gamma * d * d / ks,
        A=draw(st.floats(0.1, 2.0)),
        B=draw(st.floats(0.1, 2.0)),
        C=draw(st.floats(0.5, 1.5)),
        region_limits_over_d=(y1, y2, y3),
        passive_law=draw(st.sampled_from(["verley_sotberg", "dnv_f109"])),
        max_penetration_law=draw(st.sampled_from(["reconstruction", "reconstruction_no_half"])),
        work_integrand=draw(st.sampled_from(["total", "passive"])),
    )


@st.composite
def vl_models(draw):
    d = draw(st.floats(0.1, 2.0))
    su = draw(st.floats(1.0e3, 20.0e3))
    gs = draw(st.floats(14.0e3, 20.0e3))
    # keep S·G^0.3 <= 2.5 (validity of the penetration fit)
    x = draw(st.floats(0.05, 2.4))
    gc = su / (d * gs)
    w = x / gc**0.3 * d * su
    return VerleyLund(
        outer_diameter=d,
        undrained_shear_strength=su,
        unit_weight=gs,
        friction_coefficient=draw(st.floats(0.1, 0.8)),
        installation_load=w,
        residual_penetration_ratio=draw(st.floats(0.0, 1.0)),
    )


def _drive(model, u, v):
    u = np.asarray(u, dtype=float)
    v = np.broadcast_to(np.asarray(v, dtype=float), u.shape).copy()
    h = np.zeros((u.size, OUT_SIZE))
    drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h


def _lipschitz_check(h, du, slope_bound, peak):
    """Every change of the passive force is bounded by slope·Δu plus the change of F_peak(z).

    A jump of the backbone at a region boundary would break this bound by O(F) at one step.
    """
    p = h[:, OUT_PASSIVE]
    dp = np.abs(np.diff(p))
    dpk = np.abs(np.diff([peak(z) for z in h[:, OUT_Z]]))
    bound = slope_bound * du + dpk
    assert np.all(dp <= bound * (1.0 + 1e-9) + 1e-9 * np.max(np.abs(p))), np.max(dp - bound)


@SETTINGS
@given(vs_models(), st.floats(0.3, 1.5))
def test_vs_backbone_continuous_at_region_boundaries(model, v_factor):
    v = model.installation_load * v_factor
    n = 20_000
    u = np.linspace(0.0, 1.3 * model.y3, n + 1)
    h = _drive(model, u, v)
    p = model.packed_parameters()
    z_max = h[:, OUT_Z].max()
    fr2 = vk.peak_passive(p, z_max, v)
    y1, y2, y3 = model.y1, model.y2, model.y3
    slope = max(0.3 * fr2 / y1, 0.7 * fr2 / (y2 - y1), fr2 / (y3 - y2))
    _lipschitz_check(h, u[1] - u[0], slope, lambda z: vk.peak_passive(p, z, v))
    assert {1.0, 2.0, 3.0, 4.0} <= set(np.unique(h[:, 6]))


@SETTINGS
@given(vl_models())
def test_vl_backbone_continuous_at_region_boundaries(model):
    zi = model.initial_penetration
    y_brk = model.breakout_displacement(zi)
    y_res = model.residual_over_d * model.outer_diameter
    n = 20_000
    u = np.linspace(0.0, 1.3 * y_res, n + 1)
    h = _drive(model, u, model.installation_load)
    f = model.passive(zi)
    slope = max(f / y_brk, f / (y_res - y_brk))
    _lipschitz_check(h, u[1] - u[0], slope, lambda z: 0.0)


increments = st.lists(st.floats(-0.3, 0.3), min_size=5, max_size=120)


@SETTINGS
@given(st.one_of(vs_models(), vl_models()), increments, st.floats(0.2, 1.5))
def test_mirror_path_gives_mirrored_forces(model, steps, v_factor):
    d = model.outer_diameter
    u = np.cumsum(np.asarray(steps) * d)
    v = np.full(u.size, v_factor * model.installation_load)
    h = _drive(model, u, v)
    hm = _drive(model, -u, v)
    np.testing.assert_allclose(hm[:, OUT_R], -h[:, OUT_R], rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(hm[:, OUT_PASSIVE], -h[:, OUT_PASSIVE], rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(hm[:, OUT_Z], h[:, OUT_Z], rtol=1e-10, atol=1e-15)


@SETTINGS
@given(vs_models(), increments)
def test_penetration_never_decreases_inside_a_trough(model, steps):
    d = model.outer_diameter
    u = np.cumsum(np.asarray(steps) * d)
    p = model.packed_parameters()
    s_old = model.initial_state()
    s_new = np.empty_like(s_old)
    out = np.empty(OUT_SIZE)
    for ui in u:
        model.kernel(p, s_old, ui, model.installation_load, s_new, out)
        same_trough = s_new[vk.S_Y0] == s_old[vk.S_Y0]
        if same_trough and s_new[vk.S_PHASE] == vk.PHASE_TROUGH:
            assert s_new[S_Z] >= s_old[S_Z]
        s_old[:] = s_new


loads = st.one_of(
    st.floats(-1.0e5, 1.0e5),
    st.sampled_from([0.0, -0.0, 5e-324, 1e-300, 1e-12, -1e-12]),
)


@SETTINGS
@given(
    st.one_of(vs_models(), vl_models()),
    st.lists(st.tuples(st.floats(-2.0, 2.0), loads), min_size=1, max_size=80),
)
def test_forces_finite_for_any_valid_input(model, path):
    u = np.array([p[0] for p in path]) * model.outer_diameter
    v = np.array([p[1] for p in path])
    h = _drive(model, u, v)
    assert np.all(np.isfinite(h))
    assert np.all(h[v <= 0.0, OUT_R] == 0.0)
