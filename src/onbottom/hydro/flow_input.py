"""Near-bed flow given directly: a regular (Airy) wave or a measured velocity time series.

Regular wave
    Linear (Airy) wave theory (DNV-RP-C205 (2010) §3.2.2; Sarpkaya & Isaacson 1981, ch. 4):
    the dispersion relation ω² = g k tanh(k d) is solved for k
    (:func:`onbottom.hydro.kinematics.wave_number`), the near-bed velocity amplitude is
    U_w = π H / (T sinh(k d)) = ω (H/2) / sinh(k d), and normal to a pipe at the angle θ_w
    between the wave direction and the pipe axis

        U(t) = e(t) · U_w sin θ_w · cos(ω t),   U̇ = e U_w sin θ_w (−ω sin ωt) + ė U_w sin θ_w cos ωt

    with e(t) a linear build-up from 0 to 1 over ``build_up_s`` (1 without build-up).
    Deep water (k d >> 1): U_w → 0 as e^{−kd}; shallow water (k d << 1): U_w → (H/2)√(g/d).

    Validity (named :class:`~onbottom.errors.OutOfRangeWarning`, the run goes on): linear
    theory is a first-order theory for H/λ << 1 and H/d << 1. DNV-RP-C205 (2010) §3.2.2
    separates the Stokes (U_R < 30) from the cnoidal (U_R > 30) range by the Ursell number
    U_R = H λ² / d³; at U_R >= 30 the near-bed velocity of a real wave is more peaked and
    asymmetric than the sinusoid used here (Sarpkaya & Isaacson 1981 §4.6). A wave steeper
    than the Miche (1944) breaking limit H/λ = 0.142 tanh(k d) (deep water 1/7, shallow water
    H/d ≈ 0.88) does not exist: :class:`~onbottom.errors.InputError`.

Measured series
    A CSV file with a one-line header ``t [s], U [m/s][, dU/dt [m/s^2]]`` (column names
    ``t``/``time``, ``U``/``velocity``, ``dU/dt``/``acceleration``; the unit in brackets is
    required and must be the SI one), or arrays. Rejected by name (row and column): fewer
    than 3 samples, a non-finite value (NaN, inf, empty cell), a time that does not increase
    (duplicate or going back), a sampling interval that differs from the median interval by
    more than ``sampling_tolerance`` (relative; a gap or an irregular record — resample it
    onto a uniform grid first: the solvers interpolate linearly between uniform samples).
    The time axis is shifted to start at 0 (the first time is kept as ``t0``). Without a
    dU/dt column the acceleration is the second-order central difference of U
    (:func:`numpy.gradient`, second-order one-sided at the ends).
"""

from __future__ import annotations

import csv
import math
import os
import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from onbottom._validate import file_token, finite, non_negative, positive
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro.kinematics import regular_wave_bed_velocity, wave_number

__all__ = [
    "MICHE_BREAKING_STEEPNESS",
    "URSELL_LINEAR_LIMIT",
    "VelocitySeries",
    "linear_wave_validity",
    "read_velocity_series",
    "regular_wave_flow",
    "velocity_series",
]

URSELL_LINEAR_LIMIT = 30.0
"""Ursell number U_R = Hλ²/d³ from which linear (and Stokes) theory is poor (DNV-RP-C205
(2010) §3.2.2: cnoidal theory for U_R > 30)."""

MICHE_BREAKING_STEEPNESS = 0.142
"""Miche (1944) breaking limit H/λ = 0.142 tanh(k d) [-] (DNV-RP-C205 (2010) §3.4, breaking
wave limit)."""

SAMPLING_TOLERANCE = 1e-3
"""Default largest relative deviation of a sampling interval from the median interval [-]."""


