"""Absolute lateral static stability (DNVGL-RP-F109 (2017) §3.6, Eqs 3.38–3.41).

    lateral:   γ_SC (F*_Y + μ F*_Z) / (μ w_s + F_R) <= 1          (Eq 3.38)
    vertical:  γ_SC F*_Z / w_s <= 1                                (Eq 3.39)
    F*_Y = r_tot,y ½ ρ_w D C*_Y (U* + V*)²                          (Eq 3.40)
    F*_Z = r_tot,z ½ ρ_w D C*_Z (U* + V*)²                          (Eq 3.41)

U*, T*, V*, K* = U*T*/D, M* = V*/U* from :func:`onbottom.hydro.design_sea_state.
design_oscillation`; C*_Y, C*_Z and γ_SC from :mod:`onbottom.checks.f109_tables`; the load
reductions r_tot = r_perm r_pen r_tr from :mod:`onbottom.hydro.reductions` (Eqs 3.17–3.22);
passive resistance F_R and initial penetration z_pi per soil (F109 §3.4.6):

* sand: z_pi/D = 0.037 κ_s^−0.67 with κ_s = γ'_s D²/w_s; F_R = γ'_s D² (5 − 0.15 κ_s)
  (z_p/D)^1.25 for κ_s <= 26.7, γ'_s D² (z_p/D)^1.25 above, with κ_s = γ'_s D²/F_C and
  F_C = w_s − F*_Z (:func:`onbottom.soil.verley_sotberg.peak_passive_resistance`,
  law ``"dnv_f109"``);
* clay (Verley & Lund 1995): z_pi from :func:`onbottom.soil.verley_lund.
  clay_initial_penetration`; F_R = 4.1 s_u D G_c^−0.39 (z_p/D)^1.31 (0 when F_C <= 0);
* rock: z_p = 0, F_R = 0.

The utilisation of the check is the larger of the two left-hand sides; it passes at <= 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from onbottom._validate import finite, in_range, non_negative, one_of
from onbottom.checks.f109_tables import peak_load_coefficients, safety_factor
from onbottom.errors import InputError
from onbottom.hydro.current import SEABED_ROUGHNESS
from onbottom.hydro.design_sea_state import DEFAULT_DURATION, DesignOscillation, design_oscillation
from onbottom.hydro.reductions import (
    PERMEABLE_SEABED_REDUCTION_Z,
    penetration_reduction,
    trench_reduction,
)
from onbottom.inputs import consistency
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.inputs.storm import Current, SeaState
from onbottom.soil.verley_lund import clay_initial_penetration, clay_passive_resistance
from onbottom.soil.verley_sotberg import initial_penetration, peak_passive_resistance

__all__ = [
    "AbsoluteStabilityResult",
    "absolute_lateral_stability",
    "absolute_stability_of_sea_state",
    "initial_penetration_f109",
    "passive_resistance_f109",
    "seabed_kind",
    "seabed_roughness",
]

_D50 = np.array([0.0625, 0.25, 0.5, 1.0, 4.0, 25.0, 125.0, 500.0]) * 1e-3
_Z0 = np.array(list(SEABED_ROUGHNESS.values()))
ROCK_ROUGHNESS = SEABED_ROUGHNESS["gravel"]
"""Default z_0 [m] on rock when none is given (our choice: F109 Table 3-1 has no rock row;
the 'gravel' value is on the safe side of the coarser rows: a smaller z_0 gives a larger V)."""


def seabed_kind(seabed: Sand | Clay | Rock) -> str:
    """``"sand"``, ``"clay"`` or ``"rock"``."""
    if isinstance(seabed, Sand):
        return "sand"
    if isinstance(seabed, Clay):
        return "clay"
    if isinstance(seabed, Rock):
        return "rock"
    raise InputError(f"seabed = {seabed!r} is invalid: expected Sand, Clay or Rock")


def seabed_roughness(seabed: Sand | Clay | Rock) -> float:
    """Seabed roughness z_0 [m] (F109 Table 3-1; log–log interpolation in d_50 for sand)."""
    kind = seabed_kind(seabed)
    if kind == "clay":
        return SEABED_ROUGHNESS["silt and clay"]
    if kind == "rock":
        return ROCK_ROUGHNESS
    d50 = min(max(seabed.d50, _D50[0]), _D50[-1])
    return float(np.exp(np.interp(np.log(d50), np.log(_D50), np.log(_Z0))))


def initial_penetration_f109(pipe: Pipe, seabed: Sand | Clay | Rock) -> float:
    """Initial penetration z_pi [m] under the submerged weight w_s (F109 §3.4.6)."""
    kind = seabed_kind(seabed)
    d, ws = pipe.outer_diameter, pipe.submerged_weight
    if kind == "sand":
        return initial_penetration(seabed.submerged_unit_weight, d, ws)
    if kind == "clay":
        return clay_initial_penetration(ws, d, seabed.undrained_shear_strength, seabed.unit_weight)
    return 0.0


def passive_resistance_f109(
    pipe: Pipe, seabed: Sand | Clay | Rock, penetration: float, vertical_load: float
) -> float:
    """Passive resistance F_R [N/m] at penetration z_p and contact force F_C (F109 §3.4.6)."""
    kind = seabed_kind(seabed)
    if kind == "rock" or vertical_load <= 0.0 or penetration <= 0.0:
        return 0.0
    d = pipe.outer_diameter
    if kind == "sand":
        return peak_passive_resistance(
            seabed.submerged_unit_weight, d, vertical_load, penetration, law="dnv_f109"
        )
    return clay_passive_resistance(
        penetration, d, seabed.undrained_shear_strength, seabed.unit_weight
    )


@dataclass(frozen=True, slots=True)
class AbsoluteStabilityResult:
    """Result of the absolute lateral static stability check (SI; forces per unit length).

    Attributes: ``utilisation`` = max(lateral, vertical) [-]; ``utilisation_lateral`` (Eq
    3.38) and ``utilisation_vertical`` (Eq 3.39) [-]; ``passes`` (utilisation <= 1);
    ``gamma_sc``, ``friction_coefficient`` μ [-]; ``penetration`` z_p [m]; ``r_y``, ``r_z``
    total load reductions [-]; ``c_y``, ``c_z`` C*_Y, C*_Z [-]; ``f_y``, ``f_z`` F*_Y, F*_Z
    [N/m]; ``passive_resistance`` F_R [N/m]; ``submerged_weight`` w_s [N/m]; ``diameter`` D
    [m]; ``oscillation`` the :class:`DesignOscillation` (U*, T*, V*, K*, M* ...).
    """

    utilisation: float
    utilisation_lateral: float
    utilisation_vertical: float
    passes: bool
    gamma_sc: float
    friction_coefficient: float
    penetration: float
    r_y: float
    r_z: float
    c_y: float
    c_z: float
    f_y: float
    f_z: float
    passive_resistance: float
    submerged_weight: float
    diameter: float
    oscillation: DesignOscillation

    def as_dict(self) -> dict[str, float | bool]:
        """Scalars of the result plus U*, T*, V*, K*, M*, U_s, T_u (for JSON/tables)."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "oscillation"}
        osc = self.oscillation
        for name in ("us", "tu", "u_star", "t_star", "v_star", "k_star", "m_star"):
            out[name] = float(getattr(osc, name))
        return out


