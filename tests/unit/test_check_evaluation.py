"""The F109 checks and the loads envelope as library functions on built inputs.

``onbottom stability`` and ``onbottom loads`` are parse → call → print: their JSON equals what
:func:`onbottom.checks.evaluation.evaluate_stability` and
:func:`onbottom.checks.loads.combination_loads` return on the inputs
:mod:`onbottom.cases.stability` builds from the same file.
"""

from __future__ import annotations

import json
import warnings
from dataclasses import replace
from pathlib import Path

import pytest

from onbottom.cases.stability import (
    build_loads_inputs,
    build_stability_inputs,
    load_stability_case,
)
from onbottom.checks.evaluation import (
    DesignRequest,
    evaluate_stability,
    section_summary,
    solve_design,
)
from onbottom.checks.loads import combination_loads
from onbottom.cli.main import main
from onbottom.errors import InputError

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "stability_case.toml"


def _json(args: list[str], capsys) -> dict:
    assert main([*args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _inputs(build):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return build(load_stability_case(EXAMPLE), EXAMPLE)


def test_evaluate_stability_is_the_stability_command(capsys):
    inputs = _inputs(build_stability_inputs)
    assert inputs.design.solve_for == "concrete_thickness" and inputs.condition == "operation"
    res = evaluate_stability(inputs).as_dict()
    out = _json(["stability", str(EXAMPLE)], capsys)
    for key in ("section", "checks", "success", "message", "all_pass", "design"):
        assert json.loads(json.dumps(res[key])) == out[key], key
    assert res["section"] == section_summary(inputs.section, "operation")
    # the design solve's minimum passes, and nothing thinner does
    assert res["design"]["success"] and res["design"]["utilisation"] == pytest.approx(1.0, 1e-3)


def test_checks_only_request_has_no_design():
    inputs = replace(_inputs(build_stability_inputs), design=DesignRequest())
    res = evaluate_stability(inputs)
    assert res.design == {"solve_for": "none"} and res.success
    assert [r.name for r in res.rows][:1] == ["vertical_stability"]


def test_unknown_design_variable_is_a_named_error():
    with pytest.raises(InputError, match="solve_for = 'diameter' is invalid"):
        DesignRequest(solve_for="diameter")


def test_design_range_is_checked_once_for_both_requests():
    """DesignRequest (``onbottom stability``) and DesignRange (``onbottom assess``) share one
    range check (:class:`DesignBounds`), each error naming its own class."""
    from onbottom.assess.route import DesignRange

    for cls in (DesignRequest, DesignRange):
        with pytest.raises(InputError, match=f"{cls.__name__}.thickness_max = 0.1 is invalid"):
            cls(thickness_min=0.2, thickness_max=0.1)
        with pytest.raises(InputError, match=f"{cls.__name__}.weight_max = 5.0 is invalid"):
            cls(weight_min=10.0, weight_max=5.0)


def test_solve_design_is_the_design_of_evaluate_stability():
    inputs = _inputs(build_stability_inputs)
    i, d = inputs, inputs.design
    args = (i.section, i.seabed, i.environment, i.combinations, i.options)
    res = solve_design(d.solve_for, *args, d)
    design = evaluate_stability(inputs).design
    assert (res.value, res.utilisation) == (design["value"], design["utilisation"])
    pipe = i.section.pipe(i.condition)  # a simple pipe: its submerged weight is sized
    weight = solve_design("submerged_weight", pipe, *args[1:], d)
    assert d.weight_min < weight.value < d.weight_max and weight.utilisation <= 1.0 + 1e-3


def test_combination_loads_is_the_loads_command(capsys):
    inputs = _inputs(build_loads_inputs)
    assert inputs.seed == 0 and inputs.reductions
    res = combination_loads(inputs, duration=0.2 * 3600.0)
    out = _json(["loads", str(EXAMPLE), "--duration-hours", "0.2"], capsys)
    assert res.seed == out["seed"] == 0
    assert json.loads(json.dumps([c.as_dict() for c in res.combinations])) == out["combinations"]
    assert res.success is out["success"] is True
    # another seed: another record, same combinations
    other = combination_loads(inputs, duration=0.2 * 3600.0, seed=3)
    assert other.seed == 3 and [c.combination for c in other.combinations] == [
        c["combination"] for c in out["combinations"]
    ]
    assert other.combinations[0].as_dict() != res.combinations[0].as_dict()
