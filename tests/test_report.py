"""The validation report: registry, files, tables, pass/fail, provenance, CLI (fast sections only).

Runs the fast sections (F114, centrifuge bands, F109 design sheet, DEM: a few seconds); the
others run in the site build in CI. The F114 numbers are those of the reference table in
shared/spec/dnv-reference.md §3.3 (the same as tests/unit/test_penetration_f114.py).
"""

from __future__ import annotations

import csv
import json
import math
import re
from html.parser import HTMLParser

import pytest

from onbottom.cli.main import main
from onbottom.errors import InputError
from onbottom.report import SectionContent, SectionContext, build_report, load_sections, within
from onbottom.report.content import Check, Table, format_cell
from onbottom.report.registry import REGISTRY, section

FAST = ["f114", "centrifuge_bands", "checks_f109", "dem"]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    return build_report(tmp_path_factory.mktemp("report"), only=FAST)


class _Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.imgs, self.ids, self.hrefs, self.tables = [], set(), [], 0

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "img":
            self.imgs.append(a["src"])
        if tag == "a":
            self.hrefs.append(a["href"])
        if tag == "table":
            self.tables += 1


def test_files_written_beside_the_page(report):
    out = report.index.parent
    page = _Page()
    page.feed(report.index.read_text(encoding="utf-8"))
    assert len(page.imgs) >= 2  # the F114 figure and the committed DEM figures
    for src in page.imgs:
        assert not src.startswith(("/", "http")), src  # relative: the folder can be moved
        assert (out / src).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for href in page.hrefs:
        if href.startswith("#"):
            assert href[1:] in page.ids, href
        else:
            assert (out / href).is_file(), href
    assert {"f114", "dem", "provenance"} <= page.ids
    assert page.tables >= 4


def test_f114_table_and_checks_match_the_reference(report):
    f114 = next(s for s in report.sections if s.name == "f114")
    assert f114.state == "ok"
    # 10 reference rows x 5 levels, each within ±1 % or 0.06 kN/m of the spec table
    ref = [c for c in f114.content.checks if c.note.startswith("F114 Eq 4.9")]
    assert len(ref) == 50 and all(c.status == "pass" for c in ref)
    vesic = next(c for c in ref if c.name == "Q_v at 0.5D, γ' 16.7, φ' 40°, vesic")
    assert vesic.reference == 258.5 and vesic.value == pytest.approx(258.5, abs=0.06 + 2.585)
    # the CSV beside the page holds the same numbers as the table
    rows = list(csv.reader((report.index.parent / f114.table_files[0]).open(encoding="utf-8")))
    assert rows[0][:3] == ["γ' [kN/m³] / φ' / N_γ", "N_γ [-]", "0.1D"]
    assert len(rows) == 11
    assert float(rows[1][2]) == pytest.approx(10.6, abs=0.06)


def test_pass_fail_counts_are_consistent(report):
    data = json.loads(report.json_path.read_text(encoding="utf-8"))
    assert data["n_pass"] == report.n_pass > 0
    assert data["n_fail"] == report.n_fail
    for s in data["sections"]:
        if s["state"] == "ok":
            assert s["n_pass"] == sum(c["status"] == "pass" for c in s["checks"])
            assert s["n_fail"] == sum(c["status"] == "fail" for c in s["checks"])
    html = report.index.read_text(encoding="utf-8")
    assert f"{report.n_pass} pass" in html and f"{report.n_fail} fail" in html
    # every failing check says why (documented deviation or its own note)
    for s in report.sections:
        for c in s.content.checks:
            if c.status == "fail":
                assert c.note, c.name


def test_dem_section_reads_committed_summaries(report):
    dem = next(s for s in report.sections if s.name == "dem")
    assert dem.state == "ok"
    heave = next(c for c in dem.content.checks if c.name == "SD: heave peak / D")
    assert heave.reference == 0.25 and 0.0 < heave.value < 1.0
    assert heave.status == ("pass" if abs(heave.value - 0.25) <= 0.1 else "fail")