def absolute_lateral_stability(
    pipe: Pipe,
    seabed: Sand | Clay | Rock,
    *,
    hs: float,
    tp: float,
    depth: float,
    current_velocity: float = 0.0,
    current_reference_height: float = 1.0,
    roughness: float | None = None,
    gamma: float | None = None,
    spectrum: str = "jonswap",
    wave_direction_deg: float = 90.0,
    current_direction_deg: float = 90.0,
    spreading_s: float | None = None,
    safety_class: str = "normal",
    region: str = "north_sea_winter",
    penetration: float | None = None,
    trench_depth: float = 0.0,
    trench_angle_deg: float = 45.0,
    permeable: bool | None = None,
    duration: float = DEFAULT_DURATION,
) -> AbsoluteStabilityResult:
    """DNV-RP-F109 absolute lateral static stability of a pipe in one sea state.

    Parameters
    ----------
    pipe : Pipe
        Outer diameter D [m], submerged weight w_s [N/m], ρ_w [kg/m³] (``pipe.seawater_density``).
    seabed : Sand, Clay or Rock
        Soil (μ, γ'_s or s_u/γ_s, d_50).
    hs, tp : float
        Design H_s [m] and T_p [s], > 0.
    depth : float
        Water depth d [m], > D (an :class:`InputError` otherwise; a
        :class:`~onbottom.errors.ShallowWaterWarning` below 3 D or near breaking, see
        :mod:`onbottom.inputs.consistency`).
    current_velocity : float
        Current V(z_r) [m/s], >= 0 (a warning above 3 m/s).
    current_reference_height : float
        z_r [m], > 0.
    roughness : float or None
        z_0 [m]; None → F109 Table 3-1 from the seabed (:func:`seabed_roughness`).
    gamma : float or None
        JONSWAP γ [-]; None → DNV rule.
    spectrum : str
        ``"jonswap"`` or ``"pierson-moskowitz"``.
    wave_direction_deg, current_direction_deg : float
        Angles of waves and current to the pipe axis [deg] (90 = normal).
    spreading_s : float or None
        Spreading exponent s [-]; None → long-crested.
    safety_class : str
        ``"low"``, ``"normal"`` or ``"high"``.
    region : str
        Key of :data:`onbottom.checks.f109_tables.SAFETY_FACTORS`.
    penetration : float or None
        z_p [m], >= 0; None → initial penetration under w_s (:func:`initial_penetration_f109`).
    trench_depth : float
        z_t [m], >= 0 (0 = no trench).
    trench_angle_deg : float
        Trench wall angle θ [deg], in [5, 45] (used when ``trench_depth`` > 0).
    permeable : bool or None
        Apply r_perm,z = 0.7 (Eq 3.18); None → True on sand and rock, False on clay.
    duration : float
        Storm duration T [s] in τ = T/T_u.

    Returns
    -------
    AbsoluteStabilityResult
        ``utilisation`` (max of Eqs 3.38 and 3.39) and ``passes``.
    """
    if not isinstance(pipe, Pipe):
        raise InputError(f"pipe = {pipe!r} is invalid: expected a Pipe")
    # settings: one number per argument, checked for a section in this sea
    n = _numbers(
        hs=hs,
        tp=tp,
        depth=depth,
        current_velocity=current_velocity,
        current_reference_height=current_reference_height,
        wave_direction_deg=wave_direction_deg,
        current_direction_deg=current_direction_deg,
        trench_depth=trench_depth,
        trench_angle_deg=trench_angle_deg,
        duration=duration,
        roughness=roughness,
        gamma=gamma,
        spreading_s=spreading_s,
        penetration=penetration,
    )
    _check_section_in_sea(pipe, n)
    kind = seabed_kind(seabed)
    one_of("spectrum", spectrum, ("jonswap", "pierson-moskowitz"))
    gamma_sc = safety_factor(region, kind, safety_class)
    # the design oscillation (U*, V*, K*, M*)
    osc = _oscillation(pipe, seabed, n, spectrum)
    d, penetration = pipe.outer_diameter, n["penetration"]
    # the load reductions (penetration, trench, permeable seabed)
    zp = initial_penetration_f109(pipe, seabed) if penetration is None else penetration
    non_negative("penetration", zp)
    r_y, r_z = _load_reductions(d, kind, zp, n["trench_depth"], n["trench_angle_deg"], permeable)
    # the peak loads and the utilisations (Eqs 3.38–3.41)
    return _utilisation(pipe, seabed, osc, gamma_sc, zp, r_y, r_z)


