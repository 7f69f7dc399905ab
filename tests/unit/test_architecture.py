"""Unit test: the package layering of docs/architecture.md holds (no upward imports).

Parses every module's imports (static, so lazy imports inside functions count too) and checks
each subpackage against the dependencies the architecture allows.
"""

from __future__ import annotations

import ast
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2] / "src" / "onbottom"
BASE = {"_version", "errors", "constants", "_validate", "_casefile", "results", "_lazy", "_roots"}

ALLOWED: dict[str, set[str]] = {
    "_version": set(),
    "_lazy": set(),
    "_roots": set(),
    "errors": set(),
    "constants": set(),
    "_validate": {"errors"},
    "_casefile": {"errors"},
    "results": {"_version", "errors"},
    "inputs": BASE,
    "hydro": BASE | {"inputs"},
    "soil": BASE | {"inputs"},
    "checks": BASE | {"inputs", "hydro", "soil"},
    "dynamics": BASE | {"inputs", "hydro", "soil"},
    "dem": BASE,  # never soil/ or hydro/
    "metocean": BASE | {"inputs"},  # hindcast statistics: no physics of the pipe
    # reliability: estimators, the storm campaign (dynamics, study, metocean)
    "reliability": BASE | {"inputs", "hydro", "soil", "checks", "dynamics", "study", "metocean"},
    "study": BASE | {"inputs", "hydro", "soil", "dynamics", "checks"},
    "calibration": BASE | {"inputs", "hydro", "soil", "dynamics", "study"},
    # peers: other programs (OpenSees) solving onbottom's problems, for standing comparisons
    "peers": BASE | {"inputs", "hydro", "soil", "dynamics"},
    # assess: a route through every F109 level (onbottom assess); its report draws with plotting/
    "assess": BASE | {"inputs", "hydro", "soil", "checks", "dynamics", "study", "plotting"},
    "plotting": BASE
    | {"inputs", "hydro", "soil", "dynamics", "dem", "calibration", "study", "metocean"}
    | {"reliability"},
    # report draws its figures with plotting/ and reports the checks/ of the design cases
    "report": BASE
    | {"inputs", "hydro", "soil", "checks", "dynamics", "dem", "calibration", "study"}
    | {"plotting", "metocean", "reliability"},
    "cli": BASE
    | {"inputs", "hydro", "soil", "checks", "dynamics", "dem", "calibration", "study"}
    | {"plotting", "report", "metocean", "reliability", "assess"},
}


def _imports(path: pathlib.Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: set[str] = set()
    for node in ast.walk(tree):
        names: list[str] = []
        if isinstance(node, ast.ImportFrom) and node.module:
            names.append(node.module)
        elif isinstance(node, ast.Import):
            names.extend(a.name for a in node.names)
        for name in names:
            parts = name.split(".")
            if parts[0] == "onbottom" and len(parts) > 1:
                found.add(parts[1])
    return found


def _package_of(path: pathlib.Path) -> str:
    rel = path.relative_to(ROOT)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


MODULES = sorted(p for p in ROOT.rglob("*.py") if _package_of(p) not in {"__init__", "__main__"})


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_module_imports_only_lower_layers(path):
    pkg = _package_of(path)
    assert pkg in ALLOWED, f"{pkg} is not in the architecture table: add it to docs and here"
    upward = _imports(path) - ALLOWED[pkg] - {pkg}
    assert not upward, f"{path.relative_to(ROOT)} imports {sorted(upward)} (not allowed for {pkg})"
