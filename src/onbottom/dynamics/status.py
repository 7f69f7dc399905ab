"""The time-domain solvers' view of the one status enumeration, :mod:`onbottom.status`.

Re-exported here because the solvers and their kernels (``STATUS_*`` constants) are where the
codes are made; the enumeration itself is a base module so that the closed-form solves below
``dynamics`` (F114 embedment, the F109 design solve, the LAMMPS run) report with it too.
"""

from __future__ import annotations

from onbottom.status import (
    EXIT_INVALID_RESULT,
    EXIT_OK,
    MESSAGES,
    Status,
    exit_code,
    status_message,
)

__all__ = [
    "EXIT_INVALID_RESULT",
    "EXIT_OK",
    "MESSAGES",
    "Status",
    "exit_code",
    "status_message",
]