def linear_wave_validity(height: float, period: float, depth: float) -> dict[str, float]:
    """Wave length, Ursell number and steepness of a regular wave; warns/raises (module doc).

    Parameters
    ----------
    height : float
        Wave height H [m], > 0.
    period : float
        Wave period T [s], > 0.
    depth : float
        Water depth d [m], > 0.

    Returns
    -------
    dict
        ``wave_length`` λ [m], ``ursell`` U_R = Hλ²/d³ [-], ``steepness`` H/λ [-],
        ``height_over_depth`` H/d [-], ``kd`` [-].
    """
    h = positive("height", height)
    t = positive("period", period)
    d = positive("depth", depth)
    k = float(wave_number(2.0 * math.pi / t, d)[0])
    lam = 2.0 * math.pi / k
    ursell = h * lam**2 / d**3
    limit = MICHE_BREAKING_STEEPNESS * math.tanh(k * d)
    if h / lam > limit:
        raise InputError(
            f"height = {h!r} m is invalid with period = {t!r} s and depth = {d!r} m: the wave"
            f" steepness H/λ = {h / lam:.4g} exceeds the Miche breaking limit"
            f" 0.142·tanh(kd) = {limit:.4g} (λ = {lam:.4g} m; DNV-RP-C205 §3.4), no such"
            f" wave exists: H must be <= {limit * lam:.4g} m"
        )
    if ursell >= URSELL_LINEAR_LIMIT:
        warnings.warn(
            f"regular wave H = {h:g} m, T = {t:g} s in d = {d:g} m: Ursell number"
            f" U_R = Hλ²/d³ = {ursell:.3g} >= {URSELL_LINEAR_LIMIT:g} (λ = {lam:.4g} m),"
            " outside the range of linear (Airy) theory (DNV-RP-C205 §3.2.2: cnoidal range);"
            " the near-bed velocity of the real wave is more peaked than the sinusoid used",
            OutOfRangeWarning,
            stacklevel=3,
        )
    return {
        "wave_length": lam,
        "ursell": ursell,
        "steepness": h / lam,
        "height_over_depth": h / d,
        "kd": k * d,
    }


def regular_wave_flow(
    height: float,
    period: float,
    depth: float,
    *,
    duration: float,
    direction_deg: float = 90.0,
    build_up_s: float = 0.0,
    sample_interval: float | None = None,
) -> tuple[np.ndarray, np.ndarray, float, dict[str, float]]:
    """Near-bed velocity and acceleration normal to a pipe of a regular Airy wave (module doc).

    Parameters
    ----------
    height, period, depth : float
        H [m], T [s], d [m], > 0.
    duration : float
        Length of the record [s], > 0.
    direction_deg : float
        Angle θ_w between the wave direction and the pipe axis [deg]; 90 = normal to the
        pipe. The velocity normal to the pipe is U_w sin θ_w (signed).
    build_up_s : float
        Linear build-up of the amplitude from 0 [s], >= 0 (0 = full amplitude at t = 0).
    sample_interval : float or None
        Δt_s [s], > 0; None → T/50.

    Returns
    -------
    (U [m/s], U̇ [m/s²], Δt_s [s], parameters)
        Samples at t = j·Δt_s, j = 0 … ceil(duration/Δt_s); ``parameters`` holds
        ``amplitude`` U_w sin θ_w [m/s] and :func:`linear_wave_validity`'s values.
    """
    t_per = positive("period", period)
    dur = positive("duration", duration)
    finite("direction_deg", direction_deg)
    ramp = non_negative("build_up_s", build_up_s)
    info = linear_wave_validity(height, period, depth)
    dts = positive("sample_interval", sample_interval) if sample_interval else t_per / 50.0
    amp = regular_wave_bed_velocity(height, period, depth) * math.sin(math.radians(direction_deg))
    n = math.ceil(dur / dts - 1e-9) + 1
    t = np.arange(n) * dts
    w = 2.0 * math.pi / t_per
    if ramp > 0.0:
        e = np.minimum(t / ramp, 1.0)
        de = np.where(t < ramp, 1.0 / ramp, 0.0)
    else:
        e = np.ones(n)
        de = np.zeros(n)
    c = np.cos(w * t)
    u = e * amp * c
    a = -e * amp * w * np.sin(w * t) + de * amp * c
    return u, a, dts, {"amplitude": amp, **info}


