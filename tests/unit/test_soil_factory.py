"""Unit tests: lateral_model factory."""

from __future__ import annotations

import pytest

from onbottom import Clay, InputError, Pipe, Rock, Sand
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.factory import LATERAL_MODELS, lateral_model
from onbottom.soil.verley_lund import VerleyLund
from onbottom.soil.verley_sotberg import VerleySotberg

PIPE = Pipe(outer_diameter=0.5, submerged_weight=2.0e3)
SAND = Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6)
CLAY = Clay(undrained_shear_strength=5.0e3, submerged_unit_weight=6.0e3, unit_weight=16.0e3)


def test_names_build_the_right_models():
    assert isinstance(
        lateral_model("coulomb", PIPE, Rock(friction_coefficient=0.7)), CoulombFriction
    )
    m = lateral_model("coulomb", PIPE, Rock(friction_coefficient=0.7))
    assert m.friction_coefficient == 0.7
    s = lateral_model("verley_sotberg_silica", PIPE, SAND)
    assert isinstance(s, VerleySotberg) and s.variant == "silica"
    c = lateral_model("verley_sotberg_calcareous", PIPE, SAND, A=0.3)
    assert c.variant == "calcareous" and c.A == 0.3
    f = lateral_model("verley_sotberg_f109", PIPE, SAND)
    assert f.passive_law == "dnv_f109"
    assert isinstance(lateral_model("verley_lund", PIPE, CLAY), VerleyLund)
    assert set(LATERAL_MODELS) >= {  # the built-in ones (tests may register more)
        "coulomb",
        "verley_sotberg_silica",
        "verley_sotberg_calcareous",
        "verley_sotberg_f109",
        "verley_lund",
        "vh_parabolic",
    }


def test_bad_name_or_seabed():
    with pytest.raises(InputError, match="lateral_model.name"):
        lateral_model("mohr", PIPE, SAND)
    with pytest.raises(InputError, match="lateral_model.seabed"):
        lateral_model("verley_lund", PIPE, SAND)
    with pytest.raises(InputError, match="lateral_model.seabed"):
        lateral_model("verley_sotberg_silica", PIPE, Rock())
