"""Unit test: one status enumeration for every solver, mapped once to the CLI exit codes."""

from __future__ import annotations

import pytest

from onbottom.cli._common import EXIT_INVALID_RESULT
from onbottom.dynamics import _section_kernel as SK
from onbottom.dynamics import _storm_kernel as TK
from onbottom.dynamics import status as S
from onbottom.dynamics.pipeline import _pipeline_kernel as PK
from onbottom.dynamics.status import Status, exit_code


def test_numbers_kept_from_0_1_where_the_solvers_agreed():
    # 1, 2, -1, -2: all solvers; 3 lift-off (storm), -3 outside validity, -4 singular (pipeline)
    assert [Status.END, Status.LIMIT, Status.LIFTOFF] == [1, 2, 3]
    assert [Status.STEP_FAILED, Status.SOIL_NAN, Status.OUTSIDE_VALIDITY] == [-1, -2, -3]
    assert Status.SINGULAR == -4 and Status.RAISED == -9


@pytest.mark.parametrize("kernel", [SK, TK, PK], ids=["section", "storm", "pipeline"])
def test_every_kernel_uses_the_enumeration(kernel):
    names = [n for n in dir(kernel) if n.startswith("STATUS_")]
    assert names
    for name in names:
        assert getattr(kernel, name) == Status[name.removeprefix("STATUS_")], name


def test_exit_codes():
    assert S.EXIT_INVALID_RESULT == EXIT_INVALID_RESULT == 3
    ok = {Status.END, Status.LIMIT, Status.LIFTOFF, Status.RUNAWAY_END}
    ok |= {Status.CONVERGED, Status.AT_BOUND}
    for st in Status:
        assert exit_code(st) == (0 if st in ok else 3), st
        assert st.success == (st in ok)
    assert exit_code(42) == 3  # an unknown number is not a valid result


def test_one_message_per_status():
    assert set(S.MESSAGES) == set(Status)
    assert len(set(S.MESSAGES.values())) == len(Status)  # no two statuses read alike
    assert S.status_message(Status.END, run="storm") == "reached the end of the storm"
    assert S.status_message(2, "10D at t = 812.4 s") == (
        "runaway: stopped at the displacement limit (10D at t = 812.4 s)"
    )
    # the reason of an outside-validity flag follows a colon; an unknown number still reads
    assert S.status_message(-3, "lift-off").startswith("outside the model's validity: lift-off")
    assert S.status_message(42) == "status 42"


def test_docs_table_is_the_message_table():
    from pathlib import Path

    text = (Path(__file__).parents[2] / "docs" / "conventions.md").read_text(encoding="utf-8")
    rows = [r for r in text.splitlines() if r.startswith("| ") and "| `" in r]
    seen = {}
    for r in rows:
        cells = [c.strip() for c in r.strip("|").split("|")]
        if len(cells) == 5 and cells[1].strip("`") in Status.__members__:
            seen[Status[cells[1].strip("`")]] = (cells[3], int(cells[4]))
    internal = {Status.CHUNK, Status.BUFFER_FULL}
    assert set(seen) == set(Status) - internal
    for st, (message, exit_status) in seen.items():
        assert message == S.MESSAGES[st] and exit_status == st.exit_code, st


def test_one_enumeration_for_every_solver():
    """The closed-form solves report with the same Status (base module onbottom.status, which
    dynamics.status re-exports): positive is success, negative failure, never a bare 0."""
    import onbottom.status as base

    assert S.Status is base.Status and S.MESSAGES is base.MESSAGES
    assert [Status.CONVERGED, Status.AT_BOUND] == [6, 7]
    assert [Status.NOT_CONVERGED, Status.NO_SOLUTION] == [-5, -6]
    for st in Status:
        if st not in {Status.CHUNK, Status.BUFFER_FULL}:
            assert st.success == (st > 0), st


def test_no_solver_result_reports_success_as_zero():
    """Every result class with ``success`` and ``status`` annotates ``status`` as Status."""
    import dataclasses
    import typing

    from onbottom.calibration.fit import CalibrationResult
    from onbottom.checks.design import DesignResult
    from onbottom.dem.lammps_run import LammpsResult
    from onbottom.soil.penetration_f114 import EmbedmentResult

    for cls in (DesignResult, LammpsResult, EmbedmentResult, CalibrationResult):
        hints = typing.get_type_hints(cls)
        names = {f.name for f in dataclasses.fields(cls)}
        assert {"success", "status"} <= names and hints["status"] is Status, cls
