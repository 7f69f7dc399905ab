"""The design table: per sector, the values DNV-RP-F109's load combinations need.

F109 (2010/2017) §3.4.2: without joint statistics of waves and current, the design
environment is the more severe of the 100-year wave with the 10-year current and the 10-year
wave with the 100-year current (:func:`onbottom.inputs.environment.f109_combinations`).
Per sector (and omni) the table gives H_s for every return period (POT/GPD, with its
confidence interval), the T_p that goes with it (median of T_p | H_s of the joint model, and
its 5 %–95 % range, which F109 §3.4.4 asks to scan), the current speed for every return
period (POT of the sector's current), and — with joint statistics of waves and current
(:mod:`onbottom.metocean.current`) — the current that goes with each return-period H_s: the
median and the 90 % quantile of U | H_s (omnidirectional copula; the joint-statistics
alternative F109 §3.4.2 opens to its two combinations).

Written as ``design_table.csv`` (one row per sector) and, per sector, a TOML fragment with
``[waves]`` (100-year), ``[current]`` (10-year) and the two ``[[combinations]]`` in the keys of
``onbottom stability`` / ``onbottom storm`` case files (examples/stability_case.toml): paste it
over those tables of a case.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onbottom.errors import InputError
from onbottom.inputs.storm import Current, SeaState
from onbottom.metocean.analysis import MetoceanResult

__all__ = ["DesignRow", "design_rows", "design_table_csv", "sector_toml"]


@dataclass(frozen=True, slots=True)
class DesignRow:
    """One sector's design values (SI; NaN where the sector has too few storms).

    Attributes
    ----------
    sector : str
        Label ('omni', 'N', …).
    centre_deg : float
        Sector centre, coming from [deg] (NaN for omni).
    return_periods : tuple of float
        R [years].
    hs, hs_lower, hs_upper : tuple of float
        H_s [m] and its interval per R.
    tp, tp_low, tp_high : tuple of float
        Median T_p [s] given that H_s, and the 5 % and 95 % conditional quantiles.
    current, current_lower, current_upper : tuple of float or None
        Current speed [m/s] per R and its interval (None without current).
    current_with_hs, current_with_hs_p90 : tuple of float or None
        Median and 90 % quantile of the current speed [m/s] given the R-year H_s of the
        row (joint model; None without current).
    """

    sector: str
    centre_deg: float
    return_periods: tuple[float, ...]
    hs: tuple[float, ...]
    hs_lower: tuple[float, ...]
    hs_upper: tuple[float, ...]
    tp: tuple[float, ...]
    tp_low: tuple[float, ...]
    tp_high: tuple[float, ...]
    current: tuple[float, ...] | None
    current_lower: tuple[float, ...] | None
    current_upper: tuple[float, ...] | None
    current_with_hs: tuple[float, ...] | None = None
    current_with_hs_p90: tuple[float, ...] | None = None

    def at(self, what: str, return_period: float) -> float:
        """Value of column ``what`` (``"hs"``, ``"tp"``, ``"current"``…) at R [years]."""
        i = self.return_periods.index(float(return_period))
        vals = getattr(self, what)
        return math.nan if vals is None else float(vals[i])


def design_rows(result: MetoceanResult) -> list[DesignRow]:
    """The table's rows: omni first, then the sectors."""
    rps = tuple(float(r) for r in result.options.return_periods)
    rows = []
    centres = [math.nan, *map(float, result.centres_deg)]
    for name, c in zip(["omni", *result.sectors], centres, strict=True):
        lv = result.hs[name]
        hs = np.asarray(lv.value)
        ok = np.isfinite(hs)
        safe = np.where(ok, hs, 1.0)
        tp = np.where(ok, result.joint.tp_quantile(safe, 0.5), np.nan)
        lo = np.where(ok, result.joint.tp_quantile(safe, 0.05), np.nan)
        hi = np.where(ok, result.joint.tp_quantile(safe, 0.95), np.nan)
        cv = cl = cu = None
        if result.current is not None:
            cr = result.current[name]
            cv, cl, cu = (tuple(map(float, a)) for a in (cr.value, cr.lower, cr.upper))
        cj = cj90 = None
        if result.current_model is not None:
            cm = result.current_model
            cj = tuple(float(v) for v in np.where(ok, cm.quantile(safe, 0.5), np.nan))
            cj90 = tuple(float(v) for v in np.where(ok, cm.quantile(safe, 0.9), np.nan))
        rows.append(
            DesignRow(
                sector=name,
                centre_deg=c,
                return_periods=rps,
                hs=tuple(map(float, hs)),
                hs_lower=tuple(map(float, lv.lower)),
                hs_upper=tuple(map(float, lv.upper)),
                tp=tuple(map(float, tp)),
                tp_low=tuple(map(float, lo)),
                tp_high=tuple(map(float, hi)),
                current=cv,
                current_lower=cl,
                current_upper=cu,
                current_with_hs=cj,
                current_with_hs_p90=cj90,
            )
        )
    return rows


