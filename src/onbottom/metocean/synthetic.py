"""A synthetic hindcast drawn from known distributions (examples and verification).

The generating model (documented in docs/theory/metocean.md):

* **H_s** [m]: a stationary Gaussian AR(1) process Z_t (correlation time ``tau_hours``,
  ρ = exp(−Δt/τ) per step) mapped through the standard normal CDF Φ and the inverse
  3-parameter Weibull CDF, H_s = γ + α (−ln(1 − Φ(Z)))^(1/β) — so the marginal distribution of
  every sample is *exactly* the Weibull of DNV-RP-C205 (2019) §3.6.3 Eq. (3.6.7) form, and
  storms last about ``tau_hours`` (realistic autocorrelation; no event catalogue needed).
* **T_p | H_s** [s]: log-normal, ln T_p ~ N(μ(H_s), σ(H_s)) with μ = a0 + a1 H_s^a2 and
  σ = b0 + b1 exp(b2 H_s) (the conditional model of DNV-RP-C205 §3.6.3, written there for T_z;
  applied to T_p here), with an AR(1) normal score (same τ) so T_p is smooth in time.
* **Wave direction** [deg, coming from]: weather regimes of exponential length (mean
  ``regime_hours``); each regime draws a sector from ``sector_weights_calm`` when Z is below 1
  at its start and from ``sector_weights_storm`` otherwise (storms come mostly from W–NW), with
  a normal scatter of 12° about the sector's centre. Direction is drawn *after* H_s, so the
  marginal of H_s stays the stated Weibull; the sectors differ in their extremes.
* **Current** [m/s, deg going to]: an M2 tide (12.42 h) with a spring–neap modulation
  (14.77 d) along ``tide_axis_deg``, plus a wind-driven part 0.03·H_s [m/s per m] going with the
  waves (direction + 180°), plus a small noise. Not used for verification.

The parameter values are of the size of a North Sea shelf site; they are *chosen*, not taken
from a table of the standard. :data:`EXAMPLE_MODEL` is the model of
``examples/hindcast_synthetic.csv`` (``tools/make_synthetic_hindcast.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import special

__all__ = [
    "EXAMPLE_MODEL",
    "STORM_LEVELS_2000Y",
    "SyntheticModel",
    "simulated_storm_levels",
    "synthetic_hindcast",
    "weibull_hs_quantile",
]


@dataclass(frozen=True, kw_only=True, slots=True)
class SyntheticModel:
    """Parameters of the generating model (see the module docstring).

    Parameters
    ----------
    hs_scale, hs_shape, hs_location : float
        Weibull α [m], β [-], γ [m] of H_s.
    tp_a0, tp_a1, tp_a2 : float
        μ(H_s) = a0 + a1 H_s^a2 of ln T_p (T_p in s, H_s in m).
    tp_b0, tp_b1, tp_b2 : float
        σ(H_s) = b0 + b1 exp(b2 H_s) of ln T_p.
    tau_hours : float
        Correlation time of the normal scores [h].
    regime_hours : float
        Mean length of a direction regime [h].
    sector_weights_calm, sector_weights_storm : tuple of float
        Weights of the 8 sectors (centres 0, 45, …, 315° from) at a regime's start.
    tide_amplitude : float
        M2 tidal current amplitude at mean range [m/s].
    tide_axis_deg : float
        Direction the flood tide goes to [deg].
    """

    hs_scale: float = 1.0
    hs_shape: float = 1.35
    hs_location: float = 0.25
    tp_a0: float = 0.80
    tp_a1: float = 1.27
    tp_a2: float = 0.131
    tp_b0: float = 0.1334
    tp_b1: float = 0.0264
    tp_b2: float = -0.1906
    tau_hours: float = 24.0
    regime_hours: float = 72.0
    sector_weights_calm: tuple[float, ...] = (0.14, 0.10, 0.08, 0.10, 0.14, 0.16, 0.16, 0.12)
    sector_weights_storm: tuple[float, ...] = (0.10, 0.02, 0.02, 0.03, 0.08, 0.15, 0.35, 0.25)
    tide_amplitude: float = 0.30
    tide_axis_deg: float = 30.0
    notes: str = field(default="", compare=False)

    def tp_mu(self, hs: np.ndarray | float) -> np.ndarray | float:
        """Mean of ln T_p given H_s [m]."""
        return self.tp_a0 + self.tp_a1 * np.power(hs, self.tp_a2)

    def tp_sigma(self, hs: np.ndarray | float) -> np.ndarray | float:
        """Standard deviation of ln T_p given H_s [m]."""
        return self.tp_b0 + self.tp_b1 * np.exp(self.tp_b2 * np.asarray(hs))


EXAMPLE_MODEL = SyntheticModel()
"""The model of the shipped example ``examples/hindcast_synthetic.csv``."""


def weibull_hs_quantile(model: SyntheticModel, p: np.ndarray | float) -> np.ndarray | float:
    """H_s [m] with non-exceedance probability ``p`` of the model's Weibull marginal."""
    return model.hs_location + model.hs_scale * np.power(
        -np.log1p(-np.asarray(p)), 1.0 / model.hs_shape
    )


