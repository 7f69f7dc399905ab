"""Short-crested near-bed kinematics along a pipeline (single-summation synthesis, numpy FFT).

Near-bed wave velocity normal to a straight pipe on the x axis (wave directions θ measured
from the pipe axis, 90° = waves travelling normal to the pipe towards +y; linear wave theory,
DNV-RP-F109 (2010) §3.2)::

    u_n(x, t) = Σ_j a_j G(ω_j) sin θ_j cos(ω_j t − k_j x cos θ_j + φ_j)

synthesised by the stages of :mod:`onbottom.hydro.flow_synthesis` (the package's one flow
synthesiser: :func:`~onbottom.hydro.flow_synthesis.node_synthesis` and
:func:`~onbottom.hydro.flow_synthesis.node_block_series`), with

* a_j = √(2 S_ηη(ω_j) Δω) from the stage's JONSWAP/Pierson–Moskowitz spectrum
  (:mod:`onbottom.hydro.spectra`, DNV-RP-C205 §3.5.5), G = ω/sinh(kd) the linear transfer to
  the seabed (:mod:`onbottom.hydro.kinematics`, DNV-RP-F109 §3.4.3);
* **single summation**: one direction θ_j = θ_m + δ_j per frequency component, δ_j drawn from
  the spreading density D_w(δ) ∝ cos^s δ on |δ| < π/2 by its inverse CDF
  (:func:`onbottom.hydro.spreading.directions_cos_s`, DNV-RP-F109 (2010) Eq 3.8; the exponent
  is that of ``SeaState.spreading_s``, cos^s as in F109 — a "cos^2s" form is the same family
  with s ↔ 2s). The sea is ergodic and no spreading factor R_D is applied: the variance of
  u_n over the components tends to R_D²·M_0 (checked by a test against
  :func:`onbottom.hydro.spreading.spreading_factor`). s = 0 gives a long-crested sea;
* φ_j uniform on [0, 2π) from ``numpy.random.default_rng(storm.seed)``; phases and the
  uniform numbers behind δ_j are shared by all stages, so stage blends are coherent.

The frequencies are the harmonics ω_j = jΔω of a record ≥ the storm duration (the series does
not repeat within the storm), summed by one inverse real FFT per node and stage; nodes are
processed in blocks and the result is kept in float32 (velocity and acceleration: 8 bytes per
node and sample — 500 nodes × 3.5 h at 0.2 s ≈ 0.25 GB; with ``memory_limit`` a larger
storm is written node by node to a temporary file, :class:`WindowedNodeKinematics`, and the
solver reads the time windows it reaches: the same float32 values, a window in memory).
Stage weights (build-up, blends, decay) are those of the section storm
(:func:`onbottom.hydro.flow_synthesis.stage_weights`):
U = Σ_k w_k U_k, U̇ = Σ_k (w_k U̇_k + ẇ_k U_k).
"""

from __future__ import annotations

import hashlib
import math
import os
import tempfile
import weakref
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from onbottom._validate import positive
from onbottom.errors import InputError
from onbottom.hydro.flow_synthesis import NodeSynthesis, node_block_series, node_synthesis
from onbottom.hydro.storm_kinematics import StormKinematics, seabed_velocity_parameters
from onbottom.inputs.storm import Storm

__all__ = [
    "NodeKinematics",
    "WindowedNodeKinematics",
    "long_crested_node_kinematics",
    "pipeline_kinematics",
    "regular_node_kinematics",
]


@dataclass(frozen=True, eq=False)
class NodeKinematics:
    """Near-bed wave velocity and acceleration normal to the pipe at every node.

    Attributes
    ----------
    t0 : float
        Time of the first sample [s].
    dt : float
        Sample interval [s] (the solver interpolates linearly).
    velocity : ndarray, float32 (n_times, n_nodes)
        U [m/s].
    acceleration : ndarray, float32 (n_times, n_nodes)
        dU/dt [m/s²].
    weights : ndarray or None
        Stage weights w_k(t_j), shape (n_stages, n_times) (for per-sea-state force-model
        parameters); None when the flow is not synthesised from sea states.
    stage_parameters : tuple of dict
        Per stage: significant_velocity U_s [m/s], mean_period T_u [s], spreading_factor R_D
        (as :class:`~onbottom.hydro.storm_kinematics.StormKinematics`); empty with no stages.
    """

    t0: float
    dt: float
    velocity: np.ndarray
    acceleration: np.ndarray
    weights: np.ndarray | None = None
    stage_parameters: tuple[dict[str, float], ...] = ()

    def __post_init__(self) -> None:
        positive("NodeKinematics.dt", self.dt)
        if self.velocity.shape != self.acceleration.shape or self.velocity.ndim != 2:
            raise InputError(
                "NodeKinematics.velocity/acceleration are invalid: need equal 2-D shapes"
                f" (n_times, n_nodes), got {self.velocity.shape} and {self.acceleration.shape}"
            )
        if self.weights is not None and np.shape(self.weights) != (
            len(self.stage_parameters),
            self.velocity.shape[0],
        ):
            raise InputError(
                f"NodeKinematics.weights of shape {np.shape(self.weights)} are invalid: need"
                f" ({len(self.stage_parameters)}, {self.velocity.shape[0]}) (stages, times)"
            )

    @property
    def t_end(self) -> float:
        """Time of the last sample [s]."""
        return self.t0 + self.dt * (self.velocity.shape[0] - 1)

    @property
    def nbytes(self) -> int:
        """Memory held [bytes]."""
        return int(self.velocity.nbytes + self.acceleration.nbytes)

    @property
    def shape(self) -> tuple[int, int]:
        """(n_times, n_nodes)."""
        return (int(self.velocity.shape[0]), int(self.velocity.shape[1]))


