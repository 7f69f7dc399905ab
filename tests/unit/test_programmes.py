"""Unit tests: load-programme builders (amplitudes, inclination, V path, groups, TOML)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom import InputError
from onbottom.cases.programme import programme_from_toml
from onbottom.dynamics.programmes import (
    LoadProgramme,
    from_arrays,
    inclined_cyclic,
    irregular_wave_current_groups,
    regular_wave_current_groups,
)


def test_inclined_amplitudes_and_v_path():
    p = inclined_cyclic(10.52e3, 250.0, 40.0, 30.0, 5, installation_load=42.98e3)
    assert p.cycle_period == 40.0 and p.n_cycles == 5 and p.duration == 200.0
    for n in range(1, 6):
        h, v = p.loads_at((n - 1 + 0.25) * 40.0)
        assert h == pytest.approx(250.0 * n)
        assert v == pytest.approx(10.52e3 - 250.0 * n / math.tan(math.radians(30.0)))
        h, _ = p.loads_at((n - 1 + 0.75) * 40.0)
        assert h == pytest.approx(-250.0 * n)
    # first cycle of the paper's Fig. 6: F_V up to 0.43 kN/m
    assert 10.52e3 - p.vertical_load[:200].min() == pytest.approx(433.0, abs=0.5)
    np.testing.assert_allclose(
        p.vertical_load, 10.52e3 - np.abs(p.horizontal_load) * math.sqrt(3.0), rtol=1e-12
    )
    assert p.peak_vertical_load == 42.98e3


def test_inclined_alpha_90_keeps_v_and_triangle_shape():
    p = inclined_cyclic(1e4, 100.0, 10.0, 90.0, 3, shape="triangle", points_per_cycle=8)
    assert np.all(p.vertical_load == 1e4)
    assert p.loads_at(1.25)[0] == pytest.approx(50.0)  # half-way up the first ramp
    assert p.loads_at(12.5)[0] == pytest.approx(200.0)


def test_programme_is_immutable_and_validated():
    p = inclined_cyclic(1e4, 100.0, 10.0, 45.0, 2)
    with pytest.raises(ValueError):
        p.horizontal_load[0] = 1.0
    with pytest.raises(InputError, match="increase strictly"):
        LoadProgramme(time=[0, 1, 1], horizontal_load=[0, 1, 2], vertical_load=[1, 1, 1])
    with pytest.raises(InputError, match="differ in length"):
        LoadProgramme(time=[0, 1], horizontal_load=[0], vertical_load=[1, 1])
    with pytest.raises(InputError, match="alpha_deg"):
        inclined_cyclic(1e4, 100.0, 10.0, 0.0, 2)


def test_regular_groups_scale_and_current_bias():
    p = regular_wave_current_groups(11.2e3, 3)
    n = (p.time < 60.0).sum()
    h1, fv1 = p.horizontal_load[:n], 11.2e3 - p.vertical_load[:n]
    assert h1.max() == pytest.approx(300.0) and h1.min() == pytest.approx(-200.0, rel=1e-6)
    assert fv1.max() == pytest.approx(300.0) and fv1.min() >= -1e-9
    # group k = k × first (increment 100 %)
    h3 = p.horizontal_load[2 * n : 3 * n]
    np.testing.assert_allclose(h3, 3.0 * h1, rtol=1e-12, atol=1e-9)
    # starts and ends at zero load (taper), 6 sub-cycles: 6 positive peaks in the first group
    assert p.horizontal_load[0] == 0.0 and p.horizontal_load[-1] == 0.0
    peaks = np.sum((h1[1:-1] > h1[:-2]) & (h1[1:-1] >= h1[2:]) & (h1[1:-1] > 100.0))
    assert peaks == 6


def test_irregular_groups_seeded_and_incremented():
    a = irregular_wave_current_groups(11.46e3, 4, seed=1)
    b = irregular_wave_current_groups(11.46e3, 4, seed=1)
    c = irregular_wave_current_groups(11.46e3, 4, seed=2)
    np.testing.assert_array_equal(a.horizontal_load, b.horizontal_load)
    assert not np.allclose(a.horizontal_load, c.horizontal_load)
    n = (a.time < 50.0).sum()
    h1 = a.horizontal_load[:n]
    assert h1.max() == pytest.approx(3000.0) and h1.min() == pytest.approx(-2000.0, rel=1e-6)
    np.testing.assert_allclose(a.horizontal_load[3 * n : 4 * n], 1.3 * h1, rtol=1e-12, atol=1e-9)


def test_from_arrays_and_toml_kinds(tmp_path):
    p = from_arrays([0.0, 1.0, 2.0], [0.0, 5.0, 0.0], [10.0, 9.0, 10.0], cycle_period=2.0)
    assert p.n_cycles == 1 and p.loads_at(0.5)[0] == pytest.approx(2.5)
    q = programme_from_toml(
        {
            "programme": {
                "kind": "inclined_cyclic",
                "vertical_load_kn": 10.0,
                "amplitude_step_kn": 0.25,
                "period": 40.0,
                "alpha_deg": 30.0,
                "n_cycles": 3,
                "installation_load_kn": 40.0,
            }
        }
    )
    assert q.installation_load == 40e3 and q.horizontal_load.max() == pytest.approx(750.0)
    csv = tmp_path / "loads.csv"
    csv.write_text("t,H,V\n0,0,10\n1,1,9\n2,0,10\n")
    toml = tmp_path / "case.toml"
    toml.write_text('[programme]\nkind = "csv"\nfile = "loads.csv"\ncycle_period = 2.0\n')
    r = programme_from_toml(toml)
    assert r.horizontal_load[1] == 1e3 and r.vertical_load[1] == 9e3
    with pytest.raises(InputError, match="unknown keys"):
        programme_from_toml(
            {
                "kind": "arrays",
                "time": [0, 1],
                "horizontal_load_kn": [0, 1],
                "vertical_load_kn": [1, 1],
                "bogus": 1,
            }
        )
    with pytest.raises(InputError, match="missing"):
        programme_from_toml({"kind": "regular"})


@pytest.mark.parametrize(
    ("kind", "key", "value"),
    [("irregular", "sub_cycles", 4), ("regular", "hs", 5.0), ("regular", "seed", 3)],
)
def test_wave_group_key_of_the_other_kind_is_a_named_error(tmp_path, kind, key, value):
    """A key only the other wave-group kind takes is refused by name (it was a TypeError from
    the builder), by the programme table and by the section case with its line."""
    from onbottom.cases.section import load_section_case

    table = {"kind": kind, "vertical_load_kn": 10.0, "n_groups": 2, key: value}
    with pytest.raises(InputError, match=rf"programme\.{key} is invalid with kind = '{kind}'"):
        programme_from_toml({"programme": table})
    case = tmp_path / "case.toml"
    case.write_text(
        "[pipe]\nouter_diameter = 1.0\nsubmerged_weight_kn = 10.0\n"
        '[soil]\nmodel = "coulomb"\nfriction_coefficient = 0.5\n'
        f'[programme]\nkind = "{kind}"\nvertical_load_kn = 10.0\nn_groups = 2\n{key} = {value}\n',
        encoding="utf-8",
    )
    with pytest.raises(InputError, match=rf"line 11: programme\.{key} is invalid") as err:
        load_section_case(case)
    assert err.value.field == f"programme.{key}"


@pytest.mark.parametrize(
    ("table", "key"),
    [
        ({"kind": "irregular", "n_groups": 100_000}, "n_groups"),  # 1e8 samples
        ({"kind": "regular", "n_groups": 20_000}, "n_groups"),  # 20,000 x 6 x 100
        (
            {
                "kind": "inclined_cyclic",
                "n_cycles": 100_000,
                "amplitude_step_kn": 0.1,
                "period": 10.0,
                "alpha_deg": 30.0,
            },
            "n_cycles",
        ),
    ],
)
def test_programme_over_the_sample_limit_is_a_named_error(table, key):
    """A programme over MAX_SAMPLES is refused by the key that sized it, before the arrays are
    allocated (the schema's 100,000 groups of an irregular programme were 1e8 samples, 7 GB)."""
    from onbottom.dynamics.programmes import MAX_SAMPLES

    with pytest.raises(InputError, match=rf"{key} = 100000|{key} = 20000") as err:
        programme_from_toml({"programme": {"vertical_load_kn": 10.0} | table})
    assert f"{MAX_SAMPLES:,}" in str(err.value)
