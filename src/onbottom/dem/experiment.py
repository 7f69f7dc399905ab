"""The penetration experiment: a rigid pipe pushed down at constant speed into the specimen.

The pipe (diameter D) starts just touching the rough soil surface above the box centre
(w = 0 at first contact) and moves down at ``Loading.pipe_velocity`` under N g until
``w = final_embedment_ratio·D``.
The soil force on the pipe is the sum of its contact forces (``V`` = vertical component,
positive = soil pushes the pipe up, N per metre of pipe at model scale). Prototype values:
lengths × N, force per metre × N.

Field snapshots are stored at fixed w/D (``snapshots``) and, by default, at the peak and at the
trough of every softening episode found online (:mod:`onbottom.dem.events`).

Checkpoints: the whole state (disks, contact history, engine parameters, records, snapshots,
the softening detector and its pending candidate snapshots) is written atomically every
``checkpoint_every`` steps; ``penetrate(..., checkpoint=path)``
resumes from it. Pair forces are gathered in a fixed order and the neighbour list only adds
exact zeros, so a resumed run reproduces the uninterrupted one bitwise (tested).
"""

from __future__ import annotations

import json
import logging
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from onbottom.constants import GRAVITY
from onbottom.dem import _kernels as K
from onbottom.dem.analysis import inertial_number, measuring_circles, surface_profile
from onbottom.dem.config import DEMConfig
from onbottom.dem.engine import PipeState, Simulation, step_sizes
from onbottom.dem.events import (
    CONFIRM,
    DEFAULT_EVENT_STEP,
    DEFAULT_MAX_EVENT_SNAPSHOTS,
    END,
    NEW_PEAK,
    NEW_TROUGH,
    SofteningDetector,
)
from onbottom.dem.identity import (
    RESTART_ADVICE,
    CheckpointError,
    CheckpointMismatchError,
    check_identity,
    dem_identity,
    fingerprint,
)
from onbottom.dem.sample import Sample
from onbottom.errors import InputError
from onbottom.results import load_dataset, provenance, save_dataset

__all__ = [
    "DEFAULT_SNAPSHOTS",
    "initial_state",
    "initial_state_of",
    "make_simulation",
    "penetrate",
    "with_initial_state",
]

log = logging.getLogger(__name__)

DEFAULT_SNAPSHOTS = (0.1, 0.2, 0.3, 0.4, 0.5)
"""Embedment ratios w/D at which fields (velocity, rotation, force chains) are stored."""

_LONG = {
    "time": ("time since the pipe started", "s"),
    "w": ("embedment of the pipe invert below the initial surface (model)", "m"),
    "w_over_D": ("normalised embedment w/D", "1"),
    "V": ("vertical soil force on the pipe per unit length (model)", "N/m"),
    "H": ("horizontal soil force on the pipe per unit length (model)", "N/m"),
    "w_prototype": ("embedment at prototype scale (w·N)", "m"),
    "V_prototype": ("vertical force per unit length at prototype scale (V·N)", "N/m"),
    "unbalanced_ratio": ("mean unbalanced / mean applied force", "1"),
    "vx": ("disk velocity, x", "m/s"),
    "vy": ("disk velocity, y", "m/s"),
    "rotation": ("disk rotation since the start of penetration (ccw +)", "rad"),
    "x": ("disk centre x", "m"),
    "y": ("disk centre y", "m"),
    "radius": ("disk radius", "m"),
    "chain_fn": ("normal contact force", "N"),
    "surface": ("soil surface height", "m"),
    "surface0": ("initial soil surface height", "m"),
}

Progress = Callable[[float], None]


def make_simulation(config: DEMConfig, sample: Sample, threads: int | None = None) -> Simulation:
    """A :class:`Simulation` of ``sample`` with the design contacts at N g (no pipe yet)."""
    c = config.contacts
    num = config.numerics
    rho = config.material.density
    floor = num.penetration_mass_floor * rho * math.pi * float(sample.radii.max()) ** 2
    m_min = max(rho * math.pi * float(sample.radii.min()) ** 2, floor)
    safety = num.subcycled_dt_safety if num.subcycle else num.dt_safety
    dt, nsub = step_sizes(c, m_min, safety, num.subcycle)
    return Simulation(
        sample,
        c,
        density=config.material.density,
        damping=config.material.damping,
        dt=dt,
        skin=config.numerics.skin_ratio * 2.0 * float(sample.radii.min()),
        gravity=(0.0, -config.loading.gravity_factor * GRAVITY),
        threads=threads,
        nsub=nsub,
        inertial_mass_floor=floor,
    )


