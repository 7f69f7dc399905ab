"""The result base of every time-domain solver (like scipy's ``OdeResult``).

:class:`SolverResult` carries what every run returns — ``success``, ``status`` (a
:class:`~onbottom.dynamics.status.Status` code), ``message`` and ``data`` (an xarray Dataset
whose attributes hold the provenance: :func:`onbottom.results.provenance`) — and
:class:`~onbottom.dynamics.section.SectionResult`,
:class:`~onbottom.dynamics.storm_section.StormSectionResult` and
:class:`~onbottom.dynamics.pipeline.PipelineResult` derive from it, adding their own summary.

Shared by the three: :func:`run_outcome` words a run's end (the one table
:data:`onbottom.dynamics.status.MESSAGES`), flags a run that left its model's validity and logs
a failed or flagged run; :func:`penetration_limit` and :func:`penetration_reason` are the D/2
rule; :func:`dynamic_criteria` the F109 criteria.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr

from onbottom.dynamics.status import Status, exit_code, status_message
from onbottom.errors import InputError
from onbottom.results import annotate, save_dataset

__all__ = [
    "CRITERIA_OVER_D",
    "SolverResult",
    "dynamic_criteria",
    "penetration_limit",
    "penetration_reason",
    "records_dataset",
    "run_outcome",
]

CRITERIA_OVER_D: dict[str, float] = {"0.5D": 0.5, "10D": 10.0}
"""F109 dynamic lateral-stability criteria (DNV-RP-F109 §3.5; spec "Dynamic criteria"):
lateral displacement limits over D — 0.5D "virtually stable", 10D."""


@dataclass(frozen=True, kw_only=True)
class SolverResult:
    """What every time-domain run returns.

    Attributes
    ----------
    success : bool
        True if the run ended normally and its result is valid (:attr:`Status.success`, and
        not outside its model's validity).
    status : int
        A :class:`~onbottom.dynamics.status.Status` code (docs/conventions.md).
    message : str
        One line: how the run ended.
    data : xarray.Dataset or None
        The records with their provenance attributes (None when a run keeps none).
    """

    success: bool
    status: int
    message: str
    data: xr.Dataset | None = None

    @property
    def outcome(self) -> Status:
        """:attr:`status` as a :class:`~onbottom.dynamics.status.Status` member."""
        return Status(int(self.status))

    @property
    def exit_code(self) -> int:
        """The CLI exit status of this run (0 valid, 3 not valid)."""
        return exit_code(self.status)

    @property
    def provenance(self) -> dict[str, Any]:
        """The provenance attributes of :attr:`data` (empty without records)."""
        return {} if self.data is None else dict(self.data.attrs)

    def save(self, path: Any, *, compression_level: int = 0) -> Any:
        """Write :attr:`data` to NetCDF (atomically, :func:`onbottom.results.save_dataset`);
        ``compression_level`` 0 (none) to 9 (zlib)."""
        if self.data is None:
            raise InputError(f"{type(self).__name__}.data = None: run with record_interval set")
        return save_dataset(self.data, path, compression_level=compression_level)


def run_outcome(
    logger: logging.Logger,
    status: int,
    *,
    run: str,
    t: float,
    dt_min: float,
    detail: str = "",
    outside: str | None = None,
) -> tuple[bool, int, str]:
    """``(success, status, message)`` of a run that ended with ``status``, worded by
    :func:`~.status.status_message` (the one table, :data:`~.status.MESSAGES`).

    Parameters
    ----------
    logger : logging.Logger
        The solver module's logger: a failed or flagged run is logged there as a warning (its
        message); solvers never print.
    status : int
        The kernel's final :class:`~.status.Status`.
    run : str
        What the run went through ("load programme", "storm").
    t, dt_min : float
        Time reached and smallest step [s]: the detail of a failed run.
    detail : str
        The detail of a normal end (which limit, when, where).
    outside : str or None
        Why the run left its model's validity (:func:`penetration_reason`, lift-off), or None.
        A run that ended normally is then flagged :attr:`~.status.Status.OUTSIDE_VALIDITY`:
        "outside the model's validity: ``outside`` (the run went on: <its message>)".
    """
    success = Status(int(status)).success
    if not success:
        message = status_message(status, f"t = {t:.6g} s, dt_min = {dt_min:.3g} s", run=run)
        logger.warning("%s", message)
        return False, int(status), message
    message = status_message(status, detail, run=run)
    if outside is None:
        return True, int(status), message
    status = Status.OUTSIDE_VALIDITY
    message = status_message(status, f"{outside} (the run went on: {message})")
    logger.warning("%s", message)
    return False, int(status), message


def penetration_reason(
    limit: float,
    t: float,
    where: str,
    largest: float,
    diameter: float,
    model: str,
    largest_at: str = "",
) -> str:
    """Why a run left its soil model's range (``outside`` of :func:`run_outcome`).

    The penetration exceeded D/2 = ``limit`` [m] first at time ``t`` [s] and place ``where``
    (text: "y = 0.2 m", "node 12, x = 24 m"); the largest was ``largest`` [m] (D =
    ``diameter`` [m]), at ``largest_at`` (text, optional); ``model`` names the soil model(s)
    valid for z <= D/2 ("the verley_sotberg model").
    """
    at = f" at {largest_at}" if largest_at else ""
    return (
        f"penetration exceeded D/2 = {limit:.4g} m at t = {t:.1f} s ({where}); largest"
        f" {largest:.4g} m = {largest / diameter:.3g}D{at}; {model} valid for z <= D/2"
    )


def dynamic_criteria(
    max_displacement: float, diameter: float, stop_over_d: float | None, stopped: bool
) -> dict[str, bool]:
    """The F109 dynamic criteria (:data:`CRITERIA_OVER_D`) of a run: met when the largest
    displacement [m] is within the limit × D [m] and the run did not stop as a runaway at a
    stop limit ``stop_over_d`` [-] at or below it (the displacement would have grown on)."""
    return {
        name: bool(
            max_displacement <= lim * diameter
            and not (stopped and stop_over_d is not None and stop_over_d <= lim)
        )
        for name, lim in CRITERIA_OVER_D.items()
    }


def penetration_limit(soil: Any, diameter: float | None = None) -> float:
    """Penetration [m] beyond which a soil model is used outside its range (∞: no limit).

    D/2 for the models that carry the pipe diameter (Verley & Sotberg: the power laws in z/D
    are used for a pipe at most half buried, :data:`onbottom.soil.verley_sotberg`
    ``Z_OVER_D_RANGE``; Verley & Lund likewise); none for Coulomb friction. ``diameter``
    [m]: D to use (default: the model's own); the rule of the three solvers.
    """
    d = getattr(soil, "outer_diameter", None)
    if d is None:
        return math.inf
    return 0.5 * float(d if diameter is None else diameter)


def records_dataset(
    rows: np.ndarray, columns: Mapping[str, int], time_column: int, attrs: Mapping[str, Any]
) -> xr.Dataset:
    """The records of a section run (rows × columns of its kernel) as a Dataset over time:
    variable ``name`` from column ``columns[name]``, the time from ``time_column``, the
    provenance ``attrs``; long names and units from :func:`onbottom.results.annotate`."""
    ds = xr.Dataset(
        {k: ("time", np.ascontiguousarray(rows[:, i])) for k, i in columns.items()},
        coords={"time": np.ascontiguousarray(rows[:, time_column])},
        attrs=dict(attrs),
    )
    return annotate(ds)
