"""F109 tables, absolute lateral stability (Eqs 3.38–3.41) and vertical stability (Eq 3.1)."""

from __future__ import annotations

import math
import warnings

import pytest

from onbottom.checks import absolute_lateral_stability, peak_load_coefficients, vertical_stability
from onbottom.checks.absolute import seabed_roughness
from onbottom.checks.f109_tables import CY_TABLE, CZ_TABLE, K_GRID, M_GRID, safety_factor
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro.reductions import penetration_reduction
from onbottom.inputs import Clay, Pipe, Rock, Sand
from onbottom.soil.verley_sotberg import initial_penetration

SAND = Sand(submerged_unit_weight=10.0e3)


def test_tables_at_grid_nodes_and_spec_values():
    for i, m in enumerate(M_GRID):
        for j, k in enumerate(K_GRID):
            cy, cz = peak_load_coefficients(k, m)
            assert cy == pytest.approx(CY_TABLE[i, j]) and cz == pytest.approx(CZ_TABLE[i, j])
    # spot values of the spec transcription (dnv-reference.md §2.5)
    assert peak_load_coefficients(2.5, 0.0) == pytest.approx((13.0, 5.0))
    assert peak_load_coefficients(20.0, 0.4) == pytest.approx((1.78, 1.82))
    assert peak_load_coefficients(140.0, 0.1) == pytest.approx((1.22, 0.97))


def test_bilinear_interpolation_and_small_k_rule():
    cy, cz = peak_load_coefficients(15.0, 0.15)
    assert cy == pytest.approx((3.72 + 2.72 + 3.15 + 2.30) / 4.0)
    assert cz == pytest.approx((4.23 + 2.87 + 3.74 + 2.60) / 4.0)
    cy, cz = peak_load_coefficients(1.25, 0.0)
    assert cy == pytest.approx(13.0 * 2.5 / 1.25) and cz == pytest.approx(5.0)


def test_out_of_table_warns_and_uses_edge():
    with pytest.warns(OutOfRangeWarning, match="K"):
        cy, _ = peak_load_coefficients(200.0, 0.0)
    assert cy == pytest.approx(1.30)
    with pytest.raises(InputError):
        peak_load_coefficients(-1.0, 0.0)


def test_safety_factors():
    assert safety_factor("north_sea_winter", "sand", "normal") == 1.32
    assert safety_factor("north_sea_winter", "rock", "high") == 1.67
    assert safety_factor("gulf_of_mexico_cyclonic", "clay", "high") == 2.54
    with pytest.raises(InputError, match="safety_class = 'medium'"):
        safety_factor("north_sea_winter", "sand", "medium")


def test_absolute_check_assembles_eqs_3_38_to_3_41_on_rock():
    pipe = Pipe(outer_diameter=0.5, submerged_weight=3000.0)
    r = absolute_lateral_stability(
        pipe, Rock(friction_coefficient=0.6), hs=3.0, tp=9.0, depth=20.0, current_velocity=0.3
    )
    o = r.oscillation
    assert r.penetration == 0.0 and r.passive_resistance == 0.0
    assert r.r_y == 1.0 and r.r_z == pytest.approx(0.7)  # rock: permeable, no penetration
    q = 0.5 * 1025.0 * 0.5 * (float(o.u_star) + float(o.v_star)) ** 2
    cy, cz = peak_load_coefficients(o.k_star, o.m_star)
    assert r.f_y == pytest.approx(cy * q) and r.f_z == pytest.approx(0.7 * cz * q)
    g = 1.32
    assert r.utilisation_lateral == pytest.approx(g * (r.f_y + 0.6 * r.f_z) / (0.6 * 3000.0))
    assert r.utilisation_vertical == pytest.approx(g * r.f_z / 3000.0)
    assert r.utilisation == max(r.utilisation_lateral, r.utilisation_vertical)


