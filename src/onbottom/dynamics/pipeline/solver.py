"""Time-domain solver of the pipeline FE model in a storm (implicit HHT-α, Newton, banded).

:func:`simulate_pipeline` runs :func:`._pipeline_kernel.integrate` chunk by chunk; after each
chunk the records are kept (one file per chunk) and a checkpoint (all solver state) is
written atomically, so an interrupted run resumes from its
last chunk when called again with the same inputs (the run identity — a hash of the model,
the settings and the kinematics — must match). Theory: docs/theory/pipeline_fe.md.

Kill-safe files: the records of each chunk go to their own small file in
``<output>.part/`` (written atomically, with the run identity); when the run ends they are
written with the envelopes to a temporary NetCDF file renamed to ``output`` (``run_status =
"complete"``), and the checkpoint and the chunk files are removed. A growing HDF5 file is not
used: a kill -9 leaves its metadata half-written. A resume checks that the checkpoint and
the chunk files carry this run's identity and agree on the rows written, and logs "resuming
… from t = …"; a checkpoint of other inputs or an unreadable one, or an unreadable file under
the output's name, is a :class:`~onbottom.errors.ResultFileError` with the ``--restart``
advice. A checkpoint whose chunks are missing or disagree is not resumed (the run starts
afresh), so no record of an earlier run can leak into a new file.
"""

from __future__ import annotations

import json
import logging
import math
import os
import shutil
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from onbottom._jit import call_literal
from onbottom._validate import in_range, integer, one_of, positive
from onbottom.dynamics._settings import check_newton, check_steps
from onbottom.dynamics.driver import SpillRecorder, drive, progress_bar
from onbottom.dynamics.pipeline import _beam_kernel as B
from onbottom.dynamics.pipeline import _pipeline_kernel as K
from onbottom.dynamics.pipeline.model import PipelineModel
from onbottom.dynamics.pipeline.user_load import kernel_settings as user_load_settings
from onbottom.dynamics.result import (
    CRITERIA_OVER_D,
    SolverResult,
    dynamic_criteria,
    penetration_limit,
    penetration_reason,
    run_outcome,
)
from onbottom.dynamics.status import Status
from onbottom.errors import InputError, ResultFileError
from onbottom.hydro.force_model import N_FORCE_STATE, parameter_rows
from onbottom.hydro.short_crested import NodeKinematics, WindowedNodeKinematics
from onbottom.results import (
    RESTART_ADVICE,
    RUN_STATUS_COMPLETE,
    RunIdentity,
    annotate,
    atomic_write,
    check_result_file,
    provenance,
    run_identity,
)
from onbottom.soil.kernel_contract import MODELS_MIXED

__all__ = [
    "CRITERIA_OVER_D",
    "PipelineResult",
    "PipelineSettings",
    "pipeline_identity",
    "simulate_pipeline",
]

logger = logging.getLogger(__name__)

_PREDICTOR = 0.0
"""Weight of Δt²·a_n in the Newton starting point (0: d_n + Δt v_n; 0.5, constant
acceleration, needed more iterations in the benchmark storm)."""

FIELDS: dict[str, tuple[int, str, str]] = {
    "u_axial": (K.F_U, "axial displacement of the pipe", "m"),
    "y": (K.F_V, "lateral displacement of the pipe", "m"),
    "y_dot": (K.F_VDOT, "lateral velocity of the pipe", "m/s"),
    "z": (K.F_Z, "penetration (embedment) of the pipe invert", "m"),
    "F_soil": (K.F_SOIL, "lateral soil resistance per unit length", "N/m"),
    "F_hydro": (K.F_HYD, "lateral hydrodynamic load per unit length", "N/m"),
    "V": (K.F_VCONT, "vertical contact load per unit length", "N/m"),
    "moment": (K.F_MOM, "bending moment in the horizontal plane", "N m"),
    "axial_force": (K.F_NAX, "effective axial force (tension positive)", "N"),
    "strain": (K.F_STRAIN, "largest longitudinal fibre strain |N|/EA + |M|c/EI", "1"),
}
"""Recorded variables (time × node): kernel field, long name, units."""

ENVELOPES: dict[str, tuple[int, str, str]] = {
    "max_abs_y": (K.E_ABS_V, "largest |lateral displacement|", "m"),
    "max_y": (K.E_MAX_V, "largest lateral displacement", "m"),
    "min_y": (K.E_MIN_V, "smallest lateral displacement", "m"),
    "max_strain": (K.E_STRAIN, "largest fibre strain", "1"),
    "max_abs_moment": (K.E_ABS_M, "largest |bending moment|", "N m"),
    "max_axial_force": (K.E_MAX_N, "largest effective axial force", "N"),
    "min_axial_force": (K.E_MIN_N, "smallest effective axial force", "N"),
    "min_V": (K.E_MIN_VCONT, "smallest vertical contact load", "N/m"),
    "max_z": (K.E_MAX_Z, "largest penetration", "m"),
}
"""Envelopes along the line (dimension node), updated at every accepted step."""