def initial_state(
    config: DEMConfig, sample: Sample, circle_diameter: float | None = None
) -> xr.Dataset:
    """Measuring-circle profiles (porosity, σ_h, σ_v, K0 vs depth) of the prepared specimen.

    ``circle_diameter`` defaults to 0.5D (the paper) when the circles hold about 100 disks or
    more, otherwise 1.0D (reduced presets).
    """
    sim = make_simulation(config, sample)
    surf = sample.surface_height()
    D = config.geometry.pipe_diameter
    if circle_diameter is None:
        per_circle = math.pi * (0.25 * D) ** 2 / config.psd.mean_area()
        circle_diameter = 0.5 * D if per_circle >= 100 else D
    return measuring_circles(
        sim.pos, sim.rad, sim.contact_forces(), sample.box, surf, circle_diameter
    )


def with_initial_state(ds: xr.Dataset, config: DEMConfig, sample: Sample) -> xr.Dataset:
    """The run ``ds`` of :func:`penetrate` with the specimen's :func:`initial_state` added.

    Each profile becomes ``initial_<name>`` on the coordinate ``circle_depth`` [m], and the
    attribute ``circle_diameter`` [m] is the measuring circles' diameter (what ``onbottom dem
    penetrate`` writes, and ``onbottom dem plot`` draws).
    """
    ini = initial_state(config, sample)
    for name, da in ini.data_vars.items():
        ds[f"initial_{name}"] = da.rename({"depth": "circle_depth"})
    ds = ds.assign_coords(circle_depth=("circle_depth", ini["depth"].values))
    ds.attrs["circle_diameter"] = ini.attrs["circle_diameter"]
    return ds


def initial_state_of(ds: xr.Dataset) -> xr.Dataset | None:
    """The initial-state profiles a run or summary carries (:func:`with_initial_state`), as
    :func:`initial_state` returns them (coordinate ``depth``), with the run's ``preset``
    attribute; None when it carries none."""
    if "initial_porosity" not in ds:
        return None
    ini = xr.Dataset(
        {
            k[8:]: ds[k].rename({"circle_depth": "depth"})
            for k in ds.data_vars
            if str(k).startswith("initial_")
        }
    )
    ini.attrs["preset"] = ds.attrs.get("preset", "")
    return ini


def _touch_height(sample: Sample, xc: float, radius: float) -> float:
    """Lowest pipe-centre height at which the pipe (centre abscissa xc) touches no disk [m]."""
    dx = sample.positions[:, 0] - xc
    reach = radius + sample.radii
    sel = np.abs(dx) < reach
    y = sample.positions[sel, 1] + np.sqrt(reach[sel] ** 2 - dx[sel] ** 2)
    return float(np.max(y))


def _state_dataset(sim: Simulation) -> xr.Dataset:
    s = sim.to_sample()
    return s.to_dataset()


def _store_snapshot(ds: xr.Dataset, pre: str, snap: xr.Dataset) -> None:
    # snap.variables, not snap.data_vars: "info" lies on its own dimension (a coordinate)
    for name, var in snap.variables.items():
        ds[f"{pre}{name}"] = ([f"{pre}{d}" for d in var.dims], var.values)


def _read_snapshot(ds: xr.Dataset, pre: str) -> xr.Dataset:
    # ds.variables, not ds.data_vars: "<pre>info" lies on its own dimension, so xarray reads it
    # back as a coordinate
    vars_ = {
        str(k)[len(pre) :]: ([str(d)[len(pre) :] for d in var.dims], var.values)
        for k, var in ds.variables.items()
        if str(k).startswith(pre)
    }
    return xr.Dataset(vars_)


