"""Verification: ``onbottom assess`` on the embedded route — every section's design is at least
F109's generalized requirement (or its ``design_floor`` names the opt-in / the rule that let it
go lower), and the generalized level covers the shore approach (N ≈ 0.0085–0.0098, K ≥ 10:
Table 3-3).

The requirement is checked independently of the floor logic: the design's own generalized
rows (F109 tables at the designed pipe) must all pass.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from onbottom.assess import assess
from onbottom.assess.generalized import generalized_rows
from onbottom.cases.assess import example_path, load_route
from onbottom.checks.design import run_checks

pytestmark = pytest.mark.long


@pytest.fixture(scope="module")
def example():
    route = load_route(example_path())
    route = replace(route, levels=replace(route.levels, pipeline_fe=False))
    return route, assess(route, n_workers=0)


def test_shore_approach_covered(example):
    _, a = example
    shore = a.sections[0]
    assert shore["name"] == "shore approach"
    g = [c for c in shore["checks"] if c["level"] == "generalized"]
    assert g and all(c["covered"] for c in g)
    assert all(0.008 <= c["details"]["N"] <= 0.0105 and c["details"]["K"] >= 10 for c in g)
    assert shore["levels"]["generalized"]["success"]


def test_every_design_at_least_generalized(example):
    route, a = example
    for sec, s in zip(route.sections, a.sections, strict=True):
        fl = s["design_floor"]
        assert fl["rule"] and fl["words"]
        gen = s["levels"].get("generalized") or {}
        if not gen.get("success"):
            # not covered by the tables: the rule says so (and why the design stands)
            assert fl["rule"] in ("not_covered", "coulomb_floor", "at_or_above_coulomb",
                                  "allowed_below_coulomb", "not_checked")  # fmt: skip
            if fl["rule"] in ("coulomb_floor", "at_or_above_coulomb"):
                assert s["levels"]["dynamic"]["value"] >= fl["coulomb_value"] - 1e-12
            continue
        assert fl["rule"] in ("at_or_above_generalized", "generalized_floor")
        assert s["design_value"] >= gen["value"] - 1e-12
        # independently: the designed pipe passes F109's generalized tables in every combination
        pipe = sec.pipe.with_layer_thickness(route.design.layer, s["design_value"])
        rows = run_checks(pipe, sec.seabed, sec.environment, sec.combinations, sec.options)
        out = generalized_rows(rows, route.dynamic.allowable, seabed_model=sec.seabed_model,
                               water_density=sec.environment.water_density)  # fmt: skip
        assert out and all(g["covered"] and g["utilisation"] <= 1.0 + 1e-6 for g in out)
        if fl["rule"] == "generalized_floor":
            assert fl["dynamic_over_generalized_weight"] < 1.0
