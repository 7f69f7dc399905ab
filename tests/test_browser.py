"""The report and the documentation site, opened in a real browser (headless Chromium).

Each page is screenshotted; every image must load (``naturalWidth > 0``), no request may
fail and no internal link may be broken. Chromium is Debian's ``chromium`` package, which
``.ci/run`` installs with apt-get; where it cannot be installed the tests skip and say so.

The site: ``$ONBOTTOM_SITE_DIR`` when set (``.ci/run`` builds it with ``mkdocs build
--strict`` before the tests); otherwise the test builds a lean site itself (gallery and slow
report sections left out), or skips when the ``docs`` extra is not installed. Screenshots go
to ``$ONBOTTOM_SCREENSHOT_DIR`` when set (else a temporary folder).
"""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

_spec = importlib.util.spec_from_file_location("browser_check", ROOT / "tools" / "browser_check.py")
browser_check = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("browser_check", browser_check)  # dataclasses look the module up
_spec.loader.exec_module(browser_check)

CHROMIUM = browser_check.find_chromium()
pytestmark = pytest.mark.skipif(
    CHROMIUM is None,
    reason="Chromium is not installed (Debian: apt-get install chromium; .ci/run installs it"
    " where apt-get is available) — the browser checks of the report and the site are skipped",
)


@pytest.fixture(scope="module")
def shots(tmp_path_factory) -> Path:
    d = os.environ.get("ONBOTTOM_SCREENSHOT_DIR")
    if d:
        Path(d).mkdir(parents=True, exist_ok=True)
        return Path(d)
    return tmp_path_factory.mktemp("screenshots")


@pytest.fixture(scope="module")
def browser():
    with browser_check.Chromium(CHROMIUM) as b:
        yield b


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    env_dir = os.environ.get("ONBOTTOM_SITE_DIR")
    if env_dir:
        site = Path(env_dir)
        assert (site / "index.html").is_file(), f"ONBOTTOM_SITE_DIR={env_dir} has no index.html"
        return site
    if importlib.util.find_spec("mkdocs") is None:
        pytest.skip('the docs extra is not installed (pip install -e ".[docs]"): no site to open')
    site = tmp_path_factory.mktemp("site")
    env = dict(os.environ, ONBOTTOM_DOCS_GALLERY="skip", ONBOTTOM_DOCS_REPORT="fast")
    proc = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-d", str(site)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    return site


def _assert_page_ok(rep, min_images: int = 0) -> None:
    assert rep.ok, "\n".join(rep.problems())
    assert len(rep.images) >= min_images, rep.images
    assert all(i["naturalWidth"] > 0 for i in rep.images)
    png = rep.screenshot.read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000


def test_report_in_browser(browser, shots, tmp_path):
    from onbottom.report import build_report

    res = build_report(tmp_path / "report", only=["f114", "dem"])
    rep = browser_check.check_page(browser, res.index, shots / "report.png")
    _assert_page_ok(rep, min_images=2)
    assert rep.title == "onbottom validation report"
    assert rep.n_links >= 5  # table of contents, CSV files, report.json


@pytest.mark.slow
@pytest.mark.long
def test_site_front_page_and_report_in_browser(browser, shots, site):
    front = browser_check.check_page(browser, site / "index.html", shots / "site_front.png")
    _assert_page_ok(front)
    assert front.n_links > 20  # navigation
    report = site / "validation" / "validation-report" / "index.html"
    _assert_page_ok(
        browser_check.check_page(browser, report, shots / "site_report.png"), min_images=1
    )
    gallery = site / "gallery" / "index.html"
    rep = browser_check.check_page(browser, gallery, shots / "site_gallery.png")
    _assert_page_ok(rep)


@pytest.mark.slow
@pytest.mark.long
def test_no_broken_link_anywhere_in_the_site(site):
    errors = browser_check.site_link_errors(site)
    assert errors == [], "\n".join(errors[:50])
    assert (site / "api" / "onbottom_soil.html").is_file()  # API reference generated


def test_checker_sees_broken_images_and_links(browser, tmp_path):
    # a page with one good and one missing image, a good and a broken link, a bad fragment
    good = ROOT / "docs" / "validation" / "dem" / "dem_heave.png"
    shutil.copyfile(good, tmp_path / "ok.png")
    (tmp_path / "other.html").write_text('<p id="here">x</p>', encoding="utf-8")
    (tmp_path / "page.html").write_text(
        '<html><head><title>t</title></head><body><img src="ok.png"><img src="missing.png">'
        '<a href="other.html#here">a</a><a href="nowhere.html">b</a>'
        '<a href="other.html#absent">c</a><a href="https://example.org">d</a></body></html>',
        encoding="utf-8",
    )
    rep = browser_check.check_page(browser, tmp_path / "page.html", tmp_path / "shot.png")
    assert not rep.ok
    assert [Path(s).name for s in rep.broken_images] == ["missing.png"]
    assert len(rep.broken_links) == 2 and rep.n_external == 1
    assert any("nowhere.html" in b for b in rep.broken_links)
    assert any("absent" in b for b in rep.broken_links)
    assert sorted(browser_check.site_link_errors(tmp_path)) == sorted(
        [
            "page.html: " + (tmp_path / "nowhere.html").as_uri() + " (no such file)",
            "page.html: " + (tmp_path / "other.html").as_uri() + "#absent (no element with id"
            " 'absent')",
            "page.html: " + (tmp_path / "missing.png").as_uri() + " (no such file)",
        ]
    )


def _style(html: str) -> str:
    import re

    return re.search(r"<style>(.*?)</style>", html, re.S).group(1)


@pytest.mark.long
def test_assess_and_metocean_pages_share_one_style(browser, shots, tmp_path):
    """The assess design report and a command page (metocean) open in Chromium with the same
    style sheet, header band and contents (the reliability page is written by the same
    :func:`onbottom.report.pages.write_page` as metocean's)."""
    pytest.importorskip("pyextremes")
    pytest.importorskip("virocon")
    sys.path.insert(0, str(ROOT / "tests"))
    from assess_cases import route_document
    from onbottom.assess import assess
    from onbottom.assess.output import write_outputs
    from onbottom.cases.assess import build_route, parse_route_case
    from onbottom.cli.main import main

    a = assess(build_route(parse_route_case(route_document(seeds=1, peak_hours=0.05))),
               n_workers=0)  # fmt: skip
    write_outputs(a, tmp_path / "assess", pdf=False)
    met = tmp_path / "metocean"
    hind = ROOT / "examples" / "hindcast_synthetic.csv"
    assert main(["metocean", str(hind), "--out", str(met), "--no-figures"]) == 0
    pages = {"assess": tmp_path / "assess" / "report.html", "metocean": met / "report.html"}
    styles = set()
    for name, page in pages.items():
        rep = browser_check.check_page(browser, page, shots / f"{name}_page.png")
        _assert_page_ok(rep)
        text = page.read_text(encoding="utf-8")
        assert "<header>" in text and 'class="toc"' in text, name
        styles.add(_style(text))
    assert len(styles) == 1
