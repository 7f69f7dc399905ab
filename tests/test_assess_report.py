"""The design report of ``onbottom assess``: the pipe on the page, the absolute check by hand
from the page, the PDF holding every summary column and every section's design, validity marks,
no Python ``None`` on the page, and one design per section passing every level run (pipeline FE
included)."""

from __future__ import annotations

import html as _html
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from onbottom.assess import assess
from onbottom.assess._report import SUMMARY_COLUMNS
from onbottom.assess.output import format_value, level_name, write_outputs
from onbottom.cases.assess import build_route, parse_route_case

sys.path.insert(0, str(Path(__file__).resolve().parent))
from assess_cases import route_document


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("assess")
    doc = route_document(sections=2, seeds=2)
    doc["levels"]["pipeline_fe"] = True
    doc["pipeline"] = {"length": 60.0, "element_length": 5.0}
    route = build_route(parse_route_case(doc))
    a = assess(route, out=out, n_workers=0)
    written = write_outputs(a, out, pdf=True)
    return route, a, out, written


def _text(html: str) -> str:
    html = re.sub(r"src='data:[^']*'", "", html)
    return _html.unescape(re.sub(r"<[^>]+>", " ", html))


def _table(html: str, tid: str) -> list[list[str]]:
    m = re.search(rf'<table id="t-{tid}".*?</table>', html, re.S)
    assert m, tid
    rows = re.findall(r"<tr>(.*?)</tr>", m.group(0), re.S)
    return [[_html.unescape(re.sub(r"<[^>]+>", "", c)).strip()
             for c in re.findall(r"<td[^>]*>(.*?)</td>", r, re.S)] for r in rows]  # fmt: skip


def test_the_pipe_is_on_the_page(report):
    route, _a, out, _ = report
    html = (out / "report.html").read_text(encoding="utf-8")
    rows = {(r[0], r[1]): r[2] for r in _table(html, "pipe") if r}
    pipe = route.sections[0].pipe
    assert float(rows[("steel", "outer diameter")]) == pytest.approx(
        1e3 * pipe.steel_outer_diameter
    )
    assert float(rows[("steel", "wall thickness")]) == pytest.approx(1e3 * pipe.wall_thickness)
    for layer in pipe.layers:
        key = next(k for k in rows if k[0] == f"coating: {layer.name}" and "thickness" in k[1])
        assert float(rows[key]) == pytest.approx(1e3 * layer.thickness)
        assert float(rows[(f"coating: {layer.name}", "density")]) == pytest.approx(layer.density)
    for c in ("installation", "flooded", "hydrotest", "operation"):
        assert float(rows[(f"contents: {c}", "density")]) == getattr(pipe.contents, c)
    props = {(r[0], r[1]): r for r in _table(html, "pipe-properties") if r}
    p = pipe.properties("operation")
    r = props[("given design", "operation")]
    assert float(r[2]) == pytest.approx(1e3 * p.outer_diameter, abs=0.05)
    assert float(r[4]) == pytest.approx(p.submerged_weight, abs=0.05)
    assert float(r[5]) == pytest.approx(p.specific_gravity, abs=5e-4)
    for tid in ("basis", "levels", "solver", "s0-soil", "s0-sea"):
        assert f'<table id="t-{tid}"' in html, tid


def test_the_absolute_check_by_hand_from_the_page(report):
    """γ_SC (F*_Y + μ F*_Z) / (μ w_s + F_R) from the page's figures equals the utilisation of
    ``onbottom stability``'s check (run_checks on the same section)."""
    from onbottom.checks.design import run_checks

    route, _a, out, _ = report
    html = (out / "report.html").read_text(encoding="utf-8")
    v = {r[0]: float(r[1]) for r in _table(html, "s0-eq338") if r and r[0] != "" and
         not r[0].startswith("utilisation")}  # fmt: skip
    hand = v["γ_SC"] * (v["F*_Y"] + v["μ"] * v["F*_Z"]) / (v["μ"] * v["w_s"] + v["F_R"])
    sec = route.sections[0]
    rows = run_checks(sec.pipe, sec.seabed, sec.environment, sec.combinations, sec.options)
    util = max(r.utilisation for r in rows if r.name == "absolute_lateral")
    assert hand == pytest.approx(util, rel=1e-5)


def test_no_python_none_and_marks_with_legend(report):
    _route, a, out, _ = report
    html = (out / "report.html").read_text(encoding="utf-8")
    assert not re.search(r"\bNone\b", _text(html))
    assert "Marks on the design" in html
    # grey for what was not assessed, never green
    assert not re.search(r'class="[^"]*\bpass\b[^"]*">\s*not (covered|run)', html)
    for s in a.sections:
        assert f'href="#s{s["index"]}"' in html  # contents
    assert "time t [s]" in html and "y [m]" in html  # axis titles of y(t)
    csvs = sorted((out / "tables").glob("assess_*.csv"))
    assert len(csvs) == html.count("(CSV)")