def _numbers(**values: Any) -> dict[str, Any]:
    """The scalar arguments of :func:`absolute_lateral_stability`, each one finite number (an
    array is a named error, a 0-d array a number; the last four may be None), checked in the
    order given."""
    optional = ("roughness", "gamma", "spreading_s", "penetration")
    return {
        k: None if v is None and k in optional else finite(k, consistency.scalar(k, v))
        for k, v in values.items()
    }


def _check_section_in_sea(pipe: Pipe, n: dict[str, Any]) -> None:
    """The physical consistency of the section in its sea (errors raised, warnings issued)."""
    consistency.report(
        consistency.section_in_sea(
            diameter=pipe.outer_diameter,
            depth=n["depth"],
            hs=n["hs"],
            tp=n["tp"],
            current_velocity=n["current_velocity"],
            angles=(
                ("wave_direction_deg", n["wave_direction_deg"]),
                ("current_direction_deg", n["current_direction_deg"]),
            ),
        )
    )


def _oscillation(pipe: Pipe, seabed: Sand | Clay | Rock, n: dict[str, Any], spectrum: str) -> Any:
    """The design oscillation U*, V*, T_u, K*, M* of the sea state (:func:`design_oscillation`)."""
    z0 = seabed_roughness(seabed) if n["roughness"] is None else n["roughness"]
    return design_oscillation(
        n["hs"],
        n["tp"],
        n["depth"],
        pipe.outer_diameter,
        gamma=n["gamma"],
        spectrum=spectrum,
        wave_direction_deg=n["wave_direction_deg"],
        spreading_s=n["spreading_s"],
        current_velocity=n["current_velocity"],
        current_reference_height=n["current_reference_height"],
        current_direction_deg=n["current_direction_deg"],
        roughness=z0,
        submerged_weight=pipe.submerged_weight,
        seawater_density=pipe.seawater_density,
        duration=n["duration"],
    )


