"""StormModel: a row of inputs → the storm that runs (hand-checked mappings), its identity,
and the inputs it refuses."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from onbottom._casefile import parse_case
from onbottom.cases.storm import StormCase, build_setup
from onbottom.errors import InputError
from onbottom.reliability.dynamic import rank_importance, seeds_from_uniform
from onbottom.reliability.storm_model import StormModel
from reliability_cases import CLIMATE

ROOT = Path(__file__).resolve().parents[2]


def _setup(**storm):
    doc = tomllib.loads((ROOT / "examples" / "storm_case.toml").read_text())
    doc["storm"].update(storm)
    return build_setup(parse_case(StormCase, doc))


def test_climate_row_maps_to_the_storm_by_hand():
    m = StormModel(
        _setup(),
        inputs=("friction_coefficient", "current_velocity"),
        climate=CLIMATE,
        pipe_heading_deg=30.0,
    )
    assert m.input_names == (
        "u_hs",
        "u_tp",
        "u_direction",
        "friction_coefficient",
        "current_velocity",
    )
    # u_hs = 0 → the GPD median: u + σ/ξ((1/2)^-ξ − 1); u_tp = 0 → exp(μ(H_s));
    # Φ(0.2) = 0.579 → third sector (cumulative 0.1, 0.3, 0.6): S, 180° − 30° = 150°
    x = np.array([0.0, 0.0, 0.2, 0.5, 0.3])
    hs = 4.0 + 0.7 / -0.1 * (0.5**0.1 - 1.0)
    soil, storm, current = m.build(x, 7)
    peak = storm.stages[0]
    assert peak.hs == pytest.approx(hs, rel=1e-12)
    assert peak.tp == pytest.approx(math.exp(0.8 + 1.27 * hs**0.131), rel=1e-12)
    assert peak.direction_deg == pytest.approx(150.0)
    assert storm.seed == 7 and current.velocity == 0.3
    assert soil.name == "verley_sotberg"


def test_identity_follows_the_case_and_refusals():
    a = StormModel(_setup(), inputs=("hs", "tp"))
    b = StormModel(_setup(peak_hours=2.0), inputs=("hs", "tp"))
    assert a.identity() == StormModel(_setup(), inputs=("hs", "tp")).identity()
    assert a.identity() != b.identity()
    with pytest.raises(InputError, match="hs and tp"):
        StormModel(_setup(), inputs=("friction_coefficient",))
    with pytest.raises(InputError, match="one of"):
        StormModel(_setup(), inputs=("hs", "tp", "wave_height"))
    with pytest.raises(InputError, match="climate"):
        StormModel(_setup(), inputs=("hs",), climate=CLIMATE)


def test_seed_mapping_and_rank_importance():
    assert seeds_from_uniform(np.array([0.0, 0.5, 1.0])).tolist() == [0, 2**30, 2**31 - 1]
    rng = np.random.default_rng(1)
    x = rng.normal(size=(2000, 2))
    y = np.exp(2.0 * x[:, 0] + 1.0 * x[:, 1])  # monotone: SRRC² ∝ 4 : 1, R² ≈ 1
    imp = rank_importance(x, y, ["a", "b"])
    assert imp["a"] / imp["b"] == pytest.approx(4.0, rel=0.15)
    assert imp["storm_seed and interactions"] < 0.05
    assert sum(imp.values()) == pytest.approx(1.0)


def test_rank_importance_shares_sum_to_one_with_correlated_columns():
    """A small block whose columns are nearly collinear: raw SRRC² (about 1 + 2·0.99·c1·c2 per
    unit variance) would sum well above 1; the printed shares sum to one."""
    rng = np.random.default_rng(3)
    a = rng.normal(size=20)
    x = np.column_stack([a, a + 0.05 * rng.normal(size=20), rng.normal(size=20)])
    y = 3.0 * x[:, 0] - 2.0 * x[:, 1] + 0.3 * rng.normal(size=20)
    imp = rank_importance(x, y, ["a", "b", "c"])
    assert all(v >= 0.0 for v in imp.values())
    assert sum(imp.values()) == pytest.approx(1.0)


def test_climate_current_sets_the_storm_current_by_hand():
    from dataclasses import replace

    from onbottom.metocean.current import CurrentModel

    cm = CurrentModel(scale=0.3, shape=1.8, rho=0.6, hs_scale=1.0, hs_shape=1.35, hs_location=0.25)
    climate = replace(CLIMATE, current=cm)
    m = StormModel(_setup(), inputs=("friction_coefficient",), climate=climate)
    assert m.input_names == ("u_hs", "u_tp", "u_direction", "u_current", "friction_coefficient")
    x = np.array([0.0, 0.0, 0.2, 1.0, 0.5])
    hs = 4.0 + 0.7 / -0.1 * (0.5**0.1 - 1.0)
    # z_H = Φ⁻¹(F_H(hs)), U = α(−ln(1 − Φ(ρ z_H + √(1 − ρ²)·1)))^(1/β)
    fh = 1.0 - math.exp(-(((hs - 0.25) / 1.0) ** 1.35))
    from scipy import special

    zc = 0.6 * special.ndtri(fh) + 0.8 * 1.0
    u = 0.3 * (-math.log1p(-special.ndtr(zc))) ** (1.0 / 1.8)
    _, storm, current = m.build(x, 3)
    assert current.velocity == pytest.approx(u, rel=1e-9)
    # with sectors the current goes with the waves (sector S, heading 0: 180°)
    assert current.direction_deg == pytest.approx(storm.stages[0].direction_deg) == 180.0
    with pytest.raises(InputError, match="current_velocity comes from"):
        StormModel(_setup(), inputs=("current_velocity",), climate=climate)
