"""The 2D DEM engine: disks, walls, a driven rigid pipe (numba kernels in ``_kernels``).

:class:`Simulation` owns the state arrays and advances them with :meth:`Simulation.run`.
Model-scale SI units; disks of unit thickness (mass ρπr²·1 m, inertia ½mr²); y is up.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from onbottom import _validate as v
from onbottom.constants import GRAVITY
from onbottom.dem import _kernels as K
from onbottom.dem.config import ContactParameters, ContactSet
from onbottom.dem.sample import Sample
from onbottom.errors import InputError

__all__ = [
    "FIRE_DEFAULTS",
    "PARALLEL_MIN_DISKS",
    "PipeState",
    "Simulation",
    "critical_time_step",
    "step_sizes",
]

FIRE_DEFAULTS = {"alpha0": 0.1, "f_alpha": 0.99, "n_min": 5}
"""FIRE parameters (Bitzek et al. 2006, Phys. Rev. Lett. 97:170201, their recommended values;
the time step is not adapted, see :meth:`Simulation.set_relaxation`)."""

PARALLEL_MIN_DISKS = 5000
"""Below this number of disks the engine runs on one thread unless told otherwise (the reduced
presets, ≈ 2,000 disks, several runs side by side) [-]; the measurement that set it:
``docs/validation/dem_levers.md``."""


def critical_time_step(mass_min: float, k_max: float) -> float:
    """Critical time step √(m_min/k_max) [s] (PFC's definition for a mass on a spring).

    The leapfrog scheme is stable for Δt < 2/ω; with a disk touching a stiff wall and sticking
    in shear (translational + rotational coupling ≈ 3 k_s/m) the engine uses a safety factor
    (``Numerics.dt_safety``, default 0.5) on this value.
    """
    v.positive("mass_min", mass_min)
    v.positive("k_max", k_max)
    return math.sqrt(mass_min / k_max)


def step_sizes(
    contacts: ContactSet, mass_min: float, dt_safety: float, subcycle: bool
) -> tuple[float, int]:
    """Time step [s] and sub-steps of the stiff contacts per step [-].

    Without sub-cycling: Δt = ``dt_safety``·√(m_min/k_max) over all contacts, one sub-step.
    With it: Δt = ``dt_safety``·√(m_min/k_soil) (soil–soil k_n, k_s) and
    n_sub = ⌈√(k_stiff/k_soil)⌉ sub-steps for the wall, lid and pipe contacts
    (k_stiff: their largest k_n or k_s), so that Δt/n_sub ≤ ``dt_safety``·√(m_min/k_stiff).
    """
    c = contacts
    k_soil = max(c.soil.k_n, c.soil.k_s)
    k_stiff = max(c.pipe.k_n, c.pipe.k_s, c.wall.k_n, c.wall.k_s)
    if not subcycle or k_stiff <= k_soil:
        # the engine's original choice (k_s of the walls/pipe equals k_n in Table 3)
        k_max = max(c.soil.k_n, c.soil.k_s, c.pipe.k_n, c.wall.k_n)
        return dt_safety * critical_time_step(mass_min, k_max), 1
    nsub = math.ceil(math.sqrt(k_stiff / k_soil) - 1e-12)
    return dt_safety * critical_time_step(mass_min, k_soil), nsub


@dataclass
class PipeState:
    """Rigid pipe: centre (x, y) [m], radius [m], prescribed vertical velocity [m/s] (y up)."""

    x: float
    y: float
    radius: float
    velocity: float = 0.0
    active: bool = True


class Simulation:
    """A running DEM system.

    Parameters
    ----------
    sample
        Disks and box (the sample's arrays are copied).
    contacts
        Contact parameters per pair type.
    density
        Solid density [kg/m³].
    damping
        Local damping α [-].
    dt
        Time step [s]; ``None`` → ``dt_safety·critical_time_step``.
    dt_safety
        Safety factor on the critical time step [-].
    skin
        Verlet skin [m]; ``None`` → 0.3·d_min.
    gravity
        Gravity vector (g_x, g_y) [m/s²]; default (0, −g).
    pipe
        Optional :class:`PipeState`.
    threads
        Numba threads for the kernels; ``None`` → 1 below :data:`PARALLEL_MIN_DISKS` disks
        (thread start-up dominates on small systems and on a loaded machine), else all.
    nsub
        Sub-steps per time step [-] of the disks within half a skin of a wall, the lid or
        the pipe (zonal sub-cycling, :func:`step_sizes`, ``_kernels.fine_substeps``); 1: none.
    inertial_mass_floor
        Inertial mass scaling [kg per m of disk thickness]: every disk's inertial mass (the
        mass that divides its force, and its moment of inertia ½·m·r²) is at least this, while
        its weight stays its own m·g; the default step (``dt=None``) follows the lightest
        inertial mass. 0 (default): the true masses. A numerical device for quasi-static
        stages (inertial number well below 1e-3), not a change of the contact law: a static
        state is the same with any inertia, the path towards it is not
        (``docs/theory/dem.md``, "Speed levers").
    """

    def __init__(
        self,
        sample: Sample,
        contacts: ContactSet,
        *,
        density: float = 2650.0,
        damping: float = 0.7,
        dt: float | None = None,
        dt_safety: float = 0.5,
        skin: float | None = None,
        gravity: tuple[float, float] = (0.0, -GRAVITY),
        pipe: PipeState | None = None,
        threads: int | None = None,
        nsub: int = 1,
        inertial_mass_floor: float = 0.0,
    ) -> None:
        v.positive("density", density)
        v.non_negative("inertial_mass_floor", inertial_mass_floor)
        if not isinstance(nsub, int) or nsub < 1:
            raise InputError(f"nsub = {nsub!r} is invalid: must be an integer >= 1")
        self.nsub = nsub
        self.fire = np.zeros(K.N_FIRE)
        v.in_range("damping", damping, 0.0, 1.0, high_inclusive=False)
        self.contacts = contacts
        self.density = float(density)
        n = sample.n
        self.pos = sample.positions.copy()
        self.vel = sample.velocities.copy()
        self.om = sample.omega.copy()
        self.th = sample.theta.copy()
        self.rad = sample.radii.copy()
        self.mass = density * np.pi * self.rad**2
        # inertial mass scaling: no disk's inertia below the floor; its weight stays m·g
        self.inertial_mass = np.maximum(self.mass, float(inertial_mass_floor))
        self.inert = 0.5 * self.inertial_mass * self.rad**2
        self._kmass = np.ascontiguousarray(np.column_stack([self.inertial_mass, self.mass]))
        self.fixed = np.zeros(n, np.bool_)
        self.box = sample.box
        self.attrs = dict(sample.attrs)
        self.fsw = np.zeros((n, K.N_WALL))
        self.mrw = np.zeros((n, K.N_WALL))
        self.pfx = np.zeros(n)
        self.pfy = np.zeros(n)
        self.unb = np.zeros(n)
        self.app = np.zeros(n)
        self.prm = np.zeros(K.N_PRM)
        if n:
            m_min = float(self.inertial_mass.min())
            self.dt = dt if dt is not None else step_sizes(contacts, m_min, dt_safety, nsub > 1)[0]
        else:
            self.dt = dt if dt is not None else 1e-6
        v.positive("dt", self.dt)
        d_min = 2.0 * float(self.rad.min()) if n else 1e-3
        self.skin = float(skin) if skin is not None else 0.3 * d_min
        p = self.prm
        p[K.P_DT] = self.dt
        p[K.P_ALPHA] = damping
        self._set_contacts(contacts)
        p[K.P_X0], p[K.P_X1], p[K.P_Y0] = self.box[0], self.box[1], self.box[2]
        p[K.P_SKIN] = self.skin
        self.set_gravity(*gravity)
        self.set_pipe(pipe)
        self.step_count = 0
        self.rebuilds = 0
        if threads is None:
            threads = 1 if n < PARALLEL_MIN_DISKS else numba.config.NUMBA_NUM_THREADS
        self.threads = int(min(max(1, threads), numba.config.NUMBA_NUM_THREADS))
        # empty list, then the first build (history from the sample if present)
        self.start = np.zeros(n + 1, np.int64)
        self.nbr = np.zeros(0, np.uint32)
        self.fs = np.zeros(0)
        self.mr = np.zeros(0)
        self.rstart = np.zeros(n + 1, np.int64)
        self.ridx = np.zeros(0, np.uint32)
        self.ref = self.pos.copy()
        self._load_history(sample.contacts)
        self.rebuild()

    # ------------------------------------------------------------------ setup
    def _set_contacts(self, c: ContactSet) -> None:
        p = self.prm
        p[K.P_KN], p[K.P_KS], p[K.P_MU], p[K.P_MUR] = c.soil.k_n, c.soil.k_s, c.soil.mu, c.soil.mu_r
        p[K.P_KN_P], p[K.P_KS_P], p[K.P_MU_P], p[K.P_MUR_P] = (
            c.pipe.k_n,
            c.pipe.k_s,
            c.pipe.mu,
            c.pipe.mu_r,
        )
        p[K.P_KN_W], p[K.P_KS_W], p[K.P_MU_W], p[K.P_MUR_W] = (
            c.wall.k_n,
            c.wall.k_s,
            c.wall.mu,
            c.wall.mu_r,
        )

    def set_soil_contact(self, soil: ContactParameters) -> None:
        """Change the soil–soil contact parameters (e.g. friction during compaction)."""
        self.contacts = ContactSet(soil=soil, pipe=self.contacts.pipe, wall=self.contacts.wall)
        self._set_contacts(self.contacts)

    def set_relaxation(self, method: str) -> None:
        """``"damped"``: local damping α (the physics of the paper); ``"fire"``: FIRE.

        FIRE (Bitzek et al. 2006) replaces the local damping by a global mixing
        v ← (1 − a)v + a·|v|·F/|F| (and the same for ω with T) while the power F·v + T·ω is
        positive, and zeroes all velocities when it is not; a starts at 0.1 and shrinks by
        0.99 per step after 5 steps without a restart. The contact law is unchanged. Used
        only to reach static equilibrium (preparation), never for the penetration.
        """
        v.one_of("relaxation", method, ("damped", "fire"))
        if method == "fire" and self.nsub > 1:
            raise InputError(
                "relaxation = 'fire' is invalid with sub-cycling (nsub > 1): the sub-cycled "
                "disks are locally damped; use relaxation = 'damped' or subcycle = false"
            )
        f = self.fire
        f[:] = 0.0
        if method == "fire":
            f[K.F_ON] = 1.0
            f[K.F_ALPHA0] = FIRE_DEFAULTS["alpha0"]
            f[K.F_ALPHA] = FIRE_DEFAULTS["alpha0"]
            f[K.F_FALPHA] = FIRE_DEFAULTS["f_alpha"]
            f[K.F_NMIN] = FIRE_DEFAULTS["n_min"]

    @property
    def fire_restarts(self) -> int:
        """Number of FIRE restarts since :meth:`set_relaxation` (0 without FIRE)."""
        return int(self.fire[K.F_RESTARTS])

    def set_gravity(self, gx: float, gy: float) -> None:
        """Gravity vector [m/s²]."""
        self.prm[K.P_GX] = gx
        self.prm[K.P_GY] = gy

    @property
    def gravity(self) -> tuple[float, float]:
        """Current gravity vector [m/s²]."""
        return float(self.prm[K.P_GX]), float(self.prm[K.P_GY])

    def set_pipe(self, pipe: PipeState | None) -> None:
        """Place (or remove, with ``None``) the rigid pipe."""
        p = self.prm
        if pipe is None or not pipe.active:
            p[K.P_PIPE_ON] = 0.0
            return
        p[K.P_PIPE_ON] = 1.0
        p[K.P_PIPE_X], p[K.P_PIPE_Y], p[K.P_PIPE_R], p[K.P_PIPE_V] = (
            pipe.x,
            pipe.y,
            pipe.radius,
            pipe.velocity,
        )

    @property
    def pipe(self) -> PipeState | None:
        """Current pipe state (``None`` if there is none)."""
        p = self.prm
        if p[K.P_PIPE_ON] < 0.5:
            return None
        return PipeState(
            float(p[K.P_PIPE_X]), float(p[K.P_PIPE_Y]), float(p[K.P_PIPE_R]), float(p[K.P_PIPE_V])
        )

    def set_lid(self, y: float | None, velocity: float = 0.0, stop: float = -np.inf) -> None:
        """Activate a horizontal lid at height ``y`` moving at ``velocity`` (stops at ``stop``)."""
        p = self.prm
        if y is None:
            p[K.P_LID_ON] = 0.0
            self.fsw[:, 3] = 0.0
            self.mrw[:, 3] = 0.0
            return
        p[K.P_LID_ON] = 1.0
        p[K.P_LID_Y] = y
        p[K.P_LID_V] = velocity
        p[K.P_LID_STOP] = stop

    @property
    def lid(self) -> float | None:
        """Lid height [m] or ``None``."""
        return float(self.prm[K.P_LID_Y]) if self.prm[K.P_LID_ON] > 0.5 else None

    def lid_force(self) -> float:
        """Normal force of the disks on the lid [N per m] (0 without a lid)."""
        y = self.lid
        if y is None:
            return 0.0
        ov = self.rad - (y - self.pos[:, 1])
        return float(self.contacts.wall.k_n * np.sum(ov[ov > 0.0]))

    @property
    def time(self) -> float:
        """Simulated time [s]."""
        return float(self.prm[K.P_TIME])

    @time.setter
    def time(self, t: float) -> None:
        self.prm[K.P_TIME] = t

    @property
    def n(self) -> int:
        """Number of disks."""
        return int(self.rad.shape[0])

    # ------------------------------------------------------------- history
    def _load_history(self, contacts: dict[str, np.ndarray] | None) -> None:
        """Install contact history from a sample (pairs i<j and wall/pipe codes j<0)."""
        if not contacts or len(contacts["i"]) == 0:
            return
        i = np.asarray(contacts["i"], np.int64)
        j = np.asarray(contacts["j"], np.int64)
        fs = np.asarray(contacts["fs"], np.float64)
        mr = np.asarray(contacts["mr"], np.float64)
        walls = j < 0
        for code in range(K.N_WALL):
            sel = walls & (j == -(code + 1))
            self.fsw[i[sel], code] = fs[sel]
            self.mrw[i[sel], code] = mr[sel]
        pairs = ~walls
        order = np.lexsort((j[pairs], i[pairs]))
        pi, pj = i[pairs][order], j[pairs][order]
        self.start = np.searchsorted(pi, np.arange(self.n + 1)).astype(np.int64)
        self.nbr = pj.astype(np.uint32)
        self.fs = fs[pairs][order].copy()
        self.mr = mr[pairs][order].copy()

    def contact_history(self) -> dict[str, np.ndarray]:
        """Non-zero contact history: pairs (i<j) and wall/pipe contacts (j = −1 − wall code)."""
        counts = np.diff(self.start)
        i_pairs = np.repeat(np.arange(self.n, dtype=np.int64), counts)
        keep = (self.fs != 0.0) | (self.mr != 0.0)
        wi, wc = np.nonzero((self.fsw != 0.0) | (self.mrw != 0.0))
        return {
            "i": np.concatenate([i_pairs[keep], wi.astype(np.int64)]),
            "j": np.concatenate([self.nbr[keep].astype(np.int64), -(wc.astype(np.int64) + 1)]),
            "fs": np.concatenate([self.fs[keep], self.fsw[wi, wc]]),
            "mr": np.concatenate([self.mr[keep], self.mrw[wi, wc]]),
        }

    def rebuild(self) -> None:
        """Rebuild the neighbour list now (history carried over)."""
        previous = numba.get_num_threads()
        numba.set_num_threads(self.threads)
        try:
            out = K.build_list(
                self.pos, self.rad, self.skin, self.start, self.nbr, self.fs, self.mr
            )
        finally:
            numba.set_num_threads(previous)
        self.start, self.nbr, self.fs, self.mr, self.rstart, self.ridx = out
        self.ref[:, :] = self.pos
        self.rebuilds += 1

    # ---------------------------------------------------------------- stepping
    def run(self, nsteps: int) -> None:
        """Advance ``nsteps`` time steps."""
        if nsteps <= 0 or self.n == 0:
            return
        previous = numba.get_num_threads()
        numba.set_num_threads(self.threads)
        try:
            out = self._run(nsteps)
        finally:
            numba.set_num_threads(previous)
        self.start, self.nbr, self.fs, self.mr, self.rstart, self.ridx, nreb = out
        self.rebuilds += int(nreb)
        self.step_count += int(nsteps)

    def _run(self, nsteps: int) -> tuple:
        return K.run_steps(
            int(nsteps), self.prm, self.pos, self.vel, self.om, self.th, self.rad, self._kmass,
            self.inert, self.fixed, self.ref, self.start, self.nbr, self.fs, self.mr,
            self.rstart, self.ridx, self.fsw, self.mrw, self.pfx, self.pfy, self.unb, self.app,
            self.nsub, self.fire, numba.get_num_threads(),
        )  # fmt: skip

    # -------------------------------------------------------------- diagnostics
    def pipe_force(self) -> tuple[float, float]:
        """Force of the soil on the pipe (F_x, F_y) [N per m] at the last step.

        The vertical penetration resistance is ``V = F_y`` (soil pushes the pipe up).
        """
        fx, fy = K.pipe_force(self.pfx, self.pfy)
        return float(fx), float(fy)

    def unbalanced_ratio(self) -> float:
        """Mean unbalanced force / mean applied force (contacts + body forces) [-]."""
        su, sa = K.ratio_sums(self.unb, self.app)
        return float(su / sa) if sa > 0 else 0.0

    def mean_applied_force(self) -> float:
        """Mean magnitude of the applied force (contacts + body forces) per disk [N]."""
        _su, sa = K.ratio_sums(self.unb, self.app)
        return float(sa) / max(self.n, 1)

    def kinetic_energy(self) -> float:
        """Translational + rotational kinetic energy [J per m] (half-step velocities)."""
        return float(
            0.5 * np.sum(self.inertial_mass * np.sum(self.vel**2, axis=1))
            + 0.5 * np.sum(self.inert * self.om**2)
        )

    def contact_forces(self) -> dict[str, np.ndarray]:
        """Current disk–disk contacts: i, j, normal force F_n [N], shear force F_s [N].

        Evaluated from the current positions (F_n = k_n·overlap) and the shear history.
        """
        counts = np.diff(self.start)
        i = np.repeat(np.arange(self.n, dtype=np.int64), counts)
        j = self.nbr.astype(np.int64)
        d = np.hypot(*(self.pos[j] - self.pos[i]).T)
        ov = self.rad[i] + self.rad[j] - d
        touch = ov > 0.0
        return {
            "i": i[touch],
            "j": j[touch],
            "fn": self.contacts.soil.k_n * ov[touch],
            "fs": self.fs[touch],
        }

    def to_sample(self, **attrs: object) -> Sample:
        """Snapshot as a :class:`Sample` (with contact history)."""
        a = dict(self.attrs)
        a.update(attrs)
        return Sample(
            positions=self.pos.copy(),
            radii=self.rad.copy(),
            box=self.box,
            velocities=self.vel.copy(),
            omega=self.om.copy(),
            theta=self.th.copy(),
            contacts=self.contact_history(),
            attrs=a,
        )
