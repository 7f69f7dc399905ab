"""Unit tests: the built route of ``onbottom assess`` (onbottom.assess.route, built by
onbottom.cases.assess): what each section holds, the trial designs of the dynamic search,
pickling for Dask workers, and named errors of the value types built by hand."""

from __future__ import annotations

import pickle
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from onbottom.assess.route import (
    DesignRange,
    DynamicSettings,
    Levels,
    PipelineFESettings,
    Route,
)
from onbottom.cases.assess import build_route, load_route, parse_route_case, section_identity
from onbottom.errors import InputError
from onbottom.inputs.pipe_buildup import PipeBuildUp

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def built():
    case = parse_route_case(route_document(sections=2))
    return case, build_route(case)


def test_sections_hold_the_single_section_cases(built):
    case, route = built
    assert [s.name for s in route.sections] == ["section 0", "section 1"]
    assert route.variable == "concrete_thickness" and route.design.layer == "concrete"
    assert route.levels == Levels(generalized=False)
    assert route.dynamic.seed_list == [0, 1]
    # 0.02 h build-up + 0.1 h peak (route_document)
    assert route.dynamic.duration_s == pytest.approx(3600.0 * 0.12)
    s = route.sections[1]
    assert (s.kp_start, s.kp_end, s.water_depth) == (10000.0, 18000.0, 40.0)
    assert s.environment.water_depth == 40.0 and s.seabed_model == "sand"
    assert isinstance(s.pipe, PipeBuildUp) and s.condition == "operation"
    assert s.given_value == 0.04  # the [pipe] concrete thickness
    assert [c.name for c in s.combinations] == [c.name for c in s.storms]
    assert [c.condition for c in s.storms] == ["operation", "installation"]
    assert s.storms[1].setup.storm.stages[0].hs == 3.0  # the combination's own sea state
    assert s.storm_index("installation") == 1
    with pytest.raises(InputError, match="not a storm of section"):
        s.storm_index("nowhere")
    assert s.identity == section_identity(case, 1)
    assert s.document == case.stability_document(1)


def test_trial_storm_is_the_pipe_at_the_design_value(built):
    _, route = built
    s = route.sections[0]
    given = s.trial_storm(0, s.given_value)
    assert given.pipe == s.storms[0].setup.pipe
    thick = s.trial_storm(0, 0.1)
    assert thick.pipe.outer_diameter == pytest.approx(given.pipe.outer_diameter + 2 * 0.06)
    assert thick.pipe.submerged_weight > given.pipe.submerged_weight
    # the installation combination keeps its condition (empty pipe: lighter)
    assert s.trial_storm(1, 0.1).pipe.submerged_weight < thick.pipe.submerged_weight


def test_route_pickles_for_workers(built):
    _, route = built
    again = pickle.loads(pickle.dumps(route))
    assert again.sections[0].storms[0].setup.pipe == route.sections[0].storms[0].setup.pipe
    assert (
        again.sections[0].trial_storm(0, 0.05).pipe == route.sections[0].trial_storm(0, 0.05).pipe
    )


def test_load_route_replaces_the_seeds():
    path = ROOT / "examples" / "assess_route.toml"
    route = load_route(path, seeds=4)
    given = load_route(path)
    assert (route.dynamic.seeds, given.dynamic.seeds) == (4, 3)
    assert route.identity != given.identity  # the seeds are an input
    assert route.sections[0].identity != given.sections[0].identity


def test_value_types_name_the_field():
    with pytest.raises(InputError, match="DesignRange.variable"):
        DesignRange(variable="diameter")
    with pytest.raises(InputError, match="thickness_max"):
        DesignRange(thickness_min=0.2, thickness_max=0.1)
    with pytest.raises(InputError, match="allowable_displacement_m"):
        DynamicSettings(allowable="user")
    assert DynamicSettings(allowable="10D").allowable_for(0.4) == pytest.approx(4.0)
    assert DynamicSettings(allowable="user", allowable_displacement_m=2.0).allowable_for(9) == 2
    with pytest.raises(InputError, match="PipelineFESettings.element_length"):
        PipelineFESettings(length=10.0, element_length=6.0)
    with pytest.raises(InputError, match="pipeline_fe"):
        Levels(dynamic=False, pipeline_fe=True)


def test_route_checks_its_sections(built):
    _, route = built
    s = route.sections[0]
    with pytest.raises(InputError, match="unique"):
        replace(route, sections=(s, s))
    with pytest.raises(InputError, match="dynamic level"):
        replace(route, sections=(replace(s, trial_storm=None),))
    # without a design variable the given design's storms are enough
    plain = replace(route, design=DesignRange(variable="none"))
    assert replace(plain, sections=(replace(s, trial_storm=None),)).sections[0].name == s.name
    assert isinstance(route, Route)


def test_route_pipeline_fe_settings_old_name_is_a_deprecated_alias():
    """The route's FE settings and the solver's settings no longer share a class name; the
    route's former name still resolves, with a DeprecationWarning, for one release."""
    import onbottom.assess as assess_pkg
    from onbottom.dynamics.pipeline import PipelineSettings

    with pytest.warns(DeprecationWarning, match="renamed PipelineFESettings"):
        old = assess_pkg.PipelineSettings
    assert old is PipelineFESettings
    assert PipelineFESettings is not PipelineSettings
