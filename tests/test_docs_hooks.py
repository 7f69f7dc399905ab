"""The MkDocs hook of the documentation site (tools/docs_hooks.py): nav expansion and the
filter that keeps unit brackets in docstrings from failing the strict build."""

from __future__ import annotations

import importlib.util
import logging
import sys
from pathlib import Path

import pytest

pytest.importorskip("mkdocs", reason='the docs extra is not installed (pip install -e ".[docs]")')

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("docs_hooks", ROOT / "tools" / "docs_hooks.py")
hooks = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("docs_hooks", hooks)
_spec.loader.exec_module(hooks)


def test_folder_entries_expand_into_their_pages(tmp_path):
    (tmp_path / "theory").mkdir()
    (tmp_path / "theory" / "b.md").write_text("# Beta model\n\ntext\n", encoding="utf-8")
    (tmp_path / "theory" / "a.md").write_text("no heading\n", encoding="utf-8")
    nav = [{"Home": "index.md"}, {"Theory": "theory/"}, {"API": "api/"}]
    out = hooks._expand(nav, tmp_path)
    assert out[0] == {"Home": "index.md"}
    assert out[1] == {"Theory": [{"a": "theory/a.md"}, {"Beta model": "theory/b.md"}]}
    api = out[2]["API"]
    assert api[0] == {"Overview": "api/index.md"}
    assert {"onbottom.report": "api/onbottom_report.md"} in api


def test_generated_validation_report_page_is_listed_first(tmp_path):
    (tmp_path / "validation").mkdir()
    (tmp_path / "validation" / "x.md").write_text("# X\n", encoding="utf-8")
    (out,) = hooks._expand([{"Validation": "validation/"}], tmp_path)
    assert out["Validation"] == [
        {"Validation report": "validation/report.md"},
        {"X": "validation/x.md"},
    ]


@pytest.mark.parametrize(
    ("target", "dropped"),
    [("-", True), ("m", True), ("N/m", True), ("kN/m³", True), ("Pipe", False), ("a.b", False)],
)
def test_only_unit_brackets_are_silenced(target, dropped):
    rec = logging.LogRecord(
        "mkdocs.plugins.mkdocs_autorefs",
        logging.WARNING,
        __file__,
        1,
        f"api/x.md: Could not find cross-reference target '{target}'",
        None,
        None,
    )
    assert hooks._UnitBrackets().filter(rec) is not dropped


def test_every_library_package_has_an_api_page():
    """Each subpackage of the library is in the API reference (cli: the CLI reference; data:
    package data; peers: optional comparisons with other programs, documented on their
    validation page)."""
    src = ROOT / "src" / "onbottom"
    packages = {p.parent.name for p in src.glob("*/__init__.py")} - {"cli", "data", "peers"}
    listed = {mod for mod, _ in hooks.API_PACKAGES}
    assert {f"onbottom.{p}" for p in packages} <= listed
    assert "onbottom.assess" in listed