@dataclass(frozen=True, eq=False)
class VelocitySeries:
    """A uniformly sampled near-bed velocity record (see :func:`read_velocity_series`).

    Attributes
    ----------
    sample_interval : float
        Δt_s [s].
    velocity, acceleration : numpy.ndarray
        U [m/s], U̇ [m/s²] at t = j·Δt_s.
    t0 : float
        Time of the first sample in the source [s] (the record is shifted to start at 0).
    acceleration_given : bool
        True when U̇ came from the source, False when differentiated here.
    source : str
        File name or "arrays".
    """

    sample_interval: float
    velocity: np.ndarray
    acceleration: np.ndarray
    t0: float
    acceleration_given: bool
    source: str

    @property
    def duration(self) -> float:
        """Length of the record [s]."""
        return (self.velocity.size - 1) * self.sample_interval


def velocity_series(
    time: np.ndarray,
    velocity: np.ndarray,
    acceleration: np.ndarray | None = None,
    *,
    sampling_tolerance: float = SAMPLING_TOLERANCE,
    source: str = "arrays",
    rows: np.ndarray | None = None,
) -> VelocitySeries:
    """Check and build a :class:`VelocitySeries` from arrays (rules in the module docstring).

    Parameters
    ----------
    time : array
        t [s], strictly increasing, uniformly sampled.
    velocity : array
        U [m/s] normal to the pipe.
    acceleration : array or None
        U̇ [m/s²]; None → central differences of U.
    sampling_tolerance : float
        Largest relative deviation of an interval from the median interval [-], > 0.
    source : str
        Name used in error messages.
    rows : array or None
        Row numbers (for messages: file lines); None → sample indices.
    """
    tol = positive("sampling_tolerance", sampling_tolerance)
    cols = {"t": time, "U": velocity}
    if acceleration is not None:
        cols["dU/dt"] = acceleration
    arrs = {}
    for name, v in cols.items():
        a = np.asarray(v, dtype=float)
        if a.ndim != 1:
            raise InputError(f"{source}: column {name} must be one-dimensional (got {a.shape})")
        arrs[name] = a
    n = arrs["t"].size
    where = np.arange(n) if rows is None else np.asarray(rows)
    label = "sample" if rows is None else "line"
    for name, a in arrs.items():
        if a.size != n:
            raise InputError(
                f"{source}: column {name} has {a.size} values, column t has {n}: all columns"
                " must have one value per time"
            )
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            i = int(bad[0])
            raise InputError(
                f"{source}: {name} = {float(a[i])!r} at {label} {int(where[i])} is invalid:"
                " every"
                f" value must be a finite number ({bad.size} bad value(s) in column {name})"
            )
    if n < 3:
        raise InputError(f"{source}: {n} sample(s) is too few: a velocity series needs >= 3")
    t = arrs["t"]
    dt = np.diff(t)
    back = np.flatnonzero(dt <= 0.0)
    if back.size:
        i = int(back[0]) + 1
        kind = "duplicates" if dt[i - 1] == 0.0 else "goes back from"
        raise InputError(
            f"{source}: t = {float(t[i])!r} s at {label} {int(where[i])} {kind} the previous"
            " time"
            f" {float(t[i - 1])!r} s: time must increase strictly"
        )
    step = float(np.median(dt))
    dev = np.abs(dt - step) / step
    off = np.flatnonzero(dev > tol)
    if off.size:
        i = int(off[0]) + 1
        raise InputError(
            f"{source}: the interval t = {float(t[i - 1])!r} → {float(t[i])!r} s"
            f" ({label} {int(where[i])}) is"
            f" {dt[i - 1]:.6g} s against the median {step:.6g} s: a gap or non-uniform sampling"
            f" ({off.size} interval(s) off by more than sampling_tolerance = {tol:g});"
            " resample the record onto a uniform time grid"
        )
    u = arrs["U"]
    given = "dU/dt" in arrs
    a = arrs["dU/dt"] if given else np.gradient(u, step, edge_order=2)
    return VelocitySeries(
        sample_interval=step,
        velocity=np.ascontiguousarray(u),
        acceleration=np.ascontiguousarray(a),
        t0=float(t[0]),
        acceleration_given=given,
        source=source,
    )