@dataclass(frozen=True, kw_only=True, slots=True)
class PipelineSettings:
    """Settings of :func:`simulate_pipeline`.

    Parameters
    ----------
    alpha : float
        HHT-α parameter [-], in [−1/3, 0]; 0 = average-acceleration Newmark (no numerical
        damping, exact discrete energy identity); default −0.1 damps the spurious
        high-frequency response of stick phases and stiff axial modes (and halved the
        rejected steps of the benchmark storm).
    dt_max : float
        Initial and largest time step [s], > 0.
    dt_min : float or None
        Smallest step [s], > 0; None → dt_max·1e-4.
    max_iterations : int
        Newton iterations per step before a cut-back, >= 3.
    force_tolerance : float
        Residual tolerance relative to W_s·ℓ_e [-], in (0, 1e-2].
    max_displacement_increment_over_d : float
        Largest lateral increment of any node per step over D [-], > 0.
    growth : float
        Step growth factor after an easy step [-], in [1, 4].
    stop_displacement_over_d : float or None
        Stop when any node reaches |y| >= this × D [-]; None → run on.
    record_interval : float or None
        Time between records [s], > 0; None → envelopes and summary only.
    chunk_duration : float
        Storm time between NetCDF appends and checkpoints [s], > 0.
    strain_limit : float or None
        User strain limit [-] for the strain check, > 0 (DNV-ST-F101 gives design values).
    compression_level : int
        zlib level of the records in the NetCDF file [-], 0 (none) to 9; the records are
        written in chunks of at most 1024 rows × all nodes. Not part of the run identity (a
        run may resume with another level). Decimation: ``record_interval``.
    """

    alpha: float = -0.1
    dt_max: float = 0.1
    dt_min: float | None = None
    max_iterations: int = 8
    force_tolerance: float = 1.0e-6
    max_displacement_increment_over_d: float = 0.1
    growth: float = 1.5
    stop_displacement_over_d: float | None = None
    record_interval: float | None = 1.0
    chunk_duration: float = 600.0
    strain_limit: float | None = None
    compression_level: int = 0

    def __post_init__(self) -> None:
        c = "PipelineSettings"
        in_range(f"{c}.alpha", self.alpha, -1.0 / 3.0, 0.0)
        check_steps(c, self.dt_max, self.dt_min)
        check_newton(c, self.force_tolerance, 1e-2, self.max_iterations, 3)
        positive(f"{c}.max_displacement_increment_over_d", self.max_displacement_increment_over_d)
        in_range(f"{c}.growth", self.growth, 1.0, 4.0)
        if self.stop_displacement_over_d is not None:
            positive(f"{c}.stop_displacement_over_d", self.stop_displacement_over_d)
        if self.record_interval is not None:
            positive(f"{c}.record_interval", self.record_interval)
        positive(f"{c}.chunk_duration", self.chunk_duration)
        if self.strain_limit is not None:
            positive(f"{c}.strain_limit", self.strain_limit)
        integer(f"{c}.compression_level", self.compression_level, 0, 9)


