"""Configuration of the 2D DEM pipe-penetration experiment (frozen, validated dataclasses).

All quantities are SI at **model scale** (the centrifuge model, not the prototype). Disks have
unit thickness (1 m), as in PFC2D, so contact stiffnesses are in N/m, contact forces in N (per
metre of out-of-plane thickness) and the pipe resistance ``V`` in N/m.

Source of the presets: the penetration paper, §4.1 and Table 3 (centrifuge at 25 g, 2D DEM,
most likely Itasca PFC2D).

* :data:`SM` — medium-dense, D_r = 48 %, e = 0.227 (paper: 58,710 disks).
* :data:`SD` — dense, D_r = 78 %, e = 0.197 (paper: 60,150 disks).
* :data:`SM_DR48` — SM with the whole-box target raised so that the *interior* void ratio is
  the paper's 0.227 (D_r = 48 %).
* :data:`SM_REDUCED`, :data:`SD_REDUCED` — same contact law, stiffnesses, damping, void
  ratios, pipe diameter and g-level, but particles 3× larger (D/d50 ≈ 9.8), a 7D × 3D box and a
  pipe 5× faster, so that a case runs in about a minute. They keep the *contrast* between the
  two densities (initial stiffness, heave) but not the paper's absolute resistances; their
  inertial number is larger than 1e-3 and is reported for every run.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from typing import Any

from onbottom import _validate as v
from onbottom.errors import InputError

__all__ = [
    "PRESETS",
    "SD",
    "SD_REDUCED",
    "SM",
    "SM_DR48",
    "SM_INTERIOR_OFFSET",
    "SM_REDUCED",
    "ContactParameters",
    "ContactSet",
    "DEMConfig",
    "Geometry",
    "Loading",
    "Material",
    "Numerics",
    "ParticleSizeDistribution",
    "Preparation",
    "Target",
    "get_preset",
]


@dataclass(frozen=True)
class ContactParameters:
    """Linear contact with Coulomb friction and linear rolling resistance (PFC ``rrlinear``).

    Parameters
    ----------
    k_n
        Normal stiffness [N/m] (per metre of disk thickness).
    k_s
        Shear stiffness [N/m].
    mu
        Sliding friction coefficient [-]; shear force capped at ``mu·F_n``.
    mu_r
        Rolling-resistance coefficient [-]; rolling moment capped at ``mu_r·R̄·F_n``
        with rolling stiffness ``k_r = k_s·R̄²``. 0 disables rolling resistance.
    """

    k_n: float
    k_s: float
    mu: float
    mu_r: float = 0.0

    def __post_init__(self) -> None:
        v.positive("k_n", self.k_n)
        v.non_negative("k_s", self.k_s)
        v.in_range("mu", self.mu, 0.0, 10.0)
        v.in_range("mu_r", self.mu_r, 0.0, 10.0)


@dataclass(frozen=True)
class ContactSet:
    """Contact parameters per pair type: soil–soil, soil–pipe, soil–wall (Table 3)."""

    soil: ContactParameters
    pipe: ContactParameters
    wall: ContactParameters

    def __post_init__(self) -> None:
        for name in ("soil", "pipe", "wall"):
            if not isinstance(getattr(self, name), ContactParameters):
                raise InputError(f"contacts.{name} is invalid: expected ContactParameters")


@dataclass(frozen=True)
class Material:
    """Particle material.

    Parameters
    ----------
    density
        Solid density ρ_s [kg/m³]; disk mass m = ρ_s·π·r²·(1 m), inertia I = ½·m·r².
    damping
        Local (non-viscous, Cundall) damping coefficient α [-], 0 ≤ α < 1.
    """

    density: float = 2650.0
    damping: float = 0.7

    def __post_init__(self) -> None:
        v.positive("density", self.density)
        v.in_range("damping", self.damping, 0.0, 1.0, high_inclusive=False)


@dataclass(frozen=True)
class Geometry:
    """Box and pipe (model scale).

    Parameters
    ----------
    width
        Inner width of the box W [m] (rigid frictionless side walls).
    height
        Height of the soil specimen H [m] (rigid bottom wall; open top).
    pipe_diameter
        Pipe outer diameter D [m].
    """

    width: float
    height: float
    pipe_diameter: float

    def __post_init__(self) -> None:
        v.positive("width", self.width)
        v.positive("height", self.height)
        v.positive("pipe_diameter", self.pipe_diameter)
        if self.pipe_diameter >= self.width:
            raise InputError(
                f"pipe_diameter = {self.pipe_diameter!r} is invalid: must be < width "
                f"= {self.width!r}"
            )


@dataclass(frozen=True)
class ParticleSizeDistribution:
    """Disk-diameter distribution, uniform between ``d_min`` and ``d_max``.

    The grading curve is a straight line between ``d_min`` (0 % passing) and ``d_max``
    (100 %), so ``d_p = d_min + p·(d_max − d_min)``; ``d_min`` and ``d_max`` follow from
    ``d50`` and ``Cu = d60/d10``. ``basis = "number"`` (default) takes the percentages by
    number of particles, as PFC's ``ball distribute``/``generate`` with a uniform radius
    range does; with the paper's d50 = 0.68 mm, Cu = 1.67 and e = 0.227 this gives about
    60,000 disks in a 13D × 5.5D box, within 3 % of the paper's 58,710. ``basis = "mass"``
    takes them by solid area (mass in 2D), like a sieve curve. Valid for 1 ≤ Cu < 6.

    Parameters
    ----------
    d50
        Median diameter [m].
    cu
        Uniformity coefficient d60/d10 [-].
    basis
        ``"number"`` or ``"mass"``.
    """

    d50: float
    cu: float
    basis: str = "number"

    def __post_init__(self) -> None:
        v.positive("d50", self.d50)
        v.in_range("cu", self.cu, 1.0, 6.0, high_inclusive=False)
        v.one_of("basis", self.basis, ("number", "mass"))

    @property
    def d_min(self) -> float:
        """Smallest diameter [m]."""
        # d_p = a + p·Δ; Cu = (a + 0.6Δ)/(a + 0.1Δ) → Δ = a(Cu − 1)/(0.6 − 0.1·Cu)
        ratio = (self.cu - 1.0) / (0.6 - 0.1 * self.cu)
        return self.d50 / (1.0 + 0.5 * ratio)

    @property
    def d_max(self) -> float:
        """Largest diameter [m]."""
        ratio = (self.cu - 1.0) / (0.6 - 0.1 * self.cu)
        return self.d_min * (1.0 + ratio)

    def quantile(self, p: float) -> float:
        """Diameter d_p [m] with a fraction ``p`` (0..1) passing, on the chosen basis."""
        return self.d_min + p * (self.d_max - self.d_min)

    def sample_diameters(self, n: int, rng: Any) -> Any:
        """Draw ``n`` diameters [m] with ``rng`` (a :class:`numpy.random.Generator`)."""
        u = rng.random(n)
        a, b = self.d_min, self.d_max
        if self.basis == "number" or b == a:
            return a + u * (b - a)
        # uniform by area ⇒ number density ∝ 1/d²; inverse CDF of that
        return 1.0 / (1.0 / a - u * (1.0 / a - 1.0 / b))

    def mean_area(self) -> float:
        """Mean disk area per particle (number mean) [m²]."""
        a, b = self.d_min, self.d_max
        if b == a:
            return math.pi * a * a / 4.0
        if self.basis == "number":
            return math.pi / 4.0 * (a * a + a * b + b * b) / 3.0
        return math.pi / 4.0 * a * b


@dataclass(frozen=True)
class Target:
    """Target state of the specimen (2D void ratios, area-based).

    Parameters
    ----------
    void_ratio
        Target void ratio e = A_voids/A_solids [-].
    e_max, e_min
        2D maximum/minimum void ratios [-] (paper: 0.275, 0.175) used for D_r.
    """

    void_ratio: float
    e_max: float = 0.275
    e_min: float = 0.175

    def __post_init__(self) -> None:
        v.in_range("void_ratio", self.void_ratio, 0.05, 2.0)
        v.positive("e_max", self.e_max)
        v.positive("e_min", self.e_min)
        if self.e_min >= self.e_max:
            raise InputError(f"e_min = {self.e_min!r} is invalid: must be < e_max = {self.e_max!r}")

    @property
    def porosity(self) -> float:
        """Target porosity n = e/(1+e) [-]."""
        return self.void_ratio / (1.0 + self.void_ratio)

    @property
    def relative_density(self) -> float:
        """D_r = (e_max − e)/(e_max − e_min) [-]."""
        return (self.e_max - self.void_ratio) / (self.e_max - self.e_min)


LID_PAUSE_STEPS = 2000
"""Longest pause of the compaction lid when its pressure passes the limit [steps]."""
LID_PAUSE_CHECK = 100
"""With ``Preparation.lid_pause = "adaptive"``: steps between pressure tests in a pause."""


RELAXATIONS = ("damped", "fire", "fire-1g")
"""Values of :attr:`Preparation.relaxation`."""


@dataclass(frozen=True)
class Preparation:
    """Multi-layer under-compaction (Jiang, Konrad & Leroueil 2003, Comput. Geotech. 30:579).

    Layer i (1 = bottom) is compacted by a rigid lid, with gravity off, until its porosity
    between its design bottom ``(i−1)·H/n`` and the lid equals ``n_i = n_t·(1 + U_i)`` with
    ``U_i = U_1·(n − i)/(n − 1)`` (linear under-compaction, 0 for the top layer). The top layer
    thus closes the specimen at height H with the target mean porosity n_t.

    Parameters
    ----------
    n_layers
        Number of layers n [-].
    undercompaction
        Under-compaction U_1 of the bottom layer [-] (Jiang et al.: 0.05–0.15 in 2D).
    prep_friction
        Sliding friction μ used while compacting [-] (lower ⇒ denser jammed state); the
        design μ and μ_r are restored before gravity is applied.
    lid_speed
        Speed of the compaction lid [m/s].
    equilibrium_ratio
        Equilibrium criterion: mean unbalanced force / mean contact force below this [-].
    max_settle_time
        Upper bound of simulated time for each equilibrium stage [s].
    lid_pressure_limit
        The lid stops early when its mean pressure exceeds this [Pa] after a pause;
        ``None`` → ten times the N g overburden at the specimen base, 10·ρ_s(1 − n)·N·g·H.
    relaxation
        How the 1 g and N g equilibrium stages are cycled: ``"damped"`` (the paper's local
        damping α, the default) or ``"fire"`` (FIRE, Bitzek et al. 2006, Phys. Rev. Lett.
        97:170201, with the same contact law and the same unbalanced-force criterion; see
        ``docs/theory/dem.md``, "Speed levers"); ``"fire-1g"``: FIRE for the 1 g stage
        only, at the plain step even when the preparation sub-cycles, then the gravity ramp
        and the N g stage as ``"damped"`` (sub-cycled with ``Numerics.subcycle``).
        ``"fire-1g"`` is not equivalent at full size (opt-in, for quick approximate
        specimens).
    layer_generation
        How each loose layer is laid out before the lid compresses it: ``"lattice"``
        (default: a jittered square lattice of pitch 1.05·d_max, porosity ≈ 0.64 for the SM
        grading; the generator of every committed run) or ``"random"`` (random sequential
        addition, largest disks first, into a band of porosity 0.45: the lid travels 2.6
        times less far). ``"random"`` is not equivalent (opt-in, for quick approximate
        specimens).
    lid_pause
        What the lid does when its pressure passes the limit while it moves: it stops and
        the layer relaxes for up to :data:`LID_PAUSE_STEPS` steps; ``"fixed"`` (default,
        every committed run) waits all of them and then tests the pressure once,
        ``"adaptive"`` tests it every :data:`LID_PAUSE_CHECK` steps and moves on as soon as
        it has fallen below the limit. Either way a pressure still above the limit after the
        whole pause stops the lid for good (the layer is "pressure capped").

    How each option was checked, and why the presets set it: ``docs/validation/dem_levers.md``.
    """

    n_layers: int = 5
    undercompaction: float = 0.1
    prep_friction: float = 0.0
    lid_speed: float = 0.5
    equilibrium_ratio: float = 1e-3
    max_settle_time: float = 0.5
    lid_pressure_limit: float | None = None
    relaxation: str = "damped"
    layer_generation: str = "lattice"
    lid_pause: str = "fixed"

    def stage_relaxation(self, stage: str) -> str:
        """How the equilibrium stage ``stage`` (``"layer"``, ``"1g"``, ``"Ng"``) is cycled."""
        if self.relaxation == "fire-1g":
            return "fire" if stage == "1g" else "damped"
        return self.relaxation

    def __post_init__(self) -> None:
        if not isinstance(self.n_layers, int) or self.n_layers < 1:
            raise InputError(f"n_layers = {self.n_layers!r} is invalid: must be an integer >= 1")
        v.in_range("undercompaction", self.undercompaction, 0.0, 0.5)
        v.in_range("prep_friction", self.prep_friction, 0.0, 10.0)
        v.positive("lid_speed", self.lid_speed)
        v.in_range("equilibrium_ratio", self.equilibrium_ratio, 0.0, 1.0, low_inclusive=False)
        v.positive("max_settle_time", self.max_settle_time)
        if self.lid_pressure_limit is not None:
            v.positive("lid_pressure_limit", self.lid_pressure_limit)
        v.one_of("relaxation", self.relaxation, RELAXATIONS)
        v.one_of("layer_generation", self.layer_generation, ("random", "lattice"))
        v.one_of("lid_pause", self.lid_pause, ("fixed", "adaptive"))


@dataclass(frozen=True)
class Loading:
    """Centrifuge and pipe drive.

    Parameters
    ----------
    gravity_factor
        Centrifuge acceleration N [-] (gravity = N·g).
    pipe_velocity
        Prescribed downward pipe velocity [m/s].
    final_embedment_ratio
        Final embedment w/D [-].
    gravity_ramp_time
        Time over which gravity is ramped from 1 g to N g [s].
    """

    gravity_factor: float = 25.0
    pipe_velocity: float = 0.01
    final_embedment_ratio: float = 0.5
    gravity_ramp_time: float = 0.02

    def __post_init__(self) -> None:
        v.in_range("gravity_factor", self.gravity_factor, 1.0, 1000.0)
        v.positive("pipe_velocity", self.pipe_velocity)
        v.in_range(
            "final_embedment_ratio", self.final_embedment_ratio, 0.0, 1.0, low_inclusive=False
        )
        v.non_negative("gravity_ramp_time", self.gravity_ramp_time)


@dataclass(frozen=True)
class Numerics:
    """Integration settings.

    Parameters
    ----------
    dt_safety
        Time step = ``dt_safety`` × critical step √(m_min/k_max) [-].
    skin_ratio
        Verlet skin as a fraction of d_min [-]; lists rebuilt when a disk moved > skin/2.
    record_every
        Record the pipe force every this many steps [-].
    subcycle
        Zonal sub-cycling: the time step follows the soil–soil stiffness
        (``dt_safety``·√(m_min/k_soil)) and the disks within half a skin of a wall, the lid or
        the pipe take n_sub = ⌈√(k_stiff/k_soil)⌉ sub-steps per step for *all* their forces
        (nodal-partition sub-cycling, Belytschko, Yen & Mullen 1979; ``docs/theory/dem.md``,
        "Speed levers"), in the 1 g, ramp, N g and penetration stages; the compaction always
        takes the plain step. Same contact law and damping, 3.65 times fewer steps (on in the
        SM presets; the SD presets sub-cycle their penetration only). ``False`` (default):
        one time step for all, set by the stiffest contact. Not with
        ``Preparation.relaxation = "fire"`` when the preparation sub-cycles.
    subcycle_preparation
        With ``subcycle``: whether the 1 g, ramp and N g stages sub-cycle too [-]. ``False``:
        only the penetration sub-cycles; the whole preparation takes the plain step (the form
        of the SD presets). Default ``True``. Ignored without ``subcycle``.
    subcycle_dt_safety
        With ``subcycle``: the safety factor of the sub-cycled step [-], Δt =
        ``subcycle_dt_safety``·√(m_min/k_soil) and Δt/n_sub for the flagged disks; ``None``
        (default) → ``dt_safety``. The SD presets use 0.25.
    sort_disks
        Renumber the specimen in cell order (rows of cells 2·d_max high, then x) for memory
        locality, before each compacted layer and before the 1 g stage [-]; the physics is
        unchanged (round-off only). Default ``False``; on in the presets.
    compaction_dt_safety
        Safety factor of the compaction's time step [-]: Δt = ``compaction_dt_safety``·
        √(m_min/k_max) while the layers are laid and compressed by the lid (always the plain
        step, never sub-cycled); ``None`` (default) → ``dt_safety``. Only with frictionless
        compaction contacts (``Preparation.prep_friction`` = 0), for which values up to 1
        keep the leapfrog stable. Opt-in; no preset sets it.
    penetration_mass_floor
        Inertial mass scaling in the penetration stage [-]: no disk's inertial mass (and
        moment of inertia ½·m·r²) falls below this fraction of the largest disk's mass, while
        every disk's weight stays its own; the time step follows the lightest inertial mass,
        so 1.0 (every disk as heavy as the largest, in inertia only) lengthens it by
        d_max/d_min (2.55 for the paper's grading). 0 (default): the true masses, as the
        paper. The inertial number computed with the scaled d50 mass is recorded with the run
        (``inertial_number_scaled``); the penetration stays quasi-static while it is below
        1e-3. The preparation is never scaled (its compaction is a dynamic process). Not
        equivalent; no preset uses it (opt-in, for quick approximate runs).
    equilibrium_mass_floor
        The same inertial mass scaling in the preparation's 1 g, gravity-ramp and N g stages
        [-] (never in the compaction); their time windows and the gravity ramp are
        stretched by the same factor as the step, so the step budget is the preset's. 0
        (default): the true masses. Opt-in; not checked for equivalence.

    How each option was checked, and why the presets set it: ``docs/validation/dem_levers.md``.
    """

    dt_safety: float = 0.5
    skin_ratio: float = 0.3
    record_every: int = 200
    subcycle: bool = False
    sort_disks: bool = False
    subcycle_preparation: bool = True
    subcycle_dt_safety: float | None = None
    penetration_mass_floor: float = 0.0
    equilibrium_mass_floor: float = 0.0
    compaction_dt_safety: float | None = None

    @property
    def prep_subcycles(self) -> bool:
        """Whether the preparation's 1 g, ramp and N g stages are sub-cycled."""
        return self.subcycle and self.subcycle_preparation

    @property
    def compaction_step_safety(self) -> float:
        """Safety factor of the compaction's step (``compaction_dt_safety`` or ``dt_safety``)."""
        return self.dt_safety if self.compaction_dt_safety is None else self.compaction_dt_safety

    @property
    def subcycled_dt_safety(self) -> float:
        """Safety factor of the sub-cycled step (``subcycle_dt_safety`` or ``dt_safety``)."""
        return self.dt_safety if self.subcycle_dt_safety is None else self.subcycle_dt_safety

    def __post_init__(self) -> None:
        v.in_range("dt_safety", self.dt_safety, 0.0, 1.0, low_inclusive=False)
        if self.subcycle_dt_safety is not None:
            v.in_range("subcycle_dt_safety", self.subcycle_dt_safety, 0.0, 1.0, low_inclusive=False)
        if self.compaction_dt_safety is not None:
            v.in_range(
                "compaction_dt_safety", self.compaction_dt_safety, 0.0, 1.0, low_inclusive=False
            )
        v.in_range("penetration_mass_floor", self.penetration_mass_floor, 0.0, 1.0)
        v.in_range("equilibrium_mass_floor", self.equilibrium_mass_floor, 0.0, 1.0)
        v.in_range("skin_ratio", self.skin_ratio, 0.0, 2.0, low_inclusive=False)
        if not isinstance(self.record_every, int) or self.record_every < 1:
            raise InputError(
                f"record_every = {self.record_every!r} is invalid: must be an integer >= 1"
            )


@dataclass(frozen=True)
class DEMConfig:
    """A complete DEM penetration experiment (model scale, SI)."""

    name: str
    geometry: Geometry
    psd: ParticleSizeDistribution
    target: Target
    material: Material = field(default_factory=Material)
    contacts: ContactSet = field(
        default_factory=lambda: ContactSet(
            soil=ContactParameters(7.5e7, 5e7, 0.4, 0.8),
            pipe=ContactParameters(1e9, 1e9, 0.3, 0.0),
            wall=ContactParameters(1e9, 1e9, 0.0, 0.0),
        )
    )
    preparation: Preparation = field(default_factory=Preparation)
    loading: Loading = field(default_factory=Loading)
    numerics: Numerics = field(default_factory=Numerics)
    seed: int = 0

    def __post_init__(self) -> None:
        if not isinstance(self.seed, int) or self.seed < 0:
            raise InputError(f"seed = {self.seed!r} is invalid: must be an integer >= 0")
        if self.numerics.prep_subcycles and self.preparation.relaxation == "fire":
            raise InputError(
                "preparation.relaxation = 'fire' is invalid with numerics.subcycle = true: "
                "the sub-cycled disks are locally damped; use relaxation = 'damped'"
            )
        if self.numerics.compaction_dt_safety is not None and self.preparation.prep_friction > 0:
            raise InputError(
                f"numerics.compaction_dt_safety = {self.numerics.compaction_dt_safety!r} is"
                f" invalid with preparation.prep_friction = {self.preparation.prep_friction!r}:"
                " a longer compaction step is only for frictionless compaction contacts"
                " (prep_friction = 0)"
            )
        if self.psd.d_max >= 0.5 * self.geometry.pipe_diameter:
            raise InputError(
                f"psd.d_max = {self.psd.d_max!r} is invalid: must be < pipe_diameter/2"
            )

    def replace(self, **changes: Any) -> DEMConfig:
        """Copy with top-level fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    def estimated_particle_count(self) -> int:
        """Number of disks that fill W×H at the target void ratio [-]."""
        solids = self.geometry.width * self.geometry.height / (1.0 + self.target.void_ratio)
        return round(solids / self.psd.mean_area())

    def to_dict(self) -> dict[str, Any]:
        """Nested plain dict (JSON-able)."""
        return dataclasses.asdict(self)

    def to_json(self) -> str:
        """JSON string of :meth:`to_dict` (a DEM config file; read back with
        :func:`onbottom.cases.dem.load_dem_config` or
        :func:`~onbottom.cases.dem.dem_config_from_json`)."""
        return json.dumps(self.to_dict(), sort_keys=True)


_D = 0.020  # pipe diameter of the paper [m]

SM = DEMConfig(
    name="SM",
    geometry=Geometry(width=13 * _D, height=5.5 * _D, pipe_diameter=_D),
    psd=ParticleSizeDistribution(d50=0.68e-3, cu=1.67),
    target=Target(void_ratio=0.227),
    preparation=Preparation(n_layers=10, undercompaction=0.1, prep_friction=0.0),
    numerics=Numerics(subcycle=True, sort_disks=True),
    seed=1,
)
"""Medium-dense specimen of the paper (D_r = 48 %, e = 0.227), zonally sub-cycled
(``Numerics.subcycle``; why: ``docs/validation/dem_levers.md``)."""

SD = DEMConfig(
    name="SD",
    geometry=Geometry(width=13 * _D, height=5.5 * _D, pipe_diameter=_D),
    psd=ParticleSizeDistribution(d50=0.68e-3, cu=1.67),
    target=Target(void_ratio=0.197),
    preparation=Preparation(n_layers=10, undercompaction=0.1, prep_friction=0.0, relaxation="fire"),
    numerics=Numerics(
        subcycle=True, subcycle_preparation=False, subcycle_dt_safety=0.25, sort_disks=True
    ),
    seed=2,
)
"""Dense specimen of the paper (D_r = 78 %, e = 0.197), prepared with the plain step and FIRE
relaxation of the equilibrium stages; the penetration is zonally sub-cycled at
``subcycle_dt_safety`` 0.25 (why: ``docs/validation/dem_levers.md``)."""

SM_INTERIOR_OFFSET = 0.009
"""Whole-box target minus interior void ratio of a layer-compacted specimen at N g [-].

Measured on the full-size SM run (``docs/validation/dem_levers.md``, "Presets"). Used to aim
:data:`SM_DR48` at the paper's interior density."""

SM_DR48 = SM.replace(
    name="SM-Dr48",
    target=Target(void_ratio=round(0.227 + SM_INTERIOR_OFFSET, 3)),
    seed=3,
)
"""SM at the paper's density *in the interior*: whole-box target e = 0.236 so that the
interior (the band the void ratio is measured in) comes out near the paper's e = 0.227,
D_r = 48 %. Same contacts, box, grading and loading as :data:`SM`; seed 3
(``docs/validation/dem_penetration.md``)."""

_REDUCED_GEOMETRY = Geometry(width=7 * _D, height=3 * _D, pipe_diameter=_D)
_REDUCED_PSD = ParticleSizeDistribution(d50=3 * 0.68e-3, cu=1.67)
_REDUCED_LOADING = Loading(gravity_factor=25.0, pipe_velocity=0.05, final_embedment_ratio=0.5)

SM_REDUCED = SM.replace(
    name="SM-reduced",
    geometry=_REDUCED_GEOMETRY,
    psd=_REDUCED_PSD,
    loading=_REDUCED_LOADING,
    preparation=dataclasses.replace(SM.preparation, n_layers=4),
)
"""Reduced SM: 3× larger disks, 7D × 3D box, pipe at 0.05 m/s (about 2,000 disks)."""

SD_REDUCED = SD.replace(
    name="SD-reduced",
    geometry=_REDUCED_GEOMETRY,
    psd=_REDUCED_PSD,
    loading=_REDUCED_LOADING,
    preparation=dataclasses.replace(SD.preparation, n_layers=4),
)
"""Reduced SD: 3× larger disks, 7D × 3D box, pipe at 0.05 m/s (about 2,000 disks)."""

PRESETS: dict[str, DEMConfig] = {c.name: c for c in (SM, SD, SM_REDUCED, SD_REDUCED, SM_DR48)}
"""Presets by name: ``SM``, ``SD``, ``SM-reduced``, ``SD-reduced``, ``SM-Dr48``."""


def get_preset(name: str) -> DEMConfig:
    """Return the preset called ``name`` (see :data:`PRESETS`)."""
    v.one_of("preset", name, PRESETS)
    return PRESETS[name]
