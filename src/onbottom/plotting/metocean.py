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


def plot_threshold_choice(result: MetoceanResult, *, n_thresholds: int = 20) -> Figure:
    """Threshold stability of the omnidirectional H_s fit: the mean residual life (mean excess
    of the storm peaks over u, linear in u where the GPD holds; Coles 2001 §4.3.1) and the
    maximum-likelihood ξ̂ (scipy, location fixed at u) of the storm peaks declustered at each
    threshold u, against u; the threshold used marked."""
    from scipy import stats

    from onbottom.metocean.storms import storm_peaks

    hc = result.hindcast
    lv = result.hs["omni"]
    v = np.where(hc.observed, hc.hs, 0.0)
    u0 = float(np.quantile(v[hc.observed], 0.95))
    top = float(np.sort(lv.storms.peak)[-10]) if lv.storms.peak.size >= 10 else u0
    us = np.linspace(u0, max(top, u0 + 1e-6), n_thresholds)
    mrl, lo, hi, xi = [], [], [], []
    for u in us:
        st = storm_peaks(v, hc.step_hours, float(u), lv.storms.r_hours, hc.years)
        y = st.peak - u
        m = float(y.mean()) if y.size else np.nan
        se = float(y.std(ddof=1) / np.sqrt(y.size)) if y.size > 1 else np.nan
        mrl.append(m)
        lo.append(m - 1.96 * se)
        hi.append(m + 1.96 * se)
        xi.append(float(stats.genpareto.fit(y, floc=0.0)[0]) if y.size >= 10 else np.nan)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    a1.plot(us, mrl, "k-")
    a1.fill_between(us, lo, hi, color="0.85")
    a1.set_xlabel("threshold u [m]")
    a1.set_ylabel("mean excess of the storm peaks [m]")
    a1.set_title("mean residual life")
    a2.plot(us, xi, "ko-", ms=3)
    a2.axhline(0.0, color="0.5", lw=0.8)
    a2.set_xlabel("threshold u [m]")
    a2.set_ylabel("GPD shape ξ̂ [-]")
    a2.set_title("threshold stability")
    for ax in (a1, a2):
        ax.axvline(lv.storms.threshold, color="r", lw=0.8, label="threshold used")
        ax.grid(alpha=0.3)
    a2.legend(fontsize=8)
    fig.tight_layout()
    return fig
