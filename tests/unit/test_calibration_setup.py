"""Unit test: the parameter set and the fit files of ``onbottom calibrate``, called directly
(:func:`onbottom.calibration.parameters.calcareous_parameters`,
:func:`onbottom.calibration.summary.write_fits`)."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

from onbottom.calibration.fit import CalibrationResult
from onbottom.calibration.parameters import (
    CALCAREOUS_BOUNDS,
    CALCAREOUS_START,
    calcareous_parameters,
)
from onbottom.calibration.summary import write_fits
from onbottom.errors import InputError


def _by_name(params):
    return {p.name: p for p in params}


def test_defaults_are_table3_values_and_the_search_bounds():
    p = _by_name(calcareous_parameters(["A", "B", "C", "mu"]))
    assert list(p) == ["A", "B", "C", "mu"]  # no gamma unless varied or given
    assert {k: v.value for k, v in p.items()} == dict(CALCAREOUS_START)
    assert (p["mu"].lower, p["mu"].upper) == CALCAREOUS_BOUNDS["mu"]
    assert all(v.vary and v.units == "1" for v in p.values())


def test_fixed_start_widens_bounds_and_varied_start_is_clamped():
    p = _by_name(calcareous_parameters(["C"], bounds={"C": (0.6, 1.0)}, start={"A": 1.5, "C": 1.2}))
    assert not p["A"].vary and p["A"].value == 1.5 and p["A"].upper == 1.5  # bounds widened
    assert p["C"].vary and p["C"].value == 1.0  # 1.2 moved onto the upper bound
    assert (p["C"].lower, p["C"].upper) == (0.6, 1.0)


def test_gamma_start_from_the_option_or_the_middle_of_its_bounds():
    p = _by_name(calcareous_parameters(["gamma"]))
    assert p["gamma"].value == pytest.approx(0.5 * (4.0e3 + 10.0e3)) and p["gamma"].vary
    assert p["gamma"].units == "N/m3"
    q = _by_name(calcareous_parameters(["A"], gamma=7.5e3))
    assert q["gamma"].value == 7.5e3 and not q["gamma"].vary
    r = _by_name(calcareous_parameters(["A"], gamma=7.5e3, start={"gamma": 8.0e3}))
    assert r["gamma"].value == 8.0e3  # a start value wins over gamma


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"vary": ["phi"]}, "vary names"),
        ({"vary": []}, "at least one"),
        ({"vary": ["A", "A"]}, "repeated"),
        ({"vary": ["A"], "bounds": {"A": (0.5, 0.1)}}, "lower must be below upper"),
        ({"vary": ["A"], "start": {"phi": 1.0}}, "start 'phi'"),
    ],
)
def test_bad_sets_raise(kwargs, match):
    with pytest.raises(InputError, match=match):
        calcareous_parameters(**kwargs)


def _result(record: str, c: float) -> CalibrationResult:
    params = calcareous_parameters(["C"], start={"C": c})
    return CalibrationResult(
        parameters=params,
        names=("C",),
        std_errors={"C": 0.01},
        covariance=np.array([[1.0e-4]]),
        correlation=np.array([[1.0]]),
        misfit=0.5,
        misfits=(),
        residuals=np.zeros(1),
        success=True,
        status=0,
        message="ok",
        n_evaluations=10,
        method="local",
        wall_time=0.1,
        record_names=(record,),
    )


def test_write_fits_one_file_or_one_per_record(tmp_path):
    out = tmp_path / "fit.toml"
    assert write_fits([_result("Inclined 1", 0.8)], out) == [out]
    assert tomllib.loads(out.read_text())["parameters"]["C"]["value"] == 0.8
    results = [_result("Inclined 1", 0.8), _result("Regular", 0.9), _result("Inclined-1", 1.0)]
    paths = write_fits(results, out)
    # "Inclined 1" and "Inclined-1" both give the tag Inclined_1: the third gets _3
    assert [p.name for p in paths] == [
        "fit_Inclined_1.toml",
        "fit_Regular.toml",
        "fit_Inclined_1_3.toml",
    ]
    values = [tomllib.loads(p.read_text())["parameters"]["C"]["value"] for p in paths]
    assert values == [0.8, 0.9, 1.0]
