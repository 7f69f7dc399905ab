"""Hindcast time series: the strict CSV / NetCDF schema, its checks, and :class:`Hindcast`.

CSV layout (``#`` lines are comments; a header row, then a **units row**, then data)::

    time,hs,tp,wave_direction_deg,current_speed,current_direction_deg
    UTC,m,s,deg,m/s,deg
    2000-01-01T00:00:00Z,0.85,7.59,166.9,0.331,24.4

* ``time``: ISO 8601, UTC (a trailing ``Z`` or none; no other offset), strictly increasing at
  one constant step (gaps, duplicates and times out of order are errors naming the rows).
* ``hs`` significant wave height [m], ``tp`` spectral peak period [s],
  ``wave_direction_deg`` the direction the waves come **from** [deg, clockwise from north].
* ``current_speed`` [m/s] and ``current_direction_deg`` the direction the current goes **to**
  [deg] (oceanographic conventions). The two current columns are optional together;
  ``wave_direction_deg`` is optional too (a record without directions: ``time,hs,tp``, analysed
  omnidirectionally only).
* **Missing sea states** (a buoy's outages): a row whose values are all empty, at its place in
  the regular time grid — never a skipped time (a skipped time is a gap, an error). A row with
  some values empty and others not is an error. The record length counts the observed sea
  states only (:attr:`Hindcast.years`).

NetCDF: a ``time`` coordinate and the same variable names, each with a ``units`` attribute
(``m``; ``s``; ``deg``/``degree``/``degrees``; ``m/s``/``m s-1``).

Impossible values are errors naming the row and time: non-finite values, H_s outside
[0, 30] m, T_p outside (0, 40] s, a steepness 2πH_s/(gT_p²) above 1/7 (breaking), directions
outside [0, 360] deg, a current speed outside [0, 10] m/s, and a direction column whose values
all lie within [0, 2π] (radians, not degrees). Implausible but possible values are notes
(:func:`hindcast_notes`): an H_s that rises faster than :data:`SPIKE_RISE_M_PER_H` between
two steps (a spike, such as a one-day 25 m value in a 3 m sea).
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from onbottom._validate import header_mismatch
from onbottom.constants import GRAVITY
from onbottom.errors import InputError

__all__ = [
    "COLUMNS",
    "UNITS",
    "Hindcast",
    "hindcast_notes",
    "read_hindcast",
    "write_hindcast_csv",
]

COLUMNS: tuple[str, ...] = (
    "time",
    "hs",
    "tp",
    "wave_direction_deg",
    "current_speed",
    "current_direction_deg",
)
"""Column names of the schema, in file order (the two current columns are optional)."""
UNITS: dict[str, tuple[str, ...]] = {
    "time": ("UTC",),
    "hs": ("m",),
    "tp": ("s",),
    "wave_direction_deg": ("deg", "degree", "degrees"),
    "current_speed": ("m/s", "m s-1"),
    "current_direction_deg": ("deg", "degree", "degrees"),
}
"""Accepted unit spellings per column (the first is written)."""
MAX_STEEPNESS = 1.0 / 7.0
"""Breaking limit of a wave's steepness 2πH/(gT²) (Michell 1893, deep water)."""
_LIMITS = {
    "hs": (0.0, 30.0, "m"),
    "tp": (0.0, 40.0, "s"),
    "wave_direction_deg": (0.0, 360.0, "deg"),
    "current_speed": (0.0, 10.0, "m/s"),
    "current_direction_deg": (0.0, 360.0, "deg"),
}
_MAX_LISTED = 5

_RADIANS_MIN_ROWS = 24
"""Fewest direction values for the radians check (a day of hourly data: directions of a real
record in degrees leave [0, 2π] ≈ [0, 6.3]° long before that)."""

SPIKE_RISE_M_PER_H = 2.0
"""Fastest plausible rise of H_s between two steps [m/h] (at least 4 m per step): storms build
up over hours (growth of about 0.5–1 m/h in the severest North Sea and hurricane records); a
faster rise is a spike in the data (a note names the rows, the value is kept)."""


def _fail(field: str, message: str) -> None:
    err = InputError(message)
    err.field = field  # type: ignore[attr-defined]
    raise err