class _Events:
    """Event snapshots of a run: the detector, the candidates and the committed snapshots."""

    def __init__(self, detector: SofteningDetector, cap: int) -> None:
        self.det = detector
        self.cap = cap
        self.stored: list[xr.Dataset] = []
        self.cand: dict[str, xr.Dataset] = {}  # "bin", "peak", "trough"
        self.cand_bin = -1  # bin of cand["bin"]
        self.skipped = 0  # episodes found after the cap was reached
        self.peak_stored = False  # the current episode's peak snapshot is stored

    def meta(self) -> dict:
        return {
            "detector": self.det.state(),
            "cap": self.cap,
            "n_events": len(self.stored),
            "candidates": sorted(self.cand),
            "cand_bin": self.cand_bin,
            "skipped": self.skipped,
            "peak_stored": self.peak_stored,
        }

    @classmethod
    def from_meta(cls, meta: dict, ds: xr.Dataset) -> _Events:
        ev = cls(SofteningDetector.from_state(meta["detector"]), int(meta["cap"]))
        ev.stored = [_read_snapshot(ds, f"event{q}_") for q in range(int(meta["n_events"]))]
        ev.cand = {name: _read_snapshot(ds, f"cand_{name}_") for name in meta["candidates"]}
        ev.cand_bin = int(meta["cand_bin"])
        ev.skipped = int(meta["skipped"])
        ev.peak_stored = bool(meta["peak_stored"])
        return ev

    def _commit(self, kind: int, snap: xr.Dataset | None) -> bool:
        episode = len(self.det.episodes) if kind == 1 else len(self.det.episodes) - 1
        if snap is None:  # no candidate (records sparser than the bins): nothing to store
            return False
        tagged = snap.copy()
        tagged["event"] = ("event", np.array([kind, episode], float))
        self.stored.append(tagged)
        return True

    def record(self, sim: Simulation, theta0: np.ndarray, w: float, D: float) -> None:
        """Process the record just made at embedment ``w`` (V already in the detector)."""
        wd = w / D
        k = self.det.bin_of(wd)
        if wd >= 0.0 and k != self.cand_bin and wd >= self.det.centre(k):
            self.cand["bin"] = _snapshot(sim, theta0, wd, w)
            self.cand_bin = k

    def act(self, actions: list[tuple[str, int]]) -> None:
        """Move or commit candidates on the detector's actions for a closed bin."""
        for name, k in actions:
            snap = self.cand.get("bin") if k == self.cand_bin else None
            if name == NEW_PEAK:
                self._set("peak", snap)
                self.peak_stored = False
            elif name == NEW_TROUGH:
                self._set("trough", snap)
            elif name == CONFIRM:
                if len(self.stored) + 2 <= self.cap:
                    self.peak_stored = self._commit(1, self.cand.get("peak"))
                else:
                    self.skipped += 1
            elif name == END:
                if self.peak_stored:
                    self._commit(2, self.cand.get("trough"))
                self.peak_stored = False
                self.cand.pop("trough", None)

    def _set(self, slot: str, snap: xr.Dataset | None) -> None:
        if snap is None:
            self.cand.pop(slot, None)
        else:
            self.cand[slot] = snap


def _save_checkpoint(
    path: Path,
    sim: Simulation,
    records: dict[str, list[float]],
    snaps: list[xr.Dataset],
    meta: dict,
    theta0: np.ndarray,
    events: _Events | None = None,
) -> None:
    ds = _state_dataset(sim)
    ds["engine_prm"] = ("prm", sim.prm.copy())
    ds["theta0"] = ("particle", theta0)
    for k, vals in records.items():
        ds[f"rec_{k}"] = ("record", np.asarray(vals, float))
    extra = {"events": events.meta()} if events is not None else {}
    ds.attrs["checkpoint_meta"] = json.dumps(
        {**meta, **extra, "step_count": sim.step_count, "n_snapshots": len(snaps)}
    )
    for q, snap in enumerate(snaps):
        _store_snapshot(ds, f"snap{q}_", snap)
    if events is not None:
        for q, snap in enumerate(events.stored):
            _store_snapshot(ds, f"event{q}_", snap)
        for name, snap in events.cand.items():
            _store_snapshot(ds, f"cand_{name}_", snap)
    save_dataset(ds, path)


