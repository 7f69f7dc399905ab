"""Helpers of the tests that write small case files and run CLI commands on them: write a
case, edit its text, a TOML value, and run a command with ``--json`` (its payload read, with
no ``NaN``/``Infinity`` in it)."""

from __future__ import annotations

import json
import math
from pathlib import Path

from onbottom.cli.main import main


def write_file(folder: Path, text: str, name: str = "case.toml") -> Path:
    """``folder/name`` holding ``text``."""
    p = folder / name
    p.write_text(text, encoding="utf-8")
    return p


def edit(text: str, old: str, new: str) -> str:
    """``text`` with its first ``old`` replaced by ``new`` (``old`` must be there)."""
    assert old in text, old
    return text.replace(old, new, 1)


def no_nan(text: str) -> None:
    """Fail if the JSON ``text`` holds ``NaN`` or ``Infinity`` (not JSON)."""

    def refuse(const: str) -> None:
        raise AssertionError(f"{const} in the JSON output")

    json.loads(text, parse_constant=refuse)


def run_json(args: list, capsys) -> tuple[int, dict]:
    """Exit status and ``--json`` payload of ``onbottom ARGS`` (paths may be Path objects)."""
    rc = main([*map(str, args), "--json"])
    out = capsys.readouterr().out
    no_nan(out)
    return rc, json.loads(out)


def toml_value(v) -> str:
    """A TOML value of a bool, number (nan and inf included), string, list or inline table."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def curves_case(*, build_up_hours: float, peak_hours: float, tolerance: float) -> str:
    """A two-point ``[curves]`` case (sand, K 5 and 10, M 0.2, criterion L_10, one seed) with
    short storms: the interrupt and kill tests run it."""
    return f"""[curves]
K = [5.0, 10.0]
M = [0.2]
soils = ["sand"]
criteria = ["L_10"]
seeds = 1
build_up_hours = {build_up_hours!r}
peak_hours = {peak_hours!r}
tolerance = {tolerance!r}
"""
