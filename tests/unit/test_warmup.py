"""Issue 33 item 2: the one-time warm-up compiles the specialisations the commands use.

:func:`onbottom.study.warmup.warm_kernels` runs tiny real problems through the public solvers;
here a small target runs in this process and the kernels' dispatchers must then hold the
literal-model specialisations the commands call (``call_literal`` with the soil and force model
ids), and a second warm-up compiles nothing. The targets must cover every seabed kind of the
case files and the default force models of ``storm`` and ``assess``. The CLI runs one target.
"""

from __future__ import annotations

import json

import numba
import pytest
from click.testing import CliRunner

from onbottom.cli.json_contract import SCHEMA_VERSION, documented_keys
from onbottom.cli.main import cli, main
from onbottom.errors import InputError
from onbottom.study.warmup import (
    PIPELINE_SEABEDS,
    STORM_FORCE_MODELS,
    STORM_SEABEDS,
    TARGETS,
    WORKER_START_S,
    estimate,
    warm_kernels,
)


def _literal_firsts(dispatcher, n: int) -> set[tuple[int, ...]]:
    """The literal values of the first ``n`` argument types of each compiled signature."""
    out = set()
    for sig in dispatcher.overloads:
        head = sig[:n]
        if all(isinstance(t, numba.types.IntegerLiteral) for t in head):
            out.add(tuple(t.literal_value for t in head))
    return out


def test_section_target_leaves_the_section_kernel_specialised():
    from onbottom.dynamics import _section_kernel as K
    from onbottom.soil._dispatch import MODEL_VERLEY_SOTBERG

    calls = []
    report = warm_kernels(["section"], processes=1, progress=lambda *a: calls.append(a))
    assert [(k, n, t.name) for k, n, t in calls] == [(1, 1, "section")]
    assert report.processes == 1 and [t.target.name for t in report.targets] == ["section"]
    for fn in (K.initial_record, K.integrate):
        assert (MODEL_VERLEY_SOTBERG,) in _literal_firsts(fn, 1), fn
    again = warm_kernels(["section"], processes=1)
    assert again.compiled == 0  # in memory now: nothing to compile


def test_storm_target_compiles_both_force_models():
    from onbottom.dynamics import _storm_kernel as K
    from onbottom.hydro._force_dispatch import FORCE_MORISON, FORCE_WAKE
    from onbottom.soil._dispatch import MODEL_COULOMB

    warm_kernels(["storm-rock"], processes=1)
    got = _literal_firsts(K.integrate, 2)  # the start too (n0 < 0: ``initial`` inlined)
    assert {(MODEL_COULOMB, FORCE_MORISON), (MODEL_COULOMB, FORCE_WAKE)} <= got


def test_fixed_pipe_target_compiles_the_report_kernel_for_both_force_models():
    """The assess report's V–H figure (hydro.fixed_pipe) finds its kernel compiled."""
    from onbottom.hydro import _fixed_pipe_kernel as K
    from onbottom.hydro._force_dispatch import FORCE_MORISON, FORCE_WAKE

    warm_kernels(["fixed-pipe"], processes=1)
    assert {(FORCE_MORISON,), (FORCE_WAKE,)} <= _literal_firsts(K.fixed_pipe_record, 1)
    assert warm_kernels(["fixed-pipe"], processes=1).compiled == 0


def test_targets_cover_the_default_models():
    """Every seabed kind of a case file maps to a soil model a storm target compiles; the
    force models compiled include the defaults of storm and assess."""
    from onbottom.cases.assess import DEFAULT_FORCE_MODEL
    from onbottom.cases.force import force_model_from_case
    from onbottom.soil.registry import SEABED_MODELS, soil_model_entry

    names = {t.name for t in TARGETS}
    assert set(STORM_SEABEDS) | set(PIPELINE_SEABEDS) | {"section", "fixed-pipe"} == names

    def model_class(kind: str) -> type:
        return soil_model_entry(SEABED_MODELS[kind]).cls

    covered = {model_class(kind).model_id for kind in STORM_SEABEDS.values()}
    for kind in SEABED_MODELS:
        assert model_class(kind).model_id in covered, kind
    # the embedded assess route's seabeds (its pipeline FE run takes the governing one's)
    assert {"sand", "clay"} <= set(PIPELINE_SEABEDS.values())
    storm_default = force_model_from_case.__kwdefaults__["default"]
    assert {storm_default, DEFAULT_FORCE_MODEL} <= set(STORM_FORCE_MODELS)