def test_bands_and_design_sheet_sections(report):
    by = {s.name: s for s in report.sections}
    if by["centrifuge_bands"].state == "ok":  # H14's module and committed CSV present
        checks = {c.name: c for c in by["centrifuge_bands"].content.checks}
        assert len(checks) == 7
        reg = checks["Regular: Table 1 cycles inside the band"]
        assert reg.reference == 46.22 and reg.status == "fail" and "lift-off" in reg.note
    if by["checks_f109"].state == "ok":  # H11's design layer present
        checks = {c.name: c for c in by["checks_f109"].content.checks}
        d = checks["outer diameter D"]
        assert d.value == pytest.approx(0.2191 + 2 * (0.0055 + 0.08255), abs=1e-12)
        assert d.status == "pass" and d.reference == 0.3951


def test_provenance(report):
    p = report.provenance
    assert p["onbottom_version"]
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00", p["date_utc"])
    assert p["machine"] and p["python"] and p["run_time"] > 0
    html = report.index.read_text(encoding="utf-8")
    assert p["date_utc"] in html and p["platform"] in html
    if p["git_commit"] is not None:
        assert re.fullmatch(r"[0-9a-f]{40}", p["git_commit"]) and p["git_commit"] in html


def test_unrun_and_unavailable_sections_are_visible(report):
    states = {s.name: s.state for s in report.sections}
    assert states["centrifuge"] == "skipped"
    html = report.index.read_text(encoding="utf-8")
    for s in report.sections:
        if s.state == "unavailable":
            assert "not available in this build" in html
            assert s.reason in html


def test_missing_module_makes_a_section_unavailable(tmp_path):
    @section("zz_test_missing", "Needs a module that does not exist", 999, requires=("no_such",))
    def _build(ctx: SectionContext) -> SectionContent:  # pragma: no cover - never run
        raise AssertionError("must not run")

    @section("zz_test_raises", "Raises", 998)
    def _raises(ctx: SectionContext) -> SectionContent:
        raise ValueError("boom")

    try:
        res = build_report(tmp_path, only=["zz_test_missing", "zz_test_raises"])
    finally:
        del REGISTRY["zz_test_missing"], REGISTRY["zz_test_raises"]
    by = {s.name: s for s in res.sections}
    assert by["zz_test_missing"].state == "unavailable"
    assert "no_such" in by["zz_test_missing"].reason
    assert by["zz_test_raises"].state == "error" and "boom" in by["zz_test_raises"].reason
    assert res.n_fail == 1  # an error counts as a failure
    page = res.index.read_text(encoding="utf-8")
    assert "not available in this build" in page
    assert "ValueError: boom" in page  # a section (or its figure) that fails says why, on the page


def test_registry_order_and_validation():
    secs = load_sections()
    orders = [s.order for s in secs]
    assert orders == sorted(orders)
    assert {"f114", "centrifuge", "calibration", "dem"} <= {s.name for s in secs}
    with pytest.raises(InputError, match="name"):
        section("Bad Name", "x", 1)
    with pytest.raises(InputError, match="only"):
        build_report("unused", only=["nope"])


def test_content_helpers():
    assert within("x", 10.05, 10.0, rtol=0.01).status == "pass"
    assert within("x", 10.2, 10.0, rtol=0.01).status == "fail"
    assert within("x", float("nan"), 10.0, rtol=0.5).status == "fail"
    assert within("x", 0.05, 0.0, atol=0.06, unit="kN/m").tolerance == "±0.06 kN/m"
    assert format_cell(-4.97e-8) == "-4.97e-08" and format_cell(0.0) == "0.000"
    assert format_cell(1.23456, 2) == "1.23" and format_cell(None) == format_cell(math.nan) == "–"
    with pytest.raises(InputError, match="status"):
        Check(name="x", value=1.0, reference=1.0, tolerance="", status="ok")
    with pytest.raises(InputError, match="rows"):
        Table(caption="t", columns=["a", "b"], rows=[[1]])


def test_cli_json(tmp_path, capsys):
    assert main(["report", "--out", str(tmp_path), "--only", "f114", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n_pass"] >= 50 and (tmp_path / "index.html").is_file()
    assert {s["name"]: s["state"] for s in out["sections"]}["f114"] == "ok"


def test_cli_list_and_bad_section(capsys):
    assert main(["report", "--list", "--json"]) == 0
    names = [s["name"] for s in json.loads(capsys.readouterr().out)["sections"]]
    assert "f114" in names
    assert main(["report", "--only", "nope", "--out", "unused"]) == 1
    assert "allowed sections" in capsys.readouterr().err