def _unlink(path: str) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass


class WindowedNodeKinematics:
    """:class:`NodeKinematics` kept in a temporary file, read back in time windows.

    The file holds the float32 velocity then acceleration of each node over the whole storm
    (node-major: the order the synthesis makes them); :meth:`window` returns samples
    k0 … k1 − 1 of every node as time-major arrays, the values a :class:`NodeKinematics`
    would hold. The file is removed by :meth:`close` or when the object is collected.

    Attributes
    ----------
    t0, dt : float
        Time of the first sample and sample interval [s].
    shape : tuple of int
        (n_times, n_nodes).
    weights, stage_parameters
        As :class:`NodeKinematics`.
    digest : str
        blake2b hash of the velocity and acceleration (node by node): the run identity's.
    """

    def __init__(
        self,
        path: str | os.PathLike,
        t0: float,
        dt: float,
        shape: tuple[int, int],
        digest: str,
        weights: np.ndarray | None = None,
        stage_parameters: tuple[dict[str, float], ...] = (),
    ) -> None:
        self.path = Path(path)
        self.t0 = float(t0)
        self.dt = positive("WindowedNodeKinematics.dt", dt)
        self.shape = (int(shape[0]), int(shape[1]))
        self.digest = digest
        self.weights = weights
        self.stage_parameters = tuple(stage_parameters)
        self._finalizer = weakref.finalize(self, _unlink, str(self.path))

    @property
    def t_end(self) -> float:
        """Time of the last sample [s]."""
        return self.t0 + self.dt * (self.shape[0] - 1)

    @property
    def nbytes(self) -> int:
        """Memory a whole :class:`NodeKinematics` would hold (the file's size) [bytes]."""
        return 8 * self.shape[0] * self.shape[1]

    def window(self, k0: int, k1: int) -> tuple[np.ndarray, np.ndarray]:
        """(velocity, acceleration) of samples k0 … k1 − 1, float32 (k1 − k0, n_nodes)."""
        n_t, n = self.shape
        if not 0 <= k0 < k1 <= n_t:
            raise InputError(f"window [{k0}, {k1}) is invalid: samples 0 … {n_t} exist")
        m = k1 - k0
        out = []
        with open(self.path, "rb", buffering=0) as f:
            fd = f.fileno()
            for part in (0, 1):  # velocity, acceleration
                buf = np.empty((n, m), dtype=np.float32)
                for i in range(n):  # each node's samples k0 … k1 − 1: one read, no mapping
                    off = ((part * n + i) * n_t + k0) * 4
                    if os.preadv(fd, [buf[i]], off) != 4 * m:
                        raise OSError(f"{self.path}: short read (the file was changed)")
                out.append(np.ascontiguousarray(buf.T))
                del buf
        u, a = out
        return u, a

    def close(self) -> None:
        """Remove the file."""
        self._finalizer()

    def __enter__(self) -> WindowedNodeKinematics:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _settings(
    storm: Storm,
    depth: float,
    x: np.ndarray,
    sample_interval: float | None,
    omega_max_factor: float,
) -> tuple[np.ndarray, float]:
    """Checked inputs of :func:`pipeline_kinematics`: node positions [m] and Δt_s [s]."""
    if not isinstance(storm, Storm):
        raise InputError(f"storm = {type(storm).__name__} is invalid: expected Storm")
    positive("depth", depth)
    if omega_max_factor <= 1.0:
        raise InputError(f"omega_max_factor = {omega_max_factor!r} is invalid: must be > 1")
    tp_min = min(s.tp for s in storm.stages)
    dts = positive("sample_interval", sample_interval) if sample_interval else tp_min / 50.0
    return np.asarray(x, dtype=float), dts


