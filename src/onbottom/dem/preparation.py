"""Specimen preparation: multi-layer under-compaction, then 1 g and N g equilibria.

Method (Jiang, Konrad & Leroueil 2003, Computers and Geotechnics 30:579–597, "UCM"):

1. The solid area for the target void ratio, ``A_s = W·H/(1 + e)``, is filled with diameters
   drawn from the PSD (seeded) and split into ``n`` layers of equal solid area.
2. Layer i (1 = bottom) is generated loose on a jittered square lattice above the current
   surface and compressed by a rigid lid (gravity off, friction ``prep_friction``, no rolling
   resistance) down to the height where its porosity between its design bottom ``(i−1)H/n``
   and the lid equals ``n_i = n_t(1 + U_i)``, ``U_i = U_1 (n − i)/(n − 1)``. Compacting the
   upper layers further densifies the lower ones, which is why they start under-compacted.
   The lid also stops, and holds, when its mean pressure exceeds ``lid_pressure_limit``
   (default: ten times the N g overburden at the specimen base, 10·ρ_s(1 − n)·N·g·H): a thin
   layer next to walls cannot always reach the target porosity without large overlaps (this
   cap is an addition to Jiang et al.; the attributes record which layers were capped).
3. The lid is removed, the design μ and μ_r are restored, gravity 1 g is applied and the
   system is cycled to equilibrium; then gravity is ramped linearly to N g and cycled to a new
   equilibrium (as in the paper).

Equilibrium criterion (stated, as in PFC's "ratio-average"): mean unbalanced force over mean
applied force (contact + body forces) below ``Preparation.equilibrium_ratio``, checked every
``check_every`` steps, with a cap of ``max_settle_time`` of simulated time per stage
(``max_settle_time/5`` per compacted layer). A compacted layer is normally *stress-free* (the
target porosity of a layer is looser than frictionless jamming and gravity is off): its mean
contact force is ~1e-5 of a disk's weight and the ratio stays near 1 because the few moving
disks make all of it, so a layer also counts as settled when its mean applied force per disk is
below :data:`STRESS_FREE_FRACTION` × the mean disk weight at 1 g (measured on the SM preset:
2.5e-7 N against 1.0e-2 N). Without this test every layer ran to its time cap (≈ 3.6e5 steps).
"""

from __future__ import annotations

import json
import logging
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from onbottom.constants import GRAVITY
from onbottom.dem._generation import rsa_positions
from onbottom.dem.config import LID_PAUSE_CHECK, LID_PAUSE_STEPS, ContactParameters, DEMConfig
from onbottom.dem.engine import Simulation, step_sizes
from onbottom.dem.identity import (
    CheckpointError,
    check_identity,
    dem_identity,
    fingerprint,
    guard_output,
)
from onbottom.dem.sample import Sample
from onbottom.errors import InputError

__all__ = [
    "MAX_PARTICLES",
    "STRESS_FREE_FRACTION",
    "draw_diameters",
    "layer_targets",
    "prepare_sample",
    "prepare_to_file",
    "settle",
]

MAX_PARTICLES = 2_000_000
"""Largest specimen :func:`prepare_sample` accepts (estimated up front; the full SM and SD
presets hold about 60,000 disks)."""
BYTES_PER_PARTICLE = 2048
"""Order of the memory one disk takes in the engine (state, neighbour list, contact history)."""

STRESS_FREE_FRACTION = 1e-3
"""A compacted layer whose mean applied force per disk is below this fraction of the mean
disk weight at 1 g counts as settled (stress-free: gravity is off while compacting)."""

log = logging.getLogger(__name__)

Progress = Callable[[str, float], None]


