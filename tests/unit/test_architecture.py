"""Unit test: the package layering of docs/architecture.md holds (no upward imports).

Parses every module's imports (static, so lazy imports inside functions count too) and checks
each subpackage against the dependencies the architecture allows.
"""

from __future__ import annotations

import ast
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2] / "src" / "onbottom"
BASE = {
    "_version", "errors", "constants", "_validate", "_casefile", "results", "_lazy", "_roots",
    "_jit", "registry",
}  # fmt: skip

ALLOWED: dict[str, set[str]] = {
    "_version": set(),
    "_lazy": set(),
    "_roots": set(),
    "_jit": {"_version"},
    "errors": set(),
    "constants": set(),
    "_validate": {"errors"},
    "_casefile": {"errors"},
    "registry": {"errors"},
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
    # cases: every case-file schema and case -> model builder, just below the command line
    "cases": BASE
    | {"inputs", "hydro", "soil", "checks", "dynamics", "dem", "calibration", "study"}
    | {"plotting", "metocean", "reliability", "assess", "peers"},
    "cli": BASE
    | {"inputs", "hydro", "soil", "checks", "dynamics", "dem", "calibration", "study"}
    | {"plotting", "report", "metocean", "reliability", "assess", "cases"},
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


# ---- no private name is imported across packages ---------------------------------------------
# A private module or name (leading underscore) may be imported within its own top-level
# package (dynamics/pipeline/ may import dynamics/_x), and the base modules of BASE (_validate,
# _casefile, _lazy, _version, _roots, _jit) are imported by every package as modules — but a private
# *name* of another package or base module is not. Exceptions, each with its reason:
PRIVATE_MODULES_ALLOWED: dict[tuple[str, str], str] = {
    # (package, module): reason — none today. The kernel contracts that numba kernels of another
    # package call by static dispatch are public modules (issue 29): soil.kernel_contract,
    # hydro.kernel_contract, dynamics.pipeline.node_layout; the twin decorator is in _jit.
}
PRIVATE_NAMES_ALLOWED: dict[tuple[str, str, str], str] = {
    # (package, module, name): reason — none today (the assess entries went with issue 29
    # item 5: Checker, find_line, atomic_write, format_value and minimum_passing are public)
}
_BASE_PRIVATE = {m for m in BASE if m.startswith("_")}


def _private_imports(path: pathlib.Path) -> list[tuple[str, str | None]]:
    """(module, name) of every import of a private module or name of another package."""
    pkg = _package_of(path)
    found: list[tuple[str, str | None]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module:
            pairs = [(node.module, a.name) for a in node.names]
        elif isinstance(node, ast.Import):
            pairs = [(a.name, None) for a in node.names]
        else:
            continue
        for module, name in pairs:
            parts = module.split(".")
            if parts[0] != "onbottom":
                continue
            if len(parts) == 1:  # from onbottom import x: x is a module or a name
                if name and name.startswith("_") and name not in _BASE_PRIVATE and name != pkg:
                    found.append((module, name))
                continue
            if parts[1] == pkg:
                continue
            if any(p.startswith("_") for p in parts[2:]) or (
                parts[1].startswith("_") and parts[1] not in _BASE_PRIVATE
            ):
                found.append((module, None))
            if name and name.startswith("_") and not name.startswith("__"):
                sub = ROOT.joinpath(*parts[1:], name)
                if sub.with_suffix(".py").is_file() or sub.is_dir():  # a private module
                    found.append((f"{module}.{name}", None))
                else:
                    found.append((module, name))
    return found


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_private_name_imported_across_packages(path):
    pkg = _package_of(path)
    bad = []
    for module, name in _private_imports(path):
        if name is None and (pkg, module) in PRIVATE_MODULES_ALLOWED:
            continue
        if name is not None and (pkg, module, name) in PRIVATE_NAMES_ALLOWED:
            continue
        if name is not None and (pkg, module) in PRIVATE_MODULES_ALLOWED:
            continue  # a name of an allowed kernel module (e.g. `from ..pipeline import _x`)
        bad.append(f"{module}" + (f".{name}" if name else ""))
    assert not bad, (
        f"{path.relative_to(ROOT)} ({pkg}) imports private {bad}: make it public, or add it to"
        " the allow-list with its reason"
    )


def test_private_allow_list_is_still_needed():
    used = {(_package_of(p), m, n) for p in MODULES for m, n in _private_imports(p)}
    stale_mod = [k for k in PRIVATE_MODULES_ALLOWED if not any(u[:2] == k for u in used)]
    assert not stale_mod, f"allow-list entries no longer used: {stale_mod}"
    stale_names = [k for k in PRIVATE_NAMES_ALLOWED if k not in used]
    assert not stale_names, f"allow-list entries no longer used: {stale_names}"


# ---- only cases/ and cli/ read case files ------------------------------------------------------
# A case file is parsed through onbottom._casefile (strict schemas, file and line in errors) or
# read with tomllib; issue 29 item 5 puts every schema and case -> model builder in cases/, so
# the library's API takes built objects and no other package reads a case file.
CASE_READERS = {"cases", "cli", "_casefile"}


def _reads_case_files(path: pathlib.Path) -> list[str]:
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module:
            if node.module in {"onbottom._casefile", "tomllib"}:
                found.append(node.module)
            elif node.module == "onbottom" and any(a.name == "_casefile" for a in node.names):
                found.append("onbottom._casefile")
        elif isinstance(node, ast.Import):
            found += [a.name for a in node.names if a.name in {"onbottom._casefile", "tomllib"}]
    return found


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_only_cases_and_cli_read_case_files(path):
    pkg = _package_of(path)
    if pkg in CASE_READERS:
        return
    found = _reads_case_files(path)
    assert not found, (
        f"{path.relative_to(ROOT)} ({pkg}) reads case files ({sorted(set(found))}): the schema"
        " and its builder belong in onbottom.cases, the API takes the built objects"
    )
