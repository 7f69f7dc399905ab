"""Unit test: :mod:`onbottom.soil.backbone` — the Verley & Sotberg backbone of ``onbottom
backbone``, called directly, against hand calculations."""

from __future__ import annotations

import pytest

from onbottom.errors import InputError
from onbottom.inputs import Pipe, Sand
from onbottom.soil.backbone import backbone_run, backbone_validity, verley_sotberg_variant

PIPE = Pipe(outer_diameter=1.0, submerged_weight=10.52e3)
SAND = Sand(submerged_unit_weight=7.5e3, friction_coefficient=0.48)


def test_variants_and_factors():
    calc = verley_sotberg_variant("calcareous", PIPE, SAND)
    assert (calc.A, calc.B, calc.C) == (0.25, 0.35, 0.98)  # Youssef & Cassidy 2014 Table 3
    assert calc.y1 == pytest.approx(0.01)  # regions 0.01D/0.25D/0.75D
    silica = verley_sotberg_variant("silica", PIPE, SAND, A=0.8)
    assert silica.A == 0.8 and silica.y1 == pytest.approx(0.02)
    assert verley_sotberg_variant("f109", PIPE, SAND).passive_law == "dnv_f109"
    assert (
        verley_sotberg_variant("silica", PIPE, SAND, installation_load=40e3).installation_load
        == 40e3
    )
    with pytest.raises(InputError, match="variant"):
        verley_sotberg_variant("clay", PIPE, SAND)


def test_backbone_by_hand():
    run = backbone_run("calcareous", PIPE, SAND, factors={"A": None, "C": 0.98})
    ks = 7.5e3 * 1.0**2 / 10.52e3  # K_s = γ'D²/V
    assert run.points["K_s"] == pytest.approx(ks)
    # Eq 7 with W = V: z_i = D·C·0.037·K_s^-0.67
    assert run.points["z_i"] == pytest.approx(0.98 * 0.037 * ks**-0.67, rel=1e-12)
    assert run.points["z2"] == run.points["z_i"]  # no penetration given: z2 = z_i
    assert run.points["F_f"] == pytest.approx(0.48 * 10.52e3)  # F_f = μV
    assert run.vertical_load == 10.52e3 and run.path is None and run.validity() == []
    payload = run.as_dict()
    assert list(payload) == ["model", "parameters", "vertical_load", "backbone"]
    assert payload["model"] == "calcareous" and payload["parameters"]["A"] == 0.25
    deeper = backbone_run("calcareous", PIPE, SAND, penetration=0.1)
    assert deeper.points["z2"] == 0.1


def test_cyclic_path_summary():
    run = backbone_run("silica", PIPE, SAND, cycles=1.0)
    assert run.amplitude == pytest.approx(0.1)  # default 0.1·D
    path = run.path_summary()
    assert path["cycles"] == 1.0 and path["amplitude"] == run.amplitude
    assert path["final_penetration"] == float(run.path["z"].values[-1])
    assert path["final_penetration"] >= run.points["z_i"]  # the trough only deepens
    assert path["max_resistance"] > 0.0 and run.as_dict()["path"] == path


def test_validity_is_penetration_above_half_d():
    pts = {"z_i": 0.6, "z2": 0.5, "z3": 0.2}
    assert backbone_validity(pts, 1.0) == ["z_i = 0.6 m exceeds D/2 = 0.5 m"]
    assert backbone_validity(pts, 2.0, final_penetration=1.25) == [
        "the path's penetration 1.25 m exceeds D/2 = 1 m"
    ]
    assert backbone_validity(pts, 2.0, final_penetration=1.0) == []
