"""An installed wheel behaves like the checkout (issue 41 item 2).

Builds a wheel of the package (from a copy of the source tree, so the checkout gets no
``build/`` folder), installs it into a fresh virtual environment outside the checkout (system
site-packages for the dependencies; the checkout's ``src`` not on the path), and runs the main
job, ``onbottom assess`` on the embedded route (one seed per evaluation), there and from the
checkout. The installed package must hold every file of the checkout's package (equal content
hashes: the package data is complete) and give the same ``results.json``: the same design per
section and level, the same checks and the same dynamic results.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import onbottom
from onbottom._version import content_hash, package_files

pytestmark = pytest.mark.long

SRC = Path(onbottom.__file__).resolve().parent
REPO = SRC.parent.parent
ASSESS = ["assess", "--seeds", "1", "--workers", "0", "--no-pdf", "--quiet"]


def _run(cmd: list[str], *, env: dict[str, str], cwd: Path, timeout: float = 1200):
    out = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    assert out.returncode == 0, f"{' '.join(cmd)}\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}"
    return out


def _comparable(doc: dict, places: dict[str, str]) -> dict:
    """What a run computed (not when, where or how long): summary, sections' checks, levels
    and dynamic results, the comparison, the pipeline; the run's own folders and the
    package's folder (in file names) replaced by ``places``' names."""
    drop = {"wall_time_s", "cpu_time_s", "identity", "identity_parts", "checksum"}

    def keep(x):  # the run's own timings and identities dropped at every depth
        if isinstance(x, dict):
            return {k: keep(v) for k, v in x.items() if k not in drop}
        if isinstance(x, list):
            return [keep(v) for v in x]
        return x

    text = json.dumps(
        keep(
            {
                "summary": doc["summary"],
                "sections": doc["sections"],
                "comparison": doc["comparison"],
                "pipeline": doc.get("pipeline") or {},
            }
        )
    )
    for path, name in sorted(places.items(), key=lambda kv: -len(kv[0])):
        text = text.replace(path, name)
    return json.loads(text)


def _differences(a, b, path: str = "") -> list[str]:
    if isinstance(a, dict) and isinstance(b, dict):
        out = [f"{path}/{k}: in one only" for k in sorted(set(a) ^ set(b))]
        for k in sorted(set(a) & set(b)):
            out += _differences(a[k], b[k], f"{path}/{k}")
        return out
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for i, (x, y) in enumerate(zip(a, b, strict=True)) for d in
                _differences(x, y, f"{path}[{i}]")]  # fmt: skip
    return [] if a == b else [f"{path}: {str(a)[:120]} != {str(b)[:120]}"]


def test_wheel_in_a_fresh_venv_gives_the_checkouts_results(tmp_path):
    checkout_hash = content_hash()  # of the tree copied below
    tree = tmp_path / "tree"
    tree.mkdir()
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        if (REPO / name).is_file():
            shutil.copy2(REPO / name, tree / name)
    shutil.copytree(
        SRC,
        tree / "src" / "onbottom",
        ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "*.nbi", "*.nbc", "*.tmp"),
    )
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    wheels = tmp_path / "wheels"
    _run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(wheels), str(tree)],
        env=env,
        cwd=tmp_path,
    )
    (wheel,) = wheels.glob("onbottom-*.whl")
    venv = tmp_path / "venv"
    _run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], env=env, cwd=tmp_path)
    py = venv / "bin" / "python"
    _run(
        [str(py), "-m", "pip", "install", "-q", "--no-deps", "--force-reinstall", str(wheel)],
        env=env,
        cwd=tmp_path,
    )
    probe = _run(
        [str(py), "-c", "import onbottom, onbottom._version as v; print(onbottom.__file__);"
         " print(v.content_hash())"],
        env=env,
        cwd=tmp_path,
    ).stdout.split()  # fmt: skip
    installed, installed_hash = Path(probe[0]).resolve(), probe[1]
    assert venv.resolve() in installed.parents, installed  # not the checkout's src
    assert REPO not in installed.parents
    # every file of the checkout's package (sources, data, templates) is in the wheel
    missing = sorted(set(package_files(SRC)) - set(package_files(installed.parent)))
    assert not missing, f"not in the wheel: {missing}"
    assert installed_hash == checkout_hash

    wheel_out, edit_out = tmp_path / "wheel_out", tmp_path / "edit_out"
    _run([str(py), "-m", "onbottom", *ASSESS, "--out", str(wheel_out)], env=env, cwd=tmp_path)
    env_edit = {**env, "PYTHONPATH": str(SRC.parent)}
    _run(
        [sys.executable, "-m", "onbottom", *ASSESS, "--out", str(edit_out)],
        env=env_edit,
        cwd=tmp_path,
    )
    a = json.loads((wheel_out / "results.json").read_text(encoding="utf-8"))
    b = json.loads((edit_out / "results.json").read_text(encoding="utf-8"))
    assert a["provenance"]["onbottom_content_hash"] == b["provenance"]["onbottom_content_hash"]
    assert a["summary"] == b["summary"]
    ca = _comparable(a, {str(wheel_out): "<out>", str(installed.parent): "<package>"})
    cb = _comparable(b, {str(edit_out): "<out>", str(SRC): "<package>"})
    diffs = _differences(ca, cb)
    assert not diffs, "\n".join(diffs[:20])
