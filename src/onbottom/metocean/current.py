"""Current speed jointly with H_s: a Weibull marginal joined to H_s by a Gaussian copula.

Model (fitted to every sea state of the hindcast, as the H_s–T_p model is):

* current speed U [m/s]: 2-parameter Weibull, F_U(u) = 1 − exp(−(u/α_U)^β_U), fitted by
  maximum likelihood (scipy ``weibull_min.fit`` with the location fixed at 0) to the non-zero
  speeds;
* dependence on H_s: a Gaussian (normal) copula of correlation ρ between the normal scores
  z_H = Φ⁻¹(F_H(H_s)) — F_H the joint model's 3-parameter Weibull of H_s
  (:class:`~onbottom.metocean.joint.JointModel`) — and z_U = Φ⁻¹(F_U(U)). ρ is estimated
  from Spearman's rank correlation ρ_S of (H_s, U) over the record by the exact relation of
  the Gaussian copula, ρ = 2 sin(π ρ_S / 6) (Kruskal 1958; Joe 2014 §4.3), so the estimate
  does not depend on the marginal fits.

Given H_s = h the current is U = F_U⁻¹(Φ(ρ z_H(h) + √(1 − ρ²) u)), u ~ N(0, 1): this is the
Rosenblatt transformation the reliability climate draws with
(:class:`~onbottom.reliability.climate.StormClimate`), and :meth:`CurrentModel.quantile` gives
the current that goes with a return-period H_s in the design table (the joint-statistics
alternative to F109 (2017) §3.4.2's 100-year wave + 10-year current).

Limits: one omnidirectional model (the current's dependence on the sector is not modelled: the
per-sector current return values of the table are POT fits of each sector's own series); the
Gaussian copula has no tail dependence, so at extreme H_s the current keeps a spread about
F_U⁻¹(Φ(ρ z_H)); a tidal current is not Weibull in detail (read the marginal plot of the
report against the data). Verification: ``tests/verification/test_metocean_current.py``
recovers ρ, α_U, β_U and the conditional quantiles from a series drawn from a known model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special, stats

from onbottom._validate import in_range, positive
from onbottom.errors import InputError

__all__ = ["CurrentModel", "fit_current_model"]


@dataclass(frozen=True, kw_only=True, slots=True)
class CurrentModel:
    """A fitted (or given) current model (module docstring).

    Parameters
    ----------
    scale : float
        α_U, Weibull scale of the current speed [m/s], > 0.
    shape : float
        β_U, Weibull shape [-], > 0.
    rho : float
        ρ, normal-score correlation with H_s [-], in (−1, 1).
    hs_scale, hs_shape, hs_location : float
        The 3-parameter Weibull of H_s the scores are taken from: α [m], β [-], γ [m].
    n_states : int
        Sea states it was fitted to (0 for a given model).
    spearman : float
        ρ_S of the record (NaN for a given model).
    """

    scale: float
    shape: float
    rho: float
    hs_scale: float
    hs_shape: float
    hs_location: float
    n_states: int = 0
    spearman: float = math.nan

    def __post_init__(self) -> None:
        positive("CurrentModel.scale", self.scale)
        positive("CurrentModel.shape", self.shape)
        in_range("CurrentModel.rho", self.rho, -1.0, 1.0, low_inclusive=False, high_inclusive=False)
        positive("CurrentModel.hs_scale", self.hs_scale)
        positive("CurrentModel.hs_shape", self.hs_shape)

    def hs_score(self, hs: np.ndarray | float) -> np.ndarray:
        """z_H = Φ⁻¹(F_H(h)) of H_s = h [m] (below the Weibull's location: F_H = 0 → −8)."""
        x = np.maximum(np.asarray(hs, dtype=float) - self.hs_location, 0.0) / self.hs_scale
        # log of the survival function: keeps the score exact for H_s far in the tail
        log_sf = -np.power(x, self.hs_shape)
        z = -special.ndtri(np.exp(log_sf))
        return np.clip(z, -8.0, 8.0)

    def speed(self, hs: np.ndarray | float, u: np.ndarray | float) -> np.ndarray:
        """U [m/s] at H_s = ``hs`` [m] for the standard normal ``u`` (Rosenblatt)."""
        zu = self.rho * self.hs_score(hs) + math.sqrt(1.0 - self.rho**2) * np.asarray(u, float)
        # F_U^-1(Φ(z)) through the survival function: exact in the upper tail
        log_sf = special.log_ndtr(-zu)
        return self.scale * np.power(-log_sf, 1.0 / self.shape)

    def quantile(self, hs: np.ndarray | float, p: float = 0.5) -> np.ndarray:
        """U [m/s] with non-exceedance probability ``p`` given H_s = ``hs`` [m]."""
        in_range("p", p, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
        return self.speed(hs, special.ndtri(p))

    def marginal_quantile(self, p: np.ndarray | float) -> np.ndarray:
        """U [m/s] with non-exceedance probability ``p`` of the marginal Weibull."""
        q = np.asarray(p, dtype=float)
        return self.scale * np.power(-np.log1p(-q), 1.0 / self.shape)

    def as_dict(self) -> dict:
        """Parameters as plain numbers (provenance, JSON)."""
        return {
            "model": "Weibull current speed, Gaussian copula with Hs (rho from Spearman)",
            "scale": self.scale,
            "shape": self.shape,
            "rho": self.rho,
            "spearman": None if not math.isfinite(self.spearman) else self.spearman,
            "hs_scale": self.hs_scale,
            "hs_shape": self.hs_shape,
            "hs_location": self.hs_location,
            "n_states": self.n_states,
        }


def fit_current_model(
    hs: np.ndarray,
    current: np.ndarray,
    *,
    hs_scale: float,
    hs_shape: float,
    hs_location: float,
) -> CurrentModel:
    """Fit :class:`CurrentModel` to concurrent sea states and currents.

    Parameters
    ----------
    hs : ndarray
        H_s of every sea state [m].
    current : ndarray
        Current speed at the same times [m/s].
    hs_scale, hs_shape, hs_location : float
        The H_s Weibull (α [m], β [-], γ [m]) of the joint model, whose scores the copula
        joins (:class:`~onbottom.metocean.joint.JointModel`).

    Raises
    ------
    InputError
        Fewer than 100 sea states, unequal lengths, or a constant series.
    """
    h = np.asarray(hs, dtype=float)
    u = np.asarray(current, dtype=float)
    if h.shape != u.shape or h.ndim != 1 or h.size < 100:
        raise InputError(
            f"hs, current = {h.size}, {u.size} values is invalid: at least 100, equal lengths"
        )
    if np.ptp(u) == 0.0 or np.ptp(h) == 0.0:
        raise InputError("current_speed is invalid for a current model: the series is constant")
    pos = u[u > 0.0]
    shape, _, scale = stats.weibull_min.fit(pos, floc=0.0)
    rs = float(stats.spearmanr(h, u).statistic)
    rho = 2.0 * math.sin(math.pi * rs / 6.0)
    return CurrentModel(
        scale=float(scale),
        shape=float(shape),
        rho=float(np.clip(rho, -0.999, 0.999)),
        hs_scale=hs_scale,
        hs_shape=hs_shape,
        hs_location=hs_location,
        n_states=int(h.size),
        spearman=rs,
    )
