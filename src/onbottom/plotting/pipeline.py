"""Figures of a pipeline FE storm run: envelopes, deflected shapes, worst-node histories, GIF.

matplotlib only (Agg); the animation uses ``matplotlib.animation.PillowWriter`` (Pillow is a
matplotlib dependency), so no external encoder is needed.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["animate_pipeline", "plot_pipeline_result"]


def _records(result: Any):
    """The run's records, or None when it kept none (run without ``record_interval``); records
    that cannot be read raise (a figure is never drawn from a silently dropped file)."""
    if getattr(result, "data", None) is None and getattr(result, "netcdf", None) is None:
        return None
    return result.open_dataset()


def plot_pipeline_result(result: Any, *, title: str | None = None, n_snapshots: int = 6):
    """Four panels: |y| and strain envelopes, deflected shapes, worst-node y(t), worst-node
    soil and hydrodynamic forces (t).

    ``result``: a :class:`~onbottom.dynamics.pipeline.PipelineResult`.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    d = result.diameter
    env = result.envelopes
    x = env["x"].values
    ds = _records(result)
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
    ax = axes[0, 0]
    ax.fill_between(x, env["min_y"].values / d, env["max_y"].values / d, alpha=0.3, label="y range")
    ax.plot(x, env["max_abs_y"].values / d, "k-", lw=1.2, label="max |y|")
    for lim in (0.5, 10.0):
        if env["max_abs_y"].values.max() / d > 0.3 * lim:
            ax.axhline(lim, color="r", ls="--", lw=0.8)
            ax.text(x[-1], lim, f" {lim:g}D", color="r", va="bottom", ha="right", fontsize=8)
    ax.set_xlabel("x along the pipe [m]")
    ax.set_ylabel("lateral displacement y/D [-]")
    ax.set_title("displacement envelope")
    ax.legend(fontsize=8, loc="upper left")
    ax = axes[0, 1]
    ax.plot(x, 1e2 * env["max_strain"].values, "C3-")
    ax.set_xlabel("x along the pipe [m]")
    ax.set_ylabel("largest fibre strain [%]")
    ax.set_title("strain envelope")
    ax = axes[1, 0]
    ax2 = axes[1, 1]
    k = result.worst_node
    if ds is not None and ds.sizes.get("time", 0) > 0:
        t = ds["time"].values
        idx = np.unique(np.linspace(0, t.size - 1, n_snapshots).round().astype(int))
        cmap = plt.get_cmap("viridis")
        for j, i in enumerate(idx):
            ax.plot(
                x,
                ds["y"].values[i] / d,
                color=cmap(j / max(len(idx) - 1, 1)),
                label=f"t = {t[i]:.0f} s",
            )
        ax.set_title("deflected shape snapshots")
        ax.legend(fontsize=7, ncol=2)
        ax2.plot(t, ds["y"].values[:, k] / d, "k-", lw=1.0, label="y/D")
        ax2.set_ylabel(f"y/D at x = {result.worst_node_x:.0f} m [-]")
        axr = ax2.twinx()
        axr.plot(t, ds["F_hydro"].values[:, k] / 1e3, "C0-", lw=0.6, alpha=0.7, label="F_hydro")
        axr.plot(t, ds["F_soil"].values[:, k] / 1e3, "C1-", lw=0.6, alpha=0.7, label="F_soil")
        axr.set_ylabel("force per unit length [kN/m]")
        axr.legend(fontsize=7, loc="lower right")
        ax2.set_xlabel("time [s]")
        ax2.set_title("worst node history")
    else:
        ax.text(
            0.5, 0.5, "no records (record_interval = None)", ha="center", transform=ax.transAxes
        )
        ax2.text(0.5, 0.5, "no records", ha="center", transform=ax2.transAxes)
    ax.set_xlabel("x along the pipe [m]")
    ax.set_ylabel("y/D [-]")
    if title:
        fig.suptitle(title)
    return fig


def animate_pipeline(
    result: Any,
    path: str | os.PathLike,
    *,
    fps: int = 10,
    max_frames: int = 60,
    dpi: int = 60,
) -> Path:
    """GIF of the deflected line through the storm (PillowWriter), with the |y| envelope."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    from onbottom.errors import InputError

    ds = _records(result)
    if ds is None or ds.sizes.get("time", 0) == 0:
        raise InputError("animation is invalid for a run without records: set record_interval")
    d = result.diameter
    x = ds["x"].values
    t = ds["time"].values
    y = ds["y"].values / d
    frames = np.unique(np.linspace(0, t.size - 1, min(max_frames, t.size)).round().astype(int))
    fig, ax = plt.subplots(figsize=(8, 3.2), constrained_layout=True)
    lim = max(float(np.abs(y).max()) * 1.1, 0.1)
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(-lim, lim)
    ax.set_xlabel("x along the pipe [m]")
    ax.set_ylabel("y/D [-]")
    env_line = ax.plot(x, result.envelopes["max_abs_y"].values / d, "r:", lw=0.8)[0]
    env_line.set_label("max |y| (whole run)")
    (line,) = ax.plot(x, y[0], "k-", lw=1.5)
    label = ax.set_title("")
    ax.legend(fontsize=7, loc="upper right")

    def update(i: int):
        line.set_ydata(y[i])
        label.set_text(f"t = {t[i]:.0f} s")
        return (line, label)

    anim = FuncAnimation(fig, update, frames=frames, blit=False)
    from onbottom.results import atomic_write

    out = Path(path)

    def write(tmp: str) -> None:  # Pillow picks the format by the suffix: save as .gif first
        anim.save(tmp + ".gif", writer=PillowWriter(fps=fps), dpi=dpi)
        os.replace(tmp + ".gif", tmp)

    atomic_write(out, write)  # kill-safe: a GIF under its name is always whole
    plt.close(fig)
    return out
