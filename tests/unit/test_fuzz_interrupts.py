"""Fuzzing the interrupts class of the bad-input campaign (issue 31 item 8).

A Ctrl-C reaches Python code between two bytecodes (inside a numba kernel it waits for the
kernel's return): a :func:`sys.settrace` hook raises :class:`KeyboardInterrupt` at the n-th call
of a function of onbottom, n drawn by hypothesis over the whole run (start-up, case loading,
the solver's Python parts, writing the result, the figure, the JSON/table output). For
``stability``, ``loads``, ``storm`` (a section, and seeds in this process), ``curves`` and
``report``, whatever the moment:

* the command exits 130 with one line on stderr and no traceback (``main`` returns; nothing
  escapes it);
* a file under a final name is never a partial or foreign one: absent, or whole and equal to
  the uninterrupted run's;
* the same command run again exits 0 and gives the uninterrupted run's results, and leaves no
  temporary file, checkpoint or task store behind.

The cases are small (a few seconds each); ``ONBOTTOM_FUZZ_INTERRUPTS=50`` hunts longer.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from case_helpers import curves_case
from onbottom.cli.main import main

pytestmark = pytest.mark.filterwarnings("default::onbottom.errors.OutOfRangeWarning")

SRC = str(Path(__file__).resolve().parents[2] / "src" / "onbottom")
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

INTERRUPTS = settings(
    max_examples=int(os.environ.get("ONBOTTOM_FUZZ_INTERRUPTS", "4")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
WHERE = st.floats(min_value=0.0, max_value=1.0, exclude_max=True)


class InterruptAt:
    """``sys.settrace`` hook: counts the calls of onbottom's functions and raises
    :class:`KeyboardInterrupt` at call ``n`` (never when ``n`` is None)."""

    def __init__(self, n: int | None = None) -> None:
        self.n = n
        self.calls = 0
        self.fired = False

    def __call__(self, frame, event, arg):
        if (
            event == "call"
            and frame.f_code.co_filename.startswith(SRC)
            and frame.f_code is not main.__code__  # its first bytecode: before any handler
        ):
            self.calls += 1
            if self.calls == self.n:
                self.fired = True
                raise KeyboardInterrupt  # Python unsets the hook: one interrupt per run
        return None


def _main(argv: list[str], n: int | None = None) -> tuple[int, str, str, InterruptAt]:
    """``onbottom ARGV`` in this process with the hook; (status, stdout, stderr, hook)."""
    hook = InterruptAt(n)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        sys.settrace(hook)
        try:
            rc = main(argv)
        except KeyboardInterrupt:  # escaped main: the user would see a traceback
            rc = -2
        finally:
            sys.settrace(None)
    return rc, out.getvalue(), err.getvalue(), hook


class Case:
    """A command in its own folder: the reference run, its call count, its final files."""

    def __init__(self, root: Path, name: str, files: dict[str, str], argv, outputs) -> None:
        self.src = root / name / "src"
        self.src.mkdir(parents=True)
        for fname, text in files.items():
            (self.src / fname).write_text(text, encoding="utf-8")
        self.argv = argv  # folder -> argv
        self.outputs = outputs  # names of the final files (relative to the folder)
        ref = self.src.parent / "ref"
        shutil.copytree(self.src, ref)
        rc, _, err, hook = _main(self.argv(ref))
        assert rc == 0, err
        self.ref = ref
        self.calls = hook.calls
        self.count = 0

    def folder(self) -> Path:
        self.count += 1
        work = self.src.parent / f"run{self.count}"
        shutil.copytree(self.src, work)
        return work


def _same_file(path: Path, ref: Path) -> None:
    """``path`` is whole and equal to the reference's (NetCDF: complete and the same
    numbers; JSON: the same apart from run times; other files: present, not empty)."""
    if path.suffix == ".nc":
        with (
            xr.open_dataset(path, engine="h5netcdf") as ds,
            xr.open_dataset(ref, engine="h5netcdf") as want,
        ):
            if "run_status" in want.attrs:
                assert ds.attrs.get("run_status") == "complete", path
            assert set(ds.variables) == set(want.variables), path
            for name in want.variables:
                if name.endswith("_runtime"):
                    continue
                np.testing.assert_array_equal(ds[name].values, want[name].values, err_msg=name)
    elif path.suffix == ".json":
        assert _without_times(json.loads(path.read_text())) == _without_times(
            json.loads(ref.read_text())
        )
    elif path.suffix == ".csv":
        assert _csv_rows(path) == _csv_rows(ref)
    else:
        assert path.stat().st_size > 0 and ref.stat().st_size > 0, path


def _without_times(obj):
    if isinstance(obj, dict):
        return {
            k: _without_times(v)
            for k, v in obj.items()
            if "time" not in k and k not in {"created", "run_id", "provenance"}
        }
    if isinstance(obj, list):
        return [_without_times(v) for v in obj]
    return obj


def _csv_rows(path: Path) -> list[list[str]]:
    import csv

    with path.open(encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    keep = [i for i, name in enumerate(rows[0]) if not name.endswith("_runtime_s")]
    return [[row[i] for i in keep] for row in rows]


def _check_interrupt_then_rerun(case: Case, where: float) -> None:
    n = 1 + int(where * case.calls)
    work = case.folder()
    rc, _, err, hook = _main(case.argv(work), n)
    if hook.fired:
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert rc == 130, f"call {n} of {case.calls}: status {rc}\n{err[-2000:]}"
        assert "Traceback" not in err and len(lines) == 1, err[-2000:]
        assert lines[0].startswith("interrupted"), lines
    else:  # the run took another path with fewer calls (it ended before call n)
        assert rc == 0, err
    for name in case.outputs:  # a final name holds a whole result of this case, or nothing
        if (work / name).exists():
            _same_file(work / name, case.ref / name)
    rc, _, err, _ = _main(case.argv(work))
    assert rc == 0, f"rerun after an interrupt at call {n} of {case.calls}: status {rc}\n{err}"
    for name in case.outputs:
        _same_file(work / name, case.ref / name)
    left = sorted(p.name for p in work.iterdir()) if work.is_dir() else []
    want = sorted(p.name for p in case.src.iterdir())
    extra = sorted(set(left) - set(want) - {Path(o).parts[0] for o in case.outputs})
    assert extra == [], f"left behind after the rerun: {extra}"
    shutil.rmtree(work)


# ---------------------------------------------------------------------------------------------
STABILITY = (EXAMPLES / "stability_case.toml").read_text(encoding="utf-8")
STORM = (
    (EXAMPLES / "storm_case.toml")
    .read_text(encoding="utf-8")
    .replace("build_up_hours = 0.5", "build_up_hours = 0.0")
    .replace("peak_hours = 3.0", "peak_hours = 0.02")
)
CURVES = curves_case(build_up_hours=0.0, peak_hours=0.02, tolerance=0.3)


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    """Command name -> its :class:`Case`, built (the reference run) when first asked for."""
    root = tmp_path_factory.mktemp("interrupts")
    made: dict[str, Case] = {}

    def get(name: str) -> Case:
        if name not in made:
            made[name] = Case(root, *SPECS[name])
        return made[name]

    return get


SPECS = {
    "stability": (
        "stability",
        {"c.toml": STABILITY},
        lambda f: ["stability", str(f / "c.toml")],
        [],
    ),
    "loads": (
        "loads",
        {"c.toml": STABILITY},
        lambda f: [
            "loads",
            str(f / "c.toml"),
            "--duration-hours",
            "0.1",
            "-o",
            str(f / "peaks.nc"),
            "--plot",
            str(f / "vh.png"),
        ],
        ["peaks.nc", "vh.png"],
    ),
    "storm": (
        "storm",
        {"s.toml": STORM},
        lambda f: ["storm", str(f / "s.toml"), "--quiet"],
        ["s.nc"],
    ),
    "storm seeds": (
        "seeds",
        {"s.toml": STORM},
        lambda f: ["storm", str(f / "s.toml"), "--quiet", "--seeds", "3", "--workers", "0"],
        ["s.nc"],
    ),
    "curves": (
        "curves",
        {"c.toml": CURVES},
        lambda f: ["curves", str(f / "c.toml"), "--quiet", "--workers", "0"],
        ["c.nc", "c.csv", "c.png"],
    ),
    "report": (
        "report",
        {},
        lambda f: ["report", "--only", "checks_f109", "--out", str(f / "rep")],
        ["rep/report.json", "rep/index.html"],
    ),
}


@pytest.mark.parametrize("command", list(SPECS))
def test_interrupt_at_any_moment_is_one_line_130_and_the_rerun_is_whole(cases, command):
    case = cases(command)

    @INTERRUPTS
    @given(where=WHERE)
    def check(where):
        _check_interrupt_then_rerun(case, where)

    check()
