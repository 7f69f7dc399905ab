"""Verification: DNVGL-RP-F114 penetration geometry limits, monotonicity, solver round trips."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from onbottom import OutOfRangeWarning, SolutionError
from onbottom.soil.penetration_clay import UndrainedModel1, UndrainedModel2
from onbottom.soil.penetration_f114 import solve_embedment
from onbottom.soil.penetration_geometry import contact_width, penetrated_area
from onbottom.soil.penetration_sand import N_GAMMA_METHODS, DrainedPenetration, surcharge_depth

pytestmark = pytest.mark.verification

DIAMETERS = [0.1, 0.5, 1.3]


@pytest.mark.parametrize("d", DIAMETERS)
def test_geometry_limits_and_continuity(d):
    assert float(contact_width(0.0, d)) == 0.0
    assert float(penetrated_area(0.0, d)) == 0.0
    deep = np.linspace(0.5 * d, d, 7)
    np.testing.assert_array_equal(contact_width(deep, d), d)
    eps = 1e-9 * d
    b_left, b_mid = contact_width([0.5 * d - eps, 0.5 * d], d)
    a_left, a_mid = penetrated_area([0.5 * d - eps, 0.5 * d], d)
    assert b_left == pytest.approx(d, rel=1e-8) and b_mid == d
    assert a_left == pytest.approx(math.pi * d * d / 8, rel=1e-8)
    assert a_mid == pytest.approx(math.pi * d * d / 8, rel=1e-14)
    assert float(penetrated_area(d, d)) == pytest.approx(math.pi * d * d / 8 + d * d / 2)


@pytest.mark.parametrize("d", DIAMETERS)
def test_area_derivative_equals_contact_width(d):
    # dA_bm/dz = B(z): the displaced area grows by the chord width per unit penetration
    z = np.linspace(0.02 * d, 0.98 * d, 49)
    h = 1e-6 * d
    slope = (penetrated_area(z + h, d) - penetrated_area(z - h, d)) / (2 * h)
    np.testing.assert_allclose(slope, contact_width(z, d), rtol=1e-6)


@pytest.mark.parametrize("phi_deg", [20.0, 30.0, 38.0, 45.0])
def test_surcharge_depth_continuous_at_rankine_threshold(phi_deg):
    d = 0.5
    phi = math.radians(phi_deg)
    threshold = 0.5 * d * (1 - math.cos(math.pi / 4 + phi / 2))
    eps = 1e-10
    z0 = surcharge_depth([threshold - eps, threshold + eps], d, phi)
    assert z0[0] == 0.0 and 0.0 <= z0[1] < 1e-8
    z = np.linspace(0.0, d, 401)
    assert np.all(np.diff(surcharge_depth(z, d, phi)) >= 0.0)


@pytest.mark.parametrize("method", N_GAMMA_METHODS)
@pytest.mark.parametrize("phi_deg", [20.0, 27.5, 33.0, 40.0, 45.0])
def test_drained_resistance_monotone_in_penetration(method, phi_deg):
    model = DrainedPenetration(
        diameter=0.5, unit_weight=9e3, friction_angle_deg=phi_deg, n_gamma=method
    )
    q = model.resistance(np.linspace(0.0, 0.5, 1001))
    assert q[0] == 0.0
    assert np.all(np.diff(q) >= 0.0)


def _models():
    yield DrainedPenetration(diameter=0.5, unit_weight=16.7e3, friction_angle_deg=33)
    yield DrainedPenetration(diameter=1.0, unit_weight=8e3, friction_angle_deg=40, n_gamma="vesic")
    yield UndrainedModel1(diameter=0.5, su_mudline=2e3, su_gradient=3e3, unit_weight=6e3)
    yield UndrainedModel1(diameter=0.3, su_mudline=10e3, unit_weight=7e3, roughness=1.0)
    yield UndrainedModel2(diameter=0.5, su_mudline=1.5e3, su_gradient=1e3, unit_weight=5e3)


@pytest.mark.parametrize("model", list(_models()), ids=lambda m: m.name)
def test_embedment_round_trip(model):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OutOfRangeWarning)
        q_full = float(model.resistance(model.diameter))
        for frac in (0.01, 0.2, 0.5, 0.9, 1.0):
            load = frac * q_full
            res = solve_embedment(model, load)
            assert res.success and 0.0 < res.z <= model.diameter
            assert float(model.resistance(res.z)) == pytest.approx(load, rel=1e-8)
            assert res.resistance == pytest.approx(load, rel=1e-8)


def test_embedment_picks_the_shallowest_root():
    class Bumpy:
        """Q_v rising to 100 N/m at 0.2D, dipping to 50 and rising again (softening)."""

        name = "bumpy"
        diameter = 1.0

        def resistance(self, z):
            z = np.asarray(z, dtype=float)
            return np.where(
                z < 0.2, 500 * z, np.where(z < 0.4, 100 - 250 * (z - 0.2), 50 + 500 * (z - 0.4))
            )

        def parameters(self):
            return {}

    res = solve_embedment(Bumpy(), 75.0)
    assert res.z == pytest.approx(0.15, rel=1e-8)


@pytest.mark.parametrize("model", list(_models()), ids=lambda m: m.name)
def test_load_above_full_embedment_capacity_raises(model):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OutOfRangeWarning)
        q_full = float(model.resistance(model.diameter))
    with pytest.raises(SolutionError, match=r"exceeds the resistance at full embedment"):
        solve_embedment(model, 1.01 * q_full)