@dataclass(frozen=True, eq=False, slots=True)
class Hindcast:
    """A checked hindcast time series (SI units; see the module docstring for conventions).

    Attributes
    ----------
    time : ndarray of datetime64[s]
        UTC times, strictly increasing at a constant step.
    hs : ndarray
        Significant wave height H_s [m].
    tp : ndarray
        Spectral peak period T_p [s].
    wave_direction_deg : ndarray or None
        Wave direction, coming from [deg] (None: not in the record).
    current_speed : ndarray or None
        Current speed [m/s].
    current_direction_deg : ndarray or None
        Current direction, going to [deg].
    source : str
        File it was read from (or a description).
    """

    time: np.ndarray
    hs: np.ndarray
    tp: np.ndarray
    wave_direction_deg: np.ndarray | None
    current_speed: np.ndarray | None
    current_direction_deg: np.ndarray | None
    source: str = ""

    def __post_init__(self) -> None:
        _check_series(self)

    @property
    def step_hours(self) -> float:
        """Sampling interval [h]."""
        return float((self.time[1] - self.time[0]) / np.timedelta64(1, "s")) / 3600.0

    @property
    def observed(self) -> np.ndarray:
        """Mask of the observed (not missing) sea states."""
        return np.isfinite(np.asarray(self.hs, dtype=float))

    @property
    def n_missing(self) -> int:
        """Missing sea states (rows left empty)."""
        return int(np.count_nonzero(~self.observed))

    @property
    def years(self) -> float:
        """Length observed, n_observed·Δt [years of 365.2425 d] (n·Δt without missing
        sea states)."""
        n = len(self.time) - self.n_missing
        return n * self.step_hours / (24.0 * 365.2425)

    @property
    def has_direction(self) -> bool:
        """Whether the wave direction column is present."""
        return self.wave_direction_deg is not None

    @property
    def has_current(self) -> bool:
        """Whether the current columns are present."""
        return self.current_speed is not None

    def series(self, name: str):
        """One column as a :class:`pandas.Series` indexed by time (for pyextremes)."""
        import pandas as pd

        return pd.Series(
            np.asarray(getattr(self, name), dtype=float),
            index=pd.DatetimeIndex(self.time.astype("datetime64[ns]"), name="date-time"),
            name=name,
        )


def _row_list(rows: np.ndarray, time: np.ndarray, offset: int, label: str) -> str:
    shown = ", ".join(
        f"{label} {int(r) + offset} ({str(time[r])[:19]})" for r in rows[:_MAX_LISTED]
    )
    more = f" and {len(rows) - _MAX_LISTED} more" if len(rows) > _MAX_LISTED else ""
    return shown + more


