"""From a hindcast to the DNV-RP-F109 design table, its notes and its case fragments — the
library side of ``onbottom metocean``.

:func:`run_metocean_analysis` runs the analysis (:func:`~onbottom.metocean.analysis.
analyse_hindcast`), builds the per-sector design table (:func:`~onbottom.metocean.table.
design_rows`), the ``case_<sector>.toml`` fragments (:func:`~onbottom.metocean.table.
sector_toml`) and the notes on what the result can be trusted for; :func:`write_metocean_outputs`
writes the table, the fragments and ``metocean.nc``. The figures and the report page are drawn
by :mod:`onbottom.plotting.metocean` and :mod:`onbottom.report.pages` (higher layers).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from onbottom.errors import InputError
from onbottom.metocean.analysis import MetoceanOptions, MetoceanResult, analyse_hindcast
from onbottom.metocean.hindcast import Hindcast
from onbottom.metocean.table import DesignRow, design_rows, design_table_csv, sector_toml

__all__ = [
    "EXTRAPOLATION_FACTOR",
    "MetoceanRun",
    "extrapolation_note",
    "run_metocean_analysis",
    "write_metocean_outputs",
]

EXTRAPOLATION_FACTOR = 4.0
"""Return periods beyond this many times the record length get a note: the values are
extrapolations (Coles 2001, *An Introduction to Statistical Modeling of Extreme Values*,
§4.4)."""


def extrapolation_note(return_period: float, record_years: float) -> str | None:
    """The note of a return period [years] beyond :data:`EXTRAPOLATION_FACTOR` times the
    record's length [years] (None within it): the same words wherever such a value is used
    (``onbottom metocean``'s table, ``onbottom reliability``'s contour design)."""
    if return_period <= EXTRAPOLATION_FACTOR * record_years:
        return None
    return (
        f"return periods up to {return_period:g} years from a {record_years:.1f}-year record:"
        f" beyond about {EXTRAPOLATION_FACTOR:g} times the record the values are extrapolations"
        " (Coles 2001 §4.4); read the intervals"
    )


_ROW_KEYS = (
    "hs",
    "hs_lower",
    "hs_upper",
    "tp",
    "tp_low",
    "tp_high",
    "current",
    "current_lower",
    "current_upper",
    "current_with_hs",
    "current_with_hs_p90",
)


@dataclass(frozen=True, eq=False, slots=True)
class MetoceanRun:
    """The analysis of one hindcast with its design table, notes and case fragments (see
    :func:`run_metocean_analysis`).

    Attributes
    ----------
    result : MetoceanResult
        Storms, return values, joint models and contours.
    rows : list of DesignRow
        The design table, omni first (H_s and T_p in m and s, current in m/s).
    notes : list of str
        Where the result needs care: extrapolated return periods, no F109 fragments, sectors
        without values and why, sectors whose fragment could not be made.
    fragments : dict of str to str
        Sector label → text of its ``case_<sector>.toml`` (``[waves]``, ``[current]``, the two
        F109 §3.4.2 ``[[combinations]]``), in the table's order; empty when the return periods
        lack 10 or 100 years or the hindcast has no current.
    source : str
        The hindcast named in the fragments and the JSON summary.
    """

    result: MetoceanResult
    rows: list[DesignRow]
    notes: list[str]
    fragments: dict[str, str]
    source: str

    @property
    def hindcast(self) -> Hindcast:
        """The analysed hindcast."""
        return self.result.hindcast

    @property
    def options(self) -> MetoceanOptions:
        """The analysis options."""
        return self.result.options

    @property
    def success(self) -> bool:
        """True when the omnidirectional H_s has a finite value at every return period."""
        return bool(np.all(np.isfinite(self.result.hs["omni"].value)))

    def contour_check(self) -> dict[str, Any] | None:
        """:func:`~onbottom.metocean.joint.marginal_tail_check` at the longest return period
        (None when the omnidirectional H_s has no value there)."""
        from onbottom.metocean.joint import marginal_tail_check, tp_at_peaks_check

        lv = self.result.hs["omni"]
        rp = float(max(self.options.return_periods))
        v = float(lv.value[list(lv.return_periods).index(rp)])
        if not math.isfinite(v):
            return None
        hc = self.hindcast
        out = marginal_tail_check(self.result.joint, hc.hs[hc.observed], rp, hc.step_hours, v)
        idx = lv.storms.index
        out["tp_at_peaks"] = tp_at_peaks_check(self.result.joint, hc.hs[idx], hc.tp[idx])
        return out

    def as_dict(self, files: list[str] | None = None) -> dict[str, Any]:
        """The ``onbottom metocean --json`` summary (SI; NaN written as None); ``files``: the
        paths written (see the command's documentation for the keys)."""

        def lst(x):
            return None if x is None else [v if math.isfinite(v) else None for v in x]

        result, o = self.result, self.options
        return {
            "success": self.success,
            "hindcast": self.source,
            "years": self.hindcast.years,
            "step_hours": self.hindcast.step_hours,
            "sectors": result.sectors,
            "return_periods": list(o.return_periods),
            "ci_method": o.ci_method,
            "confidence": o.confidence,
            "table": [
                {
                    "sector": r.sector,
                    "centre_deg": r.centre_deg if math.isfinite(r.centre_deg) else None,
                    **{k: lst(getattr(r, k)) for k in _ROW_KEYS},
                }
                for r in self.rows
            ],
            "joint_model": result.joint.as_dict(),
            "current_model": (
                None if result.current_model is None else result.current_model.as_dict()
            ),
            "contour_max_hs": {f"{rp:g}": float(h.max()) for rp, (h, _) in result.contours.items()},
            "tail": None if result.tail is None else result.tail.to_dict(),
            "contour_check": self.contour_check(),
            "files": list(files or []),
            "notes": list(self.notes),
        }


def run_metocean_analysis(
    hindcast: Hindcast,
    options: MetoceanOptions | None = None,
    *,
    source: str | None = None,
    pipe_heading_deg: float | None = None,
    current_height: float = 1.0,
) -> MetoceanRun:
    """Analyse ``hindcast`` and build its DNV-RP-F109 design table, case fragments and notes.

    Parameters
    ----------
    hindcast : Hindcast
        The record (:func:`~onbottom.metocean.hindcast.read_hindcast`).
    options : MetoceanOptions or None
        Sectors, return periods [years], threshold rate, declustering, intervals; default
        :class:`~onbottom.metocean.analysis.MetoceanOptions`.
    source : str or None
        The hindcast named in the fragments' header and the summary; default
        ``hindcast.source``.
    pipe_heading_deg : float or None
        Pipe axis heading [deg from north]: sets ``direction_deg`` of the fragments (None:
        90°, waves normal to the pipe).
    current_height : float
        Height above the seabed of the hindcast's current [m] (the fragments'
        ``reference_height``).

    Returns
    -------
    MetoceanRun
        Fragments only when the return periods include 10 and 100 years and the hindcast has a
        current (F109 §3.4.2); a sector whose values cannot make a fragment (too few storms)
        gets a note instead.
    """
    o = options or MetoceanOptions()
    hc = hindcast
    src = hc.source if source is None else source
    result = analyse_hindcast(hc, o)
    rows = design_rows(result)
    from onbottom.metocean.hindcast import hindcast_notes

    notes: list[str] = hindcast_notes(hc)
    note = extrapolation_note(max(o.return_periods), hc.years)
    if note:
        notes.append(note)
    f109 = 10.0 in o.return_periods and 100.0 in o.return_periods and hc.has_current
    if not f109:
        notes.append(
            "no case_*.toml: the F109 combinations need the 10- and 100-year values and a"
            " current in the hindcast"
        )
    fragments: dict[str, str] = {}
    for row in rows:
        lv = result.hs[row.sector]
        if lv.note:
            notes.append(f"H_s {row.sector}: {lv.note}")
        if result.current is not None and result.current[row.sector].note:
            notes.append(f"current {row.sector}: {result.current[row.sector].note}")
        if not f109:
            continue
        try:
            fragments[row.sector] = sector_toml(
                row, source=src, pipe_heading_deg=pipe_heading_deg, current_height=current_height
            )
        except InputError as exc:
            notes.append(f"no case_{row.sector}.toml: {exc}")
    if result.tail is not None:  # the tail guard and the censored storms
        notes.extend(f"H_s omni: {w}" for w in result.tail.warnings)
        if result.tail.censored_peaks:
            notes.append(
                f"H_s omni: {len(result.tail.censored_peaks)} storm(s) end at a data gap of"
                " 12 h or more (peak censored: "
                + ", ".join(f"{v:.2f} at {t}" for t, v in result.tail.censored_peaks)
                + "); the censored fit is in the JSON key tail.censored_fit"
            )
    return MetoceanRun(result=result, rows=rows, notes=notes, fragments=fragments, source=src)


def write_metocean_outputs(run: MetoceanRun, out: str | Path, *, group: Any = None) -> list[Path]:
    """Write ``design_table.csv``, the ``case_<sector>.toml`` fragments and ``metocean.nc``
    into the folder ``out`` (created if missing). Returns the paths in that order.

    The files are one set (:class:`onbottom.results.OutputSet`): each is written under a
    temporary name and they are renamed together once all are written, so a failure (a full
    disk) leaves none of them under its final name. ``group``: an open
    :class:`~onbottom.results.OutputSet` of the caller (more files to come: the caller
    commits); None: this call commits its own.
    """
    from onbottom.results import OutputSet, save_dataset, write_text_atomic

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    own = group is None
    g = OutputSet() if own else group
    try:
        files = [write_text_atomic(out / "design_table.csv", design_table_csv(run.rows), group=g)]
        for sector, text in run.fragments.items():
            files.append(write_text_atomic(out / f"case_{sector}.toml", text, group=g))
        files.append(save_dataset(run.result.to_dataset(), out / "metocean.nc", group=g))
    except BaseException:
        if own:
            g.discard()
        raise
    if own:
        g.commit()
    return [Path(f) for f in files]
