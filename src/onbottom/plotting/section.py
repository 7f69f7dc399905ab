"""Figures of pipe-section simulations in the paper's figure types (Youssef & Cassidy 2014).

* w–u: penetration (vertical displacement) against horizontal displacement (Figs 9c, 11a–17a);
* H–u: horizontal load against horizontal displacement (Figs 9b, 11b–17b);
* V–H: the load path in the V–H plane (Figs 4, 9a);
* w and u against load cycles.

The figure types and axis labels keep the paper's names, u for the lateral displacement and
w for the penetration; the datasets call them ``y`` and ``z`` (``docs/conventions.md``).
Loads are displayed in kN/m; the datasets hold SI values (N/m). Functions take a
:class:`~onbottom.dynamics.section.SectionResult` or its dataset and return Axes / Figure.
"""

from __future__ import annotations

from typing import Any

import matplotlib

matplotlib.use("Agg", force=False)
import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

__all__ = [
    "PAPER_AXES",
    "plot_load_displacement",
    "plot_load_path",
    "plot_penetration_path",
    "plot_section_result",
    "plot_time_histories",
    "reproduction_figure",
]

PAPER_AXES: dict[str, dict[str, tuple[float, float]]] = {
    "inclined": {"z": (0.0, 0.12), "y": (-1.0, 4.0), "H": (-4.0, 4.0), "V": (0.0, 45.0)},
    "regular": {"z": (-0.03, 0.15), "y": (-1.0, 5.0), "H": (-8.0, 10.0), "V": (0.0, 45.0)},
    "irregular": {"z": (-0.1, 0.15), "y": (-0.5, 4.5), "H": (-8.0, 10.0), "V": (0.0, 45.0)},
}
"""Axis ranges of the paper's figures (z, y in m; H, V in kN/m), widened to fit the data.

The paper (and these figures' axis labels) writes u for the lateral displacement (the
results' ``y``) and w for the penetration (``z``): ``docs/conventions.md``."""

_KN = 1.0e-3


def _ds(result: Any) -> xr.Dataset:
    return result.data if hasattr(result, "data") else result


def _ax(ax: Axes | None) -> Axes:
    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 3.6))
    return ax


def _fit(lim: tuple[float, float] | None, data: np.ndarray, pad: float = 0.05):
    lo, hi = float(np.nanmin(data)), float(np.nanmax(data))
    if lim is not None:
        lo, hi = min(lo, lim[0]), max(hi, lim[1])
    span = hi - lo if hi > lo else 1.0
    if lim is not None and lo >= lim[0] and hi <= lim[1]:
        return lim
    return lo - pad * span, hi + pad * span


def plot_penetration_path(
    result: Any, ax: Axes | None = None, *, axes: str | None = "inclined", label: str = "model"
) -> Axes:
    """w–u (the paper's names): penetration ``z`` [m] against lateral displacement ``y`` [m]."""
    ds = _ds(result)
    ax = _ax(ax)
    ax.plot(ds["y"].values, ds["z"].values, lw=0.9, label=label)
    lim = PAPER_AXES.get(axes or "", {})
    ax.set_xlim(*_fit(lim.get("y"), ds["y"].values))
    ax.set_ylim(*_fit(lim.get("z"), ds["z"].values))
    ax.set_xlabel("Horizontal disp., u (m)")
    ax.set_ylabel("Vertical disp. (penetration), w (m)")
    ax.grid(alpha=0.3)
    return ax


def plot_load_displacement(
    result: Any, ax: Axes | None = None, *, axes: str | None = "inclined", label: str = "model"
) -> Axes:
    """H–u (the paper's names): horizontal load H [kN/m] against lateral displacement ``y`` [m]."""
    ds = _ds(result)
    ax = _ax(ax)
    h = ds["H"].values * _KN
    ax.plot(ds["y"].values, h, lw=0.9, label=label)
    lim = PAPER_AXES.get(axes or "", {})
    ax.set_xlim(*_fit(lim.get("y"), ds["y"].values))
    ax.set_ylim(*_fit(lim.get("H"), h))
    ax.set_xlabel("Horizontal disp., u (m)")
    ax.set_ylabel("Horizontal load, H (kN/m)")
    ax.grid(alpha=0.3)
    return ax


