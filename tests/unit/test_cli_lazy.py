"""Unit test: the lazy command table of ``onbottom.cli.main`` matches the real commands.

``onbottom --help`` lists the commands from :data:`onbottom.cli.main.COMMANDS` without
importing their modules (issue 33 item 1); a command's module is imported when it runs. The
table must name every command module with the command's own name and short help.
"""

from __future__ import annotations

import ast
import importlib
import json
import pathlib
import subprocess
import sys

import click
import pytest
from click.testing import CliRunner

from onbottom.cli.main import COMMAND_MODULES, COMMANDS, cli, main

SRC = pathlib.Path(__file__).resolve().parents[2] / "src"
CLI = SRC / "onbottom" / "cli"


def _defines_command(path: pathlib.Path) -> bool:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and node.name == "command":
            return True
        if isinstance(node, ast.Assign) and any(
            isinstance(t, ast.Name) and t.id == "command" for t in node.targets
        ):
            return True
    return False


def test_every_command_module_is_in_the_table():
    modules = {p.stem for p in CLI.glob("*.py") if _defines_command(p)}
    assert modules == set(COMMAND_MODULES)
    assert len(COMMAND_MODULES) == len(set(COMMAND_MODULES))


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_table_entry_matches_the_command(name):
    module, short_help = COMMANDS[name]
    command = importlib.import_module(f"onbottom.cli.{module}").command
    assert isinstance(command, click.Command)
    assert command.name == name
    assert not command.hidden
    assert command.get_short_help_str(limit=10_000) == short_help


def _eager_group() -> click.Group:
    group = click.Group(name="onbottom", help=cli.help, context_settings=dict(cli.context_settings))
    group.params = list(cli.params)
    for module, _ in COMMANDS.values():
        group.add_command(importlib.import_module(f"onbottom.cli.{module}").command)
    return group


@pytest.mark.parametrize("width", [60, 80, 100, 200])
def test_help_lists_every_command_as_the_eager_group_would(width):
    """``--help`` from the table is the help an eagerly built group prints, at any width."""
    runner = CliRunner()
    lazy = runner.invoke(cli, ["--help"], terminal_width=width, prog_name="onbottom")
    eager = runner.invoke(_eager_group(), ["--help"], terminal_width=width, prog_name="onbottom")
    assert lazy.exit_code == 0 and eager.exit_code == 0
    assert lazy.output == eager.output
    for name in COMMANDS:
        assert f"\n  {name} " in lazy.output


def test_help_imports_no_command_module():
    probe = (
        "import sys\nfrom onbottom.cli.main import main\n"
        "code = main(['--help'])\nimport json\n"
        "print(json.dumps([code, sorted(m for m in sys.modules if m.startswith('onbottom.cli.'))"
        ", sorted(m for m in sys.modules if m.split('.')[0] in"
        " ('numpy', 'numba', 'scipy', 'xarray', 'dask', 'pandas', 'matplotlib'))]))"
    )
    proc = subprocess.run(
        [sys.executable, "-c", probe],
        capture_output=True,
        text=True,
        check=True,
        env={"PYTHONPATH": str(SRC), "PATH": ""},
    )
    code, cli_modules, heavy = json.loads(proc.stdout.strip().splitlines()[-1])
    assert code == 0
    assert cli_modules == ["onbottom.cli._common", "onbottom.cli.main"]
    assert heavy == []


def test_command_runs_and_unknown_command_is_a_usage_error(capsys):
    assert main(["backbone", "--help"]) == 0
    assert "Usage: onbottom backbone" in capsys.readouterr().out
    assert main(["no-such-command"]) == 2
    assert "No such command" in capsys.readouterr().err
    # a subcommand of a group command resolves through the lazy group
    assert main(["dem", "--help"]) == 0
    assert "Commands:" in capsys.readouterr().out


def test_compile_notice_says_once_and_sums_the_outermost_compiles():
    import io

    from onbottom.cli.main import CompileNotice

    stream = io.StringIO()
    notice = CompileNotice(stream)
    assert notice.summary() is None
    for _ in range(2):  # two top-level compiles, the first with a nested one
        notice.on_start(None)
        notice.on_start(None)
        notice.on_end(None)
        notice.on_end(None)
    assert stream.getvalue().count("\n") == 1
    assert "compiling the numba kernels" in stream.getvalue()
    assert notice.summary().startswith("onbottom: compiled 4 kernel specialisations in ")


def test_compile_notice_hears_numba_once_it_is_imported():
    """The import watch registers the notice when numba loads, then leaves sys.meta_path."""
    probe = (
        "import io, sys\n"
        "from onbottom.cli.main import CompileNotice, _NumbaWatch\n"
        "notice = CompileNotice(io.StringIO())\n"
        "watch = _NumbaWatch(notice)\n"
        "sys.meta_path.insert(0, watch)\n"
        "import numba\n"
        "assert watch not in sys.meta_path\n"
        "f = numba.njit(lambda x: x + 1.0)\n"
        "f(1.0)\n"
        "print(notice.count, 'compiling' in notice.stream.getvalue())\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", probe],
        capture_output=True,
        text=True,
        check=True,
        env={"PYTHONPATH": str(SRC), "PATH": "", "NUMBA_DISABLE_JIT": "0"},
    )
    assert proc.stdout.split() == ["1", "True"]
