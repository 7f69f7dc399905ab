"""Unit tests: DNVGL-RP-F114 vertical penetration (hand calculations and the reference table).

Reference numbers: /work/shared/spec/dnv-reference.md §3.3 (D = 0.5 m, the penetration-paper
centrifuge case), rounded there to 0.1 kN/m; tolerance 1 % (or 0.06 kN/m for small values).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from onbottom import Clay, InputError, OutOfRangeWarning, Pipe, Rock, Sand
from onbottom.soil.penetration_clay import (
    BEARING_FACTOR_NC,
    UndrainedModel1,
    UndrainedModel2,
    davis_booker_factor,
)
from onbottom.soil.penetration_f114 import (
    LayConditions,
    lay_factor,
    lay_validity_tension,
    penetration_curve,
    resistance_model,
    solve_embedment,
)
from onbottom.soil.penetration_geometry import contact_width, penetrated_area
from onbottom.soil.penetration_sand import (
    DrainedBounds,
    DrainedPenetration,
    bearing_factor_n_gamma,
    bearing_factor_n_q,
    surcharge_depth,
)
from onbottom.status import Status

D = 0.5
LEVELS = np.array([0.1, 0.2, 0.3, 0.4, 0.5])

# γ' [kN/m³], φ' [deg], N_γ method, N_γ (rounded), Q_v [kN/m] at 0.1–0.5D (spec §3.3)
SPEC_TABLE = [
    (16.7, 33, "davis_booker_smooth", 14.1, [10.6, 18.8, 25.0, 33.1, 43.5]),
    (16.7, 33, "brinch_hansen", 24.4, [18.4, 32.7, 43.2, 53.9, 65.1]),
    (16.7, 33, "davis_booker_rough", 26.6, [20.0, 35.5, 46.9, 58.1, 69.5]),
    (16.7, 33, "vesic", 35.2, [26.4, 47.0, 62.1, 75.4, 87.6]),
    (16.7, 40, "davis_booker_smooth", 43.8, [32.9, 58.5, 76.8, 96.3, 121.5]),
    (16.7, 40, "brinch_hansen", 79.5, [59.8, 106.3, 139.6, 168.0, 196.2]),
    (16.7, 40, "davis_booker_rough", 85.8, [64.5, 114.6, 150.5, 180.5, 209.2]),
    (16.7, 40, "vesic", 109.4, [82.2, 146.2, 191.9, 227.8, 258.5]),
    (15.9, 33, "davis_booker_rough", None, [19.0, 33.8, 44.7, 55.3, 66.2]),
    (15.9, 40, "vesic", None, [78.3, 139.2, 182.7, 216.9, 246.1]),
]


@pytest.mark.parametrize(("gamma_kn", "phi", "method", "n_gamma", "expected"), SPEC_TABLE)
def test_drained_resistance_matches_reference_table(gamma_kn, phi, method, n_gamma, expected):
    model = DrainedPenetration(
        diameter=D, unit_weight=gamma_kn * 1e3, friction_angle_deg=phi, n_gamma=method
    )
    if n_gamma is not None:
        assert model.n_gamma_value == pytest.approx(n_gamma, abs=0.06)
    q_kn = model.resistance(LEVELS * D) / 1e3
    np.testing.assert_allclose(q_kn, expected, rtol=0.01, atol=0.06)


def test_reference_geometry_numbers():
    np.testing.assert_allclose(
        contact_width(LEVELS * D, D), [0.300, 0.400, 0.4583, 0.4899, 0.500], atol=1e-4
    )
    z0 = surcharge_depth(LEVELS * D, D, math.radians(33.0))
    np.testing.assert_allclose(z0, [0.0, 0.0, 0.0019, 0.0228, 0.0635], atol=1e-4)
    comps = DrainedPenetration(diameter=D, unit_weight=16.7e3, friction_angle_deg=33).components(
        LEVELS * D
    )
    assert np.all(comps["d_q"] <= 1.021) and np.all(comps["d_q"] >= 1.0)


def test_n_q_and_n_gamma_hand_values():
    phi = math.radians(30.0)
    nq = math.exp(math.pi * math.tan(phi)) * math.tan(math.radians(60.0)) ** 2
    assert float(bearing_factor_n_q(phi)) == pytest.approx(18.401, abs=1e-3)
    assert float(bearing_factor_n_q(phi)) == pytest.approx(nq, rel=1e-14)
    assert float(bearing_factor_n_gamma(phi, "vesic")) == pytest.approx(22.40, abs=0.01)
    assert float(bearing_factor_n_gamma(phi, "meyerhof")) == pytest.approx(15.67, abs=0.01)
    assert float(bearing_factor_n_gamma(phi, "brinch_hansen")) == pytest.approx(15.07, abs=0.01)
    assert float(bearing_factor_n_gamma(phi, "davis_booker_rough")) == pytest.approx(
        0.1054 * math.exp(9.6 * phi), rel=1e-14
    )
    with pytest.raises(InputError, match="n_gamma"):
        bearing_factor_n_gamma(phi, "terzaghi")


@pytest.mark.parametrize(
    ("method", "phi_expected"),
    [
        ("vesic", 39.5),
        ("meyerhof", 40.3),
        ("davis_booker_rough", 40.9),
        ("brinch_hansen", 41.3),
        ("davis_booker_smooth", 45.1),
    ],
)
def test_friction_angle_for_75_kn_at_tenth_diameter(method, phi_expected):
    def q_minus_target(phi_deg: float) -> float:
        model = DrainedPenetration(
            diameter=D, unit_weight=16.7e3, friction_angle_deg=phi_deg, n_gamma=method
        )
        return float(model.resistance(0.1 * D)) - 75e3

    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OutOfRangeWarning)
        phi = brentq(q_minus_target, 30.0, 49.0, xtol=1e-6)
    assert phi == pytest.approx(phi_expected, abs=0.06)


def test_depth_factor_coefficient_option():
    z = 0.45 * D
    f114 = DrainedPenetration(diameter=D, unit_weight=16e3, friction_angle_deg=35)
    hansen = DrainedPenetration(
        diameter=D, unit_weight=16e3, friction_angle_deg=35, depth_factor_coefficient=2.0
    )
    c1, c2 = f114.components(z), hansen.components(z)
    phi = math.radians(35.0)
    extra = (c1["z_0"] / c1["B"]) * math.tan(phi) * (1.0 - math.sin(phi)) ** 2
    assert float(c1["d_q"]) == pytest.approx(1.0 + 1.2 * extra, rel=1e-13)
    assert float(c2["d_q"]) == pytest.approx(1.0 + 2.0 * extra, rel=1e-13)
    assert float(hansen.resistance(z)) > float(f114.resistance(z))


def test_bounds_definition_and_order():
    bounds = DrainedBounds.from_friction_angles(
        diameter=D, unit_weight=16.7e3, lower_friction_angle_deg=33, upper_friction_angle_deg=40
    )
    assert bounds.lower.n_gamma == "davis_booker_smooth"
    assert bounds.upper.n_gamma == "davis_booker_rough"
    lo, up = bounds.resistance(LEVELS * D)
    np.testing.assert_allclose(lo / 1e3, [10.6, 18.8, 25.0, 33.1, 43.5], rtol=0.01, atol=0.06)
    np.testing.assert_allclose(up / 1e3, [64.5, 114.6, 150.5, 180.5, 209.2], rtol=0.01)
    single = DrainedBounds.from_friction_angles(
        diameter=D, unit_weight=16.7e3, lower_friction_angle_deg=36
    )
    assert single.upper.friction_angle_deg == 36
    with pytest.raises(InputError, match="upper_friction_angle_deg"):
        DrainedBounds.from_friction_angles(
            diameter=D, unit_weight=16.7e3, lower_friction_angle_deg=40, upper_friction_angle_deg=33
        )


def test_clay_model2_hand_calculation():
    su0, rho, gamma = 2.0e3, 3.0e3, 6.0e3
    model = UndrainedModel2(diameter=D, su_mudline=su0, su_gradient=rho, unit_weight=gamma)
    # z/D = 0.1: the 6(z/D)^0.25 branch governs (3.374 < 3.4)
    z = 0.05
    r = D / 2
    area = r * r * math.acos((r - z) / r) - (r - z) * math.sqrt(2 * r * z - z * z)
    su = su0 + rho * z  # 2150 Pa at the invert
    expected = (6.0 * 0.1**0.25 + 1.5 * gamma * area / (D * su)) * D * su
    assert float(model.resistance(z)) == pytest.approx(expected, rel=1e-12)
    assert float(model.resistance(z)) == pytest.approx(3719.07, abs=0.01)
    # z/D = 0.05: the 3.4(10 z/D)^0.5 branch governs
    z = 0.025
    area = r * r * math.acos((r - z) / r) - (r - z) * math.sqrt(2 * r * z - z * z)
    su = su0 + rho * z
    expected = (3.4 * math.sqrt(0.5) + 1.5 * gamma * area / (D * su)) * D * su
    assert float(model.resistance(z)) == pytest.approx(expected, rel=1e-12)


def test_clay_model2_warns_beyond_half_diameter():
    model = UndrainedModel2(diameter=D, su_mudline=2e3, unit_weight=6e3)
    with pytest.warns(OutOfRangeWarning, match="Model 2"):
        model.resistance(0.6 * D)


def test_clay_model1_homogeneous_hand_calculation():
    # ρ = 0 → κ = 0 → F = 1 exactly; z = 0.1D is above the z_su0 threshold 0.146D → d_ca = 0
    su, gamma = 5.0e3, 6.0e3
    model = UndrainedModel1(diameter=D, su_mudline=su, unit_weight=gamma)
    z = 0.05
    b = 0.3
    r = D / 2
    area = r * r * math.acos((r - z) / r) - (r - z) * math.sqrt(2 * r * z - z * z)
    expected = (2 + math.pi) * su * b + gamma * area
    assert float(model.resistance(z)) == pytest.approx(expected, rel=1e-12)
    assert float(model.resistance(z)) == pytest.approx(7773.7, abs=0.1)
    # z = 0.3D: z_su0 = z + (D/2)(√2 − 1) − B/2; s_u1 = s_u2 = s_u → d_ca = 0.3·atan(z_su0/B)
    z = 0.15
    b = 2 * math.sqrt(D * z - z * z)
    z_su0 = z + 0.5 * D * (math.sqrt(2) - 1) - b / 2
    dca = 0.3 * math.atan(z_su0 / b)
    area = r * r * math.acos((r - z) / r) - (r - z) * math.sqrt(2 * r * z - z * z)
    expected = BEARING_FACTOR_NC * su * b * (1 + dca) + gamma * area
    comps = model.components(z)
    assert float(comps["z_su0"]) == pytest.approx(z_su0, rel=1e-12)
    assert float(comps["d_ca"]) == pytest.approx(dca, rel=1e-12)
    assert float(model.resistance(z)) == pytest.approx(expected, rel=1e-12)


def test_clay_model1_with_gradient_uses_f_factor():
    su0, rho, gamma = 2.0e3, 3.0e3, 6.0e3
    model = UndrainedModel1(diameter=D, su_mudline=su0, su_gradient=rho, unit_weight=gamma)
    z = 0.05  # B = 0.3, z_su0 = 0, κ = ρB/su0 = 0.45
    f = float(davis_booker_factor(0.45, 0.67))
    expected = f * (BEARING_FACTOR_NC * su0 + rho * 0.3 / 4) * 0.3 + gamma * float(
        penetrated_area(z, D)
    )
    assert float(model.resistance(z)) == pytest.approx(expected, rel=1e-12)


def test_davis_booker_factor_shape():
    k = np.linspace(0.0, 16.0, 65)
    smooth = davis_booker_factor(k, 0.0)
    rough = davis_booker_factor(k, 1.0)
    assert smooth[0] == 1.0 and rough[0] == 1.0
    assert np.all(np.diff(smooth) > 0) and np.all(np.diff(rough) > 0)
    assert np.all(rough[1:] > smooth[1:])
    mid = davis_booker_factor(k, 0.67)
    np.testing.assert_allclose(mid, smooth + 0.67 * (rough - smooth), rtol=1e-14)
    # points read on the Davis & Booker (1973) strip-footing curves (approximate; 2 %)
    assert float(davis_booker_factor(4.0, 1.0)) == pytest.approx(1.50, rel=0.02)
    assert float(davis_booker_factor(16.0, 1.0)) == pytest.approx(1.73, rel=0.02)
    assert float(davis_booker_factor(4.0, 0.0)) == pytest.approx(1.28, rel=0.02)
    assert float(davis_booker_factor(16.0, 0.0)) == pytest.approx(1.45, rel=0.02)
    with pytest.warns(OutOfRangeWarning, match="kappa"):
        davis_booker_factor(30.0)


def test_lay_factor_hand_calculation():
    # EI·K/T0² = 1e8·4e5/(5e5)² = 160 → 160^0.25 = 3.5566 → k = 0.6 + 0.4·3.5566
    k = lay_factor(bending_stiffness=1e8, secant_stiffness=4e5, bottom_tension=5e5)
    assert k == pytest.approx(0.6 + 0.4 * 160**0.25, rel=1e-14)
    assert k == pytest.approx(2.0226, abs=1e-4)
    # below 1 → floored at 1
    assert lay_factor(bending_stiffness=1e6, secant_stiffness=1e4, bottom_tension=1e6) == 1.0
    assert lay_validity_tension(1e8, 4e3) == pytest.approx((3 * 1e4 * 4e3) ** (2 / 3))
    with pytest.warns(OutOfRangeWarning, match="bottom_tension"):
        lay_factor(
            bending_stiffness=1e8, secant_stiffness=4e5, bottom_tension=2e5, submerged_weight=4e3
        )


def test_embedment_with_lay_factor_is_self_consistent():
    model = DrainedPenetration(diameter=D, unit_weight=16.7e3, friction_angle_deg=33)
    lay = LayConditions(bending_stiffness=1e8, bottom_tension=5e5)
    res = solve_embedment(model, 4e3, lay=lay)
    assert res.success and res.status is Status.CONVERGED and res.iterations > 1
    q = float(model.resistance(res.z))
    k = lay_factor(bending_stiffness=1e8, secant_stiffness=q / res.z, bottom_tension=5e5)
    assert res.lay_factor == pytest.approx(k, rel=1e-6)
    assert q == pytest.approx(k * 4e3, rel=1e-6)
    static = solve_embedment(model, 4e3)
    assert res.z > static.z and static.lay_factor == 1.0


def test_lay_iteration_not_converged_is_reported_not_raised():
    model = DrainedPenetration(diameter=D, unit_weight=16.7e3, friction_angle_deg=33)
    lay = LayConditions(bending_stiffness=1e8, bottom_tension=5e5)
    res = solve_embedment(model, 4e3, lay=lay, max_iterations=1)
    assert not res.success and res.status is Status.NOT_CONVERGED
    assert "did not converge" in res.message and res.as_dict()["status"] == -5
    assert res.iterations == 1 and len(res.history) == 2
    with pytest.raises(InputError, match="max_iterations"):
        solve_embedment(model, 4e3, lay=lay, max_iterations=0)


def test_resistance_model_from_inputs():
    pipe = Pipe(outer_diameter=D, submerged_weight=3e3)
    sand = Sand(submerged_unit_weight=16.7e3, friction_angle_deg=33)
    model = resistance_model(pipe, sand, n_gamma="vesic")
    assert isinstance(model, DrainedPenetration)
    assert float(model.resistance(0.1 * D)) / 1e3 == pytest.approx(26.4, abs=0.06)
    clay = Clay(
        undrained_shear_strength=2e3,
        strength_gradient=3e3,
        submerged_unit_weight=6e3,
        unit_weight=16e3,
    )
    assert isinstance(resistance_model(pipe, clay), UndrainedModel1)
    m2 = resistance_model(pipe, clay, clay_model=2)
    assert isinstance(m2, UndrainedModel2) and m2.su_gradient == 3e3
    with pytest.raises(InputError, match="Rock"):
        resistance_model(pipe, Rock())
    with pytest.raises(InputError, match="clay_model"):
        resistance_model(pipe, clay, clay_model=3)


@pytest.mark.parametrize(
    ("factory", "field"),
    [
        (
            lambda: DrainedPenetration(diameter=0.0, unit_weight=1e4, friction_angle_deg=30),
            "diameter",
        ),
        (
            lambda: DrainedPenetration(diameter=D, unit_weight=-1.0, friction_angle_deg=30),
            "unit_weight",
        ),
        (
            lambda: DrainedPenetration(diameter=D, unit_weight=1e4, friction_angle_deg=60),
            "friction_angle_deg",
        ),
        (
            lambda: DrainedPenetration(
                diameter=D, unit_weight=1e4, friction_angle_deg=30, n_gamma="bogus"
            ),
            "n_gamma",
        ),
        (lambda: UndrainedModel1(diameter=D, su_mudline=0.0, unit_weight=6e3), "su_mudline"),
        (
            lambda: UndrainedModel1(diameter=D, su_mudline=1e3, unit_weight=6e3, roughness=1.5),
            "roughness",
        ),
        (
            lambda: UndrainedModel2(diameter=D, su_mudline=1e3, su_gradient=-1.0, unit_weight=6e3),
            "su_gradient",
        ),
        (lambda: LayConditions(bending_stiffness=0.0, bottom_tension=1e5), "bending_stiffness"),
    ],
)
def test_bad_input_names_the_field(factory, field):
    with pytest.raises(InputError, match=field):
        factory()


def test_penetration_outside_zero_to_diameter_is_rejected():
    model = DrainedPenetration(diameter=D, unit_weight=1e4, friction_angle_deg=30)
    with pytest.raises(InputError, match=r"z = -0.01"):
        model.resistance(-0.01)
    with pytest.raises(InputError, match=r"\[0, D\]"):
        model.resistance(0.6)
    with pytest.raises(InputError, match="load"):
        solve_embedment(model, -1.0)


def test_friction_angle_outside_validity_warns():
    with pytest.warns(OutOfRangeWarning, match="friction_angle_deg"):
        DrainedPenetration(diameter=D, unit_weight=1e4, friction_angle_deg=47)


def test_curve_dataset_units_and_provenance(tmp_path):
    from onbottom.results import load_dataset, save_dataset

    model = DrainedPenetration(diameter=D, unit_weight=16.7e3, friction_angle_deg=36)
    bounds = DrainedBounds.from_friction_angles(
        diameter=D, unit_weight=16.7e3, lower_friction_angle_deg=33, upper_friction_angle_deg=40
    )
    emb = solve_embedment(model, 40e3)
    ds = penetration_curve(model, bounds=bounds, embedment=emb, n=21)
    assert ds["Q_v"].attrs["units"] == "N/m" and ds["z"].attrs["units"] == "m"
    assert ds["Q_v_lower"].attrs["units"] == "N/m" and ds["z_over_D"].attrs["units"] == "1"
    assert ds.attrs["model"] == "dnvgl_rp_f114_drained"
    assert "smooth" in ds.attrs["bound_definition"]
    assert ds.attrs["embedment_z"] == pytest.approx(emb.z)
    assert float(ds["z_over_D"][-1]) == pytest.approx(0.5)
    assert np.all(ds["Q_v_lower"] <= ds["Q_v"]) and np.all(ds["Q_v"] <= ds["Q_v_upper"])
    back = load_dataset(save_dataset(ds, tmp_path / "curve.nc"))
    np.testing.assert_allclose(back["Q_v"].values, ds["Q_v"].values)
    # a pair of clay models as bounds
    lo = UndrainedModel1(diameter=D, su_mudline=1e3, unit_weight=6e3)
    up = UndrainedModel1(diameter=D, su_mudline=3e3, unit_weight=6e3)
    mid = UndrainedModel1(diameter=D, su_mudline=2e3, unit_weight=6e3)
    ds2 = penetration_curve(mid, np.array([0.05, 0.1]), bounds=(lo, up))
    assert np.all(ds2["Q_v_lower"] < ds2["Q_v"]) and np.all(ds2["Q_v"] < ds2["Q_v_upper"])
    with pytest.raises(InputError, match="diameter"):
        penetration_curve(
            mid, bounds=(lo, UndrainedModel1(diameter=1.0, su_mudline=1e3, unit_weight=6e3))
        )
