"""Calibration figures: measured vs simulated responses, misfit maps and slices.

Functions take records/results and return matplotlib objects; they never show or save.
Figures are built with :class:`matplotlib.figure.Figure` (no pyplot state, any backend).
Penetration w is drawn positive downwards (inverted axis), as in Youssef & Cassidy (2014),
Figs 12–17.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

__all__ = ["plot_fit", "plot_misfit_map", "plot_misfit_slices"]


def _as_ds(obj: Any) -> xr.Dataset:
    if isinstance(obj, xr.Dataset):
        return obj
    data = getattr(obj, "data", None)
    if isinstance(data, xr.Dataset):
        return data
    raise TypeError("expected an xarray.Dataset, a TestRecord or a result with .data")


def _w(ds: xr.Dataset) -> np.ndarray:
    return np.asarray(ds["z"])


def plot_fit(
    record: Any,
    simulated: Any | Sequence[Any] | None = None,
    *,
    labels: Sequence[str] | None = None,
    title: str | None = None,
) -> Figure:
    """Measured vs simulated: penetration–displacement (z–y) and displacement–time (y–t).

    Parameters
    ----------
    record : TestRecord or xarray.Dataset
        The measured test (``time`` [s], ``y`` [m], ``z`` [m]).
    simulated : Dataset/result, sequence of them, or None
        Simulations to overlay.
    labels : sequence of str or None
        Legend labels of the simulations.
    title : str or None
        Figure title (default: the record's name).
    """
    meas = _as_ds(record)
    sims = (
        []
        if simulated is None
        else (list(simulated) if isinstance(simulated, (list, tuple)) else [simulated])
    )
    labels = (
        list(labels)
        if labels is not None
        else ["simulated" if len(sims) == 1 else f"simulated {i + 1}" for i in range(len(sims))]
    )
    fig = Figure(figsize=(10.0, 4.0), layout="constrained")
    ax_wu, ax_ut = fig.subplots(1, 2)
    ax_wu.plot(meas["y"], _w(meas), "k-", lw=1.0, label="measured")
    ax_ut.plot(meas["time"], meas["y"], "k-", lw=1.0, label="measured")
    for sim, lab in zip(sims, labels, strict=True):
        ds = _as_ds(sim)
        ax_wu.plot(ds["y"], _w(ds), lw=1.0, label=lab)
        ax_ut.plot(ds["time"], ds["y"], lw=1.0, label=lab)
    limit = getattr(record, "displacement_limit", None)
    if limit is not None:
        for ax, kw in ((ax_wu, "axvline"), (ax_ut, "axhline")):
            getattr(ax, kw)(limit, color="grey", ls=":", lw=0.8, label="displacement limit")
    ax_wu.set_xlabel("lateral displacement y [m]")
    ax_wu.set_ylabel("penetration z [m]")
    ax_wu.invert_yaxis()
    ax_ut.set_xlabel("time t [s]")
    ax_ut.set_ylabel("lateral displacement y [m]")
    for ax in (ax_wu, ax_ut):
        ax.grid(True, lw=0.3)
        ax.legend(fontsize="small")
    fig.suptitle(title if title is not None else getattr(record, "name", ""))
    return fig


def plot_misfit_map(
    ds: xr.Dataset,
    x: str,
    y: str,
    *,
    var: str = "misfit",
    ax: Axes | None = None,
    log: bool = True,
    truth: Mapping[str, float] | None = None,
) -> Axes:
    """Colour map of a 2-D sweep of the misfit (other dimensions: their minimum).

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`onbottom.calibration.fit.grid_search` or
        :func:`onbottom.study.sweep.sweep`.
    x, y : str
        Swept parameters on the axes.
    var : str
        Variable to map.
    ax : Axes or None
        Axes to draw in (new figure if None).
    log : bool
        Logarithmic colour scale.
    truth : mapping or None
        Known parameter values to mark (synthetic tests).
    """
    da = ds[var]
    other = [d for d in da.dims if d not in (x, y)]
    if other:
        da = da.min(dim=other)
    da = da.transpose(y, x)
    if ax is None:
        ax = Figure(figsize=(5.5, 4.5), layout="constrained").subplots()
    values = np.asarray(da, dtype=float)
    finite = values[np.isfinite(values) & (values > 0)]
    norm = LogNorm(vmin=finite.min(), vmax=finite.max()) if log and finite.size else None
    mesh = ax.pcolormesh(ds[x], ds[y], values, shading="nearest", norm=norm, cmap="viridis_r")
    ax.figure.colorbar(mesh, ax=ax, label=da.attrs.get("long_name", var))
    if np.isfinite(values).any():
        iy, ix = np.unravel_index(np.nanargmin(values), values.shape)
        ax.plot(ds[x].values[ix], ds[y].values[iy], "r*", ms=12, label="minimum")
    if truth is not None and x in truth and y in truth:
        ax.plot(truth[x], truth[y], "wx", ms=10, mew=2, label="truth")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.legend(fontsize="small")
    return ax


def plot_misfit_slices(
    slices: Mapping[str, xr.Dataset], fitted: Mapping[str, float] | None = None
) -> Figure:
    """Misfit along each 1-D slice of :func:`onbottom.calibration.fit.misfit_slices`."""
    n = max(1, len(slices))
    fig = Figure(figsize=(3.2 * n, 3.0), layout="constrained")
    axes = fig.subplots(1, n, squeeze=False)
    for ax, (name, ds) in zip(axes[0], slices.items(), strict=False):
        ax.plot(ds[name], ds["misfit"], "o-", ms=3)
        if fitted is not None and name in fitted:
            ax.axvline(fitted[name], color="r", ls="--", lw=0.8)
        ax.set_xlabel(name)
        ax.set_ylabel("misfit Σr²")
        ax.grid(True, lw=0.3)
    return fig
