"""Strict case-file schema of the stability/loads commands: forms, inheritance, errors."""

from __future__ import annotations

import pytest

from onbottom._casefile import CaseFileError
from onbottom.cases.stability import load_stability_case
from onbottom.inputs import Clay, Pipe, PipeBuildUp, Rock, Sand

BASE = """
[seabed]
model = "sand"
submerged_unit_weight = 9.0e3
[environment]
water_depth = 20.0
[waves]
hs = 3.0
tp = 9.0
spreading_s = 4.0
[current]
velocity = 0.4
reference_height = 2.0
"""
SIMPLE = '[pipe]\nouter_diameter = 0.4\nsubmerged_weight = 1500.0\ncondition = "installation"\n'


def _load(tmp_path, text):
    p = tmp_path / "c.toml"
    p.write_text(text, encoding="utf-8")
    return load_stability_case(p)


def test_simple_pipe_and_default_combination(tmp_path):
    case = _load(tmp_path, SIMPLE + BASE)
    assert isinstance(case.section(), Pipe)
    (combo,) = case.load_combinations()
    assert combo.name == "design" and combo.condition == "installation"
    assert combo.sea_state.spreading_s == 4.0 and combo.current.velocity == 0.4
    assert isinstance(case.seabed.seabed(), Sand)


def test_combinations_inherit_and_override(tmp_path):
    text = (
        SIMPLE
        + BASE
        + (
            '[[combinations]]\nname = "a"\n[[combinations]]\nname = "b"\nhs = 4.0\n'
            'current_velocity = 0.8\ncondition = "operation"\n'
        )
    )
    a, b = _load(tmp_path, text).load_combinations()
    assert (a.sea_state.hs, a.current.velocity, a.condition) == (3.0, 0.4, "installation")
    assert (b.sea_state.hs, b.sea_state.tp, b.current.velocity) == (4.0, 9.0, 0.8)
    assert b.current.reference_height == 2.0 and b.condition == "operation"


def test_buildup_with_contents_table_and_marine_growth(tmp_path):
    text = (
        "[pipe]\nsteel_outer_diameter = 0.3\nwall_thickness = 0.015\n"
        "[pipe.contents]\noperation = 800.0\n"
        '[[pipe.layers]]\nname = "concrete"\nthickness = 0.05\ndensity = 3000.0\n'
        "[pipe.marine_growth]\nthickness = 0.02\ndensity = 1300.0\n" + BASE
    )
    sec = _load(tmp_path, text).section()
    assert isinstance(sec, PipeBuildUp)
    assert sec.outer_diameter == pytest.approx(0.3 + 0.1 + 0.04)
    assert sec.contents.operation == 800.0 and sec.contents.flooded == 1025.0


def test_clay_and_rock(tmp_path):
    clay = BASE.replace(
        "submerged_unit_weight = 9.0e3",
        "submerged_unit_weight = 6.0e3\nunit_weight = 16.0e3\nundrained_shear_strength = 4e3",
    ).replace('model = "sand"', 'model = "clay"')
    assert isinstance(_load(tmp_path, SIMPLE + clay).seabed.seabed(), Clay)
    rock = BASE.replace('model = "sand"', 'model = "rock"')
    with pytest.raises(CaseFileError, match="submerged_unit_weight does not apply to model"):
        _load(tmp_path, SIMPLE + rock)  # a sand key on rock: refused, not silently unused
    rock = rock.replace("submerged_unit_weight = 9.0e3\n", "friction_coefficient = 0.6\n")
    assert isinstance(_load(tmp_path, SIMPLE + rock).seabed.seabed(), Rock)


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        (SIMPLE.replace("submerged_weight = 1500.0\n", "") + BASE, "both outer_diameter"),
        (SIMPLE + BASE.replace('model = "sand"', 'model = "clay"'), "undrained_shear_strength"),
        (SIMPLE + BASE + '[[combinations]]\nname = "a"\n[[combinations]]\nname = "a"\n', "unique"),
        (SIMPLE + BASE + '[design]\nsolve_for = "concrete_thickness"\n', "build-up"),
        (SIMPLE + BASE + "[design]\nthickness_min = 0.2\nthickness_max = 0.1\n", "thickness_max"),
        (SIMPLE + BASE + "[stom]\nseed = 1\n", "did you mean 'storm'"),
        (SIMPLE + BASE.replace("spreading_s = 4.0", "spreading_s = -1.0"), "waves.spreading_s"),
        (
            SIMPLE
            + BASE.replace("tp = 9.0", 'tp = 9.0\ngamma = 2.0\nspectrum = "pierson-moskowitz"'),
            "JONSWAP",
        ),
    ],
)
def test_errors(tmp_path, text, needle):
    with pytest.raises(CaseFileError, match=needle):
        _load(tmp_path, text)
