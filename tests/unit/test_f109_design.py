"""F109 design: load combinations, run_checks rows, minimum concrete thickness / weight."""

from __future__ import annotations

import pytest

from onbottom.checks.design import (
    CheckOptions,
    NoFeasibleDesignError,
    design_concrete_thickness,
    design_submerged_weight,
    governing,
    run_checks,
)
from onbottom.errors import InputError, SolutionError
from onbottom.inputs import Layer, Pipe, Sand
from onbottom.inputs.environment import Environment, LoadCombination, f109_combinations
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.inputs.storm import Current, SeaState
from onbottom.status import Status

SAND = Sand(submerged_unit_weight=10.0e3)
ENV = Environment(water_depth=40.0)
BUILDUP = PipeBuildUp(
    steel_outer_diameter=0.2191,
    wall_thickness=0.0127,
    layers=(
        Layer(name="corrosion", thickness=0.0055, density=1335.0),
        Layer(name="concrete", thickness=0.05, density=3043.5),
    ),
    contents=Contents(operation=180.0),
)
COMBOS = f109_combinations(
    wave_100=SeaState(hs=5.0, tp=11.0),
    wave_10=SeaState(hs=4.2, tp=10.3),
    current_100=Current(velocity=0.5, reference_height=3.0),
    current_10=Current(velocity=0.35, reference_height=3.0),
)


def test_f109_combinations_pair_waves_and_currents():
    a, b = COMBOS
    assert a.sea_state.hs == 5.0 and a.current.velocity == 0.35
    assert b.sea_state.hs == 4.2 and b.current.velocity == 0.5
    with pytest.raises(InputError, match="LoadCombination.condition"):
        LoadCombination(name="x", sea_state=a.sea_state, current=a.current, condition="storm")
    with pytest.raises(InputError, match="Environment.water_depth"):
        Environment(water_depth=0.0)


def test_rows_per_condition_and_combination():
    rows = run_checks(BUILDUP, SAND, ENV, COMBOS)
    names = [(r.name, r.combination) for r in rows]
    assert sum(n == "vertical_stability" for n, _ in names) == 4
    assert sum(n == "absolute_lateral" for n, _ in names) == 2
    assert all(r.passes == (r.utilisation <= 1.0) for r in rows)
    g = governing(rows)
    assert g.utilisation == max(r.utilisation for r in rows)


def test_minimum_concrete_thickness_is_the_boundary():
    res = design_concrete_thickness(BUILDUP, SAND, ENV, COMBOS, thickness_max=0.15)
    assert res.success and res.status is Status.CONVERGED
    assert res.utilisation == pytest.approx(1.0, abs=2e-3) and res.utilisation <= 1.0
    below = BUILDUP.with_layer_thickness("concrete", res.value - 1e-3)
    assert governing(run_checks(below, SAND, ENV, COMBOS)).utilisation > 1.0
    # a stricter safety class needs more concrete
    high = design_concrete_thickness(
        BUILDUP, SAND, ENV, COMBOS, CheckOptions(safety_class="high"), thickness_max=0.2
    )
    assert high.value > res.value


def test_no_feasible_design_raises_named_error():
    with pytest.raises(NoFeasibleDesignError) as info:
        design_concrete_thickness(BUILDUP, SAND, ENV, COMBOS, thickness_max=0.005)
    err = info.value
    assert isinstance(err, SolutionError) and err.best_utilisation > 1.0
    assert err.bounds == (0.0, 0.005) and "concrete_thickness" in str(err)
    with pytest.raises(InputError, match="thickness_max"):
        design_concrete_thickness(BUILDUP, SAND, ENV, COMBOS, thickness_min=0.1, thickness_max=0.05)


def test_minimum_submerged_weight_of_a_simple_pipe():
    pipe = Pipe(outer_diameter=0.35, submerged_weight=500.0)
    res = design_submerged_weight(pipe, SAND, ENV, COMBOS)
    assert res.utilisation == pytest.approx(1.0, abs=2e-3) and res.utilisation <= 1.0
    assert res.section.submerged_weight == pytest.approx(res.value)


def test_floating_condition_fails_without_crashing():
    light = PipeBuildUp(steel_outer_diameter=0.5, wall_thickness=0.006)
    combo = LoadCombination(
        name="inst",
        sea_state=SeaState(hs=1.0, tp=6.0),
        current=Current(velocity=0.0),
        condition="installation",
    )
    rows = run_checks(light, SAND, ENV, [combo])
    lat = next(r for r in rows if r.name == "absolute_lateral")
    assert lat.passes is False and lat.details["message"] == "the pipe floats"


def test_minimum_passing_is_public_and_finds_the_crossing():
    """checks.design.minimum_passing on a hand-made check: utilisation 2 − x passes from x = 1
    (the root, returned on the passing side to xtol); a range that passes at once returns lo
    with status AT_BOUND; a range with no pass raises NoFeasibleDesignError with the best point."""
    from onbottom.checks.design import CheckRow, NoFeasibleDesignError, minimum_passing

    def evaluate(x):
        return [CheckRow("hand", "c", "operation", 2.0 - x, 2.0 - x <= 1.0, {})]

    r = minimum_passing(lambda x: x, evaluate, 0.0, 3.0, 7, 1e-6, "x", "m")
    assert r.status is Status.CONVERGED and r.success
    assert 1.0 <= r.value <= 1.0 + 2e-6 and r.utilisation <= 1.0
    r = minimum_passing(lambda x: x, evaluate, 1.5, 3.0, 4, 1e-6, "x", "m")
    assert r.status is Status.AT_BOUND and r.success and r.value == 1.5
    assert r.as_dict()["status"] == 7
    with pytest.raises(NoFeasibleDesignError) as err:
        minimum_passing(lambda x: x, evaluate, 0.0, 0.5, 6, 1e-6, "x", "m")
    assert err.value.best_value == 0.5
