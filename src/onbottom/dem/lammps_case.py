"""The LAMMPS case: the DEM penetration experiment as the LAMMPS deck sees it.

Part of the optional LAMMPS backend (:mod:`onbottom.dem.lammps_backend`): the contact
parameters (:class:`LammpsContact`), the case with its stages and step counts
(:class:`LammpsPenetrationCase`, built from a ``DEMConfig`` and a prepared ``Sample`` by
:meth:`LammpsPenetrationCase.from_config`), and the surface reference (:func:`touch_surface`).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from onbottom import _validate as v
from onbottom.constants import GRAVITY
from onbottom.dem.config import ContactParameters
from onbottom.errors import InputError

__all__ = ["LammpsContact", "LammpsPenetrationCase", "touch_surface"]


# --------------------------------------------------------------------------- the case
LammpsContact = ContactParameters
"""The contact of a LAMMPS run: the engine's :class:`~onbottom.dem.config.ContactParameters`
(linear contact, Coulomb friction, linear rolling resistance ``rrlinear``; k_r = k_s·R̄²).
The name is kept for the LAMMPS backend's API."""


def touch_surface(positions: np.ndarray, radii: np.ndarray, pipe_x: float, radius: float) -> float:
    """Pipe-invert height at which a pipe of ``radius`` above ``pipe_x`` first touches a disk [m].

    The same reference as :func:`onbottom.dem.experiment.penetrate` (w = 0 at first contact).
    """
    pos = np.asarray(positions, dtype=np.float64)
    dx = pos[:, 0] - pipe_x
    reach = radius + np.asarray(radii, dtype=np.float64)
    sel = np.abs(dx) < reach
    if not np.any(sel):
        raise InputError(f"pipe_x = {pipe_x!r} is invalid: no disk lies under the pipe")
    return float(np.max(pos[sel, 1] + np.sqrt(reach[sel] ** 2 - dx[sel] ** 2))) - radius


