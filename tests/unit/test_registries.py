"""Unit tests: the soil-model and design-check registries (one name → class list each)."""

from __future__ import annotations

import pytest

from onbottom import Clay, InputError, Pipe, Rock, Sand
from onbottom.checks.design import CheckOptions, run_checks
from onbottom.checks.registry import CHECKS, check_names, get_check
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.storm import Current, SeaState
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.factory import LATERAL_MODELS
from onbottom.soil.registry import (
    SEABED_MODELS,
    SOIL_MODELS,
    build_soil_model,
    soil_model_entry,
    soil_model_for_seabed,
)
from onbottom.soil.registry import soil_model_for_seabed as soil_model
from onbottom.soil.verley_lund import VerleyLund
from onbottom.soil.verley_sotberg import VerleySotberg

PIPE = Pipe(outer_diameter=0.5, submerged_weight=2.0e3)
SAND = Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6)
CLAY = Clay(undrained_shear_strength=5.0e3, submerged_unit_weight=6.0e3, unit_weight=16.0e3)


def test_soil_registry_is_the_one_list():
    assert set(LATERAL_MODELS) == set(SOIL_MODELS)
    assert set(SEABED_MODELS.values()) <= set(SOIL_MODELS)
    assert soil_model_entry("verley_lund").cls is VerleyLund


def test_seabed_kinds_build_the_models_of_before():
    # the [seabed] model vocabulary of the storm and F109 case files
    m = soil_model("sand", PIPE, SAND)
    assert isinstance(m, VerleySotberg) and m.variant == "silica"
    assert soil_model("calcareous", PIPE, SAND).variant == "calcareous"
    assert isinstance(soil_model("clay", PIPE, CLAY), VerleyLund)
    rock = Rock(friction_coefficient=0.7)
    r = soil_model("rock", PIPE, rock)
    assert isinstance(r, CoulombFriction) and r.friction_coefficient == 0.7
    assert soil_model_for_seabed("coulomb", PIPE, SAND).friction_coefficient == 0.6


def test_unknown_soil_name_lists_the_choices():
    with pytest.raises(InputError, match=r"soil\.model = 'mohr' is invalid.*'coulomb'"):
        build_soil_model("mohr", PIPE, SAND)
    with pytest.raises(InputError, match=r"seabed\.model = 'peat'.*'sand'"):
        soil_model_for_seabed("peat", PIPE, SAND)
    with pytest.raises(InputError, match="Clay"):
        build_soil_model("verley_lund", PIPE, SAND)


def _case():
    env = Environment(water_depth=20.0)
    combo = LoadCombination(
        name="c1",
        sea_state=SeaState(hs=3.0, tp=9.0),
        current=Current(velocity=0.3, reference_height=3.0),
        condition="operation",
    )
    return env, [combo]


def test_check_registry_names_and_order():
    assert check_names()[:2] == ("vertical", "absolute")
    assert get_check("absolute").rows == ("absolute_lateral", "absolute_vertical")
    env, combos = _case()
    pipe = Pipe(outer_diameter=0.5, submerged_weight=2.0e3)
    rows = run_checks(pipe, SAND, env, combos)
    assert [r.name for r in rows] == ["vertical_stability", "absolute_lateral", "absolute_vertical"]
    only = run_checks(pipe, SAND, env, combos, CheckOptions(checks=("absolute",)))
    assert [r.name for r in only] == ["absolute_lateral", "absolute_vertical"]
    assert only[0].utilisation == rows[1].utilisation


def test_unknown_check_lists_the_choices():
    with pytest.raises(InputError, match=r"checks = 'generalised' is invalid.*'vertical'"):
        CheckOptions(checks=("generalised",))
    assert "vertical" in CHECKS


def test_snapshot_of_an_unloaded_registry_keeps_the_builtin_entries():
    """A snapshot taken before the first look-up still holds the built-in entries, so a
    restore after a test's own registrations leaves the registry as a user would find it."""
    from dataclasses import dataclass

    from onbottom.registry import Registry

    @dataclass(frozen=True)
    class Entry:
        name: str
        description: str = "test"
        options: None = None

    reg: Registry[Entry] = Registry("thing", "things", loader=lambda: reg.add(Entry("builtin")))
    saved = reg.snapshot()
    assert list(saved) == ["builtin"]
    reg.add(Entry("extra"))
    reg.restore(saved)
    assert reg.names() == ("builtin",)