def _check_series(h: Hindcast, row_offset: int = 0, label: str = "index") -> None:
    """Schema and value checks; ``row_offset`` turns array indices into file lines (``label``
    names them: ``"line"`` for CSV, ``"index"`` for arrays and NetCDF)."""
    off = row_offset
    n = len(h.time)
    if n < 3:
        _fail("time", f"time = {n} rows is invalid: a hindcast needs at least 3 time steps")
    names = ["hs", "tp"] + (["wave_direction_deg"] if h.wave_direction_deg is not None else [])
    if (h.current_speed is None) != (h.current_direction_deg is None):
        _fail(
            "current_speed",
            "current_speed/current_direction_deg is invalid: give both current columns or none",
        )
    if h.current_speed is not None:
        names += ["current_speed", "current_direction_deg"]
    for name in names:
        a = getattr(h, name)
        if len(a) != n:
            _fail(name, f"{name} has {len(a)} values for {n} times")
    t = h.time
    dt = np.diff(t.astype("datetime64[s]").astype(np.int64))
    bad = np.flatnonzero(dt < 0) + 1
    if bad.size:
        _fail(
            "time",
            f"time is invalid: not increasing at {_row_list(bad, t, off, label)} (earlier"
            " than the row before; sort the file)",
        )
    dup = np.flatnonzero(dt == 0) + 1
    if dup.size:
        _fail("time", f"time is invalid: duplicate time stamps at {_row_list(dup, t, off, label)}")
    vals, counts = np.unique(dt, return_counts=True)
    step = int(vals[np.argmax(counts)])  # the most common step (the smallest on ties)
    gaps = np.flatnonzero(dt != step) + 1
    if gaps.size:
        what = ", ".join(
            f"{str(t[g - 1])[:19]} → {str(t[g])[:19]} ({dt[g - 1] / 3600.0:g} h)"
            for g in gaps[:_MAX_LISTED]
        )
        more = f" and {gaps.size - _MAX_LISTED} more" if gaps.size > _MAX_LISTED else ""
        _fail(
            "time",
            f"time is invalid: the step is {step / 3600.0:g} h but {gaps.size} interval(s)"
            f" differ (gaps or irregular sampling) at {label} "
            f"{', '.join(str(int(g) + off) for g in gaps[:_MAX_LISTED])}: {what}{more}; fill or"
            " split the record",
        )
    missing = ~np.isfinite(np.asarray(h.hs, dtype=float))
    given = np.zeros(n, dtype=bool)
    for name in names[1:]:
        given |= np.isfinite(np.asarray(getattr(h, name), dtype=float))
    partial = np.flatnonzero(missing & given)
    if partial.size:
        _fail(
            "hs",
            f"hs is invalid: missing or non-finite values at {_row_list(partial, t, off, label)}"
            " where the row's other values are given (a missing sea state leaves every value of"
            " its row empty)",
        )
    if n - np.count_nonzero(missing) < 3:
        _fail("hs", f"hs is invalid: {n - np.count_nonzero(missing)} observed sea states (< 3)")
    for name in names:
        a = np.asarray(getattr(h, name), dtype=float)
        lo, hi, unit = _LIMITS[name]
        nonfinite = np.flatnonzero(~np.isfinite(a) & ~missing)
        if nonfinite.size:
            _fail(
                name,
                f"{name} is invalid: missing or non-finite values at"
                f" {_row_list(nonfinite, t, off, label)} (a missing sea state leaves every"
                " value of its row empty)",
            )
        if name == "tp":
            out = np.flatnonzero((a <= lo) | (a > hi))
            rng = f"({lo:g}, {hi:g}]"
        else:
            out = np.flatnonzero((a < lo) | (a > hi))
            rng = f"[{lo:g}, {hi:g}]"
        if out.size:
            r = out[0]
            _fail(
                name,
                f"{name} = {a[r]!r} {unit} is invalid at {_row_list(out, t, off, label)}:"
                f" must lie in {rng} {unit} (check the unit)",
            )
    for name in ("wave_direction_deg", "current_direction_deg"):
        a = getattr(h, name)
        if a is None:
            continue
        a = np.asarray(a, dtype=float)
        ok = a[np.isfinite(a)]
        if ok.size >= _RADIANS_MIN_ROWS and float(np.max(ok)) <= 2.0 * math.pi + 1e-9:
            _fail(
                name,
                f"{name} is invalid: all {ok.size} values lie within [0, 2π] ="
                f" [0, {2.0 * math.pi:.4g}] (max {float(np.max(ok)):.4g}): they look like"
                " radians; the column is in degrees [0, 360] (multiply by 180/π)",
            )
    with np.errstate(invalid="ignore"):
        steep = 2.0 * math.pi * np.asarray(h.hs) / (GRAVITY * np.asarray(h.tp) ** 2)
        over = np.flatnonzero(steep > MAX_STEEPNESS)
    if over.size:
        r = over[0]
        _fail(
            "tp",
            f"hs, tp = {h.hs[r]:g} m, {h.tp[r]:g} s is invalid at"
            f" {_row_list(over, t, off, label)}: the steepness 2πH_s/(gT_p²) ="
            f" {steep[r]:.3g} exceeds the breaking limit 1/7"
            " (is T_p a zero-crossing or a mean period, or in the wrong unit?)",
        )


def _parse_time(text: str, row: int) -> np.datetime64:
    s = text.strip()
    if s.endswith("Z"):
        s = s[:-1]
    if "+" in s[10:] or s[10:].count("-") > 0:
        _fail("time", f"time = {text!r} is invalid at line {row}: give UTC (a trailing Z or none)")
    try:
        return np.datetime64(s, "s")
    except ValueError:
        _fail(
            "time",
            f"time = {text!r} is invalid at line {row}: expected ISO 8601, e.g."
            " 2000-01-01T00:00:00Z",
        )
    raise AssertionError  # unreachable