def design_table_csv(rows: list[DesignRow]) -> str:
    """The table as CSV text: a header, a units row, one row per sector."""
    r0 = rows[0]
    cols: list[tuple[str, str]] = [("sector", "-"), ("centre_deg", "deg")]
    for rp in r0.return_periods:
        t = f"{rp:g}y"
        cols += [
            (f"hs_{t}", "m"),
            (f"hs_{t}_lower", "m"),
            (f"hs_{t}_upper", "m"),
            (f"tp_{t}", "s"),
            (f"tp_{t}_p05", "s"),
            (f"tp_{t}_p95", "s"),
        ]
        if r0.current is not None:
            cols += [
                (f"current_{t}", "m/s"),
                (f"current_{t}_lower", "m/s"),
                (f"current_{t}_upper", "m/s"),
            ]
        if r0.current_with_hs is not None:
            cols += [(f"current_with_hs_{t}", "m/s"), (f"current_with_hs_{t}_p90", "m/s")]
    lines = [",".join(c for c, _ in cols), ",".join(u for _, u in cols)]

    def f(x: float, nd: int) -> str:
        return "" if not math.isfinite(x) else f"{x:.{nd}f}"

    for r in rows:
        vals = [r.sector, f(r.centre_deg, 1)]
        for i in range(len(r.return_periods)):
            vals += [
                f(r.hs[i], 2),
                f(r.hs_lower[i], 2),
                f(r.hs_upper[i], 2),
                f(r.tp[i], 2),
                f(r.tp_low[i], 2),
                f(r.tp_high[i], 2),
            ]
            if r.current is not None:
                vals += [f(r.current[i], 3), f(r.current_lower[i], 3), f(r.current_upper[i], 3)]
            if r.current_with_hs is not None:
                vals += [f(r.current_with_hs[i], 3), f(r.current_with_hs_p90[i], 3)]
        lines.append(",".join(vals))
    return "\n".join(lines) + "\n"


