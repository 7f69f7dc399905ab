"""Kill-safe results (issue 31 item 2): completion status, named refusals, run identity,
per-task stores, checkpoint/output consistency of the pipeline, Ctrl-C on the command line.

The random kill -9 tests of whole runs are in tests/verification/test_kill_resume.py.
"""

from __future__ import annotations

import hashlib
import json
import logging
import math
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.dynamics.pipeline import solver as S
from onbottom.errors import ResultFileError, RunInterrupted
from onbottom.hydro.short_crested import regular_node_kinematics
from onbottom.inputs.pipe import Pipe
from onbottom.results import (
    TaskStore,
    check_result_file,
    identity_hash,
    load_dataset,
    save_dataset,
    save_figure,
    write_csv_atomic,
    write_text_atomic,
)
from onbottom.soil.coulomb import CoulombFriction

SRC = Path(__file__).resolve().parents[2] / "src"
PIPE = Pipe(outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9)


def _pipeline(**kw):
    m = PipelineModel(
        pipe=PIPE,
        length=60.0,
        element_length=4.0,
        soil=CoulombFriction(friction_coefficient=0.5),
        **kw,
    )
    kin = regular_node_kinematics(
        m.x.size, 60.0, 0.05, 1.5, 10.0, ramp=20.0, x=m.x, wavelength=200.0
    )
    return m, kin


ST = PipelineSettings(record_interval=1.0, chunk_duration=10.0)


def _same(a, b) -> bool:
    """Equal, NaN equal to NaN (the JSON text of both)."""
    return json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)


# ---------------------------------------------------------------------------------------------
# result files
# ---------------------------------------------------------------------------------------------
def test_result_file_carries_its_status_and_a_partial_file_is_refused_by_name(tmp_path):
    ds = xr.Dataset({"y": ("time", np.arange(3.0))}, attrs={"model": "m"})
    save_dataset(ds, tmp_path / "a.nc")
    assert "run_status" not in ds.attrs  # the caller's dataset is left alone
    assert load_dataset(tmp_path / "a.nc").attrs["run_status"] == "complete"
    save_dataset(ds, tmp_path / "b.nc", run_status="partial")
    with pytest.raises(ResultFileError, match=r"'.*b\.nc' is partial.*interrupted"):
        load_dataset(tmp_path / "b.nc")
    assert load_dataset(tmp_path / "b.nc", allow_partial=True)["y"].size == 3


@pytest.mark.parametrize("damage", ["garbage", "truncated", "empty"])
def test_unreadable_result_is_a_named_error_with_the_restart_advice(tmp_path, damage):
    good = tmp_path / "good.nc"
    save_dataset(xr.Dataset({"y": ("t", np.arange(100.0))}), good)
    bad = tmp_path / "bad.nc"
    data = good.read_bytes()
    bad.write_bytes(
        {"garbage": b"\x89HDF\r\n\x1a\n" + os.urandom(600), "truncated": data[:700], "empty": b""}[
            damage
        ]
    )
    with pytest.raises(ResultFileError, match=r"'.*bad\.nc' is unreadable"):
        load_dataset(bad)
    advice = "rerun with --restart"
    with pytest.raises(ResultFileError, match="unreadable.*--restart") as info:
        check_result_file(bad, field="output", advice=advice)
    assert info.value.field == "output"