def test_one_design_passes_every_level_run(report):
    _route, a, out, _ = report
    p = a.pipeline
    gov = a.sections[p["index"]]
    payload = json.loads((out / "results.json").read_text())
    row = payload["summary"][p["index"]]
    if p["pass"]:
        assert gov["design_value"] == p["design_value"] == row["design_value"]
        assert p["max_displacement_m"] <= p["allowable_m"] and p["strain_check"] is not False
        assert gov["design_value"] >= gov["levels"]["dynamic"]["value"]
        assert row["governing_level"] == ("pipeline_fe" if p["raised"] else gov["governing_level"])
    else:
        assert gov["governing_level"] is None and row["design_value"] is None
        assert gov["no_design_reason"]


def test_the_pdf_holds_the_design(report):
    _route, a, out, written = report
    if written["pdf"] is not None:
        pytest.skip(written["pdf"])
    exe = shutil.which("pdftotext")
    if exe is None:
        pytest.skip("pdftotext (poppler-utils) not installed")
    text = subprocess.run([exe, "-raw", str(out / "report.pdf"), "-"], capture_output=True,
                          text=True, check=True).stdout  # fmt: skip
    flat = " ".join(text.split())
    dense = "".join(text.split())  # a header wrapped inside its cell (at a space or a "/")
    for _, header, _ in SUMMARY_COLUMNS:
        assert "".join(header.split()) in dense, header
    for s in a.sections:
        assert s["name"] in flat
        value = format_value(s["design_value"], a.route.variable)
        design = f"{value} ({level_name(s['governing_level'])})"
        assert "".join(design.split()) in dense, design
    assert re.search(r"page 1 of \d+", flat)


# ---- figures from the models that ran ------------------------------------------------------------
def _page(a, out) -> str:
    from onbottom.assess._report import render, report_context

    payload = json.loads((out / "results.json").read_text())
    return render(report_context(a, payload))


def test_a_figure_that_cannot_be_drawn_says_why(report, monkeypatch):
    """No swallowed exception: the note names the figure, the error class and its message."""
    import onbottom.assess._figures as figures
    import onbottom.assess._report as page

    def broken(*args, **kwargs):
        raise RuntimeError("no flow for this storm")

    monkeypatch.setattr(figures, "vh_figure", broken)
    monkeypatch.setattr(page, "strip_svg", lambda base: 1 / 0)
    _route, a, out, _ = report
    html = _page(a, out)
    text = _text(html)
    assert text.count("V–H diagram not drawn: RuntimeError: no flow for this storm") == len(
        a.sections
    )
    assert "Dynamic level strip plot not drawn: ZeroDivisionError: division by zero" in text
    assert html.count('class="fail figure-not-drawn"') >= len(a.sections) + 1
    assert "alt='V–H diagram" not in html


def test_the_vh_diagram_is_computed_with_the_route_force_model(report, monkeypatch):
    """A spy on the fixed-pipe loads: every V–H cycle comes from the force model (and soil) that
    the route built for the section's storms, named in the caption."""
    import onbottom.hydro.fixed_pipe as fixed_pipe

    seen = []
    real = fixed_pipe.fixed_pipe_envelope

    def spy(force_model, kinematics, **kw):
        seen.append(force_model)
        return real(force_model, kinematics, **kw)

    monkeypatch.setattr(fixed_pipe, "fixed_pipe_envelope", spy)
    route, a, out, _ = report
    html = _page(a, out)
    built = [st.setup.force_model for sec in route.sections for st in sec.storms]
    assert seen and all(any(m is b for b in built) for m in seen)
    assert {m.name for m in seen} == {route.force_model} == {"wake"}
    text = _text(html)
    assert text.count("force model wake (as built from the case's [hydro])") == len(a.sections)
    assert "verley_sotberg soil model" in text
    assert "Morison C_D 0.9" not in text


def test_a_non_default_force_model_draws_its_own_loads(report):
    """The same section with its storms on Morison drag alone (C_L = 0, given in place of the
    route's wake model): every cycle's lift is zero, V = w_s (a default model would lift)."""
    import dataclasses

    from onbottom.assess._figures import _storm_envelope, vh_figure
    from onbottom.hydro.force_model import MorisonLift

    route, a, _out, _ = report
    drag = MorisonLift(cd=1.2, cm=0.0, cl=0.0, added_mass=0.0)
    sec = route.sections[0]
    storms = tuple(
        dataclasses.replace(st, setup=dataclasses.replace(st.setup, force_model=drag))
        for st in sec.storms
    )
    sec = dataclasses.replace(sec, storms=storms)
    env, used = _storm_envelope(sec.storms[0].setup)
    assert used["force"] == "morison_lift" and env.n_cycles > 0
    assert np.all(env.lift == 0.0)
    assert np.all(env.vertical == sec.storms[0].setup.pipe.submerged_weight)
    body, caption = vh_figure(a.sections[0], sec)
    assert body.startswith("<img") and "force model morison_lift" in caption