@dataclass(frozen=True, kw_only=True)
class PipelineResult(SolverResult):
    """Result of :func:`simulate_pipeline` (a :class:`~onbottom.dynamics.result.SolverResult`).

    Attributes
    ----------
    success : bool
        True when the run ended normally (end of storm or runaway stop).
    status : int
        A :class:`~onbottom.dynamics.status.Status`: 1 end, 2 runaway stop, −1 step failure, −2 soil
        NaN, −3 a node's penetration left the soil model's range (beyond D/2 for Verley & Sotberg /
        Verley & Lund, as the section solvers; the run went on, its numbers are kept, ``success`` is
        False and the message names the time, node and x), −4 singular Jacobian.
    message : str
    diameter : float
        D [m].
    x : ndarray
        Node positions [m].
    max_displacement : float
        Largest |y| of any node over the run [m].
    worst_node : int
        Node of ``max_displacement``.
    max_strain : float
        Largest fibre strain of any node [-].
    criteria : dict
        {"0.5D": bool, "10D": bool} and "strain" (None without a strain limit).
    summary : dict
        Counters, energies and events (see :func:`simulate_pipeline`).
    envelopes : xarray.Dataset
        Envelopes along the line (dimension ``node``, coordinate ``x``).
    data : xarray.Dataset or None
        Records (time × node) when kept in memory (no NetCDF file given).
    netcdf : Path or None
        File with records and envelopes.
    run_id : str
    """

    success: bool
    status: int
    message: str
    diameter: float
    x: np.ndarray
    max_displacement: float
    worst_node: int
    max_strain: float
    criteria: dict[str, bool | None]
    summary: dict[str, float] = field(default_factory=dict)
    envelopes: xr.Dataset | None = None
    data: xr.Dataset | None = None
    netcdf: Path | None = None
    run_id: str = ""

    @property
    def worst_node_x(self) -> float:
        """Position of the node with the largest displacement [m]."""
        return float(self.x[self.worst_node])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (keys of ``onbottom storm --json`` for a pipeline case)."""
        return {
            "max_displacement_m": self.max_displacement,
            "max_displacement_over_D": self.max_displacement / self.diameter,
            "max_strain": self.max_strain,
            "worst_node_x_m": self.worst_node_x,
            "criteria": dict(self.criteria),
            "status": self.status,
            "success": self.success,
            "message": self.message,
            "summary": dict(self.summary),
            "netcdf": None if self.netcdf is None else str(self.netcdf),
            "run_id": self.run_id,
        }

    def open_dataset(self) -> xr.Dataset:
        """The records: in memory, or loaded from the NetCDF file."""
        if self.data is not None:
            return self.data
        if self.netcdf is None:
            raise InputError("PipelineResult has no records: run with record_interval set")
        from onbottom.results import load_dataset

        return load_dataset(self.netcdf)


def pipeline_identity(
    model: PipelineModel,
    kinematics: NodeKinematics | WindowedNodeKinematics,
    settings: PipelineSettings,
    extra: Any = None,
    force_parameters: np.ndarray | None = None,
) -> RunIdentity:
    """The run identity (:func:`onbottom.results.run_identity`) of everything that determines
    a run: model, settings, kinematics; its ``digest`` is the ``run_id`` of the checkpoint,
    the chunk files and the result.

    ``force_parameters``: the force model's parameter rows; folded in only when they change
    along the storm (per sea state), so a constant model keeps the identity of earlier runs.
    Windowed kinematics enter through their digest (node by node, not the arrays' bytes).
    """
    meta = {
        "model": model.describe(),
        # the output's compression is not part of the run (a run may resume with another)
        "settings": {k: v for k, v in asdict(settings).items() if k != "compression_level"},
        "kinematics": [kinematics.t0, kinematics.dt, list(kinematics.shape)],
        "extra": extra,
    }
    if isinstance(kinematics, WindowedNodeKinematics):
        meta["kinematics_digest"] = kinematics.digest
        arrays = []
    else:
        arrays = [kinematics.velocity, kinematics.acceleration]
    if force_parameters is not None and force_parameters.shape[0] > 1:
        arrays.append(force_parameters)
    return run_identity(meta, *arrays)


def _kernel_settings(
    model: PipelineModel,
    kin: NodeKinematics | WindowedNodeKinematics,
    s: PipelineSettings,
    r_perm_z: float,
):
    d = model.pipe.outer_diameter
    fm = model.force_model
    st = np.zeros(K.N_SETTINGS)
    st[K.ST_DT_MAX] = s.dt_max
    st[K.ST_DT_MIN] = s.dt_min if s.dt_min is not None else s.dt_max * 1e-4
    st[K.ST_ALPHA] = s.alpha
    st[K.ST_MAX_ITER] = s.max_iterations
    st[K.ST_RTOL] = s.force_tolerance
    st[K.ST_FSCALE] = model.pipe.submerged_weight * model.length / model.n_elements
    st[K.ST_DU_MAX] = s.max_displacement_increment_over_d * d
    st[K.ST_V_LIMIT] = (
        math.inf if s.stop_displacement_over_d is None else s.stop_displacement_over_d * d
    )
    st[K.ST_STOP_AT_LIMIT] = 0.0 if s.stop_displacement_over_d is None else 1.0
    st[K.ST_GROWTH] = s.growth
    st[K.ST_RHO] = model.pipe.seawater_density
    st[K.ST_D] = d
    st[K.ST_FORCE_MODEL] = fm.model_id
    st[K.ST_R_PERM_Z] = r_perm_z
    st[K.ST_RELVEL] = 1.0 if model.relative_velocity else 0.0
    st[K.ST_DELTA_AX] = model.axial_mobilisation
    st[K.ST_FIBRE] = model.fibre_distance
    st[K.ST_T_KIN0] = kin.t0
    st[K.ST_DT_KIN] = kin.dt
    st[K.ST_KIN_K0] = 0.0
    st[K.ST_KIN_NT] = kin.shape[0]
    st[K.ST_PEN_RED] = 1.0 if model.reductions.penetration else 0.0
    st[K.ST_EA] = model.ea
    st[K.ST_EI] = model.ei
    st[K.ST_PREDICTOR] = _PREDICTOR
    st[K.ST_CTOL] = 1e-9 * d
    st[K.ST_Z_LIMIT] = _penetration_limit(model)
    st[K.ST_UL_KIND :] = user_load_settings(model.user_load)
    return st


def _penetration_limit(model: PipelineModel) -> float:
    """D/2 when a section's soil model carries D (Verley & Sotberg, Verley & Lund; the rule of
    the section solvers), else ∞ (Coulomb)."""
    d = model.pipe.outer_diameter
    return min(penetration_limit(sec.model, d) for sec in model.sections)


def partial_path(output: str | os.PathLike) -> Path:
    """The folder of the records of a run writing ``output``: ``<output>.part``."""
    p = Path(output)
    return p.with_name(p.name + ".part")


def _chunk_file(folder: Path, index: int) -> Path:
    return folder / f"chunk_{index:06d}.npz"


def _write_npz_atomic(path: Path, **arrays: np.ndarray) -> None:
    """``arrays`` to ``path`` (npz) under a temporary name, then renamed (as every result)."""

    def write(tmp: str) -> None:
        with open(tmp, "wb") as fh:
            np.savez(fh, **arrays)

    atomic_write(path, write)


class _Writer:
    """Keeps the records of a run as one small file per chunk in ``<output>.part/``; at
    :meth:`finish` writes them with the envelopes into a temporary NetCDF file and renames it
    to the output's name (``run_status = "complete"``).

    Each chunk file is written atomically and carries the run identity, so a kill at any
    moment leaves whole chunks (a growing HDF5 file does not survive a kill -9: its metadata
    is left half-written, "bad object header version number"). :meth:`commit` is called
    before each checkpoint, which records how many chunks belong to it.
    """

    def __init__(
        self,
        path: Path,
        x: np.ndarray,
        attrs: Mapping[str, Any],
        run_id: str,
        resume: tuple[int, int, float] = (0, 0, math.nan),
        compression_level: int = 0,
    ) -> None:
        self.path = path
        self.compression_level = compression_level
        self.folder = partial_path(path)
        self.x = x
        self.attrs = dict(attrs)
        self.run_id = run_id
        self.rows, self.chunks, self.last_time = resume
        self._t: list[np.ndarray] = []
        self._r: list[np.ndarray] = []
        if self.folder.exists() and not self.folder.is_dir():
            self.folder.unlink()
        # chunks beyond the checkpoint (written before a kill) and temporaries go
        for f in list(self.folder.glob("chunk_*")) if self.folder.is_dir() else []:
            tail = f.name[len("chunk_") :].split(".", 1)[0]
            if not tail.isdigit() or int(tail) >= self.chunks or f.suffix == ".tmp":
                f.unlink(missing_ok=True)

    def append(self, t: np.ndarray, rec: np.ndarray) -> None:
        m = t.size
        if m == 0:
            return
        ks = [k for (k, _l, _u) in FIELDS.values()]
        self._t.append(np.array(t[:m], dtype=np.float64))
        self._r.append(rec[:m][:, ks, :].astype(np.float32))

    def commit(self) -> None:
        """Write the rows appended since the last commit as the next chunk file."""
        if not self._t:
            return
        t = np.concatenate(self._t)
        r = np.concatenate(self._r)
        _write_npz_atomic(
            _chunk_file(self.folder, self.chunks), run_id=np.array(self.run_id), t=t, rec=r
        )
        self.chunks += 1
        self.rows += t.size
        self.last_time = float(t[-1])
        self._t.clear()
        self._r.clear()

    def finish(self, envelopes: xr.Dataset, attrs: Mapping[str, Any]) -> None:
        """Write the result file (temporary name, then rename)."""
        import h5netcdf

        self.commit()
        x = self.x
        n = x.size

        def write(tmp: str) -> None:
            with h5netcdf.File(tmp, "w") as f:
                f.dimensions = {"time": self.rows, "node": n}
                tv = f.create_variable("time", ("time",), np.float64)
                tv.attrs.update(long_name="time", units="s")
                xv = f.create_variable("x", ("node",), np.float64, data=x)
                xv.attrs.update(long_name="position along the pipe", units="m")
                # chunked (≤ 1024 rows × all nodes), deflated at compression_level when > 0
                opts: dict[str, Any] = {}
                if self.rows > 0:
                    opts["chunks"] = (min(self.rows, 1024), n)
                if self.compression_level > 0:
                    opts.update(
                        compression="gzip", compression_opts=self.compression_level, shuffle=True
                    )
                for name, (_k, long_name, units) in FIELDS.items():
                    v = f.create_variable(name, ("time", "node"), np.float32, **opts)
                    v.attrs.update(long_name=long_name, units=units, coordinates="x")
                r0 = 0
                for i in range(self.chunks):
                    with np.load(_chunk_file(self.folder, i)) as z:
                        t, rec = z["t"], z["rec"]
                    m = t.size
                    f.variables["time"][r0 : r0 + m] = t
                    for j, name in enumerate(FIELDS):
                        f.variables[name][r0 : r0 + m, :] = rec[:, j, :]
                    r0 += m
                for name in envelopes.data_vars:
                    v = f.create_variable(name, ("node",), np.float64, data=envelopes[name].values)
                    v.attrs.update(envelopes[name].attrs)
                for k, v in {**self.attrs, **attrs}.items():
                    f.attrs[k] = v
                f.attrs["run_status"] = RUN_STATUS_COMPLETE

        atomic_write(self.path, write)

    def discard(self) -> None:
        """Remove the chunk files (once :meth:`finish` has renamed the result)."""
        if self.folder.is_dir():
            for f in self.folder.glob("chunk_*"):
                f.unlink(missing_ok=True)
            try:
                self.folder.rmdir()
            except OSError:
                pass

    def close(self) -> None:
        """Nothing stays open between chunks (kept for the interrupt path)."""


def _save_checkpoint(
    path: Path,
    run_id: str,
    rows: int,
    chunks: int,
    last_time: float,
    state: Mapping[str, np.ndarray],
) -> None:
    _write_npz_atomic(
        path,
        run_id=np.array(run_id),
        rows=np.array(rows),
        chunks=np.array(chunks),
        last_time=np.array(last_time),
        **state,
    )


def _load_checkpoint(
    path: Path, run_id: str, resume: str
) -> tuple[int, int, float, dict[str, np.ndarray]] | None:
    """(rows, chunks, time of the last row, state) of a checkpoint of this run, or None if
    there is none; an unreadable checkpoint or one of other inputs is a
    :class:`ResultFileError`."""
    if not path.exists():
        if resume == "require":
            raise InputError(f"checkpoint = {str(path)!r} is invalid: no such file to resume")
        return None
    try:
        with np.load(path) as z:
            found = str(z["run_id"])
            skip = ("run_id", "rows", "chunks", "last_time")
            state = {k: z[k].copy() for k in z.files if k not in skip}
            rows = int(z["rows"])
            chunks = int(z["chunks"])
            last = float(z["last_time"])
    except Exception as exc:  # any damage (a zip error, a missing array, ...)
        raise ResultFileError(
            f"checkpoint {str(path)!r} is unreadable (corrupt, truncated or not a checkpoint:"
            f" {type(exc).__name__}); {RESTART_ADVICE}",
            field="checkpoint",
        ) from None
    if found != run_id:
        raise ResultFileError(
            f"checkpoint {str(path)!r} belongs to another run: its run identity"
            f" {found[:12]}… differs from {run_id[:12]}… (other inputs); {RESTART_ADVICE},"
            " or give another --output",
            field="checkpoint",
        )
    return rows, chunks, last, state


def _partial_agrees(
    folder: Path, run_id: str, rows: int, chunks: int, last_time: float
) -> str | None:
    """None if the chunk files 0 … ``chunks`` − 1 of ``folder`` carry ``run_id`` and hold
    ``rows`` records, the last at ``last_time``; otherwise why they cannot be resumed."""
    n = 0
    t_last = math.nan
    for i in range(chunks):
        f = _chunk_file(folder, i)
        if not f.exists():
            return f"its partial records {str(f)!r} are missing"
        try:
            with np.load(f) as z:
                found = str(z["run_id"])
                t = z["t"]
        except Exception as exc:  # any damage
            return f"its partial records {str(f)!r} are unreadable ({type(exc).__name__})"
        if found != run_id:
            return f"its partial records {str(f)!r} belong to another run"
        n += t.size
        if t.size:
            t_last = float(t[-1])
    if n != rows:
        return f"its partial records hold {n} rows, the checkpoint {rows}"
    if rows > 0 and not (math.isnan(last_time) or t_last == last_time):
        return "its partial records disagree with it (other times)"
    return None


def _finished_output(path: Path, run_id: str) -> dict[str, Any] | None:
    """Attributes of ``path`` when it is a complete result of this run; None if it is absent
    or a complete result of another run; an unreadable file is a :class:`ResultFileError`."""
    if not path.exists():
        return None
    attrs = check_result_file(
        path, allow_partial=True, what="output", field="output", advice=RESTART_ADVICE
    )
    if attrs.get("run_status") == RUN_STATUS_COMPLETE and str(attrs.get("run_id")) == run_id:
        return attrs
    return None


class _KinematicsWindow:
    """The kinematics arrays the kernel reads: the whole storm's, or a window of windowed
    kinematics that covers each call (settings[ST_KIN_K0] follows the window)."""

    WINDOW_BYTES = 64 * 2**20
    """Largest window [bytes] beyond the span of one call."""

    def __init__(self, kin: NodeKinematics | WindowedNodeKinematics, st: np.ndarray, span: float):
        self.kin = kin
        self.st = st
        self.k0 = self.k1 = 0
        if isinstance(kin, WindowedNodeKinematics):
            self.u = self.a = None
            n_t, n = kin.shape
            self.rows = max(min(n_t, self.WINDOW_BYTES // (8 * max(n, 1))), 4)
            self.rows = max(self.rows, min(n_t, math.ceil(span / kin.dt) + 4))
        else:
            self.u = np.ascontiguousarray(kin.velocity, dtype=np.float32)
            self.a = np.ascontiguousarray(kin.acceleration, dtype=np.float32)

    def cover(self, t_a: float, t_b: float) -> tuple[np.ndarray, np.ndarray]:
        """(velocity, acceleration) arrays holding every sample a call from t_a to t_b reads."""
        kin = self.kin
        if not isinstance(kin, WindowedNodeKinematics):
            return self.u, self.a
        n_t = kin.shape[0]
        i_a = max(math.floor((t_a - kin.t0) / kin.dt) - 1, 0)
        i_b = min(math.floor((t_b - kin.t0) / kin.dt) + 3, n_t)
        if self.u is None or i_a < self.k0 or i_b > self.k1:
            k1 = min(max(i_a + self.rows, i_b), n_t)
            k0 = max(min(i_a, k1 - self.rows), 0)
            self.u = self.a = None  # the old window goes before the new one is read
            self.u, self.a = kin.window(k0, k1)
            self.k0, self.k1 = k0, k1
            self.st[K.ST_KIN_K0] = k0
        return self.u, self.a


def simulate_pipeline(
    model: PipelineModel,
    kinematics: NodeKinematics | WindowedNodeKinematics,
    *,
    duration: float | None = None,
    settings: PipelineSettings | None = None,
    output: str | os.PathLike | None = None,
    checkpoint: str | os.PathLike | None = None,
    progress: bool = False,
    attrs: Mapping[str, Any] | None = None,
    identity_extra: Any = None,
    resume: str = "auto",
) -> PipelineResult:
    """Simulate the pipeline through the storm whose node kinematics are given.

    Parameters
    ----------
    model : PipelineModel
    kinematics : NodeKinematics or WindowedNodeKinematics
        Near-bed velocity/acceleration normal to the pipe at every node (n_nodes columns);
        windowed kinematics are read in windows as the run advances (the same results).
    duration : float or None
        Simulated time [s], > 0; None → the end of the kinematics.
    settings : PipelineSettings or None
    output : path or None
        NetCDF file for the records and envelopes, written under a temporary name when the
        run ends (the records are kept chunk by chunk in ``<output>.part/`` meanwhile);
        None → records kept in memory (``result.data``).
    checkpoint : path or None
        Checkpoint file (npz); None with ``output`` → ``output`` + ".ckpt.npz". An existing
        checkpoint with the same run identity is resumed (with the partial file
        ``<output>.part`` it describes); another identity, or an unreadable checkpoint, is a
        :class:`~onbottom.errors.ResultFileError` advising ``--restart``. The checkpoint is
        removed when the run ends.
    progress : bool
        tqdm progress bar over chunks.
    attrs : mapping or None
        Extra provenance attributes.
    identity_extra : any
        Extra JSON-able data folded into the run identity (e.g. the case file's text).
    resume : {"auto", "never", "require"}
        "auto": return the finished ``output`` of this run (same identity) as it is, or
        resume its checkpoint, or start anew (replacing an output of other inputs when the
        run ends) when there is no checkpoint or its partial file is missing or damaged;
        "never": discard any checkpoint and partial file and start anew (``--restart``);
        "require": return or resume, or raise :class:`~onbottom.errors.InputError`.
        Resuming logs "resuming <output> from t = … s" (logger ``onbottom``, level INFO).

    Returns
    -------
    PipelineResult
        ``summary`` holds n_steps, n_rejected, mean_newton_iterations, final_time [s],
        time_to_stop_displacement [s] (nan if not reached), n_liftoff (node-steps),
        first_liftoff_time [s], first_liftoff_x [m], work_hydro [J], work_soil [J],
        kinetic_energy [J], strain_energy [J], energy_residual [J] (KE + SE − W_hydro −
        W_soil; ≈ 0 for α = 0), negative_pivot_steps.

    The run is four stages: the settings are checked (:func:`_checked_settings`), the run is
    set up (:func:`_setup`: kernel arrays, identity, files) and started, resumed or found
    finished (:func:`_start`), the time loop runs chunk by chunk (:func:`_time_loop`), and
    the result is assembled (:func:`_result`).
    """
    s, t_end = _checked_settings(model, kinematics, settings, duration, resume)
    run = _setup(model, kinematics, s, t_end, output, checkpoint, attrs, identity_extra)
    finished = _start(run, resume)
    if finished is not None:
        return finished
    status, records = _time_loop(run, progress)
    return _result(run, status, records)


def _checked_settings(
    model: PipelineModel,
    kinematics: NodeKinematics | WindowedNodeKinematics,
    settings: PipelineSettings | None,
    duration: float | None,
    resume: str,
) -> tuple[PipelineSettings, float]:
    """Settings stage: the inputs checked; (settings, end time [s])."""
    if not isinstance(model, PipelineModel):
        raise InputError(f"model = {type(model).__name__} is invalid: expected PipelineModel")
    if not isinstance(kinematics, NodeKinematics | WindowedNodeKinematics):
        raise InputError(
            f"kinematics = {type(kinematics).__name__} is invalid: expected NodeKinematics"
        )
    s = settings if settings is not None else PipelineSettings()
    one_of("resume", resume, ("auto", "never", "require"))
    n = model.x.size
    if kinematics.shape[1] != n:
        raise InputError(
            f"kinematics has {kinematics.shape[1]} node columns, the model"
            f" {n} nodes: generate the kinematics at model.x"
        )
    t_end = kinematics.t_end if duration is None else positive("duration", duration)
    if t_end > kinematics.t_end + 1e-9:
        raise InputError(
            f"duration = {t_end!r} s is invalid: the kinematics end at {kinematics.t_end:g} s"
        )
    return s, t_end


@dataclass(eq=False)
class _Run:
    """Everything one run of :func:`simulate_pipeline` holds between its stages: the inputs
    and kernel arrays (set up once), then the solver state (fresh or resumed) that the time
    loop advances in place."""

    model: PipelineModel
    kinematics: NodeKinematics | WindowedNodeKinematics
    s: PipelineSettings
    t_end: float
    arr: dict[str, np.ndarray]
    st: np.ndarray
    soil_id: int
    force_id: int
    fparams: np.ndarray
    kin: _KinematicsWindow
    run_id: str
    t_out: np.ndarray
    out_path: Path | None
    ckpt: Path | None
    base_attrs: dict[str, Any]
    rec: np.ndarray
    rec_t: np.ndarray
    # solver state (set by _start)
    vec: np.ndarray | None = None
    scal: np.ndarray | None = None
    sstate: np.ndarray | None = None
    axst: np.ndarray | None = None
    nodal: np.ndarray | None = None
    env: np.ndarray | None = None
    fstate: np.ndarray | None = None
    done: int = K.STATUS_CHUNK
    resumed: tuple[int, int, float] | None = None  # (rows, chunks, last time) of a resume
    writer: _Writer | None = None  # the records' files (with an output), set by the loop

    @property
    def x(self) -> np.ndarray:
        return self.model.x

    @property
    def d(self) -> float:
        return self.model.pipe.outer_diameter


def _setup(
    model: PipelineModel,
    kinematics: NodeKinematics | WindowedNodeKinematics,
    s: PipelineSettings,
    t_end: float,
    output: str | os.PathLike | None,
    checkpoint: str | os.PathLike | None,
    attrs: Mapping[str, Any] | None,
    identity_extra: Any,
) -> _Run:
    """Setup stage: kernel settings and arrays, the models to compile, the force parameters,
    the run identity, output times, file names, provenance and the record buffer."""
    n = model.x.size
    arr = model.arrays()
    r_perm_z = float(arr["r_perm_z"][0])
    st = _kernel_settings(model, kinematics, s, r_perm_z)
    # the kernels compile the soil and force models used only (numba literals)
    used = np.unique(arr["model_ids"])
    soil_id = int(used[0]) if used.size == 1 else MODELS_MIXED
    force_id = int(model.force_model.model_id)
    fparams = parameter_rows(
        model.force_model,
        kinematics.weights,
        kinematics.stage_parameters,
        model.current,
        model.pipe.outer_diameter,
    )
    kin = _KinematicsWindow(kinematics, st, s.chunk_duration)
    run_id = pipeline_identity(model, kinematics, s, [t_end, identity_extra], fparams).digest
    if s.record_interval is not None:
        n_out = math.floor(t_end / s.record_interval + 1e-9) + 1
        t_out = s.record_interval * np.arange(n_out)
    else:
        t_out = np.zeros(0)
    out_path = None if output is None else Path(output)
    ckpt = (
        Path(checkpoint)
        if checkpoint is not None
        else (None if out_path is None else out_path.with_name(out_path.name + ".ckpt.npz"))
    )
    base_attrs = provenance(
        "pipeline_fe",
        model.describe(),
        settings=asdict(s),
        run_id=run_id,
        integrator="HHT-alpha",
        source="docs/theory/pipeline_fe.md",
        **dict(attrs or {}),
    )
    # the kernel's record buffer (rows of per_chunk output times)
    per_chunk = 1
    if t_out.size:
        per_chunk = max(math.ceil(s.chunk_duration / s.record_interval) + 2, 2)
    return _Run(
        model=model, kinematics=kinematics, s=s, t_end=t_end, arr=arr, st=st,
        soil_id=soil_id, force_id=force_id, fparams=fparams, kin=kin, run_id=run_id,
        t_out=t_out, out_path=out_path, ckpt=ckpt, base_attrs=base_attrs,
        rec=np.zeros((per_chunk, K.N_FIELDS, n)), rec_t=np.zeros(per_chunk),
    )  # fmt: skip


def _start(run: _Run, resume: str) -> PipelineResult | None:
    """Start stage: the finished result of this run when its output is there (returned);
    else the solver state resumed from the checkpoint, or a fresh start (set on ``run``)."""
    out_path, ckpt, run_id = run.out_path, run.ckpt, run.run_id
    state = None
    if out_path is not None and resume != "never":
        finished = _finished_output(out_path, run_id)
        if finished is not None:
            # killed after the final rename, before the clean-up: the checkpoint (a file) and
            # the chunk folder (a directory) are left; both go
            if ckpt is not None:
                ckpt.unlink(missing_ok=True)
            shutil.rmtree(partial_path(out_path), ignore_errors=True)
            logger.info("%s is the finished result of this run: returned as it is", out_path)
            return _result_from_file(out_path, finished, run.model, run.s, run_id)
        if resume == "require" and out_path.exists() and (ckpt is None or not ckpt.exists()):
            raise ResultFileError(
                f"output {str(out_path)!r} belongs to another run (other inputs) and there is"
                " no checkpoint of this run to resume",
                field="output",
            )
    if ckpt is not None and resume == "never":
        ckpt.unlink(missing_ok=True)
    elif ckpt is not None:
        loaded = _load_checkpoint(ckpt, run_id, resume)
        if loaded is not None:
            rows, chunks, last_time, state = loaded
            why = (
                None
                if out_path is None
                else _partial_agrees(partial_path(out_path), run_id, rows, chunks, last_time)
            )
            if why is not None:
                msg = f"checkpoint {str(ckpt)!r} cannot be resumed: {why}"
                if resume == "require":
                    raise ResultFileError(f"{msg}; {RESTART_ADVICE}", field="checkpoint")
                logger.warning("%s; starting afresh", msg)
                ckpt.unlink(missing_ok=True)
                state = None
            else:
                logger.info(
                    "resuming %s from t = %.6g s (checkpoint %s)",
                    out_path if out_path is not None else "the run",
                    float(state["scal"][K.SC_T]),
                    ckpt,
                )
                run.resumed = (rows, chunks, last_time)
    if state is None:
        _fresh_state(run)
    else:
        _resumed_state(run, state)
    return None


def _fresh_state(run: _Run) -> None:
    """The solver state at the start of the storm, with a₀ = M⁻¹P(t₀, d₀, v₀)."""
    arr, n = run.arr, run.x.size
    vec = np.zeros((K.N_VEC, B.NDOF_NODE * n))
    scal = np.zeros(K.N_SCAL)
    scal[K.SC_T] = run.kinematics.t0
    scal[K.SC_DT] = run.s.dt_max
    scal[K.SC_T_LIFT] = math.nan
    scal[K.SC_T_LIMIT] = math.nan
    scal[K.SC_LIFT_NODE] = -1.0
    scal[K.SC_T_ZLIMIT] = math.nan
    scal[K.SC_ZLIMIT_NODE] = -1.0
    sstate = arr["sstate"]
    axst = arr["axst"]
    fstate = np.zeros((n, N_FORCE_STATE))
    nodal = np.zeros((3, n))
    env = np.zeros((K.N_ENV, n))
    env[K.E_MIN_V] = 0.0
    env[K.E_MIN_N] = math.inf
    env[K.E_MAX_N] = -math.inf
    env[K.E_MIN_VCONT] = math.inf
    ok = K.initial_acceleration(
        run.soil_id, run.force_id,
        run.st, arr["props"], arr["nodes"], arr["fixed"], arr["spring"], arr["model_ids"],
        arr["sparams"], sstate, axst, run.fparams, fstate,
        *run.kin.cover(scal[K.SC_T], scal[K.SC_T]),
        arr["uload"], vec, scal, nodal, run.t_out, run.t_end, run.rec, run.rec_t, env,
    )  # fmt: skip
    if not ok:
        raise InputError("the soil kernel returned NaN at the start (invalid soil model)")
    run.vec, run.scal, run.sstate, run.axst = vec, scal, sstate, axst
    run.nodal, run.env, run.fstate = nodal, env, fstate


def _resumed_state(run: _Run, state: dict[str, np.ndarray]) -> None:
    """The solver state of a checkpoint."""
    run.done = int(state.pop("status"))
    run.vec, run.scal, run.sstate, run.axst, run.nodal, run.env, run.fstate = (
        state["vec"], state["scal"], state["sstate"], state["axst"], state["nodal"],
        state["env"], state["fstate"],
    )  # fmt: skip


def _time_loop(run: _Run, progress: bool) -> tuple[int, tuple[list[np.ndarray], ...] | None]:
    """Loop stage: :func:`._pipeline_kernel.integrate` chunk by chunk under the driver, the
    records kept (chunk files, or in memory without an output), a checkpoint per chunk.

    Returns the final status and, without an output file, the records kept in memory
    (times, rows); with one, the records stay in the writer (``run.writer``) to be finished.
    """
    s, arr, st, kin = run.s, run.arr, run.st, run.kin
    vec, scal, sstate, axst = run.vec, run.scal, run.sstate, run.axst
    nodal, env, fstate = run.nodal, run.env, run.fstate
    t_end, ckpt = run.t_end, run.ckpt
    writer = None
    if run.out_path is not None:
        resumed = run.resumed if run.resumed is not None else (0, 0, math.nan)
        writer = _Writer(
            run.out_path, run.x, run.base_attrs, run.run_id, resumed, s.compression_level
        )
    run.writer = writer
    mem_t: list[np.ndarray] = []
    mem_r: list[np.ndarray] = []

    def keep(t: np.ndarray, r: np.ndarray) -> None:
        if writer is not None:
            writer.append(t.copy(), r)
        else:
            mem_t.append(t.copy())
            mem_r.append(r.copy())

    # the kernel fills rec/rec_t from row 0 at each call: the driver spills them to ``keep``
    recorder = SpillRecorder(keep, run.rec_t, run.rec)

    def advance(t_stop: float, _rows: np.ndarray, _n: int) -> tuple[int, int]:
        m, status = call_literal(
            K.integrate, 2, run.soil_id, run.force_id,
            st, arr["props"], arr["nodes"], arr["fixed"], arr["spring"],
            arr["model_ids"], arr["sparams"], sstate, axst, run.fparams, fstate,
            *kin.cover(scal[K.SC_T], t_stop),
            arr["uload"], vec, scal, nodal, run.t_out, t_end, t_stop, run.rec, run.rec_t, env,
            False,
        )  # fmt: skip
        # a full buffer returns STATUS_CHUNK before t_stop
        if status == K.STATUS_CHUNK and scal[K.SC_T] < t_stop - 1e-9 * (1 + t_stop):
            return m, Status.BUFFER_FULL
        return m, status

    def after_chunk(status: int) -> None:
        if writer is not None:
            writer.commit()
        if ckpt is not None and writer is not None:
            _save_checkpoint(
                ckpt,
                run.run_id,
                writer.rows,
                writer.chunks,
                writer.last_time if writer.rows else math.nan,
                {"vec": vec, "scal": scal, "sstate": sstate, "axst": axst, "nodal": nodal,
                 "fstate": fstate, "env": env, "status": np.array(status)},
            )  # fmt: skip

    try:
        with progress_bar(progress, round(t_end), "pipeline storm", "s") as bar:
            status = drive(
                advance,
                lambda _k: min(float(scal[K.SC_T]) + s.chunk_duration, t_end),
                recorder=recorder,
                status=run.done,
                bar=bar,
                position=lambda: round(scal[K.SC_T]),
                after_chunk=after_chunk,
            )
    except BaseException:
        if writer is not None:
            writer.close()
        raise
    return status, (None if writer is not None else (mem_t, mem_r))


def _summary(run: _Run) -> dict[str, float]:
    """Counters, energies and events of the run (``PipelineResult.summary``)."""
    arr, vec, scal, st, x, n = run.arr, run.vec, run.scal, run.st, run.x, run.x.size
    d_fin = vec[K.V_D]
    mass = np.zeros(B.NDOF_NODE * n)
    nodes = arr["nodes"]
    mass[0::3], mass[1::3], mass[2::3] = (
        nodes[:, K.ND_MASS_U],
        nodes[:, K.ND_MASS_V],
        nodes[:, K.ND_J],
    )
    ke = 0.5 * float(np.sum(mass * vec[K.V_V] ** 2))
    # the plain-Python twin: ~2 ms per 1000 elements once per run, where the jitted kernel
    # would cost a first run its compiling
    se = float(B.strain_energy_py(d_fin, arr["props"])) + 0.5 * float(
        np.sum(arr["spring"] * d_fin**2)
    )
    w_h = float(scal[K.SC_W_HYD])
    w_s = float(scal[K.SC_W_SOIL])
    n_steps = float(scal[K.SC_NSTEP])
    lift_node = int(scal[K.SC_LIFT_NODE])
    summary = {
        "n_steps": n_steps,
        "n_rejected": float(scal[K.SC_NREJ]),
        "mean_newton_iterations": float(scal[K.SC_NITER]) / max(n_steps + scal[K.SC_NREJ], 1.0),
        "final_time": float(scal[K.SC_T]),
        "time_to_stop_displacement": float(scal[K.SC_T_LIMIT]),
        "n_liftoff": float(scal[K.SC_N_LIFT]),
        "first_liftoff_time": float(scal[K.SC_T_LIFT]),
        "first_liftoff_x": float(x[lift_node]) if lift_node >= 0 else math.nan,
        "work_hydro": w_h,
        "work_soil": w_s,
        "kinetic_energy": ke,
        "strain_energy": se,
        "energy_residual": ke + se - w_h - w_s,
        "negative_pivot_steps": float(scal[K.SC_NEG_PIVOT]),
        "n_factorisations": float(scal[K.SC_N_FACTOR]),
        "n_nodes": float(n),
    }
    z_node = int(scal[K.SC_ZLIMIT_NODE])
    summary["out_of_range_time"] = float(scal[K.SC_T_ZLIMIT])
    summary["out_of_range_node"] = float(z_node)
    summary["out_of_range_x"] = float(x[z_node]) if z_node >= 0 else math.nan
    summary["penetration_limit"] = float(st[K.ST_Z_LIMIT])
    return summary


def _result(run: _Run, status: int, records: tuple[list[np.ndarray], ...] | None) -> PipelineResult:
    """Result stage: the summary, the verdict, the envelopes, and the records (the output
    file finished under its name, or a Dataset in memory)."""
    s, scal, st, env, x, d = run.s, run.scal, run.st, run.env, run.x, run.d
    env_ds = _envelopes(x, env)
    k_worst = int(np.argmax(env[K.E_ABS_V]))
    vmax = float(env[K.E_ABS_V, k_worst])
    emax = float(np.max(env[K.E_STRAIN]))
    stopped = status == K.STATUS_LIMIT
    criteria = _criteria(vmax, emax, d, stopped, s)
    summary = _summary(run)
    z_node = int(scal[K.SC_ZLIMIT_NODE])
    outside = None
    if z_node >= 0:
        k_z = int(np.argmax(env[K.E_MAX_Z]))
        outside = penetration_reason(
            float(st[K.ST_Z_LIMIT]), float(scal[K.SC_T_ZLIMIT]),
            f"node {z_node}, x = {x[z_node]:.4g} m", float(env[K.E_MAX_Z, k_z]), d,
            "the soil models", f"x = {x[k_z]:.4g} m",
        )  # fmt: skip
    success, status, message = run_outcome(
        logger, status, run="storm", t=scal[K.SC_T], dt_min=st[K.ST_DT_MIN],
        detail=_limit_detail(s, scal[K.SC_T_LIMIT], x[k_worst]) if stopped else "",
        outside=outside,
    )  # fmt: skip
    final_attrs = {
        "status": int(status),
        "message": message,
        "max_displacement": vmax,
        "max_strain": emax,
        "out_of_range": int(z_node >= 0),
        "out_of_range_time": float(scal[K.SC_T_ZLIMIT]),
        "out_of_range_x": summary["out_of_range_x"],
        "summary": json.dumps(summary, default=float),
    }
    data = None
    if run.writer is not None:
        # the result takes its name, then the checkpoint and the chunks go: a kill in between
        # leaves a finished output of this run, which a second call returns at once
        run.writer.finish(env_ds, final_attrs)
        if run.ckpt is not None:
            run.ckpt.unlink(missing_ok=True)
        run.writer.discard()
    elif records is not None and records[0]:
        mem_t, mem_r = records
        tt = np.concatenate(mem_t)
        rr = np.concatenate(mem_r)
        data = xr.Dataset(
            {
                name: (("time", "node"), rr[:, k, :], {"long_name": ln, "units": u})
                for name, (k, ln, u) in FIELDS.items()
            },
            coords={"time": tt, "x": ("node", x)},
            attrs={**run.base_attrs, **final_attrs},
        )
        data = annotate(xr.merge([data, env_ds], combine_attrs="override"))
    return PipelineResult(
        success=success,
        status=int(status),
        message=message,
        diameter=d,
        x=x,
        max_displacement=vmax,
        worst_node=k_worst,
        max_strain=emax,
        criteria=criteria,
        summary=summary,
        envelopes=env_ds,
        data=data,
        netcdf=run.out_path,
        run_id=run.run_id,
    )


def _limit_detail(s: PipelineSettings, t: float, x_worst: float) -> str:
    """Which limit a stopped run reached, when, and where the largest |y| is."""
    return f"{s.stop_displacement_over_d:g}D at t = {t:.1f} s; largest |y| at x = {x_worst:.4g} m"


def _envelopes(x: np.ndarray, env: np.ndarray) -> xr.Dataset:
    return xr.Dataset(
        {
            name: ("node", env[k].copy(), {"long_name": ln, "units": u})
            for name, (k, ln, u) in ENVELOPES.items()
        },
        coords={"x": ("node", x, {"long_name": "position along the pipe", "units": "m"})},
    )


def _criteria(
    vmax: float, emax: float, d: float, stopped: bool, s: PipelineSettings
) -> dict[str, bool | None]:
    criteria: dict[str, bool | None] = {
        **dynamic_criteria(vmax, d, s.stop_displacement_over_d, stopped)
    }
    criteria["strain"] = None if s.strain_limit is None else bool(emax <= s.strain_limit)
    return criteria


def _result_from_file(
    path: Path, attrs: Mapping[str, Any], model: PipelineModel, s: PipelineSettings, run_id: str
) -> PipelineResult:
    """The :class:`PipelineResult` of a finished output file of this run."""
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        env_ds = xr.Dataset(
            {name: ("node", ds[name].values.copy(), dict(ds[name].attrs)) for name in ENVELOPES},
            coords={"x": ("node", model.x, {"long_name": "position along the pipe", "units": "m"})},
        )
    status = int(attrs["status"])
    env_abs = env_ds["max_abs_y"].values
    k_worst = int(np.argmax(env_abs))
    vmax = float(env_abs[k_worst])
    emax = float(np.max(env_ds["max_strain"].values))
    d = model.pipe.outer_diameter
    return PipelineResult(
        success=Status(status).success,
        status=status,
        message=str(attrs["message"]),
        diameter=d,
        x=model.x,
        max_displacement=vmax,
        worst_node=k_worst,
        max_strain=emax,
        criteria=_criteria(vmax, emax, d, status == K.STATUS_LIMIT, s),
        summary=json.loads(attrs["summary"]),
        envelopes=env_ds,
        data=None,
        netcdf=path,
        run_id=run_id,
    )