def test_atomic_writers_leave_the_old_file_or_none_when_the_writer_fails(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    csv_path = tmp_path / "t.csv"
    write_csv_atomic(csv_path, [{"a": 1, "b": 2.5}], ["a", "b"])
    assert csv_path.read_text(encoding="utf-8").splitlines() == ["a,b", "1,2.5"]
    with pytest.raises(ValueError):  # a row with a key outside the header
        write_csv_atomic(csv_path, [{"a": 1, "c": 3}], ["a", "b"])
    assert csv_path.read_text(encoding="utf-8").splitlines() == ["a,b", "1,2.5"]
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    png = save_figure(fig, tmp_path / "f.png", dpi=50)
    plt.close(fig)
    assert png.read_bytes()[:4] == b"\x89PNG"
    write_text_atomic(tmp_path / "x.txt", "ok")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.png", "t.csv", "x.txt"]


def test_identity_hash_is_stable_and_the_pipeline_identity_is_unchanged():
    a = identity_hash({"x": 1.0, "s": "a"}, np.arange(3.0))
    assert a == identity_hash({"s": "a", "x": 1.0}, np.arange(3.0))
    assert a != identity_hash({"s": "a", "x": 1.0 + 1e-15}, np.arange(3.0))
    assert a != identity_hash({"s": "a", "x": 1.0}, np.arange(4.0))
    assert identity_hash(f"<obj at {hex(id(a))}>") == identity_hash("<obj at 0xdeadbeef>")
    # the formula of the checkpoints since issue 31, with the package's content hash (issue
    # 41): a checkpoint written by other code is another run
    from onbottom._version import content_hash

    m, kin = _pipeline()
    h = hashlib.sha256()
    meta = {
        "model": m.describe(),
        # compression_level (issue 33) is output format, left out of the identity: the
        # settings hashed are those of the checkpoints written before it existed
        "settings": {k: v for k, v in S.asdict(ST).items() if k != "compression_level"},
        "kinematics": [kin.t0, kin.dt, list(kin.velocity.shape)],
        "extra": None,
        "onbottom_content": content_hash(),
    }
    h.update(json.dumps(meta, sort_keys=True, default=str).encode())
    h.update(np.ascontiguousarray(kin.velocity).tobytes())
    h.update(np.ascontiguousarray(kin.acceleration).tobytes())
    assert S.pipeline_identity(m, kin, ST).digest == h.hexdigest()


def test_task_store_round_trip_foreign_and_corrupt_files_restart(tmp_path):
    folder = tmp_path / "run.nc.tasks"
    st = TaskStore(folder, {"case": "A"}, what="seed")
    row = {"seed": 3, "y": 0.1 + 0.2, "nan": math.nan, "n": np.int64(7), "f": np.float32(0.5)}
    st.put({"seed": 3}, row)
    got = TaskStore(folder, {"case": "A"}).load([{"seed": 1}, {"seed": 3}])
    assert list(got) == [1]
    assert got[1]["y"] == 0.1 + 0.2 and math.isnan(got[1]["nan"]) and got[1]["n"] == 7
    with pytest.raises(ResultFileError, match=r"seed file .* belongs to another run.*--restart"):
        TaskStore(folder, {"case": "B"}, what="seed").load([{"seed": 3}])
    assert TaskStore(folder, {"case": "B"}, restart=True).load([{"seed": 3}]) == {}
    st.put({"seed": 4}, {"a": 1})
    (f,) = folder.glob("*.json")
    f.write_text("{not json", encoding="utf-8")
    with pytest.raises(ResultFileError, match="unreadable.*--restart"):
        st.load([{"seed": 4}])
    TaskStore.delete(folder)
    assert not folder.exists()


# ---------------------------------------------------------------------------------------------
# pipeline: partial records, checkpoint, resume
# ---------------------------------------------------------------------------------------------
def _interrupt_at_call(monkeypatch, n):
    calls = {"n": 0}
    real = S.K.integrate

    def flaky(*args):
        calls["n"] += 1
        if calls["n"] == n:
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(S.K, "integrate", flaky)
    return real


def test_interrupted_pipeline_leaves_no_final_file_and_resumes_with_a_log_line(
    tmp_path, monkeypatch, caplog
):
    m, kin = _pipeline()
    ref = simulate_pipeline(m, kin, settings=ST, output=tmp_path / "ref.nc")
    assert not (tmp_path / "ref.nc.ckpt.npz").exists()  # removed after success
    assert not (tmp_path / "ref.nc.part").exists()
    assert load_dataset(tmp_path / "ref.nc").attrs["run_status"] == "complete"
    out = tmp_path / "run.nc"
    real = _interrupt_at_call(monkeypatch, 4)
    with pytest.raises(KeyboardInterrupt):
        simulate_pipeline(m, kin, settings=ST, output=out)
    monkeypatch.setattr(S.K, "integrate", real)
    assert not out.exists()  # nothing a later run could take for a result
    assert (tmp_path / "run.nc.ckpt.npz").exists() and any((tmp_path / "run.nc.part").iterdir())
    with caplog.at_level(logging.INFO, logger="onbottom"):
        res = simulate_pipeline(m, kin, settings=ST, output=out)
    assert any("resuming" in r.message and "from t = 30" in r.message for r in caplog.records)
    a, b = load_dataset(tmp_path / "ref.nc"), res.open_dataset()
    for name in ("time", "y", "strain", "max_abs_y"):
        np.testing.assert_array_equal(a[name].values, b[name].values)
    assert _same(res.summary, ref.summary)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ref.nc", "run.nc"]


def test_stale_checkpoint_without_its_records_starts_afresh(tmp_path, monkeypatch, caplog):
    """The issue's case: the records gone, the old checkpoint must not be resumed (a time
    series starting at t = 3002 s)."""
    m, kin = _pipeline()
    ref = simulate_pipeline(m, kin, settings=ST)
    out = tmp_path / "run.nc"
    real = _interrupt_at_call(monkeypatch, 4)
    with pytest.raises(KeyboardInterrupt):
        simulate_pipeline(m, kin, settings=ST, output=out)
    monkeypatch.setattr(S.K, "integrate", real)
    for f in (tmp_path / "run.nc.part").iterdir():
        f.unlink()
    with caplog.at_level(logging.WARNING, logger="onbottom"):
        res = simulate_pipeline(m, kin, settings=ST, output=out)
    assert any("cannot be resumed" in r.message for r in caplog.records)
    ds = res.open_dataset()
    assert ds["time"].values[0] == 0.0
    np.testing.assert_array_equal(ds["y"].values, ref.data["y"].values.astype(np.float32))


def test_foreign_or_corrupt_checkpoint_and_corrupt_output_are_named_errors(tmp_path, monkeypatch):
    m, kin = _pipeline()
    out = tmp_path / "run.nc"
    real = _interrupt_at_call(monkeypatch, 2)
    with pytest.raises(KeyboardInterrupt):
        simulate_pipeline(m, kin, settings=ST, output=out)
    monkeypatch.setattr(S.K, "integrate", real)
    m2, _ = _pipeline(effective_axial_force=-1e4)
    with pytest.raises(ResultFileError, match=r"checkpoint .* belongs to another run.*--restart"):
        simulate_pipeline(m2, kin, settings=ST, output=out)
    ckpt = tmp_path / "run.nc.ckpt.npz"
    ckpt.write_bytes(ckpt.read_bytes()[:200])
    with pytest.raises(ResultFileError, match=r"checkpoint .* is unreadable.*--restart") as info:
        simulate_pipeline(m, kin, settings=ST, output=out)
    assert info.value.field == "checkpoint"
    fresh = simulate_pipeline(m, kin, settings=ST, output=out, resume="never")  # --restart
    assert fresh.success and not ckpt.exists()
    # a corrupt file under the output's name (as a kill -9 of an older onbottom left it)
    out.write_bytes(b"\x89HDF\r\n\x1a\n" + os.urandom(3000))
    with pytest.raises(ResultFileError, match=r"output '.*run\.nc' is unreadable.*--restart"):
        simulate_pipeline(m, kin, settings=ST, output=out)
    assert simulate_pipeline(m, kin, settings=ST, output=out, resume="never").success
    assert load_dataset(out).attrs["run_status"] == "complete"


def test_finished_output_of_this_run_is_returned_and_of_other_inputs_replaced(tmp_path):
    m, kin = _pipeline()
    out = tmp_path / "run.nc"
    a = simulate_pipeline(m, kin, settings=ST, output=out)
    stamp = out.stat().st_mtime_ns
    b = simulate_pipeline(m, kin, settings=ST, output=out)
    assert out.stat().st_mtime_ns == stamp and _same(b.summary, a.summary)
    assert b.criteria == a.criteria and b.max_displacement == a.max_displacement
    m2, _ = _pipeline(effective_axial_force=-1e4)
    c = simulate_pipeline(m2, kin, settings=ST, output=out)
    assert load_dataset(out).attrs["run_id"] == c.run_id != a.run_id


# ---------------------------------------------------------------------------------------------
# seeds and curve points streamed to a store; Ctrl-C
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def storm_case():
    from onbottom.inputs.soil import Sand
    from onbottom.inputs.storm import Current, SeaState, Storm
    from onbottom.soil.verley_sotberg import VerleySotberg

    pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm(stages=(SeaState(hs=4.68, tp=10.8, duration_s=120.0),), build_up_s=20.0)
    kw = {"depth": 13.0, "current": Current(velocity=0.91, z0=5.2e-6)}
    return pipe, soil, storm, kw


def test_interrupted_seeds_resume_without_repeating_and_equal_a_whole_run(
    tmp_path, monkeypatch, storm_case
):
    from onbottom.study import storm_seeds as SS

    pipe, soil, storm, kw = storm_case
    ref = SS.run_storm_seeds(pipe, soil, storm, seeds=5, n_workers=0, **kw)
    store = tmp_path / "s.nc.tasks"
    calls: list[int] = []
    real = SS._SeedJob.__call__

    def counting(self, seed):
        calls.append(int(seed))
        if len(calls) == 3 and stop:
            raise KeyboardInterrupt
        return real(self, seed)

    monkeypatch.setattr(SS._SeedJob, "__call__", counting)
    stop = True
    with pytest.raises(RunInterrupted, match=r"after 2 of 5 seeds; they are kept in .*tasks"):
        SS.run_storm_seeds(pipe, soil, storm, seeds=5, n_workers=0, store=store, **kw)
    assert len(list(store.glob("*.json"))) == 2
    stop, calls[:] = False, []
    again = SS.run_storm_seeds(pipe, soil, storm, seeds=5, n_workers=0, store=store, **kw)
    assert calls == [2, 3, 4]  # the two finished seeds are not run again
    for name in ("max_displacement", "final_displacement", "n_steps", "status"):
        np.testing.assert_array_equal(again.data[name].values, ref.data[name].values)
    assert again.statistics == ref.statistics
    # other inputs: the kept seeds are refused by name, --restart discards them
    with pytest.raises(ResultFileError, match="another run.*--restart"):
        SS.run_storm_seeds(pipe, soil, storm.with_seed(0), seeds=5, n_workers=0, store=store,
                           depth=14.0, current=kw["current"])  # fmt: skip
    calls[:] = []
    SS.run_storm_seeds(pipe, soil, storm, seeds=5, n_workers=0, store=store, restart=True, **kw)
    assert calls == [0, 1, 2, 3, 4]


def test_interrupted_curve_points_resume_without_repeating(tmp_path, monkeypatch):
    from onbottom.study import stability_curves as SC

    fast = SC.CurveSettings(seeds=1, build_up_hours=0.01, peak_hours=0.03, tolerance=0.3)
    grid = ([5.0, 10.0], [0.2])
    ref = SC.stability_curves(*grid, soils=["sand"], criteria=["L_10"], settings=fast,
                              n_workers=0)  # fmt: skip
    store = tmp_path / "c.nc.tasks"
    calls: list[float] = []
    real = SC._PointJob.__call__

    def counting(self, item):
        calls.append(item[1])
        if len(calls) == 2 and stop:
            raise KeyboardInterrupt
        return real(self, item)

    monkeypatch.setattr(SC._PointJob, "__call__", counting)
    stop = True
    with pytest.raises(RunInterrupted, match="after 1 of 2 points"):
        SC.stability_curves(*grid, soils=["sand"], criteria=["L_10"], settings=fast,
                            n_workers=0, store=store)  # fmt: skip
    stop, calls[:] = False, []
    again = SC.stability_curves(*grid, soils=["sand"], criteria=["L_10"], settings=fast,
                                n_workers=0, store=store)  # fmt: skip
    assert calls == [10.0]
    for name in ("L_10", "L_10_bracket_low", "L_10_bracket_high", "L_10_storms"):
        np.testing.assert_array_equal(again[name].values, ref[name].values)


def test_ctrl_c_on_the_command_line_is_one_line_and_status_130(tmp_path, monkeypatch, capsys):
    from onbottom.cli.main import main
    from onbottom.study import storm_seeds as SS

    case = Path(__file__).resolve().parents[2] / "examples" / "storm_case.toml"

    def interrupted(*a, **k):
        raise RunInterrupted("interrupted after 150 of 400 seeds; they are kept in x.tasks")

    monkeypatch.setattr(SS, "run_storm_seeds", interrupted)
    rc = main(["storm", str(case), "--seeds", "400", "-o", str(tmp_path / "s.nc"), "--quiet"])
    err = capsys.readouterr().err
    assert rc == 130
    assert err.strip().splitlines() == [
        "interrupted after 150 of 400 seeds; they are kept in x.tasks"
    ]
    rc = main(["storm", str(case), "--seeds", "4", "-o", str(tmp_path / "s.nc"), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 130 and out["error"]["type"] == "Interrupted"


def test_a_process_dies_with_its_parent_even_while_busy(tmp_path):
    """die_with_parent (the embedded Dask workers' preload): kill -9 the parent, the child
    goes too, although it spins in a loop."""
    script = tmp_path / "parent.py"
    script.write_text(
        textwrap.dedent(
            """
            import subprocess, sys, time
            child = subprocess.Popen([sys.executable, "-c", (
                "from onbottom.study.engine import die_with_parent\\n"
                "die_with_parent()\\n"
                "print('armed', flush=True)\\n"
                "while True: pass\\n")], stdout=subprocess.PIPE, text=True)
            assert child.stdout.readline().strip() == "armed"
            print(child.pid, flush=True)
            time.sleep(600)
            """
        ),
        encoding="utf-8",
    )
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    parent = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True,
                              env=env)  # fmt: skip
    child_pid = int(parent.stdout.readline())
    os.kill(parent.pid, signal.SIGKILL)
    parent.wait()
    for _ in range(600):  # liveness guard only: the kernel kills the child at once
        try:
            os.kill(child_pid, 0)
        except ProcessLookupError:
            break
        if Path(f"/proc/{child_pid}/stat").exists():
            state = Path(f"/proc/{child_pid}/stat").read_text().split(")")[-1].split()[0]
            if state == "Z":  # dead, waiting for its (new) parent to reap it
                break
        time.sleep(0.1)
    else:
        os.kill(child_pid, signal.SIGKILL)
        pytest.fail("the child survived its parent")


def test_storm_command_names_a_corrupt_output_and_restart_recovers(tmp_path, capsys):
    """The issue's report: a corrupt NetCDF under the final name (an older onbottom killed
    mid-write) is a named error advising --restart; --restart replaces it."""
    from onbottom.cli.main import main

    text = (Path(__file__).resolve().parents[2] / "examples" / "pipeline_case.toml").read_text(
        encoding="utf-8"
    )
    lines = []
    for line in text.splitlines():
        key = line.split("=")[0].strip()
        lines.append({"length": "length = 40.0", "peak_hours": "peak_hours = 0.01"}.get(key, line))
    case = tmp_path / "p.toml"
    case.write_text("\n".join(lines) + "\n", encoding="utf-8")
    out = tmp_path / "p.nc"
    out.write_bytes(b"\x89HDF\r\n\x1a\n" + os.urandom(2000))
    assert main(["storm", str(case), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "p.nc' is unreadable" in err and "--restart" in err
    assert main(["storm", str(case), "--quiet", "--restart"]) == 0
    capsys.readouterr()
    assert load_dataset(out).attrs["run_status"] == "complete"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.nc", "p.toml"]


def test_killed_after_the_final_rename_the_rerun_returns_the_result_and_cleans_up(tmp_path):
    """A kill between the rename of the finished output and the clean-up leaves the chunk
    folder (a directory) beside the result; the rerun returns the result and removes it (found
    by the random kill -9 test under load: 'p.nc.part: Is a directory')."""
    m, kin = _pipeline()
    out = tmp_path / "run.nc"
    ref = simulate_pipeline(m, kin, settings=ST, output=out)
    (tmp_path / "run.nc.part").mkdir()
    (tmp_path / "run.nc.part" / "chunk_000000.npz").write_bytes(b"left by a kill")
    res = simulate_pipeline(m, kin, settings=ST, output=out)
    assert _same(res.summary, ref.summary)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc"]
