"""``onbottom assess`` and ``onbottom reliability`` before any work: the budget of the storms
(a named refusal above it, ``--force`` to go on, the wording of ``storm`` and ``curves``), and
the ``--out`` folder of assess (the home folder and folders holding files onbottom did not
write are refused unless ``--force``; a lock file stops a second run, a stale lock of a dead
process is taken over with a note)."""

from __future__ import annotations

import json
import os
import re
import shutil
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from onbottom.assess.output import LOCK_NAME, MARK_NAME, claim_output_folder
from onbottom.cli.main import main
from onbottom.errors import InputError

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from assess_cases import route_document, route_toml

ROOT = Path(__file__).resolve().parents[2]


def _error(args: list, capsys) -> dict:
    rc = main([*map(str, args), "--json"])
    out = capsys.readouterr()
    assert rc == 1, out
    assert "Traceback" not in out.err
    return json.loads(out.out)["error"]


def _route(tmp_path: Path, **dynamic) -> Path:
    doc = route_document()
    doc["dynamic"] |= dynamic
    case = tmp_path / "route.toml"
    case.write_text(route_toml(doc), encoding="utf-8")
    return case


# ---- budgets ---------------------------------------------------------------------------------
def test_assess_of_1000_seeds_of_100_hour_storms_is_refused_before_work(tmp_path, capsys):
    case = _route(tmp_path, seeds=1000, peak_hours=100.0)
    out = tmp_path / "out"
    err = _error(["assess", case, "--out", out, "--workers", "0"], capsys)
    assert err["type"] == "BudgetError" and err["field"] == "[dynamic]"
    assert "storms of 100 h" in err["message"] and "--force" in err["message"]
    assert not out.exists()  # refused before any work or file


def test_assess_budget_estimate_counts_the_search():
    from onbottom.cases.assess import build_route, parse_route_case
    from onbottom.cli.assess import estimate

    route = build_route(parse_route_case(route_document(seeds=2)))
    est = estimate(route, workers=1)
    # 2 combinations x 2 seeds x (1 given design + 3 + log2(0.2 m / 0.004 m) -> 6 trials + 3)
    assert est.runs == 2 * 2 * (1 + 3 + 6)
    doc = route_document(seeds=2)
    doc["levels"]["dynamic"] = False
    assert estimate(build_route(parse_route_case(doc)), workers=1) is None


def test_assess_budget_counts_one_pipeline_fe_storm_per_section():
    """Hand calculation of the pipeline cost model (dynamics.pipeline.storm_run.run_cost:
    1 µs per node-step, 0.5 MB per node-hour): 200 m / 5 m → 41 nodes; a storm of
    0.02 h + 0.1 h = 432 s at dt_max 0.1 s → 4320 steps, 41 × 4320 × 1e-6 = 0.17712 CPU-s and
    0.5e6 × 41 × 0.12 h = 2.46 MB of kinematics; one worker."""
    from onbottom.cases.assess import build_route, parse_route_case
    from onbottom.cli.assess import estimate

    doc = route_document(sections=3, seeds=2)
    base = estimate(build_route(parse_route_case(doc)), workers=1)
    doc["levels"]["pipeline_fe"] = True
    doc["pipeline"] = {"sections": "every", "length": 200.0, "element_length": 5.0}
    every = estimate(build_route(parse_route_case(doc)), workers=1)
    per_storm, kinematics = 41 * 4320 * 1.0e-6, 0.5e6 * 41 * 0.12
    assert every.runs == base.runs + 3
    assert every.wall_s == pytest.approx(base.wall_s + 3 * per_storm)
    assert every.memory_bytes == pytest.approx(base.memory_bytes + kinematics + 3 * 2000)
    assert "3 pipeline storms" in every.what
    doc["pipeline"]["sections"] = "governing"  # the governing section's FE storm only
    governing = estimate(build_route(parse_route_case(doc)), workers=1)
    assert governing.runs == base.runs + 1
    assert governing.wall_s == pytest.approx(base.wall_s + per_storm)


def test_reliability_of_1e9_storms_is_a_budget_refusal(tmp_path, capsys):
    pytest.importorskip("openturns")
    pytest.importorskip("zarr")
    text = (ROOT / "examples" / "reliability_case.toml").read_text(encoding="utf-8")
    shutil.copy(ROOT / "examples" / "hindcast_synthetic.csv", tmp_path)
    text = re.sub(r"(?m)^max_storms = .*$", "max_storms = 1000000000", text)
    case = tmp_path / "case.toml"
    case.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    err = _error(["reliability", case, "--out", out, "--workers", "0"], capsys)
    assert err["type"] == "BudgetError" and err["field"] == "reliability.max_storms"
    assert "--force" in err["message"] and not out.exists()


