"""One pipeline FE run through a storm, from built objects (``onbottom storm`` with ``[pipeline]``).

:class:`PipelineStormRun` is a plain value type: the pipeline model, the storm setup and the
solver settings (:mod:`onbottom.cases.pipeline` builds it from a case file; it can be built by
hand). :func:`simulate_pipeline_storm` draws the node kinematics of one seed of the storm and
runs :func:`onbottom.dynamics.pipeline.simulate_pipeline`; :func:`run_cost` is the cost model
that refuses an excessive mesh up front and sizes seed campaigns
(:func:`onbottom.study.pipeline_seeds.estimate_pipeline_seeds`).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onbottom.dynamics.pipeline.model import PipelineModel
from onbottom.dynamics.pipeline.solver import PipelineResult, PipelineSettings, simulate_pipeline
from onbottom.dynamics.storm_setup import StormSetup
from onbottom.hydro.storm_kinematics import StormKinematics

if TYPE_CHECKING:
    from onbottom.hydro.short_crested import NodeKinematics, WindowedNodeKinematics
    from onbottom.inputs.storm import Storm

__all__ = [
    "BYTES_PER_NODE_HOUR",
    "KINEMATICS_MEMORY_LIMIT",
    "SECONDS_PER_NODE_STEP",
    "PipelineStormRun",
    "RunCost",
    "node_kinematics",
    "run_cost",
    "simulate_pipeline_storm",
    "storm_duration",
]

#: Cost figures of the pipeline FE used to refuse a mesh up front: about 1 µs per node and
#: time step (H13's benchmark); 0.5 MB per node and hour of storm for the kinematics, a
#: conservative figure (H18 measured 0.13 MB per node-hour in the final arrays of
#: examples/pipeline_case.toml at the default sample interval T_p/50; synthesis needs
#: working copies on top).
SECONDS_PER_NODE_STEP = 1.0e-6
BYTES_PER_NODE_HOUR = 0.5e6
KINEMATICS_MEMORY_LIMIT = 256 * 2**20
"""Storm kinematics larger than this [bytes] are kept in a temporary file and read in time
windows as the run advances (:class:`~onbottom.hydro.short_crested.WindowedNodeKinematics`:
the same values, the same results)."""


def storm_duration(storm: Storm | StormKinematics) -> float:
    """Duration [s] of a spectral :class:`Storm` or of given kinematics (regular, measured)."""
    return float(storm.duration_s if hasattr(storm, "duration_s") else storm.duration)


@dataclass(frozen=True)
class RunCost:
    """Estimated cost of one pipeline storm (:func:`run_cost`).

    Attributes
    ----------
    nodes : int
        FE nodes [-].
    storm_s, run_s : float
        Storm duration and simulated time [s] (``run_s`` <= ``storm_s``).
    steps : float
        Time steps at the largest step [-].
    cpu_s : float
        Computing time on one core [s] (:data:`SECONDS_PER_NODE_STEP` per node-step).
    memory_bytes : float
        Storm kinematics [bytes] (:data:`BYTES_PER_NODE_HOUR` per node-hour of storm).
    """

    nodes: int
    storm_s: float
    run_s: float
    steps: float
    cpu_s: float
    memory_bytes: float


def run_cost(
    nodes: int, storm: Storm | StormKinematics, duration: float | None, dt_max: float
) -> RunCost:
    """Cost of ``nodes`` nodes through ``storm`` for ``duration`` [s] (None → the whole storm)
    at the largest time step ``dt_max`` [s]."""
    storm_s = storm_duration(storm)
    run_s = storm_s if duration is None else min(duration, storm_s)
    steps = run_s / dt_max
    return RunCost(
        nodes=int(nodes),
        storm_s=storm_s,
        run_s=run_s,
        steps=steps,
        cpu_s=SECONDS_PER_NODE_STEP * nodes * steps,
        memory_bytes=BYTES_PER_NODE_HOUR * nodes * storm_s / 3600.0,
    )


@dataclass(frozen=True)
class PipelineStormRun:
    """A pipeline FE storm run, built (picklable: a seed campaign sends it to its workers).

    Parameters
    ----------
    model : PipelineModel
        The line, its soil along the route, its hydrodynamic force model and current.
    setup : StormSetup
        The storm (``storm``: a spectral :class:`Storm`, or the :class:`StormKinematics` of a
        regular wave or a measured record), ``depth`` [m], ``sample_interval`` [s] and
        ``seeds`` (the default number of storms).
    settings : PipelineSettings
        HHT-α, time steps [s], Newton tolerances, records and checkpoints.
    duration : float or None
        Simulate only [0, duration] [s]; None → the whole storm.
    animation : path or None
        GIF of the line in the storm asked for by the case (written by the caller).
    attrs : mapping
        Provenance attributes of the results (e.g. ``case_file``).
    identity : mapping
        More identity of the run for resuming (e.g. ``case``: the case file's text): a
        checkpoint or finished output resumes only a run of the same identity.
    """

    model: PipelineModel
    setup: StormSetup
    settings: PipelineSettings
    duration: float | None = None
    animation: Path | None = None
    attrs: Mapping[str, Any] = field(default_factory=dict)
    identity: Mapping[str, Any] = field(default_factory=dict)

    def cost(self) -> RunCost:
        """:func:`run_cost` of this run."""
        return run_cost(
            int(self.model.x.size), self.setup.storm, self.duration, self.settings.dt_max
        )


def node_kinematics(run: PipelineStormRun, seed: int) -> NodeKinematics | WindowedNodeKinematics:
    """Near-bed kinematics at the nodes of ``run`` for storm ``seed``.

    A spectral storm is drawn short-crested with seed ``seed``; a regular wave (travelling
    along the line at its angle) or a measured record (in phase along the line) is
    long-crested and has no seed. Kinematics above :data:`KINEMATICS_MEMORY_LIMIT` are
    windowed (read from a temporary file as the run advances).
    """
    from onbottom.hydro.short_crested import long_crested_node_kinematics, pipeline_kinematics

    setup, model = run.setup, run.model
    if isinstance(setup.storm, StormKinematics):
        return long_crested_node_kinematics(setup.storm, model.x.size, model.x)
    storm = setup.storm.with_seed(int(seed))
    return pipeline_kinematics(
        storm,
        setup.depth,
        model.x,
        sample_interval=setup.sample_interval,
        memory_limit=KINEMATICS_MEMORY_LIMIT,
    )


def simulate_pipeline_storm(
    run: PipelineStormRun,
    seed: int,
    *,
    output: str | os.PathLike | None = None,
    progress: bool = False,
    restart: bool = False,
) -> PipelineResult:
    """Simulate ``run`` through storm ``seed``.

    Parameters
    ----------
    run : PipelineStormRun
    seed : int
        Seed of the random phases (see :func:`node_kinematics`).
    output : path or None
        NetCDF file, written as ``<output>.part`` during the run and renamed when complete;
        its checkpoint ``<output>.ckpt.npz`` resumes an interrupted run of the same identity
        (removed at the end); a finished output of the same run is returned as it is.
    progress : bool
        Progress bar.
    restart : bool
        Discard checkpoints and partial files of an earlier run and start afresh.
    """
    kin = node_kinematics(run, seed)
    try:
        return _simulate(run, seed, kin, output, progress, restart)
    finally:
        close = getattr(kin, "close", None)
        if close is not None:
            close()  # a windowed storm's temporary file


def _simulate(run, seed, kin, output, progress, restart) -> PipelineResult:
    return simulate_pipeline(
        run.model,
        kin,
        duration=run.duration,
        settings=run.settings,
        output=output,
        progress=progress,
        attrs={**run.attrs, "seed": int(seed)},
        identity_extra={**run.identity, "seed": int(seed)},
        resume="never" if restart else "auto",
    )