def _load_checkpoint(
    path: Path, config: DEMConfig, threads: int | None, identity: dict | None = None
):
    try:
        ds = load_dataset(path)
        meta = json.loads(ds.attrs["checkpoint_meta"])
        for key in ("step_count", "n_snapshots", "surf0"):
            meta[key]  # presence check
        sample = Sample.from_dataset(ds)
        ds["engine_prm"], ds["theta0"]  # presence check
    except Exception as exc:  # any failure to read means: not a usable checkpoint
        raise CheckpointError(
            f"penetration checkpoint {path} cannot be read ({type(exc).__name__}: {exc}); it"
            f" is truncated, corrupt or not a checkpoint; {RESTART_ADVICE}"
        ) from None
    if identity is not None:
        check_identity(meta.get("identity"), identity, path, what="penetration checkpoint")
    sim = make_simulation(config, sample, threads)
    sim.prm[:] = ds["engine_prm"].values
    sim.step_count = int(meta["step_count"])
    records = {str(k)[4:]: list(ds[k].values) for k in ds.data_vars if str(k).startswith("rec_")}
    snaps = [_read_snapshot(ds, f"snap{q}_") for q in range(int(meta["n_snapshots"]))]
    events = None
    if "events" in meta:
        try:
            events = _Events.from_meta(meta["events"], ds)
        except Exception as exc:
            raise CheckpointError(
                f"penetration checkpoint {path} holds unreadable event-snapshot state"
                f" ({type(exc).__name__}: {exc}); {RESTART_ADVICE}"
            ) from None
    return sim, records, snaps, meta, ds["theta0"].values, events


def _snapshot(sim: Simulation, theta0: np.ndarray, ratio: float, w: float) -> xr.Dataset:
    c = sim.contact_forces()
    return xr.Dataset(
        {
            "x": ("particle", sim.pos[:, 0].copy()),
            "y": ("particle", sim.pos[:, 1].copy()),
            "vx": ("particle", sim.vel[:, 0].copy()),
            "vy": ("particle", sim.vel[:, 1].copy()),
            "rotation": ("particle", sim.th - theta0),
            "chain_i": ("chain", c["i"]),
            "chain_j": ("chain", c["j"]),
            "chain_fn": ("chain", c["fn"]),
            "info": ("info", np.array([ratio, w, sim.pipe.y if sim.pipe else np.nan])),
        }
    )