# ---- the --out folder --------------------------------------------------------------------------
def test_out_with_files_onbottom_did_not_write_is_refused_unless_force(tmp_path, capsys):
    case = _route(tmp_path)
    out = tmp_path / "mine"
    out.mkdir()
    (out / "report.html").write_text("<html>my own page</html>", encoding="utf-8")
    err = _error(["assess", case, "--out", out, "--workers", "0"], capsys)
    assert err["field"] == "--out" and "onbottom did not write" in err["message"]
    assert "report.html" in err["message"] and "--force" in err["message"]
    assert (out / "report.html").read_text(encoding="utf-8") == "<html>my own page</html>"
    with claim_output_folder(out, force=True) as held:  # --force: accepted, and marked
        assert held.notes == [] and (out / LOCK_NAME).is_file()
    assert not (out / LOCK_NAME).exists() and (out / MARK_NAME).is_file()
    claim_output_folder(out).release()  # marked: accepted from now on


def test_out_of_an_earlier_run_without_the_mark_is_accepted(tmp_path):
    out = tmp_path / "old"
    (out / "sections").mkdir(parents=True)
    (out / "results.json").write_text("{}", encoding="utf-8")
    (out / "report.html").write_text(
        '<!DOCTYPE html><html><head><meta name="generator" content="onbottom assess 0.1.0">',
        encoding="utf-8",
    )
    claim_output_folder(out).release()


def test_home_folder_is_refused(tmp_path, monkeypatch):
    monkeypatch.setenv("HOME", str(tmp_path))
    for force in (False, True):
        with pytest.raises(InputError, match="the home folder") as err:
            claim_output_folder(tmp_path, force=force)
        assert err.value.field == "--out"


def test_lock_refuses_a_second_run_and_takes_over_a_dead_ones(tmp_path):
    out = tmp_path / "out"
    live = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        out.mkdir()
        (out / MARK_NAME).write_text("x", encoding="utf-8")
        (out / LOCK_NAME).write_text(f"{live.pid} {socket.gethostname()}\n", encoding="utf-8")
        with pytest.raises(InputError, match=rf"in use: process {live.pid} on") as err:
            claim_output_folder(out)
        assert err.value.field == "--out"
    finally:
        live.kill()
        live.wait()
    with claim_output_folder(out) as held:  # the process is gone: taken over
        assert len(held.notes) == 1 and f"process {live.pid}, which is gone" in held.notes[0]
        assert (out / LOCK_NAME).read_text().split()[0] == str(os.getpid())
        with pytest.raises(InputError, match=rf"in use: process {os.getpid()} on"):
            claim_output_folder(out)  # this run holds it
    assert not (out / LOCK_NAME).exists()


def test_reliability_out_with_files_onbottom_did_not_write_is_refused(tmp_path, capsys):
    pytest.importorskip("openturns")
    pytest.importorskip("zarr")
    shutil.copy(ROOT / "examples" / "reliability_case.toml", tmp_path / "case.toml")
    shutil.copy(ROOT / "examples" / "hindcast_synthetic.csv", tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    (out / "thesis.tex").write_text("mine", encoding="utf-8")
    err = _error(["reliability", tmp_path / "case.toml", "--out", out, "--workers", "0"], capsys)
    assert err["field"] == "--out" and "thesis.tex" in err["message"]
    assert sorted(p.name for p in out.iterdir()) == ["thesis.tex"]


def test_pipeline_fe_of_assess_keeps_no_checkpoint_so_no_restart_advice(tmp_path, monkeypatch):
    """assess has no --restart: its pipeline FE trials run without a checkpoint file (the
    accepted run's envelopes are written after the search), so a checkpoint of other inputs
    (an edited [pipeline]) can never stop it with advice naming options assess lacks."""
    import onbottom.dynamics.pipeline as dp
    from onbottom.assess.pipeline import run_governing_pipeline
    from onbottom.cases.assess import build_route, parse_route_case

    doc = route_document()
    doc["levels"]["pipeline_fe"] = True
    doc["pipeline"] = {"length": 40.0, "element_length": 5.0}
    route = build_route(parse_route_case(doc))
    combo = route.sections[0].storms[0].name
    sections = [
        {
            "name": route.sections[0].name,
            "index": 0,
            "design_value": 0.04,
            "dynamic": {
                "base": {combo: {"utilisation": 0.5, "seeds": [0], "max_displacement": [0.01]}}
            },
        }
    ]
    (tmp_path / "pipeline.nc.checkpoint").write_text("from another run", encoding="utf-8")
    calls = []

    class Done(Exception):
        pass

    def fake(*args, **kwargs):
        calls.append(kwargs)
        raise Done

    monkeypatch.setattr(dp, "simulate_pipeline", fake)
    with pytest.raises(Done):
        run_governing_pipeline(route, sections, out=tmp_path)
    assert len(calls) == 1
    assert calls[0].get("output") is None and "resume" not in calls[0]