def _ar1(rng: np.random.Generator, n: int, rho: float) -> np.ndarray:
    """Unit-variance stationary Gaussian AR(1) series of length ``n``."""
    from scipy.signal import lfilter

    e = rng.standard_normal(n) * math.sqrt(1.0 - rho * rho)
    e[0] = rng.standard_normal()
    return lfilter([1.0], [1.0, -rho], e)


def synthetic_hindcast(
    model: SyntheticModel = EXAMPLE_MODEL,
    *,
    years: float = 25.0,
    step_hours: float = 3.0,
    seed: int = 0,
    start: str = "2000-01-01T00:00",
) -> dict[str, np.ndarray]:
    """Draw a hindcast from ``model``.

    Parameters
    ----------
    model : SyntheticModel
        The generating model.
    years : float
        Length [years of 365.2425 d].
    step_hours : float
        Sampling interval [h].
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    start : str
        First time stamp (UTC, ISO 8601).

    Returns
    -------
    dict of arrays
        ``time`` (datetime64[s]), ``hs`` [m], ``tp`` [s], ``wave_direction_deg`` [deg, from],
        ``current_speed`` [m/s], ``current_direction_deg`` [deg, going to].
    """
    rng = np.random.default_rng(seed)
    n = round(years * 365.2425 * 24.0 / step_hours)
    rho = math.exp(-step_hours / model.tau_hours)
    z = _ar1(rng, n, rho)
    u = special.ndtr(z)
    hs = np.asarray(weibull_hs_quantile(model, u))
    zt = _ar1(rng, n, rho)
    tp = np.exp(model.tp_mu(hs) + model.tp_sigma(hs) * zt)

    # direction regimes
    sector = np.empty(n, dtype=np.int64)
    calm = np.asarray(model.sector_weights_calm) / np.sum(model.sector_weights_calm)
    storm = np.asarray(model.sector_weights_storm) / np.sum(model.sector_weights_storm)
    i = 0
    while i < n:
        length = max(1, round(rng.exponential(model.regime_hours) / step_hours))
        w = storm if z[i] > 1.0 else calm
        sector[i : i + length] = rng.choice(8, p=w)
        i += length
    scatter = 12.0 * _ar1(rng, n, rho)
    wdir = np.mod(45.0 * sector + scatter, 360.0)

    # current: M2 tide with spring-neap modulation + wind-driven part with the waves
    t_h = np.arange(n) * step_hours
    tide = (
        model.tide_amplitude
        * (1.0 + 0.3 * np.cos(2.0 * math.pi * t_h / (14.77 * 24.0)))
        * np.cos(2.0 * math.pi * t_h / 12.42 + 0.7)
    )
    ax = math.radians(model.tide_axis_deg)
    to_wave = np.radians(wdir + 180.0)
    wind = 0.03 * hs
    east = tide * math.sin(ax) + wind * np.sin(to_wave) + 0.02 * rng.standard_normal(n)
    north = tide * math.cos(ax) + wind * np.cos(to_wave) + 0.02 * rng.standard_normal(n)
    speed = np.hypot(east, north)
    cdir = np.mod(np.degrees(np.arctan2(east, north)), 360.0)

    t0 = np.datetime64(start, "s")
    time = t0 + (np.arange(n) * round(step_hours * 3600.0)).astype("timedelta64[s]")
    return {
        "time": time,
        "hs": hs,
        "tp": tp,
        "wave_direction_deg": wdir,
        "current_speed": speed,
        "current_direction_deg": cdir,
    }


STORM_LEVELS_2000Y: dict[float, float] = {1.0: 4.63, 10.0: 5.67, 100.0: 6.52}
"""Storm-based H_s return levels [m] of :data:`EXAMPLE_MODEL` from a 2000-year draw
(:func:`simulated_storm_levels` with its defaults, to 0.01 m): the "true" answers the analysis
of the 25-year example is compared with (docs/theory/metocean.md; a slow test recomputes them)."""


def simulated_storm_levels(
    model: SyntheticModel = EXAMPLE_MODEL,
    return_periods: tuple[float, ...] = (1.0, 10.0, 100.0),
    *,
    years: float = 2000.0,
    seed: int = 99,
    threshold: float = 3.5,
    r_hours: float = 48.0,
    step_hours: float = 3.0,
) -> dict[float, float]:
    """Empirical storm-based return levels of ``model``: from a draw of ``years``, for each R
    [years] the H_s [m] midway between the k-th and (k+1)-th largest declustered storm peaks,
    k = years/R — a level exceeded by exactly k storms, i.e. on average once in R years.

    Parameters
    ----------
    model : SyntheticModel
        The generating model.
    return_periods : tuple of float
        R [years]; years/R must be at least 1.
    years : float
        Length of the draw [years].
    seed : int
        Seed of the draw.
    threshold : float
        Storm threshold [m] (below every level asked for).
    r_hours : float
        Declustering time [h].
    step_hours : float
        Sampling interval [h].
    """
    from onbottom.metocean.storms import decluster

    d = synthetic_hindcast(model, years=years, step_hours=step_hours, seed=seed)
    hs = d["hs"]
    peaks = np.sort(hs[decluster(hs, step_hours, threshold, r_hours)])[::-1]
    out = {}
    for r in return_periods:
        k = round(years / r)
        out[float(r)] = float(0.5 * (peaks[k - 1] + peaks[k]))
    return out
