"""One status enumeration for every solver that reports success, and its CLI exit codes.

The centrifuge section (:func:`onbottom.dynamics.section.simulate_section`), the storm section
(:func:`onbottom.dynamics.storm_section.simulate_storm_section`) and the pipeline FE
(:func:`onbottom.dynamics.pipeline.simulate_pipeline`) return, and write in their result files
(attribute ``status``), one of the codes below; their numba kernels use the same numbers
(``STATUS_*`` module constants taken from :class:`Status`). Positive: the run ended normally
(a physical outcome); zero and 4: internal (a chunk or the record buffer ended, never
returned); negative: the run failed or left its model's validity (its numbers are kept but
not valid). The closed-form solves that iterate use the same enumeration: the F114 embedment
(:func:`onbottom.soil.penetration_f114.solve_embedment`: :attr:`Status.CONVERGED` or
:attr:`Status.NOT_CONVERGED`), the F109 design solve (:class:`onbottom.checks.design.DesignResult`:
:attr:`Status.CONVERGED`, :attr:`Status.AT_BOUND`; :attr:`Status.NO_SOLUTION` in the stability
evaluation's design table), the dynamic design search of the route assessment
(:func:`onbottom.assess.dynamic.search_dynamic`: the same three), the calibration
(:class:`onbottom.calibration.fit.CalibrationResult`: ``CONVERGED``, ``NOT_CONVERGED``,
``NO_SOLUTION``) and the LAMMPS run
(:class:`onbottom.dem.lammps_run.LammpsResult`: :attr:`Status.END` or :attr:`Status.RAISED`).
A result's ``success`` is ``status.success``.
Table: docs/conventions.md, "Solver status". This is a base module (every package may import
it); :mod:`onbottom.dynamics.status` re-exports it for the time-domain solvers.

Every solver and the CLI word a run's end through one table, :data:`MESSAGES`, and
:func:`status_message`: the line of the status, then the solver's detail (which limit, where
and when) in parentheses — after a colon for :attr:`Status.OUTSIDE_VALIDITY`.

"Ran on until the pipe stopped" (the centrifuge section) is 5, apart from 3, "lift-off".
"""

from __future__ import annotations

from collections.abc import Mapping
from enum import IntEnum
from types import MappingProxyType

__all__ = [
    "EXIT_INVALID_RESULT",
    "EXIT_OK",
    "MESSAGES",
    "Status",
    "exit_code",
    "status_message",
]

EXIT_OK = 0
"""CLI exit status of a valid result."""

EXIT_INVALID_RESULT = 3
"""CLI exit status of a result that is not valid (a failed run or one outside its model's
validity); equals :data:`onbottom.cli._common.EXIT_INVALID_RESULT`."""


class Status(IntEnum):
    """Outcome of a time-domain run (an ``int``: compares equal to its value).

    ========  =================  ==========================================================
    code      name               meaning
    ========  =================  ==========================================================
    0         CHUNK              internal: the chunk ended (``t_stop``), go on
    1         END                ran to the end of the load programme / storm
    2         LIMIT              stopped at the displacement limit (runaway, terminal event)
    3         LIFTOFF            storm section: lift-off, the run stopped (``liftoff="stop"``)
    4         BUFFER_FULL        internal: the record buffer is full, grow it and go on
    5         RUNAWAY_END        centrifuge section: reached the limit, ran on until the pipe
                                 stopped (``after_limit="runaway_end"``)
    6         CONVERGED          an iterative solve converged (F114 embedment, design solve)
    7         AT_BOUND           design solve: the lower bound of the range already passes
    −1        STEP_FAILED        a time step did not converge at the smallest step
    −2        SOIL_NAN           a soil kernel returned NaN (unknown model id, invalid state)
    −3        OUTSIDE_VALIDITY   the run left its model's validity (penetration > D/2,
                                 lift-off in a centrifuge programme); numbers kept
    −4        SINGULAR           pipeline: the Jacobian became singular (a mechanism)
    −5        NOT_CONVERGED      an iterative solve did not converge (last iterate returned)
    −6        NO_SOLUTION        design solve: no value in the range passes; calibration:
                                 every simulation failed at the fitted parameters
    −9        RAISED             a run of a study raised an exception (seeds, campaigns)
    ========  =================  ==========================================================
    """

    CHUNK = 0
    END = 1
    LIMIT = 2
    LIFTOFF = 3
    BUFFER_FULL = 4
    RUNAWAY_END = 5
    CONVERGED = 6
    AT_BOUND = 7
    STEP_FAILED = -1
    SOIL_NAN = -2
    OUTSIDE_VALIDITY = -3
    SINGULAR = -4
    NOT_CONVERGED = -5
    NO_SOLUTION = -6
    RAISED = -9

    @property
    def success(self) -> bool:
        """True for a normal end (END, LIMIT, LIFTOFF, RUNAWAY_END, CONVERGED, AT_BOUND)."""
        return self in _SUCCESS

    @property
    def exit_code(self) -> int:
        """The CLI exit status of a run ending with this status (:func:`exit_code`)."""
        return EXIT_OK if self.success else EXIT_INVALID_RESULT


