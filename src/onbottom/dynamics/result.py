"""The result base of every time-domain solver (like scipy's ``OdeResult``).

:class:`SolverResult` carries what every run returns — ``success``, ``status`` (a
:class:`~onbottom.dynamics.status.Status` code), ``message`` and ``data`` (an xarray Dataset
whose attributes hold the provenance: :func:`onbottom.results.provenance`) — and
:class:`~onbottom.dynamics.section.SectionResult`,
:class:`~onbottom.dynamics.storm_section.StormSectionResult` and
:class:`~onbottom.dynamics.pipeline.PipelineResult` derive from it, adding their own summary.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import xarray as xr

from onbottom.dynamics.status import Status, exit_code
from onbottom.errors import InputError
from onbottom.results import save_dataset

__all__ = ["SolverResult"]


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
