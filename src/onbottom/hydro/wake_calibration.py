"""Calibration protocol of the wake model against peak-load coefficients C*_Y(K*, M*), C*_Z.

**Regular protocol** (:func:`regular_peak_coefficients`): a fixed pipe (ẏ = 0) in the flow
U(t) = U* sin(2πt/T*) plus a current V* = M* U*, K* = U* T*/D, started from rest (zero state);
``n_cycles`` periods of ``steps_per_cycle`` samples; the peak |F_Y| and the peak F_Z of the
**last** period (the wake is then established: from the second reversal on, every half-cycle
meets a wake made by a full half-cycle), divided by ½ρD(U* + V*)². The model's coefficients
depend on K*, M* only (every length scales with D, every velocity with U*), so the protocol
runs with D = 1 m, ρ = 1 kg/m³, U* = 1 m/s.

The target tables (DNV-RP-F109 (2017) Tables 3-9/3-10, :mod:`onbottom.checks.f109_tables`)
are passed in as arrays: ``hydro/`` sits below ``checks/`` in the layering.
:func:`compare_with_tables` gives the model/table ratios, their RMS and the worst cell;
:func:`fit_wake_model` fits chosen constants by least squares on ln(C_model / C_table) over
both tables (``tools/calibrate_wake.py`` runs it and writes the validation page).

**Irregular check** (:func:`jonswap_record`, :func:`record_peaks`): the same fixed pipe in a
JONSWAP near-bed velocity record (random phases, :mod:`onbottom.hydro.flow_synthesis`) plus a
current; the record is split into half-cycles at the sign changes of U + V, and the largest
per-half-cycle peaks of |F_Y| and F_Z are compared by the caller with F109's F* at the design
U*, T* (F109 (2017) §3.4.3: U* = k_U U_s, T* = k_T T_u).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import least_squares

from onbottom._jit import numba_njit as njit
from onbottom._validate import integer, non_negative, positive
from onbottom.constants import GRAVITY
from onbottom.errors import InputError
from onbottom.hydro._force_contract import FO_FY, FO_FZ, FO_SIZE, N_FORCE_STATE
from onbottom.hydro._wake_kernel import wake_kernel
from onbottom.hydro.design_sea_state import (
    jonswap_gamma,
    peak_period_factor,
    peak_velocity_factor,
    significant_bed_velocity,
)
from onbottom.hydro.flow_synthesis import bed_spectrum, midpoint_grid, random_phase_series
from onbottom.hydro.wake import WakeModel

__all__ = [
    "FITTED_CONSTANTS",
    "WakeCalibrationResult",
    "compare_with_tables",
    "drive_fixed_pipe",
    "fit_wake_model",
    "jonswap_record",
    "record_peaks",
    "regular_peak_coefficients",
]

FITTED_CONSTANTS: tuple[str, ...] = (
    "drag_excess",
    "lift_excess",
    "drag_relaxation",
    "lift_relaxation",
    "wake_ratio",
    "wake_decay",
    "slack_exponent",
)
"""The :class:`WakeModel` fields fitted by default (C_D∞, C_L∞, C_M, r_0, λ_o are fixed; see its
doc)."""

_BOUNDS: dict[str, tuple[float, float]] = {
    "drag_excess": (-0.9, 10.0),
    "lift_excess": (-0.8, 10.0),
    "drag_relaxation": (0.05, 200.0),
    "lift_relaxation": (0.05, 200.0),
    "wake_ratio": (0.0, 2.0),
    "wake_decay": (0.05, 200.0),
    "slack_exponent": (0.0, 20.0),
    "slack_threshold": (0.0, 0.9),
    "wake_onset": (0.0, 5.0),
    "cd_steady": (0.1, 3.0),
    "cl_steady": (0.1, 3.0),
    "cm": (1.0, 6.0),
}


@njit(cache=True)
def drive_fixed_pipe(params, t, u, dudt, vc, d, rho, fy, fz):
    """Evaluate the wake kernel along a record for a fixed pipe (ẏ = 0), from a zero state.

    t, u, dudt: time [s], wave velocity [m/s] and acceleration [m/s²] samples; vc current
    [m/s]; d [m]; rho [kg/m³]. Writes F_Y and F_Z [N/m] into ``fy``, ``fz``.
    """
    state_old = np.zeros(N_FORCE_STATE)
    state_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    for i in range(t.shape[0]):
        wake_kernel(params, state_old, t[i], u[i], dudt[i], vc, 0.0, d, rho, state_new, out)
        fy[i] = out[FO_FY]
        fz[i] = out[FO_FZ]
        for j in range(N_FORCE_STATE):
            state_old[j] = state_new[j]


@njit(cache=True)
def _regular_grid(params, k_star, m_star, n_cycles, steps_per_cycle, cy, cz):
    state_old = np.zeros(N_FORCE_STATE)
    state_new = np.zeros(N_FORCE_STATE)
    out = np.zeros(FO_SIZE)
    for c in range(k_star.shape[0]):
        period = k_star[c]  # D = 1, U* = 1
        vc = m_star[c]
        omega = 2.0 * math.pi / period
        dt = period / steps_per_cycle
        for j in range(N_FORCE_STATE):
            state_old[j] = 0.0
        fy_max = 0.0
        fz_max = 0.0
        last = (n_cycles - 1) * steps_per_cycle
        for i in range(n_cycles * steps_per_cycle + 1):
            t = i * dt
            u = math.sin(omega * t)
            dudt = omega * math.cos(omega * t)
            wake_kernel(params, state_old, t, u, dudt, vc, 0.0, 1.0, 1.0, state_new, out)
            for j in range(N_FORCE_STATE):
                state_old[j] = state_new[j]
            if i > last:
                fy_max = max(fy_max, abs(out[FO_FY]))
                fz_max = max(fz_max, out[FO_FZ])
        norm = 0.5 * (1.0 + vc) ** 2
        cy[c] = fy_max / norm
        cz[c] = fz_max / norm


def regular_peak_coefficients(
    model: WakeModel,
    k_star: ArrayLike,
    m_star: ArrayLike,
    *,
    n_cycles: int = 4,
    steps_per_cycle: int = 400,
) -> tuple[NDArray, NDArray]:
    """Per-cycle peak load coefficients of the regular protocol (module docstring) [-].

    Parameters
    ----------
    model : WakeModel
        The force model.
    k_star, m_star : array_like
        K* = U* T*/D > 0 and M* = V*/U* >= 0 [-], broadcast together.
    n_cycles : int
        Periods run from rest, >= 2; the peaks are those of the last one.
    steps_per_cycle : int
        Samples per period, >= 16.

    Returns
    -------
    cy, cz : arrays
        max |F_Y| / (½ρD(U*+V*)²) and max F_Z / (½ρD(U*+V*)²) of the last period.
    """
    n = integer("n_cycles", n_cycles, 2, 1000)
    ns = integer("steps_per_cycle", steps_per_cycle, 16, 10**6)
    k, m = np.broadcast_arrays(np.asarray(k_star, dtype=float), np.asarray(m_star, dtype=float))
    if np.any(~np.isfinite(k) | (k <= 0.0)):
        raise InputError(f"k_star = {k!r} is invalid: must be finite and > 0")
    if np.any(~np.isfinite(m) | (m < 0.0)):
        raise InputError(f"m_star = {m!r} is invalid: must be finite and >= 0")
    cy = np.empty(k.size)
    cz = np.empty(k.size)
    _regular_grid(model.parameters(), k.ravel().copy(), m.ravel().copy(), n, ns, cy, cz)
    return cy.reshape(k.shape), cz.reshape(k.shape)


@dataclass(frozen=True)
class WakeCalibrationResult:
    """Model against table over a K*, M* grid (arrays indexed [M*, K*], like F109's tables).

    ``ratio_y``, ``ratio_z`` = C_model/C_table; ``rms_log`` = RMS of ln(ratio) over both
    tables; ``rms_log_y``/``rms_log_z`` per table; ``rms_rel`` = RMS of (ratio − 1) over both;
    ``worst`` = (table "Y"/"Z", K*, M*, ratio) of the cell with the largest |ln ratio|.
    """

    model: WakeModel
    k_grid: NDArray
    m_grid: NDArray
    cy: NDArray
    cz: NDArray
    cy_target: NDArray
    cz_target: NDArray
    n_cycles: int
    steps_per_cycle: int

    @property
    def ratio_y(self) -> NDArray:
        """C_Y,model / C*_Y [-]."""
        return self.cy / self.cy_target

    @property
    def ratio_z(self) -> NDArray:
        """C_Z,model / C*_Z [-]."""
        return self.cz / self.cz_target

    @property
    def rms_log_y(self) -> float:
        """RMS of ln(C_Y,model / C*_Y) [-]."""
        return float(np.sqrt(np.mean(np.log(self.ratio_y) ** 2)))

    @property
    def rms_log_z(self) -> float:
        """RMS of ln(C_Z,model / C*_Z) [-]."""
        return float(np.sqrt(np.mean(np.log(self.ratio_z) ** 2)))

    @property
    def rms_log(self) -> float:
        """RMS of ln(model/table) over both tables [-]."""
        r = np.concatenate([np.log(self.ratio_y).ravel(), np.log(self.ratio_z).ravel()])
        return float(np.sqrt(np.mean(r**2)))

    @property
    def rms_rel(self) -> float:
        """RMS of (model/table − 1) over both tables [-]."""
        r = np.concatenate([self.ratio_y.ravel(), self.ratio_z.ravel()]) - 1.0
        return float(np.sqrt(np.mean(r**2)))

    @property
    def worst(self) -> tuple[str, float, float, float]:
        """(table, K*, M*, ratio) of the cell with the largest |ln(model/table)|."""
        ly = np.abs(np.log(self.ratio_y))
        lz = np.abs(np.log(self.ratio_z))
        which, arr, ratio = (
            ("Y", ly, self.ratio_y) if ly.max() >= lz.max() else ("Z", lz, self.ratio_z)
        )
        im, ik = np.unravel_index(int(np.argmax(arr)), arr.shape)
        return which, float(self.k_grid[ik]), float(self.m_grid[im]), float(ratio[im, ik])

    def summary(self) -> dict[str, Any]:
        """Figures of merit and the fitted constants."""
        which, k, m, r = self.worst
        d: dict[str, Any] = {
            "rms_log": self.rms_log,
            "rms_log_y": self.rms_log_y,
            "rms_log_z": self.rms_log_z,
            "rms_rel": self.rms_rel,
            "worst_table": which,
            "worst_k_star": k,
            "worst_m_star": m,
            "worst_ratio": r,
            "n_cycles": self.n_cycles,
            "steps_per_cycle": self.steps_per_cycle,
        }
        d.update({f: getattr(self.model, f) for f in FITTED_CONSTANTS})
        return d


def _grid(k_grid: ArrayLike, m_grid: ArrayLike, cy: ArrayLike, cz: ArrayLike):
    k = np.asarray(k_grid, dtype=float)
    m = np.asarray(m_grid, dtype=float)
    ty = np.asarray(cy, dtype=float)
    tz = np.asarray(cz, dtype=float)
    if k.ndim != 1 or m.ndim != 1 or ty.shape != (m.size, k.size) or tz.shape != ty.shape:
        raise InputError(
            f"tables of shape {ty.shape}/{tz.shape} are invalid for K* ({k.size}) and"
            f" M* ({m.size}) grids: expected ({m.size}, {k.size}) arrays [M*, K*]"
        )
    if np.any(~np.isfinite(ty) | (ty <= 0.0)) or np.any(~np.isfinite(tz) | (tz <= 0.0)):
        raise InputError("target coefficients are invalid: must be finite and > 0")
    kk, mm = np.meshgrid(k, m)
    return k, m, ty, tz, kk, mm


def compare_with_tables(
    model: WakeModel,
    k_grid: ArrayLike,
    m_grid: ArrayLike,
    cy_target: ArrayLike,
    cz_target: ArrayLike,
    *,
    n_cycles: int = 4,
    steps_per_cycle: int = 400,
) -> WakeCalibrationResult:
    """Run the regular protocol over the grid and compare with the tables [M*, K*]."""
    k, m, ty, tz, kk, mm = _grid(k_grid, m_grid, cy_target, cz_target)
    cy, cz = regular_peak_coefficients(
        model, kk, mm, n_cycles=n_cycles, steps_per_cycle=steps_per_cycle
    )
    return WakeCalibrationResult(model, k, m, cy, cz, ty, tz, n_cycles, steps_per_cycle)


def fit_wake_model(
    k_grid: ArrayLike,
    m_grid: ArrayLike,
    cy_target: ArrayLike,
    cz_target: ArrayLike,
    *,
    start: WakeModel | None = None,
    free: tuple[str, ...] = FITTED_CONSTANTS,
    n_cycles: int = 4,
    steps_per_cycle: int = 400,
) -> WakeCalibrationResult:
    """Least-squares fit of the ``free`` constants of ``start`` to the tables.

    Residuals: ln(C_model/C_table) of every cell of both tables (equal weights; the log makes
    a 10 % miss count the same on C* = 13 and on C* = 0.9). scipy.optimize.least_squares,
    trust-region reflective within the bounds of ``_BOUNDS``, from ``start`` (default:
    :class:`WakeModel` defaults).
    """
    model0 = WakeModel() if start is None else start
    unknown = [f for f in free if f not in _BOUNDS]
    if unknown or not free:
        raise InputError(
            f"free = {free!r} is invalid: choose a non-empty subset of {tuple(_BOUNDS)}"
        )
    k, m, ty, tz, kk, mm = _grid(k_grid, m_grid, cy_target, cz_target)
    target = np.log(np.concatenate([ty.ravel(), tz.ravel()]))
    lo = np.array([_BOUNDS[f][0] for f in free])
    hi = np.array([_BOUNDS[f][1] for f in free])
    x0 = np.clip([float(getattr(model0, f)) for f in free], lo, hi)

    def residuals(x: NDArray) -> NDArray:
        trial = dataclasses.replace(model0, **dict(zip(free, map(float, x), strict=True)))
        cy, cz = regular_peak_coefficients(
            trial, kk, mm, n_cycles=n_cycles, steps_per_cycle=steps_per_cycle
        )
        return np.log(np.concatenate([cy.ravel(), cz.ravel()])) - target

    sol = least_squares(residuals, x0, bounds=(lo, hi), x_scale="jac")
    best = dataclasses.replace(model0, **dict(zip(free, map(float, sol.x), strict=True)))
    return compare_with_tables(
        best, k, m, ty, tz, n_cycles=n_cycles, steps_per_cycle=steps_per_cycle
    )


def jonswap_record(
    hs: float,
    tp: float,
    depth: float,
    *,
    duration: float = 10800.0,
    seed: int = 0,
    samples_per_peak_period: int = 40,
    n_components: int = 4096,
    chunk: int = 2048,
) -> dict[str, Any]:
    """A near-bed JONSWAP velocity record and F109's design oscillation for it.

    Long-crested waves normal to the pipe, JONSWAP with the DNV γ rule, linear transfer to the
    seabed, random phases (``seed``) over ``n_components`` bands up to 5 ω_p (the record
    repeats after n_components·T_p/5: keep that above ``duration``), sampled at
    T_p/``samples_per_peak_period``, synthesised in chunks of ``chunk`` samples.

    Returns a dict: ``t`` [s], ``u`` [m/s], ``dudt`` [m/s²] arrays; ``u_star`` = k_U U_s [m/s]
    and ``t_star`` = k_T T_u [s] (DNV-RP-F109 (2017) Eq 3.16, τ = duration/T_u).
    """
    positive("hs", hs)
    positive("tp", tp)
    positive("depth", depth)
    positive("duration", duration)
    integer("samples_per_peak_period", samples_per_peak_period, 8, 10**4)
    integer("n_components", n_components, 8, 10**6)
    integer("chunk", chunk, 1, 10**7)
    gamma = float(jonswap_gamma(hs, tp))
    us, tu = (float(x) for x in significant_bed_velocity(hs, tp, depth, gamma))
    u_star = float(peak_velocity_factor(duration / tu)) * us
    tn = math.sqrt(depth / GRAVITY)
    t_star = float(peak_period_factor(tn / tu, gamma)) * tu
    w, _ = midpoint_grid(tp, n_components, 5.0)
    s_uu = bed_spectrum(w, depth, hs, tp, gamma)
    dt = tp / samples_per_peak_period
    t = np.arange(0.0, duration + 0.5 * dt, dt)
    u = np.empty_like(t)
    dudt = np.empty_like(t)
    for a in range(0, t.size, chunk):
        u[a : a + chunk], dudt[a : a + chunk] = random_phase_series(w, s_uu, t[a : a + chunk], seed)
    return {"t": t, "u": u, "dudt": dudt, "u_star": u_star, "t_star": t_star}


def record_peaks(
    model: WakeModel, record: dict[str, Any], diameter: float, current: float = 0.0
) -> dict[str, float]:
    """Largest per-half-cycle peak loads of a fixed pipe in ``record`` (:func:`jonswap_record`).

    The record is split into half-cycles at the sign changes of U + V. Returns ``k_star``,
    ``m_star`` of the design oscillation; ``cy_max``, ``cz_max`` = the largest per-half-cycle
    max |F_Y| and max F_Z divided by ½ρD(U* + V)² (ρ cancels); ``velocity_ratio`` = max |U + V|
    of the record / (U* + V); ``n_half_cycles``.
    """
    positive("diameter", diameter)
    non_negative("current", current)
    t, u, dudt = record["t"], record["u"], record["dudt"]
    u_star, t_star = record["u_star"], record["t_star"]
    fy = np.empty_like(t)
    fz = np.empty_like(t)
    drive_fixed_pipe(model.parameters(), t, u, dudt, float(current), float(diameter), 1.0, fy, fz)
    q = u + current
    sign = np.sign(q)
    edges = np.flatnonzero(sign[1:] * sign[:-1] < 0.0) + 1
    starts = np.concatenate([[0], edges])
    fy_half = np.maximum.reduceat(np.abs(fy), starts)
    fz_half = np.maximum.reduceat(fz, starts)
    norm = 0.5 * diameter * (u_star + current) ** 2
    return {
        "k_star": u_star * t_star / diameter,
        "m_star": current / u_star,
        "cy_max": float(fy_half.max()) / norm,
        "cz_max": float(fz_half.max()) / norm,
        "velocity_ratio": float(np.abs(q).max()) / (u_star + current),
        "n_half_cycles": float(starts.size),
    }