def test_bad_targets_and_process_counts_are_named_errors():
    with pytest.raises(InputError, match="targets = 'nope'"):
        warm_kernels(["nope"])
    with pytest.raises(InputError, match="processes = 0"):
        warm_kernels(["section"], processes=0)


def test_two_worker_processes_run_two_targets():
    calls = []
    report = warm_kernels(
        ["section", "storm-rock"], processes=2, progress=lambda k, n, t: calls.append((k, n))
    )
    assert report.processes == 2
    assert sorted(t.target.name for t in report.targets) == ["section", "storm-rock"]
    assert calls == [(1, 2), (2, 2)]
    assert all(t.wall_s > 0 and t.compiled >= 0 for t in report.targets)


def test_estimate_deals_the_measured_targets_to_the_processes():
    """Hand calculation from the table: one process runs the targets one after the other; two
    take the next target as each finishes, after their start."""
    cpu_of = {t.name: t.cpu_s for t in TARGETS}
    cpu, wall, workers = estimate(["section", "storm-rock"], processes=1)
    assert workers == 1
    assert cpu == pytest.approx(cpu_of["section"] + cpu_of["storm-rock"]) == wall
    cpu, wall, workers = estimate(["pipeline", "storm-sand", "section"], processes=2)
    p, s, c = cpu_of["pipeline"], cpu_of["storm-sand"], cpu_of["section"]
    assert workers == 2 and cpu == pytest.approx(p + s + c + 2 * WORKER_START_S)
    # the second process runs storm-sand then section while the first runs the pipeline
    assert wall == pytest.approx(WORKER_START_S + max(p, s + c))
    assert estimate(["section"], processes=4)[2] == 1  # never more processes than targets
    assert all(t.cpu_s > 0 for t in TARGETS)


def test_cli_help_lists_the_targets():
    res = CliRunner().invoke(cli, ["warmup", "--help"])
    assert res.exit_code == 0
    for t in TARGETS:
        assert t.name in res.output


def test_cli_runs_one_target_with_json(capsys):
    code = main(["warmup", "--only", "section", "--processes", "1", "--json"])
    captured = capsys.readouterr()
    assert code == 0
    out = json.loads(captured.out)
    assert out["schema_version"] == SCHEMA_VERSION
    assert set(out) == documented_keys("warmup")
    (row,) = out["targets"]
    assert set(row) == documented_keys("warmup", "targets[]")
    assert row["name"] == "section" and out["processes"] == 1
    assert "compiling centrifuge-section kernel" in captured.err and "(1/1)" in captured.err
    # the duration is said before anything compiles
    first = captured.err.splitlines()[0]
    assert first.startswith("onbottom warmup: compiling 1 kernel group on 1 process: about")
    assert "CPU-s" in first and "free cores" in first


def test_cli_quiet_prints_the_totals_only(capsys):
    code = main(["warmup", "--only", "section", "--processes", "1", "--quiet"])
    captured = capsys.readouterr()
    assert code == 0 and captured.err == ""
    assert "warm-up done: 1 kernel group in" in captured.out


@pytest.mark.parametrize("processes", ["1", "2"])
def test_ctrl_c_during_warmup_exits_130_with_one_line(tmp_path, processes):
    """Ctrl-C after the first progress line, while numba compiles (in this process, where LLVM's
    ctypes callbacks would swallow it, or in pool workers): exit 130, one line, no traceback."""
    import os
    import signal
    import subprocess
    import sys
    import time

    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}  # nothing cached: compiles
    cmd = [sys.executable, "-m", "onbottom", "warmup", "--only", "pipeline",
           "--only", "storm-sand", "--processes", processes]  # fmt: skip
    p = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first = p.stderr.readline()
        assert first.startswith("onbottom warmup: compiling")
        time.sleep(1.5)  # inside the compile
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 130, err
    assert "Traceback" not in err and "Exception ignored" not in err
    lines = [x for x in err.splitlines() if x.strip()]
    assert lines[-1].startswith("interrupted") and "warmup again" in lines[-1]
    assert not [x for x in lines if not x.startswith(("onbottom warmup: compiling", "interrupted"))]
