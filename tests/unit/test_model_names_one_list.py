"""Unit test: the registries are the one list of model names.

No module outside the registries writes a list of registered soil or force model names (a
tuple, list or set literal, or a ``Literal[...]`` type, holding two or more of them): case
files, the CLI and the docs read the names from :data:`onbottom.soil.registry.SOIL_MODELS`
and :data:`onbottom.hydro.registry.FORCE_REGISTRY`. A single name (a default, a branch on one
model) is not a list.
"""

from __future__ import annotations

import ast
from pathlib import Path

from onbottom.hydro.registry import FORCE_REGISTRY
from onbottom.soil.factory import LATERAL_MODELS
from onbottom.soil.registry import SOIL_MODELS

SRC = Path(__file__).resolve().parents[2] / "src" / "onbottom"
REGISTRIES = {"soil/registry.py", "hydro/registry.py"}
ALLOWED = {
    # the warm-up's targets: which models `onbottom warmup` compiles, a choice, not the list
    ("study/warmup.py", ("morison", "wake")),
}


def _lists(tree: ast.AST, names: set[str]):
    for node in ast.walk(tree):
        elts = None
        if isinstance(node, ast.Tuple | ast.List | ast.Set):
            elts = node.elts
        elif isinstance(node, ast.Subscript) and getattr(node.value, "id", None) == "Literal":
            elts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        found = tuple(
            e.value for e in elts or () if isinstance(e, ast.Constant) and e.value in names
        )
        if len(found) >= 2:
            yield node.lineno, found


def test_no_list_of_model_names_outside_the_registries():
    names = set(SOIL_MODELS.names()) | set(FORCE_REGISTRY.names())
    found = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        if rel in REGISTRIES:
            continue
        for line, group in _lists(ast.parse(path.read_text(encoding="utf-8")), names):
            if (rel, group) not in ALLOWED:
                found.append(f"{rel}:{line} {group}")
    assert not found, "model names listed outside the registries:\n" + "\n".join(found)


def test_a_model_registered_later_is_in_every_view():
    from onbottom.soil.coulomb import CoulombFriction
    from onbottom.soil.registry import register_soil_model

    entry = register_soil_model("later_model", CoulombFriction, description="test")
    try:
        assert "later_model" in LATERAL_MODELS  # a live view, not a snapshot
        assert "later_model" in SOIL_MODELS.table()
    finally:
        del SOIL_MODELS[entry.name]
