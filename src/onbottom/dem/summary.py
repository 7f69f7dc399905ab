"""Small summaries of a DEM penetration run: the curves worth keeping, not the particles.

A full-size run (≈ 60k disks, ≈ 3.6e6 steps) stores every disk at every snapshot; what a report
and the comparison with the paper need is far smaller:

* the V–w curve averaged in bins of w/D (mean, min and max in each bin, model and prototype
  scale): the raw record oscillates by a few % from step to step (force chains building and
  buckling), so a value "at 0.4D" is the bin mean, and a drop is measured on the bin means;
* softening episodes: where the bin-mean curve falls by more than a stated fraction below its
  running peak before climbing back (the paper's "periodic softening" of the dense sand);
* the soil surface before and after, smoothed, and the heave next to the pipe: its peak (outside
  the pipe's footprint) and its extent;
* the initial measuring-circle profiles when the run carries them (``initial_*`` variables, as
  written by ``onbottom dem penetrate``);
* for a run with event snapshots (peak and trough of each softening episode, found online by
  :mod:`onbottom.dem.events`), whether each episode's shear band reaches the soil surface
  (:func:`band_episodes`, :func:`onbottom.dem.analysis.band_to_surface`).

Nothing here depends on the soil models: the comparison with DNVGL-RP-F114 is drawn in
``onbottom.plotting.dem_f114``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from onbottom import _validate as _v
from onbottom.dem.analysis import band_to_surface
from onbottom.results import provenance

__all__ = [
    "BAND_THRESHOLD_DEG",
    "SofteningEpisode",
    "band_episodes",
    "binned_resistance",
    "heave_metrics",
    "softening_episodes",
    "summarize_run",
]


@dataclass(frozen=True, slots=True)
class SofteningEpisode:
    """One drop of the bin-mean V–w curve below its running peak.

    Attributes
    ----------
    w_peak, w_trough : float
        Embedment ratios w/D [-] of the peak and of the lowest point of the drop.
    v_peak, v_trough : float
        Bin-mean resistance at those points [N/m, same scale as the input].
    """

    w_peak: float
    w_trough: float
    v_peak: float
    v_trough: float

    @property
    def drop_fraction(self) -> float:
        """Relative drop 1 − V_trough/V_peak [-]."""
        return 1.0 - self.v_trough / self.v_peak


def binned_resistance(
    w_over_d: np.ndarray, resistance: np.ndarray, step: float = 0.005, w_max: float | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Bin a V–w record on w/D.

    Parameters
    ----------
    w_over_d : array
        Embedment ratio w/D of each record [-].
    resistance : array
        Resistance of each record [N/m, any scale].
    step : float
        Bin width in w/D [-], > 0.
    w_max : float, optional
        Upper end of the bins [-] (default: the largest w/D recorded).

    Returns
    -------
    (centres, mean, minimum, maximum)
        Bin centres [-] and the mean, min and max of ``resistance`` in each bin (NaN in an
        empty bin); bins are [k·step, (k+1)·step) from w/D = 0, records with w < 0 dropped.
    """
    _v.positive("step", step)
    w = np.asarray(w_over_d, float)
    f = np.asarray(resistance, float)
    if w.shape != f.shape:
        raise ValueError(f"w_over_d and resistance differ in shape: {w.shape} vs {f.shape}")
    top = float(np.nanmax(w)) if w_max is None and w.size else float(w_max or 0.0)
    n = max(1, int(np.ceil(top / step - 1e-9)))
    keep = (w >= 0.0) & np.isfinite(f)
    idx = np.minimum((w[keep] / step).astype(int), n - 1)
    fk = f[keep]
    count = np.bincount(idx, minlength=n).astype(float)
    total = np.bincount(idx, weights=fk, minlength=n)
    mean = np.full(n, np.nan)
    np.divide(total, count, out=mean, where=count > 0)
    lo = np.full(n, np.inf)
    hi = np.full(n, -np.inf)
    np.minimum.at(lo, idx, fk)
    np.maximum.at(hi, idx, fk)
    lo[count == 0] = np.nan
    hi[count == 0] = np.nan
    return (np.arange(n) + 0.5) * step, mean, lo, hi


