"""Unit tests of the uncertain inputs (onbottom.reliability.distributions)."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.reliability.distributions import UncertainParameter, parameter_from_table


@pytest.mark.parametrize(
    ("kind", "params", "mean", "std"),
    [
        ("normal", {"mean": 0.6, "std": 0.06}, 0.6, 0.06),
        ("lognormal", {"mean": 10.0e3, "std": 1.5e3}, 10.0e3, 1.5e3),
        ("uniform", {"low": 0.4, "high": 0.8}, 0.6, 0.4 / np.sqrt(12.0)),
        ("gumbel", {"mean": 5.0, "std": 0.8}, 5.0, 0.8),
    ],
)
def test_openturns_distribution_has_the_stated_moments(kind, params, mean, std):
    pytest.importorskip("openturns")
    p = UncertainParameter("x", kind, params)
    d = p.openturns()
    assert d.getMean()[0] == pytest.approx(mean, rel=1e-9)
    assert d.getStandardDeviation()[0] == pytest.approx(std, rel=1e-9)
    assert p.mean() == pytest.approx(mean, rel=1e-12)
    assert list(d.getDescription()) == ["x"]


def test_weibull_mean_and_default_location():
    pytest.importorskip("openturns")
    p = UncertainParameter("hs", "weibull", {"scale": 1.0, "shape": 1.35})
    assert p.parameters["location"] == 0.0
    assert p.openturns().getMean()[0] == pytest.approx(p.mean(), rel=1e-9)


def test_from_case_table():
    p = parameter_from_table(
        "friction_coefficient", {"distribution": "normal", "mean": 0.6, "std": 0.06}
    )
    assert p.distribution == "normal" and p.parameters == {"mean": 0.6, "std": 0.06}
    f = parameter_from_table("submerged_weight", 1500.0)
    assert f.distribution == "fixed" and not f.is_random and f.mean() == 1500.0


@pytest.mark.parametrize(
    ("name", "table", "match"),
    [
        ("mu", {"distribution": "normal", "mean": 0.6}, "takes mean, std"),
        ("mu", {"distribution": "normal", "mean": 0.6, "std": -0.1}, r"mu.std = -0.1"),
        ("mu", {"distribution": "beta", "a": 1}, "mu.distribution = 'beta'"),
        ("mu", {"distribution": "uniform", "low": 1.0, "high": 0.5}, "low < high"),
        ("mu", {"distribution": "normal", "mean": "0.6", "std": 0.1}, "mu.mean"),
        ("mu", "0.6", "a number or a table"),
    ],
)
def test_bad_tables_name_the_field(name, table, match):
    with pytest.raises(InputError, match=match):
        parameter_from_table(name, table)
