"""Unit tests: trial designs as ``replace``-s on built objects
(:class:`onbottom.assess.route.DesignTrials`) and the stated FE mesh rule
(:func:`onbottom.assess.pipeline.fe_mesh`).

A trial built by ``replace`` must be the very setup the ``onbottom storm`` loader builds from
the section's storm document with the trial pipe (the path it replaces), pickle for pickle."""

from __future__ import annotations

import math
import pickle
import sys
import warnings
from pathlib import Path

import pytest

from onbottom.assess.pipeline import MESH_RULE, fe_mesh
from onbottom.cases.assess import build_route, parse_route_case, trial_pipe
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document


def _loader_setup(case, i, k, x):
    """The storm loader on section ``i``'s storm document ``k`` with the trial pipe (``x``
    None: the given pipe)."""
    from onbottom._casefile import parse_case
    from onbottom.cases.storm import StormCase, build_setup

    doc = case.storm_document(i, case.combination_names(i)[k])
    if x is not None:
        doc["pipe"] = trial_pipe(doc["pipe"], case.solve_for, case.design.layer, x)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return build_setup(parse_case(StormCase, doc), None)


def _simple_pipe_case():
    doc = route_document(sections=1)
    doc["pipe"] = {"outer_diameter": 0.3, "submerged_weight": 400.0, "condition": "operation"}
    doc["design"] = {"weight_min": 50.0, "weight_max": 3000.0}
    doc["route"]["sections"][0]["seabed"]["trench_depth"] = 0.1
    doc["hydro"] = {"reductions": True}
    return parse_route_case(doc)


@pytest.mark.parametrize("x", [0.0, 0.013, 0.04, 0.2])
def test_buildup_trial_is_the_loaders_setup(x):
    case = parse_route_case(route_document(sections=2))
    route = build_route(case)
    for i, s in enumerate(route.sections):
        for k in range(len(s.storms)):
            assert pickle.dumps(s.trial_storm(k, x)) == pickle.dumps(_loader_setup(case, i, k, x))


@pytest.mark.parametrize("w", [60.0, 400.0, 2999.0])
def test_simple_pipe_trial_with_a_trench_is_the_loaders_setup(w):
    case = _simple_pipe_case()
    s = build_route(case).sections[0]
    trial = s.trial_storm(0, w)
    assert trial.pipe.submerged_weight == w
    assert trial.reductions.trench_depth_over_d == pytest.approx(0.1 / 0.3)
    assert pickle.dumps(trial) == pickle.dumps(_loader_setup(case, 0, 0, w))


def test_a_floating_trial_raises_a_named_error():
    """A 610 mm line, 10 mm wall, empty (installation) without concrete floats: the trial
    raises (the dynamic search counts it as failing), as the storm loader did."""
    doc = route_document(sections=1)
    doc["pipe"] |= {"steel_outer_diameter": 0.61, "wall_thickness": 0.01}
    doc["pipe"]["layers"][1]["thickness"] = 0.08
    trials = build_route(parse_route_case(doc)).sections[0].trial_storm
    assert trials.conditions[1] == "installation"
    with pytest.raises(InputError, match="floats"):
        trials(1, 0.0)
    assert trials(1, 0.08).pipe.submerged_weight > 0.0  # the given design sinks


def test_design_trials_refuse_a_wrong_variable():
    s = build_route(_simple_pipe_case()).sections[0]
    from dataclasses import replace

    with pytest.raises(InputError, match="concrete_thickness' is invalid for a simple pipe"):
        replace(s.trial_storm, variable="concrete_thickness")(0, 0.05)
    with pytest.raises(InputError, match="DesignTrials.conditions"):
        replace(s.trial_storm, conditions=())


# ---- the FE mesh rule ----------------------------------------------------------------------------
PIPE = Pipe(outer_diameter=0.3, submerged_weight=600.0, bending_stiffness=9.0e6)


