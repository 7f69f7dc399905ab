"""One name per thing (docs/contributing.md, "Names of readers and builders"; docs/conventions.md,
"One name per quantity"): the readers and builders of case files follow one rule, two classes
never share the name ``PipelineSettings`` (nor any other name), and ``soil/`` writes ``y`` for
the lateral displacement (never ``u``)."""

from __future__ import annotations

import ast
import importlib
import inspect
import io
import pkgutil
import re
import sys
import tokenize
from pathlib import Path

import pytest

import onbottom.cases
import onbottom.soil

READER_MODULES = [
    "onbottom._casefile",
    "onbottom.results",
    "onbottom.calibration.records",
    *(f"onbottom.cases.{m.name}" for m in pkgutil.iter_modules(onbottom.cases.__path__)),
]


def _readers_and_builders():
    for name in READER_MODULES:
        mod = importlib.import_module(name)
        for fname, fn in vars(mod).items():
            if (
                inspect.isfunction(fn)
                and fn.__module__ == name
                and re.match(r"(load|build)_", fname)
            ):
                yield pytest.param(fn, id=f"{name}.{fname}")


def _words(camel: str) -> list[str]:
    return [w.lower() for w in re.findall(r"[A-Z]+(?![a-z])|[A-Z][a-z]*", camel)]


@pytest.mark.parametrize("fn", list(_readers_and_builders()))
def test_reader_or_builder_returns_what_it_names(fn):
    """``load_<what>`` / ``build_<what>`` return ``<what>`` (a ``*Case`` document for
    ``load_<kind>_case``), never a bare dict."""
    ret = fn.__annotations__.get("return")
    assert ret is not None, f"{fn.__name__} has no return annotation"
    ret = ret if isinstance(ret, str) else getattr(ret, "__name__", str(ret))
    assert not re.match(r"(dict|Mapping|typing\.Mapping|collections\.abc\.Mapping)\b", ret), (
        f"{fn.__name__} returns a bare dict ({ret}): return a named type"
    )
    if ret in ("Any", "M"):
        return  # a lazily imported type, or load_case_file's schema parameter
    what = fn.__name__.split("_")[-1]  # the last word: case, route, setup, run...
    assert what in _words(ret.split(".")[-1]), (
        f"{fn.__name__} returns {ret}: its name does not say so"
    )


def test_one_pipeline_settings_class():
    """The solver's settings own the name; the route's FE settings have their own."""
    from onbottom.assess.route import PipelineFESettings
    from onbottom.dynamics.pipeline import PipelineSettings

    assert PipelineSettings.__module__ == "onbottom.dynamics.pipeline.solver"
    assert PipelineFESettings is not PipelineSettings
    src = Path(onbottom.__file__).parent
    defs = [
        str(p.relative_to(src))
        for p in src.rglob("*.py")
        if re.search(r"^class PipelineSettings\b", p.read_text(encoding="utf-8"), re.M)
    ]
    assert defs == [str(Path("dynamics/pipeline/solver.py"))]


# Pairs not yet renamed, each with why: the entry names the class and the one file whose
# definition is to be renamed.
_SHARED_CLASS_NAMES: dict[tuple[str, str], str] = {}


def test_no_class_name_is_defined_twice():
    """Two classes of one name are a reader's trap (which ``DesignTable`` is this?): every
    class name of ``src/onbottom`` (private ones included) is defined once, but for the
    justified pairs of :data:`_SHARED_CLASS_NAMES`."""
    src = Path(onbottom.__file__).parent
    where: dict[str, list[str]] = {}
    for path in sorted(src.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ClassDef):
                where.setdefault(node.name, []).append(path.relative_to(src).as_posix())
    allowed = {name for name, _ in _SHARED_CLASS_NAMES}
    twice = {n: files for n, files in where.items() if len(files) > 1 and n not in allowed}
    assert not twice, twice
    for (name, path), reason in _SHARED_CLASS_NAMES.items():
        assert reason and path in where.get(name, []), (name, path)
        assert len(where[name]) == 2, (name, where[name])


_DISPLACEMENT_U = {"u", "du", "u_new", "u_old", "u_path", "S_U"}


def test_soil_writes_y_for_the_lateral_displacement():
    """No identifier of ``soil/`` names the displacement ``u`` (``k_u``, the unloading
    stiffness, and ``s_u``, the undrained strength, are other quantities)."""
    found = []
    for path in sorted(Path(onbottom.soil.__file__).parent.glob("*.py")):
        tokens = tokenize.generate_tokens(io.StringIO(path.read_text(encoding="utf-8")).readline)
        for tok in tokens:
            if tok.type == tokenize.NAME and tok.string in _DISPLACEMENT_U:
                found.append(f"{path.name}:{tok.start[0]}: {tok.string}")
    assert not found, found


def test_every_soil_kernel_takes_y_new():
    """The kernel contract's third argument is the trial displacement ``y_new``, in every
    registered model (the recipe's model outside the package included)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    import recipe_models  # noqa: F401  (registers adhesive_coulomb)
    from onbottom.soil._dispatch import _KERNELS
    from onbottom.soil.registry import SOIL_MODELS

    for name in SOIL_MODELS.names():
        kernel = _KERNELS[SOIL_MODELS[name].cls.model_id]
        py = getattr(kernel, "py_func", kernel)
        params = list(inspect.signature(py).parameters)
        assert params[:4] == ["params", "state_old", "y_new", "v_load"], (name, params)