def penetrate(
    config: DEMConfig,
    sample: Sample,
    *,
    checkpoint: str | Path | None = None,
    checkpoint_every: int = 200_000,
    resume: bool = True,
    snapshots: tuple[float, ...] = DEFAULT_SNAPSHOTS,
    threads: int | None = None,
    max_steps: int | None = None,
    progress: Progress | None = None,
    restart: bool = False,
    event_snapshots: bool = True,
    event_drop_fraction: float = 0.05,
    event_step: float = DEFAULT_EVENT_STEP,
    max_event_snapshots: int = DEFAULT_MAX_EVENT_SNAPSHOTS,
) -> xr.Dataset:
    """Push the pipe into ``sample`` and return the V–w record and the field snapshots.

    Parameters
    ----------
    config
        Experiment configuration (velocity, final embedment, contacts ...).
    sample
        Specimen at N g equilibrium (from :func:`~onbottom.dem.preparation.prepare_sample`).
    checkpoint
        Checkpoint file (NetCDF); written every ``checkpoint_every`` steps, read when it exists
        and ``resume`` is true. It carries the run identity (configuration, seed, velocity,
        specimen, engine and file-format versions, :mod:`onbottom.dem.identity`): resuming a
        checkpoint of another run raises
        :class:`~onbottom.dem.identity.CheckpointMismatchError` naming the differing fields,
        an unreadable one :class:`~onbottom.dem.identity.CheckpointError`.
    checkpoint_every
        Steps between checkpoints [-].
    snapshots
        Embedment ratios w/D at which fields are stored.
    threads
        Numba threads (``None`` → automatic, see :class:`~onbottom.dem.engine.Simulation`).
    max_steps
        Stop after this many steps of this call (the run can then be resumed); ``None`` → run
        to the final embedment.
    progress
        Callback receiving the fraction of the final embedment reached.
    restart
        Delete an existing checkpoint and start afresh.
    event_snapshots
        Also store a field snapshot at the peak and at the trough of every softening episode
        found while the pipe goes down (:mod:`onbottom.dem.events`: the summary's episode
        definition applied online to bin means of V).
    event_drop_fraction
        Smallest drop below the running peak that makes an episode [-], in (0, 1) (the
        summary's ``drop_fraction``).
    event_step
        Bin width of the detector's V averaging in w/D [-] (the summary's ``step``); one
        candidate snapshot per bin.
    max_event_snapshots
        Cap on the stored event snapshots (peak and trough in pairs) [-], >= 2; episodes found
        after it is reached are counted in ``attrs["event_episodes_skipped"]``.

    Returns
    -------
    xarray.Dataset
        Variables on ``record``: time, w, w_over_D, V, H, prototype values, unbalanced ratio;
        snapshot fields on ``snapshot`` × ``particle`` (the fixed ones first, then the event
        snapshots in the order stored; ``snapshot_kind`` "fixed"/"peak"/"trough",
        ``snapshot_w``, ``snapshot_V`` (V of the record the fields belong to),
        ``snapshot_V_bin`` (bin mean of V there), ``snapshot_episode`` (-1 for fixed));
        force chains flattened on ``chain`` with ``chain_snapshot``; initial/final surface
        profiles; attributes with the inertial number, the time step, ``complete`` (False
        when stopped by ``max_steps``) and the event-snapshot settings and counts
        (``event_*``; ``event_snapshots_capped`` = 1 when the cap was hit).
    """
    # settings
    D = config.geometry.pipe_diameter
    N = config.loading.gravity_factor
    w_end = config.loading.final_embedment_ratio * D
    v = config.loading.pipe_velocity
    _check_run_options(checkpoint_every, max_steps, event_snapshots, max_event_snapshots)
    # validates event_step and event_drop_fraction (named InputErrors)
    fresh_events = _Events(
        SofteningDetector(step=event_step, drop_fraction=event_drop_fraction),
        int(max_event_snapshots),
    )
    identity = dem_identity(config, "penetration", sample=sample).fields
    ck = Path(checkpoint) if checkpoint is not None else None
    if ck is not None and restart:
        ck.unlink(missing_ok=True)
    # setup: a fresh run, or the checkpoint's
    if ck is not None and resume and ck.exists():
        run = _resume(ck, config, threads, identity, snapshots, D, fresh_events, event_snapshots)
    else:
        run = _start(config, sample, threads, D, v, fresh_events if event_snapshots else None)
    run.meta["identity"] = identity
    surf0 = float(run.meta["surf0"])
    steps_total = math.ceil(w_end / v / run.sim.dt)
    # the loop: push, record, checkpoint
    _push(
        run,
        snapshots,
        D,
        v,
        surf0,
        steps_total,
        rec_every=config.numerics.record_every,
        max_steps=max_steps,
        progress=progress,
        ck=ck,
        checkpoint_every=checkpoint_every,
    )
    return _result(config, sample, run, ck, identity, steps_total, surf0, N)


def _check_run_options(
    checkpoint_every: int, max_steps: int | None, event_snapshots: bool, max_event_snapshots: int
) -> None:
    """Named errors for the run options of :func:`penetrate`."""
    if int(checkpoint_every) < 1:
        raise CheckpointError(
            f"checkpoint_every = {checkpoint_every!r} is invalid: must be >= 1",
            field="checkpoint_every",
        )
    if max_steps is not None and int(max_steps) < 0:
        raise CheckpointError(
            f"max_steps = {max_steps!r} is invalid: must be >= 0", field="max_steps"
        )
    if not isinstance(event_snapshots, bool | np.bool_):
        raise InputError(f"event_snapshots = {event_snapshots!r} is invalid: must be True or False")
    if (
        isinstance(max_event_snapshots, bool)
        or not isinstance(max_event_snapshots, int | np.integer)
        or max_event_snapshots < 2
    ):
        raise InputError(
            f"max_event_snapshots = {max_event_snapshots!r} is invalid: must be an integer >= 2"
            " (peak and trough are stored in pairs)"
        )


@dataclass
class _PenetrationRun:
    """The state of a penetration between the stages of :func:`penetrate` (and in its
    checkpoint): the simulation, the records, the field snapshots, the run's metadata
    (``surf0``, ``xc``, identity), the initial rotations and the event-snapshot state."""

    sim: Simulation
    records: dict[str, list]
    snaps: list
    meta: dict[str, Any]
    theta0: np.ndarray
    events: _Events | None
    events_note: str = ""