def sector_toml(
    row: DesignRow,
    *,
    source: str,
    pipe_heading_deg: float | None = None,
    current_height: float = 1.0,
) -> str:
    """A TOML fragment of ``[waves]``, ``[current]`` and the two F109 ``[[combinations]]``
    for one sector, in the keys of ``stability``/``storm`` case files.

    Parameters
    ----------
    row : DesignRow
        The sector's values (needs the 10- and 100-year return periods).
    source : str
        The hindcast named in the header comment.
    pipe_heading_deg : float or None
        Pipe axis heading [deg from north]; when given, ``direction_deg`` (the wave direction
        to the pipe axis) is the sector centre minus the heading, modulo 360 (omni: 90°, the
        worst case).
    current_height : float
        Height above the seabed of the hindcast current [m] (``reference_height``).

    Raises
    ------
    InputError
        10 or 100 years missing from the return periods, or no values for them (too few
        storms in the sector), or values that are no valid sea state/current.
    """
    for rp in (10.0, 100.0):
        if rp not in row.return_periods:
            raise InputError(
                f"return_periods = {list(row.return_periods)!r} is invalid for the F109 table:"
                " include 10 and 100 (F109 §3.4.2)"
            )
    if row.current is None:
        raise InputError("the hindcast has no current columns: the F109 table needs them")
    hs100, tp100 = row.at("hs", 100), row.at("tp", 100)
    hs10, tp10 = row.at("hs", 10), row.at("tp", 10)
    c10, c100 = row.at("current", 10), row.at("current", 100)
    if not all(math.isfinite(x) for x in (hs100, tp100, hs10, tp10, c10, c100)):
        raise InputError(
            f"sector {row.sector}: too few storms for 10- and 100-year values (NaN in the table)"
        )
    if pipe_heading_deg is None or not math.isfinite(row.centre_deg):
        direction = 90.0
        dir_note = "worst case, waves normal to the pipe"
        if math.isfinite(row.centre_deg):
            dir_note += " (--pipe-heading-deg gives the sector's own)"
    else:
        direction = (row.centre_deg - pipe_heading_deg) % 360.0
        dir_note = f"sector centre {row.centre_deg:g}° − pipe heading {pipe_heading_deg:g}°"
    # the values must be valid inputs of the cases that paste them
    SeaState(hs=round(hs100, 2), tp=round(tp100, 2), direction_deg=direction)
    SeaState(hs=round(hs10, 2), tp=round(tp10, 2), direction_deg=direction)
    Current(velocity=round(c10, 3), reference_height=current_height, direction_deg=direction)
    Current(velocity=round(c100, 3), reference_height=current_height, direction_deg=direction)
    where = (
        "all directions"
        if row.sector == "omni"
        else (f"sector {row.sector} (waves from {row.centre_deg:g}°)")
    )
    lines = [
        f"# onbottom metocean — {where}; hindcast {source}",
        "# H_s: POT/GPD return values (pyextremes); T_p: median of T_p|H_s (DNV-RP-C205 §3.6.3",
        f"# joint model, virocon); 100-yr T_p 5–95 %: {row.at('tp_low', 100):.1f}–"
        f"{row.at('tp_high', 100):.1f} s (F109 §3.4.4: check the range)",
        "",
        "[waves]                         # 100-year sea state",
        f"hs = {hs100:.2f}                     # m (CI {row.at('hs_lower', 100):.2f}–"
        f"{row.at('hs_upper', 100):.2f})",
        f"tp = {tp100:.2f}                    # s",
        f"direction_deg = {direction:.1f}            # to the pipe axis: {dir_note}",
        "",
        "[current]                       # 10-year current",
        f"velocity = {c10:.3f}               # m/s at reference_height",
        f"reference_height = {current_height:g}          # m above the seabed of the"
        " hindcast's current",
        f"direction_deg = {direction:.1f}",
        "",
        "[[combinations]]",
        'name = "100-yr wave + 10-yr current"',
        "",
        "[[combinations]]",
        'name = "10-yr wave + 100-yr current"',
        f"hs = {hs10:.2f}",
        f"tp = {tp10:.2f}",
        f"current_velocity = {c100:.3f}",
        "",
    ]
    if row.current_with_hs is not None:
        cj, cj90 = row.at("current_with_hs", 100), row.at("current_with_hs_p90", 100)
        lines += [
            "# Joint statistics of waves and current (F109 §3.4.2 allows them in place of the",
            f"# two combinations): the current with the 100-year H_s is {cj:.3f} m/s (median),",
            f"# {cj90:.3f} m/s (90 %) — Weibull current, Gaussian copula with H_s"
            " (docs/theory/metocean.md).",
            "",
        ]
    return "\n".join(lines)
