"""Unit tests: Brent's method of :mod:`onbottom._roots` against known roots and scipy's brentq."""

from __future__ import annotations

import math

import pytest
from scipy.optimize import brentq as scipy_brentq

from onbottom._roots import brentq

CASES = [
    # f, a, b, exact root
    (lambda x: x * x - 2.0, 0.0, 2.0, math.sqrt(2.0)),
    (lambda x: math.cos(x) - x, 0.0, 1.0, 0.7390851332151607),
    (lambda x: x**3 - 2.0 * x - 5.0, 2.0, 3.0, 2.0945514815423265),  # Wallis' cubic
    (lambda x: math.exp(x) - 10.0, -5.0, 5.0, math.log(10.0)),
    (lambda x: (x - 0.3) ** 3, -1.0, 1.0, 0.3),  # triple root: interpolation fails, bisects
    (lambda x: 1.0 if x > 0.123456 else -1.0, 0.0, 1.0, 0.123456),  # a jump, like a verdict
    (lambda x: math.atan(1e6 * (x - 0.5)), 0.0, 3.0, 0.5),  # steep
]


@pytest.mark.parametrize("xtol", [1e-12, 1e-5, 1e-2])
@pytest.mark.parametrize("case", range(len(CASES)))
def test_root_within_the_tolerance_as_scipy(case, xtol):
    f, a, b, root = CASES[case]
    # the triple root needs more than the default 100 steps at xtol 1e-12, in both
    ours = brentq(f, a, b, xtol=xtol, maxiter=1000)
    theirs = scipy_brentq(f, a, b, xtol=xtol, maxiter=1000)
    bound = xtol + 4.0 * 2.22e-16 * abs(root)
    assert abs(ours - root) <= bound
    assert abs(theirs - root) <= bound
    assert abs(ours - theirs) <= bound


def test_evaluations_are_few_on_a_smooth_function():
    calls = []

    def f(x):
        calls.append(x)
        return math.cos(x) - x

    brentq(f, 0.0, 1.0, xtol=1e-12)
    assert len(calls) <= 12  # bisection alone would need 42


def test_reversed_bracket_and_zero_at_an_end():
    assert brentq(lambda x: x - 0.25, 1.0, 0.0, xtol=1e-14) == pytest.approx(0.25, abs=1e-14)
    assert brentq(lambda x: x, 0.0, 1.0) == 0.0
    assert brentq(lambda x: x - 1.0, 0.0, 1.0) == 1.0


def test_refusals():
    with pytest.raises(ValueError, match="different signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(ValueError, match="NaN"):
        brentq(lambda x: math.nan, -1.0, 1.0)
    with pytest.raises(ValueError, match="xtol"):
        brentq(lambda x: x, -1.0, 1.0, xtol=0.0)
    with pytest.raises(ValueError, match="rtol"):
        brentq(lambda x: x, -1.0, 1.0, rtol=1e-17)
    with pytest.raises(RuntimeError, match="no convergence in 3 steps"):
        brentq(lambda x: (x - 0.3) ** 3, -1.0, 1.0, xtol=1e-12, maxiter=3)


def test_design_solve_agrees_with_scipy_brentq(monkeypatch):
    """The F109 minimum concrete thickness with either root finder: the same within xtol."""
    import onbottom._roots
    from onbottom.checks.design import design_concrete_thickness
    from onbottom.inputs import Layer, Sand
    from onbottom.inputs.environment import Environment, f109_combinations
    from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
    from onbottom.inputs.storm import Current, SeaState

    buildup = PipeBuildUp(
        steel_outer_diameter=0.2191,
        wall_thickness=0.0127,
        layers=(
            Layer(name="corrosion", thickness=0.0055, density=1335.0),
            Layer(name="concrete", thickness=0.04, density=3043.5),
        ),
        contents=Contents(operation=180.0),
    )
    env = Environment(water_depth=45.0)
    combos = f109_combinations(
        wave_100=SeaState(hs=5.0, tp=11.0),
        wave_10=SeaState(hs=4.2, tp=10.3),
        current_100=Current(velocity=0.5, reference_height=3.0),
        current_10=Current(velocity=0.35, reference_height=3.0),
    )
    sand = Sand(submerged_unit_weight=10.0e3)
    ours = design_concrete_thickness(buildup, sand, env, combos, thickness_max=0.15)
    monkeypatch.setattr(onbottom._roots, "brentq", scipy_brentq)
    theirs = design_concrete_thickness(buildup, sand, env, combos, thickness_max=0.15)
    assert ours.success and theirs.success
    assert abs(ours.value - theirs.value) <= 2e-5  # xtol 1e-5 m, each stepped to the pass side
    assert ours.utilisation <= 1.0