@dataclass(frozen=True)
class LammpsPenetrationCase:
    """The experiment as the LAMMPS deck sees it (model scale, SI, disks 1 m thick).

    Stages, in order: gravity ramp from ``gravity`` to ``gravity_factor·gravity`` over
    ``gravity_ramp_time`` (skipped if 0); settling at full gravity for ``settle_time``
    (skipped if 0); penetration: the pipe moves down at ``pipe_velocity`` from its start
    position until the embedment reaches ``final_embedment``. The pipe is present (at rest)
    during the first two stages.

    Parameters
    ----------
    positions
        Disk centres, shape (n, 2) [m], y up.
    radii
        Disk radii, shape (n,) [m].
    box
        ``(x_min, x_max, y_min, y_top)`` [m]: side walls at x_min/x_max, bottom wall at y_min.
    density
        Solid density ρ [kg/m³]; m = ρ·π·r²·1 m.
    damping
        Local damping coefficient α [-] (force and moment).
    soil, pipe, wall
        Contact parameters of the soil–soil, soil–pipe and soil–wall contacts.
    pipe_diameter
        Pipe diameter D [m].
    pipe_x
        Abscissa of the pipe axis [m].
    surface_y
        Reference soil-surface height [m]; the embedment is w = surface_y − y_invert.
    pipe_start_embedment
        Embedment at the start [m] (negative: the pipe starts above the surface).
    final_embedment
        Embedment at which the run stops [m].
    pipe_velocity
        Downward pipe velocity [m/s].
    gravity_factor
        Final gravity in multiples of ``gravity`` [-].
    gravity_ramp_time, settle_time
        Durations of the ramp and settle stages [s] (settling is extended by less than
        ``record_every`` steps so that the pipe starts on an output step).
    dt
        Time step [s].
    skin
        Neighbour-list skin [m].
    record_every
        Output interval [steps] of the V–w curve.
    velocities, omega
        Initial velocities (n, 2) [m/s] and angular velocities (n,) [rad/s]; zero if None.
    gravity
        Gravitational acceleration at 1 g [m/s²].
    """

    positions: np.ndarray
    radii: np.ndarray
    box: tuple[float, float, float, float]
    density: float
    damping: float
    soil: LammpsContact
    pipe: LammpsContact
    wall: LammpsContact
    pipe_diameter: float
    pipe_x: float
    surface_y: float
    pipe_start_embedment: float
    final_embedment: float
    pipe_velocity: float
    gravity_factor: float
    gravity_ramp_time: float
    settle_time: float
    dt: float
    skin: float
    record_every: int
    velocities: np.ndarray | None = None
    omega: np.ndarray | None = None
    gravity: float = GRAVITY
    name: str = "case"
    extra: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        pos = np.ascontiguousarray(self.positions, dtype=np.float64)
        rad = np.ascontiguousarray(self.radii, dtype=np.float64)
        n = rad.shape[0]
        if n < 1:
            raise InputError("radii is invalid: need at least one disk")
        if pos.shape != (n, 2):
            raise InputError(f"positions shape = {pos.shape!r} is invalid: must be ({n}, 2)")
        if not np.all(rad > 0.0):
            raise InputError("radii is invalid: every radius must be > 0")
        object.__setattr__(self, "positions", pos)
        object.__setattr__(self, "radii", rad)
        box = tuple(float(b) for b in self.box)
        if len(box) != 4 or not (box[0] < box[1] and box[2] < box[3]):
            raise InputError(f"box = {self.box!r} is invalid: need (x_min < x_max, y_min < y_top)")
        object.__setattr__(self, "box", box)
        v.positive("density", self.density)
        v.in_range("damping", self.damping, 0.0, 1.0, high_inclusive=False)
        v.positive("pipe_diameter", self.pipe_diameter)
        v.in_range("pipe_x", self.pipe_x, box[0], box[1])
        v.finite("surface_y", self.surface_y)
        v.finite("pipe_start_embedment", self.pipe_start_embedment)
        v.finite("final_embedment", self.final_embedment)
        if self.final_embedment < self.pipe_start_embedment:
            raise InputError(
                f"final_embedment = {self.final_embedment!r} is invalid: must be >= "
                f"pipe_start_embedment = {self.pipe_start_embedment!r}"
            )
        v.positive("pipe_velocity", self.pipe_velocity)
        v.in_range("gravity_factor", self.gravity_factor, 0.0, 1000.0)
        v.non_negative("gravity_ramp_time", self.gravity_ramp_time)
        v.non_negative("settle_time", self.settle_time)
        v.positive("dt", self.dt)
        v.positive("skin", self.skin)
        if not isinstance(self.record_every, (int, np.integer)) or self.record_every < 1:
            raise InputError(
                f"record_every = {self.record_every!r} is invalid: must be an integer >= 1"
            )
        v.non_negative("gravity", self.gravity)
        for name in ("velocities", "omega"):
            val = getattr(self, name)
            if val is not None:
                arr = np.ascontiguousarray(val, dtype=np.float64)
                want = (n, 2) if name == "velocities" else (n,)
                if arr.shape != want:
                    raise InputError(f"{name} shape = {arr.shape!r} is invalid: must be {want}")
                object.__setattr__(self, name, arr)

    # ----------------------------------------------------------------- derived
    @property
    def n(self) -> int:
        """Number of disks."""
        return int(self.radii.shape[0])

    @property
    def masses(self) -> np.ndarray:
        """Disk masses m = ρ·π·r²·(1 m) [kg]."""
        return self.density * math.pi * self.radii**2

    @property
    def pipe_start_centre_y(self) -> float:
        """Height of the pipe axis at the start [m]."""
        return self.surface_y - self.pipe_start_embedment + 0.5 * self.pipe_diameter

    @property
    def n_ramp(self) -> int:
        """Steps of the gravity ramp."""
        return round(self.gravity_ramp_time / self.dt)

    @property
    def n_settle(self) -> int:
        """Steps of the settling stage.

        ``settle_time/dt`` rounded up so that the pipe starts on a multiple of
        ``record_every`` (LAMMPS prints on step numbers divisible by the interval, so the
        curve then has a row at the start of the penetration and every interval after it).
        """
        n = round(self.settle_time / self.dt)
        every = int(self.record_every)
        return n + (-(self.n_ramp + n)) % every

    @property
    def n_penetration(self) -> int:
        """Steps of the penetration stage: travel/(v·Δt) rounded up to whole output intervals.

        The last record is then at (or just past) ``final_embedment``, as in
        :func:`onbottom.dem.experiment.penetrate`.
        """
        travel = self.final_embedment - self.pipe_start_embedment
        n = max(math.ceil(travel / (self.pipe_velocity * self.dt) - 1e-9), 0)
        return n + (-n) % int(self.record_every)

    @property
    def n_steps(self) -> int:
        """Total number of steps."""
        return self.n_ramp + self.n_settle + self.n_penetration

    def parameters(self) -> dict[str, Any]:
        """Scalar parameters (JSON-able) for provenance."""
        out: dict[str, Any] = {}
        for k, val in asdict(self).items():
            if k in ("positions", "radii", "velocities", "omega", "extra"):
                continue
            out[k] = list(val) if isinstance(val, tuple) else val
        out["n_particles"] = self.n
        return out

    # ----------------------------------------------------------------- from onbottom objects
    @classmethod
    def from_config(
        cls,
        config: Any,
        sample: Any,
        *,
        surface_y: float | None = None,
        pipe_x: float | None = None,
        pipe_start_embedment: float = 0.0,
        final_embedment: float | None = None,
        dt: float | None = None,
        ramp_gravity: bool = False,
        settle_time: float = 0.0,
        **overrides: Any,
    ) -> LammpsPenetrationCase:
        """Build the case from a ``DEMConfig`` and a prepared ``Sample`` (``onbottom.dem``).

        Parameters
        ----------
        config
            The experiment (``onbottom.dem.config.DEMConfig`` or any object with the same
            attributes: ``material``, ``contacts``, ``geometry``, ``loading``, ``numerics``).
        sample
            The prepared specimen (``onbottom.dem.sample.Sample``: ``positions``, ``radii``,
            ``box``, ``velocities``, ``omega``, ``surface_height()``).
        surface_y
            Reference surface [m]; default :func:`touch_surface` under the pipe, so that
            w = 0 at the first contact, as in :func:`onbottom.dem.experiment.penetrate`.
        pipe_x
            Pipe axis abscissa [m]; default the box centre.
        pipe_start_embedment
            Start embedment [m] (negative: above the surface).
        final_embedment
            Final embedment [m]; default ``loading.final_embedment_ratio·D``.
        dt
            Time step [s]; default ``numerics.dt_safety·√(m_min/k_max)``.
        ramp_gravity
            If True, ramp gravity from 1 g to N g over ``loading.gravity_ramp_time`` first
            (for a specimen prepared at 1 g); a specimen already at N g needs False.
        settle_time
            Settling time at full gravity before the pipe moves [s].
        **overrides
            Any other field of :class:`LammpsPenetrationCase`.
        """
        geo, load, num, mat = config.geometry, config.loading, config.numerics, config.material
        if getattr(num, "penetration_mass_floor", 0.0) > 0.0:
            raise InputError(
                f"numerics.penetration_mass_floor = {num.penetration_mass_floor!r} is invalid"
                " for the LAMMPS backend: it runs the true masses only (must be 0)"
            )
        radii = np.asarray(sample.radii, dtype=np.float64)
        box = tuple(float(b) for b in sample.box)
        D = float(geo.pipe_diameter)
        if pipe_x is None:
            pipe_x = 0.5 * (box[0] + box[1])
        if surface_y is None:
            surface_y = touch_surface(sample.positions, radii, float(pipe_x), 0.5 * D)
        if final_embedment is None:
            final_embedment = float(load.final_embedment_ratio) * D
        soil = config.contacts.soil
        pipe = config.contacts.pipe
        wall = config.contacts.wall
        if dt is None:
            m_min = float(mat.density) * math.pi * float(radii.min()) ** 2
            k_max = max(soil.k_n, soil.k_s, pipe.k_n, wall.k_n)  # as the engine
            dt = float(num.dt_safety) * math.sqrt(m_min / k_max)
        skin = float(getattr(num, "skin_ratio", 0.3)) * 2.0 * float(radii.min())
        kwargs: dict[str, Any] = dict(
            positions=np.asarray(sample.positions),
            radii=radii,
            box=box,
            density=float(mat.density),
            damping=float(mat.damping),
            soil=soil,
            pipe=pipe,
            wall=wall,
            pipe_diameter=D,
            pipe_x=float(pipe_x),
            surface_y=float(surface_y),
            pipe_start_embedment=float(pipe_start_embedment),
            final_embedment=float(final_embedment),
            pipe_velocity=float(load.pipe_velocity),
            gravity_factor=float(load.gravity_factor),
            gravity_ramp_time=float(load.gravity_ramp_time) if ramp_gravity else 0.0,
            settle_time=float(settle_time),
            dt=float(dt),
            skin=skin,
            record_every=int(num.record_every),
            velocities=getattr(sample, "velocities", None),
            omega=getattr(sample, "omega", None),
            name=str(getattr(config, "name", "case")),
        )
        kwargs.update(overrides)
        return cls(**kwargs)
