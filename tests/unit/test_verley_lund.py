"""Unit tests: Verley & Lund clay (DNV-RP-F109 §3.4.6 hand calculations) and its kernel."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom import Clay, InputError, OutOfRangeWarning, Pipe
from onbottom.soil import _verley_lund_kernel as k
from onbottom.soil._path import drive_path, drive_path_py
from onbottom.soil.base import OUT_PASSIVE, OUT_R, OUT_REGION, OUT_SIZE, OUT_Z
from onbottom.soil.verley_lund import (
    VerleyLund,
    clay_initial_penetration,
    clay_passive_resistance,
    penetration_group,
)

# Hand calculation: D = 0.5 m, W = 1.0 kN/m, s_u = 5 kPa, γ_s = 16 kN/m³ (total)
# S = 1000/(0.5·5000) = 0.4; G_c = 5000/(0.5·16000) = 0.625; G_c^0.3 = 0.868489
D, W, SU, GS = 0.5, 1.0e3, 5.0e3, 16.0e3


def test_penetration_group_both_readings():
    assert penetration_group(W, D, SU, GS) == pytest.approx(0.347395, rel=1e-5)
    assert penetration_group(W, D, SU, GS, form="quotient") == pytest.approx(0.460570, rel=1e-5)


def test_initial_penetration_hand_calc():
    # z/D = 0.0071·X^3.2 + 0.062·X^0.7
    assert clay_initial_penetration(W, D, SU, GS) / D == pytest.approx(0.0298189, rel=1e-4)
    zq = clay_initial_penetration(W, D, SU, GS, form="quotient")
    assert zq / D == pytest.approx(0.0366269, rel=1e-4)


def test_passive_hand_calc_and_f109_form():
    z = 0.0298189 * D
    fr = clay_passive_resistance(z, D, SU, GS)
    assert fr == pytest.approx(123.5705, rel=1e-4)
    # F109 form F_R/F_C = 4.1·κ_c/G_c^0.39·(z/D)^1.31 with κ_c = s_u·D/F_C: independent of F_C
    for fc in (500.0, 2000.0):
        kappa = SU * D / fc
        assert fr == pytest.approx(fc * 4.1 * kappa / 0.625**0.39 * (z / D) ** 1.31, rel=1e-12)


def test_validity_warning_beyond_group_limit():
    with pytest.warns(OutOfRangeWarning, match="penetration group"):
        clay_initial_penetration(20.0e3, D, SU, GS)


@pytest.fixture
def clay_model():
    pipe = Pipe(outer_diameter=D, submerged_weight=W)
    clay = Clay(undrained_shear_strength=SU, submerged_unit_weight=6.0e3, unit_weight=GS)
    return VerleyLund.from_seabed(pipe, clay)


def _drive(model, u, v):
    u = np.asarray(u, dtype=float)
    v = np.broadcast_to(np.asarray(v, dtype=float), u.shape).copy()
    h = np.zeros((u.size, OUT_SIZE))
    state = drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h, state


def test_from_seabed_unit_weight_choice():
    pipe = Pipe(outer_diameter=D, submerged_weight=W)
    clay = Clay(undrained_shear_strength=SU, submerged_unit_weight=6.0e3, unit_weight=GS)
    assert VerleyLund.from_seabed(pipe, clay).unit_weight == GS
    assert VerleyLund.from_seabed(pipe, clay, unit_weight="submerged").unit_weight == 6.0e3
    with pytest.raises(InputError, match="unit_weight"):
        VerleyLund.from_seabed(pipe, clay, unit_weight="dry")


def test_monotonic_backbone(clay_model):
    m = clay_model
    zi = m.initial_penetration
    y_brk = m.breakout_displacement(zi)
    assert y_brk == pytest.approx((0.02 + 0.25 * zi / D) * D)
    u = np.linspace(0.0, 2.0 * D, 4001)[1:]
    h, state = _drive(m, u, W)
    fr = m.passive(zi)
    i = np.searchsorted(u, y_brk)
    assert h[i - 1, OUT_PASSIVE] == pytest.approx(fr * u[i - 1] / y_brk, rel=1e-9)
    zres = 0.5 * zi
    np.testing.assert_allclose(h[u > 1.5 * D, OUT_Z], zres, rtol=1e-12)
    np.testing.assert_allclose(h[u > 1.5 * D, OUT_PASSIVE], m.passive(zres), rtol=1e-12)
    assert set(np.unique(h[:, OUT_REGION])) == {1.0, 3.0, 4.0}
    assert state[k.S_PHASE] == 2.0


def test_lift_off_and_twin(clay_model):
    rng = np.random.default_rng(5)
    n = 3000
    u = np.cumsum(rng.normal(0.0, 0.01, n) + 0.03 * (rng.random(n) < 0.02))
    v = W * (1.0 + 0.6 * rng.standard_normal(n))
    h1, s1 = _drive(clay_model, u, v)
    h2 = np.zeros_like(h1)
    m = clay_model
    s2 = drive_path_py(m.python_kernel, m.packed_parameters(), m.initial_state(), u, v, h2)
    assert np.all(np.isfinite(h1))
    assert np.all(h1[v <= 0.0, OUT_R] == 0.0)
    assert len(np.unique(h1[:, OUT_REGION])) == 3
    np.testing.assert_allclose(h1, h2, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(s1, s2, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize(
    ("field", "kwargs"),
    [
        ("undrained_shear_strength", {"undrained_shear_strength": 0.0}),
        ("penetration_form", {"penetration_form": "ratio"}),
        ("residual_over_d", {"residual_over_d": 0.01}),
        ("residual_penetration_ratio", {"residual_penetration_ratio": 1.5}),
        ("breakout_over_d", {"breakout_over_d": (0.0, 0.25)}),
    ],
)
def test_bad_input_names_the_field(field, kwargs):
    base = {
        "outer_diameter": D,
        "undrained_shear_strength": SU,
        "unit_weight": GS,
        "friction_coefficient": 0.2,
        "installation_load": W,
    }
    with pytest.raises(InputError, match=field):
        VerleyLund(**{**base, **kwargs})


def test_backbone_points_match_the_kernel(clay_model):
    m = clay_model
    pts = m.backbone_points(W)
    uu = np.linspace(0.0, pts["y3"] + 0.1, 20001)[1:]
    h, _ = _drive(m, uu, W)
    i_brk = np.argmin(np.abs(uu - pts["y1"]))
    assert h[i_brk, OUT_PASSIVE] == pytest.approx(pts["F_r2"], rel=1e-3)
    assert h[-1, OUT_PASSIVE] == pytest.approx(pts["F_r3"], rel=1e-12)
    assert pts["F_f"] == pytest.approx(0.2 * W)


def test_model_warns_once_outside_the_fit_range():
    with pytest.warns(OutOfRangeWarning, match="penetration group") as rec:
        m = VerleyLund(
            outer_diameter=D,
            undrained_shear_strength=SU,
            unit_weight=GS,
            friction_coefficient=0.2,
            installation_load=20.0e3,
        )
        m.packed_parameters()
        m.initial_state()
    assert len(rec) == 1
