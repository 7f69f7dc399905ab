"""Figures of a hindcast analysis (:mod:`onbottom.metocean`).

* :func:`plot_return_levels` — return value against return period (log axis) for H_s and the
  current: the fitted GPD curve of the whole record, its confidence intervals at the asked
  return periods, the storm peaks at their empirical return periods (Weibull plotting
  position R_i = T(N + 1)/(N i) for the i-th largest of N peaks in T years), and the sectors'
  curves.
* :func:`plot_contours` — the sea states of the record (H_s against T_p, density) with the
  IFORM contours of the joint model.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg", force=False)
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from onbottom.metocean.analysis import MetoceanResult
from onbottom.metocean.extremes import ReturnLevels, gpd_return_level

__all__ = ["plot_contours", "plot_return_levels"]


def _curve(ax, lv: ReturnLevels, rp: np.ndarray, **kw) -> None:
    if not np.isfinite(lv.scale):
        return
    s = lv.storms
    ax.plot(rp, gpd_return_level(rp, s.threshold, lv.scale, lv.shape, s.rate), **kw)


def _panel(ax, levels: dict[str, ReturnLevels], sectors: list[str], label: str, unit: str):
    omni = levels["omni"]
    rps = omni.return_periods
    rp = np.geomspace(0.5, max(200.0, 2.0 * rps.max()), 200)
    if len(sectors) > 1:
        cmap = plt.get_cmap("tab10" if len(sectors) <= 10 else "hsv", max(len(sectors), 10))
        for k, name in enumerate(sectors):
            _curve(ax, levels[name], rp, color=cmap(k), lw=0.9, alpha=0.8, label=name)
    _curve(ax, omni, rp, color="k", lw=2.0, label="all directions (GPD)")
    peaks = np.sort(omni.storms.peak)[::-1]
    if peaks.size:
        n, years = peaks.size, omni.storms.years
        emp = years * (n + 1) / (n * np.arange(1, n + 1))
        ax.plot(emp, peaks, "o", ms=3, mfc="none", color="k", label="storm peaks")
    ok = np.isfinite(omni.value)
    ax.errorbar(
        rps[ok],
        omni.value[ok],
        yerr=[omni.value[ok] - omni.lower[ok], omni.upper[ok] - omni.value[ok]],
        fmt="s",
        color="C3",
        capsize=4,
        label=f"{100 * omni.confidence:g}% interval",
    )
    ax.set_xscale("log")
    ax.set_xlabel("return period [years]")
    ax.set_ylabel(f"{label} [{unit}]")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7, ncol=2)


def plot_return_levels(result: MetoceanResult, *, title: str | None = None) -> Figure:
    """Return-level plot(s): H_s, and the current speed when the hindcast has it."""
    n = 2 if result.current is not None else 1
    fig, axes = plt.subplots(1, n, figsize=(6.0 * n, 4.8), layout="constrained", squeeze=False)
    _panel(axes[0, 0], result.hs, result.sectors, "H_s", "m")
    axes[0, 0].set_title("significant wave height (sectors: waves from)", fontsize=9)
    if result.current is not None:
        _panel(axes[0, 1], result.current, result.sectors, "current speed", "m/s")
        axes[0, 1].set_title("current speed (sectors: coming from)", fontsize=9)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def plot_contours(result: MetoceanResult, *, title: str | None = None) -> Figure:
    """H_s–T_p sea states of the record and the IFORM contours of the joint model."""
    hc = result.hindcast
    obs = hc.observed  # missing sea states left out
    hs_obs, tp_obs = hc.hs[obs], hc.tp[obs]
    fig, ax = plt.subplots(figsize=(6.4, 5.0), layout="constrained")
    hb = ax.hexbin(tp_obs, hs_obs, gridsize=60, bins="log", cmap="Greys", mincnt=1)
    fig.colorbar(hb, ax=ax, label="sea states per bin")
    for k, (rp, (h, t)) in enumerate(sorted(result.contours.items())):
        ax.plot(
            np.append(t, t[0]),
            np.append(h, h[0]),
            color=f"C{k}",
            lw=1.5,
            label=f"{rp:g}-year IFORM contour",
        )
        lv = result.hs["omni"]
        if rp in list(lv.return_periods):
            i = list(lv.return_periods).index(rp)
            if np.isfinite(lv.value[i]):
                ax.axhline(lv.value[i], color=f"C{k}", ls=":", lw=1.0)
    tp_line = np.linspace(max(1.0, float(tp_obs.min())), float(tp_obs.max()) * 1.1, 100)
    ax.plot(
        tp_line, 9.80665 * tp_line**2 / (2 * np.pi * 15.0), "k--", lw=0.8, label="steepness 1/15"
    )
    ax.set_ylim(
        0.0, max(float(hs_obs.max()), max(h.max() for h, _ in result.contours.values())) * 1.1
    )
    ax.set_xlabel("T_p [s]")
    ax.set_ylabel("H_s [m]")
    ax.set_title(title or "sea states and IFORM contours (dotted: POT return values)", fontsize=9)
    ax.legend(fontsize=8, loc="upper left")
    return fig
