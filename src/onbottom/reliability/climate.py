"""The storm climate of a site as uncertain inputs of a reliability analysis.

From a :class:`~onbottom.metocean.analysis.MetoceanResult` (``onbottom metocean``): storms
arrive as a Poisson process of rate λ per year; each storm's peak H_s exceeds the threshold u
by a generalised Pareto excess (σ, ξ) (Coles 2001, §4.3); its T_p follows the joint model's
log-normal T_p | H_s (DNV-RP-C205 §3.6.3); the sector the waves come from is drawn with the
storms' observed sector frequencies; with a current model
(:class:`~onbottom.metocean.current.CurrentModel`, fitted to the hindcast's current) the
current speed at the storm peak follows U | H_s (Weibull marginal, Gaussian copula with H_s).

The inputs are standard normal variables — ``u_hs``, ``u_tp``, with sectors ``u_direction``,
with a current model ``u_current`` — mapped to the sea state by the Rosenblatt transformation
(:meth:`StormClimate.sea_state`): H_s = u + G⁻¹(Φ(u_hs)), T_p = exp(μ(H_s) + σ(H_s) u_tp),
sector = the first k with Φ(u_direction) ≤ F_k (cumulative frequencies),
U = F_U⁻¹(Φ(ρ z_H(H_s) + √(1 − ρ²) u_current)). FORM in these
variables is the inverse-FORM of environmental contours (Winterstein et al. 1993), and a
limit state over a storm gives P[failure | storm]; a year fails when any of its storms does:
P_annual = 1 − exp(−λ P[failure | storm]) (:meth:`StormClimate.annual_probability`).
Without a current model the current, and always the soil, are further
:class:`UncertainParameter` inputs given by the user.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special

from onbottom._validate import in_range, positive
from onbottom.errors import InputError
from onbottom.metocean.current import CurrentModel
from onbottom.metocean.joint import JointModel
from onbottom.reliability.distributions import UncertainParameter

__all__ = ["StormClimate"]


@dataclass(frozen=True, kw_only=True, slots=True)
class StormClimate:
    """Storms of a site: rate, peak-H_s GPD, T_p | H_s model, sector frequencies.

    Parameters
    ----------
    rate : float
        λ, storms per year [1/year], > 0.
    threshold : float
        u, the H_s above which a storm counts [m], ≥ 0.
    gpd_scale : float
        σ of the excess of the peak H_s over u [m], > 0.
    gpd_shape : float
        ξ [-], in [−1, 1].
    joint : JointModel
        T_p | H_s model.
    sectors : tuple of str
        Sector labels (empty: omnidirectional).
    sector_frequencies : tuple of float
        Share of the storms from each sector (sums to 1).
    sector_centres_deg : tuple of float
        Sector centres, coming from [deg].
    current : CurrentModel or None
        Current speed given H_s (None: the current is not part of the climate).
    """

    rate: float
    threshold: float
    gpd_scale: float
    gpd_shape: float
    joint: JointModel
    sectors: tuple[str, ...] = ()
    sector_frequencies: tuple[float, ...] = ()
    sector_centres_deg: tuple[float, ...] = ()
    current: CurrentModel | None = None

    def __post_init__(self) -> None:
        positive("StormClimate.rate", self.rate)
        in_range("StormClimate.threshold", self.threshold, 0.0, 30.0)
        positive("StormClimate.gpd_scale", self.gpd_scale)
        in_range("StormClimate.gpd_shape", self.gpd_shape, -1.0, 1.0)
        n = len(self.sectors)
        if len(self.sector_frequencies) != n or len(self.sector_centres_deg) != n:
            raise InputError("StormClimate: one frequency and one centre per sector")
        if n and not math.isclose(sum(self.sector_frequencies), 1.0, abs_tol=1e-9):
            raise InputError(
                f"StormClimate.sector_frequencies = {self.sector_frequencies!r} is invalid:"
                " they must sum to 1"
            )

    @classmethod
    def from_result(cls, result, *, current: bool = False) -> StormClimate:
        """The climate of an analysed hindcast: the omnidirectional storms' GPD and rate, the
        joint model, the sectors' shares of the omnidirectional storm peaks (by the wave
        direction at each peak) and, with ``current``, the hindcast's current model."""
        from onbottom.metocean.storms import sector_mask

        lv = result.hs["omni"]
        if not math.isfinite(lv.scale):
            raise InputError("the hindcast has too few storms for a storm climate")
        hc = result.hindcast
        n = result.options.sectors
        names: tuple[str, ...] = ()
        freq: tuple[float, ...] = ()
        centres: tuple[float, ...] = ()
        if n > 1:
            d = hc.wave_direction_deg[lv.storms.index]
            counts = np.array([np.count_nonzero(sector_mask(d, n, k)) for k in range(n)])
            names = tuple(result.sectors)
            freq = tuple(float(c) for c in counts / counts.sum())
            centres = tuple(float(c) for c in result.centres_deg)
        if current and result.current_model is None:
            raise InputError(
                "reliability.climate.current = true is invalid: the hindcast has no current"
                " columns (current_speed, current_direction_deg)"
            )
        return cls(
            current=result.current_model if current else None,
            rate=lv.storms.rate,
            threshold=lv.storms.threshold,
            gpd_scale=lv.scale,
            gpd_shape=lv.shape,
            joint=result.joint,
            sectors=names,
            sector_frequencies=freq,
            sector_centres_deg=centres,
        )

    def parameters(self) -> list[UncertainParameter]:
        """The standard normal inputs of a storm: ``u_hs``, ``u_tp`` (``u_direction``,
        ``u_current``)."""
        names = ["u_hs", "u_tp"] + (["u_direction"] if self.sectors else [])
        names += ["u_current"] if self.current is not None else []
        return [UncertainParameter(n, "normal", {"mean": 0.0, "std": 1.0}) for n in names]

    def peak_hs(self, u_hs: np.ndarray) -> np.ndarray:
        """Storm peak H_s [m] for standard normal ``u_hs`` (GPD quantile at Φ(u_hs))."""
        q = special.ndtr(np.asarray(u_hs, dtype=float))
        xi, s = self.gpd_shape, self.gpd_scale
        if abs(xi) < 1e-12:
            return self.threshold - s * np.log1p(-q)
        return self.threshold + s / xi * (np.power(1.0 - q, -xi) - 1.0)

    def sea_state(self, u: np.ndarray) -> dict[str, np.ndarray]:
        """H_s [m], T_p [s], the sector index (−1 without sectors) and the current speed
        ``current`` [m/s] (NaN without a current model) of each row of ``u`` (columns in the
        order of :meth:`parameters`)."""
        a = np.atleast_2d(np.asarray(u, dtype=float))
        hs = self.peak_hs(a[:, 0])
        tp = np.exp(self.joint.tp_mu(hs) + self.joint.tp_sigma(hs) * a[:, 1])
        if self.sectors:
            cum = np.cumsum(self.sector_frequencies)
            k = np.searchsorted(cum, special.ndtr(a[:, 2]), side="left")
            sector = np.minimum(k, len(self.sectors) - 1)
        else:
            sector = np.full(a.shape[0], -1)
        if self.current is not None:
            current = self.current.speed(hs, a[:, -1])
        else:
            current = np.full(a.shape[0], np.nan)
        return {"hs": hs, "tp": tp, "sector": sector, "current": current}

    def exceedance_per_storm(self, hs: float) -> float:
        """P[storm peak H_s > ``hs``] (closed form of the GPD; 1 below the threshold)."""
        x = (hs - self.threshold) / self.gpd_scale
        if x <= 0.0:
            return 1.0
        xi = self.gpd_shape
        if abs(xi) < 1e-12:
            return math.exp(-x)
        base = 1.0 + xi * x
        return 0.0 if base <= 0.0 else base ** (-1.0 / xi)

    def annual_probability(self, per_storm: float) -> float:
        """P[a year has at least one failing storm] = 1 − exp(−λ p) (Poisson storms)."""
        in_range("per_storm probability", per_storm, 0.0, 1.0)
        return float(-math.expm1(-self.rate * per_storm))
