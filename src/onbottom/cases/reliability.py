"""Reliability case files: a storm case (``onbottom storm``'s tables) with a ``[reliability]``
table (``examples/reliability_case.toml``).

``[reliability]`` (strict; SI unless a key says otherwise):

* ``limits``: displacement limits, each ``"0.5D"``-style (a multiple of the pipe's outer
  diameter) or a number of metres (default ``["0.5D", "10D"]``); each once, and at most
  ``[solver] max_displacement_over_d`` D (the storms stop there);
* ``method``: ``"importance"`` (default: chosen by a coverage test), ``"subset"`` or
  ``"monte_carlo"``; ``form_storms`` (storms per iteration of importance sampling's pilot);
  ``target_cv`` (default 0.1), ``max_storms`` (per limit), ``block_size`` (storms per block /
  per subset level), ``task_size`` (storms per Dask task), ``seed`` (the generator's seed);
* ``storms_per_year`` (λ; required without a climate, refused beside one: the climate's
  ``storm_rate`` is the rate), ``design_life_years``, ``safety_class`` (``"low"``,
  ``"medium"`` (default) or ``"high"``: the DNV-OS-F101 target annual failure probability the
  estimates are compared with);
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

:func:`load_reliability_setup` reads such a file and builds the plain
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

__all__ = ["ReliabilityCase", "ReliabilitySetup", "load_reliability_setup", "parse_limit"]


class ClimateTable(StrictModel):
    hindcast: str = Field(min_length=1, description="hindcast CSV/NetCDF, relative to the case")
    sectors: int = Field(1, ge=1, le=36, description="direction sectors [-]")
    pipe_heading_deg: float = Field(0.0, ge=0.0, le=360.0, description="[deg from north]")
    storm_rate: float = Field(3.0, ge=0.5, le=50.0, description="target storms per year")
    current: bool = Field(False, description="current speed from the hindcast's joint model")


class ReliabilityDesignTable(StrictModel):
    return_period: float = Field(100.0, ge=1.0, le=1.0e4, description="[years]")
    contour_points: int = Field(
        12, ge=8, le=360, description="IFORM contour points [-] (the contour needs >= 8)"
    )
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
    design: ReliabilityDesignTable | None = None


class ReliabilityCase(StrictModel):
    reliability: ReliabilityTable


def _hindcast(case: Path, value: str, chk: Any) -> Path:
    """The hindcast file of ``[reliability.climate]``: in the case file's folder tree, and a
    file (errors name the key and its line, never the file's content)."""
    from onbottom.cases.storm import case_relative

    key = "reliability.climate.hindcast"
    try:
        path = case_relative(case, value, field=key)
    except CaseFileError as exc:
        chk.fail(key, str(exc))
    if not path.is_file():
        chk.fail(key, f"{key} = {value!r} is invalid: no file {path}")
    return path


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


def load_reliability_setup(path: str | os.PathLike) -> ReliabilitySetup:
    """Read a reliability case and build its :class:`ReliabilitySetup` (errors:
    :class:`CaseFileError` naming the key)."""
    from onbottom.cases.storm import StormCase, build_setup
    from onbottom.cases.tables import Checker
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
    chk = Checker(p, text)
    soil_inputs = [k for k in ("friction_coefficient", "submerged_unit_weight") if k in t.inputs]
    if soil_inputs and storm_case.soil is not None and storm_case.soil.model is not None:
        chk.fail(
            f"reliability.inputs.{soil_inputs[0]}",
            f"reliability.inputs.{soil_inputs[0]} is invalid with [soil] model ="
            f" {storm_case.soil.model!r}: random seabed properties rebuild the seabed kind's"
            " default model; remove [soil] or make the seabed properties fixed",
        )
    try:
        inputs = tuple(parameter_from_table(k, v) for k, v in t.inputs.items())
    except InputError as exc:
        chk.fail("reliability.inputs", str(exc))
    d = float(setup.pipe.outer_diameter)
    stop = float(storm_case.solver.max_displacement_over_d)
    limits = []
    for i, v in enumerate(t.limits):
        key = f"reliability.limits[{i}]"
        try:
            label, metres = parse_limit(v, d)
        except InputError as exc:
            chk.fail(key, str(exc))
        if metres > stop * d * (1.0 + 1e-9):
            chk.fail(
                key,
                f"{key} = {v!r} ({metres:.4g} m = {metres / d:.4g} D) is invalid: the storm runs"
                f" stop at solver.max_displacement_over_d = {stop:g} D, so a larger limit is"
                f" never exceeded; give a limit in (0, {stop:g}D] (F109's criteria are 0.5D"
                " and 10D) or raise solver.max_displacement_over_d",
            )
        same = [j for j, (_, m) in enumerate(limits) if abs(m - metres) <= 1e-9 * metres]
        if same:
            chk.fail(
                key,
                f"{key} = {v!r} is invalid: the same limit as reliability.limits[{same[0]}]"
                f" ({metres:.4g} m); each limit once",
            )
        limits.append((label, metres))
    if t.climate is None and t.storms_per_year is None:
        chk.fail(
            "reliability.storms_per_year",
            "reliability.storms_per_year is needed without [reliability.climate] (the storm"
            " rate λ [1/year])",
        )
    if t.climate is not None and t.storms_per_year is not None:
        chk.fail(
            "reliability.storms_per_year",
            f"reliability.storms_per_year = {t.storms_per_year!r} conflicts with"
            " [reliability.climate]: the storm rate is the hindcast's peaks-over-threshold"
            f" rate (reliability.climate.storm_rate = {t.climate.storm_rate:g} per year);"
            " remove one of them",
        )
    if t.design is not None and t.climate is None:
        chk.fail(
            "reliability.design",
            "[reliability.design] needs [reliability.climate] (the contour's joint model)",
        )
    c = t.climate
    climate = (
        None
        if c is None
        else ClimateSettings(
            hindcast=_hindcast(p, c.hindcast, chk),
            sectors=c.sectors,
            pipe_heading_deg=c.pipe_heading_deg,
            storm_rate=c.storm_rate,
            current=c.current,
        )
    )
    design = None if t.design is None else ContourDesign(**t.design.model_dump())
    if design is not None and design.top_points > design.contour_points:
        chk.fail(
            "reliability.design.top_points",
            f"reliability.design.top_points = {design.top_points} is invalid: more than the"
            f" contour's reliability.design.contour_points = {design.contour_points}",
        )
    try:
        return ReliabilitySetup(
            storm=setup,
            limits=tuple(limits),
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
    except InputError as exc:  # the setup's own checks, under the case file's keys
        msg = re.sub(r"\b(?:ReliabilitySetup|ContourDesign|ClimateSettings)\.", "reliability.",
                     str(exc))  # fmt: skip
        m = re.match(r"(reliability\.[\w.]+)", msg)
        chk.fail(m.group(1) if m else "reliability", msg)
