"""V–w plots of vertical pipe penetration (DNVGL-RP-F114 curves, measured and DEM data).

Figures are built with :class:`matplotlib.figure.Figure` directly (no pyplot state, no backend
switch), so they render headless (Agg) and can be saved with ``fig.savefig``.
The layout follows the penetration paper's Fig. 5: resistance V (kN/m) on the horizontal axis,
normalised embedment w/D on the vertical axis, increasing downward.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from onbottom.errors import InputError

__all__ = ["overlay_penetration_data", "plot_penetration_curve"]

_KN = 1.0e-3


def _axes(ax: Axes | None) -> tuple[Figure, Axes]:
    if ax is None:
        fig = Figure(figsize=(5.0, 5.5), layout="constrained")
        return fig, fig.add_subplot()
    return ax.figure, ax  # type: ignore[return-value]


def _finish(ax: Axes) -> None:
    ax.set_xlabel("Penetration resistance V (kN/m)")
    ax.set_ylabel("Embedment w/D (-)")
    if not ax.yaxis_inverted():
        ax.invert_yaxis()
    ax.set_xlim(left=0.0)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")


def plot_penetration_curve(
    curve: xr.Dataset,
    *,
    ax: Axes | None = None,
    embedment_z: float | None = None,
    embedment_load: float | None = None,
    label: str | None = None,
) -> tuple[Figure, Axes]:
    """Plot Q_v against z/D with the lower/upper estimates shaded and the embedment marked.

    Parameters
    ----------
    curve : xarray.Dataset
        From :func:`onbottom.soil.penetration_f114.penetration_curve` (``Q_v`` [N/m] on
        coordinate ``z`` [m], optionally ``Q_v_lower``/``Q_v_upper``).
    ax : Axes or None
        Axes to draw on; a new figure if None.
    embedment_z : float or None
        Embedment to mark [m]; default the ``embedment_z`` attribute of ``curve`` if present.
    embedment_load : float or None
        Load at the embedment [N/m] (default attribute ``embedment_load`` times
        ``embedment_lay_factor``).
    label : str or None
        Legend label of the best-estimate curve.

    Returns
    -------
    (Figure, Axes)
    """
    if "Q_v" not in curve or "z" not in curve.coords:
        raise InputError("curve is invalid: expected a Dataset with Q_v on coordinate z")
    d = float(curve.attrs.get("diameter", np.nan))
    zd = curve["z_over_D"].values if "z_over_D" in curve.coords else curve["z"].values / d
    fig, ax = _axes(ax)
    ax.plot(curve["Q_v"].values * _KN, zd, color="C0", lw=2.0, label=label or "F114 estimate")
    if "Q_v_lower" in curve and "Q_v_upper" in curve:
        lo = curve["Q_v_lower"].values * _KN
        up = curve["Q_v_upper"].values * _KN
        ax.fill_betweenx(zd, lo, up, color="C0", alpha=0.15, lw=0.0)
        ax.plot(lo, zd, color="C0", ls="--", lw=1.0, label="lower estimate")
        ax.plot(up, zd, color="C0", ls=":", lw=1.2, label="upper estimate")
    if embedment_z is None and "embedment_z" in curve.attrs:
        embedment_z = float(curve.attrs["embedment_z"])
        if embedment_load is None and "embedment_load" in curve.attrs:
            embedment_load = float(curve.attrs["embedment_load"]) * float(
                curve.attrs.get("embedment_lay_factor", 1.0)
            )
    if embedment_z is not None:
        zmark = embedment_z / d
        ax.axhline(zmark, color="C3", lw=0.8, ls="-.")
        if embedment_load is not None:
            ax.plot(
                [embedment_load * _KN],
                [zmark],
                "o",
                color="C3",
                label=f"embedment z/D = {zmark:.3f}",
            )
    _finish(ax)
    return fig, ax


def overlay_penetration_data(
    ax: Axes,
    w: ArrayLike,
    v: ArrayLike,
    *,
    diameter: float | None = None,
    label: str = "measured",
    **style: Any,
) -> Axes:
    """Overlay a measured or DEM V–w record on penetration axes.

    Parameters
    ----------
    ax : Axes
        Axes from :func:`plot_penetration_curve` (or any V–w/D axes).
    w : array_like
        Embedment of the invert [m]; if ``diameter`` is None, already normalised w/D [-].
    v : array_like
        Vertical resistance [N/m], same length as ``w`` (prototype scale for centrifuge data).
    diameter : float or None
        D [m] used to normalise ``w``.
    label : str
        Legend label.
    **style
        Passed to ``Axes.plot`` (color, ls, marker, ...).

    Returns
    -------
    Axes
    """
    wa = np.asarray(w, dtype=float).ravel()
    va = np.asarray(v, dtype=float).ravel()
    if wa.shape != va.shape:
        raise InputError(
            f"w and v are invalid: lengths {wa.size} and {va.size} differ (must be equal)"
        )
    if diameter is not None:
        if not diameter > 0.0:
            raise InputError(f"diameter = {diameter!r} is invalid: must be > 0")
        wa = wa / diameter
    style.setdefault("lw", 1.0)
    ax.plot(va * _KN, wa, label=label, **style)
    _finish(ax)
    return ax
