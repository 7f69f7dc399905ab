"""Unit test: no function or method in src/onbottom is over 120 lines, numba kernels aside.

A function's length is from its ``def`` line to its last line (decorators excluded). A numba
kernel (decorated with ``onbottom._jit.njit`` / ``jitted_only`` / ``numba_njit`` or numba's own
``njit`` / ``jit``)
may be longer: a kernel cannot call Python stages. A long driver is split into named stages a
reader can follow (settings → setup → loop → result).
"""

from __future__ import annotations

import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2] / "src" / "onbottom"
MAX_LINES = 120
NUMBA_DECORATORS = {"njit", "jitted_only", "numba_njit", "jit"}


def _decorator_name(node: ast.expr) -> str:
    if isinstance(node, ast.Call):
        node = node.func
    if isinstance(node, ast.Attribute):
        return node.attr
    return node.id if isinstance(node, ast.Name) else ""


def _is_kernel(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    return any(_decorator_name(d) in NUMBA_DECORATORS for d in fn.decorator_list)


def _functions(path: pathlib.Path):
    """(qualified name, def line, length) of every function and method of ``path``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))

    def walk(node: ast.AST, prefix: str):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef):
                name = f"{prefix}{child.name}"
                if not _is_kernel(child):
                    yield name, child.lineno, child.end_lineno - child.lineno + 1
                yield from walk(child, f"{name}.")
            elif isinstance(child, ast.ClassDef):
                yield from walk(child, f"{prefix}{child.name}.")
            else:
                yield from walk(child, prefix)

    yield from walk(tree, "")


def _long_functions() -> dict[str, str]:
    found = {}
    for path in sorted(ROOT.rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        for name, line, length in _functions(path):
            if length > MAX_LINES:
                found[f"{rel}::{name}"] = f"src/onbottom/{rel}:{line} {name}: {length} lines"
    return found


def test_no_function_over_120_lines():
    offenders = [where for key, where in _long_functions().items()]
    assert not offenders, (
        f"functions over {MAX_LINES} lines (split them into named stages):\n" + "\n".join(offenders)
    )


def test_the_scan_measures_def_to_end_and_skips_kernels(tmp_path):
    body = "\n".join(f"    x{i} = {i}" for i in range(MAX_LINES))
    src = (
        f"def long():\n{body}\n\n"
        f"@njit(cache=True)\ndef kernel():\n{body}\n\n"
        f"@jitted_only\ndef callee():\n{body}\n\n"
        f"class C:\n    def short(self):\n        return 1\n"
    )
    path = tmp_path / "m.py"
    path.write_text(src, encoding="utf-8")
    got = {name: length for name, _, length in _functions(path)}
    assert got == {"long": MAX_LINES + 1, "C.short": 2}
