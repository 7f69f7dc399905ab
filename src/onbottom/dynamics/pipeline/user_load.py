"""User-given distributed loads q(x, t) on the pipeline (imposed-load studies, peer checks).

A user load is added to the hydrodynamic load of every node as a lumped nodal force
ℓ_i·q(x_i, t) (ℓ_i the tributary length), laterally (y) and optionally axially (x). It does not
depend on the pipe's motion (no tangent) and is not reduced by the F109 load reductions.
Two callable-free forms, both evaluated inside the numba time loop:

- :class:`TravellingSineLoad`: q(x, t) = r(t)·A·sin(2π(x/λ − (t − t_s)/T)), a sinusoid
  travelling in +x at λ/T, switched on at t_s with a half-cosine ramp
  r = ½(1 − cos(π(t − t_s)/T_r)) over T_r (r = 0 before t_s, 1 after t_s + T_r);
- :class:`TableLoad`: samples q[t_k, node] at t_k = t₀ + kΔt, linear in time between samples,
  held at the first row before t₀ and at the last row after the table.

Give it as ``PipelineModel(..., user_load=...)``. For a load alone, switch the hydrodynamic
loads off with still water and no relative-velocity drag: ``relative_velocity=False`` and
:func:`still_water` kinematics (then f_hyd ≡ 0; the added mass C_a stays in the lateral mass).
Theory: docs/theory/pipeline_fe.md, "User loads".
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from onbottom._validate import non_negative, positive
from onbottom.dynamics.pipeline import _pipeline_kernel as K
from onbottom.errors import InputError
from onbottom.hydro.short_crested import NodeKinematics

__all__ = ["TableLoad", "TravellingSineLoad", "UserLoad", "still_water"]

# kernel encoding: settings[K.ST_UL_KIND + UL_*] (see _pipeline_kernel.add_user_load)
UL_NONE = K.UL_NONE
UL_SINE = K.UL_SINE
UL_TABLE = K.UL_TABLE
UL_KIND = 0
UL_AMP_Y = K.ST_UL_AMP_Y - K.ST_UL_KIND
UL_AMP_X = K.ST_UL_AMP_X - K.ST_UL_KIND
UL_WAVENUMBER = K.ST_UL_WAVENUMBER - K.ST_UL_KIND
UL_OMEGA = K.ST_UL_OMEGA - K.ST_UL_KIND
UL_RAMP = K.ST_UL_RAMP - K.ST_UL_KIND
UL_START = K.ST_UL_START - K.ST_UL_KIND
UL_T0 = K.ST_UL_T0 - K.ST_UL_KIND
UL_DT = K.ST_UL_DT - K.ST_UL_KIND
N_UL = K.N_SETTINGS - K.ST_UL_KIND


class UserLoad:
    """Base of the user loads: :meth:`at` (NumPy), :meth:`kernel_settings`, :meth:`table`."""

    def at(self, x: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        """Lateral and axial load (q_y, q_x) [N/m] at positions ``x`` [m] and time ``t`` [s]."""
        raise NotImplementedError

    def kernel_settings(self) -> np.ndarray:
        """The N_UL kernel settings."""
        raise NotImplementedError

    def table(self, n_nodes: int) -> np.ndarray:
        """Kernel table (n_times, 2, n_nodes): rows q_y, q_x (a 1×2×1 dummy when unused)."""
        return np.zeros((1, 2, 1))

    def check_nodes(self, n_nodes: int) -> None:
        """Raise :class:`~onbottom.errors.InputError` if the load does not fit ``n_nodes``."""

    def describe(self) -> dict[str, Any]:
        """Provenance (part of the run identity)."""
        raise NotImplementedError


@dataclass(frozen=True, kw_only=True)
class TravellingSineLoad(UserLoad):
    """q(x, t) = r(t)·A·sin(2π(x/λ − (t − t_s)/T)), travelling in +x.

    Parameters
    ----------
    amplitude : float
        Lateral amplitude A_y [N/m] (signed, finite).
    wavelength : float
        λ [m], > 0.
    period : float
        T [s], > 0.
    ramp : float
        Half-cosine ramp duration T_r [s], >= 0 (0: switched on at once).
    axial_amplitude : float
        Axial amplitude A_x [N/m] of the same sinusoid (signed, finite; default 0).
    start : float
        Switch-on time t_s [s], finite (default 0): no load before it.
    """

    amplitude: float
    wavelength: float
    period: float
    ramp: float = 0.0
    axial_amplitude: float = 0.0
    start: float = 0.0

    def __post_init__(self) -> None:
        c = "TravellingSineLoad"
        for name in ("amplitude", "axial_amplitude", "start"):
            v = getattr(self, name)
            if not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InputError(f"{c}.{name} = {v!r} is invalid: must be a finite number")
        positive(f"{c}.wavelength", self.wavelength)
        positive(f"{c}.period", self.period)
        non_negative(f"{c}.ramp", self.ramp)

    def ramp_factor(self, t: np.ndarray | float) -> np.ndarray:
        """r(t) [-]."""
        tau = np.asarray(t, dtype=float) - self.start
        if self.ramp > 0.0:
            r = 0.5 * (1.0 - np.cos(np.pi * np.clip(tau / self.ramp, 0.0, 1.0)))
        else:
            r = np.ones_like(tau)
        return np.where(tau > 0.0, r, 0.0)

    def at(self, x: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        xx = np.asarray(x, dtype=float)
        s = self.ramp_factor(t) * np.sin(
            2.0 * math.pi * xx / self.wavelength - 2.0 * math.pi * (t - self.start) / self.period
        )
        return self.amplitude * s, self.axial_amplitude * s

    def kernel_settings(self) -> np.ndarray:
        k = np.zeros(N_UL)
        k[UL_KIND] = UL_SINE
        k[UL_AMP_Y] = self.amplitude
        k[UL_AMP_X] = self.axial_amplitude
        k[UL_WAVENUMBER] = 2.0 * math.pi / self.wavelength
        k[UL_OMEGA] = 2.0 * math.pi / self.period
        k[UL_RAMP] = self.ramp
        k[UL_START] = self.start
        return k

    def describe(self) -> dict[str, Any]:
        return {
            "kind": "travelling_sine",
            "amplitude": self.amplitude,
            "axial_amplitude": self.axial_amplitude,
            "wavelength": self.wavelength,
            "period": self.period,
            "ramp": self.ramp,
            "start": self.start,
        }


@dataclass(frozen=True, kw_only=True, eq=False)
class TableLoad(UserLoad):
    """Sampled load q[t_k, node] at t_k = t₀ + kΔt, linear in time, held outside the table.

    Parameters
    ----------
    dt : float
        Sample interval Δt [s], > 0.
    lateral : array (n_times, n_nodes)
        q_y [N/m] at the model's nodes (finite), n_times >= 1.
    axial : array (n_times, n_nodes) or None
        q_x [N/m] (finite), same shape; None → 0.
    t0 : float
        Time of the first row [s], finite (default 0).
    """

    dt: float
    lateral: np.ndarray
    axial: np.ndarray | None = None
    t0: float = 0.0

    def __post_init__(self) -> None:
        c = "TableLoad"
        positive(f"{c}.dt", self.dt)
        if not math.isfinite(self.t0):
            raise InputError(f"{c}.t0 = {self.t0!r} is invalid: must be finite")
        lat = np.array(self.lateral, dtype=float)
        if lat.ndim != 2 or lat.shape[0] < 1 or lat.shape[1] < 1:
            raise InputError(
                f"{c}.lateral of shape {lat.shape} is invalid: need (n_times >= 1, n_nodes)"
            )
        if not np.all(np.isfinite(lat)):
            raise InputError(f"{c}.lateral is invalid: contains NaN or infinite values")
        lat.setflags(write=False)
        object.__setattr__(self, "lateral", lat)
        if self.axial is not None:
            ax = np.array(self.axial, dtype=float)
            if ax.shape != lat.shape:
                raise InputError(
                    f"{c}.axial of shape {ax.shape} is invalid: must equal lateral's {lat.shape}"
                )
            if not np.all(np.isfinite(ax)):
                raise InputError(f"{c}.axial is invalid: contains NaN or infinite values")
            ax.setflags(write=False)
            object.__setattr__(self, "axial", ax)

    @property
    def n_nodes(self) -> int:
        """Number of node columns."""
        return int(self.lateral.shape[1])

    def check_nodes(self, n_nodes: int) -> None:
        if self.n_nodes != n_nodes:
            raise InputError(
                f"TableLoad.lateral has {self.n_nodes} node columns, the model {n_nodes} nodes:"
                " sample the load at model.x"
            )

    def _row(self, t: float) -> tuple[int, float]:
        n = self.lateral.shape[0]
        s = (t - self.t0) / self.dt
        if n == 1 or s <= 0.0:
            return 0, 0.0
        if s >= n - 1:
            return n - 2, 1.0
        i = int(s)
        return i, s - i

    def at(self, x: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        """(q_y, q_x) [N/m] at the nodes (``x`` must have n_nodes entries; only its size is
        used: the table is given at the nodes)."""
        self.check_nodes(np.asarray(x).size)
        i, f = self._row(t)
        ax = self.axial if self.axial is not None else np.zeros_like(self.lateral)
        if self.lateral.shape[0] == 1:
            return self.lateral[0].copy(), ax[0].copy()
        qy = (1.0 - f) * self.lateral[i] + f * self.lateral[i + 1]
        qx = (1.0 - f) * ax[i] + f * ax[i + 1]
        return qy, qx

    def kernel_settings(self) -> np.ndarray:
        k = np.zeros(N_UL)
        k[UL_KIND] = UL_TABLE
        k[UL_T0] = self.t0
        k[UL_DT] = self.dt
        return k

    def table(self, n_nodes: int) -> np.ndarray:
        self.check_nodes(n_nodes)
        tab = np.zeros((self.lateral.shape[0], 2, n_nodes))
        tab[:, 0, :] = self.lateral
        if self.axial is not None:
            tab[:, 1, :] = self.axial
        return tab

    def describe(self) -> dict[str, Any]:
        h = hashlib.sha256(np.ascontiguousarray(self.lateral).tobytes())
        if self.axial is not None:
            h.update(np.ascontiguousarray(self.axial).tobytes())
        return {
            "kind": "table",
            "t0": self.t0,
            "dt": self.dt,
            "shape": list(self.lateral.shape),
            "axial": self.axial is not None,
            "sha256": h.hexdigest(),
        }


def kernel_settings(load: UserLoad | None) -> np.ndarray:
    """The N_UL kernel settings of ``load`` (all zero, kind none, without one)."""
    return np.zeros(N_UL) if load is None else load.kernel_settings()


def still_water(n_nodes: int, duration: float, t0: float = 0.0) -> NodeKinematics:
    """Zero-flow kinematics (two samples) for a run loaded by a user load alone.

    With ``PipelineModel(relative_velocity=False)`` the hydrodynamic load is then zero
    (with relative velocity on, still water still damps the motion by drag on −ẏ).
    ``duration`` [s], > 0; ``t0`` [s] the start time.
    """
    positive("duration", duration)
    z = np.zeros((2, int(n_nodes)), dtype=np.float32)
    return NodeKinematics(t0=float(t0), dt=float(duration), velocity=z, acceleration=z.copy())
