"""Pipe build-up: hand calculations of D, mass, w_s, s_g, EI, EA per condition."""

from __future__ import annotations

import math

import pytest

from onbottom.constants import GRAVITY
from onbottom.errors import InputError
from onbottom.inputs import Layer, Pipe
from onbottom.inputs.pipe_buildup import CONDITIONS, Contents, PipeBuildUp


def _sheet(**kw) -> PipeBuildUp:
    return PipeBuildUp(
        steel_outer_diameter=0.2191,
        wall_thickness=0.0127,
        layers=(
            Layer(name="corrosion", thickness=0.0055, density=1335.0),
            Layer(name="concrete", thickness=0.08255, density=3043.5),
        ),
        **kw,
    )


def test_hand_calculation_of_a_bare_tube():
    # steel tube D_s = 1, t = 0.1, ρ = 8000, contents 1000: areas π(1 − 0.64)/4, π 0.64/4
    b = PipeBuildUp(
        steel_outer_diameter=1.0,
        wall_thickness=0.1,
        steel_density=8000.0,
        youngs_modulus=2.0e11,
        contents=Contents.uniform(1000.0),
        seawater_density=1000.0,
    )
    p = b.properties("operation")
    a_steel = math.pi * 0.36 / 4.0
    assert p.outer_diameter == pytest.approx(1.0)
    assert p.mass == pytest.approx(8000.0 * a_steel + 1000.0 * math.pi * 0.64 / 4.0)
    assert p.buoyancy == pytest.approx(1000.0 * GRAVITY * math.pi / 4.0)
    assert p.submerged_weight == pytest.approx(p.mass * GRAVITY - p.buoyancy)
    assert p.specific_gravity == pytest.approx(p.mass * GRAVITY / p.buoyancy)
    assert p.axial_stiffness == pytest.approx(2.0e11 * a_steel)
    assert p.bending_stiffness == pytest.approx(2.0e11 * math.pi * (1.0 - 0.8**4) / 64.0)


def test_design_sheet_pipe_diameter_and_specific_gravity():
    # public F109 design sheet: D 0.3951 m (rounded sheet value), s_g 2.7585
    p = _sheet(contents=Contents.uniform(1025.0)).properties("operation")
    assert p.outer_diameter == pytest.approx(0.3952, abs=1e-12)
    assert p.outer_diameter == pytest.approx(0.3951, abs=1.5e-4)
    assert p.specific_gravity == pytest.approx(2.7585, rel=2e-4)


def test_conditions_differ_only_by_contents():
    b = _sheet(contents=Contents(installation=0.0, operation=800.0))
    props = {c: b.properties(c) for c in CONDITIONS}
    di = props["installation"].steel_inner_diameter
    assert props["flooded"].mass - props["installation"].mass == pytest.approx(
        1025.0 * math.pi * di**2 / 4.0
    )
    assert props["operation"].contents_mass == pytest.approx(800.0 * math.pi * di**2 / 4.0)
    assert len({props[c].outer_diameter for c in CONDITIONS}) == 1


def test_marine_growth_adds_diameter_and_mass():
    bare = _sheet()
    grown = _sheet(marine_growth=Layer(name="marine growth", thickness=0.05, density=1325.0))
    assert grown.outer_diameter == pytest.approx(bare.outer_diameter + 0.1)
    d0, d1 = bare.outer_diameter, grown.outer_diameter
    dm = grown.properties().mass - bare.properties().mass
    assert dm == pytest.approx(1325.0 * math.pi * (d1**2 - d0**2) / 4.0)


def test_pipe_and_from_layers_agree_and_simple_pipe_still_works():
    b = _sheet(contents=Contents.uniform(1025.0))
    p = b.pipe("operation")
    q = Pipe.from_layers(
        steel_outer_diameter=0.2191, wall_thickness=0.0127, layers=b.layers, contents_density=1025.0
    )
    assert p.submerged_weight == pytest.approx(q.submerged_weight)
    assert p.axial_stiffness == pytest.approx(q.axial_stiffness) and p.axial_stiffness > 0
    simple = Pipe(outer_diameter=0.4, submerged_weight=1500.0)
    assert simple.axial_stiffness == 0.0


def test_with_layer_thickness():
    b = _sheet().with_layer_thickness("concrete", 0.03)
    assert b.layers[1].thickness == 0.03
    with pytest.raises(InputError, match="layer = 'concret'"):
        b.with_layer_thickness("concret", 0.03)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"wall_thickness": 0.2}, "PipeBuildUp.wall_thickness"),
        ({"wall_thickness": 0.0}, "PipeBuildUp.wall_thickness"),
        ({"steel_density": -1.0}, "PipeBuildUp.steel_density"),
        ({"youngs_modulus": float("nan")}, "PipeBuildUp.youngs_modulus"),
    ],
)
def test_bad_input_names_field(kwargs, field):
    base = {"steel_outer_diameter": 0.3, "wall_thickness": 0.01}
    with pytest.raises(InputError, match=field):
        PipeBuildUp(**{**base, **kwargs})


def test_floating_pipe_and_unknown_condition():
    b = PipeBuildUp(steel_outer_diameter=0.5, wall_thickness=0.005)
    assert b.properties("installation").submerged_weight < 0.0
    with pytest.raises(InputError, match="floats"):
        b.pipe("installation")
    with pytest.raises(InputError, match="condition = 'storm'"):
        b.properties("storm")
    with pytest.raises(InputError, match="Contents.flooded"):
        Contents(flooded=-1.0)
