"""Unit test: which solver a storm case file is for is decided in cases/, not in the CLI."""

from __future__ import annotations

import ast
from pathlib import Path

from onbottom.cases.pipeline import is_pipeline_case


def test_a_pipeline_table_makes_a_pipeline_case(tmp_path):
    section = tmp_path / "section.toml"
    section.write_text('[pipe]\ndiameter = 0.5\n[storm]\nkind = "regular"\n', encoding="utf-8")
    pipeline = tmp_path / "pipeline.toml"
    pipeline.write_text("[pipe]\ndiameter = 0.5\n[pipeline]\nlength = 200.0\n", encoding="utf-8")
    broken = tmp_path / "broken.toml"
    broken.write_text("[pipeline\n", encoding="utf-8")  # the storm loader names the line
    as_json = tmp_path / "pipeline.json"
    as_json.write_text('{"pipeline": {"length": 200.0}}', encoding="utf-8")
    assert not is_pipeline_case(section)
    assert is_pipeline_case(pipeline)
    assert not is_pipeline_case(broken)
    assert is_pipeline_case(as_json)


def test_the_storm_command_reads_no_case_file_itself():
    src = Path(__file__).resolve().parents[2] / "src" / "onbottom" / "cli" / "storm.py"
    tree = ast.parse(src.read_text(encoding="utf-8"))
    modules = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert "onbottom._casefile" not in modules and "tomllib" not in modules
    assert "onbottom.cases.pipeline" in modules