def plot_load_path(
    result: Any,
    ax: Axes | None = None,
    *,
    axes: str | None = "inclined",
    installation_load: float | None = None,
) -> Axes:
    """V–H: the applied load path, H [kN/m] against V [kN/m] (paper Fig. 9a).

    ``installation_load`` [N/m] marks V_peak (the preceding vertical penetration step).
    """
    ds = _ds(result)
    ax = _ax(ax)
    h = ds["H"].values * _KN
    v = ds["V"].values * _KN
    ax.plot(v, h, lw=0.8, label="load path")
    if installation_load is not None:
        ax.plot([installation_load * _KN, v[0]], [0.0, 0.0], "k--", lw=0.8, label="V_peak → V_i")
        ax.plot([installation_load * _KN], [0.0], "kv")
    lim = PAPER_AXES.get(axes or "", {})
    ax.set_xlim(*_fit(lim.get("V"), v))
    ax.set_ylim(*_fit(lim.get("H"), h))
    ax.set_xlabel("Vertical load, V (kN/m)")
    ax.set_ylabel("Horizontal load, H (kN/m)")
    ax.grid(alpha=0.3)
    return ax


def plot_time_histories(
    result: Any, axs: tuple[Axes, Axes] | None = None, *, cycle_period: float | None = None
) -> tuple[Axes, Axes]:
    """``y`` and ``z`` (the paper's u and w) against time, or cycles given ``cycle_period`` [s]."""
    ds = _ds(result)
    if axs is None:
        _, axs = plt.subplots(2, 1, sharex=True, figsize=(5.0, 4.0))
    x = ds["time"].values
    xlabel = "Time (s)"
    if cycle_period:
        x = x / cycle_period
        xlabel = "Load cycles"
    axs[0].plot(x, ds["y"].values, lw=0.9)
    axs[0].set_ylabel("u (m)")
    axs[1].plot(x, ds["z"].values, lw=0.9)
    axs[1].set_ylabel("w (m)")
    axs[1].set_xlabel(xlabel)
    for a in axs:
        a.grid(alpha=0.3)
    return axs


def plot_section_result(
    result: Any,
    *,
    title: str | None = None,
    kind: str = "inclined",
    installation_load: float | None = None,
    cycle_period: float | None = None,
    displacement_limit: float | None = None,
) -> Figure:
    """One figure per test: (a) V–H load path, (b) H–u, (c) w–u, (d) u and w vs cycles.

    Parameters
    ----------
    result : SectionResult or xarray.Dataset
        The simulation.
    title : str or None
        Figure title.
    kind : {"inclined", "regular", "irregular"}
        Selects the paper's axis ranges (:data:`PAPER_AXES`).
    installation_load : float or None
        V_peak [N/m], drawn on the load path.
    cycle_period : float or None
        [s]; the time panel is drawn in load cycles if given.
    displacement_limit : float or None
        [m]; drawn as a dashed line on the u panels.
    """
    fig = plt.figure(figsize=(10.0, 7.2), layout="constrained")
    gs = fig.add_gridspec(2, 2)
    ax_a = fig.add_subplot(gs[0, 0])
    ax_b = fig.add_subplot(gs[0, 1])
    ax_c = fig.add_subplot(gs[1, 0])
    sub = gs[1, 1].subgridspec(2, 1, hspace=0.05)
    ax_d1 = fig.add_subplot(sub[0])
    ax_d2 = fig.add_subplot(sub[1], sharex=ax_d1)
    plot_load_path(result, ax_a, axes=kind, installation_load=installation_load)
    plot_load_displacement(result, ax_b, axes=kind)
    plot_penetration_path(result, ax_c, axes=kind)
    plot_time_histories(result, (ax_d1, ax_d2), cycle_period=cycle_period)
    if displacement_limit is not None:
        for a in (ax_b, ax_c):
            a.axvline(displacement_limit, color="k", ls="--", lw=0.7)
        ax_d1.axhline(displacement_limit, color="k", ls="--", lw=0.7)
    for a, tag in zip((ax_a, ax_b, ax_c, ax_d1), "abcd", strict=True):
        a.set_title(f"{tag}-", loc="left", fontsize=9)
    if title:
        fig.suptitle(title)
    return fig


def reproduction_figure(row: Any, result: Any) -> Figure:
    """Figure of one run of the Youssef & Cassidy reproduction (onbottom.study.youssef_cassidy).

    ``row`` is a ``ReproductionRow`` (test, parameter set, A, B, C, μ, γ'); ``result`` its
    SectionResult. Axis ranges follow the paper's figure for the test's kind.
    """
    attrs = result.data.attrs
    name = str(row.test)
    kind = "regular" if name == "Regular" else "irregular" if name == "Irregular" else "inclined"
    cp = attrs.get("cycle_period")
    lim = attrs.get("displacement_limit")
    return plot_section_result(
        result,
        title=f"{name} — {row.parameter_set} (A={row.A:g}, B={row.B:g}, C={row.C:g},"
        f" μ={row.mu:g}, γ'={row.gamma_kn:g} kN/m³)",
        kind=kind,
        installation_load=float(attrs["installation_load"]),
        cycle_period=float(cp) if isinstance(cp, (int, float)) else None,
        displacement_limit=float(lim) if isinstance(lim, (int, float)) else None,
    )
