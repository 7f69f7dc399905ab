"""Response-based design along an environmental contour, against F109's return-period storm.

1. The IFORM contour of the joint H_s–T_p model for the return period R and a sea-state
   duration equal to the storm's peak (α = Δt/R; :func:`onbottom.metocean.joint.iform_contour`);
   its points with H_s at or above ``upper_fraction`` of the contour's highest H_s (where the
   response lives) are run with ``seeds`` storms each, soil and current at the case's values
   (the inputs' means when they are uncertain) — or, when the current comes from the
   hindcast's joint model, the median current given each point's H_s (the F109 storm of step
   4 likewise).
2. The ``top_points`` points with the highest mean maximum displacement are rerun with
   ``top_seeds`` storms (the seeds of step 1 are reused: only new seeds run).
3. The design displacement is the ``fractile`` of the maximum displacement over the seeds at
   the governing point (the highest fractile among the top points): the short-term
   variability of the storm, which the contour (built from the sea-state variables only)
   omits, is kept by a fractile above the median (Winterstein et al. 1993; Haver &
   Winterstein 2009 recommend the 90 % fractile in the absence of an omission factor).
4. The F109 return-period approach on the same case: the R-year storm-peak H_s (the POT
   return value of ``onbottom metocean``) with its median T_p, run with ``top_seeds`` storms;
   its mean and fractile of the maximum displacement.

All runs go through a :class:`~onbottom.reliability.campaign.Campaign` (resumable).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from onbottom._validate import in_range, integer
from onbottom.reliability.campaign import Campaign

__all__ = ["ResponseDesignResult", "response_based_design"]


@dataclass(frozen=True)
class ResponseDesignResult:
    """Result of :func:`response_based_design` (displacements in m)."""

    return_period: float
    fractile: float
    points: list[dict[str, Any]] = field(default_factory=list)
    governing: dict[str, Any] = field(default_factory=dict)
    design_displacement: float = math.nan
    f109: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "return_period": self.return_period,
            "fractile": self.fractile,
            "points": self.points,
            "governing": self.governing,
            "design_displacement": self.design_displacement,
            "f109": self.f109,
        }


def _stats(y: np.ndarray, q: float) -> dict[str, float]:
    y = y[np.isfinite(y)]
    if not y.size:
        return {"mean": math.nan, "median": math.nan, "fractile": math.nan, "n": 0}
    return {
        "mean": float(y.mean()),
        "median": float(np.median(y)),
        "fractile": float(np.quantile(y, q)),
        "max": float(y.max()),
        "n": int(y.size),
    }


def response_based_design(
    campaign: Campaign,
    base_row: dict[str, float],
    contour: tuple[np.ndarray, np.ndarray],
    f109_sea_state: tuple[float, float],
    *,
    return_period: float,
    seeds: int = 2,
    top_points: int = 2,
    top_seeds: int = 8,
    fractile: float = 0.9,
    upper_fraction: float = 0.6,
    current_given_hs: Callable[[float], float] | None = None,
) -> ResponseDesignResult:
    """Steps 1–4 of the module docstring.

    Parameters
    ----------
    campaign : Campaign
        Over a :class:`~onbottom.reliability.storm_model.StormModel` whose inputs start with
        ``hs``, ``tp``.
    base_row : dict
        Values of the model's other inputs (the case's or the means).
    contour : (hs [m], tp [s]) arrays
        The IFORM contour.
    f109_sea_state : (hs [m], tp [s])
        F109's R-year sea state.
    return_period : float
        R [years].
    seeds, top_points, top_seeds : int
        Seeds per contour point, points rerun, seeds there (>= 1).
    fractile : float
        Fractile of the design displacement, in (0, 1).
    upper_fraction : float
        Points with H_s >= this share of the contour's highest H_s are run, in (0, 1].
    current_given_hs : callable or None
        H_s [m] → the current speed [m/s] that goes with it (the median of the hindcast's
        U | H_s): sets the model's ``current_velocity`` input at each point and at F109's sea
        state. None: the current is in ``base_row`` (or the case's).
    """
    names = campaign.model.input_names
    k = campaign.model.output_names.index("max_displacement")
    n1 = integer("seeds", seeds, 1, 1000)
    ntop = integer("top_points", top_points, 1, 360)
    n2 = integer("top_seeds", top_seeds, 1, 10000)
    in_range("fractile", fractile, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    in_range("upper_fraction", upper_fraction, 0.0, 1.0, low_inclusive=False)
    hs_c, tp_c = (np.asarray(a, dtype=float) for a in contour)
    keep = np.flatnonzero(hs_c >= upper_fraction * hs_c.max())

    def row(hs: float, tp: float) -> np.ndarray:
        vals = {**base_row, "hs": hs, "tp": tp}
        if current_given_hs is not None:
            vals["current_velocity"] = float(current_given_hs(hs))
        return np.array([vals[n] for n in names], dtype=float)

    def run(hs: float, tp: float, n: int) -> np.ndarray:
        x = np.repeat(row(hs, tp)[None, :], n, axis=0)
        out, _ = campaign.evaluate(x, np.arange(n, dtype=np.int64))
        return out[:, k]

    points = []
    for i in keep:
        y = run(float(hs_c[i]), float(tp_c[i]), n1)
        points.append(
            {"hs": float(hs_c[i]), "tp": float(tp_c[i]), "seeds": n1, **_stats(y, fractile)}
        )
    order = sorted(range(len(points)), key=lambda j: -np.nan_to_num(points[j]["mean"], nan=-1))
    for j in order[:ntop]:
        p = points[j]
        y = run(p["hs"], p["tp"], max(n1, n2))
        p.update({"seeds": max(n1, n2), **_stats(y, fractile)})
    top = [points[j] for j in order[:ntop]]
    gov = max(top, key=lambda p: np.nan_to_num(p["fractile"], nan=-1.0))
    hs_f, tp_f = f109_sea_state
    y_f = run(float(hs_f), float(tp_f), n2)
    return ResponseDesignResult(
        return_period=float(return_period),
        fractile=float(fractile),
        points=points,
        governing=dict(gov),
        design_displacement=float(gov["fractile"]),
        f109={"hs": float(hs_f), "tp": float(tp_f), "seeds": n2, **_stats(y_f, fractile)},
    )
