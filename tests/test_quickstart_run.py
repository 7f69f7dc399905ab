"""Every command of the quick start runs, from a folder of its own, and leaves the repository
clean (docs/quickstart.md: "from a folder of your own holding a link to examples/").

The page's command lines (code blocks and inline code, as :mod:`tests.unit.test_quickstart_commands`
reads them) run in page order in one temporary folder with a link to the repository's
``examples/``, through a shell (the page's redirections work); each must exit 0. The
repository's ``git status`` is the same before and after. Long: minutes of storms."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_quickstart_commands import _run_lines  # noqa: E402

LINES = _run_lines()

pytestmark = pytest.mark.long


def _status() -> str:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        return ""
    return subprocess.run(["git", "status", "--porcelain"], cwd=ROOT, capture_output=True,
                          text=True, check=False).stdout  # fmt: skip


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    before = _status()
    d = tmp_path_factory.mktemp("quickstart")
    (d / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    yield d
    assert _status() == before, "the quick start's commands changed the repository"


@pytest.mark.parametrize("line", LINES)
def test_quickstart_command_runs(line, folder):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), env.get("PYTHONPATH", "")])
    r = subprocess.run(line, shell=True, cwd=folder, env=env, capture_output=True, text=True,
                       timeout=1800, check=False)  # fmt: skip
    assert r.returncode == 0, f"{line}\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}"
