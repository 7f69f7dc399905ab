"""Unit test: the packages export their names lazily and ``import onbottom`` stays light.

Issue 33 item 1: ``import onbottom`` (and every ``import onbottom.<pkg>.<module>``, which runs
the package ``__init__`` first) must not load numba, scipy, xarray or dask; the names of each
``__all__`` still resolve (``from onbottom.soil import VerleySotberg``), and each package's
lazy table, its ``__all__`` and its ``TYPE_CHECKING`` imports (read by type checkers,
mkdocstrings and ``test_architecture.py``) name the same things.
"""

from __future__ import annotations

import ast
import importlib
import json
import pathlib
import subprocess
import sys

import pytest

from onbottom._lazy import lazy_table

SRC = pathlib.Path(__file__).resolve().parents[2] / "src"
ROOT = SRC / "onbottom"
HEAVY = ("numba", "scipy", "xarray", "dask", "pandas", "matplotlib")

PACKAGES = sorted(
    ".".join(p.relative_to(SRC).parent.parts)
    for p in ROOT.rglob("__init__.py")
    if "_lazy" in p.read_text(encoding="utf-8")
)


def _loaded_after(code: str) -> list[str]:
    """Top-level names of the modules loaded by ``code`` in a fresh interpreter."""
    probe = f"{code}\nimport json, sys\nprint(json.dumps(sorted(sys.modules)))"
    proc = subprocess.run(
        [sys.executable, "-c", probe],
        capture_output=True,
        text=True,
        check=True,
        env={"PYTHONPATH": str(SRC), "PATH": ""},
    )
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _heavy(modules: list[str]) -> list[str]:
    return sorted({m.split(".")[0] for m in modules} & set(HEAVY))


def test_packages_found():
    assert "onbottom" in PACKAGES and "onbottom.soil" in PACKAGES
    assert len(PACKAGES) >= 10


def test_import_onbottom_loads_no_heavy_library():
    loaded = _loaded_after("import onbottom")
    assert _heavy(loaded) == []


def test_import_of_every_package_loads_no_heavy_library():
    loaded = _loaded_after("\n".join(f"import {pkg}" for pkg in PACKAGES))
    assert _heavy(loaded) == []
    # and no submodule beyond those the packages' own __init__ needs
    assert "onbottom.soil.penetration_f114" not in loaded
    assert "onbottom.dynamics.section" not in loaded


def test_stability_command_loads_no_scipy_or_solver_library():
    """``onbottom stability`` (checks and the design solve) needs neither scipy nor xarray.

    numba still loads: the V&S and V&L formulas live beside their kernels (the checks call
    the plain-Python ``py_func`` of the kernel helpers, nothing is compiled).
    """
    case = SRC.parent / "examples" / "stability_case.toml"
    loaded = _loaded_after(
        "from onbottom.cli.main import main\n"
        f"assert main(['stability', {str(case)!r}, '--json']) == 0"
    )
    assert set(_heavy(loaded)) <= {"numba", "scipy"}  # numba imports the scipy package itself
    assert not [m for m in loaded if m.startswith(("scipy.optimize", "scipy.linalg"))]


def test_lazy_name_loads_its_module_only_when_used():
    loaded = _loaded_after("import onbottom\nonbottom.Storm")
    assert "onbottom.inputs.storm" in loaded
    assert _heavy(loaded) == []


@pytest.mark.parametrize("package", PACKAGES)
def test_every_name_in_all_resolves(package):
    mod = importlib.import_module(package)
    assert len(mod.__all__) == len(set(mod.__all__)), "duplicate names in __all__"
    for name in mod.__all__:
        value = getattr(mod, name)
        assert value is not None, f"{package}.{name}"
    assert set(mod.__all__) <= set(dir(mod))


@pytest.mark.parametrize("package", PACKAGES)
def test_lazy_table_matches_all(package):
    mod = importlib.import_module(package)
    table = lazy_table(package)
    assert table, f"{package} has no lazy table"
    eager = set(mod.__all__) - set(table)
    if package == "onbottom":  # the version, the errors and the inputs load at once (light)
        assert eager == {
            "__version__",
            "InputError",
            "OnbottomError",
            "OutOfRangeWarning",
            "SolutionError",
            "Clay",
            "Layer",
            "Pipe",
            "Rock",
            "Sand",
        }
    else:
        assert eager == set(), f"{package}: names in __all__ without a lazy entry"
    assert set(table) <= set(mod.__all__), f"{package}: lazy names missing from __all__"
    for name, module in table.items():
        assert module.startswith(package + ".") or package == "onbottom", (name, module)
        assert getattr(importlib.import_module(module), name) is getattr(mod, name)


@pytest.mark.parametrize("package", [p for p in PACKAGES if p != "onbottom"])
def test_type_checking_imports_match_lazy_table(package):
    """The ``if TYPE_CHECKING:`` imports name exactly the lazy table (static tools read them)."""
    path = SRC.joinpath(*package.split(".")) / "__init__.py"
    tree = ast.parse(path.read_text(encoding="utf-8"))
    static: dict[str, str] = {}
    for node in tree.body:
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING":
            for imp in node.body:
                assert isinstance(imp, ast.ImportFrom) and imp.module
                for alias in imp.names:
                    static[alias.asname or alias.name] = imp.module
    assert static == lazy_table(package)


def test_unknown_name_raises_attribute_error():
    import onbottom.soil

    with pytest.raises(AttributeError, match="no attribute 'NoSuchModel'"):
        onbottom.soil.NoSuchModel
    assert not hasattr(onbottom.soil, "NoSuchModel")


def test_from_import_of_lazy_names():
    from onbottom import Storm, VerleySotberg
    from onbottom.dynamics.pipeline import simulate_pipeline
    from onbottom.soil import VerleySotberg as VS

    assert VS is VerleySotberg
    assert Storm.__module__ == "onbottom.inputs.storm"
    assert simulate_pipeline.__module__ == "onbottom.dynamics.pipeline.solver"
