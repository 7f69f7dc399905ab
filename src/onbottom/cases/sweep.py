"""Sweep grid files (TOML) for ``onbottom sweep``: a parametric sweep of a registered function.

Grid file (see ``examples/sweep_grid.toml``)::

    [sweep]
    function = "centrifuge_response"   # a registered function name
    seed = 1                           # optional: per-point random streams
    batch_size = 2                     # optional: runs per Dask task

    [grid]                             # one dimension per entry, in this order
    A = [0.15, 0.25, 0.35]
    B = { start = 0.2, stop = 0.5, num = 4 }     # numpy.linspace
    mu = { values = [0.48, 0.85] }

    [fixed]                            # keyword arguments passed to every run
    test = "Inclined 1"

Functions: only those registered by name in :mod:`onbottom.study.functions` —
``centrifuge_response`` (:func:`onbottom.study.functions.centrifuge_response`), ``misfit``
(:func:`onbottom.calibration.fit.record_misfit`; ``[fixed] record = "path"`` is loaded as a
:class:`~onbottom.calibration.records.TestRecord`, relative to the grid file) and any a user
registers from Python (``onbottom.study.functions.register``). A grid file never imports code.

The file is checked against a strict schema (unknown tables or keys are errors with the line
and a did-you-mean), and the grid and fixed names against the function's arguments
(:func:`read_grid`); its result is what :func:`onbottom.study.sweep.sweep` takes.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Annotated, Any

import numpy as np
from pydantic import Field

from onbottom._casefile import CaseFileError, StrictModel, parse_case, read_toml

__all__ = [
    "MAX_POINTS",
    "GridFile",
    "LinspaceAxis",
    "SweepTable",
    "ValuesAxis",
    "read_grid",
    "resolve_function",
]

_Scalar = bool | int | float | str


class SweepTable(StrictModel):
    """``[sweep]``: the function (a registered name) and run options."""

    function: str = Field(description="registered function name")
    seed: Annotated[int, Field(ge=0)] | None = None
    batch_size: Annotated[int, Field(ge=1, le=1_000_000)] | None = None


class ValuesAxis(StrictModel):
    """``name = { values = [...] }``."""

    values: list[_Scalar] = Field(min_length=1, max_length=100_000)


class LinspaceAxis(StrictModel):
    """``name = { start, stop, num }`` (numpy.linspace)."""

    start: float
    stop: float
    num: Annotated[int, Field(ge=1, le=100_000)]


class GridFile(StrictModel):
    """Schema of a sweep grid file."""

    sweep: SweepTable
    grid: dict[str, Any] = Field(min_length=1)
    fixed: dict[str, _Scalar] = Field(default_factory=dict)


MAX_POINTS = 10_000_000
"""Largest number of grid points a sweep file may ask for."""


def resolve_function(spec: str):
    """The registered sweep function ``spec`` (never imports code named in a file)."""
    import onbottom.calibration.fit  # noqa: F401 - registers "misfit"
    from onbottom.study.functions import get_function

    return get_function(spec)


def _axis(name: str, spec: Any, file: Path, text: str) -> list[Any]:
    field = f"grid.{name}"
    if isinstance(spec, list):
        values = spec
        if not values:
            raise CaseFileError(
                f"{file}: {field} is invalid: empty list", field=field, file=str(file)
            )
    elif isinstance(spec, Mapping):
        model = LinspaceAxis if "values" not in spec else ValuesAxis
        axis = parse_case(model, spec, file=file, text=text, root=field)
        if isinstance(axis, ValuesAxis):
            values = list(axis.values)
        else:
            values = np.linspace(axis.start, axis.stop, axis.num).tolist()
    else:
        raise CaseFileError(
            f"{file}: {field} = {spec!r} is invalid: expected a list, {{values = [...]}} or"
            " {start, stop, num}",
            field=field,
            file=str(file),
        )
    for i, v in enumerate(values):
        if isinstance(v, (list, dict)) or (isinstance(v, float) and not np.isfinite(v)):
            raise CaseFileError(
                f"{file}: {field}[{i}] = {v!r} is invalid: expected a finite number or a string",
                field=f"{field}[{i}]",
                file=str(file),
            )
    return values


def read_grid(path: str | Path) -> dict[str, Any]:
    """Parse and check a grid TOML file into ``function``, ``grid``, ``fixed`` and options."""
    from onbottom.study.functions import check_arguments

    p = Path(path)
    doc, text = read_toml(p)
    spec = parse_case(GridFile, doc, file=p, text=text)
    fn = resolve_function(spec.sweep.function)
    grid = {k: _axis(k, v, p, text) for k, v in spec.grid.items()}
    n_points = int(np.prod([len(v) for v in grid.values()], dtype=float))
    if n_points > MAX_POINTS:
        raise CaseFileError(
            f"{p}: grid is invalid: {n_points} points, more than the {MAX_POINTS} allowed",
            field="grid",
            file=str(p),
        )
    fixed = dict(spec.fixed)
    check_arguments(fn, list(grid), where="grid")
    check_arguments(fn, list(fixed), where="fixed")
    if spec.sweep.function == "misfit":
        from onbottom._casefile import resolve_path
        from onbottom.calibration.records import load_record

        if "record" not in fixed:
            raise CaseFileError(
                f"{p}: fixed.record is missing: function 'misfit' needs [fixed] record = 'path'",
                field="fixed.record",
                file=str(p),
            )
        fixed["record"] = load_record(
            resolve_path(str(fixed["record"]), relative_to=p, field="fixed.record")
        )
    return {
        "function": fn,
        "function_name": spec.sweep.function,
        "grid": grid,
        "fixed": fixed,
        "seed": spec.sweep.seed,
        "batch_size": spec.sweep.batch_size,
    }