def _read_csv(path: Path) -> Hindcast:
    with path.open(encoding="utf-8", newline="") as fh:
        lines = [
            (i + 1, ln) for i, ln in enumerate(fh) if ln.strip() and not ln.lstrip().startswith("#")
        ]
    if len(lines) < 2:
        _fail("header", f"{path}: expected a header row and a units row, then data")
    header_row, header = lines[0]
    cols = [c.strip() for c in next(csv.reader([header]))]
    allowed = (list(COLUMNS), list(COLUMNS[:4]), list(COLUMNS[:3]))
    if cols not in allowed:
        _fail(
            "header",
            f"header (line {header_row}) is invalid ({header_mismatch(cols, COLUMNS)}):"
            " expected"
            f" {','.join(COLUMNS)!r} (the two current columns may be left out, and then the"
            " wave direction too)",
        )
    units_row, units_line = lines[1]
    units = [u.strip() for u in next(csv.reader([units_line]))]
    if len(units) != len(cols):
        _fail(
            "units",
            f"units row (line {units_row}) has {len(units)} entries for {len(cols)} columns",
        )
    for c, u in zip(cols, units, strict=True):
        if u not in UNITS[c]:
            _fail(
                c,
                f"{c} unit = {u!r} (line {units_row}) is invalid: expected"
                f" {' or '.join(map(repr, UNITS[c]))} (convert the column to SI)",
            )
    n = len(lines) - 2
    if n < 1:
        _fail(
            "time",
            f"{path}: no data rows after the header and the units row (line {units_row}): a"
            " hindcast needs at least 3 time steps",
        )
    time = np.empty(n, dtype="datetime64[s]")
    data = np.empty((n, len(cols) - 1))
    for k, (lineno, ln) in enumerate(lines[2:]):
        parts = ln.rstrip("\r\n").split(",")
        if len(parts) != len(cols):
            _fail("row", f"line {lineno} has {len(parts)} fields: expected {len(cols)}")
        time[k] = _parse_time(parts[0], lineno)
        for j, p in enumerate(parts[1:]):
            try:
                data[k, j] = float(p) if p.strip() else math.nan
            except ValueError:
                _fail(
                    cols[j + 1],
                    f"{cols[j + 1]} = {p!r} is invalid at line {lineno}: expected a number",
                )
    rows = np.array([ln for ln, _ in lines[2:]])
    cur = len(cols) == 6
    h = Hindcast.__new__(Hindcast)
    fields = dict(
        time=time,
        hs=data[:, 0],
        tp=data[:, 1],
        wave_direction_deg=data[:, 2] if len(cols) > 3 else None,
        current_speed=data[:, 3] if cur else None,
        current_direction_deg=data[:, 4] if cur else None,
        source=str(path),
    )
    for k, v in fields.items():
        object.__setattr__(h, k, v)
    # messages name file lines: the data lines are consecutive (comments only above them)
    if np.any(np.diff(rows) != 1):
        _fail(
            "row",
            f"{path}: comment or blank lines among the data (after line"
            f" {rows[np.flatnonzero(np.diff(rows) != 1)[0]]})",
        )
    _check_series(h, row_offset=int(rows[0]), label="line")
    return h


def _read_netcdf(path: Path) -> Hindcast:
    import xarray as xr

    try:
        ds = xr.open_dataset(path)
    except (OSError, ValueError) as exc:
        _fail("file", f"{path}: cannot be read as NetCDF ({exc})")
    with ds:
        if "time" not in ds.coords and "time" not in ds:
            _fail("time", f"{path}: no 'time' coordinate")
        needed = list(COLUMNS[1:3])
        if "wave_direction_deg" in ds:
            needed.append("wave_direction_deg")
        cur = "current_speed" in ds or "current_direction_deg" in ds
        if cur:
            needed += list(COLUMNS[4:])
        arrays = {}
        for name in needed:
            if name not in ds:
                _fail(
                    name,
                    f"{path}: variable {name!r} is missing (expected {', '.join(COLUMNS[1:])})",
                )
            u = str(ds[name].attrs.get("units", ""))
            if u not in UNITS[name]:
                _fail(
                    name,
                    f"{name} units = {u!r} is invalid: expected"
                    f" {' or '.join(map(repr, UNITS[name]))} (a 'units' attribute in SI)",
                )
            arrays[name] = np.asarray(ds[name].values, dtype=float).ravel()
        time = np.asarray(ds["time"].values)
        if not np.issubdtype(time.dtype, np.datetime64):
            _fail(
                "time",
                f"{path}: 'time' is not decoded as dates (give CF 'units' like"
                " 'hours since 2000-01-01')",
            )
        time = time.astype("datetime64[s]")
    h = Hindcast.__new__(Hindcast)
    for k, v in dict(
        time=time,
        hs=arrays["hs"],
        tp=arrays["tp"],
        wave_direction_deg=arrays.get("wave_direction_deg"),
        current_speed=arrays.get("current_speed"),
        current_direction_deg=arrays.get("current_direction_deg"),
        source=str(path),
    ).items():
        object.__setattr__(h, k, v)
    _check_series(h)  # NetCDF: time indices from 0
    return h


