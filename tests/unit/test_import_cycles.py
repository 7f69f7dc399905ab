"""No import cycle between modules of the same package of ``onbottom``.

The graph is built statically with :mod:`ast` from every ``import`` / ``from ... import``
in ``src/onbottom``, at module level and inside functions alike (a deferred import is still a
dependency a reader has to follow). An edge ``a -> b`` is kept when ``a`` and ``b`` are modules of
the same package (same parent folder); a cycle among them is a circle inside a folder.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
PACKAGE = "onbottom"

# Cycles that remain, each with its reason (keep this list minimal).
KNOWN_CYCLES: dict[frozenset[str], str] = {}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in (SRC / PACKAGE).rglob("*.py")}


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    if node.level > 1:
        base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports(module: str, path: Path, known: set[str]) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    is_package = path.name == "__init__.py"
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(module, is_package, node)
            # ``from pkg import mod`` imports the module ``pkg.mod`` when there is one
            targets = [
                f"{base}.{alias.name}" if f"{base}.{alias.name}" in known else base
                for alias in node.names
            ]
        else:
            continue
        for target in targets:
            while target and target not in known:
                target = target.rpartition(".")[0]
            if target and target != module:
                found.add(target)
    return found


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    known = set(modules)
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        parent = name.rpartition(".")[0]
        graph[name] = {
            t
            for t in _imports(name, path, known)
            # same folder: siblings, not the package's own __init__ (a parent) nor subpackages
            if t.rpartition(".")[0] == parent and t != parent
        }
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_graph_sees_imports() -> None:
    graph = _graph()
    assert "onbottom.cases.storm" in graph
    assert "onbottom.cases.tables" in graph["onbottom.cases.storm"]


def test_no_import_cycle_within_a_package() -> None:
    cycles = [c for c in _cycles(_graph()) if frozenset(c) not in KNOWN_CYCLES]
    assert not cycles, "import cycles inside a package: " + "; ".join(
        " <-> ".join(c) for c in cycles
    )


def test_known_cycles_still_exist() -> None:
    present = {frozenset(c) for c in _cycles(_graph())}
    stale = [sorted(c) for c in KNOWN_CYCLES if c not in present]
    assert not stale, f"known cycles no longer present, remove them from the list: {stale}"
