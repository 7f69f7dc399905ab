"""Load programmes for load-controlled pipe-section simulations.

A :class:`LoadProgramme` is an immutable, piecewise-linear history of the horizontal load
H(t) and the vertical contact load V(t) = V_i − F_V(t) per unit length, with the metadata the
solver and the reports need (installation load V_peak, cycle period, number of cycles).

Builders follow the loading protocols of the Youssef (2012) centrifuge tests as described by
Youssef & Cassidy (2014), ISOPE, pp. 141–148:

* :func:`inclined_cyclic` — cyclic H of growing amplitude with V on an inclined load path,
  F_V = |H|/tan α (α to the V axis; docs/conventions.md).
* :func:`regular_wave_current_groups` — groups of identical regular wave-plus-current load
  sub-cycles, each later group scaled up by a fixed increment of the first group's loads.
* :func:`irregular_wave_current_groups` — the same with a seeded irregular (JONSWAP) sea.
* :func:`from_arrays` — a user's own programme (from a case file's ``[programme]`` table, a
  TOML file or a CSV: :func:`onbottom.cases.programme.programme_from_toml`).

The wave-plus-current shapes come from the Morison model of :mod:`onbottom.hydro` and are then
scaled to the paper's first-cycle peaks (the paper's own histories came from UWAHYDRO, which is
not available); see docs/validation/youssef_cassidy_2014.md.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from onbottom._validate import in_range, non_negative, one_of, positive
from onbottom.errors import InputError
from onbottom.hydro.flow_synthesis import near_bed_velocity_series, regular_velocity_series
from onbottom.hydro.forces import MorisonCoefficients, horizontal_force, lift_force

_DEFAULT_COEFFICIENTS = MorisonCoefficients()

MAX_SAMPLES = 10_000_000
"""Largest number of samples a built programme may hold [-] (80 MB per load array; the
section solver steps at least once per sample)."""


def _check_samples(field: str, value: Any, samples: int) -> None:
    """A named error, before anything is allocated, for a programme over :data:`MAX_SAMPLES`."""
    if samples > MAX_SAMPLES:
        raise InputError(
            f"{field} = {value!r} is invalid: the programme would hold {samples:,} samples,"
            f" more than the {MAX_SAMPLES:,} allowed"
        )


__all__ = [
    "MAX_SAMPLES",
    "LoadProgramme",
    "from_arrays",
    "inclined_cyclic",
    "irregular_wave_current_groups",
    "regular_wave_current_groups",
]


def _frozen(a: Any, name: str) -> np.ndarray:
    arr = np.array(a, dtype=float, copy=True).ravel()
    if not np.all(np.isfinite(arr)):
        raise InputError(f"LoadProgramme.{name} is invalid: contains non-finite values")
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, kw_only=True, eq=False)
class LoadProgramme:
    """A load history H(t), V(t) per unit length, linear between samples.

    Parameters
    ----------
    time : array
        Sample times t [s], strictly increasing, t[0] >= 0, at least 2 samples.
    horizontal_load : array
        H(t) [N/m], positive in +u.
    vertical_load : array
        V(t) = V_i − F_V(t) [N/m], positive in compression (V <= 0 is lift-off).
    installation_load : float or None
        Largest vertical load V_peak carried on virgin soil before the programme [N/m]
        (the soil model's installation load); None = the largest V of the programme.
    cycle_period : float or None
        Duration of one load cycle (or group) [s]; None for non-cyclic programmes.
    n_cycles : int or None
        Number of cycles (groups) in the programme.
    name : str
        Label.
    metadata : mapping
        Builder arguments and notes, stored in result provenance.
    """

    time: np.ndarray
    horizontal_load: np.ndarray
    vertical_load: np.ndarray
    installation_load: float | None = None
    cycle_period: float | None = None
    n_cycles: int | None = None
    name: str = "custom"
    metadata: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        t = _frozen(self.time, "time")
        h = _frozen(self.horizontal_load, "horizontal_load")
        v = _frozen(self.vertical_load, "vertical_load")
        if t.size < 2:
            raise InputError(f"LoadProgramme.time has {t.size} samples: at least 2 are needed")
        if h.size != t.size or v.size != t.size:
            raise InputError(
                "LoadProgramme arrays differ in length: "
                f"time {t.size}, horizontal_load {h.size}, vertical_load {v.size}"
            )
        if t[0] < 0.0 or np.any(np.diff(t) <= 0.0):
            raise InputError("LoadProgramme.time is invalid: must start >= 0 and increase strictly")
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "horizontal_load", h)
        object.__setattr__(self, "vertical_load", v)
        if self.installation_load is not None:
            positive("LoadProgramme.installation_load", self.installation_load)
        if self.cycle_period is not None:
            positive("LoadProgramme.cycle_period", self.cycle_period)
        object.__setattr__(self, "metadata", dict(self.metadata))

    @property
    def duration(self) -> float:
        """End time of the programme [s]."""
        return float(self.time[-1])

    @property
    def peak_vertical_load(self) -> float:
        """Installation load V_peak if given, else max V of the programme [N/m]."""
        if self.installation_load is not None:
            return float(self.installation_load)
        return float(np.max(self.vertical_load))

    @property
    def sample_interval(self) -> float:
        """Median spacing of the samples [s] (the solver's default largest time step)."""
        return float(np.median(np.diff(self.time)))

    def loads_at(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """H and V [N/m] at times ``t`` (linear interpolation, held constant past the end)."""
        return (
            np.interp(t, self.time, self.horizontal_load),
            np.interp(t, self.time, self.vertical_load),
        )

    def cycles_at(self, t: float) -> float | None:
        """Elapsed load cycles at time ``t`` [-] (None for non-cyclic programmes)."""
        if self.cycle_period is None:
            return None
        return float((t - self.time[0]) / self.cycle_period)


# ---------------------------------------------------------------------------------------------
# builders
# ---------------------------------------------------------------------------------------------
def _unit_cycle(shape: str, points_per_cycle: int) -> tuple[np.ndarray, np.ndarray]:
    """Phase τ in [0, 1) and unit-amplitude H shape of one cycle: +peak at τ = ¼, −peak at ¾."""
    tau = np.arange(points_per_cycle) / points_per_cycle
    if shape == "sine":
        return tau, np.sin(2.0 * math.pi * tau)
    # triangle through 0 → +1 → 0 → −1 → 0
    return tau, np.interp(tau, [0.0, 0.25, 0.5, 0.75, 1.0], [0.0, 1.0, 0.0, -1.0, 0.0])


def inclined_cyclic(
    vertical_load: float,
    amplitude_step: float,
    period: float,
    alpha_deg: float,
    n_cycles: int,
    *,
    shape: str = "sine",
    points_per_cycle: int = 200,
    installation_load: float | None = None,
    name: str = "inclined",
) -> LoadProgramme:
    """Cyclic horizontal load of growing amplitude on an inclined V–H load path.

    Cycle n (n = 1, 2, ...) swings H to +n·ΔH and to −n·ΔH (+peak at ¼ of the cycle, −peak at
    ¾); the vertical load follows V = V_i − |H|/tan α (Youssef & Cassidy 2014, Figs 5–6:
    ΔH = 0.25 kN/m per cycle, 40 s per cycle, α = 30° for tests 1–3).

    Parameters
    ----------
    vertical_load : float
        V_i, the vertical load at H = 0 [N/m], > 0.
    amplitude_step : float
        ΔH, amplitude increase per cycle [N/m], > 0.
    period : float
        Cycle duration [s], > 0.
    alpha_deg : float
        Inclination α of the load path to the V axis [deg], in (0, 90]; 90 = constant V.
    n_cycles : int
        Number of cycles, >= 1.
    shape : {"sine", "triangle"}
        Shape of H within a cycle.
    points_per_cycle : int
        Samples per cycle (>= 8); also the solver's default largest step (period/points).
    installation_load : float or None
        V_peak [N/m] applied before the programme (see :class:`LoadProgramme`).
    name : str
        Label.
    """
    vi = positive("vertical_load", vertical_load)
    dh = positive("amplitude_step", amplitude_step)
    T = positive("period", period)
    alpha = in_range("alpha_deg", alpha_deg, 0.0, 90.0, low_inclusive=False)
    one_of("shape", shape, ("sine", "triangle"))
    if int(n_cycles) < 1 or int(points_per_cycle) < 8:
        raise InputError(
            f"n_cycles = {n_cycles!r}, points_per_cycle = {points_per_cycle!r} are invalid:"
            " need n_cycles >= 1 and points_per_cycle >= 8"
        )
    n = int(n_cycles)
    _check_samples("n_cycles", n_cycles, n * int(points_per_cycle))
    tau, unit = _unit_cycle(shape, int(points_per_cycle))
    k = np.repeat(np.arange(1, n + 1), tau.size)
    t = (np.tile(tau, n) + k - 1) * T
    h = np.tile(unit, n) * k * dh
    t = np.append(t, n * T)
    h = np.append(h, 0.0)
    inv_tan = 0.0 if alpha == 90.0 else 1.0 / math.tan(math.radians(alpha))
    v = vi - np.abs(h) * inv_tan
    return LoadProgramme(
        time=t,
        horizontal_load=h,
        vertical_load=v,
        installation_load=installation_load,
        cycle_period=T,
        n_cycles=n,
        name=name,
        metadata={
            "builder": "inclined_cyclic",
            "vertical_load": vi,
            "amplitude_step": dh,
            "period": T,
            "alpha_deg": alpha,
            "shape": shape,
            "points_per_cycle": int(points_per_cycle),
        },
    )


def _taper(n: int, fraction: float) -> np.ndarray:
    """Cosine taper rising over the first and falling over the last ``fraction`` of n samples."""
    w = np.ones(n)
    m = round(fraction * n)
    if m > 0:
        ramp = 0.5 * (1.0 - np.cos(math.pi * np.arange(m) / m))
        w[:m] = ramp
        w[n - m :] = ramp[::-1]
    return w


def _scaled_group(
    fh: np.ndarray,
    fv: np.ndarray,
    h_peak: float,
    v_peak: float,
) -> tuple[np.ndarray, np.ndarray]:
    sh = h_peak / float(np.max(fh))
    sv = v_peak / float(np.max(fv)) if np.max(fv) > 0.0 else 0.0
    return fh * sh, fv * sv


def _current_for_ratio(shape_fn, target: float) -> float:
    """Current ratio M in [0, 3] giving min(F_H)/max(F_H) = target (bisection)."""
    from scipy.optimize import brentq

    def g(m: float) -> float:
        fh, _ = shape_fn(m)
        return float(np.min(fh) / np.max(fh)) - target

    lo, hi = 0.0, 3.0
    if g(lo) * g(hi) > 0.0:
        # the target ratio is not reachable: use the closer end
        return lo if abs(g(lo)) < abs(g(hi)) else hi
    return float(brentq(g, lo, hi, xtol=1e-10))


def _groups(
    fh1: np.ndarray,
    fv1: np.ndarray,
    tau: np.ndarray,
    vertical_load: float,
    group_period: float,
    n_groups: int,
    increment: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n = int(n_groups)
    fac = 1.0 + increment * np.arange(n)  # group k (0-based) = (1 + increment·k) × first group
    t = (np.tile(tau, n) + np.repeat(np.arange(n), tau.size)) * group_period
    h = np.concatenate([f * fh1 for f in fac])
    fv = np.concatenate([f * fv1 for f in fac])
    t = np.append(t, n * group_period)
    h = np.append(h, 0.0)
    fv = np.append(fv, 0.0)
    return t, h, vertical_load - fv


def regular_wave_current_groups(
    vertical_load: float,
    n_groups: int,
    *,
    group_period: float = 60.0,
    sub_cycles: int = 6,
    h_peak: float = 0.3e3,
    h_trough: float = -0.2e3,
    v_peak: float = 0.3e3,
    increment: float = 1.0,
    coefficients: MorisonCoefficients = _DEFAULT_COEFFICIENTS,
    taper_fraction: float = 0.05,
    points_per_sub_cycle: int = 100,
    installation_load: float | None = None,
    name: str = "regular",
) -> LoadProgramme:
    """Groups of regular wave-plus-current load sub-cycles (Youssef & Cassidy 2014, Fig. 7).

    The first group's shape is the Morison load of U(t) = U_w sin(ωt) plus a current V = M·U_w
    (:mod:`onbottom.hydro.forces`), with M solved so that min F_H / max F_H = h_trough/h_peak
    (the current bias of the paper's figure); F_H is then scaled to max ``h_peak`` and the lift
    F_V to max ``v_peak``. A cosine taper over ``taper_fraction`` of the group at each end
    starts and ends every group at zero load. Group k (1-based) carries
    (1 + increment·(k − 1)) × the first group's loads (increment = 1: k × first).

    Parameters
    ----------
    vertical_load : float
        V_i [N/m], > 0.
    n_groups : int
        Number of groups (the paper's "cycles"), >= 1.
    group_period : float
        Duration of one group [s], > 0 (paper: 60 s).
    sub_cycles : int
        Identical wave cycles per group, >= 1 (paper: 6).
    h_peak, h_trough : float
        First-group extreme horizontal loads [N/m] (paper figure: about +0.3 and −0.2 kN/m).
    v_peak : float
        First-group largest lift F_V [N/m] (paper figure: about 0.3 kN/m), >= 0.
    increment : float
        Load increase per group as a fraction of the first group's loads [-], >= 0.
    coefficients : MorisonCoefficients
        C_D, C_M, C_L of the shape model.
    taper_fraction : float
        Fraction of the group tapered at each end [-], in [0, 0.25].
    points_per_sub_cycle : int
        Samples per sub-cycle, >= 16.
    installation_load : float or None
        V_peak [N/m].
    name : str
        Label.
    """
    vi = positive("vertical_load", vertical_load)
    tg = positive("group_period", group_period)
    hp = positive("h_peak", h_peak)
    in_range("h_trough", h_trough, -hp, 0.0)
    non_negative("v_peak", v_peak)
    non_negative("increment", increment)
    in_range("taper_fraction", taper_fraction, 0.0, 0.25)
    if int(sub_cycles) < 1 or int(n_groups) < 1 or int(points_per_sub_cycle) < 16:
        raise InputError(
            f"sub_cycles = {sub_cycles!r}, n_groups = {n_groups!r}, points_per_sub_cycle ="
            f" {points_per_sub_cycle!r} are invalid: need >= 1, >= 1 and >= 16"
        )
    npts = int(sub_cycles) * int(points_per_sub_cycle)
    _check_samples("n_groups", n_groups, int(n_groups) * npts)
    tau = np.arange(npts) / npts
    # shape in a reference flow: D = 1 m, U_w = 1 m/s, wave period = 10 s (only the shape and
    # the drag/inertia ratio matter after scaling)
    t_ref = tau * 10.0 * int(sub_cycles)
    uw, dudt = regular_velocity_series(t_ref, 1.0, 10.0)
    window = _taper(npts, taper_fraction)

    def shape(m: float) -> tuple[np.ndarray, np.ndarray]:
        fh = horizontal_force(uw, dudt, m, 1.0, coefficients) * window
        fv = lift_force(uw, m, 1.0, coefficients) * window
        return fh, fv

    return _wave_current_programme(
        shape,
        tau,
        vertical_load=vi,
        group_period=tg,
        n_groups=int(n_groups),
        h_peak=hp,
        h_trough=float(h_trough),
        v_peak=float(v_peak),
        increment=float(increment),
        coefficients=coefficients,
        taper_fraction=float(taper_fraction),
        installation_load=installation_load,
        name=name,
        metadata={"builder": "regular_wave_current_groups", "sub_cycles": int(sub_cycles)},
    )


def irregular_wave_current_groups(
    vertical_load: float,
    n_groups: int,
    *,
    group_period: float = 50.0,
    hs: float = 6.0,
    tp: float = 12.0,
    depth: float = 60.0,
    waves_per_group: float = 5.0,
    seed: int = 2012,
    h_peak: float = 3.0e3,
    h_trough: float = -2.0e3,
    v_peak: float = 3.0e3,
    increment: float = 0.1,
    coefficients: MorisonCoefficients = _DEFAULT_COEFFICIENTS,
    taper_fraction: float = 0.05,
    points_per_group: int = 1000,
    installation_load: float | None = None,
    name: str = "irregular",
) -> LoadProgramme:
    """Groups of irregular wave-plus-current loads (Youssef & Cassidy 2014, Fig. 8).

    The first group's shape: near-bed velocity of a JONSWAP sea (H_s, T_p, depth; seeded
    random phases, :func:`onbottom.hydro.flow_synthesis.near_bed_velocity_series`) over a record of
    ``waves_per_group``·T_p, plus a current M·U_s with M solved so that
    min F_H / max F_H = h_trough/h_peak; Morison F_H and lift F_V are scaled to ``h_peak`` and
    ``v_peak``, tapered at the group ends, and the record is mapped linearly onto
    ``group_period``. Group k carries (1 + increment·(k − 1)) × the first group's loads
    (paper: +10% of the first cycle per cycle, 50 s per cycle).

    Parameters
    ----------
    vertical_load : float
        V_i [N/m], > 0.
    n_groups : int
        Number of groups, >= 1.
    group_period : float
        Duration of one group on the programme's time axis [s], > 0.
    hs, tp, depth : float
        Sea state of the shape model: H_s [m], T_p [s], water depth [m], all > 0.
    waves_per_group : float
        Record length of the shape model in peak periods [-], > 0.
    seed : int
        Random-phase seed (same seed, same programme).
    h_peak, h_trough, v_peak : float
        First-group extremes [N/m] (paper figure: about +3, −2 and 3 kN/m).
    increment : float
        Load increase per group as a fraction of the first group's loads [-], >= 0.
    coefficients : MorisonCoefficients
        C_D, C_M, C_L of the shape model.
    taper_fraction : float
        Fraction of the group tapered at each end [-], in [0, 0.25].
    points_per_group : int
        Samples per group, >= 64.
    installation_load : float or None
        V_peak [N/m].
    name : str
        Label.
    """
    vi = positive("vertical_load", vertical_load)
    tg = positive("group_period", group_period)
    positive("hs", hs)
    positive("tp", tp)
    positive("depth", depth)
    positive("waves_per_group", waves_per_group)
    hp = positive("h_peak", h_peak)
    in_range("h_trough", h_trough, -hp, 0.0)
    non_negative("v_peak", v_peak)
    non_negative("increment", increment)
    in_range("taper_fraction", taper_fraction, 0.0, 0.25)
    if int(n_groups) < 1 or int(points_per_group) < 64:
        raise InputError(
            f"n_groups = {n_groups!r}, points_per_group = {points_per_group!r} are invalid:"
            " need >= 1 and >= 64"
        )
    npts = int(points_per_group)
    _check_samples("n_groups", n_groups, int(n_groups) * npts)
    tau = np.arange(npts) / npts
    t_rec = tau * waves_per_group * tp
    u, dudt = near_bed_velocity_series(t_rec, hs, tp, depth, seed=seed)
    us = 2.0 * float(np.std(u))
    window = _taper(npts, taper_fraction)

    def shape(m: float) -> tuple[np.ndarray, np.ndarray]:
        fh = horizontal_force(u, dudt, m * us, 1.0, coefficients) * window
        fv = lift_force(u, m * us, 1.0, coefficients) * window
        return fh, fv

    return _wave_current_programme(
        shape,
        tau,
        vertical_load=vi,
        group_period=tg,
        n_groups=int(n_groups),
        h_peak=hp,
        h_trough=float(h_trough),
        v_peak=float(v_peak),
        increment=float(increment),
        coefficients=coefficients,
        taper_fraction=float(taper_fraction),
        installation_load=installation_load,
        name=name,
        metadata={
            "builder": "irregular_wave_current_groups",
            "hs": float(hs),
            "tp": float(tp),
            "depth": float(depth),
            "waves_per_group": float(waves_per_group),
            "seed": int(seed),
        },
    )


def _wave_current_programme(
    shape: Any,
    tau: np.ndarray,
    *,
    vertical_load: float,
    group_period: float,
    n_groups: int,
    h_peak: float,
    h_trough: float,
    v_peak: float,
    increment: float,
    coefficients: MorisonCoefficients,
    taper_fraction: float,
    installation_load: float | None,
    name: str,
    metadata: dict[str, Any],
) -> LoadProgramme:
    """Shared tail of the wave-plus-current builders: current ratio, scaling, groups.

    ``shape(m)`` returns the first group's (F_H, F_V) for current ratio m; m is solved so that
    min F_H / max F_H = h_trough/h_peak, the loads are scaled to the peaks and repeated in
    growing groups.
    """
    m = _current_for_ratio(shape, h_trough / h_peak)
    fh1, fv1 = _scaled_group(*shape(m), h_peak, v_peak)
    t, h, v = _groups(fh1, fv1, tau, vertical_load, group_period, n_groups, increment)
    return LoadProgramme(
        time=t,
        horizontal_load=h,
        vertical_load=v,
        installation_load=installation_load,
        cycle_period=group_period,
        n_cycles=n_groups,
        name=name,
        metadata={
            **metadata,
            "vertical_load": vertical_load,
            "group_period": group_period,
            "h_peak": h_peak,
            "h_trough": h_trough,
            "v_peak": v_peak,
            "increment": increment,
            "current_ratio": m,
            "coefficients": [coefficients.drag, coefficients.inertia, coefficients.lift],
            "taper_fraction": taper_fraction,
        },
    )


def from_arrays(
    time: Any,
    horizontal_load: Any,
    vertical_load: Any,
    *,
    installation_load: float | None = None,
    cycle_period: float | None = None,
    name: str = "custom",
) -> LoadProgramme:
    """A programme from sample arrays (t [s], H [N/m], V [N/m]); see :class:`LoadProgramme`."""
    t = np.asarray(time, dtype=float)
    n_cycles = None
    if cycle_period is not None:
        n_cycles = math.ceil((t[-1] - t[0]) / positive("cycle_period", cycle_period) - 1e-9)
    return LoadProgramme(
        time=t,
        horizontal_load=horizontal_load,
        vertical_load=vertical_load,
        installation_load=installation_load,
        cycle_period=cycle_period,
        n_cycles=n_cycles,
        name=name,
        metadata={"builder": "from_arrays"},
    )