_SUCCESS = frozenset(
    {
        Status.END,
        Status.LIMIT,
        Status.LIFTOFF,
        Status.RUNAWAY_END,
        Status.CONVERGED,
        Status.AT_BOUND,
    }
)

MESSAGES: Mapping[Status, str] = MappingProxyType(
    {
        Status.CHUNK: "internal: the chunk ended",
        Status.END: "reached the end of the {run}",
        Status.LIMIT: "runaway: stopped at the displacement limit",
        Status.LIFTOFF: "lift-off: the lift exceeded the submerged weight, the run stopped",
        Status.BUFFER_FULL: "internal: the record buffer is full",
        Status.RUNAWAY_END: "runaway: reached the displacement limit, ran on until the pipe"
        " stopped",
        Status.CONVERGED: "converged",
        Status.AT_BOUND: "the lower bound of the range already passes",
        Status.STEP_FAILED: "a time step did not converge at the smallest step",
        Status.SOIL_NAN: "a soil kernel returned NaN (unknown model id or invalid state)",
        Status.OUTSIDE_VALIDITY: "outside the model's validity",
        Status.SINGULAR: "the Jacobian became singular (a mechanism: check the end conditions)",
        Status.NOT_CONVERGED: "the iteration did not converge (the last iterate is returned)",
        Status.NO_SOLUTION: "no value in the range is a solution",
        Status.RAISED: "the run raised an exception",
    }
)
"""The one line of each :class:`Status` (docs/conventions.md, "Solver status"); ``{run}`` is
what the run went through: "load programme" (centrifuge section) or "storm"."""


def status_message(status: int, detail: str = "", *, run: str = "run") -> str:
    """The one-line message of a run that ended with ``status`` (:data:`MESSAGES`).

    Parameters
    ----------
    status : int
        A :class:`Status` code (an unknown number reads "status N").
    detail : str
        What only the solver knows: which limit, when, where (``"10D at t = 812.4 s"``);
        appended in parentheses, or after a colon for :attr:`Status.OUTSIDE_VALIDITY` (the
        detail is then the reason).
    run : str
        What the run went through, for :attr:`Status.END`: "load programme" or "storm".
    """
    try:
        st = Status(int(status))
    except ValueError:
        base = f"status {int(status)}"
    else:
        base = MESSAGES[st].format(run=run)
        if detail and st == Status.OUTSIDE_VALIDITY:
            return f"{base}: {detail}"
    return f"{base} ({detail})" if detail else base


def exit_code(status: int) -> int:
    """CLI exit status of a run that ended with ``status``: 0 valid, 3 not valid.

    Every command that runs a solver maps its status through here (docs/conventions.md).
    An unknown number counts as not valid.
    """
    try:
        return Status(int(status)).exit_code
    except ValueError:
        return EXIT_INVALID_RESULT
