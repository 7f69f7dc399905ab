"""What a reliability run needs: plain value types, built from a case file or by hand.

:func:`onbottom.reliability.run.run_reliability` takes a :class:`ReliabilitySetup` as it is;
:func:`onbottom.cases.reliability.load_reliability_setup` builds one from a storm case file with
a ``[reliability]`` table (``onbottom reliability``), the limits already in metres.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from onbottom._validate import in_range, integer, one_of, positive
from onbottom.dynamics.storm_setup import StormSetup
from onbottom.errors import InputError
from onbottom.reliability.distributions import UncertainParameter

__all__ = ["ClimateSettings", "ContourDesign", "ReliabilitySetup"]

METHODS = ("subset", "importance", "monte_carlo")
"""Estimators of :func:`onbottom.reliability.dynamic.estimate_exceedance` a setup may name."""


@dataclass(frozen=True)
class ClimateSettings:
    """The storm climate from a hindcast (:class:`~onbottom.reliability.climate.StormClimate`).

    Parameters
    ----------
    hindcast : Path
        Hindcast file (CSV/NetCDF, :func:`onbottom.metocean.read_hindcast`).
    sectors : int
        Direction sectors [-] (1: omnidirectional, waves from the storm's direction).
    pipe_heading_deg : float
        Pipe heading [deg from north], in [0, 360].
    storm_rate : float
        Target storms per year of the peaks-over-threshold selection [1/year].
    current : bool
        True: the current speed is drawn with the sea state from the hindcast's current model
        (U | H_s, :mod:`onbottom.metocean.current`).
    """

    hindcast: Path
    sectors: int = 1
    pipe_heading_deg: float = 0.0
    storm_rate: float = 3.0
    current: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "hindcast", Path(self.hindcast))
        integer("ClimateSettings.sectors", self.sectors, 1, 36)
        in_range("ClimateSettings.pipe_heading_deg", self.pipe_heading_deg, 0.0, 360.0)
        positive("ClimateSettings.storm_rate", self.storm_rate)


@dataclass(frozen=True)
class ContourDesign:
    """The response-based design on an IFORM contour (:mod:`onbottom.reliability.design`).

    Parameters
    ----------
    return_period : float
        Return period of the contour [years].
    contour_points : int
        Points on the contour [-].
    seeds : int
        Storms (seeds) per contour point [-].
    top_points : int
        Highest-response points rerun with more seeds [-].
    top_seeds : int
        Seeds at those points [-].
    fractile : float
        Fractile of the design displacement [-], in (0, 1).
    """

    return_period: float = 100.0
    contour_points: int = 12
    seeds: int = 2
    top_points: int = 2
    top_seeds: int = 8
    fractile: float = 0.9

    def __post_init__(self) -> None:
        positive("ContourDesign.return_period", self.return_period)
        integer("ContourDesign.contour_points", self.contour_points, 8)
        integer("ContourDesign.seeds", self.seeds, 1)
        integer("ContourDesign.top_points", self.top_points, 1)
        integer("ContourDesign.top_seeds", self.top_seeds, 1)
        in_range(
            "ContourDesign.fractile",
            self.fractile,
            0.0,
            1.0,
            low_inclusive=False,
            high_inclusive=False,
        )


@dataclass(frozen=True)
class ReliabilitySetup:
    """A reliability run: the storm on the pipe section, the limits, the estimator.

    Parameters
    ----------
    storm : StormSetup
        The storm case (pipe, soil, flow, solver settings) the random inputs perturb.
    limits : tuple of (str, float)
        (label, limit [m]) of each displacement limit, e.g. ``("0.5D", 0.2)``.
    seabed_model : str
        The seabed's soil model name (``sand``, ``calcareous``, ``clay``, ``rock``, ...).
    inputs : tuple of UncertainParameter
        The uncertain inputs of the case (in order; the climate adds its own).
    method : str
        ``"subset"``, ``"importance"`` or ``"monte_carlo"``.
    target_cv : float
        Target coefficient of variation of each estimate [-].
    max_storms : int
        Storms per limit at most [-].
    block_size : int
        Storms per block / per subset level [-].
    task_size : int
        Storms per Dask task [-].
    seed : int
        Seed of openturns' generator [-].
    storms_per_year : float or None
        λ [1/year]; required without a climate (which gives its own rate).
    design_life_years : float
        Design life [years].
    form_storms : int
        Storms per iteration of importance sampling's cross-entropy pilot [-] (at most 4
        iterations).
    safety_class : str
        ``"low"``, ``"medium"`` or ``"high"``: the DNV-OS-F101 target annual failure
        probability the estimates are compared with
        (:data:`onbottom.reliability.run.F101_TARGETS`).
    climate : ClimateSettings or None
        The sea state drawn from a hindcast's storm climate; None: from ``inputs``.
    design : ContourDesign or None
        The response-based design (needs ``climate``).
    """

    storm: StormSetup
    limits: tuple[tuple[str, float], ...]
    seabed_model: str
    inputs: tuple[UncertainParameter, ...] = ()
    method: str = "importance"
    target_cv: float = 0.1
    max_storms: int = 5000
    block_size: int = 200
    task_size: int = 4
    seed: int = 0
    storms_per_year: float | None = None
    design_life_years: float = 25.0
    form_storms: int = 150
    safety_class: str = "medium"
    climate: ClimateSettings | None = None
    design: ContourDesign | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "limits", tuple((str(a), float(b)) for a, b in self.limits))
        object.__setattr__(self, "inputs", tuple(self.inputs))
        if not self.limits:
            raise InputError("ReliabilitySetup.limits = () is invalid: give at least one limit")
        for label, value in self.limits:
            positive(f"ReliabilitySetup.limits[{label!r}]", value)
        one_of("ReliabilitySetup.method", self.method, METHODS)
        one_of("ReliabilitySetup.safety_class", self.safety_class, ("low", "medium", "high"))
        in_range("ReliabilitySetup.target_cv", self.target_cv, 0.0, 1.0, low_inclusive=False)
        for name in ("max_storms", "block_size", "task_size", "form_storms"):
            integer(f"ReliabilitySetup.{name}", getattr(self, name), 1)
        integer("ReliabilitySetup.seed", self.seed, 0)
        positive("ReliabilitySetup.design_life_years", self.design_life_years)
        if self.storms_per_year is not None:
            positive("ReliabilitySetup.storms_per_year", self.storms_per_year)
        elif self.climate is None:
            raise InputError(
                "ReliabilitySetup.storms_per_year = None is invalid without a climate: give the"
                " storm rate [1/year]"
            )
        if self.design is not None and self.climate is None:
            raise InputError(
                "ReliabilitySetup.design is invalid without a climate: the contour needs the"
                " hindcast's joint model"
            )