def _start(
    config: DEMConfig,
    sample: Sample,
    threads: int | None,
    D: float,
    v: float,
    events: _Events | None,
) -> _PenetrationRun:
    """A fresh run: the pipe above the sample's centre, touching its rough surface at w = 0."""
    sim = make_simulation(config, sample, threads)
    xc = 0.5 * (sample.box[0] + sample.box[1])
    # w = 0 when the pipe first touches the rough surface
    surf0 = _touch_height(sample, xc, 0.5 * D) - 0.5 * D
    sim.set_pipe(PipeState(xc, surf0 + 0.5 * D, 0.5 * D, -v))
    sim.time = 0.0
    theta0 = sim.th.copy()
    records: dict[str, list] = {k: [] for k in ("time", "w", "V", "H", "unbalanced_ratio")}
    return _PenetrationRun(sim, records, [], {"surf0": surf0, "xc": xc}, theta0, events)


def _resume(
    ck: Path,
    config: DEMConfig,
    threads: int | None,
    identity: dict[str, Any],
    snapshots: tuple[float, ...],
    D: float,
    fresh_events: _Events,
    event_snapshots: bool,
) -> _PenetrationRun:
    """The run of checkpoint ``ck`` (its identity checked); its event detector when it has
    one under the same settings, none (with a note) when it has none."""
    sim, records, snaps, meta, theta0, ck_events = _load_checkpoint(ck, config, threads, identity)
    log.info("resumed from %s at step %d", ck, sim.step_count)
    meta.pop("events", None)
    events: _Events | None = fresh_events if event_snapshots else None
    events_note = ""
    if event_snapshots and ck_events is None:
        events = None
        events_note = "checkpoint without event-snapshot state: event snapshots off"
        log.warning("resumed %s has no event-snapshot state: event snapshots off", ck)
    elif event_snapshots and ck_events is not None:
        _check_event_settings(ck_events, fresh_events, ck)
        events = ck_events
    return _PenetrationRun(sim, records, snaps, meta, theta0, events, events_note)


