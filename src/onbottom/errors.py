"""Exceptions and warnings shared by every onbottom package.

* :class:`InputError` — an input value is invalid. It names the field, the value and the
  allowed range. Subclass of :class:`ValueError` so generic handlers still catch it.
* :class:`OutOfRangeWarning` — a value lies outside the calibration range of an empirical
  correlation. The computation goes on; the message gives the range and the source.
* :class:`SolutionError` — an equation has no solution in the admissible interval (for example
  no embedment ``0 < z <= D`` balances the applied load).
* :class:`PhysicalConsistencyWarning` (an :class:`OutOfRangeWarning`) — inputs that are each
  valid but unusual together or for the physics (shallow water against the pipe, a current
  faster than 3 m/s, a layer lighter than water); its subclasses :class:`ShallowWaterWarning`
  and :class:`UnitSlipWarning` (a value that looks typed in another unit: radians for degrees).
* :class:`BudgetError` — a run's estimated time or memory exceeds the stated budget (an
  :class:`InputError`; ``--force`` runs it anyway).
"""

from __future__ import annotations

__all__ = [
    "BudgetError",
    "InputError",
    "OnbottomError",
    "OutOfRangeWarning",
    "PhysicalConsistencyWarning",
    "ResultFileError",
    "RunInterrupted",
    "ShallowWaterWarning",
    "SolutionError",
    "UnitSlipWarning",
]


class OnbottomError(Exception):
    """Base class of every error raised on purpose by onbottom."""


class InputError(OnbottomError, ValueError):
    """An input value is invalid (wrong sign, outside its physical range, wrong type)."""


class SolutionError(OnbottomError, RuntimeError):
    """A requested solution does not exist within the admissible interval."""


class OutOfRangeWarning(UserWarning):
    """A value lies outside the range over which an empirical correlation was calibrated."""


class PhysicalConsistencyWarning(OutOfRangeWarning):
    """Inputs valid one by one but physically unusual together (see ``inputs/consistency.py``)."""


class ShallowWaterWarning(PhysicalConsistencyWarning):
    """The water is shallow against the pipe (depth < 3 D) or the sea state is near breaking."""


class UnitSlipWarning(PhysicalConsistencyWarning):
    """A value looks typed in another unit (radians in a ``_deg`` key, MPa for Pa, …)."""


class BudgetError(InputError):
    """The estimated run time or memory of a run exceeds the stated budget (``--force``)."""


class ResultFileError(InputError):
    """A result, partial-result or checkpoint file cannot be trusted: unreadable (corrupt,
    truncated, not a result), marked ``run_status = "partial"`` (an interrupted run), or
    written by another run (its run identity differs). The message names the file and, where
    a run writes it, says how to start afresh (``--restart``); ``field`` names the option or
    file at fault ("output", "checkpoint") or is None."""

    def __init__(self, message: str, *, field: str | None = None) -> None:
        super().__init__(message)
        self.field = field


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) stopped a run; the message says what was kept and how to resume.

    A subclass of :class:`KeyboardInterrupt`, so code that lets interrupts through still
    does; the command line turns it into one line on stderr and exit status 130.
    """
