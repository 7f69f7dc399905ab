"""Checks shared by the settings of the three time-domain solvers: time steps, the Newton
iteration and the chunks (:class:`~onbottom.dynamics.section.SolverSettings`,
:class:`~onbottom.dynamics.storm_section.StormSolverSettings`,
:class:`~onbottom.dynamics.pipeline.PipelineSettings`)."""

from __future__ import annotations

from onbottom._validate import in_range, integer, positive
from onbottom.errors import InputError


def check_steps(owner: str, dt_max: float | None, dt_min: float | None) -> None:
    """``dt_max`` [s] > 0 (None: the solver's default), ``dt_min`` [s] > 0 and <= dt_max."""
    if dt_max is not None:
        positive(f"{owner}.dt_max", dt_max)
    if dt_min is not None:
        positive(f"{owner}.dt_min", dt_min)
        if dt_max is not None and dt_min > dt_max:
            raise InputError(
                f"{owner}.dt_min = {dt_min!r} is invalid: must be <= dt_max = {dt_max!r}"
            )


def check_newton(
    owner: str,
    force_tolerance: float,
    tolerance_max: float,
    max_iterations: int,
    min_iterations: int,
) -> None:
    """``force_tolerance`` [-] in (0, tolerance_max]; ``max_iterations`` a whole number >=
    ``min_iterations``."""
    in_range(f"{owner}.force_tolerance", force_tolerance, 0.0, tolerance_max, low_inclusive=False)
    integer(f"{owner}.max_iterations", max_iterations, min_iterations)


def check_chunks(owner: str, chunks: int) -> None:
    """``chunks`` (progress updates per run) a whole number >= 1."""
    integer(f"{owner}.chunks", chunks, 1)
