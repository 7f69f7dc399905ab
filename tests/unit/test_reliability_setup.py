"""Unit tests: the reliability setup (onbottom.reliability.setup), a plain value type built
from a case file by onbottom.cases.reliability, and its named errors when built by hand."""

from __future__ import annotations

import re
import shutil
from dataclasses import replace
from pathlib import Path

import pytest

from onbottom._casefile import CaseFileError
from onbottom.cases.reliability import load_reliability_setup
from onbottom.errors import InputError
from onbottom.reliability.distributions import UncertainParameter
from onbottom.reliability.run import planned_storms
from onbottom.reliability.setup import ClimateSettings, ContourDesign, ReliabilitySetup

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "reliability_case.toml"


@pytest.fixture(scope="module")
def setup() -> ReliabilitySetup:
    return load_reliability_setup(EXAMPLE)


def test_case_file_builds_the_setup(setup):
    d = setup.storm.pipe.outer_diameter
    assert setup.limits == (("0.5D", pytest.approx(0.5 * d)), ("10D", pytest.approx(10 * d)))
    assert setup.climate is not None and setup.climate.hindcast.is_absolute()
    assert setup.climate.hindcast == EXAMPLE.parent / "hindcast_synthetic.csv"
    assert isinstance(setup.design, ContourDesign)
    assert all(isinstance(p, UncertainParameter) for p in setup.inputs)
    assert setup.seabed_model == "sand"
    # the progress total: limits x max_storms, and the contour runs of the design
    n = len(setup.limits) * setup.max_storms
    if setup.method == "importance":
        n += len(setup.limits) * setup.form_storms
    c = setup.design
    n += c.contour_points * c.seeds + c.top_points * c.top_seeds + c.top_seeds
    assert planned_storms(setup) == n


def test_hand_built_setup_names_the_field(setup):
    with pytest.raises(InputError, match="storms_per_year"):
        replace(setup, climate=None, design=None, storms_per_year=None)
    with pytest.raises(InputError, match="ReliabilitySetup.design"):
        replace(setup, climate=None, storms_per_year=2.0)
    with pytest.raises(InputError, match="ReliabilitySetup.method"):
        replace(setup, method="form")
    with pytest.raises(InputError, match="limits"):
        replace(setup, limits=())
    with pytest.raises(InputError, match="ClimateSettings.sectors"):
        ClimateSettings(hindcast="h.csv", sectors=0)
    with pytest.raises(InputError, match="ContourDesign.fractile"):
        ContourDesign(fractile=1.0)
    plain = replace(setup, climate=None, design=None, storms_per_year=2.0)
    assert plain.storms_per_year == 2.0 and plain.limits == setup.limits


def test_case_errors_keep_their_keys(tmp_path):
    text = EXAMPLE.read_text(encoding="utf-8")
    shutil.copy(EXAMPLE.parent / "hindcast_synthetic.csv", tmp_path)
    no_climate = re.sub(r"(?ms)^\[reliability\.(climate|design)\].*?(?=^\[|\Z)", "", text)
    p = tmp_path / "case.toml"
    p.write_text(no_climate, encoding="utf-8")
    with pytest.raises(CaseFileError) as err:
        load_reliability_setup(p)
    assert err.value.field == "reliability.storms_per_year"
    p.write_text(re.sub(r"(?m)^limits = .*$", 'limits = ["2 diameters"]', text), "utf-8")
    with pytest.raises(CaseFileError, match="reliability.limits") as err:
        load_reliability_setup(p)
    assert err.value.field == "reliability.limits[0]" and err.value.line is not None
