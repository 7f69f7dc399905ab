"""Unit test: :mod:`onbottom.soil.penetration_table` — the F114 models from soil values and the
table, embedment and validity of ``onbottom penetration``, called directly."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from onbottom.errors import InputError, OutOfRangeWarning, SolutionError
from onbottom.soil.penetration_clay import UndrainedModel1, UndrainedModel2
from onbottom.soil.penetration_f114 import LayConditions
from onbottom.soil.penetration_sand import DrainedPenetration
from onbottom.soil.penetration_table import drained_estimates, penetration_run, undrained_model
from onbottom.status import Status

SAND = {"diameter": 0.5, "unit_weight": 16.7e3}
CLAY = {"diameter": 0.5, "su_mudline": 2.0e3, "su_gradient": 3.0e3, "unit_weight": 6.0e3}


def test_drained_estimates_default_to_the_best_estimate_angle():
    model, bounds = drained_estimates(friction_angle_deg=33.0, n_gamma="vesic", **SAND)
    assert model == DrainedPenetration(friction_angle_deg=33.0, n_gamma="vesic", **SAND)
    # lower: same φ', Davis & Booker smooth N_γ; upper: same φ', rough N_γ
    assert bounds.lower == DrainedPenetration(
        friction_angle_deg=33.0, n_gamma="davis_booker_smooth", **SAND
    )
    assert bounds.upper.friction_angle_deg == 33.0
    assert bounds.upper.n_gamma == "davis_booker_rough"
    _, wide = drained_estimates(
        friction_angle_deg=35.0,
        lower_friction_angle_deg=32.0,
        upper_friction_angle_deg=40.0,
        **SAND,
    )
    assert (wide.lower.friction_angle_deg, wide.upper.friction_angle_deg) == (32.0, 40.0)


def test_undrained_model_one_or_two():
    m1 = undrained_model(1, roughness=0.2, **CLAY)
    assert m1 == UndrainedModel1(roughness=0.2, **CLAY)
    assert undrained_model("2", **CLAY) == UndrainedModel2(**CLAY)
    with pytest.raises(InputError, match="model"):
        undrained_model(3, **CLAY)


def test_table_and_embedment_balance_the_load():
    model, bounds = drained_estimates(friction_angle_deg=33.0, **SAND)
    levels = np.array([0.1, 0.3])
    run = penetration_run(model, levels, bounds=bounds, load=40.0e3)
    rows = run.rows()
    np.testing.assert_array_equal(rows["z"], levels * 0.5)
    np.testing.assert_array_equal(rows["Q_v"], model.resistance(levels * 0.5))
    np.testing.assert_array_equal(rows["Q_v_lower"], bounds.lower.resistance(levels * 0.5))
    assert run.embedment.resistance == pytest.approx(40.0e3, rel=1e-8)  # Q_v(z) = W
    assert run.validity == () and run.embedment_dict()["success"] is True
    assert run.curve is None
    # no load: no embedment; the curve runs to z/D = 0.5 at least, 201 points
    plain = penetration_run(undrained_model(2, **CLAY), [0.2], curve=True)
    assert plain.embedment is None and plain.embedment_dict() is None
    assert "Q_v_lower" not in plain.rows()
    assert plain.curve.sizes["z"] == 201
    assert float(plain.curve["z_over_D"].max()) == pytest.approx(0.5)


def test_lay_factor_outside_its_validity_is_a_note():
    model = undrained_model(2, **CLAY)
    lay = LayConditions(bending_stiffness=1.0e8, bottom_tension=150.0e3)
    # T_0 must exceed (3·sqrt(EI)·W)^(2/3) = (3·1e4·3e3)^(2/3) = 2.008e5 N
    with pytest.warns(OutOfRangeWarning, match="bottom_tension"):
        run = penetration_run(model, [0.1], load=3.0e3, lay=lay)
    assert len(run.validity) == 1 and "2.008e+05 N" in run.validity[0]
    emb = run.embedment_dict()
    assert emb["success"] is False and emb["status"] == Status.OUTSIDE_VALIDITY == -3
    assert emb["message"] == "outside the model's validity at the solution: " + run.validity[0]
    assert emb["design_load"] == pytest.approx(emb["lay_factor"] * 3.0e3)


def test_load_above_full_embedment_raises():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OutOfRangeWarning)
        with pytest.raises(SolutionError, match="exceeds the resistance at full embedment"):
            penetration_run(undrained_model(2, **CLAY), [0.1], load=1.0e6)
