"""Data flows one way in ``onbottom assess``: the route case is read (and validated) once, and
nothing below ``cases/`` calls back into ``cases/`` while the route runs — the trial designs
of the dynamic search and the pipeline FE are ``replace``-s on built objects
(:class:`onbottom.assess.route.DesignTrials`), never case documents read again.

Every Python function whose code lives in ``src/onbottom/cases/`` is counted by a profile hook
(:func:`sys.setprofile`, this thread: ``--workers 0`` runs every section here), so a loader,
builder, pydantic validator or helper of ``cases/`` reached by any path is seen, however it was
imported.
"""

from __future__ import annotations

import json
import sys
import threading
from collections import Counter
from pathlib import Path

import pytest

import onbottom.cases
import onbottom.cases.assess as cases_assess
from onbottom.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from assess_cases import route_document, route_toml  # noqa: E402

CASES_DIR = str(Path(onbottom.cases.__file__).resolve().parent)


class CasesCalls:
    """Counts the calls of functions defined under ``onbottom/cases/`` while active."""

    def __init__(self) -> None:
        self.calls: Counter[str] = Counter()

    def _profile(self, frame, event, arg):  # the sys.setprofile hook
        if event == "call":
            code = frame.f_code
            if code.co_filename.startswith(CASES_DIR):
                self.calls[f"{Path(code.co_filename).name}:{code.co_qualname}"] += 1

    def __enter__(self) -> CasesCalls:
        sys.setprofile(self._profile)
        threading.setprofile(self._profile)
        return self

    def __exit__(self, *exc: object) -> None:
        sys.setprofile(None)
        threading.setprofile(None)


def test_the_hook_sees_a_call_into_cases():
    """The control: a call into ``cases/`` (as the old trial storms made, a storm document
    through the storm loader) is counted."""
    with CasesCalls() as hook:
        cases_assess.trial_pipe({"submerged_weight": 1.0}, "submerged_weight", "", 2.0)
    assert hook.calls["assess.py:trial_pipe"] == 1


@pytest.fixture(scope="module")
def one_way_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("one_way")
    case = d / "route.toml"
    doc = route_document(sections=1, seeds=2, peak_hours=0.05)
    doc["levels"]["pipeline_fe"] = True
    doc["pipeline"] = {"length": 40.0, "element_length": 5.0}
    case.write_text(route_toml(doc), encoding="utf-8")
    reading, running = CasesCalls(), CasesCalls()
    load_route = cases_assess.load_route

    def counted_load_route(*args, **kwargs):
        with reading:
            route = load_route(*args, **kwargs)
        running.__enter__()  # from here on the route runs; stopped after main returns
        return route

    mp = pytest.MonkeyPatch()
    mp.setattr(cases_assess, "load_route", counted_load_route)
    try:
        rc = main(["assess", str(case), "--out", str(d / "out"), "--workers", "0", "--quiet",
                   "--no-pdf"])  # fmt: skip
    finally:
        running.__exit__()
        mp.undo()
    return rc, reading, running, json.loads((d / "out" / "results.json").read_text())


def test_no_call_into_cases_while_the_route_runs(one_way_run):
    rc, reading, running, results = one_way_run
    assert rc == 0
    sec = results["sections"][0]
    trials = sec["dynamic"]["bisection"]["trials"]
    assert len(trials) >= 2, "the dynamic search ran trial designs"
    assert results["pipeline"] is not None, "the pipeline FE ran on a trial design's setup"
    # the case was read through the loaders of cases/ ...
    assert reading.calls["assess.py:load_route"] == 1
    assert reading.calls["storm.py:build_setup"] >= 1
    # ... and nothing of cases/ ran afterwards, whatever the number of trials
    assert dict(running.calls) == {}
