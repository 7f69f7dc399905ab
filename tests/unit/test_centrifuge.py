"""Unit tests: the centrifuge presets carry the paper's tables; α inference by limit equilibrium."""

from __future__ import annotations

import math

import pytest

from onbottom import InputError
from onbottom.dynamics.centrifuge import (
    RECOMMENDED,
    TESTS,
    alpha_range_from_limit_equilibrium,
    build_programme,
    build_soil,
    get_test,
)


def test_tables_1_2_3():
    t = TESTS["Inclined 1"]
    assert (t.installation_load, t.vertical_load, t.displacement_limit, t.cycles_used) == (
        42.98e3,
        10.52e3,
        3.0,
        13.27,
    )
    assert (t.table2.A, t.table2.B, t.table2.C, t.table2.mu) == (0.25, 0.35, 0.79, 0.48)
    assert TESTS["Irregular"].table2.C == 1.12 and TESTS["Regular"].cycles_used == 46.22
    assert (RECOMMENDED.A, RECOMMENDED.B, RECOMMENDED.C) == (0.25, 0.35, 0.98)
    # Table 3 C is the average of Table 2 C (paper text)
    mean_c = sum(x.table2.C for x in TESTS.values()) / 7
    assert mean_c == pytest.approx(0.98, abs=0.01)
    assert len(TESTS) == 7


def test_names_are_tolerant():
    assert get_test("inclined-1").name == "Inclined 1"
    assert get_test("IRREGULAR").name == "Irregular"
    with pytest.raises(InputError, match="Inclined 1"):
        get_test("Inclined 9")


def test_alpha_inference_brackets_the_chosen_values():
    lo, hi = alpha_range_from_limit_equilibrium(0.75, 11.12e3, 3.75e3)
    assert lo < TESTS["Inclined 4"].alpha_deg <= hi
    # the ranges the module docstring states (issue 31: they once said 22.8° and 63.7°)
    assert (round(lo, 1), round(hi, 1)) == (25.6, 31.5)
    lo, hi = alpha_range_from_limit_equilibrium(0.85, 11.71e3, 7.5e3)
    assert lo < TESTS["Inclined 5"].alpha_deg <= hi
    assert (round(lo, 1), round(hi, 1)) == (63.6, 69.0)
    # tests 1-3 (α = 30° given by the paper) fall in their own ranges only with passive help
    lo, hi = alpha_range_from_limit_equilibrium(0.48, 10.52e3, 3.5e3, max_passive=1.0e3)
    assert lo < 30.0 <= hi
    # hand check of the bound: H_f(α) = μV/(1 + μ/tanα) equals the amplitude at α = hi
    _, hi = alpha_range_from_limit_equilibrium(0.6, 1e4, 3e3)
    assert 0.6 * 1e4 / (1 + 0.6 / math.tan(math.radians(hi))) == pytest.approx(3e3)


def test_programmes_and_soils_of_presets():
    p = build_programme("Inclined 2")
    assert p is build_programme("Inclined 2")  # cached
    assert p.installation_load == 23.30e3 and p.vertical_load[0] == 9.60e3
    assert p.n_cycles >= math.ceil(13.75)
    q = build_programme("Inclined 2", time_basis="prototype")
    assert q.cycle_period == 50 * p.cycle_period
    s = build_soil("Inclined 3", parameters="recommended")
    assert (s.A, s.B, s.C, s.friction_coefficient) == (0.25, 0.35, 0.98, 0.65)
    s2 = build_soil("Inclined 3", C=1.0, gamma=8e3)
    assert s2.C == 1.0 and s2.submerged_unit_weight == 8e3 and s2.B == 0.45
    assert build_soil("Regular", model="coulomb").friction_coefficient == 0.85


def test_centrifuge_run_is_the_built_simulation():
    """run_centrifuge_test is centrifuge_run(...).simulate(): the built run holds the
    programme, soil, mass and limit of the test, and simulating it gives the same numbers."""
    import dataclasses

    from onbottom.dynamics.centrifuge import (
        ADDED_MASS_COEFFICIENT,
        build_pipe,
        centrifuge_run,
        run_centrifuge_test,
    )
    from onbottom.dynamics.section import section_mass

    t = TESTS["Inclined 1"]
    run = centrifuge_run("Inclined 1", n_cycles=2, dt=0.05)
    assert run.displacement_limit == t.displacement_limit and run.settings.dt_max == 0.05
    assert run.mass == section_mass(build_pipe(t), ADDED_MASS_COEFFICIENT)
    assert run.attrs["test"] == "Inclined 1" and run.attrs["parameter_set"] == "table2"
    a = run.simulate()
    b = run_centrifuge_test("Inclined 1", n_cycles=2, dt=0.05)
    assert a.summary == b.summary and a.status == b.status
    with pytest.raises(dataclasses.FrozenInstanceError):
        run.mass = 1.0  # type: ignore[misc]
