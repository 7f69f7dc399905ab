"""Seeded near-bed flow of a storm on a pipe section: U(t), U̇(t) normal to the pipe and V.

The flow is synthesised by :func:`onbottom.hydro.flow_synthesis.section_storm_flow` (the
package's one flow synthesiser, where the spectrum, amplitudes, phases, spreading and stage
blending are described): for each stage of a :class:`~onbottom.inputs.storm.Storm` the JONSWAP
(or Pierson–Moskowitz) surface spectrum (DNV-RP-C205 §3.5.5) is transferred to the seabed with
linear wave theory, S_UU = G² S_ηη, G = ω / sinh(k d) (DNV-RP-F109 §3.4.3), and synthesised by
random phases,

    U(t) = R_D · Σ_j a_j cos(ω_j t + φ_j),   a_j = √(2 S_UU(ω_j) Δω),

on the harmonics ω_j = j·Δω of the storm's length (the series never repeats within the storm),
one inverse real FFT per stage. The phases φ_j are drawn once per storm from
``numpy.random.default_rng(seed)`` and shared by all stages, so stage blends are coherent and
the same seed gives bitwise the same series on any machine with the same numpy.

R_D is the F109 spreading reduction for a short-crested sea on a section (DNV-RP-F109 (2017)
§3.4.3, :func:`onbottom.hydro.spreading.spreading_factor`); for a long-crested sea
R_D = |sin θ_w|. The sign of sin θ_w sets the direction of U (waves travelling towards −y
give −U).

The steady current is the mean of the log profile over the diameter (DNV-RP-F109 Eq 3.3,
:func:`onbottom.hydro.current.mean_current_over_pipe`), times sin θ_c with its sign.

Stage weights w_k(t) (linear build-up, blends, decay; see :class:`~onbottom.inputs.storm.Storm`)
multiply each stage's series: U = Σ w_k U_k, U̇ = Σ (w_k U̇_k + ẇ_k U_k).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from onbottom._validate import positive
from onbottom.constants import GRAVITY
from onbottom.errors import InputError
from onbottom.hydro import spreading
from onbottom.hydro.current import mean_current_over_pipe
from onbottom.hydro.flow_synthesis import sea_state_spectrum, section_storm_flow
from onbottom.hydro.kinematics import seabed_transfer
from onbottom.hydro.spectra import spectral_moment
from onbottom.inputs.storm import Current, SeaState, Storm

__all__ = [
    "StormKinematics",
    "current_normal_to_pipe",
    "sea_state_for_velocity",
    "seabed_velocity_parameters",
    "storm_kinematics",
]


def seabed_velocity_parameters(
    sea: SeaState, depth: float, n: int = 4096, omega_max_factor: float = 8.0
) -> dict[str, float]:
    """U_s = 2√M_0 [m/s] (with R_D), T_u = 2π√(M_0/M_2) [s] and R_D [-] of a sea state.

    Parameters
    ----------
    sea : SeaState
    depth : float
        Water depth d [m], > 0.
    """
    positive("depth", depth)
    wp = 2.0 * math.pi / sea.tp
    w = np.linspace(wp * 1e-3, omega_max_factor * wp, n)
    suu = seabed_transfer(w, depth) ** 2 * sea_state_spectrum(sea, w)
    m0 = spectral_moment(w, suu, 0)
    m2 = spectral_moment(w, suu, 2)
    rd = float(spreading.spreading_factor(sea.spreading_s, wave_direction_deg=sea.direction_deg))
    # waves that do not reach the seabed (deep water): no flow, T_u of the surface (m0/m2 → the
    # surface spectrum's ratio is not defined once both moments underflow; T_p is a bound)
    t_u = 2.0 * math.pi * math.sqrt(m0 / m2) if m2 > 0.0 else sea.tp
    return {
        "significant_velocity": 2.0 * math.sqrt(m0) * rd,
        "mean_period": t_u,
        "spreading_factor": rd,
    }


def current_normal_to_pipe(
    current: Current | None, diameter: float, z0: float | None = None
) -> float:
    """Mean current over the pipe diameter normal to the pipe V [m/s], signed (F109 Eq 3.3).

    ``current.z0`` wins over ``z0``; one of them is needed for a non-zero current.
    """
    if current is None or current.velocity == 0.0:
        return 0.0
    rough = current.z0 if current.z0 is not None else z0
    if rough is None:
        raise InputError(
            "Current.z0 = None is invalid here: give the seabed roughness z0 (DNV-RP-F109"
            " Table 3-1) in [current] or the seabed d50"
        )
    v = mean_current_over_pipe(current.velocity, current.reference_height, diameter, rough, 90.0)
    return v * math.sin(math.radians(current.direction_deg))


@dataclass(frozen=True, kw_only=True, eq=False)
class StormKinematics:
    """Sampled near-bed flow of one storm on a section.

    Attributes
    ----------
    sample_interval : float
        Δt_s between samples [s]; sample j is at t = j·Δt_s.
    velocity, acceleration : numpy.ndarray
        U(t_j) [m/s] and U̇(t_j) [m/s²] normal to the pipe (R_D and direction included).
    current : float
        V [m/s], signed, normal to the pipe.
    duration : float
        Storm duration [s] (last sample time).
    weights : numpy.ndarray
        Stage weights w_k(t_j), shape (n_stages, n) (for per-sea-state coefficients).
    stage_parameters : list of dict
        Per stage: significant_velocity U_s, mean_period T_u, spreading_factor R_D.
    seed : int
    """

    sample_interval: float
    velocity: np.ndarray
    acceleration: np.ndarray
    current: float
    duration: float
    weights: np.ndarray
    stage_parameters: list[dict[str, float]] = field(default_factory=list)
    seed: int = 0

    def __post_init__(self) -> None:
        # an empty or inconsistent flow is a named error, never a run (an empty
        # stage_parameters would run with an empty coefficient array and forces ≈ 1e-320)
        cls = "StormKinematics"
        dts = self.sample_interval
        if not (isinstance(dts, int | float) and math.isfinite(dts) and dts > 0.0):
            raise InputError(f"{cls}.sample_interval = {dts!r} is invalid: must be > 0 s")
        u = np.asarray(self.velocity)
        a = np.asarray(self.acceleration)
        if u.ndim != 1 or u.size < 2:
            raise InputError(
                f"{cls}.velocity has shape {u.shape}: need a 1-D series of >= 2 samples"
            )
        if a.shape != u.shape:
            raise InputError(
                f"{cls}.acceleration has shape {a.shape}, velocity {u.shape}: must match"
            )
        for name, arr in (("velocity", u), ("acceleration", a)):
            if np.isfinite(arr).all():
                continue
            bad = np.flatnonzero(~np.isfinite(arr))
            if bad.size:
                raise InputError(
                    f"{cls}.{name}[{int(bad[0])}] = {float(arr[bad[0]])!r} is invalid: must be"
                    " finite"
                )
        if not math.isfinite(self.current):
            raise InputError(f"{cls}.current = {self.current!r} is invalid: must be finite")
        t_last = (u.size - 1) * dts
        if not (0.0 < self.duration <= t_last * (1.0 + 1e-9) + 1e-12):
            raise InputError(
                f"{cls}.duration = {self.duration!r} s is invalid: must lie in (0, {t_last:g}]"
                f" s, the time of the last sample ({u.size} samples every {dts:g} s)"
            )
        w = np.asarray(self.weights)
        ns = len(self.stage_parameters)
        if ns == 0:
            raise InputError(
                f"{cls}.stage_parameters = [] is invalid: give one dict per stage with"
                " significant_velocity [m/s] and mean_period [s] (the force model's K and M"
                " come from them); use StormKinematics.regular/from_series or storm_kinematics"
            )
        if w.ndim != 2 or w.shape != (ns, u.size):
            raise InputError(
                f"{cls}.weights has shape {w.shape}: expected (stages, samples) = ({ns}, {u.size})"
            )
        for i, p in enumerate(self.stage_parameters):
            us = p.get("significant_velocity") if isinstance(p, dict) else None
            tu = p.get("mean_period") if isinstance(p, dict) else None
            if us is None or not math.isfinite(us) or us < 0.0:
                raise InputError(
                    f"{cls}.stage_parameters[{i}].significant_velocity = {us!r} is invalid:"
                    " must be a finite value >= 0 m/s"
                )
            if tu is None or not math.isfinite(tu) or tu <= 0.0:
                raise InputError(
                    f"{cls}.stage_parameters[{i}].mean_period = {tu!r} is invalid: must be > 0 s"
                )

    @property
    def time(self) -> np.ndarray:
        """Sample times [s]."""
        return np.arange(self.velocity.size) * self.sample_interval

    @classmethod
    def regular(
        cls,
        height: float,
        period: float,
        depth: float,
        *,
        duration: float,
        diameter: float,
        direction_deg: float = 90.0,
        build_up_s: float = 0.0,
        current: Current | None = None,
        z0: float | None = None,
        sample_interval: float | None = None,
    ) -> StormKinematics:
        """Flow of a regular Airy wave (:func:`onbottom.hydro.flow_input.regular_wave_flow`).

        Parameters
        ----------
        height, period, depth : float
            Wave height H [m], period T [s], water depth d [m], > 0.
        duration : float
            Record length [s], > 0.
        diameter : float
            Pipe outer diameter D [m], > 0 (for the current averaged over D).
        direction_deg : float
            Wave direction relative to the pipe axis θ_w [deg] (90: normal to the pipe).
        build_up_s : float
            Linear build-up of the amplitude [s], >= 0.
        current : Current or None
        z0 : float or None
            Seabed roughness [m] when ``current.z0`` is None.
        sample_interval : float or None
            Δt_s [s]; None → T/50.

        ``stage_parameters``: one stage with U_s = U_w sin θ_w (the velocity amplitude, the
        regular-wave U* of DNV-RP-F109 §3.4.3) and T_u = T, so K = U_w T/D, M = V/U_w.
        """
        from onbottom.hydro.flow_input import regular_wave_flow

        d = positive("diameter", diameter)
        u, a, dts, info = regular_wave_flow(
            height,
            period,
            depth,
            duration=duration,
            direction_deg=direction_deg,
            build_up_s=build_up_s,
            sample_interval=sample_interval,
        )
        params = {
            "significant_velocity": abs(info["amplitude"]),
            "mean_period": float(period),
            "spreading_factor": abs(math.sin(math.radians(direction_deg))),
            "kind": "regular",
            "height": float(height),
            "depth": float(depth),
            "ursell": info["ursell"],
            "wave_length": info["wave_length"],
            "direction_deg": float(direction_deg),
            "build_up_s": float(build_up_s),
            "amplitude": info["amplitude"],
        }
        return cls(
            sample_interval=dts,
            velocity=u,
            acceleration=a,
            current=current_normal_to_pipe(current, d, z0),
            duration=(u.size - 1) * dts,
            weights=np.ones((1, u.size)),
            stage_parameters=[params],
        )

    @classmethod
    def from_series(
        cls,
        series: Any,
        *,
        diameter: float,
        current: Current | None = None,
        z0: float | None = None,
        sampling_tolerance: float | None = None,
    ) -> StormKinematics:
        """Flow of a measured velocity record normal to the pipe.

        Parameters
        ----------
        series : path or VelocitySeries
            CSV file (:func:`onbottom.hydro.flow_input.read_velocity_series`) or a checked
            :class:`~onbottom.hydro.flow_input.VelocitySeries` (from arrays:
            :func:`~onbottom.hydro.flow_input.velocity_series`).
        diameter : float
            Pipe outer diameter D [m], > 0 (for the current averaged over D).
        current : Current or None
            Steady current added to the record (None: the record holds all the flow).
        z0 : float or None
        sampling_tolerance : float or None
            Relative tolerance on the sampling interval [-] (None: the reader's default).

        ``stage_parameters``: one stage with U_s = 2·std(U) and T_u = 2π·std(U)/std(U̇), the
        spectral definitions U_s = 2√M_0, T_u = 2π√(M_0/M_2) of DNV-RP-F109 §3.4.3 estimated
        from the record (U̇ has the spectrum ω² S_UU).
        """
        from onbottom.hydro.flow_input import VelocitySeries, read_velocity_series

        d = positive("diameter", diameter)
        if isinstance(series, VelocitySeries):
            vs = series
        elif isinstance(series, str | os.PathLike):
            kw = {} if sampling_tolerance is None else {"sampling_tolerance": sampling_tolerance}
            vs = read_velocity_series(series, **kw)
        else:
            raise InputError(
                f"series = {type(series).__name__} is invalid: expected a CSV path or a"
                " VelocitySeries"
            )
        su = float(np.std(vs.velocity))
        sa = float(np.std(vs.acceleration))
        if su <= 0.0 or sa <= 0.0:
            tu = vs.duration
        else:
            tu = 2.0 * math.pi * su / sa
        params = {
            "significant_velocity": 2.0 * su,
            "mean_period": tu,
            "spreading_factor": 1.0,
            "kind": "measured",
            "source": vs.source,
            "t0": vs.t0,
            "acceleration_given": int(vs.acceleration_given),
        }
        n = vs.velocity.size
        return cls(
            sample_interval=vs.sample_interval,
            velocity=vs.velocity,
            acceleration=vs.acceleration,
            current=current_normal_to_pipe(current, d, z0),
            duration=vs.duration,
            weights=np.ones((1, n)),
            stage_parameters=[params],
        )


def storm_kinematics(
    storm: Storm,
    depth: float,
    *,
    diameter: float,
    current: Current | None = None,
    z0: float | None = None,
    sample_interval: float | None = None,
    omega_max_factor: float = 5.0,
) -> StormKinematics:
    """Synthesise the near-bed flow of a storm normal to a pipe section (module docstring).

    Parameters
    ----------
    storm : Storm
        Stages, envelope and seed.
    depth : float
        Water depth d [m], > 0.
    diameter : float
        Pipe outer diameter D [m], > 0 (for the current averaged over D).
    current : Current or None
        Steady current; None = no current.
    z0 : float or None
        Seabed roughness [m] used when ``current.z0`` is None.
    sample_interval : float or None
        Δt_s [s], > 0; None → min(T_p)/50.
    omega_max_factor : float
        Highest synthesised frequency as a multiple of the highest ω_p [-], > 1 (the seabed
        transfer makes S_UU negligible beyond about 3 ω_p in water of moderate depth).
    """
    if not isinstance(storm, Storm):
        raise InputError(f"storm = {type(storm).__name__} is invalid: expected Storm")
    positive("depth", depth)
    d = positive("diameter", diameter)
    if omega_max_factor <= 1.0:
        raise InputError(f"omega_max_factor = {omega_max_factor!r} is invalid: must be > 1")
    tp_min = min(s.tp for s in storm.stages)
    dts = positive("sample_interval", sample_interval) if sample_interval else tp_min / 50.0
    u, a, weights = section_storm_flow(storm, depth, dts, omega_max_factor)
    params = [seabed_velocity_parameters(sea, depth) for sea in storm.stages]
    v = current_normal_to_pipe(current, d, z0)
    return StormKinematics(
        sample_interval=dts,
        velocity=u,
        acceleration=a,
        current=v,
        duration=storm.duration_s,
        weights=weights,
        stage_parameters=params,
        seed=storm.seed,
    )


def sea_state_for_velocity(
    significant_velocity: float,
    mean_period: float,
    *,
    tn_over_tp: float = 0.1,
    gamma: float = 3.3,
    duration_s: float = 10800.0,
) -> tuple[SeaState, float]:
    """A JONSWAP sea state and water depth giving a target U_s [m/s] and T_u [s].

    For a fixed T_n/T_p (T_n = √(d/g)) and γ, T_u/T_p and U_s/H_s·(T_n) are fixed ratios of the
    linear transfer (the F109 Figs 3-2/3-3 quantities), so T_p = T_u/(T_u/T_p),
    d = g (T_n/T_p · T_p)² and H_s = U_s/(U_s/H_s). Used to build storms for prescribed K, N
    (stability curves). Long-crested, normal to the pipe.

    Returns
    -------
    (SeaState, depth [m])
    """
    us = positive("significant_velocity", significant_velocity)
    tu = positive("mean_period", mean_period)
    positive("tn_over_tp", tn_over_tp)
    ref = SeaState(hs=1.0, tp=10.0, gamma=gamma, duration_s=duration_s)
    d_ref = GRAVITY * (tn_over_tp * 10.0) ** 2
    p = seabed_velocity_parameters(ref, d_ref)
    tp = tu / (p["mean_period"] / 10.0)
    depth = GRAVITY * (tn_over_tp * tp) ** 2
    p2 = seabed_velocity_parameters(SeaState(hs=1.0, tp=tp, gamma=gamma), depth)
    hs = us / p2["significant_velocity"]
    if not 0.0 < hs <= 30.0 or not 0.0 < tp <= 40.0:
        raise InputError(
            f"no sea state gives U_s = {us:g} m/s, T_u = {tu:g} s within H_s <= 30 m,"
            f" T_p <= 40 s (got H_s = {hs:.3g} m, T_p = {tp:.3g} s)"
        )
    return SeaState(hs=hs, tp=tp, gamma=gamma, duration_s=duration_s), depth
