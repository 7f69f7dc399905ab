"""Design sea states of DNV-RP-F109: U_s, T_u and the design single oscillation (vectorised).

Every function takes arrays (or scalars) of sea states and broadcasts them, so a scatter
diagram or a sweep needs no loop and no frequency grid from the user.

Sources (DNV-RP-F109 (2017) §3.4.3, §3.5 and Eq 3.3; theory page
``docs/theory/dnv_rp_f109.md``):

* JONSWAP / Pierson–Moskowitz spectrum and the γ rule: DNV-RP-C205 (2010) §3.5.5,
  DNV-RP-F109 (2010/2017) §3.4.3 (same formulas as :mod:`onbottom.hydro.spectra`).
* Linear transfer to the seabed G(ω) = ω/sinh(kd), S_UU = G² S_ηη, U_s = 2√M_0,
  T_u = 2π√(M_0/M_2): F109 §3.4.3 (its Figs 3-2/3-3 are graphs of this integral).
* Design single oscillation (F109 (2017) Eq 3.16 and §3.6.2): U* = k_U U_s, T* = k_T T_u,
  k_U = ½(√(2 ln τ) + 0.5772/√(2 ln τ)), τ = T/T_u (T = 10 800 s),
  k_T = k_t − 5(k_t − 1) T_n/T_u for T_n/T_u <= 0.2, else 1; k_t = 1.25 (γ = 1),
  1.21 (γ = 3.3), 1.17 (γ = 5), linear in γ between (our assumption; F109 gives the three
  values only); T_n = √(d/g).
* Dimensionless groups (F109 §3.5): K = U_s T_u/D, M = V/U_s, N = U_s/(g T_u),
  L = w_s/(½ ρ_w D U_s²); K* = U* T*/D, M* = V*/U*.

Frequency integration: ω = x ω_p on a fixed grid x ∈ [0.25, 12] of ``n_omega`` points
(trapezoid, default 600: U_s and T_u within 2e-5 of a 20 000-point grid for d = 5–500 m,
H_s = 1–10 m, T_p = 5–18 s). Below 0.25 ω_p the spectrum is < e⁻³⁰⁰ of its peak; the unit
test compares with the scalar integration of :mod:`onbottom.hydro.kinematics` on a grid
reaching 15 ω_p.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import in_range, one_of
from onbottom.constants import GRAVITY, RHO_SEAWATER
from onbottom.errors import InputError
from onbottom.hydro.current import mean_current_over_pipe
from onbottom.hydro.spreading import spreading_factor

__all__ = [
    "DEFAULT_DURATION",
    "SPECTRA",
    "DesignOscillation",
    "design_oscillation",
    "jonswap_gamma",
    "peak_period_factor",
    "peak_velocity_factor",
    "significant_bed_velocity",
]

DEFAULT_DURATION = 10_800.0
"""Design storm duration T [s] in τ = T/T_u (3 h; DNV-RP-F109 §3.4.3 and §3.6.2)."""

SPECTRA: tuple[str, ...] = ("jonswap", "pierson-moskowitz")
"""Wave spectra: JONSWAP (γ from the DNV rule or given) or Pierson–Moskowitz (γ = 1)."""

_X_MIN, _X_MAX = 0.25, 12.0
_BLOCK = 128
_KT_GAMMA = np.array([1.0, 3.3, 5.0])
_KT_VALUE = np.array([1.25, 1.21, 1.17])


def _array(name: str, value: ArrayLike, low: float, *, inclusive: bool = False) -> NDArray:
    a = np.asarray(value, dtype=float)
    bad = ~np.isfinite(a) | ((a < low) if inclusive else (a <= low))
    if np.any(bad):
        v = a[bad].flat[0] if a.ndim else float(a)
        op = ">=" if inclusive else ">"
        raise InputError(f"{name} = {v!r} is invalid: must be finite and {op} {low:g}")
    return a


def jonswap_gamma(hs: ArrayLike, tp: ArrayLike) -> NDArray:
    """DNV rule for the JONSWAP peak-enhancement factor γ [-], vectorised.

    φ = T_p/√H_s; γ = 5 for φ <= 3.6, exp(5.75 − 1.15 φ) for 3.6 < φ < 5, 1 for φ >= 5
    (DNV-RP-C205 §3.5.5.5; DNV-RP-F109 §3.4.3). ``hs`` [m] > 0, ``tp`` [s] > 0.
    """
    h = _array("hs", hs, 0.0)
    t = _array("tp", tp, 0.0)
    phi = t / np.sqrt(h)
    return np.where(phi <= 3.6, 5.0, np.where(phi < 5.0, np.exp(5.75 - 1.15 * phi), 1.0))


def _wave_number(omega: NDArray, depth: NDArray) -> NDArray:
    """k solving ω² = g k tanh(k d), broadcast over ω and d.

    Explicit start of Guo (2002, Coastal Eng. 45:71–74; relative error < 0.75 %), then Newton
    iterations to a relative step of 1e-12 (three or four from this start).
    """
    y = omega**2 * depth / GRAVITY
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        kd = y * (1.0 - np.exp(-(y**1.2454))) ** (-1.0 / 2.4908)
    k = np.where(y > 0.0, kd, 0.0) / depth
    for _ in range(20):
        with np.errstate(over="ignore"):
            th = 1.0 - 2.0 / (np.exp(2.0 * k * depth) + 1.0)  # tanh via exp: 3× faster
        f = GRAVITY * k * th - omega**2
        df = GRAVITY * th + GRAVITY * k * depth * (1.0 - th**2)
        step = f / df
        k = k - step
        if np.all(np.abs(step) <= 1e-12 * k):
            break
    return k


def significant_bed_velocity(
    hs: ArrayLike,
    tp: ArrayLike,
    depth: ArrayLike,
    gamma: ArrayLike | None = None,
    spectrum: str = "jonswap",
    *,
    n_omega: int = 600,
) -> tuple[NDArray, NDArray]:
    """Significant near-bed velocity U_s and mean zero-up-crossing period T_u (vectorised).

    Long-crested waves, velocity along the wave direction (apply the spreading and direction
    factor R_D of :func:`onbottom.hydro.spreading.spreading_factor` for the component normal
    to the pipe). U_s = 2√M_0, T_u = 2π√(M_0/M_2) of S_UU(ω) = [ω/sinh(kd)]² S_ηη(ω)
    (DNV-RP-F109 (2017) §3.4.3).

    Parameters
    ----------
    hs : array_like
        Significant wave height H_s [m], > 0.
    tp : array_like
        Spectral peak period T_p [s], > 0.
    depth : array_like
        Water depth d [m], > 0.
    gamma : array_like or None
        JONSWAP peak enhancement γ [-] in [1, 7]; None → DNV rule (:func:`jonswap_gamma`).
        Ignored (γ = 1) for ``spectrum="pierson-moskowitz"``.
    spectrum : str
        ``"jonswap"`` or ``"pierson-moskowitz"``.
    n_omega : int
        Number of frequencies of the integration grid (>= 200).

    Returns
    -------
    (U_s, T_u) : arrays broadcast from the inputs
        [m/s], [s]. Scalars in give 0-d arrays out.
    """
    one_of("spectrum", spectrum, SPECTRA)
    if n_omega < 200:
        raise InputError(f"n_omega = {n_omega!r} is invalid: must be >= 200")
    h = _array("hs", hs, 0.0)
    t = _array("tp", tp, 0.0)
    d = _array("depth", depth, 0.0)
    if spectrum == "pierson-moskowitz":
        g = np.ones_like(h * t)
    elif gamma is None:
        g = jonswap_gamma(h, t)
    else:
        g = np.asarray(gamma, dtype=float)
        bad = ~np.isfinite(g) | (g < 1.0) | (g > 7.0)
        if np.any(bad):
            v = g[bad].flat[0] if g.ndim else float(g)
            raise InputError(f"gamma = {v!r} is invalid: must lie in [1, 7]")
    h, t, d, g = np.broadcast_arrays(h, t, d, g)
    shape = h.shape
    h, t, d, g = (a.reshape(-1, 1) for a in (h, t, d, g))
    x = np.linspace(_X_MIN, _X_MAX, n_omega)[None, :]
    # JONSWAP (DNV-RP-C205 §3.5.5) in x = ω/ω_p: S = α g² ω_p⁻⁵ · x⁻⁵ e^(−1.25 x⁻⁴) · γ^r(x)
    sigma = np.where(x <= 1.0, 0.07, 0.09)
    r = np.exp(-((x - 1.0) ** 2) / (2.0 * sigma**2))
    shape_x = x**-5.0 * np.exp(-1.25 * x**-4.0)
    us = np.empty(h.shape[0])
    tu = np.empty(h.shape[0])
    for i in range(0, h.shape[0], _BLOCK):  # blocks of sea states: bounded memory
        b = slice(i, i + _BLOCK)
        wp = 2.0 * math.pi / t[b]
        w = x * wp
        alpha = 5.0 / 16.0 * h[b] ** 2 * wp**4 / GRAVITY**2 * (1.0 - 0.287 * np.log(g[b]))
        s_eta = alpha * GRAVITY**2 * wp**-5.0 * shape_x * g[b] ** r
        k = _wave_number(w, d[b])
        e = np.exp(-np.minimum(k * d[b], 700.0))
        s_uu = (2.0 * w * e / (1.0 - e * e)) ** 2 * s_eta  # G = ω/sinh(kd) = 2ω e^−kd/(1 − e^−2kd)
        m0 = np.trapezoid(s_uu, w, axis=1)
        m2 = np.trapezoid(w**2 * s_uu, w, axis=1)
        us[b] = 2.0 * np.sqrt(m0)
        tu[b] = 2.0 * math.pi * np.sqrt(m0 / m2)
    return us.reshape(shape), tu.reshape(shape)


def peak_velocity_factor(tau: ArrayLike) -> NDArray:
    """k_U = ½(√(2 ln τ) + 0.5772/√(2 ln τ)) [-] (DNV-RP-F109 (2017) Eq 3.16), τ > 1."""
    tt = _array("tau", tau, 1.0)
    a = np.sqrt(2.0 * np.log(tt))
    return 0.5 * (a + 0.5772 / a)


def peak_period_factor(tn_over_tu: ArrayLike, gamma: ArrayLike) -> NDArray:
    """k_T [-] (DNV-RP-F109 (2017) Eq 3.16).

    k_T = k_t − 5(k_t − 1)·T_n/T_u for T_n/T_u <= 0.2, 1 otherwise; k_t = 1.25, 1.21, 1.17
    for γ = 1, 3.3, 5 (linear in γ between; held constant outside [1, 5]).
    """
    r = _array("T_n/T_u", tn_over_tu, 0.0, inclusive=True)
    g = _array("gamma", gamma, 0.0)
    kt = np.interp(g, _KT_GAMMA, _KT_VALUE)
    return np.where(r <= 0.2, kt - 5.0 * (kt - 1.0) * r, 1.0)


@dataclass(frozen=True, slots=True)
class DesignOscillation:
    """Design sea state quantities of DNV-RP-F109, arrays broadcast over the sea states.

    Attributes (SI): ``hs`` [m], ``tp`` [s], ``depth`` [m], ``phi`` = T_p/√H_s [s/√m],
    ``gamma`` [-], ``tn`` = √(d/g) [s], ``us_long_crested`` U_s before spreading [m/s],
    ``spreading_factor`` R_D [-], ``us`` = R_D U_s normal to the pipe [m/s], ``tu`` T_u [s],
    ``tau`` = T/T_u [-], ``k_u``, ``k_t`` [-], ``u_star`` U* [m/s], ``t_star`` T* [s],
    ``v_star`` V* mean current normal to the pipe over D [m/s], ``diameter`` D [m],
    ``k`` = U_s T_u/D, ``m`` = V/U_s, ``n`` = U_s/(g T_u), ``l`` = w_s/(½ρ_w D U_s²)
    (NaN where w_s not given), ``k_star`` = U* T*/D, ``m_star`` = V*/U* [-].
    """

    hs: NDArray
    tp: NDArray
    depth: NDArray
    phi: NDArray
    gamma: NDArray
    tn: NDArray
    us_long_crested: NDArray
    spreading_factor: NDArray
    us: NDArray
    tu: NDArray
    tau: NDArray
    k_u: NDArray
    k_t: NDArray
    u_star: NDArray
    t_star: NDArray
    v_star: NDArray
    diameter: NDArray
    k: NDArray
    m: NDArray
    n: NDArray
    l: NDArray
    k_star: NDArray
    m_star: NDArray

    def as_dict(self) -> dict[str, NDArray]:
        """Field name → array."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def design_oscillation(
    hs: ArrayLike,
    tp: ArrayLike,
    depth: ArrayLike,
    diameter: ArrayLike,
    *,
    gamma: ArrayLike | None = None,
    spectrum: str = "jonswap",
    wave_direction_deg: ArrayLike = 90.0,
    spreading_s: float | None = None,
    current_velocity: ArrayLike = 0.0,
    current_reference_height: float = 1.0,
    current_direction_deg: float = 90.0,
    roughness: float = 1.0e-5,
    submerged_weight: ArrayLike | None = None,
    seawater_density: float = RHO_SEAWATER,
    duration: float = DEFAULT_DURATION,
) -> DesignOscillation:
    """U_s, T_u, R_D, k_U, k_T, U*, T*, V*, K, M, N, L, τ, K*, M* of DNV-RP-F109 (vectorised).

    Parameters
    ----------
    hs, tp, depth : array_like
        H_s [m], T_p [s], water depth d [m], all > 0.
    diameter : array_like
        Pipe outer diameter D [m], > 0.
    gamma : array_like or None
        JONSWAP γ [-]; None → DNV rule.
    spectrum : str
        ``"jonswap"`` or ``"pierson-moskowitz"``.
    wave_direction_deg : array_like
        Angle θ_w between the wave direction and the pipe axis [deg] (90 = normal).
    spreading_s : float or None
        cos^s spreading exponent s [-] (F109 suggests 2–8); None or 0 → long-crested.
    current_velocity : array_like
        Current V(z_r) at the reference height [m/s], >= 0.
    current_reference_height : float
        z_r [m], > 0.
    current_direction_deg : float
        Angle θ_c between the current and the pipe axis [deg].
    roughness : float
        Seabed roughness z_0 [m] (F109 Table 3-1; default fine sand 1e-5).
    submerged_weight : array_like or None
        w_s [N/m] for the weight parameter L; None → L = NaN.
    seawater_density : float
        ρ_w [kg/m³].
    duration : float
        Storm duration T [s] in τ = T/T_u (F109: 10 800 s).
    """
    in_range("duration", duration, 60.0, 1.0e6)
    zr = float(current_reference_height)
    if not zr > float(roughness):
        raise InputError(
            f"current_reference_height = {zr!r} m is invalid: must lie above the seabed"
            f" roughness z_0 = {float(roughness):g} m (F109 Eq 3.3 log profile)"
        )
    gam = (
        np.ones_like(np.asarray(hs, dtype=float))
        if spectrum == "pierson-moskowitz"
        else (jonswap_gamma(hs, tp) if gamma is None else np.asarray(gamma, dtype=float))
    )
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):  # checked below
        us_lc, tu = significant_bed_velocity(hs, tp, depth, gam, spectrum)
    dia = _array("diameter", diameter, 0.0)
    rd = spreading_factor(spreading_s, wave_direction_deg=wave_direction_deg)
    us = rd * us_lc
    vel = np.asarray(current_velocity, dtype=float)
    v_star = np.vectorize(
        lambda v, dd: mean_current_over_pipe(
            float(v), current_reference_height, float(dd), roughness, current_direction_deg
        )
    )(vel, dia)
    d = np.asarray(depth, dtype=float)
    tn = np.sqrt(d / GRAVITY)
    if not (np.all(np.isfinite(us_lc)) and np.all(np.isfinite(tu))):
        raise InputError(
            f"tp = {tp!r} s is invalid with hs = {hs!r} m, depth = {depth!r} m: the spectral"
            " bed velocity is not finite (T_p far too small for H_s; check the units)"
        )
    tau = duration / tu
    k_u = peak_velocity_factor(tau)
    k_t = peak_period_factor(tn / tu, gam)
    u_star = k_u * us
    t_star = k_t * tu
    with np.errstate(divide="ignore", invalid="ignore"):
        m = np.where(us > 0.0, v_star / us, np.inf)
        m_star = np.where(u_star > 0.0, v_star / u_star, np.inf)
        if submerged_weight is None:
            ell = np.full(np.broadcast(us, dia).shape, np.nan)
        else:
            ell = np.asarray(submerged_weight, dtype=float) / (0.5 * seawater_density * dia * us**2)
    h = np.asarray(hs, dtype=float)
    t = np.asarray(tp, dtype=float)
    b = np.broadcast_arrays(
        h, t, d, t / np.sqrt(h), gam, tn, us_lc, rd, us, tu, tau, k_u, k_t, u_star, t_star,
        v_star, dia, us * tu / dia, m, us / (GRAVITY * tu), ell, u_star * t_star / dia, m_star,
    )  # fmt: skip
    return DesignOscillation(*(np.array(a, dtype=float) for a in b))