class _MemorySink:
    """Node blocks into float32 (n_t, n_nodes) arrays held in memory."""

    def __init__(self, n_t: int, n_nodes: int) -> None:
        self.vel = np.empty((n_t, n_nodes), dtype=np.float32)
        self.acc = np.empty((n_t, n_nodes), dtype=np.float32)

    def write(self, b0: int, ub: np.ndarray, ab: np.ndarray) -> None:
        nb = ub.shape[0]
        self.vel[:, b0 : b0 + nb] = ub.T
        self.acc[:, b0 : b0 + nb] = ab.T

    def abort(self) -> None:
        pass

    def result(self, syn: NodeSynthesis, params: tuple[dict[str, float], ...]) -> NodeKinematics:
        return NodeKinematics(
            t0=0.0,
            dt=syn.sample_interval,
            velocity=self.vel,
            acceleration=self.acc,
            weights=syn.weights,
            stage_parameters=params,
        )


class _FileSink:
    """Node blocks into a temporary float32 file (node-major), hashed as they are written."""

    def __init__(self, n_t: int, n_nodes: int) -> None:
        fd, self.path = tempfile.mkstemp(prefix="onbottom-kinematics-", suffix=".f32")
        self.f = os.fdopen(fd, "wb")
        self.hu, self.ha = hashlib.blake2b(digest_size=16), hashlib.blake2b(digest_size=16)
        self.row = n_t * 4  # bytes of one node's series
        self.shape = (n_t, n_nodes)

    def write(self, b0: int, ub: np.ndarray, ab: np.ndarray) -> None:
        bu = ub.astype(np.float32).tobytes()
        ba = ab.astype(np.float32).tobytes()
        self.hu.update(bu)
        self.ha.update(ba)
        self.f.seek(b0 * self.row)
        self.f.write(bu)
        self.f.seek((self.shape[1] + b0) * self.row)
        self.f.write(ba)

    def abort(self) -> None:
        self.f.close()
        _unlink(self.path)

    def result(
        self, syn: NodeSynthesis, params: tuple[dict[str, float], ...]
    ) -> WindowedNodeKinematics:
        self.f.close()
        return WindowedNodeKinematics(
            self.path,
            0.0,
            syn.sample_interval,
            self.shape,
            self.hu.hexdigest() + self.ha.hexdigest(),
            weights=syn.weights,
            stage_parameters=params,
        )


def _synthesise_nodes(
    syn: NodeSynthesis, xx: np.ndarray, block_nodes: int, sink: _MemorySink | _FileSink
) -> None:
    """Evaluate the flow block by block of ``block_nodes`` nodes into ``sink``."""
    half = syn.n_fft // 2 + 1
    work = np.zeros((min(block_nodes, max(xx.size, 1)), half), dtype=complex)
    try:
        for b0 in range(0, xx.size, block_nodes):
            ub, ab = node_block_series(syn, xx[b0 : b0 + block_nodes], work)
            sink.write(b0, ub, ab)
    except BaseException:
        sink.abort()
        raise


def pipeline_kinematics(
    storm: Storm,
    depth: float,
    x: np.ndarray,
    *,
    sample_interval: float | None = None,
    omega_max_factor: float = 5.0,
    block_nodes: int = 64,
    memory_limit: int | None = None,
) -> NodeKinematics | WindowedNodeKinematics:
    """Near-bed velocity and acceleration normal to the pipe at positions ``x`` through a storm.

    Stages: checked settings → set-up of harmonics, phases and directions
    (:func:`onbottom.hydro.flow_synthesis.node_synthesis`) → node blocks
    (:func:`~onbottom.hydro.flow_synthesis.node_block_series`) into memory or a file → result.

    Parameters
    ----------
    storm : Storm
        Stages (H_s, T_p, γ, direction, spreading s), envelope and seed.
    depth : float
        Water depth d [m], > 0.
    x : array
        Node positions along the pipe axis [m].
    sample_interval : float or None
        Δt_s [s], > 0; None → min(T_p)/50 (the solver interpolates linearly in time).
    omega_max_factor : float
        Highest frequency as a multiple of the highest ω_p [-], > 1.
    block_nodes : int
        Nodes per FFT block (size of the complex work array).
    memory_limit : int or None
        Kinematics larger than this [bytes] (8 per node and sample) are written to a
        temporary file and returned as :class:`WindowedNodeKinematics` (the same values, read
        in windows by the solver); None: always held whole.
    """
    xx, dts = _settings(storm, depth, x, sample_interval, omega_max_factor)
    syn = node_synthesis(storm, depth, dts, omega_max_factor)
    spill = memory_limit is not None and 8 * syn.n_t * xx.size > memory_limit
    sink = (_FileSink if spill else _MemorySink)(syn.n_t, xx.size)
    _synthesise_nodes(syn, xx, block_nodes, sink)
    params = tuple(seabed_velocity_parameters(s, depth) for s in storm.stages)
    return sink.result(syn, params)


