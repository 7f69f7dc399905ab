"""Unit tests: the CLI entry point (in-process)."""

from __future__ import annotations

import subprocess
import sys

from onbottom.cli.main import main


def test_help_and_version(capsys):
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    assert "onbottom" in out and "--json" in out
    assert main(["--version"]) == 0


def test_unknown_command_is_a_usage_error(capsys):
    assert main(["no-such-command"]) == 2


def test_python_dash_m_entry_point():
    proc = subprocess.run(
        [sys.executable, "-m", "onbottom", "--help"], capture_output=True, text=True, check=False
    )
    assert proc.returncode == 0, proc.stderr
    assert "Usage" in proc.stdout
