"""Unit tests: input validation and derived pipe properties (hand calculations)."""

from __future__ import annotations

import math

import pytest

from onbottom import InputError
from onbottom.constants import GRAVITY
from onbottom.inputs import Clay, Layer, Pipe, Rock, Sand


def test_pipe_derived_mass_from_submerged_weight():
    p = Pipe(outer_diameter=1.0, submerged_weight=10_000.0, seawater_density=1025.0)
    b = 1025.0 * GRAVITY * math.pi / 4.0  # 7894.9 N/m
    assert p.buoyancy == pytest.approx(b)
    assert p.structural_mass == pytest.approx((10_000.0 + b) / GRAVITY)
    assert p.specific_gravity == pytest.approx((10_000.0 + b) / b)
    # C_a = 2.29 on a plane wall: 2.29·1025·π/4 = 1843.6 kg/m
    assert p.added_mass() == pytest.approx(2.29 * 1025.0 * math.pi / 4.0)


def test_pipe_from_layers_hand_calculation():
    # 0.3239 m steel, 15.9 mm wall, 50 mm concrete at 3040 kg/m3, empty
    p = Pipe.from_layers(
        steel_outer_diameter=0.3239,
        wall_thickness=0.0159,
        layers=(Layer(thickness=0.05, density=3040.0, name="concrete"),),
    )
    di = 0.3239 - 2 * 0.0159
    m_steel = 7850.0 * math.pi / 4 * (0.3239**2 - di**2)
    d = 0.3239 + 0.1
    m_conc = 3040.0 * math.pi / 4 * (d**2 - 0.3239**2)
    ws = (m_steel + m_conc) * GRAVITY - 1025.0 * GRAVITY * math.pi / 4 * d**2
    assert p.outer_diameter == pytest.approx(d)
    assert p.submerged_weight == pytest.approx(ws)
    assert p.bending_stiffness == pytest.approx(207e9 * math.pi / 64 * (0.3239**4 - di**4))


def test_floating_pipe_is_rejected_with_field_name():
    with pytest.raises(InputError, match="submerged_weight"):
        Pipe.from_layers(steel_outer_diameter=1.0, wall_thickness=0.01)


@pytest.mark.parametrize(
    ("factory", "field", "value"),
    [
        (lambda v: Pipe(outer_diameter=v, submerged_weight=1.0), "Pipe.outer_diameter", -1.0),
        (lambda v: Pipe(outer_diameter=1.0, submerged_weight=v), "Pipe.submerged_weight", 0.0),
        (lambda v: Sand(submerged_unit_weight=v), "Sand.submerged_unit_weight", -5.0),
        (
            lambda v: Sand(submerged_unit_weight=8e3, friction_coefficient=v),
            "Sand.friction_coefficient",
            3.0,
        ),
        (
            lambda v: Sand(submerged_unit_weight=8e3, friction_angle_deg=v),
            "Sand.friction_angle_deg",
            80.0,
        ),
        (
            lambda v: Clay(undrained_shear_strength=v, submerged_unit_weight=6e3, unit_weight=16e3),
            "Clay.undrained_shear_strength",
            -1.0,
        ),
        (lambda v: Rock(friction_coefficient=v), "Rock.friction_coefficient", 0.0),
    ],
)
def test_bad_input_names_field_value_and_range(factory, field, value):
    with pytest.raises(InputError) as info:
        factory(value)
    msg = str(info.value)
    assert field in msg and repr(float(value)) in msg
    assert "must" in msg


@pytest.mark.parametrize("value", [float("nan"), float("inf"), "1.0", None, True])
def test_non_numbers_are_rejected(value):
    with pytest.raises(InputError, match="Pipe.outer_diameter"):
        Pipe(outer_diameter=value, submerged_weight=1.0)


def test_inputs_are_immutable():
    p = Pipe(outer_diameter=1.0, submerged_weight=1.0)
    with pytest.raises(AttributeError):
        p.outer_diameter = 2.0  # type: ignore[misc]


def test_clay_strength_profile():
    c = Clay(
        undrained_shear_strength=2e3,
        strength_gradient=1.5e3,
        submerged_unit_weight=6e3,
        unit_weight=16e3,
    )
    assert c.strength_at(0.5) == pytest.approx(2.75e3)
    assert c.strength_at(-1.0) == pytest.approx(2e3)