_NAMES = {
    "t": ("t", "time"),
    "U": ("u", "velocity"),
    "dU/dt": ("du/dt", "dudt", "acceleration"),
}
_KNOWN = ("t [s]", "U [m/s]", "dU/dt [m/s^2]", "t", "U", "dU/dt", "time", "velocity")
_UNITS = {
    "t": ("s",),
    "U": ("m/s",),
    "dU/dt": ("m/s^2", "m/s2", "m/s²", "m s^-2", "m/s/s"),
}
_HEADER = re.compile(r"^\s*([^\[\]]+?)\s*(?:\[\s*([^\]]*?)\s*\])?\s*$")


def read_velocity_series(
    path: str | os.PathLike, *, sampling_tolerance: float = SAMPLING_TOLERANCE
) -> VelocitySeries:
    """Read a measured near-bed velocity record from CSV (format and checks: module doc).

    Parameters
    ----------
    path : path
        CSV file, comma separated, one header line ``t [s], U [m/s][, dU/dt [m/s^2]]``;
        lines starting with ``#`` are comments.
    sampling_tolerance : float
        Largest relative deviation of a sampling interval from the median [-], > 0.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"velocity series {p}: cannot be read ({exc})") from None
    lines = [(i + 1, ln) for i, ln in enumerate(text.splitlines()) if ln.strip() and ln[0] != "#"]
    if not lines:
        raise InputError(f"{p}: empty file: expected a header 't [s], U [m/s][, dU/dt [m/s^2]]'")
    head_no, head = lines[0]
    header = next(csv.reader([head]))
    order: list[str] = []
    for col, cell in enumerate(header):
        m = _HEADER.match(cell)
        name = m.group(1).strip().lower() if m else cell.strip().lower()
        unit = (m.group(2) or "").strip() if m else ""
        key = next((k for k, alias in _NAMES.items() if name in alias), None)
        if key is None:
            raise InputError(
                f"{p}, line {head_no}: column {col + 1} {file_token(cell, _KNOWN)} is unknown:"
                " expected"
                " 't [s]', 'U [m/s]' and optionally 'dU/dt [m/s^2]'"
            )
        if key in order:
            raise InputError(f"{p}, line {head_no}: column {key} appears twice")
        if not unit:
            raise InputError(
                f"{p}, line {head_no}: column {file_token(cell, _KNOWN)} has no unit: write it"
                " in brackets,"
                f" e.g. '{key} [{_UNITS[key][0]}]'"
            )
        if unit not in _UNITS[key]:
            raise InputError(
                f"{p}, line {head_no}: column {key} unit [{unit}] is invalid: must be"
                f" [{_UNITS[key][0]}] (SI; convert the record first)"
            )
        order.append(key)
    for need in ("t", "U"):
        if need not in order:
            raise InputError(f"{p}, line {head_no}: column {need} is missing from the header")
    data: dict[str, list[float]] = {k: [] for k in order}
    rows = []
    for line_no, ln in lines[1:]:
        cells = next(csv.reader([ln]))
        if len(cells) != len(order):
            raise InputError(
                f"{p}, line {line_no}: {len(cells)} value(s), the header has {len(order)} columns"
            )
        for key, cell in zip(order, cells, strict=True):
            try:
                data[key].append(float(cell) if cell.strip() else math.nan)
            except ValueError:
                raise InputError(
                    f"{p}, line {line_no}: {key} = {file_token(cell)} is invalid: not a number"
                ) from None
        rows.append(line_no)
    return velocity_series(
        np.array(data["t"]),
        np.array(data["U"]),
        np.array(data["dU/dt"]) if "dU/dt" in data else None,
        sampling_tolerance=sampling_tolerance,
        source=str(p),
        rows=np.array(rows, dtype=int),
    )