def _load_reductions(
    d: float,
    kind: str,
    zp: float,
    trench_depth: float,
    trench_angle_deg: float,
    permeable: bool | None,
) -> tuple[float, float]:
    """r_y, r_z [-]: the penetration, trench and permeable-seabed (Eq 3.18) reductions of the
    horizontal and vertical peak loads (:mod:`onbottom.hydro.reductions`)."""
    r_pen_y, r_pen_z = (float(r) for r in penetration_reduction(zp / d))
    zt = non_negative("trench_depth", trench_depth)
    r_tr_y, r_tr_z = trench_reduction(zt / d, trench_angle_deg) if zt > 0.0 else (1.0, 1.0)
    if zt > 0.0:
        in_range("trench_angle_deg", trench_angle_deg, 5.0, 45.0)
    perm = (kind != "clay") if permeable is None else bool(permeable)
    r_y = r_pen_y * r_tr_y
    r_z = (PERMEABLE_SEABED_REDUCTION_Z if perm else 1.0) * r_pen_z * r_tr_z
    return r_y, r_z


def _utilisation(
    pipe: Pipe,
    seabed: Sand | Clay | Rock,
    osc: Any,
    gamma_sc: float,
    zp: float,
    r_y: float,
    r_z: float,
) -> AbsoluteStabilityResult:
    """Peak loads F*_Y, F*_Z (Eqs 3.40, 3.41) and the utilisations (Eqs 3.38, 3.39)."""
    d, ws, rho = pipe.outer_diameter, pipe.submerged_weight, pipe.seawater_density
    k_star = float(osc.k_star)
    m_star = float(osc.m_star)
    if not math.isfinite(k_star) or k_star <= 0.0:
        # no waves (U* = 0): current only, K* → ∞ → steady-flow row and column
        k_star, m_star = 1.0e9, math.inf
    cy, cz = (float(c) for c in peak_load_coefficients(k_star, m_star))
    q = 0.5 * rho * d * (float(osc.u_star) + float(osc.v_star)) ** 2
    f_y = r_y * cy * q
    f_z = r_z * cz * q
    mu = seabed.friction_coefficient
    f_r = passive_resistance_f109(pipe, seabed, zp, ws - f_z)
    resist = mu * ws + f_r
    u_lat = gamma_sc * (f_y + mu * f_z) / resist if resist > 0.0 else math.inf
    u_vert = gamma_sc * f_z / ws if ws > 0.0 else math.inf
    util = max(u_lat, u_vert)
    return AbsoluteStabilityResult(
        utilisation=util,
        utilisation_lateral=u_lat,
        utilisation_vertical=u_vert,
        passes=bool(util <= 1.0),
        gamma_sc=gamma_sc,
        friction_coefficient=mu,
        penetration=zp,
        r_y=r_y,
        r_z=r_z,
        c_y=cy,
        c_z=cz,
        f_y=f_y,
        f_z=f_z,
        passive_resistance=f_r,
        submerged_weight=ws,
        diameter=d,
        oscillation=osc,
    )


def absolute_stability_of_sea_state(
    pipe: Pipe,
    seabed: Sand | Clay | Rock,
    sea_state: SeaState,
    current: Current | None,
    depth: float,
    **options: object,
) -> AbsoluteStabilityResult:
    """:func:`absolute_lateral_stability` for a :class:`SeaState` and a :class:`Current`.

    H_s, T_p, γ, spectrum, direction, spreading and duration come from ``sea_state``; V(z_r),
    z_r, direction and z_0 from ``current`` (None → no current); ``depth`` [m]; ``options``
    are the remaining keywords of :func:`absolute_lateral_stability` (safety_class, region,
    penetration, trench_depth, trench_angle_deg, permeable).
    """
    if not isinstance(sea_state, SeaState):
        raise InputError(f"sea_state = {sea_state!r} is invalid: expected SeaState")
    if current is not None and not isinstance(current, Current):
        raise InputError(f"current = {current!r} is invalid: expected Current or None")
    cur = {}
    if current is not None:
        a = current.direction_deg % 360.0
        cur = {
            "current_velocity": current.velocity,
            "current_reference_height": current.reference_height,
            "current_direction_deg": a if a <= 180.0 else 360.0 - a,
            "roughness": current.z0,
        }
    return absolute_lateral_stability(
        pipe,
        seabed,
        hs=sea_state.hs,
        tp=sea_state.tp,
        depth=depth,
        gamma=sea_state.gamma,
        spectrum=sea_state.spectrum,
        wave_direction_deg=sea_state.direction_deg,
        spreading_s=sea_state.spreading_s or None,
        duration=sea_state.duration_s,
        **cur,
        **options,
    )