def hindcast_notes(h: Hindcast) -> list[str]:
    """Notes on a valid hindcast's plausibility: H_s rises faster than
    :data:`SPIKE_RISE_M_PER_H` (at least 4 m in one step), naming the first rows (file or
    array rows, times). The values are kept: a note, not an error."""
    hs = np.asarray(h.hs, dtype=float)
    ok = np.flatnonzero(np.isfinite(hs))
    if ok.size < 2:
        return []
    step_h = h.step_hours
    rise = np.diff(hs[ok])
    hours = np.diff(ok) * step_h
    limit = np.maximum(SPIKE_RISE_M_PER_H * hours, 4.0)
    jumps = np.flatnonzero(rise > limit)
    if not jumps.size:
        return []
    rows = ok[jumps + 1]
    shown = ", ".join(
        f"{str(h.time[r])[:19]} ({hs[ok[j]]:.3g} → {hs[r]:.3g} m)"
        for j, r in zip(jumps[:_MAX_LISTED], rows[:_MAX_LISTED], strict=True)
    )
    more = f" and {rows.size - _MAX_LISTED} more" if rows.size > _MAX_LISTED else ""
    return [
        f"hs: {rows.size} outlier(s): H_s rises faster than {SPIKE_RISE_M_PER_H:g} m/h (at"
        f" least 4 m in one {step_h:g}-h step) at {shown}{more}; a spike in the data? The"
        " values are used as given: check the record"
    ]


def read_hindcast(path: str | os.PathLike) -> Hindcast:
    """Read and check a hindcast (``.csv`` or ``.nc``); see the module docstring.

    Raises
    ------
    InputError
        Wrong columns or units, gaps, duplicates, times out of order, impossible values —
        naming the column, the row (file line for CSV, time index for NetCDF) and the time.
    """
    p = Path(path)
    if not p.is_file():
        _fail("HINDCAST", f"HINDCAST = {str(p)!r} is invalid: no such file")
    suffix = p.suffix.lower()
    if suffix == ".csv":
        return _read_csv(p)
    if suffix in (".nc", ".nc4", ".netcdf"):
        return _read_netcdf(p)
    _fail("HINDCAST", f"HINDCAST = {str(p)!r} is invalid: the file name must end in .csv or .nc")
    raise AssertionError  # unreachable


def write_hindcast_csv(
    path: str | os.PathLike, data: dict[str, np.ndarray], *, comments: tuple[str, ...] = ()
) -> Path:
    """Write a hindcast in the CSV schema (``data`` as returned by
    :func:`~onbottom.metocean.synthetic.synthetic_hindcast`; ``wave_direction_deg`` and the
    current may be absent or None); directions to 0.1°, H_s to cm, T_p to 0.01 s, current to
    mm/s; NaN (a missing sea state) as an empty cell."""
    from onbottom.results import write_text_atomic

    cur = "current_speed" in data and data["current_speed"] is not None
    dirs = data.get("wave_direction_deg") is not None
    cols = COLUMNS if cur else COLUMNS[:4] if dirs else COLUMNS[:3]
    out = [f"# {c}\n" for c in comments]
    out.append(",".join(cols) + "\n")
    out.append(",".join(UNITS[c][0] for c in cols) + "\n")
    t = np.asarray(data["time"]).astype("datetime64[s]").astype(str)
    fmt = {
        "hs": "{:.2f}",
        "tp": "{:.2f}",
        "wave_direction_deg": "{:.1f}",
        "current_speed": "{:.3f}",
        "current_direction_deg": "{:.1f}",
    }
    columns = [np.asarray(data[c]) for c in cols[1:]]

    def cell(c: str, v: float) -> str:
        return fmt[c].format(v) if math.isfinite(v) else ""  # missing: empty

    for i in range(len(t)):
        out.append(
            t[i]
            + "Z,"
            + ",".join(cell(c, col[i]) for c, col in zip(cols[1:], columns, strict=True))
            + "\n"
        )
    return write_text_atomic(path, "".join(out))
