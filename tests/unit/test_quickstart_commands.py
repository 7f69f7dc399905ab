"""Every command line of the quick start parses against the real command (issue 31 item 6).

The page's ``onbottom …`` lines (code blocks and inline code) are split as a shell would and
handed to click's parser of that command, run from a folder with a link to examples/ (as the
page says): the command exists, every option is one it takes with a valid value, and every
input file the line names exists.
Nothing is run here (``tests/test_quickstart_run.py``, long, runs them all from a temporary
folder).
"""

from __future__ import annotations

import os
import re
import shlex
from pathlib import Path

import click
import pytest

from onbottom.cli.main import cli

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "quickstart.md"


def _command_lines() -> list[str]:
    text = PAGE.read_text(encoding="utf-8")
    lines = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        lines += [ln.split("#")[0].strip() for ln in block.splitlines()]
    lines = [ln.split(">")[0].strip() for ln in lines]  # "onbottom assess --example > f"
    lines += re.findall(r"`(onbottom [^`|]+)`", text)  # not "dem prepare|penetrate|plot"
    # a command line has arguments ("onbottom calibrate" alone names a command in the prose)
    return [ln for ln in lines if ln.startswith("onbottom ") and len(shlex.split(ln)) > 2]


def _run_lines() -> list[str]:
    """The page's command lines as a shell runs them (redirections kept), page order."""
    text = PAGE.read_text(encoding="utf-8")
    lines = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        lines += [ln.split("#")[0].strip() for ln in block.splitlines()]
    lines += re.findall(r"`(onbottom [^`|]+)`", text)
    return [
        ln
        for ln in lines
        if ln == "onbottom warmup" or (ln.startswith("onbottom ") and len(shlex.split(ln)) > 2)
    ]


LINES = _command_lines()


def test_the_quickstart_shows_the_stability_commands():
    named = {shlex.split(ln)[1] for ln in LINES}
    assert {
        "assess",
        "metocean",
        "reliability",
        "stability",
        "loads",
        "storm",
        "curves",
        "report",
    } <= named


@pytest.mark.parametrize("line", LINES)
def test_quickstart_command_line_parses(line, monkeypatch, tmp_path):
    # the page's own folder: a link to examples/ and the route the page writes first
    from onbottom.cases.assess import example_path

    (tmp_path / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    (tmp_path / "my_route.toml").write_text(example_path().read_text(encoding="utf-8"))
    monkeypatch.chdir(tmp_path)
    args = shlex.split(line)[1:]
    ctx = click.Context(cli)
    name, command, rest = cli.resolve_command(ctx, args)
    assert command is not None, line
    while isinstance(command, click.Group):  # e.g. dem prepare
        name, command, rest = command.resolve_command(ctx, rest)
    if "--list" in rest or "--help" in rest:
        return
    with command.make_context(name, rest, parent=ctx) as sub:
        for value in sub.params.values():
            if isinstance(value, Path) and value.suffix == ".toml":
                assert os.path.isfile(value), f"{line}: {value} does not exist"
