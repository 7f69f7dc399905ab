"""Unit test: the import table of docs/architecture.md is the code's, both ways.

The table ("## Import table": package or base module → what it imports) is parsed from the
markdown. Every module's imports (static, so lazy imports inside functions count too) must be
listed for its package, every listed entry must be used by some module of that package (the doc
cannot overstate), the table has no circle (nothing lower imports anything higher), and the
"depends on" column of the package table says the same as the import table.
"""

from __future__ import annotations

import ast
import pathlib
import re

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
ROOT = REPO / "src" / "onbottom"
DOC = REPO / "docs" / "architecture.md"
TOP = "onbottom"  # the package's own __init__.py (its lazy exports)

BASE_PACKAGES = frozenset({"results"})  # base modules that grew into packages of their own
BASE = (
    frozenset(p.stem for p in ROOT.glob("*.py") if p.stem not in {"__init__", "__main__"})
    | BASE_PACKAGES
)  # the base modules: every top-level module of the package, and the base packages
PACKAGES = frozenset(p.name for p in ROOT.iterdir() if (p / "__init__.py").is_file())


def _table_rows(text: str, heading: str) -> list[list[str]]:
    """The cells of the first markdown table after ``heading`` (header and rule dropped)."""
    lines = text.splitlines()
    i = lines.index(heading)
    rows: list[list[str]] = []
    for line in lines[i + 1 :]:
        if line.startswith("#"):
            break
        if line.startswith("|"):
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
        elif rows:
            break
    return rows[2:]


def _names(cell: str) -> set[str]:
    return set(re.findall(r"`([^`]+)`", cell))


def _import_table() -> dict[str, set[str]]:
    table: dict[str, set[str]] = {}
    for row in _table_rows(DOC.read_text(encoding="utf-8"), "## Import table"):
        (name,) = _names(row[0])
        assert name not in table, f"{name} has two rows in the import table"
        table[name] = _names(row[1]) if row[1] != "—" else set()
    return table


TABLE = _import_table()


def _unit_of(name: str) -> str:
    """The table row a top-level name belongs to (a package, a base module, or the top)."""
    return TOP if name == "__init__" else name


def _imports(path: pathlib.Path) -> dict[str, int]:
    """Top-level onbottom units imported by ``path`` → the first line importing each."""
    found: dict[str, int] = {}
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        names: list[str] = []
        if isinstance(node, ast.ImportFrom):
            assert node.level == 0, f"{path}:{node.lineno}: relative import (use onbottom.x)"
            parts = (node.module or "").split(".")
            if parts[0] != "onbottom":
                continue
            if len(parts) > 1:
                names.append(parts[1])
            else:  # from onbottom import x: a module, a subpackage or an export of the top
                for a in node.names:
                    names.append(a.name if a.name in BASE | PACKAGES else TOP)
        elif isinstance(node, ast.Import):
            for a in node.names:
                parts = a.name.split(".")
                if parts[0] == "onbottom":
                    names.append(parts[1] if len(parts) > 1 else TOP)
        for name in names:
            found.setdefault(name, node.lineno)
    return found


def _package_of(path: pathlib.Path) -> str:
    rel = path.relative_to(ROOT)
    return rel.parts[0] if len(rel.parts) > 1 else _unit_of(rel.stem)


MODULES = sorted(ROOT.rglob("*.py"))


def _expand(unit: str, entries: set[str]) -> set[str]:
    """What a row allows: ``base`` is any base module (never for a base module's own row)."""
    return (entries - {"base"}) | (BASE if "base" in entries and unit not in BASE else set())


def test_every_package_and_base_module_has_one_row():
    units = set(BASE) | set(PACKAGES) | {TOP, "__main__"}
    assert set(TABLE) == units, (
        f"rows missing: {sorted(units - set(TABLE))}; rows of nothing: "
        f"{sorted(set(TABLE) - units)} (docs/architecture.md, Import table)"
    )
    for unit, entries in TABLE.items():
        unknown = entries - units - {"base"}
        assert not unknown, f"{unit}: {sorted(unknown)} is no package or base module"
        if unit in BASE:
            assert entries <= BASE, f"base module {unit} imports a package: {entries - BASE}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_module_imports_are_in_the_table(path):
    unit = _package_of(path)
    allowed = _expand(unit, TABLE.get(unit, set()))
    extra = {n: line for n, line in _imports(path).items() if n != unit and n not in allowed}
    where = ", ".join(f"{n} (line {line})" for n, line in sorted(extra.items()))
    assert not extra, (
        f"{path.relative_to(ROOT)} imports {where}: not in the row of {unit} of the import"
        " table in docs/architecture.md (add it there if the layering allows it)"
    )


def test_no_table_entry_overstates():
    used: dict[str, set[str]] = {}
    for path in MODULES:
        unit = _package_of(path)
        used.setdefault(unit, set()).update(n for n in _imports(path) if n != unit)
    stale = []
    for unit, entries in TABLE.items():
        got = used.get(unit, set())
        for entry in sorted(entries):
            ok = bool(got & (BASE - {unit})) if entry == "base" else entry in got
            if not ok:
                stale.append(f"{unit} → {entry}")
    assert not stale, f"docs/architecture.md's import table lists imports no module makes: {stale}"


def test_the_table_has_no_circle():
    graph = {u: _expand(u, e) - {u} for u, e in TABLE.items()}
    done: set[str] = set()

    def visit(u: str, path: tuple[str, ...]) -> None:
        if u in path:
            raise AssertionError("import circle: " + " → ".join((*path[path.index(u) :], u)))
        if u in done:
            return
        for v in sorted(graph.get(u, ())):
            visit(v, (*path, u))
        done.add(u)

    for u in sorted(graph):
        visit(u, ())


def test_package_table_depends_on_says_the_same():
    """The "depends on" column of the package table names the packages of the import table."""
    rows = _table_rows(DOC.read_text(encoding="utf-8"), "# Architecture")
    checked = 0
    for row in rows:
        names = _names(row[0])
        if len(names) != 1:
            continue  # the base row
        unit = next(iter(names)).rstrip("/")
        if unit not in PACKAGES:
            continue
        said = {n.rstrip("/") for n in _names(row[-1])} & PACKAGES
        assert said == TABLE[unit] & PACKAGES, (
            f"docs/architecture.md: {unit}'s depends-on says {sorted(said)}, the import table"
            f" {sorted(TABLE[unit] & PACKAGES)}"
        )
        checked += 1
    assert checked == len(PACKAGES - BASE_PACKAGES)


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
