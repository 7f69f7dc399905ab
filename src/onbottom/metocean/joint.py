"""Joint model of H_s and T_p and its environmental contours (virocon).

Model (DNV-RP-C205 (2019) §3.6.3, Eqs. 3.6.7–3.6.9; the "DNVGL_Hs_Tz" model that virocon
ships as ``get_DNVGL_Hs_Tz``, applied here to T_p):

* H_s: 3-parameter Weibull, F(h) = 1 − exp(−((h − γ)/α)^β), fitted by the method of moments
  to every sea state of the record;
* ln T_p | H_s: normal with mean μ(h) = a0 + a1 h^a2 and standard deviation
  σ(h) = b0 + b1 exp(b2 h), the parameters fitted by virocon to the per-interval estimates
  (0.5 m wide H_s intervals).

IFORM contour (Haver & Winterstein 2009; Winterstein et al. 1993): for a return period R and
sea-state duration Δt the exceedance probability of one sea state is α = Δt/R and the contour
is the image of the circle of radius β = Φ⁻¹(1 − α) in standard normal space through the
Rosenblatt transformation, H_s = F⁻¹(Φ(u1)), T_p = exp(μ(H_s) + σ(H_s) u2). Every sea state
of the record counts as independent: the contour's highest H_s is above the POT return level
of the storm peaks (serial correlation, Haver & Winterstein 2009 §3); the table uses the POT
value for H_s and the joint model only for the T_p that goes with it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special

from onbottom._validate import in_range, integer, positive
from onbottom.errors import InputError

__all__ = ["JointModel", "fit_joint_model", "iform_contour", "iform_contour_closed_form"]


def _power3(x, a, b, c):
    return a + b * x**c


def _exp3(x, a, b, c):
    return a + b * np.exp(c * x)


@dataclass(frozen=True, kw_only=True, slots=True)
class JointModel:
    """A fitted (or given) Weibull H_s – log-normal T_p|H_s model.

    Parameters
    ----------
    hs_scale, hs_shape, hs_location : float
        Weibull α [m] (> 0), β [-] (> 0), γ [m] (≥ 0) of H_s.
    mu : tuple of float
        (a0, a1, a2) of μ(h) = a0 + a1 h^a2, the mean of ln T_p (T_p in s, h in m).
    sigma : tuple of float
        (b0, b1, b2) of σ(h) = b0 + b1 exp(b2 h), the standard deviation of ln T_p.
    n_states : int
        Sea states it was fitted to (0 for a given model).
    """

    hs_scale: float
    hs_shape: float
    hs_location: float
    mu: tuple[float, float, float]
    sigma: tuple[float, float, float]
    n_states: int = 0

    def __post_init__(self) -> None:
        positive("JointModel.hs_scale", self.hs_scale)
        positive("JointModel.hs_shape", self.hs_shape)
        in_range("JointModel.hs_location", self.hs_location, -1.0, 30.0)
        if len(self.mu) != 3 or len(self.sigma) != 3:
            raise InputError("JointModel.mu/sigma is invalid: three coefficients each")

    def tp_mu(self, hs: np.ndarray | float) -> np.ndarray:
        """μ(h), mean of ln T_p given H_s = h [m]."""
        return _power3(np.asarray(hs, dtype=float), *self.mu)

    def tp_sigma(self, hs: np.ndarray | float) -> np.ndarray:
        """σ(h), standard deviation of ln T_p given H_s = h [m]."""
        return _exp3(np.asarray(hs, dtype=float), *self.sigma)

    def tp_quantile(self, hs: np.ndarray | float, p: float = 0.5) -> np.ndarray:
        """T_p [s] with non-exceedance probability ``p`` given H_s [m] (p = 0.5: median)."""
        return np.exp(self.tp_mu(hs) + self.tp_sigma(hs) * special.ndtri(p))

    def hs_quantile(self, p: np.ndarray | float) -> np.ndarray:
        """H_s [m] with non-exceedance probability ``p`` (marginal Weibull)."""
        q = np.asarray(p, dtype=float)
        return self.hs_location + self.hs_scale * np.power(-np.log1p(-q), 1.0 / self.hs_shape)

    def virocon(self):
        """The model as a virocon ``GlobalHierarchicalModel`` with these parameters."""
        from virocon import GlobalHierarchicalModel, LogNormalDistribution, WeibullDistribution

        a0, a1, a2 = self.mu
        b0, b1, b2 = self.sigma
        dists = [
            {
                "distribution": WeibullDistribution(
                    alpha=self.hs_scale, beta=self.hs_shape, gamma=self.hs_location
                )
            },
            {
                "distribution": LogNormalDistribution(),
                "conditional_on": 0,
                "parameters": {
                    # plain callables: virocon takes them as given (not fitted) dependences
                    "mu": lambda x: _power3(x, a0, a1, a2),
                    "sigma": lambda x: _exp3(x, b0, b1, b2),
                },
            },
        ]
        return GlobalHierarchicalModel(dists)

    def as_dict(self) -> dict:
        """Parameters as plain numbers (provenance)."""
        return {
            "model": "DNV-RP-C205 3.6.3: Weibull Hs, lognormal Tp|Hs",
            "hs_scale": self.hs_scale,
            "hs_shape": self.hs_shape,
            "hs_location": self.hs_location,
            "mu": list(self.mu),
            "sigma": list(self.sigma),
            "n_states": self.n_states,
        }


def fit_joint_model(hs: np.ndarray, tp: np.ndarray) -> JointModel:
    """Fit the DNV-RP-C205 §3.6.3 model to sea states with virocon (``get_DNVGL_Hs_Tz``'s
    descriptions: Weibull by moments, 0.5 m H_s intervals, dependence functions by least
    squares).

    Parameters
    ----------
    hs : ndarray
        H_s of every sea state [m].
    tp : ndarray
        T_p of every sea state [s].
    """
    import warnings

    from virocon import GlobalHierarchicalModel, get_DNVGL_Hs_Tz

    h = np.asarray(hs, dtype=float)
    t = np.asarray(tp, dtype=float)
    if h.shape != t.shape or h.ndim != 1 or h.size < 100:
        raise InputError(f"hs, tp = {h.size} sea states is invalid: at least 100, equal lengths")
    dist, fit, _ = get_DNVGL_Hs_Tz()
    model = GlobalHierarchicalModel(dist)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # scipy's optimiser in virocon's fit
        model.fit(np.column_stack([h, t]), fit)
    w = model.distributions[0].parameters
    cp = model.distributions[1].conditional_parameters
    mu = cp["mu"].parameters
    sg = cp["sigma"].parameters
    return JointModel(
        hs_scale=float(w["alpha"]),
        hs_shape=float(w["beta"]),
        hs_location=float(w["gamma"]),
        mu=(float(mu["a"]), float(mu["b"]), float(mu["c"])),
        sigma=(float(sg["a"]), float(sg["b"]), float(sg["c"])),
        n_states=int(h.size),
    )


def marginal_tail_check(
    model: JointModel,
    hs: np.ndarray,
    return_period: float,
    state_hours: float,
    pot_value: float,
) -> dict:
    """The H_s marginal's tail against the data, and why the contour and the POT value differ.

    Returns a dict: ``levels`` — for the empirical exceedance probabilities 1e-2, 1e-3, 1e-4 of
    a sea state and the record maximum, the H_s level [m], its empirical and its fitted
    exceedance probability (moment-fitted Weibull); ``contour_max_hs`` [m] of the
    ``return_period`` IFORM contour, ``alpha`` (its exceedance probability per sea state),
    ``pot_value`` [m] and ``ratio`` contour / POT; ``mle_contour_max_hs`` [m]: the same contour
    with a 3-parameter maximum-likelihood Weibull (scipy) for comparison, and ``mle_levels``
    (its fitted exceedances at the same levels).

    Parameters
    ----------
    model : JointModel
        The fitted joint model.
    hs : ndarray
        The observed sea states' H_s [m].
    return_period : float
        R [years].
    state_hours : float
        Sea-state duration [h].
    pot_value : float
        The storm-based (POT) R-year H_s [m].
    """
    from scipy import stats

    h = np.asarray(hs, dtype=float)
    h = h[np.isfinite(h)]
    a = _alpha(return_period, state_hours)
    beta = -float(special.ndtri(a))
    levels = [float(np.quantile(h, 1.0 - q)) for q in (1e-2, 1e-3, 1e-4)] + [float(h.max())]

    def exceed(x, scale, shape, loc):
        return float(np.exp(-((max(x - loc, 0.0) / scale) ** shape)))

    top = float(model.hs_quantile(special.ndtr(beta)))
    c, loc, sc = stats.weibull_min.fit(
        h, model.hs_shape, loc=min(model.hs_location, float(h.min()) - 1e-3), scale=model.hs_scale
    )
    mle_top = float(loc + sc * (-math.log(special.ndtr(-beta))) ** (1.0 / c))
    return {
        "levels": [
            {
                "hs": x,
                "empirical": float(np.mean(h > x)),
                "fitted": exceed(x, model.hs_scale, model.hs_shape, model.hs_location),
                "mle": exceed(x, sc, c, loc),
            }
            for x in levels
        ],
        "return_period": float(return_period),
        "alpha": a,
        "contour_max_hs": top,
        "pot_value": float(pot_value),
        "ratio": top / pot_value if pot_value > 0 else math.nan,
        "mle_contour_max_hs": mle_top,
        "mle": {"scale": float(sc), "shape": float(c), "location": float(loc)},
    }


def tp_at_peaks_check(model: JointModel, hs: np.ndarray, tp: np.ndarray) -> dict:
    """T_p | H_s checked on storm peaks: the probability integral transform
    z = (ln T_p − μ(H_s))/σ(H_s) of each peak's sea state is standard normal if the model holds
    there. Returns ``n``, ``mean_z`` (> 0: the model's T_p too short at the peaks, < 0: too
    long), ``std_z`` and the Kolmogorov–Smirnov distance and p-value of Φ(z) against U(0, 1).

    Parameters
    ----------
    model : JointModel
        The joint model.
    hs, tp : ndarray
        H_s [m] and T_p [s] of the storm peaks.
    """
    from scipy import stats

    h = np.asarray(hs, dtype=float)
    t = np.asarray(tp, dtype=float)
    ok = np.isfinite(h) & np.isfinite(t) & (t > 0)
    z = (np.log(t[ok]) - model.tp_mu(h[ok])) / model.tp_sigma(h[ok])
    if z.size < 3:
        return {"n": int(z.size), "mean_z": math.nan, "std_z": math.nan, "ks": math.nan,
                "ks_p": math.nan}  # fmt: skip
    ks = stats.kstest(special.ndtr(z), "uniform")
    return {
        "n": int(z.size),
        "mean_z": float(z.mean()),
        "std_z": float(z.std(ddof=1)),
        "ks": float(ks.statistic),
        "ks_p": float(ks.pvalue),
    }


def _alpha(return_period: float, state_hours: float) -> float:
    positive("return_period", return_period)
    positive("state_hours", state_hours)
    return state_hours / (return_period * 365.2425 * 24.0)


def iform_contour(
    model: JointModel, return_period: float, state_hours: float, n_points: int = 180
) -> tuple[np.ndarray, np.ndarray]:
    """IFORM contour of ``model`` by virocon's ``IFORMContour``.

    Parameters
    ----------
    model : JointModel
        The joint model.
    return_period : float
        R [years].
    state_hours : float
        Sea-state duration Δt [h] (the record's step).
    n_points : int
        Points on the contour, in [8, 3600].

    Returns
    -------
    (hs [m], tp [s]) arrays of the contour points.
    """
    from virocon import IFORMContour

    n = integer("n_points", n_points, 8, 3600)
    c = IFORMContour(model.virocon(), _alpha(return_period, state_hours), n_points=n)
    xy = np.asarray(c.coordinates, dtype=float)
    return xy[:, 0], xy[:, 1]


def iform_contour_closed_form(
    model: JointModel, return_period: float, state_hours: float, n_points: int = 180
) -> tuple[np.ndarray, np.ndarray]:
    """The same contour written out (verification twin of :func:`iform_contour`): angles
    θ_i = 2πi/n, u = β(cos θ, sin θ), β = Φ⁻¹(1 − Δt/R)."""
    n = integer("n_points", n_points, 8, 3600)
    beta = -special.ndtri(_alpha(return_period, state_hours))
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    u1, u2 = beta * np.cos(th), beta * np.sin(th)
    hs = model.hs_quantile(special.ndtr(u1))
    tp = np.exp(model.tp_mu(hs) + model.tp_sigma(hs) * u2)
    return hs, tp
