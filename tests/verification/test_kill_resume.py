"""kill -9 at random moments of a pipeline run, a storm-seeds run and a curves run (issue 31).

Each test runs the command once uninterrupted (the reference, and the measure T of its wall
time), then a few times killed with SIGKILL after a delay drawn from a seeded RNG, one in each
slice of [0, 1.1 T], or after the first chunk or task was kept — during start-up, mid-run, while
writing the result, or after it ended — and then once more to completion. Whatever the kill time:

* a file under the final name is whole: a complete result equal to the reference (never a
  corrupt or partial file that a later run or reader would take for a result);
* the Dask workers die with their killed parent;
* the rerun exits 0, resumes what was kept ("resuming …" when a checkpoint or finished tasks
  were left) and gives results bitwise equal to the uninterrupted run, and leaves no
  checkpoint, partial records or task store behind.

No assertion depends on how long anything takes: the kill time only selects which state the
run is left in, and every state must lead to a valid outcome. A Ctrl-C (SIGINT to the process
group, as a terminal sends it) of a seeds run ends with one line and status 130, and so does a
SIGINT at random moments of ``stability`` and ``loads`` (start-up included). The in-process
counterpart, an interrupt at a random call of onbottom's code in every stability command, is
``tests/unit/test_fuzz_interrupts.py``. The module is in the ``long`` tier
(``python3 -m pytest -m long``).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from case_helpers import curves_case

psutil = pytest.importorskip("psutil")

pytestmark = [pytest.mark.verification, pytest.mark.slow, pytest.mark.long]

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
RNG_SEED = 31


def _command(args: list[str]) -> list[str]:
    return [sys.executable, "-m", "onbottom", *args]


def _run(args: list[str], cwd: Path) -> tuple[subprocess.CompletedProcess, float]:
    t0 = time.perf_counter()
    p = subprocess.run(_command(args), cwd=cwd, env=ENV, capture_output=True, text=True)
    return p, time.perf_counter() - t0


def _start(args: list[str], cwd: Path, capture: bool = False) -> subprocess.Popen:
    """The command started in its own session (output captured as text, or discarded)."""
    out = subprocess.PIPE if capture else subprocess.DEVNULL
    return subprocess.Popen(
        _command(args),
        cwd=cwd,
        env=ENV,
        stdout=out,
        stderr=out,
        text=capture,
        start_new_session=True,
    )


def _kill_after(args: list[str], cwd: Path, delay: float, after=None) -> None:
    """Start the command, SIGKILL it (the parent only) ``delay`` s after its start — or after
    ``after()`` first holds (e.g. a first chunk kept: a kill mid-run) —; check that its child
    processes (Dask workers) die with it."""
    proc = _start(args, cwd)
    if after is not None:
        for _ in range(3000):  # until the event (a hang guard of 300 s, no timing check)
            if after() or proc.poll() is not None:
                break
            time.sleep(0.1)
    try:
        proc.wait(timeout=delay)
        return  # finished before the kill: a valid state too
    except subprocess.TimeoutExpired:
        pass
    try:
        children = psutil.Process(proc.pid).children(recursive=True)
    except psutil.NoSuchProcess:
        children = []
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    _, alive = psutil.wait_procs(children, timeout=120)  # a hang guard, not a timing check
    for c in alive:
        c.kill()
    assert not alive, f"{len(alive)} worker process(es) survived their killed parent"


def _kills(t_ref: float, n_start: int, n_event: int) -> list[tuple[float, bool]]:
    """Random kill times (seeded): ``n_start`` counted from the start, one in each equal
    slice of [0, 1.1 T]; ``n_event`` counted from the first kept chunk or task, in
    [0, 0.3 T]. (delay, from the event?) pairs."""
    rng = np.random.default_rng(RNG_SEED)
    u = rng.uniform(0.0, 1.0, n_start)
    out = [(1.1 * t_ref * (i + u[i]) / n_start, False) for i in range(n_start)]
    return out + [(float(x), True) for x in rng.uniform(0.0, 0.3 * t_ref, n_event)]


def _any_file(folder: Path, pattern: str):
    return lambda: folder.is_dir() and any(folder.glob(pattern))


def _assert_same_dataset(path: Path, ref: xr.Dataset, attrs: tuple[str, ...] = ()) -> None:
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert ds.attrs["run_status"] == "complete"
        assert set(ds.data_vars) == set(ref.data_vars)
        for name in ref.variables:
            np.testing.assert_array_equal(ds[name].values, ref[name].values, err_msg=name)
        for a in attrs:
            assert ds.attrs[a] == ref.attrs[a], a


def _leftovers(folder: Path, keep: set[str]) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name not in keep)


def _load(path: Path) -> xr.Dataset:
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        return ds.load()


# ---------------------------------------------------------------------------------------------
def _pipeline_case(folder: Path) -> Path:
    text = (EXAMPLES / "pipeline_case.toml").read_text(encoding="utf-8")
    lines = []
    for line in text.splitlines():
        key = line.split("=")[0].strip()
        if key == "length":
            line = "length = 60.0"
        elif key == "peak_hours":
            line = "peak_hours = 0.5"
        elif key == "record_interval":
            line = "record_interval = 1.0\nchunk_duration = 20.0"
        lines.append(line)
    case = folder / "p.toml"
    case.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return case


def test_pipeline_run_killed_at_random_moments(tmp_path):
    case = _pipeline_case(tmp_path)
    ref_run, t_ref = _run(["storm", case.name, "--quiet", "-o", "ref.nc"], tmp_path)
    assert ref_run.returncode == 0, ref_run.stderr
    ref = _load(tmp_path / "ref.nc")
    out = tmp_path / "p.nc"
    for delay, mid in _kills(t_ref, 2, 2):
        event = _any_file(tmp_path / "p.nc.part", "chunk_*.npz") if mid else None
        _kill_after(["storm", case.name, "--quiet"], tmp_path, delay, event)
        if out.exists():  # only ever a whole result of this run
            _assert_same_dataset(out, ref, ("summary", "run_id", "status"))
        had_checkpoint = (tmp_path / "p.nc.ckpt.npz").exists() and not out.exists()
        left = _leftovers(tmp_path, {"p.toml", "ref.nc"})
        print(f"kill at {delay:.1f} of {t_ref:.1f} s: left {left}")
        rerun, _ = _run(["storm", case.name, "--quiet"], tmp_path)
        assert rerun.returncode == 0, rerun.stderr
        if had_checkpoint:
            assert "resuming p.nc from t = " in rerun.stderr
        _assert_same_dataset(out, ref, ("summary", "run_id", "status"))
        assert _leftovers(tmp_path, {"p.toml", "ref.nc", "p.nc"}) == []
        out.unlink()


# ---------------------------------------------------------------------------------------------
def _storm_case(folder: Path, peak_hours: float) -> Path:
    text = (EXAMPLES / "storm_case.toml").read_text(encoding="utf-8")
    text = text.replace("build_up_hours = 0.5", "build_up_hours = 0.02")
    text = text.replace("peak_hours = 3.0", f"peak_hours = {peak_hours}")
    case = folder / "s.toml"
    case.write_text(text, encoding="utf-8")
    return case


@pytest.mark.dask
def test_storm_seeds_run_killed_at_random_moments(tmp_path):
    case = _storm_case(tmp_path, 1.0)
    args = ["storm", case.name, "--seeds", "16", "--workers", "2", "--quiet"]
    ref_run, t_ref = _run([*args, "-o", "ref.nc"], tmp_path)
    assert ref_run.returncode == 0, ref_run.stderr
    ref = _load(tmp_path / "ref.nc")
    out, store = tmp_path / "s.nc", tmp_path / "s.nc.tasks"
    for delay, mid in _kills(t_ref, 1, 2):
        _kill_after(args, tmp_path, delay, _any_file(store, "*.json") if mid else None)
        if out.exists():
            _assert_same_dataset(out, ref, ("stat_mean", "stat_max"))
        kept = len(list(store.glob("*.json"))) if store.is_dir() else 0
        print(f"kill at {delay:.1f} of {t_ref:.1f} s: {kept} seeds kept, final {out.exists()}")
        rerun, _ = _run(args, tmp_path)
        assert rerun.returncode == 0, rerun.stderr
        if kept:
            assert f"resuming: {kept} of 16 seeds already done" in rerun.stderr
        _assert_same_dataset(out, ref, ("stat_mean", "stat_max"))
        assert _leftovers(tmp_path, {"s.toml", "ref.nc", "s.nc"}) == []
        out.unlink()


@pytest.mark.dask
def test_storm_seeds_ctrl_c_is_one_line_status_130_and_resumes(tmp_path):
    case = _storm_case(tmp_path, 0.5)
    args = ["storm", case.name, "--seeds", "40", "--workers", "2", "--quiet"]
    store = tmp_path / "s.nc.tasks"
    proc = _start(args, tmp_path, capture=True)  # its own process group, as a terminal's job
    for _ in range(3000):  # until a seed is kept (hang guard: 300 s)
        if (store.is_dir() and any(store.glob("*.json"))) or proc.poll() is not None:
            break
        time.sleep(0.1)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    children = psutil.Process(proc.pid).children(recursive=True)
    os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C: the whole group, workers included
    _, err = proc.communicate()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert proc.returncode == 130, err
    assert "Traceback" not in err
    assert len(lines) == 1 and lines[0].startswith("interrupted after "), err
    assert "run the same command again" in lines[0]
    _, alive = psutil.wait_procs(children, timeout=120)
    for c in alive:
        c.kill()
    assert not alive, "workers outlived the interrupted run"
    kept = len(list(store.glob("*.json")))
    assert kept >= 1
    rerun, _ = _run(args, tmp_path)
    assert rerun.returncode == 0, rerun.stderr
    assert f"resuming: {kept} of 40 seeds already done" in rerun.stderr
    with xr.open_dataset(tmp_path / "s.nc", engine="h5netcdf") as ds:
        assert ds.sizes["seed"] == 40 and ds.attrs["run_status"] == "complete"
    assert not store.exists()


# ---------------------------------------------------------------------------------------------
CURVES = curves_case(build_up_hours=0.02, peak_hours=0.05, tolerance=0.2)


@pytest.mark.dask
def test_curves_run_killed_at_random_moments(tmp_path):
    case = tmp_path / "c.toml"
    case.write_text(CURVES, encoding="utf-8")
    args = ["curves", case.name, "--workers", "2", "--quiet"]
    ref_run, t_ref = _run([*args, "-o", "ref.nc"], tmp_path)
    assert ref_run.returncode == 0, ref_run.stderr
    ref = _load(tmp_path / "ref.nc")
    ref_csv = _csv_without_run_times(tmp_path / "ref.csv")
    keep = {"c.toml", "ref.nc", "ref.csv", "ref.png"}
    for delay, mid in _kills(t_ref, 1, 1):
        event = _any_file(tmp_path / "c.nc.tasks", "*.json") if mid else None
        _kill_after(args, tmp_path, delay, event)
        variables = [v for v in ref.data_vars if not v.endswith("_runtime")]
        if (tmp_path / "c.nc").exists():
            _assert_same_dataset_vars(tmp_path / "c.nc", ref, variables)
        if (tmp_path / "c.csv").exists():
            assert _csv_without_run_times(tmp_path / "c.csv") == ref_csv
        kept = len(list((tmp_path / "c.nc.tasks").glob("*.json")))
        print(f"kill at {delay:.1f} of {t_ref:.1f} s: {kept} points kept")
        rerun, _ = _run(args, tmp_path)
        assert rerun.returncode == 0, rerun.stderr
        if kept:
            assert f"resuming: {kept} of 2 points already done" in rerun.stderr
        _assert_same_dataset_vars(tmp_path / "c.nc", ref, variables)
        assert _csv_without_run_times(tmp_path / "c.csv") == ref_csv
        assert _leftovers(tmp_path, keep | {"c.nc", "c.csv", "c.png"}) == []
        for name in ("c.nc", "c.csv", "c.png"):
            (tmp_path / name).unlink()


def _csv_without_run_times(path: Path) -> list[list[str]]:
    """The curve CSV's rows without the per-point run-time columns (they differ between runs;
    every other value must be the same text)."""
    import csv

    with path.open(encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    keep = [i for i, name in enumerate(rows[0]) if not name.endswith("_runtime_s")]
    return [[row[i] for i in keep] for row in rows]


def _assert_same_dataset_vars(path: Path, ref: xr.Dataset, variables: list[str]) -> None:
    """Same L, brackets and storm counts (the per-point run times differ between runs)."""
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert ds.attrs["run_status"] == "complete"
        for name in variables:
            np.testing.assert_array_equal(ds[name].values, ref[name].values, err_msg=name)


# ---------------------------------------------------------------------------------------------
def test_ctrl_c_at_random_moments_of_the_stability_commands(tmp_path):
    """A real SIGINT (as a terminal sends it) at random moments of ``stability`` and of
    ``loads`` — while Python loads onbottom, parses the case, computes, writes: status 130
    with one line and no traceback, or a finished run; a ``loads`` output is whole or absent."""
    case = tmp_path / "c.toml"
    case.write_text((EXAMPLES / "stability_case.toml").read_text(encoding="utf-8"), "utf-8")
    commands = {
        "stability": ["stability", case.name],
        "loads": ["loads", case.name, "--duration-hours", "0.1", "-o", "p.nc"],
    }
    for name, args in commands.items():
        ref_run, t_ref = _run(args, tmp_path)
        assert ref_run.returncode == 0, ref_run.stderr
        t_ref = min(t_ref, _run(args, tmp_path)[1])  # the first run also warms the file cache
        if name == "loads":
            ref = _load(tmp_path / "p.nc")
            (tmp_path / "p.nc").unlink()
        for delay, _ in _kills(t_ref, 3, 0):
            proc = _start(args, tmp_path, capture=True)
            try:
                _, err = proc.communicate(timeout=delay)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGINT)
                _, err = proc.communicate()
            lines = [ln for ln in err.splitlines() if ln.strip()]
            print(f"{name}: SIGINT at {delay:.1f} of {t_ref:.1f} s: status {proc.returncode}")
            # -SIGINT: the signal came before Python set its handler (nothing printed at all)
            assert proc.returncode in (0, 130, -signal.SIGINT), err
            assert "Traceback" not in err, err
            if proc.returncode == 130:
                assert len(lines) == 1 and lines[0].startswith("interrupted"), err
            if name == "loads" and (tmp_path / "p.nc").exists():
                with xr.open_dataset(tmp_path / "p.nc", engine="h5netcdf") as ds:
                    for var in ref.variables:
                        np.testing.assert_array_equal(ds[var].values, ref[var].values)
                (tmp_path / "p.nc").unlink()
