"""Figures of a reliability campaign (:mod:`onbottom.reliability`).

* :func:`plot_exceedance` — probability per storm that the maximum lateral displacement
  exceeds y, against y/D (log–log): subset simulation's intermediate levels and each limit's
  estimate with its ±1.96 CV band (an upper bound drawn as a triangle).
* :func:`plot_convergence` — each estimate against the storms run (per block or subset level).
* :func:`plot_importance` — the sensitivity of each estimate to each input (SRRC² over all storms).
* :func:`plot_design` — response-based design: the contour points' maximum displacements
  (mean and fractile) against H_s, and F109's return-period storm.
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg", force=False)
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

__all__ = ["plot_convergence", "plot_design", "plot_exceedance", "plot_importance"]


def plot_exceedance(estimates, diameter: float, *, title: str | None = None) -> Figure:
    """Exceedance probability per storm against displacement over D (module docstring)."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for e in estimates:
        if e.curve:
            y, p = zip(*e.curve, strict=True)
            ax.plot(
                np.array(y) / diameter,
                p,
                "o-",
                ms=3,
                lw=1,
                alpha=0.6,
                label=f"subset levels ({e.label} run)",
            )
        marker = "v" if e.upper_bound else "s"
        ax.plot(
            e.limit / diameter,
            e.probability,
            marker,
            ms=8,
            label=f"P[Y > {e.label}] = {e.probability:.2g}" + (" (bound)" if e.upper_bound else ""),
        )
        lo, hi = e.interval
        if math.isfinite(hi) and hi > 0.0:  # the 95 % interval (a bound: from 1e-3 of it)
            lo = max(lo, hi * 1e-3) if math.isfinite(lo) else hi * 1e-3
            ax.vlines(e.limit / diameter, lo, hi, color="k")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("maximum lateral displacement y / D [-]")
    ax.set_ylabel("P[Y > y] per storm")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title(title or "exceedance probability per storm")
    fig.tight_layout()
    return fig


def plot_convergence(estimates) -> Figure:
    """Estimate against storms run, with ±1.96 CV where known."""
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for e in estimates:
        if not e.history:
            continue
        n, p, cv = (np.array(v, dtype=float) for v in zip(*e.history, strict=True))
        (line,) = ax.plot(n, p, "o-", ms=3, label=f"{e.label} ({e.method})")
        ok = np.isfinite(cv)
        if ok.any():
            ax.fill_between(
                n[ok],
                p[ok] * (1 - 1.96 * cv[ok]),
                p[ok] * (1 + 1.96 * cv[ok]),
                color=line.get_color(),
                alpha=0.2,
            )
    ax.set_yscale("log")
    ax.set_xlabel("storms run")
    ax.set_ylabel("P per storm (subset: level probability)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("estimator convergence")
    fig.tight_layout()
    return fig


def plot_importance(estimates) -> Figure:
    """Bars of each input's share per estimate."""
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    names: list[str] = []
    for e in estimates:
        names += [k for k in e.importance if k not in names]
    width = 0.8 / max(1, len(estimates))
    x = np.arange(len(names))
    for i, e in enumerate(estimates):
        ax.bar(
            x + i * width,
            [e.importance.get(k, 0.0) for k in names],
            width,
            label=f"{e.label}: {e.importance_kind}",
        )
    ax.set_xticks(x + 0.4 - width / 2, names, rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("share [-]")
    ax.legend(fontsize=7)
    ax.set_title("importance of the inputs")
    fig.tight_layout()
    return fig


def plot_design(design, diameter: float) -> Figure:
    """Contour points' maximum displacement against H_s, and F109's storm."""
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    pts = design.points
    hs = [p["hs"] for p in pts]
    ax.plot(hs, [p["mean"] / diameter for p in pts], "o", label="contour point: mean")
    ax.plot(
        hs,
        [p["fractile"] / diameter for p in pts],
        "^",
        label=f"contour point: {design.fractile:g} fractile",
    )
    f = design.f109
    ax.plot(
        f["hs"],
        f["fractile"] / diameter,
        "r*",
        ms=12,
        label=f"F109 {design.return_period:g}-year H_s, median T_p: {design.fractile:g} fractile",
    )
    ax.axhline(
        design.design_displacement / diameter,
        color="k",
        ls="--",
        lw=1,
        label="response-based design displacement",
    )
    ax.set_xlabel("H_s [m]")
    ax.set_ylabel("maximum lateral displacement / D [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title(f"{design.return_period:g}-year contour: response-based design")
    fig.tight_layout()
    return fig