def draw_diameters(config: DEMConfig, rng: np.random.Generator) -> np.ndarray:
    """Diameters [m] whose total disk area is the target solid area W·H/(1+e)."""
    g = config.geometry
    target = g.width * g.height / (1.0 + config.target.void_ratio)
    n_est = int(target / config.psd.mean_area() * 1.1) + 16
    d = config.psd.sample_diameters(n_est, rng)
    area = np.cumsum(np.pi * d**2 / 4.0)
    while area[-1] < target:
        more = config.psd.sample_diameters(n_est // 10 + 16, rng)
        d = np.concatenate([d, more])
        area = np.cumsum(np.pi * d**2 / 4.0)
    k = int(np.searchsorted(area, target))  # area[k] >= target
    if k > 0 and abs(area[k - 1] - target) < abs(area[k] - target):
        k -= 1
    return d[: k + 1]


def layer_targets(config: DEMConfig, layer_solid_area: np.ndarray) -> np.ndarray:
    """Lid stop heights (relative to the box bottom) of the layers [m] (Jiang et al. 2003)."""
    g = config.geometry
    n_l = len(layer_solid_area)
    n_t = config.target.porosity
    u1 = config.preparation.undercompaction
    tops = np.empty(n_l)
    for i in range(n_l):
        u_i = u1 * (n_l - 1 - i) / (n_l - 1) if n_l > 1 else 0.0
        n_i = min(n_t * (1.0 + u_i), 0.9)
        tops[i] = i * g.height / n_l + layer_solid_area[i] / (g.width * (1.0 - n_i))
    return tops


def _lattice(
    diam: np.ndarray, x0: float, width: float, y_base: float, rng: np.random.Generator
) -> np.ndarray:
    """Loose, non-overlapping positions on a jittered square lattice above ``y_base``."""
    s = 1.05 * float(diam.max())
    ncol = max(1, int(width / s))
    s_x = width / ncol
    n = len(diam)
    idx = np.arange(n)
    col = idx % ncol
    row = idx // ncol
    slack_x = np.maximum(0.0, s_x - diam) / 2.0
    slack_y = np.maximum(0.0, s - diam) / 2.0
    x = x0 + (col + 0.5) * s_x + slack_x * (2.0 * rng.random(n) - 1.0)
    y = y_base + (row + 0.5) * s + slack_y * (2.0 * rng.random(n) - 1.0)
    return np.stack([x, y], axis=1)


LOOSE_POROSITY = 0.45
"""Porosity of a freshly generated ``"random"`` layer [-]. Random sequential addition,
largest disks first, still places every disk of the SM grading within 2,000 tries at 0.38;
at 0.45 a layer of 6,000 disks takes about 0.01 s."""


def _random_layer(
    diam: np.ndarray, x0: float, width: float, y_base: float, rng: np.random.Generator
) -> np.ndarray:
    """Loose, non-overlapping, statistically isotropic positions above ``y_base``.

    Random sequential addition (largest disks first, each at uniform random centres until it
    overlaps none placed before) into a band ``width`` wide whose height gives the porosity
    :data:`LOOSE_POROSITY`; the band grows by 10 % and the layer is redrawn in the rare case
    a disk finds no place in 2,000 tries. For the SM grading the layer starts 2.6 times
    less far above its target than on the square lattice of :func:`_lattice`.
    """
    order = np.argsort(-diam, kind="stable")
    d = np.ascontiguousarray(diam[order])
    height = float(np.sum(np.pi * d**2 / 4.0)) / ((1.0 - LOOSE_POROSITY) * width)
    while True:
        u = rng.random((200 * len(d) + 10_000, 2))
        pos, _ = rsa_positions(d, x0, width, y_base, height, u, 2000)
        if not np.isnan(pos).any():
            break
        height *= 1.1
    out = np.empty_like(pos)
    out[order] = pos
    return out


def settle(
    sim: Simulation,
    ratio: float,
    max_time: float,
    *,
    check_every: int = 500,
    min_time: float = 0.0,
    force_floor: float = 0.0,
    start_time: float | None = None,
    on_check: Callable[[float], None] | None = None,
    relaxation: str = "damped",
) -> tuple[bool, float]:
    """Cycle until the unbalanced-force ratio < ``ratio`` (after ``min_time``) or ``max_time``.

    ``force_floor`` [N]: the assembly also counts as settled when the mean applied force per
    disk falls below it (a stress-free assembly has nothing to balance: its ratio stays near 1
    while a few disks drift, which is noise, not imbalance). 0 disables the test.
    ``start_time`` [s]: simulated time at which the stage began (default: now), so that a stage
    resumed from a checkpoint keeps its original time window. ``on_check(fraction)`` is called
    after every check that does not end the stage (fraction of ``max_time`` used).
    ``relaxation``: ``"damped"`` (local damping) or ``"fire"``; FIRE can meet the ratio while
    the assembly still moves, so when it does the velocities are zeroed and the cycling goes
    on with local damping until the criterion holds again (the end state meets the same
    criterion under the same law as a damped stage). The simulation is left damped.

    Returns (converged, final ratio).
    """
    t0 = sim.time if start_time is None else start_time
    t_end = t0 + max_time
    t_min = t0 + min_time
    r = math.inf
    sim.set_relaxation(relaxation)
    polishing = relaxation == "damped"
    try:
        while sim.time < t_end:
            sim.run(check_every)
            r = sim.unbalanced_ratio()
            if sim.time >= t_min and (r < ratio or sim.mean_applied_force() < force_floor):
                if polishing:
                    return True, r
                sim.vel[:] = 0.0
                sim.om[:] = 0.0
                sim.set_relaxation("damped")
                polishing = True
                continue
            if on_check is not None:
                on_check((sim.time - t0) / max_time)
    finally:
        sim.set_relaxation("damped")
    return False, r


class _StageClock:
    """Accumulates wall-clock time and steps per preparation stage into ``timings``."""

    def __init__(self, timings: dict[str, float] | None) -> None:
        self.timings = timings
        self.reset()

    def reset(self, steps: int = 0) -> None:
        self.t = time.perf_counter()
        self.steps = steps

    def lap(self, stage: str, steps: int, disks: int) -> None:
        now = time.perf_counter()
        if self.timings is not None:
            d = self.timings
            d[f"{stage}_wall"] = d.get(f"{stage}_wall", 0.0) + now - self.t
            d[f"{stage}_steps"] = d.get(f"{stage}_steps", 0) + steps - self.steps
            key = f"{stage}_disk_steps"
            d[key] = d.get(key, 0) + disks * (steps - self.steps)
            d[f"{stage}_disks"] = disks
        self.t = now
        self.steps = steps


def _read_checkpoint(ck: Path, identity: dict) -> Sample:
    """The checkpoint in ``ck`` if it is readable and belongs to the run ``identity``."""
    from onbottom.dem.identity import RESTART_ADVICE

    try:
        saved = Sample.load(ck)
        meta = saved.attrs["_checkpoint"]
        for key in ("layers_done", "rng_state", "time", "lid"):
            meta[key]  # presence check
    except Exception as exc:  # any failure to read means: not a usable checkpoint
        raise CheckpointError(
            f"preparation checkpoint {ck} cannot be read ({type(exc).__name__}: {exc}); it is"
            f" truncated, corrupt or not a checkpoint; {RESTART_ADVICE}"
        ) from None
    check_identity(meta.get("identity"), identity, ck, what="preparation checkpoint")
    return saved


def prepare_sample(
    config: DEMConfig,
    progress: Progress | None = None,
    checkpoint: str | Path | None = None,
    checkpoint_every: int = 100_000,
    timings: dict[str, float] | None = None,
    *,
    restart: bool = False,
) -> Sample:
    """Prepare the specimen of ``config`` at N g equilibrium (seeded, reproducible).

    The stages, each a function of this module: :func:`_draw_layers` (the disk population,
    split into layers), then per layer :func:`_generate_layer` (the loose layer above the
    surface) and :func:`_compact_layer` (the lid down to the layer's target, then settled),
    :func:`_release_lid` (lid off, design contact), :func:`_settle_1g` (equilibrium at 1 g),
    :func:`_ramp_gravity` (1 g → N g), :func:`_settle_ng` (equilibrium at N g) and
    :func:`_finish` (the specimen at rest, with its attributes).

    Parameters
    ----------
    config
        Experiment configuration.
    progress
        Optional callback ``progress(stage, fraction_done)``.
    checkpoint
        Optional file written (atomically) after each compacted layer, at the start of the N g
        stage and every ``checkpoint_every`` steps of the 1 g and N g equilibria, and read back
        when it exists, so an interrupted preparation resumes where it stopped with the same
        result (the random-generator state and the stage's start time are stored with it).
        Deleted when done. It carries the run identity (:mod:`onbottom.dem.identity`): a
        checkpoint of another configuration, seed or engine version raises
        :class:`~onbottom.dem.identity.CheckpointMismatchError`, an unreadable one
        :class:`~onbottom.dem.identity.CheckpointError`.
    checkpoint_every
        Steps between checkpoints inside the 1 g and N g equilibria [-].
    timings
        Optional dict filled with the wall-clock time [s] and the number of steps of each
        stage of this call (``<stage>_wall``, ``<stage>_steps``, ``<stage>_disk_steps``,
        ``<stage>_disks`` (at the end of the stage) for
        ``generation``, ``compaction``, ``1g``, ``ramp``, ``Ng``; a resumed stage counts
        only the work of this call). Diagnostics only: the sample does not depend on it.
    restart
        Discard an existing checkpoint and start afresh.

    Returns
    -------
    Sample
        With attributes: void ratio after each stage, convergence of each equilibrium stage,
        the unbalanced-force ratios, the number of disks, the gravity factor.
    """
    clock = _StageClock(timings)
    if int(checkpoint_every) < 1:
        raise CheckpointError(
            f"checkpoint_every = {checkpoint_every!r} is invalid: must be >= 1",
            field="checkpoint_every",
        )
    n_est = config.estimated_particle_count()
    if n_est > MAX_PARTICLES:
        raise InputError(
            f"geometry is invalid: the specimen would hold about {n_est:.3g} disks (about"
            f" {n_est * BYTES_PER_PARTICLE / 1024**3:.3g} GiB of memory), more than the"
            f" {MAX_PARTICLES:.0e} allowed; reduce the box or enlarge the disks"
        )
    identity = dem_identity(config, "preparation").fields
    ck = Path(checkpoint) if checkpoint is not None else None
    if ck is not None and restart:
        ck.unlink(missing_ok=True)
    saved = _read_checkpoint(ck, identity) if ck is not None and ck.exists() else None
    rng = np.random.default_rng(config.seed)
    diam, layers, tops = _draw_layers(config, rng)
    run = _Preparation(config, diam, identity, ck, int(checkpoint_every), progress, clock)
    first_layer = run.resume(saved, rng) if saved is not None else 0
    for li, ix in enumerate(layers):
        if li < first_layer:
            continue
        _generate_layer(run, diam[ix], rng)
        _compact_layer(run, li, len(layers), float(tops[li]), rng)
    run.rng_state = rng.bit_generator.state
    _release_lid(run)
    if run.stage == "1g":
        _settle_1g(run)
        _ramp_gravity(run)
    _settle_ng(run)
    out = _finish(run)
    if ck is not None and ck.exists():
        ck.unlink()
    return out


def prepare_to_file(
    config: DEMConfig,
    out: str | Path,
    *,
    progress: Callable[[float], None] | None = None,
    restart: bool = False,
    field: str = "out",
) -> Sample:
    """Prepare the specimen of ``config`` and save it to ``out``; resumable per compacted layer.

    ``out`` is refused when it holds the result of another run, unless ``restart``
    (:func:`~onbottom.dem.identity.guard_output`, errors naming ``field``). The layer
    checkpoint ``<out>.prep-checkpoint.nc`` is written after every layer, read when a previous
    run was interrupted (if it belongs to the same run), and removed once the specimen is
    saved. ``progress(fraction_done)`` (optional) gets the fraction of the whole preparation:
    compaction 0–0.8, 1 g equilibrium 0.8–0.9, the gravity ramp and N g equilibrium 0.9–1.
    """
    from onbottom.results import clean_stale_temporaries

    out = Path(out)
    guard_output(out, dem_identity(config, "preparation").fields, restart=restart, field=field)
    checkpoint = out.with_name(out.name + ".prep-checkpoint.nc")
    clean_stale_temporaries(out)
    clean_stale_temporaries(checkpoint)

    def report(stage: str, f: float) -> None:
        if progress is not None:
            start = 0.8 if stage == "1g" else 0.9
            progress(0.8 * f if stage == "compaction" else start + 0.1 * f)

    sample = prepare_sample(config, progress=report, checkpoint=checkpoint, restart=restart)
    sample.save(out)
    checkpoint.unlink(missing_ok=True)
    return sample


class _Preparation:
    """One preparation in progress: its configuration, derived steps, simulation and checkpoint.

    Holds what the stage functions share: the step sizes and sub-cycling of each stage
    (:meth:`subcycled`, :meth:`step_size`), the current :class:`Simulation` (``sim``), the bed
    between layers (``bed``), the sample attributes (``attrs``), the values carried from
    stage to stage and through a checkpoint (``stage``, ``stage_values``), and the
    checkpoint file.
    """

    def __init__(
        self,
        config: DEMConfig,
        diam: np.ndarray,
        identity: dict,
        ck: Path | None,
        checkpoint_every: int,
        progress: Progress | None,
        clock: _StageClock,
    ) -> None:
        self.config = config
        self.prep = config.preparation
        self.identity = identity
        self.ck = ck
        self.checkpoint_every = checkpoint_every
        self.progress = progress
        self.clock = clock
        g = config.geometry
        self.box = (0.0, g.width, 0.0, g.height)
        self.d_min = float(diam.min())
        soil = config.contacts.soil
        self.prep_soil = ContactParameters(soil.k_n, soil.k_s, self.prep.prep_friction, 0.0)
        self.bed = Sample(np.zeros((0, 2)), np.zeros(0), self.box)
        self.attrs: dict[str, object] = {
            "config": config.to_json(),
            "layers": self.prep.n_layers,
            # the configuration itself is under "config"; the rest of the identity here
            "run_identity": json.dumps(
                {k: v for k, v in identity.items() if k != "config"}, sort_keys=True
            ),
            "run_fingerprint": fingerprint(identity),
        }
        self.sim: Simulation | None = None
        self.stage = "compaction"
        self.stage_values: dict[str, float] = {}
        self.rng_state: dict | None = None
        self.last_saved = 0
        self.n_g = config.loading.gravity_factor
        m_min = config.material.density * math.pi * (diam.min() / 2) ** 2
        self.w_mean = config.material.density * math.pi * float(np.mean(diam**2)) / 4.0 * GRAVITY
        # the compaction always takes the plain step; with Numerics.subcycle (and
        # subcycle_preparation) the 1 g and N g stages are zonally sub-cycled (a sub-cycled
        # compaction gave stiffer specimens, see docs/validation/dem_levers.md)
        # (Numerics.compaction_dt_safety: its own plain step; frictionless contacts only)
        num = config.numerics
        self.dt_compaction, _ = step_sizes(
            config.contacts, m_min, num.compaction_step_safety, False
        )
        self.nsub_sub = (
            step_sizes(config.contacts, m_min, num.subcycled_dt_safety, True)[1]
            if num.prep_subcycles
            else 1
        )
        # inertial mass scaling of the 1 g, ramp and N g stages (Numerics.equilibrium_mass_floor;
        # never the compaction): the steps follow the lightest inertial mass
        self.floor_eq = (
            num.equilibrium_mass_floor
            * config.material.density
            * math.pi
            * (float(diam.max()) / 2) ** 2
        )
        m_eq = max(m_min, self.floor_eq)
        # a scaled assembly's own time scale is longer by the same factor as its step: the
        # 1 g / N g time windows and the ramp are stretched alike (the preset's step budget)
        self.stretch = math.sqrt(m_eq / m_min)
        self.dt_plain_eq = step_sizes(config.contacts, m_eq, num.dt_safety, False)[0]
        self.dt_sub_eq = (
            step_sizes(config.contacts, m_eq, num.subcycled_dt_safety, True)[0]
            if num.prep_subcycles
            else self.dt_plain_eq
        )

    def subcycled(self, stage: str) -> bool:
        """Whether ``stage`` takes the sub-cycled step (FIRE needs the plain one)."""
        if stage == "compaction":
            return False
        return self.prep.stage_relaxation(stage) != "fire" and self.nsub_sub > 1

    def step_size(self, stage: str) -> float:
        """Time step [s] of ``stage``."""
        if stage == "compaction":
            return self.dt_compaction
        return self.dt_sub_eq if self.subcycled(stage) else self.dt_plain_eq

    def new_sim(self, sample: Sample, stage: str) -> Simulation:
        """A simulation of ``sample`` with the step (and inertia) of ``stage``."""
        config = self.config
        s = Simulation(
            sample,
            config.contacts,
            density=config.material.density,
            damping=config.material.damping,
            dt=self.step_size(stage),
            skin=config.numerics.skin_ratio * self.d_min,
            gravity=(0.0, 0.0),
            nsub=self.nsub_sub if self.subcycled(stage) else 1,
            inertial_mass_floor=0.0 if stage == "compaction" else self.floor_eq,
        )
        s.set_soil_contact(self.prep_soil)
        return s

    def rebuild(self, sample: Sample, stage: str) -> None:
        """Replace ``sim`` by one of ``sample`` for ``stage``, keeping its time and step count."""
        assert self.sim is not None
        t_now, steps = self.sim.time, self.sim.step_count
        self.sim = self.new_sim(sample, stage)
        self.sim.time, self.sim.step_count = t_now, steps

    def step_of(self, stage: str) -> None:
        """Rebuild ``sim`` with the step of ``stage`` if it has another (same state)."""
        assert self.sim is not None
        nsub = self.nsub_sub if self.subcycled(stage) else 1
        if self.sim.nsub != nsub or self.sim.dt != self.step_size(stage):
            self.rebuild(self.sim.to_sample(), stage)

    def resume(self, saved: Sample, rng: np.random.Generator) -> int:
        """Continue from the checkpoint ``saved``; returns the number of layers done."""
        meta = saved.attrs.pop("_checkpoint")
        first_layer = int(meta["layers_done"])
        self.stage = str(meta.get("stage", "compaction"))
        self.stage_values = dict(meta.get("stage_values", {}))
        rng.bit_generator.state = meta["rng_state"]
        self.attrs = saved.attrs
        self.bed = saved
        self.sim = self.new_sim(saved, self.stage)
        self.sim.time = float(meta["time"])
        if meta["lid"] is not None:
            self.sim.set_lid(float(meta["lid"]), 0.0)
        log.info(
            "resumed preparation from %s (layer %d, stage %s)", self.ck, first_layer, self.stage
        )
        return first_layer

    def save(self, layers_done: int, rng_state: dict, **stage: Any) -> None:
        """Write the checkpoint of the current simulation (``stage``: further metadata)."""
        assert self.sim is not None and self.ck is not None
        snap = self.sim.to_sample()
        snap.attrs = dict(self.attrs)
        snap.attrs["_checkpoint"] = {
            "identity": self.identity,
            "layers_done": layers_done,
            "rng_state": rng_state,
            "time": self.sim.time,
            "lid": self.sim.lid,
            **stage,
        }
        snap.save(self.ck)
        self.last_saved = self.sim.step_count

    def save_stage(self, name: str) -> None:
        """Checkpoint inside the equilibrium stage ``name`` (every layer done, lid off)."""
        assert self.rng_state is not None
        self.save(self.prep.n_layers, self.rng_state, stage=name, stage_values=self.stage_values)

    def equilibrium(self, name: str) -> tuple[bool, float]:
        """Cycle stage ``name`` to equilibrium within its time window (resumable)."""
        assert self.sim is not None

        def check(fraction: float) -> None:
            assert self.sim is not None
            if (
                self.ck is not None
                and self.sim.step_count - self.last_saved >= self.checkpoint_every
            ):
                self.save_stage(name)
            if self.progress is not None:
                self.progress(name, min(fraction, 1.0))

        result = settle(
            self.sim,
            self.prep.equilibrium_ratio,
            self.prep.max_settle_time * self.stretch,
            min_time=5e-3 * self.stretch,
            start_time=self.stage_values[f"t0_{name}"],
            on_check=check,
            relaxation=self.prep.stage_relaxation(name),
        )
        if self.progress is not None:
            self.progress(name, 1.0)
        return result


def _draw_layers(
    config: DEMConfig, rng: np.random.Generator
) -> tuple[np.ndarray, list[np.ndarray], np.ndarray]:
    """Stage 0, the disk population: diameters [m], their layers, and the lid targets [m].

    The diameters fill the target solid area (:func:`draw_diameters`), are shuffled, and
    split into ``n_layers`` groups of equal solid area (indices into the diameters, bottom
    layer first); the lid stop height of each layer follows :func:`layer_targets`.
    """
    diam = draw_diameters(config, rng)
    rng.shuffle(diam)
    area = np.pi * diam**2 / 4.0
    cum = np.cumsum(area)
    n_l = config.preparation.n_layers
    bounds = np.searchsorted(cum, cum[-1] * np.arange(1, n_l) / n_l)
    layers = np.split(np.arange(len(diam)), bounds)
    tops = layer_targets(config, np.array([area[ix].sum() for ix in layers]))
    return diam, layers, tops


def _generate_layer(run: _Preparation, diam: np.ndarray, rng: np.random.Generator) -> None:
    """Stage 1, per layer: lay the loose disks ``diam`` [m] out above the current surface.

    On a jittered square lattice (:func:`_lattice`) or by random sequential addition
    (:func:`_random_layer`), following ``Preparation.layer_generation``; with
    ``Numerics.sort_disks`` the whole specimen is renumbered in cell order (compaction mixes
    each layer over its height; round-off only). Starts a new simulation at the compaction
    step, with the time of the previous one.
    """
    bed, g = run.bed, run.config.geometry
    y_base = float(np.max(bed.positions[:, 1] + bed.radii)) if bed.n else 0.0
    generate = _random_layer if run.prep.layer_generation == "random" else _lattice
    new_pos = generate(diam, 0.0, g.width, y_base, rng)
    sample = Sample(
        np.concatenate([bed.positions, new_pos]),
        np.concatenate([bed.radii, diam / 2.0]),
        run.box,
        velocities=np.concatenate([bed.velocities, np.zeros((len(diam), 2))]),
        omega=np.concatenate([bed.omega, np.zeros(len(diam))]),
        contacts=bed.contacts,
    )
    if run.config.numerics.sort_disks:
        sample = sample.permuted(sample.cell_order())
    t_prev = run.sim.time if run.sim is not None else 0.0
    run.sim = run.new_sim(sample, "compaction")
    run.sim.time = t_prev
    run.clock.lap("generation", 0, run.sim.n)


def _lid_pressure_cap(config: DEMConfig) -> float:
    """Lid pressure [Pa] above which the lid pauses (``Preparation.lid_pressure_limit``)."""
    prep = config.preparation
    if prep.lid_pressure_limit is not None:
        return prep.lid_pressure_limit
    return (
        10.0
        * config.material.density
        * (1 - config.target.porosity)
        * config.loading.gravity_factor
        * GRAVITY
        * config.geometry.height
    )


def _compact_layer(
    run: _Preparation, li: int, n_l: int, stop: float, rng: np.random.Generator
) -> None:
    """Stage 2, per layer: the lid compresses layer ``li`` down to ``stop`` [m], then it settles.

    Gravity off, friction ``prep_friction``. The lid moves at ``lid_speed`` and pauses when
    its force passes the pressure cap (``lid_pause``: a fixed :data:`LID_PAUSE_STEPS`, or
    adaptive); a force still above the cap after the pause stops it for good (the layer is
    "pressure capped"). The layer then settles (:func:`settle`, a stress-free layer counting
    as settled, :data:`STRESS_FREE_FRACTION`); the layer's attributes are recorded, the bed
    kept for the next layer and the checkpoint written.
    """
    sim, prep, width = run.sim, run.prep, run.config.geometry.width
    assert sim is not None
    p_cap = _lid_pressure_cap(run.config)
    lid0 = float(np.max(sim.pos[:, 1] + sim.rad)) + 1e-6
    sim.set_lid(lid0, -prep.lid_speed, stop=max(stop, 0.0))
    capped = False
    while sim.lid is not None and sim.lid > stop + 1e-12:
        sim.run(50)
        if sim.lid_force() > p_cap * width:
            # pause and let the layer relax: a fast lid hitting loose disks also gives
            # large transient forces; only a force that persists means a jammed layer
            sim.set_lid(sim.lid, 0.0)
            if prep.lid_pause == "adaptive":
                for _ in range(LID_PAUSE_STEPS // LID_PAUSE_CHECK):
                    sim.run(LID_PAUSE_CHECK)
                    if sim.lid_force() <= p_cap * width:
                        break
            else:
                sim.run(LID_PAUSE_STEPS)
            if sim.lid_force() > p_cap * width:
                capped = True
                break
            sim.set_lid(sim.lid, -prep.lid_speed, stop=max(stop, 0.0))
        if run.progress is not None:
            done = (lid0 - sim.lid) / max(lid0 - stop, 1e-12)
            run.progress("compaction", (li + min(done, 1.0)) / n_l)
    ok_l, r = settle(
        sim,
        prep.equilibrium_ratio,
        prep.max_settle_time / 5.0,
        min_time=2e-3,
        force_floor=STRESS_FREE_FRACTION * run.w_mean,
        relaxation=prep.stage_relaxation("layer"),
    )
    log.info("layer %d/%d: lid %.5f m (target %.5f), ratio %.2e", li + 1, n_l, sim.lid, stop, r)
    run.clock.lap("compaction", sim.step_count, sim.n)
    run.attrs[f"layer{li + 1}_settled"] = bool(ok_l)
    run.attrs[f"layer{li + 1}_lid"] = float(sim.lid or 0.0)
    run.attrs[f"layer{li + 1}_lid_target"] = stop
    run.attrs[f"layer{li + 1}_pressure_capped"] = capped
    run.bed = sim.to_sample()
    if run.ck is not None:
        run.save(li + 1, rng.bit_generator.state)
    if run.progress is not None:
        run.progress("compaction", (li + 1) / n_l)
    run.clock.reset()


def _release_lid(run: _Preparation) -> None:
    """Stage 3: the lid is removed and the design contact (μ, μ_r) restored.

    Records the compacted void ratio (under the lid) and the start of the 1 g stage; with
    ``Numerics.sort_disks`` renumbers the specimen in cell order (idempotent on resume), and
    switches the simulation from the compaction's step to the equilibrium stage's.
    """
    sim = run.sim
    assert sim is not None
    if run.stage == "compaction":
        run.stage_values["e_compacted"] = sim.to_sample().void_ratio(top=sim.lid)
        run.stage_values["t0_1g"] = sim.time
        run.stage = "1g"
    sim.set_lid(None)
    if run.config.numerics.sort_disks:
        # renumber in cell order for memory locality (round-off only; idempotent on resume)
        snap = sim.to_sample()
        order = snap.cell_order()
        if not np.array_equal(order, np.arange(snap.n)):
            run.rebuild(snap.permuted(order), run.stage)
    run.step_of(run.stage)  # from the compaction's plain step to the equilibrium stage's
    assert run.sim is not None
    run.sim.set_soil_contact(run.config.contacts.soil)


def _settle_1g(run: _Preparation) -> None:
    """Stage 4: gravity 1 g, cycled to equilibrium (``Preparation.relaxation``, resumable).

    Records convergence, final ratio and void ratio at 1 g in ``stage_values``.
    """
    assert run.sim is not None
    run.sim.set_gravity(0.0, -GRAVITY)
    run.clock.reset(run.sim.step_count)
    ok1, r1 = run.equilibrium("1g")
    run.clock.lap("1g", run.sim.step_count, run.sim.n)
    run.stage_values.update(ok1=float(ok1), r1=r1, e_1g=run.sim.to_sample().void_ratio())


def _ramp_gravity(run: _Preparation) -> None:
    """Stage 5: gravity ramped linearly from 1 g to N g over ``Loading.gravity_ramp_time``.

    In chunks of about 200 steps (stretched with the inertial mass scaling); with
    ``relaxation = "fire-1g"`` the ramp already takes the N g stage's step. Records the start
    of the N g stage and writes a checkpoint.
    """
    assert run.sim is not None
    if run.subcycled("Ng") != run.subcycled("1g"):  # "fire-1g": the ramp takes the N g step
        run.step_of("Ng")
        run.sim.set_soil_contact(run.config.contacts.soil)
        run.sim.set_gravity(0.0, -GRAVITY)
    sim, n_g = run.sim, run.n_g
    ramp = run.config.loading.gravity_ramp_time * run.stretch
    if ramp > 0:
        n_chunks = max(1, int(ramp / (200 * sim.dt)))
        steps = max(1, round(ramp / sim.dt / n_chunks))
        for c in range(n_chunks):
            f = 1.0 + (n_g - 1.0) * (c + 1) / n_chunks
            sim.set_gravity(0.0, -f * GRAVITY)
            sim.run(steps)
    run.clock.lap("ramp", sim.step_count, sim.n)
    run.stage_values["t0_Ng"] = sim.time
    run.stage = "Ng"
    if run.ck is not None:
        run.save_stage(run.stage)


def _settle_ng(run: _Preparation) -> None:
    """Stage 6: gravity N g, cycled to equilibrium (resumable); records its convergence."""
    assert run.sim is not None
    run.sim.set_gravity(0.0, -run.n_g * GRAVITY)
    run.clock.reset(run.sim.step_count)
    ok2, r2 = run.equilibrium("Ng")
    run.clock.lap("Ng", run.sim.step_count, run.sim.n)
    run.stage_values.update(ok2=float(ok2), r2=r2)


def _finish(run: _Preparation) -> Sample:
    """Stage 7: the specimen at rest (velocities, spins and rotations zeroed), with attributes.

    Void ratio after each stage, convergence and final ratio of each equilibrium stage, the
    criterion, the step and the simulated time.
    """
    sim, sv = run.sim, run.stage_values
    assert sim is not None
    out = sim.to_sample()
    out.velocities[:] = 0.0
    out.omega[:] = 0.0
    out.theta[:] = 0.0
    e_ng = out.void_ratio()
    out.attrs.update(
        run.attrs,
        stage="N g equilibrium",
        gravity_factor=run.n_g,
        n_particles=out.n,
        void_ratio_compacted=sv["e_compacted"],
        void_ratio_1g=sv["e_1g"],
        void_ratio_Ng=e_ng,
        equilibrium_1g_converged=bool(sv["ok1"]),
        equilibrium_1g_ratio=sv["r1"],
        equilibrium_Ng_converged=bool(sv["ok2"]),
        equilibrium_Ng_ratio=sv["r2"],
        equilibrium_criterion=(
            f"mean unbalanced force / mean applied force < {run.prep.equilibrium_ratio:g}"
        ),
        dt=sim.dt,
        time_prepared=sim.time,
    )
    return out
