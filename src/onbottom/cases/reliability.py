"""Reliability case files: a storm case (``onbottom storm``'s tables) with a ``[reliability]``
table (``examples/reliability_case.toml``).

``[reliability]`` (strict; SI unless a key says otherwise):

* ``limits``: displacement limits, each ``"0.5D"``-style (a multiple of the pipe's outer
  diameter) or a number of metres (default ``["0.5D", "10D"]``);
* ``method``: ``"importance"`` (default: chosen by a coverage test), ``"subset"`` or
  ``"monte_carlo"``; ``form_storms`` (storms per iteration of importance sampling's pilot);
  ``target_cv`` (default 0.1), ``max_storms`` (per limit), ``block_size`` (storms per block /
  per subset level),
  ``task_size`` (storms per Dask task), ``seed`` (openturns' generator);
* ``storms_per_year`` (λ; required without a climate), ``design_life_years``,
  ``safety_class`` (``"low"``, ``"medium"`` (default) or ``"high"``: the DNV-OS-F101 target
  annual failure probability the estimates are compared with);
* ``[reliability.climate]``: ``hindcast`` (CSV/NetCDF, relative to the case file),
  ``sectors`` (1: omnidirectional, waves from the case's direction), ``pipe_heading_deg``,
  ``storm_rate`` (the POT threshold's target storms per year), ``current`` (true: the current
  speed is drawn with the sea state from the hindcast's current model, U | H_s,
  :mod:`onbottom.metocean.current`; then ``current_velocity`` is not an input): the sea state
  (H_s, T_p, sector, current) is drawn from
  :class:`~onbottom.reliability.climate.StormClimate`;
* ``[reliability.inputs]``: ``name = number`` or ``name = {distribution = ..., ...}`` for
  ``hs``, ``tp`` (without a climate), ``direction_deg``, ``current_velocity``,
  ``current_direction_deg``, ``friction_coefficient``, ``submerged_unit_weight``;
* ``[reliability.design]`` (needs a climate): ``return_period`` [years], ``contour_points``,
  ``seeds`` per contour point, ``top_points`` and ``top_seeds`` (the highest-response points
  rerun with more seeds), ``fractile`` of the design displacement
  (:mod:`onbottom.reliability.design`).

:func:`load_reliability_case` reads such a file and builds the plain
:class:`~onbottom.reliability.setup.ReliabilitySetup` that
:func:`onbottom.reliability.run.run_reliability` takes (the limits in metres, the hindcast
path resolved against the case file's folder).
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any, Literal

from pydantic import Field

from onbottom._casefile import CaseFileError, StrictModel, parse_case, read_json, read_toml
from onbottom.reliability.distributions import parameter_from_table
from onbottom.reliability.setup import ClimateSettings, ContourDesign, ReliabilitySetup

__all__ = ["ReliabilityCase", "ReliabilitySetup", "load_reliability_case", "parse_limit"]


class ClimateTable(StrictModel):
    hindcast: str = Field(min_length=1, description="hindcast CSV/NetCDF, relative to the case")
    sectors: int = Field(1, ge=1, le=36, description="direction sectors [-]")
    pipe_heading_deg: float = Field(0.0, ge=0.0, le=360.0, description="[deg from north]")
    storm_rate: float = Field(3.0, ge=0.5, le=50.0, description="target storms per year")
    current: bool = Field(False, description="current speed from the hindcast's joint model")


class DesignTable(StrictModel):
    return_period: float = Field(100.0, ge=1.0, le=1.0e4, description="[years]")
    contour_points: int = Field(12, ge=4, le=360, description="IFORM contour points [-]")
    seeds: int = Field(2, ge=1, le=1000, description="seeds per contour point [-]")
    top_points: int = Field(2, ge=1, le=360, description="points rerun with more seeds [-]")
    top_seeds: int = Field(8, ge=1, le=10000, description="seeds at those points [-]")
    fractile: float = Field(0.9, gt=0.0, lt=1.0, description="design fractile [-]")


class ReliabilityTable(StrictModel):
    limits: list[str | float] = Field(default_factory=lambda: ["0.5D", "10D"])
    method: Literal["subset", "importance", "monte_carlo"] = "importance"
    target_cv: float = Field(0.1, gt=0.0, le=1.0)
    max_storms: int = Field(5000, ge=10, le=10**9, description="storms per limit [-]")
    block_size: int = Field(200, ge=10, le=10**6, description="storms per block / level")
    task_size: int = Field(4, ge=1, le=10**4, description="storms per Dask task")
    seed: int = Field(0, ge=0, le=2**32 - 1)
    storms_per_year: float | None = Field(None, gt=0.0, le=1.0e4, description="[1/year]")
    design_life_years: float = Field(25.0, gt=0.0, le=1.0e4, description="[years]")
    safety_class: Literal["low", "medium", "high"] = "medium"
    form_storms: int = Field(150, ge=10, le=10**5, description="pilot storms per iteration")
    climate: ClimateTable | None = None
    inputs: dict[str, float | dict[str, Any]] = Field(default_factory=dict)
    design: DesignTable | None = None


class ReliabilityCase(StrictModel):
    reliability: ReliabilityTable


_LIMIT = re.compile(r"^\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*D\s*$")


def parse_limit(value: str | float, diameter: float) -> tuple[str, float]:
    """(label, metres) of a limit: ``"0.5D"`` → 0.5·D, a number → metres."""
    from onbottom.errors import InputError

    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if value <= 0:
            raise InputError(f"reliability.limits = {value!r} is invalid: must be > 0 m")
        return f"{value:g} m", float(value)
    m = _LIMIT.match(str(value))
    if not m or float(m.group(1)) <= 0.0:
        raise InputError(
            f"reliability.limits = {value!r} is invalid: a number of metres or a multiple of"
            ' D such as "0.5D"'
        )
    return f"{float(m.group(1)):g}D", float(m.group(1)) * diameter


def load_reliability_case(path: str | os.PathLike) -> ReliabilitySetup:
    """Read a reliability case and build its :class:`ReliabilitySetup` (errors:
    :class:`CaseFileError` naming the key)."""
    from onbottom.cases.storm import StormCase, build_setup, case_relative
    from onbottom.errors import InputError

    p = Path(path)
    doc, text = read_json(p) if p.suffix.lower() == ".json" else read_toml(p)
    if not isinstance(doc, dict) or "reliability" not in doc:
        raise CaseFileError(
            f"{p}: no [reliability] table (limits, method, inputs...)",
            field="reliability",
            file=str(p),
        )
    rel = parse_case(ReliabilityCase, {"reliability": doc["reliability"]}, file=p, text=text)
    rest = {k: v for k, v in doc.items() if k != "reliability"}
    storm_case = parse_case(StormCase, rest, file=p, text=text)
    setup = build_setup(storm_case, p)
    t = rel.reliability
    try:
        inputs = tuple(parameter_from_table(k, v) for k, v in t.inputs.items())
        d = float(setup.pipe.outer_diameter)
        limits = tuple(parse_limit(v, d) for v in t.limits)
    except InputError as exc:
        raise CaseFileError(f"{p}: {exc}", field="reliability", file=str(p)) from None
    if t.climate is None and t.storms_per_year is None:
        raise CaseFileError(
            f"{p}: reliability.storms_per_year is needed without [reliability.climate]",
            field="reliability.storms_per_year",
            file=str(p),
        )
    if t.design is not None and t.climate is None:
        raise CaseFileError(
            f"{p}: [reliability.design] needs [reliability.climate] (the contour's joint model)",
            field="reliability.design",
            file=str(p),
        )
    c = t.climate
    climate = (
        None
        if c is None
        else ClimateSettings(
            hindcast=case_relative(p, c.hindcast),
            sectors=c.sectors,
            pipe_heading_deg=c.pipe_heading_deg,
            storm_rate=c.storm_rate,
            current=c.current,
        )
    )
    design = None if t.design is None else ContourDesign(**t.design.model_dump())
    return ReliabilitySetup(
        storm=setup,
        limits=limits,
        seabed_model=storm_case.seabed.model,
        inputs=inputs,
        method=t.method,
        target_cv=t.target_cv,
        max_storms=t.max_storms,
        block_size=t.block_size,
        task_size=t.task_size,
        seed=t.seed,
        storms_per_year=t.storms_per_year,
        design_life_years=t.design_life_years,
        safety_class=t.safety_class,
        form_storms=t.form_storms,
        climate=climate,
        design=design,
    )
