"""``onbottom assess`` end to end on a small route: outputs, JSON, resume, case untouched,
and the design report opened in headless Chromium (skipped, with the reason, without it)."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

from onbottom.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from assess_cases import route_document  # noqa: E402

_spec = importlib.util.spec_from_file_location("browser_check", ROOT / "tools" / "browser_check.py")
browser_check = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("browser_check", browser_check)
_spec.loader.exec_module(browser_check)


def _toml(doc: dict) -> str:
    """A route document as TOML (the few value types the tests use)."""

    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        return repr(v)

    lines: list[str] = []

    def table(prefix: str, d: dict, array: bool = False) -> None:
        lines.append(f"[[{prefix}]]" if array else f"[{prefix}]")
        subs = []
        for k, v in d.items():
            if isinstance(v, dict):
                subs.append((k, v, False))
            elif isinstance(v, list) and v and isinstance(v[0], dict):
                subs.append((k, v, True))
            else:
                lines.append(f"{k} = {val(v)}")
        for k, v, arr in subs:
            if arr:
                for item in v:
                    table(f"{prefix}.{k}", item, True)
            else:
                table(f"{prefix}.{k}", v)

    for k, v in doc.items():
        if k == "route":
            lines.append(f"[route]\nname = {val(v['name'])}")
            for s in v["sections"]:
                table("route.sections", s, True)
        else:
            table(k, v)
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    d = tmp_path_factory.mktemp("assess")
    case = d / "route.toml"
    doc = route_document(sections=2)
    doc["levels"]["pipeline_fe"] = True  # the report's pipeline page, opened in Chromium too
    doc["pipeline"] = {"length": 60.0, "element_length": 5.0}
    case.write_text(_toml(doc), encoding="utf-8")
    before = case.read_bytes()
    out = d / "out"
    rc = main(["assess", str(case), "--out", str(out), "--workers", "0", "--quiet", "--no-pdf"])
    return case, before, out, rc


def test_outputs_written_case_untouched(run, capsys):
    case, before, out, rc = run
    assert rc == 0
    assert case.read_bytes() == before
    for name in ("report.html", "results.json", "dynamic.nc"):
        assert (out / name).is_file(), name
    payload = json.loads((out / "results.json").read_text())
    from onbottom.assess.output import RESULTS_KEYS

    assert tuple(payload) == RESULTS_KEYS
    assert [r["section"] for r in payload["summary"]] == ["section 0", "section 1"]
    assert payload["provenance"]["case_sha256"]
    # rerun: every section is reused (same inputs)
    rc = main(["assess", str(case), "--out", str(out), "--workers", "0", "--json", "--no-pdf"])
    assert rc == 0
    again = json.loads(capsys.readouterr().out)
    assert again["provenance"]["sections_reused"] == ["section 0", "section 1"]
    # the JSON contract (cli/json_contract.py, docs/json.md)
    from onbottom.cli.json_contract import documented_keys

    assert set(again) == documented_keys("assess")
    for row in again["summary"]:
        assert set(row) == documented_keys("assess", "summary[]")


def test_bad_case_named_error(tmp_path, capsys):
    doc = route_document()
    doc["route"]["sections"][0]["water_depth"] = -1.0
    case = tmp_path / "bad.toml"
    case.write_text(_toml(doc), encoding="utf-8")
    rc = main(["assess", str(case), "--out", str(tmp_path / "o"), "--json"])
    assert rc == 1
    err = json.loads(capsys.readouterr().out)["error"]
    assert "water_depth" in err["message"]
    assert not (tmp_path / "o").exists()  # no work, no output


def test_embedded_example_printed(capsys):
    from onbottom.cases.assess import example_path

    assert main(["assess", "--example"]) == 0
    assert capsys.readouterr().out == example_path().read_text(encoding="utf-8")


CHROMIUM = browser_check.find_chromium()


@pytest.mark.skipif(
    CHROMIUM is None,
    reason="Chromium is not installed (Debian: apt-get install chromium) — the browser check"
    " of the assess design report is skipped",
)
def test_report_opens_in_chromium(run, tmp_path):
    _, _, out, _ = run
    with browser_check.Chromium(CHROMIUM) as b:
        rep = browser_check.check_page(b, out / "report.html", tmp_path / "assess.png")
    assert rep.ok, "\n".join(rep.problems())
    assert rep.title.startswith("On-bottom stability assessment")


def test_no_design_in_range_exits_3(tmp_path, capsys):
    doc = route_document()
    doc["levels"] = {"generalized": False, "dynamic": False}
    doc["design"]["thickness_max"] = 0.002  # the absolute method needs far more
    case = tmp_path / "narrow.toml"
    case.write_text(_toml(doc), encoding="utf-8")
    rc = main(
        ["assess", str(case), "--out", str(tmp_path / "o"), "--workers", "0", "--quiet", "--no-pdf"]
    )
    assert rc == 3
    assert "no solution" in capsys.readouterr().out
    assert (tmp_path / "o" / "report.html").is_file()  # the outputs are still written


def test_warnings_printed_once_as_notes_and_listed_in_the_report(tmp_path, capsys):
    """A coating lighter than water warns once (a `note:` line, no source line), however many
    sections and conditions meet it, and the report lists it."""
    doc = route_document(sections=2)
    doc["levels"] = {"generalized": False, "dynamic": False}
    doc["pipe"]["layers"][0]["density"] = 940.0  # a 3LPP-like layer, lighter than water
    case = tmp_path / "light.toml"
    case.write_text(_toml(doc), encoding="utf-8")
    out = tmp_path / "o"
    rc = main(["assess", str(case), "--out", str(out), "--workers", "0", "--quiet", "--no-pdf"])
    assert rc == 0
    cap = capsys.readouterr()
    lines = [ln for ln in (cap.out + cap.err).splitlines() if "lighter than the water" in ln]
    assert len(lines) == 1 and lines[0].startswith("note: "), lines
    assert "warnings.warn" not in cap.out + cap.err
    html = (out / "report.html").read_text(encoding="utf-8")
    assert "lighter than the water" in html