def regular_node_kinematics(
    n_nodes: int,
    duration: float,
    dt: float,
    amplitude: float,
    period: float,
    *,
    ramp: float = 0.0,
    x: np.ndarray | None = None,
    wavelength: float | None = None,
) -> NodeKinematics:
    """Regular near-bed velocity U = e(t)·U_w sin(ωt − κx) at every node (tests, examples).

    ``ramp`` [s]: linear ramp of the amplitude from 0; ``wavelength`` [m] along the pipe (None:
    in phase along the whole line, i.e. a long-crested wave normal to the pipe).
    """
    n_t = math.ceil(duration / dt) + 1
    t = dt * np.arange(n_t)
    w = 2.0 * math.pi / positive("period", period)
    kx = 0.0 if wavelength is None else 2.0 * math.pi / wavelength
    xx = np.zeros(n_nodes) if x is None else np.asarray(x, dtype=float)
    arg = w * t[:, None] - kx * xx[None, :]
    if ramp > 0.0:
        e = np.minimum(t / ramp, 1.0)[:, None]
        de = np.where(t < ramp, 1.0 / ramp, 0.0)[:, None]
    else:
        e = np.ones((n_t, 1))
        de = np.zeros((n_t, 1))
    u = amplitude * np.sin(arg)
    a = amplitude * w * np.cos(arg)
    return NodeKinematics(
        t0=0.0,
        dt=dt,
        velocity=(e * u).astype(np.float32),
        acceleration=(e * a + de * u).astype(np.float32),
    )


def long_crested_node_kinematics(
    kinematics: StormKinematics, n_nodes: int, x: np.ndarray | None = None
) -> NodeKinematics:
    """The flow of a :class:`~onbottom.hydro.storm_kinematics.StormKinematics` at every node of
    a line (a long-crested flow: a regular wave or a measured record).

    A regular wave (``StormKinematics.regular``) at the angle θ_w to the pipe axis travels
    along the line: U(x, t) = e(t)·U_w sin θ_w·cos(ωt − k x cos θ_w) (k from the dispersion
    relation; x = 0 is the section's flow); at θ_w = 90° every node is in phase. A measured
    record (or no ``x``) acts in phase at every node. The current is not included (the
    pipeline model carries it per node).

    Parameters
    ----------
    kinematics : StormKinematics
    n_nodes : int
        Number of nodes, >= 1.
    x : array or None
        Node positions along the pipe [m] (n_nodes values) for the phase of a regular wave.
    """
    n = int(n_nodes)
    if n < 1:
        raise InputError(f"n_nodes = {n_nodes!r} is invalid: must be >= 1")
    p = kinematics.stage_parameters[0]
    kx = 0.0
    if p.get("kind") == "regular" and x is not None:
        cos_t = math.cos(math.radians(p["direction_deg"]))
        kx = 0.0 if abs(cos_t) < 1e-12 else 2.0 * math.pi / p["wave_length"] * cos_t
    if kx == 0.0:
        u = np.asarray(kinematics.velocity, dtype=np.float32)
        a = np.asarray(kinematics.acceleration, dtype=np.float32)
        return NodeKinematics(
            t0=0.0,
            dt=float(kinematics.sample_interval),
            velocity=np.ascontiguousarray(np.repeat(u[:, None], n, axis=1)),
            acceleration=np.ascontiguousarray(np.repeat(a[:, None], n, axis=1)),
        )
    xx = np.asarray(x, dtype=float)
    if xx.shape != (n,):
        raise InputError(f"x has shape {xx.shape}: expected ({n},) node positions [m]")
    t = kinematics.time[:, None]
    w = 2.0 * math.pi / p["mean_period"]
    ramp = p.get("build_up_s", 0.0)
    if ramp > 0.0:
        e = np.minimum(t / ramp, 1.0)
        de = np.where(t < ramp, 1.0 / ramp, 0.0)
    else:
        e = np.ones_like(t)
        de = np.zeros_like(t)
    arg = w * t - kx * xx[None, :]
    amp = p["amplitude"]
    c = np.cos(arg)
    vel = e * amp * c
    acc = -e * amp * w * np.sin(arg) + de * amp * c
    return NodeKinematics(
        t0=0.0,
        dt=float(kinematics.sample_interval),
        velocity=np.ascontiguousarray(vel, dtype=np.float32),
        acceleration=np.ascontiguousarray(acc, dtype=np.float32),
    )
