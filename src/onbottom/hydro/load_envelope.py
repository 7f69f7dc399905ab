"""V–H load envelope of a sea state: peak hydrodynamic loads of every wave cycle.

The seed paper (Youssef & Cassidy 2014, Fig. 4) plots the peak hydrodynamic loads of 1- to
1000-year sea states in V–H space and finds that most lie between lines at about 20° and 45°
from the V axis — the reason for the load angles of its inclined-load centrifuge tests. This
module makes that plot's data for any sea state:

1. U(t), dU/dt: seeded random-phase synthesis of the JONSWAP bed-velocity spectrum
   (:func:`onbottom.hydro.flow_synthesis.bed_velocity_record`: the record of
   :func:`~onbottom.hydro.flow_synthesis.near_bed_velocity_series` — same frequencies,
   amplitudes and phases — evaluated by one inverse FFT), long-crested, scaled by the
   spreading factor R_D (:mod:`onbottom.hydro.spreading`), over ``duration`` (3 h).
2. Loads on a fixed pipe (Morison, :func:`onbottom.hydro.forces.horizontal_force` and
   :func:`~onbottom.hydro.forces.lift_force`, times the reductions r_y, r_z):
   F_Y = r_y[½ρ D C_D (U+V)|U+V| + ρ πD²/4 C_M dU/dt],  F_Z = r_z ½ρ D C_L (U+V)².
3. Wave cycles between zero up-crossings of U(t); in each, the instant of the largest |F_Y|
   (our choice: the seed paper says "peak loading points" without defining them; the load
   pair at the instant of peak horizontal load is what a pipe feels at once). That instant
   gives H = |F_Y| and V = w_s − F_Z.
4. The load angle from the V axis, β = atan2(H, V) (90° and more when the pipe is lifted off,
   V <= 0), and the fraction of cycles with 20° <= β <= 45°.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onbottom._validate import in_range, non_negative, positive
from onbottom.constants import RHO_SEAWATER
from onbottom.errors import InputError
from onbottom.hydro.design_sea_state import DEFAULT_DURATION, jonswap_gamma
from onbottom.hydro.flow_synthesis import bed_velocity_record
from onbottom.hydro.forces import MorisonCoefficients, horizontal_force, lift_force
from onbottom.hydro.spreading import spreading_factor

__all__ = ["LoadEnvelope", "cycle_peak_loads", "load_envelope"]


@dataclass(frozen=True, slots=True)
class LoadEnvelope:
    """Peak loads of every wave cycle of one simulated record (SI, per unit length).

    Attributes: ``time`` of each peak [s]; ``horizontal`` H = |F_Y| [N/m]; ``lift`` F_Z [N/m];
    ``vertical`` V = w_s − F_Z [N/m]; ``angle_deg`` β = atan2(H, V) [deg];
    ``submerged_weight`` w_s [N/m]; ``duration`` [s]; ``seed``; ``hs`` [m]; ``tp`` [s].
    """

    time: NDArray
    horizontal: NDArray
    lift: NDArray
    vertical: NDArray
    angle_deg: NDArray
    submerged_weight: float
    duration: float
    seed: int | None
    hs: float
    tp: float

    @property
    def n_cycles(self) -> int:
        """Number of wave cycles (zero up-crossing to zero up-crossing) [-]."""
        return int(self.time.size)

    def fraction_between(self, low_deg: float = 20.0, high_deg: float = 45.0) -> float:
        """Fraction of cycles whose angle β lies in [low_deg, high_deg] [-] (NaN if none)."""
        if self.time.size == 0:
            return math.nan
        a = self.angle_deg
        return float(np.mean((a >= low_deg) & (a <= high_deg)))


def cycle_peak_loads(
    time: NDArray, u: NDArray, f_y: NDArray, f_z: NDArray
) -> tuple[NDArray, NDArray, NDArray]:
    """For each cycle between zero up-crossings of ``u``: (time, |F_Y|, F_Z) at max |F_Y|.

    Only complete cycles count (the part before the first and after the last up-crossing is
    dropped).
    """
    u = np.asarray(u, dtype=float)
    up = np.flatnonzero((u[:-1] < 0.0) & (u[1:] >= 0.0)) + 1
    if up.size < 2:
        return np.empty(0), np.empty(0), np.empty(0)
    a = np.abs(np.asarray(f_y, dtype=float))
    idx = np.array([s + int(np.argmax(a[s:e])) for s, e in itertools.pairwise(up)])
    return np.asarray(time)[idx], a[idx], np.asarray(f_z, dtype=float)[idx]


def load_envelope(
    *,
    hs: float,
    tp: float,
    depth: float,
    diameter: float,
    submerged_weight: float,
    current: float = 0.0,
    gamma: float | None = None,
    spectrum: str = "jonswap",
    wave_direction_deg: float = 90.0,
    spreading_s: float | None = None,
    coefficients: MorisonCoefficients | None = None,
    r_y: float = 1.0,
    r_z: float = 1.0,
    density: float = RHO_SEAWATER,
    duration: float = DEFAULT_DURATION,
    samples_per_peak_period: int = 40,
    n_components: int | None = None,
    seed: int | None = 0,
) -> LoadEnvelope:
    """Peak loads per wave cycle of a ``duration``-long record of one sea state.

    Parameters
    ----------
    hs, tp : float
        H_s [m], T_p [s], > 0.
    depth : float
        Water depth [m], > 0.
    diameter : float
        Pipe outer diameter D [m], > 0.
    submerged_weight : float
        w_s [N/m], > 0.
    current : float
        Mean current normal to the pipe over D, V [m/s] (F109 Eq 3.3), >= 0.
    gamma : float or None
        JONSWAP γ [-]; None → DNV rule; ignored for Pierson–Moskowitz.
    spectrum : str
        ``"jonswap"`` or ``"pierson-moskowitz"``.
    wave_direction_deg : float
        Waves to the pipe axis [deg]; with ``spreading_s``, scales U by R_D.
    spreading_s : float or None
        cos^s exponent [-]; None/0 → long-crested.
    coefficients : MorisonCoefficients or None
        C_D, C_M, C_L; None → ``MorisonCoefficients(drag=0.7, inertia=3.29, lift=0.9)``.
    r_y, r_z : float
        Load reductions r_tot,y and r_tot,z [-] in [0, 1] (F109 Eqs 3.17–3.22).
    density : float
        ρ_w [kg/m³].
    duration : float
        Record length [s] (F109 design sea state: 3 h).
    samples_per_peak_period : int
        Time steps per T_p (>= 16).
    n_components : int or None
        Frequency components of the synthesis (>= 64). The record repeats after 2π/Δω =
        n T_p/5 (Δω = 5 ω_p/n), which must be at least ``duration``; None → the smallest such
        n (5 · duration/T_p, about 5000 for 3 h at T_p = 10.8 s).
    seed : int or None
        Random-phase seed.
    """
    positive("hs", hs)
    tp = positive("tp", tp)
    positive("depth", depth)
    d = positive("diameter", diameter)
    ws = positive("submerged_weight", submerged_weight)
    non_negative("current", current)
    in_range("r_y", r_y, 0.0, 1.0)
    in_range("r_z", r_z, 0.0, 1.0)
    dur = in_range("duration", duration, 10.0 * tp, 1.0e6)
    if samples_per_peak_period < 16:
        raise InputError(
            f"samples_per_peak_period = {samples_per_peak_period!r} is invalid: must be >= 16"
        )
    if n_components is None:
        n_components = max(64, math.ceil(5.0 * dur / tp))
    if n_components < 64:
        raise InputError(f"n_components = {n_components!r} is invalid: must be >= 64")
    repeat = n_components * tp / 5.0
    if repeat < dur:
        raise InputError(
            f"n_components = {n_components} is invalid: the record would repeat after"
            f" {repeat:.0f} s < duration {dur:.0f} s; use at least"
            f" {math.ceil(n_components * dur / repeat)}"
        )
    coef = coefficients if coefficients is not None else MorisonCoefficients(drag=0.7)
    g = 1.0 if spectrum == "pierson-moskowitz" else (
        float(jonswap_gamma(hs, tp)) if gamma is None else gamma
    )  # fmt: skip
    rd = float(spreading_factor(spreading_s, wave_direction_deg=wave_direction_deg))
    t, u, dudt = bed_velocity_record(
        hs, tp, depth, g, seed, n_components, dur, samples_per_peak_period
    )
    u *= rd
    dudt *= rd
    f_y = r_y * horizontal_force(u, dudt, current, d, coef, density)
    f_z = r_z * lift_force(u, current, d, coef, density)
    tc, h, fz = cycle_peak_loads(t, u, f_y, f_z)
    v = ws - fz
    ang = np.degrees(np.arctan2(h, v))
    return LoadEnvelope(tc, h, fz, v, ang, ws, dur, seed, float(hs), tp)


def envelopes_dataset(envelopes: list[LoadEnvelope], names: list[str], **attrs: object):
    """xarray Dataset of cycle peaks: dims (combination, cycle), NaN-padded; units from
    :data:`onbottom.results.VARIABLES`, provenance attributes (seed, duration, ``attrs``)."""
    import xarray as xr

    from onbottom.results import annotate, provenance

    if len(envelopes) != len(names) or not envelopes:
        raise InputError("envelopes and names must be non-empty and of equal length")
    n = max(e.n_cycles for e in envelopes)

    def pad(get) -> NDArray:
        out = np.full((len(envelopes), n), np.nan)
        for i, e in enumerate(envelopes):
            out[i, : e.n_cycles] = get(e)
        return out

    dims = ("combination", "cycle")
    ds = xr.Dataset(
        {
            "peak_time": (dims, pad(lambda e: e.time)),
            "H_peak": (dims, pad(lambda e: e.horizontal)),
            "F_Z_peak": (dims, pad(lambda e: e.lift)),
            "V_peak": (dims, pad(lambda e: e.vertical)),
            "load_angle": (dims, pad(lambda e: e.angle_deg)),
            "fraction_20_45": (("combination",), [e.fraction_between() for e in envelopes]),
            "w_s": (("combination",), [e.submerged_weight for e in envelopes]),
        },
        coords={"combination": list(names), "cycle": np.arange(n)},
    )
    ds.attrs.update(
        provenance(
            "F109 V-H load envelope (Morison + lift, peak |F_Y| per wave cycle)",
            seed=envelopes[0].seed if envelopes[0].seed is not None else "none",
            duration=envelopes[0].duration,
            **attrs,
        )
    )
    return annotate(ds)
