"""Backbone and penetration-path plots of the trough-based lateral resistance models.

* :func:`plot_backbone` — force–displacement backbone in the style of Verley & Sotberg (1994)
  Fig. 1 / Youssef & Cassidy (2014) Fig. 10: passive envelope through (y1, F_r1), (y2, F_r2),
  (y3, F_r3), Coulomb friction μV and their sum, regions 1–4 marked, both directions.
* :func:`plot_path_response` — resistance and penetration against lateral displacement for a
  displacement path (output of :func:`onbottom.soil.response.path_response`).

Functions return a :class:`matplotlib.figure.Figure` built without pyplot (no global state,
no GUI backend: save it with ``fig.savefig``; it renders with the Agg canvas).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

__all__ = ["backbone_arrays", "plot_backbone", "plot_path_response"]

_REGION_LABELS = ("1 elastic", "2 accumulation", "3 breakout", "4 residual")
_REGION_COLOURS = ("#e8f1fa", "#fdf3e1", "#f9e3e3", "#eeeeee")


def backbone_arrays(points: Mapping[str, float], extent: float = 1.3) -> dict[str, np.ndarray]:
    """Backbone polyline from region limits and forces (both directions about the origin).

    Parameters
    ----------
    points : mapping
        y1, y2, y3 [m], F_r1, F_r2, F_r3, F_f [N/m] (as returned by
        :meth:`onbottom.soil.verley_sotberg.VerleySotberg.backbone_points`).
    extent : float
        The curve runs to ``extent``·y3 on each side.

    Returns
    -------
    dict
        ``y`` [m], ``passive``, ``friction``, ``total`` [N/m] (resistance to motion away from
        the trough centre: positive on both sides).
    """
    y1, y2, y3 = points["y1"], points["y2"], points["y3"]
    f = [0.0, points["F_r1"], points["F_r2"], points["F_r3"], points["F_r3"]]
    yr = np.array([0.0, y1, y2, y3, extent * y3])
    y = np.concatenate([-yr[:0:-1], yr])
    passive = np.concatenate([np.array(f)[:0:-1], f])
    friction = np.full(y.size, points["F_f"])
    return {"y": y, "passive": passive, "friction": friction, "total": passive + friction}


def plot_backbone(
    points: Mapping[str, float],
    *,
    diameter: float | None = None,
    title: str | None = None,
    units_kn: bool = True,
) -> Figure:
    """Force–displacement backbone with regions 1–4 marked (V&S Fig. 1 / Y&C Fig. 10 type).

    Parameters
    ----------
    points : mapping
        Backbone points (see :func:`backbone_arrays`).
    diameter : float or None
        D [m]; if given, the displacement axis is y/D.
    title : str or None
        Axes title.
    units_kn : bool
        Display forces in kN/m (values stay SI in ``points``).
    """
    arr = backbone_arrays(points)
    sx = 1.0 / diameter if diameter else 1.0
    sf = 1.0e-3 if units_kn else 1.0
    unit = "kN/m" if units_kn else "N/m"
    fig = Figure(figsize=(8.0, 6.5), layout="constrained")
    ax_p, ax_t = fig.subplots(2, 1, sharex=True, height_ratios=(3, 2))
    edges = [0.0, points["y1"], points["y2"], points["y3"], arr["y"][-1]]
    for ax in (ax_p, ax_t):
        for side in (1.0, -1.0):
            for i in range(4):
                lo, hi = sorted((side * edges[i] * sx, side * edges[i + 1] * sx))
                ax.axvspan(lo, hi, color=_REGION_COLOURS[i], lw=0)
        ax.axvline(0.0, color="0.5", lw=0.5)
    for i in range(1, 4):
        mid = 0.5 * (edges[i] + edges[i + 1]) * sx
        for x, label in ((mid, _REGION_LABELS[i]), (-mid, str(i + 1))):
            ax_p.text(
                x,
                1.01,
                label,
                transform=ax_p.get_xaxis_transform(),
                ha="center",
                va="bottom",
                fontsize=8,
            )
    ax_p.text(
        0.0,
        1.01,
        "1",
        transform=ax_p.get_xaxis_transform(),
        ha="center",
        va="bottom",
        fontsize=8,
    )
    ax_p.plot(arr["y"] * sx, arr["passive"] * sf, "C3-", lw=2, label="passive F_r")
    for yn, fn in (("y1", "F_r1"), ("y2", "F_r2"), ("y3", "F_r3")):
        for side in (1.0, -1.0):
            ax_p.plot(side * points[yn] * sx, points[fn] * sf, "C3o", ms=4)
        ax_p.annotate(
            f"{fn} = {points[fn] * sf:.4g}",
            (points[yn] * sx, points[fn] * sf),
            textcoords="offset points",
            xytext=(4, 6),
            fontsize=8,
        )
    ax_p.set_ylim(0.0, 1.25 * max(points["F_r2"], points["F_r3"], 1e-12) * sf)
    ax_p.set_ylabel(f"passive resistance F_r [{unit}]")
    ax_t.plot(arr["y"] * sx, arr["total"] * sf, "k-", lw=2, label="total F_h = μV + F_r")
    ax_t.plot(arr["y"] * sx, arr["friction"] * sf, "C0--", lw=1, label="friction μV")
    ax_t.set_ylim(0.0, 1.15 * np.max(arr["total"]) * sf)
    ax_t.set_ylabel(f"resistance [{unit}]")
    ax_t.legend(loc="lower center", fontsize=8)
    ax_t.set_xlabel("lateral displacement from the trough centre, y/D [-]" if diameter else "y [m]")
    if title:
        fig.suptitle(title)
    return fig


def plot_path_response(
    ds: xr.Dataset, *, diameter: float | None = None, units_kn: bool = True
) -> Figure:
    """Resistance and penetration against lateral displacement along a path.

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`onbottom.soil.response.path_response` (y, F_soil, F_passive, z, ...).
    diameter : float or None
        D [m]; if given, y and z are shown as y/D and z/D.
    units_kn : bool
        Display forces in kN/m.
    """
    sx = 1.0 / diameter if diameter else 1.0
    sf = 1.0e-3 if units_kn else 1.0
    u = ds["y"].values * sx
    fig = Figure(figsize=(7.0, 6.5), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    ax1.plot(u, ds["F_soil"].values * sf, "k-", lw=1, label="total R")
    ax1.plot(u, ds["F_passive"].values * sf, "C3-", lw=0.8, label="passive")
    ax1.set_ylabel("soil resistance [kN/m]" if units_kn else "soil resistance [N/m]")
    ax1.axhline(0.0, color="0.5", lw=0.5)
    ax1.legend(fontsize=8)
    ax2.plot(u, ds["z"].values * sx, "C0-", lw=1)
    ax2.invert_yaxis()
    ax2.set_ylabel("penetration z/D [-] (down)" if diameter else "penetration z [m] (down)")
    ax2.set_xlabel("lateral displacement y/D [-]" if diameter else "lateral displacement y [m]")
    model = ds.attrs.get("model", "")
    if model:
        ax1.set_title(f"{model}: response along the displacement path")
    return fig