def test_mesh_rule_by_hand():
    """Deep water (d = 500 m, T = 8 s): λ = g T²/(2π) = 99.92 m. k_s = 0.6 · 600 / (0.02 ·
    0.3) = 6.0e4 N/m², β = (6e4 / (4 · 9e6))^(1/4) = 0.20205 /m, 1/β = 4.949 m, 12/β = 59.4 m:
    L = λ; h <= min(λ/16 = 6.245 m, 1/β = 4.949 m) → n_e = ceil(99.92/4.949) = 21."""
    m = fe_mesh(PIPE, 0.6, 500.0, 8.0)
    lam = 9.80665 * 64.0 / (2.0 * math.pi)
    assert m["wavelength"] == pytest.approx(lam, rel=1e-9)
    assert m["beta"] == pytest.approx((6.0e4 / 3.6e7) ** 0.25, rel=1e-12)
    assert m["length"] == pytest.approx(lam, rel=1e-9)
    assert m["n_elements"] == 21
    assert m["element_length"] * m["n_elements"] == pytest.approx(m["length"])
    assert m["element_length"] <= min(lam / 16.0, 1.0 / m["beta"])
    assert m["rule"] == MESH_RULE


def test_mesh_rule_bending_length_governs_a_stiff_line_in_short_waves():
    """Shallow, short waves and a stiff line: L = 12/β when it exceeds λ_p."""
    stiff = Pipe(outer_diameter=0.3, submerged_weight=600.0, bending_stiffness=9.0e9)
    m = fe_mesh(stiff, 0.6, 500.0, 4.0)  # λ = 24.98 m; 1/β = 27.8 m
    assert m["length"] == pytest.approx(12.0 / m["beta"])
    assert m["element_length"] <= m["wavelength"] / 16.0


def test_mesh_rule_is_insensitive_to_the_soil_stiffness():
    """1/β ∝ k_s^(-1/4): twice the friction (twice k_s) shortens 1/β by 2^(1/4) = 1.19."""
    a, b = fe_mesh(PIPE, 0.3, 500.0, 8.0), fe_mesh(PIPE, 0.6, 500.0, 8.0)
    assert a["beta"] / b["beta"] == pytest.approx(2.0**-0.25)


def _count_builds(monkeypatch):
    """Count the ``onbottom storm`` loader's builds (:func:`onbottom.cases.storm.build_setup`)."""
    import onbottom.cases.storm as storm_cases

    calls = []
    real = storm_cases.build_setup

    def counted(case, path=None):
        calls.append(case)
        return real(case, path)

    monkeypatch.setattr(storm_cases, "build_setup", counted)
    return calls


def test_each_storm_setup_is_built_once_and_is_the_loaders(monkeypatch):
    """Validating a route builds each section's storm setups; building the route takes those
    very objects (no second read), and the run builds none (trials are ``replace``-s)."""
    from onbottom.assess import assess

    calls = _count_builds(monkeypatch)
    doc = route_document(sections=2, seeds=1, peak_hours=0.02)
    doc["levels"] |= {"absolute": False}
    case = parse_route_case(doc)
    assert len(calls) == 2 * 2  # 2 sections x 2 load combinations
    route = build_route(case)
    assert len(calls) == 4
    for i, s in enumerate(route.sections):
        for k, c in enumerate(s.storms):
            assert pickle.dumps(c.setup) == pickle.dumps(_loader_setup(case, i, k, None))
    del calls[:]
    assess(route, n_workers=0)
    assert calls == []


def test_load_route_validates_the_seeds_it_builds(tmp_path, monkeypatch):
    """``load_route(seeds=N)`` validates the case with N seeds and builds each setup once."""
    from assess_cases import route_toml
    from onbottom.cases.assess import load_route

    doc = route_document(sections=2, seeds=3)
    path = tmp_path / "route.toml"
    path.write_text(route_toml(doc), encoding="utf-8")
    calls = _count_builds(monkeypatch)
    route = load_route(path, seeds=1)
    assert len(calls) == 4
    assert {c.setup.seeds for s in route.sections for c in s.storms} == {1}
    assert route.dynamic.seeds == 1
    doc["dynamic"]["seeds"] = 1
    assert route.identity == build_route(parse_route_case(doc)).identity
