"""The route :func:`onbottom.assess.assess` runs on: plain value types, built once.

:func:`onbottom.cases.assess.load_route` builds a :class:`Route` from a route case file
(``onbottom assess``); the assessment takes it as it is. A :class:`Section` holds what every
level needs — the pipe section, seabed, environment, load combinations and check options of
the static levels, the :class:`~onbottom.dynamics.storm_setup.StormSetup` of each load
combination at the given design, and a :data:`TrialStorm` that builds them at a trial design
(the dynamic search and the pipeline FE). Every object is picklable: a section is the task a
Dask worker runs.

Data flows one way: the case file is read and validated once, by :mod:`onbottom.cases.assess`;
a trial design is a :func:`dataclasses.replace` on the built objects (:class:`DesignTrials`:
the layer thickness of the built :class:`~onbottom.inputs.pipe_buildup.PipeBuildUp`, or the
submerged weight of the built :class:`~onbottom.inputs.pipe.Pipe`, then the soil model and
load reductions that depend on the pipe), never a case document read again.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

from onbottom._validate import in_range, integer, non_negative, one_of, positive
from onbottom.checks.design import CheckOptions
from onbottom.checks.evaluation import DesignBounds
from onbottom.dynamics.storm_setup import StormSetup
from onbottom.errors import InputError
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.pipe_buildup import PipeBuildUp
from onbottom.inputs.soil import Clay, Rock, Sand

__all__ = [
    "ALLOWABLE_OVER_D",
    "VARIABLES",
    "DesignRange",
    "DesignTrials",
    "DynamicSettings",
    "Levels",
    "PipelineFESettings",
    "Route",
    "Section",
    "SoilChoice",
    "StormCombination",
    "TrialStorm",
]

ALLOWABLE_OVER_D: dict[str, float] = {"0.5D": 0.5, "10D": 10.0}
"""Allowable lateral displacement of the dynamic level as a multiple of D (F109 §3.5)."""

VARIABLES = ("concrete_thickness", "submerged_weight", "none")
"""Design variables: the concrete (``layer``) thickness of a build-up pipe [m], the submerged
weight of a simple pipe [N/m], or none (every level at the given design)."""

TrialStorm = Callable[[int, float], StormSetup]
"""``trial(k, x)``: the storm setup of load combination ``k`` (an index of
:attr:`Section.storms`) for the pipe at design value ``x`` (m of the design layer, or N/m);
it raises where that pipe cannot be built (it floats in the combination's condition), and the
dynamic search counts the trial as failing."""


@dataclass(frozen=True)
class Levels:
    """The levels run (the pipeline FE needs the dynamic level).

    ``generalized`` is F109 §3.5 from F109's tables; ``dynamic_curves`` (the tool's own curve
    sweeps, NetCDF files of ``onbottom curves``; empty: not run) is a separate level, never
    F109's. ``allow_below_generalized``: the reason text of a route that accepts a design
    below F109's generalized requirement (None: the design is raised to it);
    ``allow_below_coulomb``: likewise for the Coulomb-friction lower bound of the dynamic level
    where F109's tables do not cover a current-dominated point (M >= 0.8).
    """

    absolute: bool = True
    generalized: bool = True
    dynamic: bool = True
    pipeline_fe: bool = False
    dynamic_curves: tuple[str, ...] = ()
    allow_below_generalized: str | None = None
    allow_below_coulomb: str | None = None

    def __post_init__(self) -> None:
        if self.pipeline_fe and not self.dynamic:
            raise InputError(
                "Levels.pipeline_fe = True is invalid without dynamic = True: the pipeline FE"
                " runs the governing storm of the dynamic level"
            )


@dataclass(frozen=True, kw_only=True)
class DesignRange(DesignBounds):
    """The design variable and its search range.

    Parameters
    ----------
    variable : str
        One of :data:`VARIABLES`.
    layer, thickness_min, thickness_max, weight_min, weight_max
        The search range (:class:`~onbottom.checks.evaluation.DesignBounds`): the layer of the
        build-up whose thickness is sized (``concrete_thickness``), the thickness range [m],
        the submerged-weight range [N/m].
    """

    variable: str = "concrete_thickness"

    def __post_init__(self) -> None:
        one_of("DesignRange.variable", self.variable, VARIABLES)
        super().__post_init__()


@dataclass(frozen=True)
class DynamicSettings:
    """The dynamic level: storms over seeds and the minimum-weight search.

    Parameters
    ----------
    seeds : int
        Storms per evaluation [-].
    first_seed : int
        First random-phase seed [-].
    allowable : str
        ``"0.5D"``, ``"10D"`` (multiples of the trial design's D) or ``"user"``.
    allowable_displacement_m : float or None
        The allowable displacement [m] of ``allowable = "user"``.
    build_up_hours, peak_hours : float
        Storm build-up and peak duration [h] (of the storm setups).
    thickness_tolerance_m : float
        Search tolerance on the thickness [m].
    weight_tolerance_n_per_m : float
        Search tolerance on the submerged weight [N/m].
    """

    seeds: int = 5
    first_seed: int = 0
    allowable: str = "0.5D"
    allowable_displacement_m: float | None = None
    build_up_hours: float = 0.5
    peak_hours: float = 3.0
    thickness_tolerance_m: float = 1.0e-3
    weight_tolerance_n_per_m: float = 5.0

    def __post_init__(self) -> None:
        integer("DynamicSettings.seeds", self.seeds, 1)
        integer("DynamicSettings.first_seed", self.first_seed, 0)
        one_of("DynamicSettings.allowable", self.allowable, (*ALLOWABLE_OVER_D, "user"))
        if (self.allowable == "user") != (self.allowable_displacement_m is not None):
            raise InputError(
                f"DynamicSettings.allowable_displacement_m = {self.allowable_displacement_m!r}"
                " is invalid: give it [m] with allowable = 'user' only"
            )
        if self.allowable_displacement_m is not None:
            positive("DynamicSettings.allowable_displacement_m", self.allowable_displacement_m)
        non_negative("DynamicSettings.build_up_hours", self.build_up_hours)
        positive("DynamicSettings.peak_hours", self.peak_hours)
        positive("DynamicSettings.thickness_tolerance_m", self.thickness_tolerance_m)
        positive("DynamicSettings.weight_tolerance_n_per_m", self.weight_tolerance_n_per_m)

    @property
    def seed_list(self) -> list[int]:
        """The seeds of every evaluation: ``first_seed``, ``first_seed + 1``, ..."""
        return list(range(self.first_seed, self.first_seed + self.seeds))

    @property
    def duration_s(self) -> float:
        """Storm duration [s]: build-up and peak."""
        return 3600.0 * (self.build_up_hours + self.peak_hours)

    def allowable_for(self, diameter: float) -> float:
        """Allowable max lateral displacement [m] of a pipe of outer diameter D [m]."""
        if self.allowable == "user":
            return float(self.allowable_displacement_m)
        return ALLOWABLE_OVER_D[self.allowable] * diameter


@dataclass(frozen=True)
class PipelineFESettings:
    """The pipeline FE run of the governing section (:mod:`onbottom.assess.pipeline`): the
    modelled line and its limits. The time integration's settings are the solver's own
    (:class:`onbottom.dynamics.pipeline.PipelineSettings`), derived from the dynamic level's.

    Parameters
    ----------
    length : float
        Modelled line length L [m].
    element_length : float
        Element length [m], at most L/2.
    end_conditions : str
        ``"fixed"``, ``"pinned"`` or ``"free"``.
    strain_limit : float
        Strain limit [-] (a fraction, not %).
    duration : float or None
        Simulate only [0, duration] of the storm [s] (None: all of it).
    sections : str
        ``"governing"``: the FE runs on the governing section only (the heaviest design);
        ``"every"``: it checks every section's design, in that section's task (on its Dask
        worker), from the section's accepted design.
    mesh : str
        ``"given"``: ``length`` and ``element_length`` as given; ``"rule"``: both from the
        section, sea state and pipe (:func:`onbottom.assess.pipeline.fe_mesh`).
    """

    length: float = 200.0
    element_length: float = 5.0
    end_conditions: str = "fixed"
    strain_limit: float = 2.0e-3
    duration: float | None = None
    sections: str = "governing"
    mesh: str = "given"

    def __post_init__(self) -> None:
        one_of("PipelineFESettings.sections", self.sections, ("governing", "every"))
        one_of("PipelineFESettings.mesh", self.mesh, ("given", "rule"))
        positive("PipelineFESettings.length", self.length)
        in_range("PipelineFESettings.element_length", self.element_length, 0.0, 0.5 * self.length,
                 low_inclusive=False)  # fmt: skip
        ends = ("fixed", "pinned", "free")
        one_of("PipelineFESettings.end_conditions", self.end_conditions, ends)
        positive("PipelineFESettings.strain_limit", self.strain_limit)
        if self.duration is not None:
            positive("PipelineFESettings.duration", self.duration)


@dataclass(frozen=True)
class StormCombination:
    """One load combination of the dynamic level: its name, the pipe condition and the storm
    setup at the given design."""

    name: str
    condition: str
    setup: StormSetup


@dataclass(frozen=True)
class SoilChoice:
    """A soil model by its registry name (:mod:`onbottom.soil.registry`) with its options,
    validated when the case was read: :meth:`build` makes it for a trial pipe (the models
    depend on the pipe's D and w_s, e.g. the as-laid penetration).

    Parameters
    ----------
    name : str
        Registered soil model name (``verley_sotberg_silica``, ...).
    options : dict
        Keyword options of the model (units as its class states).
    where : str
        The case-file key named by an error (``soil.model`` or ``seabed.model``).
    """

    name: str
    options: dict[str, Any] = field(default_factory=dict)
    where: str = "soil.model"

    def build(self, pipe: Pipe, seabed: Sand | Clay | Rock) -> Any:
        """The soil model for ``pipe`` on ``seabed``."""
        from onbottom.soil.registry import build_soil_model

        return build_soil_model(self.name, pipe, seabed, where=self.where, **self.options)


@dataclass(frozen=True)
class DesignTrials:
    """The :data:`TrialStorm` of a section from built objects: ``trials(k, x)`` is the storm
    setup of load combination ``k`` at design value ``x`` — a :func:`dataclasses.replace` of
    that combination's setup at the given design with the trial pipe, its soil model and its
    load reductions. Nothing is read or validated again (the case was, once).

    Parameters
    ----------
    section : Pipe or PipeBuildUp
        The pipe section at the given design (the route's ``[pipe]``, built).
    variable : str
        ``concrete_thickness`` (the thickness [m] of ``layer`` of a build-up) or
        ``submerged_weight`` (w_s [N/m] of a simple pipe).
    layer : str
        The build-up layer sized (``concrete_thickness``).
    conditions : tuple of str
        The pipe condition of each load combination (``operation``, ``installation``, ...).
    setups : tuple of StormSetup
        The storm setup of each load combination at the given design.
    soil : SoilChoice
        The soil model, rebuilt for each trial pipe.
    trench_depth : float or None
        Trench depth z_t [m] of the F109 load reductions (rebuilt as z_t/D for each trial
        pipe); None: the setups run without load reductions.
    """

    section: Pipe | PipeBuildUp
    variable: str
    layer: str
    conditions: tuple[str, ...]
    setups: tuple[StormSetup, ...]
    soil: SoilChoice
    trench_depth: float | None = None

    def __post_init__(self) -> None:
        one_of("DesignTrials.variable", self.variable, VARIABLES[:2])
        if len(self.conditions) != len(self.setups):
            raise InputError(
                f"DesignTrials.conditions has {len(self.conditions)} entries, setups"
                f" {len(self.setups)}: give one condition per load combination"
            )

    def pipe(self, k: int, x: float) -> Pipe:
        """The pipe of load combination ``k`` at design value ``x``; raises
        :class:`~onbottom.errors.InputError` where it floats (w_s <= 0) in that condition."""
        if self.variable == "submerged_weight":
            if isinstance(self.section, PipeBuildUp):
                raise InputError(
                    "DesignTrials.variable = 'submerged_weight' is invalid for a build-up pipe:"
                    " size concrete_thickness"
                )
            return replace(self.section, submerged_weight=float(x))
        if not isinstance(self.section, PipeBuildUp):
            raise InputError(
                "DesignTrials.variable = 'concrete_thickness' is invalid for a simple pipe:"
                " size submerged_weight"
            )
        return self.section.with_layer_thickness(self.layer, float(x)).pipe(self.conditions[k])

    def __call__(self, k: int, x: float) -> StormSetup:
        base = self.setups[k]
        pipe = self.pipe(k, x)
        reductions = base.reductions
        if self.trench_depth is not None:
            if self.trench_depth > pipe.outer_diameter:
                raise InputError(
                    f"seabed.trench_depth = {self.trench_depth!r} m is invalid: deeper than the"
                    f" trial pipe's outer diameter {pipe.outer_diameter:.4g} m"
                )
            reductions = replace(
                reductions, trench_depth_over_d=self.trench_depth / pipe.outer_diameter
            )
        soil = self.soil.build(pipe, base.seabed)
        return replace(base, pipe=pipe, soil=soil, reductions=reductions)


@dataclass(frozen=True)
class Section:
    """One KP section of the route, built.

    Parameters
    ----------
    name : str
        Label of the section.
    kp_start, kp_end : float
        KP range [m].
    water_depth : float
        d [m].
    seabed_model : str
        Soil model name of the seabed (``sand``, ``calcareous``, ``clay``, ``rock``, ...).
    pipe : Pipe or PipeBuildUp
        The pipe section at the given design.
    condition : str
        The pipe's condition (``operation``, ...) of the weight saved.
    seabed : Sand, Clay or Rock
        The seabed of the F109 checks.
    environment : Environment
        Depth, water density and viscosity.
    combinations : tuple of LoadCombination
        The load combinations of the static checks.
    options : CheckOptions
        Settings of the F109 checks.
    given_value : float or None
        The design variable of the given pipe [m or N/m] (None: the pipe has none).
    storms : tuple of StormCombination
        The storms of the dynamic level at the given design (empty without it).
    trial_storm : TrialStorm or None
        The storm setups at a trial design (the dynamic search, the pipeline FE).
    identity : str
        A key that changes with every input of the section's results (the resume key of
        ``sections/*.json``; :mod:`onbottom.cases.assess` hashes the section's case documents
        and the onbottom version); empty: the section is always run, never resumed.
    document : dict
        The section's inputs as plain data, reported in ``results.json``
        (``stability_document``: the ``onbottom stability`` case of the section).
    gap : str
        Why the KP range before this section (from the previous section's end) is not
        assessed, with that range; empty: the sections meet. Reported in the section's notes.
    """

    name: str
    kp_start: float
    kp_end: float
    water_depth: float
    seabed_model: str
    pipe: Pipe | PipeBuildUp
    condition: str
    seabed: Sand | Clay | Rock
    environment: Environment
    combinations: tuple[LoadCombination, ...]
    options: CheckOptions
    given_value: float | None = None
    storms: tuple[StormCombination, ...] = ()
    trial_storm: TrialStorm | None = None
    identity: str = ""
    document: dict[str, Any] = field(default_factory=dict)
    gap: str = ""

    def __post_init__(self) -> None:
        if not self.name:
            raise InputError("Section.name = '' is invalid: give a label")
        if not (math.isfinite(self.kp_start) and self.kp_end > self.kp_start):
            raise InputError(
                f"Section.kp_end = {self.kp_end!r} is invalid: must lie after kp_start ="
                f" {self.kp_start!r} m"
            )
        positive("Section.water_depth", self.water_depth)

    def storm_index(self, name: str) -> int:
        """Index in :attr:`storms` of the load combination ``name``."""
        for k, s in enumerate(self.storms):
            if s.name == name:
                return k
        raise InputError(
            f"combination = {name!r} is invalid: not a storm of section {self.name!r}"
            f" ({', '.join(repr(s.name) for s in self.storms) or 'none'})"
        )


@dataclass(frozen=True)
class Route:
    """A route: its KP sections and the settings of every level.

    Parameters
    ----------
    name : str
        Label of the route.
    sections : tuple of Section
        The KP sections (unique names).
    design : DesignRange
        The design variable and its range.
    levels : Levels
        The levels run.
    dynamic : DynamicSettings
        The dynamic level's settings.
    pipeline : PipelineFESettings
        The pipeline FE's settings (``levels.pipeline_fe``).
    water_density : float
        ρ_w [kg/m³] (the report's V–H diagram).
    force_model : str
        Name of the dynamic level's force model (the report's validity notes).
    identity : str
        A key of the whole route's inputs (``results.json`` provenance ``run_identity``).
    """

    name: str
    sections: tuple[Section, ...]
    design: DesignRange = DesignRange()
    levels: Levels = Levels()
    dynamic: DynamicSettings = DynamicSettings()
    pipeline: PipelineFESettings = PipelineFESettings()
    water_density: float = 1025.0
    force_model: str = "wake"
    identity: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "sections", tuple(self.sections))
        names = [s.name for s in self.sections]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise InputError(f"Route.sections = {dup!r} is invalid: section names must be unique")
        if self.levels.dynamic:
            for s in self.sections:
                if not s.storms or (self.design.variable != "none" and s.trial_storm is None):
                    raise InputError(
                        f"Route.sections[{s.name!r}] is invalid for the dynamic level: give its"
                        " storms (and trial_storm with a design variable)"
                    )

    @property
    def variable(self) -> str:
        """The design variable (:data:`VARIABLES`)."""
        return self.design.variable
