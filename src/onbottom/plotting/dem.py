"""Figures of the DEM penetration experiment (the paper's Figs. 5, 7–11).

Every function takes result Datasets (from :func:`onbottom.dem.experiment.penetrate` and
:func:`onbottom.dem.experiment.initial_state`) and returns a matplotlib Figure. Bound curves
(e.g. DNVGL-RP-F114 upper/lower bounds computed by ``onbottom.soil``) are passed as arrays so
that this module needs no soil model.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.patches import Circle

__all__ = [
    "plot_force_chains",
    "plot_initial_state",
    "plot_resistance",
    "plot_resistance_with_bounds",
    "plot_rotation_field",
    "plot_rotation_increment",
    "plot_surface",
    "plot_velocity_field",
]


def _label(ds: xr.Dataset) -> str:
    return str(ds.attrs.get("preset", "DEM"))


def plot_resistance(
    results: xr.Dataset | list[xr.Dataset],
    *,
    prototype: bool = True,
    ax=None,
    reference: dict[str, dict[float, float]] | None = None,
    reference_label: str = "paper (centrifuge)",
) -> Figure:
    """V–w/D curve(s); prototype scale (kN/m) by default, else model scale (N/m).

    ``results`` may be raw runs (every record) or run summaries
    (:func:`onbottom.dem.summary.summarize_run`: bin means drawn as a line, the bin min–max as a
    band). ``reference`` maps a preset name to published points {w/D: V [N/m, prototype]}
    drawn as markers of the same colour (prototype scale only).
    """
    runs = results if isinstance(results, list) else [results]
    if ax is None:
        fig, ax = plt.subplots(figsize=(5, 4))
    else:
        fig = ax.figure
    scale = 1e3 if prototype else 1.0
    for ds in runs:
        if "V_mean" in ds:  # a summary
            key = "V_prototype_" if prototype else "V_"
            w = ds["w_over_D"].values
            (line,) = ax.plot(ds[key + "mean"].values / scale, w, label=_label(ds) + " (bin mean)")
            ax.fill_betweenx(
                w,
                ds[key + "min"].values / scale,
                ds[key + "max"].values / scale,
                color=line.get_color(),
                alpha=0.2,
                lw=0,
            )
        else:
            V = ds["V_prototype"] if prototype else ds["V"]
            (line,) = ax.plot(V.values / scale, ds["w_over_D"].values, label=_label(ds))
        points = (reference or {}).get(_label(ds)) if prototype else None
        if points:
            ws = sorted(points)
            ax.plot(
                [points[k] / scale for k in ws],
                ws,
                "o",
                mfc="none",
                color=line.get_color(),
                label=f"{_label(ds)}: {reference_label}",
            )
    ax.set_xlabel("V [kN/m] (prototype)" if prototype else "V [N/m] (model)")
    ax.set_ylabel("w/D [-]")
    ax.invert_yaxis()
    ax.xaxis.set_label_position("top")
    ax.xaxis.tick_top()
    ax.grid(True, alpha=0.3)
    ax.legend()
    return fig


def plot_resistance_with_bounds(
    results: xr.Dataset | list[xr.Dataset],
    w_over_D: np.ndarray,
    lower: np.ndarray,
    upper: np.ndarray,
    *,
    bound_label: str = "DNVGL-RP-F114",
    reference: dict[str, dict[float, float]] | None = None,
) -> Figure:
    """DEM V–w/D (prototype, kN/m) against lower/upper bound curves.

    Parameters
    ----------
    w_over_D
        Embedment ratios of the bound curves [-].
    lower, upper
        Bound resistances at prototype scale [N/m].
    reference
        Published points by preset, see :func:`plot_resistance`.
    """
    fig = plot_resistance(results, prototype=True, reference=reference)
    ax = fig.axes[0]
    w = np.asarray(w_over_D, float)
    ax.plot(np.asarray(lower) / 1e3, w, "k--", label=f"{bound_label} lower bound")
    ax.plot(np.asarray(upper) / 1e3, w, "k-.", label=f"{bound_label} upper bound")
    ax.fill_betweenx(w, np.asarray(lower) / 1e3, np.asarray(upper) / 1e3, color="0.85", zorder=0)
    # below the axes: with a dense and a medium-dense run no corner of the plot is empty
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.04), ncol=2, fontsize="small")
    return fig


def plot_initial_state(initial: xr.Dataset | list[xr.Dataset], pipe_diameter: float) -> Figure:
    """Porosity, σ_h, σ_v and K0 against depth/D from the measuring circles (paper Fig. 7)."""
    runs = initial if isinstance(initial, list) else [initial]
    fig, axes = plt.subplots(1, 4, figsize=(11, 4), sharey=True)
    for ds in runs:
        z = ds["depth"].values / pipe_diameter
        lab = str(ds.attrs.get("preset", ""))
        axes[0].plot(ds["porosity"].values, z, "o-", label=lab)
        axes[1].plot(ds["sigma_h"].values / 1e3, z, "o-", label=lab)
        axes[2].plot(ds["sigma_v"].values / 1e3, z, "o-", label=lab)
        axes[3].plot(ds["K0"].values, z, "o-", label=lab)
    for a, t in zip(axes, ["porosity n [-]", "σ_h [kPa]", "σ_v [kPa]", "K0 [-]"], strict=True):
        a.set_xlabel(t)
        a.grid(True, alpha=0.3)
    axes[0].set_ylabel("depth / D [-]")
    axes[0].invert_yaxis()
    axes[0].legend()
    return fig


def plot_surface(results: xr.Dataset | list[xr.Dataset]) -> Figure:
    """Soil surface heave (final − initial) against x/D (paper Fig. 8).

    Raw runs: the change of the highest disk top per bin. Summaries: the smoothed heave (thick)
    over the raw change (thin).
    """
    runs = results if isinstance(results, list) else [results]
    fig, ax = plt.subplots(figsize=(7, 3))
    for ds in runs:
        D = float(ds.attrs["pipe_diameter"])
        if "heave" in ds:  # a summary: smoothed heave (pipe footprint blank) over the raw change
            (line,) = ax.plot(ds["x_over_D"].values, ds["heave"].values / D, label=_label(ds))
            raw = (ds["surface"] - ds["surface0"]).values / D
            ax.plot(ds["x_over_D"].values, raw, lw=0.5, alpha=0.4, color=line.get_color())
            continue
        xc = 0.5 * (float(ds["x_bin"].min()) + float(ds["x_bin"].max()))
        heave = (ds["surface"] - ds["surface0"]).values / D
        ax.plot((ds["x_bin"].values - xc) / D, heave, label=_label(ds))
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("x/D from the pipe axis [-]")
    ax.set_ylabel("surface change / D [-]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return fig


def _snap_index(ds: xr.Dataset, ratio: float) -> int:
    return int(np.argmin(np.abs(ds["snapshot"].values - ratio)))


def _frame(ax, ds: xr.Dataset, k: int) -> None:
    D = float(ds.attrs["pipe_diameter"])
    x = ds["x"].values[k]
    y = ds["y"].values[k]
    xc = 0.5 * (x.min() + x.max())
    surf = float(ds.attrs["surface0_at_pipe"])
    w = float(ds["snapshot_w"].values[k])
    ax.add_patch(Circle((xc, surf + 0.5 * D - w), 0.5 * D, fc="0.6", ec="k", zorder=5))
    ax.set_aspect("equal")
    ax.set_xlim(x.min(), x.max())
    ax.set_ylim(y.min(), max(y.max(), surf + D) * 1.02)
    ax.set_title(f"{_label(ds)}  w = {ds['snapshot'].values[k]:.1f}D")
    ax.set_xticks([])
    ax.set_yticks([])


def plot_velocity_field(ds: xr.Dataset, ratio: float = 0.5) -> Figure:
    """Particle velocity magnitude and direction at embedment ``ratio``·D (paper Fig. 9)."""
    k = _snap_index(ds, ratio)
    fig, ax = plt.subplots(figsize=(9, 4))
    x, y = ds["x"].values[k], ds["y"].values[k]
    vx, vy = ds["vx"].values[k], ds["vy"].values[k]
    sp = np.hypot(vx, vy)
    sc = ax.scatter(x, y, s=2, c=sp, cmap="viridis_r", vmin=0, vmax=np.percentile(sp, 99.5))
    fast = sp > 0.1 * sp.max()
    ax.quiver(x[fast], y[fast], vx[fast], vy[fast], color="r", scale=20 * sp.max(), width=0.002)
    fig.colorbar(sc, ax=ax, label="|v| [m/s]")
    _frame(ax, ds, k)
    return fig


def plot_rotation_field(ds: xr.Dataset, ratio: float = 0.5, threshold_deg: float = 20.0) -> Figure:
    """Disk rotations since the start: > ``threshold_deg`` ccw red, cw green (paper Fig. 10)."""
    k = _snap_index(ds, ratio)
    fig, ax = plt.subplots(figsize=(9, 4))
    x, y = ds["x"].values[k], ds["y"].values[k]
    rot = np.degrees(ds["rotation"].values[k])
    ax.scatter(x, y, s=1, c="0.85")
    ccw = rot > threshold_deg
    cw = rot < -threshold_deg
    ax.scatter(x[ccw], y[ccw], s=3, c="tab:red", label=f"ccw > {threshold_deg:g}°")
    ax.scatter(x[cw], y[cw], s=3, c="tab:green", label=f"cw > {threshold_deg:g}°")
    ax.legend(loc="lower right", fontsize=8)
    _frame(ax, ds, k)
    return fig


def plot_force_chains(ds: xr.Dataset, ratio: float = 0.5, threshold: float = 200.0) -> Figure:
    """Contact forces above ``threshold`` [N] as lines of width ∝ force (paper Fig. 11)."""
    k = _snap_index(ds, ratio)
    fig, ax = plt.subplots(figsize=(9, 4))
    x, y = ds["x"].values[k], ds["y"].values[k]
    sel = (ds["chain_snapshot"].values == k) & (ds["chain_fn"].values > threshold)
    i = ds["chain_i"].values[sel]
    j = ds["chain_j"].values[sel]
    fn = ds["chain_fn"].values[sel]
    segs = np.stack([np.stack([x[i], y[i]], 1), np.stack([x[j], y[j]], 1)], 1)
    fmax = fn.max() if fn.size else 1.0
    ax.add_collection(LineCollection(segs, linewidths=0.3 + 2.5 * fn / fmax, colors="k"))
    ax.text(0.01, 0.02, f"{sel.sum()} contacts > {threshold:g} N", transform=ax.transAxes)
    _frame(ax, ds, k)
    return fig


def plot_rotation_increment(ds: xr.Dataset, band: dict, threshold_deg: float = 10.0) -> Figure:
    """Incremental rotation of every disk from a softening peak to its trough.

    ``band`` is one entry of :func:`onbottom.dem.summary.band_episodes` (snapshot indices,
    w/D, drop, the connecting cluster's mask). Disks drawn at the trough: rotation increment
    in colour (clipped at ±3·threshold), those above ``threshold_deg`` outlined; the cluster
    joining the pipe to the surface (if any) in black.
    """
    p, t = int(band["peak"]), int(band["trough"])
    fig, ax = plt.subplots(figsize=(9, 4))
    x, y = ds["x"].values[t], ds["y"].values[t]
    inc = np.degrees(ds["rotation"].values[t] - ds["rotation"].values[p])
    lim = 3.0 * threshold_deg
    sc = ax.scatter(x, y, s=2, c=np.clip(inc, -lim, lim), cmap="coolwarm", vmin=-lim, vmax=lim)
    big = np.abs(inc) > threshold_deg
    ax.scatter(x[big], y[big], s=6, facecolors="none", edgecolors="0.3", lw=0.4)
    mask = np.asarray(band.get("band", np.zeros(x.size, bool)), bool)
    if mask.any():
        ax.scatter(x[mask], y[mask], s=6, c="k", label="band reaching the surface")
        ax.legend(loc="lower right", fontsize=8)
    fig.colorbar(sc, ax=ax, label="rotation peak→trough [deg] (ccw +)")
    _frame(ax, ds, t)
    verdict = "reaches the surface" if band["reaches_surface"] else "does not reach the surface"
    ax.set_title(
        f"{_label(ds)}  w/D {band['w_peak']:.3f}→{band['w_trough']:.3f}, drop"
        f" {band['drop_percent']:.1f} %: band {verdict} (|Δθ| > {threshold_deg:g}°)",
        fontsize=9,
    )
    return fig