def softening_episodes(
    w_over_d: np.ndarray, v_mean: np.ndarray, drop_fraction: float = 0.05
) -> list[SofteningEpisode]:
    """Drops of a (binned) V–w curve below its running peak by more than ``drop_fraction``.

    An episode starts at a running peak, ends when the curve climbs back above that peak (or at
    the end of the record); it is kept when its lowest point lies more than
    ``drop_fraction``·V_peak below the peak. A monotonically hardening curve has none.

    Parameters
    ----------
    w_over_d, v_mean : array
        Curve to scan [-], [N/m] (NaNs are skipped).
    drop_fraction : float
        Smallest relative drop that counts [-], in (0, 1).
    """
    _v.in_range("drop_fraction", drop_fraction, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    ok = np.isfinite(v_mean)
    w = np.asarray(w_over_d, float)[ok]
    f = np.asarray(v_mean, float)[ok]
    out: list[SofteningEpisode] = []
    k = 0
    while k < len(f):
        # climb to a running peak
        while k + 1 < len(f) and f[k + 1] >= f[k]:
            k += 1
        peak_k = k
        j = k + 1
        trough_k = peak_k
        while j < len(f) and f[j] <= f[peak_k]:
            if f[j] < f[trough_k]:
                trough_k = j
            j += 1
        if f[peak_k] > 0 and f[trough_k] < (1.0 - drop_fraction) * f[peak_k]:
            out.append(SofteningEpisode(w[peak_k], w[trough_k], f[peak_k], f[trough_k]))
        k = j if j > k + 1 else k + 1
    return out


BAND_THRESHOLD_DEG = 10.0
"""Incremental rotation peak → trough above which a disk belongs to a band [deg]."""


def _d50(ds: xr.Dataset) -> float:
    import json

    return float(json.loads(ds.attrs["config"])["psd"]["d50"])


def band_episodes(
    ds: xr.Dataset, *, threshold_deg: float = BAND_THRESHOLD_DEG
) -> list[dict[str, object]]:
    """Per softening episode with both event snapshots: does its band reach the surface?

    For each peak → trough pair of ``ds`` (a run of :func:`onbottom.dem.experiment.penetrate`
    with event snapshots) the incremental rotation of every disk between the two snapshots goes
    to :func:`onbottom.dem.analysis.band_to_surface` (disks rotated by more than
    ``threshold_deg``, clustered by the 1.1·(r_i + r_j) neighbour rule; the band reaches the
    surface when one cluster joins the pipe's contact zone to the surface within 2·d50, at
    least 0.75D from the axis), in the trough's positions.

    Returns
    -------
    list of dict
        ``episode``, ``w_peak``, ``w_trough`` (w/D of the snapshots [-]), ``drop_percent``
        (100·(1 − V_trough/V_peak), bin means), ``reaches_surface``, ``outcrop_x_over_D``,
        ``cluster_size`` (disks in the largest rotated cluster touching the pipe),
        ``n_rotated``, ``peak``/``trough`` (snapshot indices) and ``band``
        (mask of the connecting cluster).
    """
    _v.in_range("threshold_deg", threshold_deg, 0.0, 180.0, low_inclusive=False)
    if "snapshot_kind" not in ds:
        return []
    D = float(ds.attrs["pipe_diameter"])
    kinds = ds["snapshot_kind"].values.astype(str)
    episode = ds["snapshot_episode"].values
    surf0 = float(ds.attrs["surface0_at_pipe"])
    x_bin = ds["x_bin"].values
    pipe_x = float(ds.attrs.get("pipe_x", 0.5 * (float(x_bin.min()) + float(x_bin.max()))))
    d50 = _d50(ds)
    out = []
    for e in sorted({int(v) for v in episode if v >= 0}):
        peaks = np.nonzero((episode == e) & (kinds == "peak"))[0]
        troughs = np.nonzero((episode == e) & (kinds == "trough"))[0]
        if not (peaks.size and troughs.size):
            continue
        p, t = int(peaks[0]), int(troughs[0])
        w_t = float(ds["snapshot_w"].values[t])
        res = band_to_surface(
            ds["x"].values[t],
            ds["y"].values[t],
            ds["radius"].values,
            ds["rotation"].values[t] - ds["rotation"].values[p],
            pipe_x,
            surf0 + 0.5 * D - w_t,
            0.5 * D,
            d50,
            threshold_deg=threshold_deg,
        )
        vp, vt = (float(ds["snapshot_V_bin"].values[k]) for k in (p, t))
        out.append(
            {
                "episode": e,
                "w_peak": float(ds["snapshot_w"].values[p]) / D,
                "w_trough": w_t / D,
                "drop_percent": 100.0 * (1.0 - vt / vp),
                "reaches_surface": bool(res["reaches_surface"]),
                "outcrop_x_over_D": float(res["outcrop_x_over_D"]),
                "cluster_size": int(res["band_size"]),
                "n_rotated": int(res["n_rotated"]),
                "peak": p,
                "trough": t,
                "band": res["band"],
            }
        )
    return out


def heave_metrics(
    x: np.ndarray,
    surface0: np.ndarray,
    surface: np.ndarray,
    x_pipe: float,
    diameter: float,
    *,
    smooth_bins: int = 5,
    footprint_ratio: float = 0.75,
    extent_fraction: float = 0.25,
) -> dict[str, object]:
    """Heave next to the pipe from the surface before and after.

    Parameters
    ----------
    x : array
        Bin centres [m].
    surface0, surface : array
        Surface heights before and after [m] (highest disk top per bin; NaN = empty bin).
    x_pipe : float
        Pipe axis [m].
    diameter : float
        Pipe diameter D [m].
    smooth_bins : int
        Width of the centred moving average applied to the change [bins] (a bin surface
        scatters by about one grain).
    footprint_ratio : float
        Bins with |x − x_pipe| < footprint_ratio·D are the pipe's, not heave [-].
    extent_fraction : float
        The heave extends as far as the smoothed heave stays above this fraction of its peak
        (on each side) [-].

    Returns
    -------
    dict
        ``change`` (smoothed surface change [m] per bin, NaN inside the footprint),
        ``peak_over_D`` (max smoothed heave / D, larger of the two sides), ``peak_x_over_D``
        (its signed position from the axis), ``extent_over_D`` (mean over the two sides of the
        distance from the axis to where the heave falls below the fraction), ``mean_over_D``
        (mean heave / D over footprint edge … 2.5D from the axis).
    """
    _v.positive("diameter", diameter)
    if smooth_bins < 1:
        raise ValueError(f"smooth_bins = {smooth_bins!r} is invalid: must be >= 1")
    dx = np.asarray(x, float) - x_pipe
    change = np.asarray(surface, float) - np.asarray(surface0, float)
    good = np.isfinite(change)
    kernel = np.ones(smooth_bins)
    num = np.convolve(np.where(good, change, 0.0), kernel, mode="same")
    den = np.convolve(good.astype(float), kernel, mode="same")
    smooth = np.full_like(change, np.nan)
    np.divide(num, den, out=smooth, where=den > 0)
    smooth[np.abs(dx) < footprint_ratio * diameter] = np.nan
    peaks = []
    extents = []
    for side in (-1.0, 1.0):
        sel = np.isfinite(smooth) & (side * dx > 0)
        if not np.any(sel):
            continue
        d_side = np.abs(dx[sel])
        h_side = smooth[sel]
        order = np.argsort(d_side)
        d_side, h_side = d_side[order], h_side[order]
        kp = int(np.argmax(h_side))
        peaks.append((h_side[kp], side * d_side[kp]))
        beyond = np.nonzero(h_side[kp:] < extent_fraction * max(h_side[kp], 0.0))[0]
        extents.append(d_side[kp + beyond[0]] if beyond.size else d_side[-1])
    peak, x_peak = max(peaks) if peaks else (np.nan, np.nan)
    near = np.isfinite(smooth) & (np.abs(dx) <= 2.5 * diameter)
    return {
        "change": smooth,
        "peak_over_D": float(peak / diameter),
        "peak_x_over_D": float(x_peak / diameter),
        "extent_over_D": float(np.mean(extents) / diameter) if extents else float("nan"),
        "mean_over_D": float(np.mean(smooth[near]) / diameter) if np.any(near) else float("nan"),
    }


def summarize_run(
    ds: xr.Dataset,
    *,
    step: float = 0.005,
    drop_fraction: float = 0.05,
    report_at: tuple[float, ...] = (0.05, 0.1, 0.2, 0.3, 0.4, 0.5),
    band_threshold_deg: float = BAND_THRESHOLD_DEG,
) -> xr.Dataset:
    """The small summary of a penetration result (see the module docstring).

    Parameters
    ----------
    ds : xarray.Dataset
        Result of :func:`onbottom.dem.experiment.penetrate` (possibly incomplete).
    step : float
        Bin width of the V–w curve in w/D [-].
    drop_fraction : float
        Smallest drop counted as softening [-] (see :func:`softening_episodes`).
    report_at : tuple of float
        Embedment ratios w/D at which the bin-mean prototype V is reported in the attributes.
    band_threshold_deg : float
        Rotation threshold of the band-to-surface test [deg] (see :func:`band_episodes`).

    Returns
    -------
    xarray.Dataset
        ``V_mean/V_min/V_max`` (model, N/m) and ``V_prototype_mean`` etc. on ``w_over_D``;
        surfaces and smoothed heave on ``x_over_D``; ``softening_*`` (w/D and prototype V of
        each episode's peak and trough) on ``episode``; ``band_*`` (the run's event episodes:
        w/D of peak and trough snapshots, drop %, reaches_surface 0/1, outcrop x/D, cluster
        size) on ``band_episode`` when the run has event snapshots of one episode or more;
        ``initial_*`` circle profiles when present;
        attributes: the run's provenance, ``V_prototype_at_<r>D`` [N/m], heave metrics,
        softening episodes (JSON-like strings) and the stated averaging rules.
    """
    D = float(ds.attrs["pipe_diameter"])
    N = float(ds.attrs["gravity_factor"])
    w = ds["w_over_D"].values
    # the V–w curve in bins, its softening episodes, the surface heave
    centres, mean, lo, hi = binned_resistance(w, ds["V"].values, step)
    eps = softening_episodes(centres, mean, drop_fraction)
    x = ds["x_bin"].values
    box_mid = 0.5 * (float(x.min()) + float(x.max()))
    x_pipe = float(ds.attrs.get("pipe_x", box_mid))
    heave = heave_metrics(x, ds["surface0"].values, ds["surface"].values, x_pipe, D)
    out = _curve_and_surfaces(ds, N, centres, mean, lo, hi, heave, (x - x_pipe) / D)
    _add_softening(out, eps, N)
    bands = band_episodes(ds, threshold_deg=band_threshold_deg)
    _add_bands(out, bands)
    for name in ds.data_vars:
        if str(name).startswith("initial_"):
            out[name] = ds[name]
    # attributes: the run's, the summary's provenance and rules, V at the reported w/D
    attrs = {k: ds.attrs[k] for k in ds.attrs if not str(k).startswith("_")}
    attrs.update(
        provenance(
            "dem.penetration.summary",
            None,
            source_model=str(ds.attrs.get("model", "")),
            bin_step_w_over_D=step,
            drop_fraction=drop_fraction,
            averaging=(
                "V in bins of w/D (mean, min, max); softening = bin-mean drop > drop_fraction "
                "below the running peak; heave = surface change smoothed over 5 bins, "
                "bins within 0.75D of the axis excluded, extent where heave > 25 % of its peak"
            ),
            w_over_D_reached=float(np.nanmax(w)) if w.size else 0.0,
            heave_peak_over_D=heave["peak_over_D"],
            heave_peak_x_over_D=heave["peak_x_over_D"],
            heave_extent_over_D=heave["extent_over_D"],
            heave_mean_over_D=heave["mean_over_D"],
            softening_episodes=len(eps),
            softening=";".join(
                f"{e.w_peak:.3f}-{e.w_trough:.3f}D:{e.v_peak * N / 1e3:.1f}->"
                f"{e.v_trough * N / 1e3:.1f}kN/m"
                for e in eps
            ),
        )
    )
    for r in report_at:
        k = int(np.floor(r / step - 1e-9))
        # the bin whose centre is nearest to r from below and above: average the two
        ks = [i for i in (k, k + 1) if 0 <= i < len(mean) and np.isfinite(mean[i])]
        val = float(np.mean(mean[ks]) * N) if ks and r <= np.nanmax(w) + 1e-12 else float("nan")
        attrs[f"V_prototype_at_{r:g}D"] = val
    if bands:
        attrs.update(
            band_threshold_deg=band_threshold_deg,
            band_rule="onbottom.dem.summary.band_episodes",
            band_episodes=len(bands),
            band_episodes_reaching_surface=sum(b["reaches_surface"] for b in bands),
        )
    out.attrs.update(attrs)
    return out


def _curve_and_surfaces(
    ds: xr.Dataset,
    N: float,
    centres: np.ndarray,
    mean: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    heave: dict,
    x_over_d: np.ndarray,
) -> xr.Dataset:
    """The binned V (model and prototype, N/m) on ``w_over_D``, the surfaces and the smoothed
    heave on ``x_over_D``."""
    return xr.Dataset(
        {
            "V_mean": ("w_over_D", mean, {"long_name": "bin-mean resistance", "units": "N/m"}),
            "V_min": ("w_over_D", lo, {"long_name": "bin-minimum resistance", "units": "N/m"}),
            "V_max": ("w_over_D", hi, {"long_name": "bin-maximum resistance", "units": "N/m"}),
            "V_prototype_mean": (
                "w_over_D",
                mean * N,
                {"long_name": "bin-mean resistance, prototype", "units": "N/m"},
            ),
            "V_prototype_min": ("w_over_D", lo * N, {"units": "N/m"}),
            "V_prototype_max": ("w_over_D", hi * N, {"units": "N/m"}),
            "surface0": (
                "x_over_D",
                ds["surface0"].values,
                {"long_name": "initial surface height", "units": "m"},
            ),
            "surface": (
                "x_over_D",
                ds["surface"].values,
                {"long_name": "final surface height", "units": "m"},
            ),
            "heave": (
                "x_over_D",
                heave["change"],
                {"long_name": "smoothed surface change (NaN under the pipe)", "units": "m"},
            ),
        },
        coords={
            "w_over_D": ("w_over_D", centres, {"long_name": "embedment / D (bin centre)"}),
            "x_over_D": ("x_over_D", x_over_d, {"long_name": "x from pipe axis / D"}),
        },
    )


def _add_softening(out: xr.Dataset, eps: list, N: float) -> None:
    """``softening_*`` on ``episode``: w/D and prototype V of each episode's peak and trough."""
    for key, attr, unit in (
        ("w_peak", "w_peak", "1"),
        ("w_trough", "w_trough", "1"),
        ("V_prototype_peak", "v_peak", "N/m"),
        ("V_prototype_trough", "v_trough", "N/m"),
    ):
        scale = N if unit == "N/m" else 1.0
        out[f"softening_{key}"] = (
            "episode",
            np.array([getattr(e, attr) * scale for e in eps], float),
            {"long_name": f"softening episode {key.replace('_', ' ')}", "units": unit},
        )


def _add_bands(out: xr.Dataset, bands: list[dict]) -> None:
    """``band_*`` on ``band_episode`` (the run's event episodes), when there are any."""
    for key, unit, ln in (
        ()
        if not bands
        else (
            ("w_peak", "1", "w/D of the peak snapshot"),
            ("w_trough", "1", "w/D of the trough snapshot"),
            ("drop_percent", "%", "drop of the bin-mean V, peak to trough"),
            ("reaches_surface", "1", "1 if a band of rotated disks joins pipe and surface"),
            ("outcrop_x_over_D", "1", "signed distance of the band's outcrop from the axis / D"),
            ("cluster_size", "1", "disks in the largest rotated cluster touching the pipe"),
        )
    ):
        vals = [b[key] for b in bands]
        arr = np.array(vals, int if key in ("reaches_surface", "cluster_size") else float)
        out[f"band_{key}"] = ("band_episode", arr, {"long_name": ln, "units": unit})
