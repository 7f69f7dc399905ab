"""Figures of a pipe section in a storm and of stability curves.

* :func:`plot_storm_result` — displacement y/D and penetration z/D against time, hydrodynamic
  load H against displacement, and the V–H path (contact force against horizontal load)
  coloured by time; the F109 limits 0.5D and 10D are drawn where they fall in range.
* :func:`plot_stability_curves` — L/(2 + M)² against K, one line per M (the form of the
  DNV-RP-F109 generalized-stability tables), for L_stable and L_10.

Loads in kN/m; datasets hold SI values.
"""

from __future__ import annotations

from typing import Any

import matplotlib

matplotlib.use("Agg", force=False)
import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.figure import Figure

__all__ = ["plot_stability_curves", "plot_storm_result"]

_KN = 1.0e-3


def plot_storm_result(result: Any, *, title: str | None = None) -> Figure:
    """Four panels of a :class:`~onbottom.dynamics.storm_section.StormSectionResult`."""
    ds: xr.Dataset = result.data if hasattr(result, "data") else result
    if ds is None:
        raise ValueError("the result has no records (run with record_interval set)")
    d = float(ds.attrs.get("diameter", getattr(result, "diameter", 1.0)))
    t_h = ds["time"].values / 3600.0
    fig, axes = plt.subplots(2, 2, figsize=(10.0, 7.0), layout="constrained")
    ax = axes[0, 0]
    ax.plot(t_h, ds["y"].values / d, lw=0.8)
    ymax = float(np.nanmax(np.abs(ds["y"].values))) / d
    for lim, style in ((0.5, "--"), (10.0, ":")):
        if ymax >= 0.3 * lim:
            ax.axhline(lim, color="r", ls=style, lw=0.8, label=f"{lim:g}D")
            ax.axhline(-lim, color="r", ls=style, lw=0.8)
    ax.set_xlabel("time [h]")
    ax.set_ylabel("lateral displacement y/D [-]")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize=8)
    ax = axes[0, 1]
    ax.plot(t_h, ds["z"].values / d, lw=0.8, color="C1")
    ax.set_xlabel("time [h]")
    ax.set_ylabel("penetration z/D [-]")
    ax = axes[1, 0]
    ax.plot(ds["y"].values / d, ds["F_hydro"].values * _KN, lw=0.5, color="C2")
    ax.set_xlabel("y/D [-]")
    ax.set_ylabel("hydrodynamic load H [kN/m]")
    ax = axes[1, 1]
    sc = ax.scatter(
        ds["F_hydro"].values * _KN,
        ds["V"].values * _KN,
        c=t_h,
        s=1.5,
        cmap="viridis",
        rasterized=True,
    )
    ax.set_xlabel("hydrodynamic load H [kN/m]")
    ax.set_ylabel("contact force V = w_s − F_Z [kN/m]")
    fig.colorbar(sc, ax=ax, label="time [h]")
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def plot_stability_curves(curves: xr.Dataset, *, title: str | None = None) -> Figure:
    """L/(2 + M)² against K, one line per M, one panel per soil (rows) and criterion (columns).

    ``curves`` is the dataset of :func:`onbottom.study.stability_curves.stability_curves`
    (variables ``L_stable`` and ``L_10`` over dimensions soil, N, M, K). Points whose storms
    left the soil model's range (``<criterion>_out_of_range`` = 1) are drawn as open markers
    with a red edge ("outside soil model range" in the legend). Where the dataset holds the
    per-seed statistic, L is its fractile (lines) and the median of the per-seed L is drawn
    as small crosses of the same colour ("median over the seeds").
    """
    soils = [str(s) for s in curves["soil"].values]
    crits = [c for c in ("L_stable", "L_10") if c in curves]
    n_values = curves["N"].values
    fig, axes = plt.subplots(
        len(soils),
        len(crits),
        figsize=(5.0 * len(crits), 3.6 * len(soils)),
        squeeze=False,
        layout="constrained",
    )
    for i, soil in enumerate(soils):
        for j, crit in enumerate(crits):
            ax = axes[i, j]
            marked = False
            median_shown = False
            for kn, n in enumerate(n_values):
                for km, m in enumerate(curves["M"].values):
                    y = curves[crit].sel(soil=soil, N=n, M=m).values / (2.0 + m) ** 2
                    label = f"M = {m:g}" + (f", N = {n:g}" if len(n_values) > 1 else "")
                    ax.plot(
                        curves["K"].values,
                        y,
                        marker="o",
                        ms=3,
                        color=f"C{km}",
                        ls=("-", "--", ":", "-.")[kn % 4],
                        label=label,
                    )
                    if f"{crit}_median" in curves:
                        med = curves[f"{crit}_median"].sel(soil=soil, N=n, M=m).values
                        ax.plot(
                            curves["K"].values,
                            med / (2.0 + m) ** 2,
                            ls="none",
                            marker="x",
                            ms=4,
                            color=f"C{km}",
                            label=None if median_shown else "median over the seeds",
                        )
                        median_shown = True
                    flag = f"{crit}_out_of_range"
                    if flag in curves:
                        out = curves[flag].sel(soil=soil, N=n, M=m).values == 1
                        if out.any():
                            ax.plot(
                                curves["K"].values[out],
                                y[out],
                                ls="none",
                                marker="o",
                                ms=7,
                                mfc="white",
                                mec="red",
                                mew=1.2,
                                label=None if marked else "outside soil model range",
                            )
                            marked = True
            ax.set_xscale("log")
            ax.set_xlabel("K = U_s T_u / D [-]")
            ax.set_ylabel(f"{crit} / (2 + M)² [-]")
            ax.set_title(f"{soil}: {crit} ({'0.5D' if crit == 'L_stable' else '10D'})", fontsize=9)
            ax.grid(True, which="both", lw=0.3)
            ax.legend(fontsize=7)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def plot_curves_against_m(
    sweeps: dict[str, xr.Dataset], *, criterion: str = "L_stable", n_value: float | None = None
) -> Figure:
    """L/(2 + M)² against M, one line per K and one line style per sweep (force model), one
    panel per soil.

    The form in which DNV-RP-F109's generalized method is usually discussed: at K >= 10 L rises
    with M to a peak near M ≈ 0.8–1 and settles toward a current-dominated value; at low M it
    falls as K grows. ``sweeps`` maps a label (e.g. the force model) to a curve dataset of
    :func:`onbottom.study.stability_curves.stability_curves`; ``n_value`` picks N (default the
    first). Points outside the soil model's range: open red markers.
    """
    first = next(iter(sweeps.values()))
    soils = [str(s) for s in first["soil"].values]
    n = float(first["N"].values[0]) if n_value is None else float(n_value)
    fig, axes = plt.subplots(
        1, len(soils), figsize=(5.2 * len(soils), 3.8), squeeze=False, layout="constrained"
    )
    styles = ("-", "--", ":", "-.")
    for i, soil in enumerate(soils):
        ax = axes[0, i]
        for s_idx, (label, ds) in enumerate(sweeps.items()):
            if criterion not in ds:
                continue
            m = ds["M"].values
            for k_idx, k in enumerate(ds["K"].values):
                y = ds[criterion].sel(soil=soil, N=n, K=k).values / (2.0 + m) ** 2
                ax.plot(
                    m,
                    y,
                    marker="o",
                    ms=3,
                    color=f"C{k_idx}",
                    ls=styles[s_idx % 4],
                    label=f"{label}, K = {k:g}",
                )
                flag = f"{criterion}_out_of_range"
                if flag in ds:
                    out = ds[flag].sel(soil=soil, N=n, K=k).values == 1
                    if out.any():
                        ax.plot(m[out], y[out], ls="none", marker="o", ms=7, mfc="white",
                                mec="red", mew=1.2)  # fmt: skip
        ax.set_xscale("symlog", linthresh=0.2)
        ax.set_yscale("log")
        ax.set_xlabel("M = V / U_s [-]")
        ax.set_ylabel(f"{criterion} / (2 + M)² [-]  (L = w_s / (½ρ D U_s²))")
        ax.set_title(f"{soil}, N = {n:g}: {criterion}", fontsize=9)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=6, ncol=2)
    return fig