def test_absolute_check_sand_penetration_and_passive_resistance():
    pipe = Pipe(outer_diameter=0.4, submerged_weight=2500.0)
    r = absolute_lateral_stability(pipe, SAND, hs=2.0, tp=8.0, depth=15.0)
    assert r.penetration == pytest.approx(initial_penetration(10.0e3, 0.4, 2500.0))
    assert r.r_y == pytest.approx(1.0 - 1.4 * r.penetration / 0.4)
    fc = 2500.0 - r.f_z
    ks = 10.0e3 * 0.16 / fc
    assert ks < 26.7
    assert r.passive_resistance == pytest.approx(
        10.0e3 * 0.16 * (5.0 - 0.15 * ks) * (r.penetration / 0.4) ** 1.25
    )


def test_heavier_pipe_lower_utilisation_and_clay_uses_its_gamma():
    kw = {"hs": 3.0, "tp": 9.0, "depth": 20.0, "current_velocity": 0.5}
    light = absolute_lateral_stability(
        Pipe(outer_diameter=0.5, submerged_weight=2000.0), SAND, **kw
    )
    heavy = absolute_lateral_stability(
        Pipe(outer_diameter=0.5, submerged_weight=6000.0), SAND, **kw
    )
    assert heavy.utilisation < light.utilisation
    clay = Clay(undrained_shear_strength=5e3, submerged_unit_weight=8e3, unit_weight=18e3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OutOfRangeWarning)
        rc = absolute_lateral_stability(
            Pipe(outer_diameter=0.5, submerged_weight=2000.0), clay, **kw
        )
    assert rc.gamma_sc == 1.40
    # clay is not permeable: r_z = r_pen,z only (Eq 3.20)
    assert rc.r_z == pytest.approx(float(penetration_reduction(rc.penetration / 0.5)[1]))


def test_roughness_from_d50():
    assert seabed_roughness(Sand(submerged_unit_weight=1e4, d50=0.25e-3)) == pytest.approx(1e-5)
    assert seabed_roughness(Sand(submerged_unit_weight=1e4, d50=1.0e-3)) == pytest.approx(1e-4)
    mid = seabed_roughness(Sand(submerged_unit_weight=1e4, d50=math.sqrt(0.25e-3 * 0.5e-3)))
    assert mid == pytest.approx(math.sqrt(1e-5 * 4e-5))


def test_vertical_stability_hand_calculation():
    pipe = Pipe(outer_diameter=0.5, submerged_weight=100.0)
    b = pipe.buoyancy
    r = vertical_stability(pipe)
    assert r.utilisation == pytest.approx(1.1 * b / (100.0 + b))
    assert r.passes is False  # s_g ≈ 1.05 < 1.1
    assert vertical_stability(Pipe(outer_diameter=0.5, submerged_weight=2000.0)).passes


def test_bad_inputs():
    with pytest.raises(InputError, match="pipe = "):
        absolute_lateral_stability("pipe", SAND, hs=1.0, tp=5.0, depth=10.0)
    with pytest.raises(InputError, match="region = 'arctic'"):
        absolute_lateral_stability(
            Pipe(outer_diameter=0.5, submerged_weight=1e3),
            SAND,
            hs=1.0,
            tp=5.0,
            depth=10.0,
            region="arctic",
        )


def test_sea_state_wrapper_matches_keywords():
    from onbottom.checks import absolute_stability_of_sea_state
    from onbottom.inputs.storm import Current, SeaState

    pipe = Pipe(outer_diameter=0.4, submerged_weight=2500.0)
    ss = SeaState(hs=2.0, tp=8.0, direction_deg=270.0, spreading_s=6.0)
    cur = Current(velocity=0.4, reference_height=2.0, direction_deg=270.0)
    a = absolute_stability_of_sea_state(pipe, SAND, ss, cur, 15.0, safety_class="high")
    b = absolute_lateral_stability(
        pipe, SAND, hs=2.0, tp=8.0, depth=15.0, current_velocity=0.4,
        current_reference_height=2.0, wave_direction_deg=270.0, current_direction_deg=90.0,
        spreading_s=6.0, safety_class="high",
    )  # fmt: skip
    assert a.utilisation == pytest.approx(b.utilisation)
    assert absolute_stability_of_sea_state(pipe, SAND, ss, None, 15.0).oscillation.v_star == 0.0