def _push(
    run: _PenetrationRun,
    snapshots: tuple[float, ...],
    D: float,
    v: float,
    surf0: float,
    steps_total: int,
    *,
    rec_every: int,
    max_steps: int | None,
    progress: Progress | None,
    ck: Path | None,
    checkpoint_every: int,
) -> None:
    """Push the pipe (velocity ``v`` [m/s]) down ``rec_every`` steps at a time to
    ``steps_total`` (or ``max_steps`` of this call): a record per chunk, field snapshots as
    the embedment passes them, the event detector fed, a checkpoint every
    ``checkpoint_every`` steps."""
    sim, records, snaps, theta0, events = run.sim, run.records, run.snaps, run.theta0, run.events
    next_ck = (sim.step_count // checkpoint_every + 1) * checkpoint_every
    done_here = 0
    while True:
        assert sim.pipe is not None
        w = surf0 - (sim.pipe.y - 0.5 * D)
        while len(snaps) < len(snapshots) and w >= snapshots[len(snaps)] * D - 0.5 * v * sim.dt:
            snaps.append(_snapshot(sim, theta0, snapshots[len(snaps)], w))
        if sim.step_count >= steps_total:
            break
        if max_steps is not None and done_here >= max_steps:
            break
        n = min(rec_every, steps_total - sim.step_count)
        sim.run(n)
        done_here += n
        fx, fy = sim.pipe_force()
        w_now = surf0 - (sim.pipe.y - 0.5 * D)
        records["time"].append(sim.time)
        records["w"].append(w_now)
        records["V"].append(fy)
        records["H"].append(fx)
        records["unbalanced_ratio"].append(sim.unbalanced_ratio())
        if events is not None:
            events.act(events.det.push(w_now / D, fy))
            events.record(sim, theta0, w_now, D)
        if progress is not None:
            progress(min(1.0, sim.step_count / steps_total))
        if ck is not None and sim.step_count >= next_ck:
            _save_checkpoint(ck, sim, records, snaps, run.meta, theta0, events)
            next_ck += checkpoint_every


def _result(
    config: DEMConfig,
    sample: Sample,
    run: _PenetrationRun,
    ck: Path | None,
    identity: dict[str, Any],
    steps_total: int,
    surf0: float,
    N: float,
) -> xr.Dataset:
    """The result of :func:`penetrate` (an unfinished run checkpointed first): the records,
    the snapshots, the event-snapshot attributes and the run identity."""
    sim, events = run.sim, run.events
    complete = sim.step_count >= steps_total
    if ck is not None and not complete:
        _save_checkpoint(ck, sim, run.records, run.snaps, run.meta, run.theta0, events)
    if events is not None and complete:
        # the record ends: the open bin closes, a drop still under way ends there
        events.act(events.det.close_bin())
        events.act([(a, events.det.bin) for a in events.det.finish()])
    ds = _assemble(config, sample, sim, run.records, run.snaps, surf0, complete, N, events)
    _event_attrs(ds, events, run.events_note)
    # the configuration itself is in attrs["config"]; the rest of the identity here
    ds.attrs["run_identity"] = json.dumps(
        {k: v for k, v in identity.items() if k != "config"}, sort_keys=True
    )
    ds.attrs["run_fingerprint"] = fingerprint(identity)
    ds.attrs["sample_fingerprint"] = identity["sample"]
    return ds


def _event_attrs(ds: xr.Dataset, events: _Events | None, events_note: str) -> None:
    """The event-snapshot settings and counts (``event_*`` attributes) of the result."""
    if events is not None:
        ds.attrs.update(
            event_snapshots=1,
            event_settings=(
                f"step={events.det.step:g} w/D, drop_fraction={events.det.drop_fraction:g},"
                f" max={events.cap} (rule: onbottom.dem.events)"
            ),
            event_episodes_found=len(events.det.episodes) + int(events.det.confirmed),
            event_episodes_skipped=int(events.skipped),
            event_snapshots_capped=int(events.skipped > 0),
        )
        if events.skipped:
            ds.attrs["event_snapshots_note"] = (
                f"cap of {events.cap} event snapshots reached: {events.skipped} later episodes"
                " have no snapshots"
            )
    else:
        ds.attrs["event_snapshots"] = 0
        if events_note:
            ds.attrs["event_snapshots_note"] = events_note


def _check_event_settings(found: _Events, asked: _Events, path: Path) -> None:
    """Refuse to resume event detection under other settings than it was started with."""
    diff = [
        f"{name}: checkpoint {a!r}, asked {b!r}"
        for name, a, b in (
            ("event_step", found.det.step, asked.det.step),
            ("event_drop_fraction", found.det.drop_fraction, asked.det.drop_fraction),
            ("max_event_snapshots", found.cap, asked.cap),
        )
        if a != b
    ]
    if diff:
        raise CheckpointMismatchError(
            f"penetration checkpoint {path} detects softening episodes with other settings"
            f" ({'; '.join(diff)}); resume with the same settings or {RESTART_ADVICE}",
            [d.split(":")[0] for d in diff],
            field=diff[0].split(":")[0],
        )


def _record_at(w: np.ndarray, V: np.ndarray, at: np.ndarray) -> np.ndarray:
    """V of the record nearest to each embedment ``at`` (NaN without records)."""
    if w.size == 0:
        return np.full(at.shape, np.nan)
    return V[np.argmin(np.abs(w[None, :] - at[:, None]), axis=1)]


def _bin_mean_at(wd: np.ndarray, V: np.ndarray, at: np.ndarray, step: float) -> np.ndarray:
    """Mean V of the records in the bin of w/D (width ``step``) holding each ``at``."""
    out = np.full(at.shape, np.nan)
    kr = np.floor(wd / step)
    for q, a in enumerate(at):
        sel = (kr == np.floor(a / step)) & np.isfinite(V) & (wd >= 0.0)
        if np.any(sel):
            out[q] = float(np.mean(V[sel]))
    return out


def _assemble(
    config: DEMConfig,
    sample: Sample,
    sim: Simulation,
    records: dict[str, list[float]],
    snaps: list[xr.Dataset],
    surf0: float,
    complete: bool,
    N: float,
    events: _Events | None = None,
) -> xr.Dataset:
    D = config.geometry.pipe_diameter
    w = np.asarray(records["w"], float)
    V = np.asarray(records["V"], float)
    bin_w = 2.0 * config.psd.d_max
    xs, top0 = surface_profile(sample.positions, sample.radii, sample.box, bin_w)
    _, top1 = surface_profile(sim.pos, sim.rad, sample.box, bin_w)
    data: dict[str, tuple] = {
        "time": ("record", np.asarray(records["time"], float)),
        "w": ("record", w),
        "w_over_D": ("record", w / D),
        "V": ("record", V),
        "H": ("record", np.asarray(records["H"], float)),
        "w_prototype": ("record", w * N),
        "V_prototype": ("record", V * N),
        "unbalanced_ratio": ("record", np.asarray(records["unbalanced_ratio"], float)),
        "surface0": ("x_bin", top0),
        "surface": ("x_bin", top1),
        "radius": ("particle", sim.rad.copy()),
    }
    kinds = ["fixed"] * len(snaps)
    episode = [-1] * len(snaps)
    if events is not None and events.stored:
        for ev in events.stored:
            kind, ep = (int(v) for v in ev["event"].values)
            kinds.append("peak" if kind == 1 else "trough")
            episode.append(ep)
        snaps = [*snaps, *events.stored]
    if snaps:
        for name in ("x", "y", "vx", "vy", "rotation"):
            data[name] = (("snapshot", "particle"), np.stack([s[name].values for s in snaps]))
        data["chain_i"] = ("chain", np.concatenate([s["chain_i"].values for s in snaps]))
        data["chain_j"] = ("chain", np.concatenate([s["chain_j"].values for s in snaps]))
        data["chain_fn"] = ("chain", np.concatenate([s["chain_fn"].values for s in snaps]))
        data["chain_snapshot"] = (
            "chain",
            np.concatenate([np.full(s.sizes["chain"], q) for q, s in enumerate(snaps)]),
        )
        sw = np.array([float(s["info"].values[1]) for s in snaps])
        data["snapshot_w"] = ("snapshot", sw)
        data["snapshot_kind"] = ("snapshot", np.array(kinds, dtype=str))
        data["snapshot_episode"] = ("snapshot", np.array(episode, int))
        data["snapshot_V"] = ("snapshot", _record_at(w, V, sw))
        step = events.det.step if events is not None else DEFAULT_EVENT_STEP
        data["snapshot_V_bin"] = ("snapshot", _bin_mean_at(w / D, V, sw / D, step))
    coords = {"x_bin": ("x_bin", xs)}
    if snaps:
        coords["snapshot"] = ("snapshot", np.array([float(s["info"].values[0]) for s in snaps]))
    ds = xr.Dataset(data, coords=coords)
    for name, (ln, un) in _LONG.items():
        if name in ds:
            ds[name].attrs.update(long_name=ln, units=un)
    porosity = sample.void_ratio() / (1.0 + sample.void_ratio())
    inum = inertial_number(
        config.loading.pipe_velocity,
        config.geometry.height,
        config.psd.d50,
        config.material.density,
        porosity,
        N,
    )
    # with inertial mass scaling the d50 disk's inertia is max(m50, floor): I grows as its root
    rho, d50 = config.material.density, config.psd.d50
    m50 = rho * math.pi * d50 * d50 / 4.0
    floor = config.numerics.penetration_mass_floor * rho * math.pi * float(sample.radii.max()) ** 2
    inum_scaled = inum * math.sqrt(max(m50, floor) / m50)
    ds.attrs.update(
        provenance(
            "dem.penetration",
            None,
            config=config.to_json(),
            preset=config.name,
            n_particles=int(sim.n),
            dt=float(sim.dt),
            steps=int(sim.step_count),
            rebuilds=int(sim.rebuilds),
            inertial_number=float(inum),
            inertial_number_scaled=float(inum_scaled),
            quasi_static=int(inum_scaled <= 1e-3),
            complete=int(complete),
            gravity_factor=float(N),
            pipe_diameter=float(D),
            surface0_at_pipe=float(surf0),
            pipe_x=float(sim.pipe.x) if sim.pipe is not None else float("nan"),
            initial_void_ratio=float(sample.void_ratio()),
            seed=int(config.seed),
            engine_prm_layout="see onbottom.dem._kernels P_* indices",
        )
    )
    ds.attrs["n_prm"] = K.N_PRM
    return ds
