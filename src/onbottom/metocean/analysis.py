"""The metocean analysis of a hindcast: storms and return values per direction sector, the
joint H_s–T_p model and its IFORM contours — one call, one result with a NetCDF form.

Sectors are directions the waves come **from**; the current is sectored by the direction it
comes from (its going-to direction + 180°), so sector k pairs waves and current that push the
pipe the same way. Sector 'omni' is the whole record.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from onbottom._validate import in_range, integer, one_of, positive
from onbottom.errors import InputError
from onbottom.metocean.current import CurrentModel, fit_current_model
from onbottom.metocean.extremes import CI_METHODS, ReturnLevels, fit_return_levels
from onbottom.metocean.hindcast import Hindcast
from onbottom.metocean.joint import JointModel, fit_joint_model, iform_contour
from onbottom.metocean.storms import sector_edges, sector_mask, storm_peaks, threshold_for_rate
from onbottom.metocean.tail import TailCheck, check_tail

__all__ = [
    "MIN_TARGET_STORMS",
    "MetoceanOptions",
    "MetoceanResult",
    "analyse_hindcast",
    "sector_names",
]

_COMPASS = (
    "N",
    "NNE",
    "NE",
    "ENE",
    "E",
    "ESE",
    "SE",
    "SSE",
    "S",
    "SSW",
    "SW",
    "WSW",
    "W",
    "WNW",
    "NW",
    "NNW",
)


def sector_names(n_sectors: int) -> list[str]:
    """Labels of ``n_sectors`` sectors: compass points for 4, 8 and 16, else ``"000"``…"""
    centres, _ = sector_edges(n_sectors)
    if n_sectors in (4, 8, 16):
        step = 16 // n_sectors
        return [_COMPASS[i * step] for i in range(n_sectors)]
    return [f"{c:03.0f}" for c in centres]


@dataclass(frozen=True, kw_only=True, slots=True)
class MetoceanOptions:
    """Choices of the analysis.

    Parameters
    ----------
    sectors : int
        Number of equal direction sectors, in [1, 36] (1: omnidirectional only).
    return_periods : tuple of float
        R [years], each in [0.1, 10000]; the F109 table needs 10 and 100.
    storm_rate : float
        Target number of storms per year that sets each series' threshold, in [0.5, 50].
    r_hours : float
        Declustering time [h], in [3, 720].
    confidence : float
        Level of the confidence intervals, in (0.5, 1).
    ci_method : str
        Confidence intervals: ``"profile"`` (profile likelihood, default) or ``"bootstrap"``
        (pyextremes); see :mod:`onbottom.metocean.extremes`.
    n_bootstrap : int
        Bootstrap samples per fit, in [20, 5000] (``"bootstrap"`` only).
    seed : int
        Seed of the bootstraps.
    contour_points : int
        Points per IFORM contour.
    """

    sectors: int = 8
    return_periods: tuple[float, ...] = (1.0, 10.0, 100.0)
    storm_rate: float = 3.0
    r_hours: float = 48.0
    confidence: float = 0.95
    ci_method: str = "profile"
    n_bootstrap: int = 200
    seed: int = 0
    contour_points: int = 180

    def __post_init__(self) -> None:
        integer("sectors", self.sectors, 1, 36)
        if not self.return_periods:
            raise InputError("return_periods = () is invalid: give at least one")
        for r in self.return_periods:
            in_range("return_periods", r, 0.1, 1.0e4)
        in_range("storm_rate", self.storm_rate, 0.5, 50.0)
        in_range("r_hours", self.r_hours, 3.0, 720.0)
        in_range("confidence", self.confidence, 0.5, 1.0, low_inclusive=False, high_inclusive=False)
        one_of("ci_method", self.ci_method, CI_METHODS)
        integer("n_bootstrap", self.n_bootstrap, 20, 5000)
        integer("contour_points", self.contour_points, 8, 3600)


@dataclass(frozen=True, eq=False, slots=True)
class MetoceanResult:
    """Everything the analysis found (see :func:`analyse_hindcast`)."""

    hindcast: Hindcast
    options: MetoceanOptions
    sectors: list[str]
    centres_deg: np.ndarray
    hs: dict[str, ReturnLevels]
    current: dict[str, ReturnLevels] | None
    joint: JointModel
    contours: dict[float, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    current_model: CurrentModel | None = None
    tail: TailCheck | None = None
    """The omnidirectional H_s fit's tail guard, exponential alternative and censored storms
    (:mod:`onbottom.metocean.tail`); None when it has no fit."""

    def to_dataset(self):
        """Return levels, thresholds, storm counts and contours as an xarray Dataset (SI,
        provenance attributes)."""
        import xarray as xr

        from onbottom.results import provenance

        names = ["omni", *self.sectors]
        rps = np.asarray(self.options.return_periods, dtype=float)
        coords = {"sector": names, "return_period": rps}

        def block(levels: dict[str, ReturnLevels], prefix: str, unit: str, what: str) -> dict:
            two = ("sector", "return_period")
            conf = f"{self.options.confidence:g}"
            out = {}
            for key, long_name in (
                ("value", f"{what} return value"),
                ("lower", f"lower {conf} confidence bound"),
                ("upper", f"upper {conf} confidence bound"),
            ):
                arr = np.array([getattr(levels[s], key) for s in names])
                var = f"{prefix}_return_value" if key == "value" else f"{prefix}_{key}"
                out[var] = (two, arr, {"units": unit, "long_name": long_name})
            for var, get, u, long_name in (
                ("threshold", lambda lv: lv.storms.threshold, unit, "POT threshold u"),
                ("storms", lambda lv: lv.storms.peak.size, "1", "declustered storms"),
                ("gpd_shape", lambda lv: lv.shape, "1", "GPD shape xi"),
                ("gpd_scale", lambda lv: lv.scale, unit, "GPD scale sigma"),
            ):
                vals = [get(levels[s]) for s in names]
                out[f"{prefix}_{var}"] = ("sector", vals, {"units": u, "long_name": long_name})
            return out

        data = block(self.hs, "hs", "m", "significant wave height")
        if self.current is not None:
            data |= block(self.current, "current", "m/s", "current speed")
        ds = xr.Dataset(data, coords=coords)
        ds["sector_centre"] = (
            "sector",
            np.concatenate(([np.nan], self.centres_deg)),
            {"units": "deg", "long_name": "sector centre (coming from)"},
        )
        for rp, (h, t) in self.contours.items():
            tag = f"{rp:g}".replace(".", "p")
            ds[f"contour_{tag}y_hs"] = (f"contour_{tag}y_point", h, {"units": "m"})
            ds[f"contour_{tag}y_tp"] = (f"contour_{tag}y_point", t, {"units": "s"})
        o = self.options
        ds.attrs.update(
            provenance(
                "onbottom.metocean: POT/GPD per sector (pyextremes), DNV-RP-C205 Hs-Tp model"
                " and IFORM contours (virocon)",
                {
                    "sectors": o.sectors,
                    "return_periods": list(o.return_periods),
                    "storm_rate": o.storm_rate,
                    "r_hours": o.r_hours,
                    "confidence": o.confidence,
                    "ci_method": o.ci_method,
                    "n_bootstrap": o.n_bootstrap,
                    "seed": o.seed,
                },
                hindcast=self.hindcast.source,
                hindcast_years=self.hindcast.years,
                hindcast_step_hours=self.hindcast.step_hours,
                joint_model=self.joint.as_dict(),
                current_model=None if self.current_model is None else self.current_model.as_dict(),
                direction_convention="waves: coming from; current sectored by coming-from"
                " (going-to + 180 deg)",
                pyextremes_version=_version("pyextremes"),
                virocon_version=_version("virocon"),
            )
        )
        return ds


def _version(dist: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(dist)
    except PackageNotFoundError:
        return "unknown"


MIN_TARGET_STORMS = 20
"""Fewest storms the threshold aims at, whatever the rate (short records)."""


def _levels(values, hc: Hindcast, o: MetoceanOptions, name: str) -> ReturnLevels:
    values = np.where(np.isfinite(values), values, 0.0)  # a missing sea state is no storm
    rate = max(o.storm_rate, MIN_TARGET_STORMS / hc.years)
    u = (
        threshold_for_rate(values, hc.step_hours, o.r_hours, hc.years, rate)
        if np.count_nonzero(values > 0) > 1
        else np.inf
    )
    storms = storm_peaks(values, hc.step_hours, u, o.r_hours, hc.years)
    return fit_return_levels(
        values,
        hc.time,
        storms,
        o.return_periods,
        confidence=o.confidence,
        n_bootstrap=o.n_bootstrap,
        seed=o.seed,
        name=name,
        ci_method=o.ci_method,
        observed_years=hc.years if hc.n_missing else None,
    )


def analyse_hindcast(hindcast: Hindcast, options: MetoceanOptions | None = None) -> MetoceanResult:
    """Storms, return values per sector (H_s, current), joint model and contours, and (with
    current columns) the current's joint model with H_s (:mod:`onbottom.metocean.current`).

    Each series (omni and each sector's masked series) gets its own threshold, set so that
    about ``storm_rate`` storms a year (and at least :data:`MIN_TARGET_STORMS` in the record)
    exceed it, declustered with ``r_hours``. Missing sea states count as no storm, and the
    storm rate is per observed year; the joint models are fitted to the observed states.
    """
    o = options or MetoceanOptions()
    hc = hindcast
    positive("hindcast length", hc.years)
    if o.sectors > 1 and not hc.has_direction:
        err = InputError(
            f"sectors = {o.sectors} is invalid: the hindcast has no wave_direction_deg column"
            " (an omnidirectional analysis only: sectors = 1)"
        )
        err.field = "sectors"  # type: ignore[attr-defined]
        raise err
    centres, _ = sector_edges(o.sectors)
    names = sector_names(o.sectors)
    hs: dict[str, ReturnLevels] = {"omni": _levels(hc.hs, hc, o, "hs")}
    cur: dict[str, ReturnLevels] | None = None
    if hc.has_current:
        cur = {"omni": _levels(hc.current_speed, hc, o, "current")}
        cur_from = np.mod(hc.current_direction_deg + 180.0, 360.0)
    for k, name in enumerate(names):
        if o.sectors == 1:  # the one sector is the record
            hs[name] = hs["omni"]
            if cur is not None:
                cur[name] = cur["omni"]
            continue
        m = sector_mask(hc.wave_direction_deg, o.sectors, k)
        hs[name] = _levels(np.where(m, hc.hs, 0.0), hc, o, "hs")
        if cur is not None:
            mc = sector_mask(cur_from, o.sectors, k)
            cur[name] = _levels(np.where(mc, hc.current_speed, 0.0), hc, o, "current")
    obs = hc.observed
    joint = fit_joint_model(hc.hs[obs], hc.tp[obs])
    current_model = None
    if hc.has_current:
        current_model = fit_current_model(
            hc.hs[obs],
            hc.current_speed[obs],
            hs_scale=joint.hs_scale,
            hs_shape=joint.hs_shape,
            hs_location=joint.hs_location,
        )
    contours = {
        float(rp): iform_contour(joint, rp, hc.step_hours, o.contour_points)
        for rp in o.return_periods
    }
    tail = None
    omni = hs["omni"]
    if np.isfinite(omni.shape):
        tail = check_tail(
            omni, hc.hs, hc.observed, hc.time, hc.step_hours, omni.storms.peak.size / hc.years
        )
    return MetoceanResult(
        tail=tail,
        hindcast=hc,
        options=o,
        sectors=names,
        centres_deg=centres,
        hs=hs,
        current=cur,
        joint=joint,
        contours=contours,
        current_model=current_model,
    )
