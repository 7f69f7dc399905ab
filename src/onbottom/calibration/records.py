"""Test records: measured (or simulated) pipe-section tests as calibration data.

A :class:`TestRecord` is the time history of one load-controlled pipe test — horizontal load
H, vertical load V, lateral displacement y and penetration z against time — plus the metadata
needed to simulate it again (test programme, pipe diameter, installation load V_peak, vertical
load V_i during cycling, the box's displacement limit). Laboratory tests, centrifuge tests,
section-solver results and DEM runs all become records, so the fitter sees one kind of data.

File formats (full description in ``docs/calibration.md``)
-----------------------------------------------------------
CSV
    A header block of ``# key: value [unit]`` lines, then one line of column names, then one
    line of units, then the data::

        # onbottom test record v1
        # name: Inclined 1
        # programme: inclined_1
        # diameter: 1.0 m
        # V_peak: 42.98 kN/m
        # V_i: 10.52 kN/m
        # displacement_limit: 3.0 m
        time,H,V,y,z
        s,kN/m,kN/m,m,mm
        0.0,0.0,10.52,0.0,65.1
        ...

    Required columns: ``time``, ``y``, ``z``; ``H`` and ``V`` are optional but recommended.
    Further columns are kept (converted when their unit is known).
NetCDF
    A Dataset with coordinate ``time`` and variables ``y``, ``z`` (``H``, ``V``), each with a
    ``units`` attribute; metadata as global attributes (``record_name``, ``programme``,
    ``diameter``, ``V_peak``, ``V_i``, ``displacement_limit``, ``t_cyclic_start``,
    ``cycle_period``) in SI, any further attributes kept in ``metadata``.

Units are converted to SI on loading (e.g. kN/m → N/m, mm → m, min → s); an unknown unit, a
missing or non-numeric value, or a time that does not increase raises
:class:`~onbottom.errors.InputError` naming the column and the row.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np
import xarray as xr

from onbottom._validate import non_negative, positive
from onbottom.errors import InputError
from onbottom.results import annotate, load_dataset, provenance, save_dataset

__all__ = [
    "UNIT_FACTORS",
    "TestRecord",
    "load_record",
    "record_from_result",
    "save_record",
    "to_si",
]

FORMAT_TAG = "onbottom test record v1"

# quantity kind of each known column, and the SI unit written by save_record
_COLUMN_KIND = {
    "time": "time",
    "H": "force_per_length",
    "V": "force_per_length",
    "y": "length",
    "z": "length",
}

_SI_UNIT = {"time": "s", "force_per_length": "N/m", "length": "m", "unit_weight": "N/m3"}

UNIT_FACTORS: Mapping[str, Mapping[str, float]] = MappingProxyType(
    {
        "time": MappingProxyType({"s": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0}),
        "force_per_length": MappingProxyType(
            {"N/m": 1.0, "kN/m": 1e3, "MN/m": 1e6, "N/mm": 1e3, "kN/mm": 1e6}
        ),
        "length": MappingProxyType({"m": 1.0, "mm": 1e-3, "cm": 1e-2, "km": 1e3}),
        "unit_weight": MappingProxyType(
            {"N/m3": 1.0, "N/m^3": 1.0, "N/m³": 1.0, "kN/m3": 1e3, "kN/m^3": 1e3, "kN/m³": 1e3}
        ),
        "dimensionless": MappingProxyType({"1": 1.0, "-": 1.0, "": 1.0}),
    }
)
"""Accepted units per quantity kind and their factor to SI (value_SI = value × factor)."""

# metadata keys with their quantity kind (values stored in SI)
_META_KIND = {
    "diameter": "length",
    "V_peak": "force_per_length",
    "V_i": "force_per_length",
    "displacement_limit": "length",
    "t_cyclic_start": "time",
    "cycle_period": "time",
}


def to_si(value: float, unit: str, kind: str, *, field_name: str = "value") -> float:
    """Convert ``value`` given in ``unit`` to SI for a quantity ``kind``.

    Parameters
    ----------
    value : float
        Number in ``unit``.
    unit : str
        One of ``UNIT_FACTORS[kind]`` (whitespace ignored).
    kind : str
        ``"time"``, ``"force_per_length"``, ``"length"``, ``"unit_weight"`` or
        ``"dimensionless"``.
    field_name : str
        Name used in the error message.
    """
    table = UNIT_FACTORS.get(kind)
    if table is None:
        raise InputError(f"quantity kind {kind!r} of {field_name} is unknown")
    key = unit.strip()
    if key not in table:
        raise InputError(
            f"{field_name}: unit {unit!r} is invalid for a {kind.replace('_', ' ')} quantity;"
            f" must be one of {', '.join(repr(u) for u in table if u)}"
        )
    return float(value) * table[key]


def _kind_of_unit(unit: str) -> str | None:
    for kind, table in UNIT_FACTORS.items():
        if unit.strip() in table and kind != "dimensionless":
            return kind
    return None


@dataclass(frozen=True, kw_only=True, eq=False)
class TestRecord:
    """One load-controlled pipe-section test (measured or simulated), in SI units.

    Parameters
    ----------
    name : str
        Label of the test (e.g. ``"Inclined 1"``).
    data : xarray.Dataset
        Coordinate ``time`` [s] strictly increasing; variables ``y`` lateral displacement [m]
        and ``z`` penetration of the invert [m, positive down]; optionally ``H`` horizontal
        and ``V`` vertical load per unit length [N/m]. A private copy is kept.
    diameter : float
        Pipe outer diameter D [m], > 0.
    programme : str
        Name of the load programme that reproduces the test (e.g. a centrifuge preset
        ``"inclined_1"``); empty if the test is to be driven by its recorded loads.
    V_peak : float or None
        Largest vertical load applied on virgin soil (installation) [N/m], > 0.
    V_i : float or None
        Vertical load at the start of the cyclic programme [N/m], > 0.
    displacement_limit : float or None
        Largest lateral displacement the apparatus allows; the test stops there [m], > 0.
    t_cyclic_start : float
        Time at which the cyclic programme starts [s]; the *initial penetration* of the
        objective is z at this time. Default 0 (the record starts with the cycles).
    cycle_period : float or None
        Duration of one load cycle [s] (cycles to the limit = time to limit / period).
    metadata : mapping
        Any further information (source, date, notes); stored read-only.
    """

    __test__ = False  # not a pytest test class despite the name

    name: str
    data: xr.Dataset
    diameter: float
    programme: str = ""
    V_peak: float | None = None
    V_i: float | None = None
    displacement_limit: float | None = None
    t_cyclic_start: float = 0.0
    cycle_period: float | None = None
    metadata: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise InputError(
                f"TestRecord.name = {self.name!r} is invalid: expected a non-empty str"
            )
        positive("TestRecord.diameter", self.diameter)
        for key in ("V_peak", "V_i", "displacement_limit", "cycle_period"):
            value = getattr(self, key)
            if value is not None:
                object.__setattr__(self, key, positive(f"TestRecord.{key}", value))
        object.__setattr__(
            self, "t_cyclic_start", non_negative("TestRecord.t_cyclic_start", self.t_cyclic_start)
        )
        object.__setattr__(self, "metadata", MappingProxyType(dict(self.metadata)))
        object.__setattr__(self, "data", _validated_data(self.data, self.name))

    # ---- convenience ----------------------------------------------------------------------
    @property
    def time(self) -> np.ndarray:
        """Time base [s] (read-only view)."""
        return self.data["time"].values

    @property
    def y(self) -> np.ndarray:
        """Lateral displacement [m]."""
        return self.data["y"].values

    @property
    def z(self) -> np.ndarray:
        """Penetration of the invert [m, positive down]."""
        return self.data["z"].values

    def attrs(self) -> dict[str, Any]:
        """Metadata as NetCDF-safe global attributes (SI values; None omitted)."""
        out: dict[str, Any] = {
            "format": FORMAT_TAG,
            "record_name": self.name,
            "programme": self.programme,
            "diameter": self.diameter,
            "t_cyclic_start": self.t_cyclic_start,
        }
        for key in ("V_peak", "V_i", "displacement_limit", "cycle_period"):
            value = getattr(self, key)
            if value is not None:
                out[key] = value
        for key, value in self.metadata.items():
            out[f"meta_{key}"] = value if isinstance(value, (str, int, float)) else str(value)
        return out

    def to_dataset(self) -> xr.Dataset:
        """The data with metadata as attributes (what :func:`save_record` writes to NetCDF)."""
        ds = self.data.copy(deep=True)
        ds.attrs = {**provenance("TestRecord"), **self.attrs()}
        return ds


def _validated_data(data: xr.Dataset, name: str) -> xr.Dataset:
    if not isinstance(data, xr.Dataset):
        raise InputError(f"TestRecord.data of {name!r} is invalid: expected an xarray.Dataset")
    if "time" not in data.coords and "time" not in data.variables:
        raise InputError(f"TestRecord.data of {name!r} is invalid: column 'time' is missing")
    for col in ("y", "z"):
        if col not in data.variables:
            raise InputError(f"TestRecord.data of {name!r} is invalid: column {col!r} is missing")
    ds = data.copy(deep=True)
    if "time" not in ds.coords:
        ds = ds.set_coords("time")
    t = np.asarray(ds["time"].values, dtype=float)
    if t.ndim != 1 or t.size < 2:
        raise InputError(f"TestRecord.data of {name!r}: column 'time' needs at least 2 rows")
    for col in ("time", *[str(v) for v in ds.data_vars]):
        values = np.asarray(ds[col].values)
        if values.dtype.kind not in "fiu":
            continue
        bad = np.flatnonzero(~np.isfinite(values.astype(float)))
        if bad.size:
            raise InputError(
                f"record {name!r}: column {col!r} row {int(bad[0])} is {values[bad[0]]!r}:"
                " missing or non-finite values are not allowed"
            )
    steps = np.diff(t)
    bad = np.flatnonzero(steps <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise InputError(
            f"record {name!r}: column 'time' row {i} is {float(t[i])!r} after"
            f" {float(t[i - 1])!r}:"
            " time must increase strictly"
        )
    for col in ds.variables:
        if col in _COLUMN_KIND:
            ds[col].attrs["units"] = _SI_UNIT[_COLUMN_KIND[str(col)]]
        ds[col].values.setflags(write=False)  # a record is data: read-only
    return annotate(ds)


# ---- CSV ----------------------------------------------------------------------------------
def _parse_header_value(key: str, raw: str, path: str) -> Any:
    raw = raw.strip()
    kind = _META_KIND.get(key)
    parts = raw.split(None, 1)
    if kind is None:
        # free metadata: number if it looks like one
        try:
            return float(raw) if parts and len(parts) == 1 else raw
        except ValueError:
            return raw
    try:
        number = float(parts[0])
    except (ValueError, IndexError) as exc:
        raise InputError(f"{path}: header {key!r} = {raw!r} is invalid: expected a number") from exc
    unit = parts[1] if len(parts) > 1 else _SI_UNIT[kind]
    return to_si(number, unit, kind, field_name=f"{path}: header {key!r}")


_HEADER_ALIASES = {"name": "name", "test": "programme", "programme": "programme", "D": "diameter"}


def _read_csv(path: Path) -> TestRecord:
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    header: dict[str, Any] = {}
    n_header = 0
    for line in lines:
        if not line.startswith("#"):
            break
        n_header += 1
        body = line[1:].strip()
        if not body or body == FORMAT_TAG or ":" not in body:
            continue
        key, raw = body.split(":", 1)
        key = _HEADER_ALIASES.get(key.strip(), key.strip())
        if key in ("name", "programme"):
            header[key] = raw.strip()
        else:
            header[key] = _parse_header_value(key, raw, str(path))
    rows = list(csv.reader(io.StringIO("\n".join(lines[n_header:]))))
    if len(rows) < 2:
        raise InputError(f"{path}: expected a line of column names and a line of units")
    names = [c.strip() for c in rows[0]]
    units = [c.strip() for c in rows[1]]
    if len(units) != len(names):
        raise InputError(
            f"{path}: {len(names)} column names but {len(units)} units (line {n_header + 2})"
        )
    if len(set(names)) != len(names):
        raise InputError(f"{path}: duplicate column names in {names}")
    for required in ("time", "y", "z"):
        if required not in names:
            raise InputError(f"{path}: column {required!r} is missing (columns: {names})")
    factors: list[float] = []
    kinds: list[str | None] = []
    for col, unit in zip(names, units, strict=True):
        kind = _COLUMN_KIND.get(col) or _kind_of_unit(unit)
        kinds.append(kind)
        factors.append(
            to_si(1.0, unit, kind, field_name=f"{path}: column {col!r}") if kind else 1.0
        )
    data_rows = rows[2:]
    values = np.empty((len(data_rows), len(names)))
    first_data_line = n_header + 3
    for r, row in enumerate(data_rows):
        if len(row) != len(names):
            raise InputError(
                f"{path}: row {r} (line {first_data_line + r}) has {len(row)} values,"
                f" expected {len(names)}"
            )
        for c, cell in enumerate(row):
            cell = cell.strip()
            try:
                x = float(cell) if cell else math.nan
            except ValueError:
                x = math.nan
            if not math.isfinite(x):
                raise InputError(
                    f"{path}: column {names[c]!r} row {r} (line {first_data_line + r}) is"
                    f" {cell!r}: missing or non-numeric values are not allowed"
                )
            values[r, c] = x * factors[c]
    t = values[:, names.index("time")]
    steps = np.diff(t)
    bad = np.flatnonzero(steps <= 0.0)
    if bad.size:
        r = int(bad[0]) + 1
        raise InputError(
            f"{path}: column 'time' row {r} (line {first_data_line + r}) = {float(t[r])!r} s"
            f" after {float(t[r - 1])!r} s: time must increase strictly"
        )
    ds = xr.Dataset(coords={"time": ("time", t)})
    for c, col in enumerate(names):
        if col == "time":
            continue
        ds[col] = ("time", values[:, c])
        unit = _SI_UNIT[kinds[c]] if kinds[c] else units[c]
        ds[col].attrs["units"] = unit
    return _record_from_header(header, ds, str(path))


def _record_from_header(header: Mapping[str, Any], ds: xr.Dataset, source: str) -> TestRecord:
    known = {
        "name",
        "programme",
        "diameter",
        "V_peak",
        "V_i",
        "displacement_limit",
        "t_cyclic_start",
        "cycle_period",
    }
    if "diameter" not in header:
        raise InputError(
            f"{source}: header 'diameter' (pipe outer diameter D, e.g. '1.0 m') is missing"
        )
    meta = {k: v for k, v in header.items() if k not in known}
    return TestRecord(
        name=str(header.get("name") or Path(source).stem),
        data=ds,
        diameter=header["diameter"],
        programme=str(header.get("programme", "")),
        V_peak=header.get("V_peak"),
        V_i=header.get("V_i"),
        displacement_limit=header.get("displacement_limit"),
        t_cyclic_start=header.get("t_cyclic_start", 0.0),
        cycle_period=header.get("cycle_period"),
        metadata=meta,
    )


def _write_csv(record: TestRecord, path: Path) -> None:
    ds = record.data
    cols = [
        "time",
        *[c for c in ("H", "V", "y", "z") if c in ds],
        *[
            str(c)
            for c in ds.data_vars
            if c not in ("H", "V", "y", "z") and ds[c].dims == ("time",)
        ],
    ]
    lines = [f"# {FORMAT_TAG}", f"# name: {record.name}"]
    if record.programme:
        lines.append(f"# programme: {record.programme}")
    lines.append(f"# diameter: {record.diameter!r} m")
    for key in ("V_peak", "V_i", "displacement_limit", "t_cyclic_start", "cycle_period"):
        value = getattr(record, key)
        if value is not None:
            lines.append(f"# {key}: {value!r} {_SI_UNIT[_META_KIND[key]]}")
    for key, value in record.metadata.items():
        lines.append(f"# {key}: {value}")
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(cols)
    writer.writerow(
        [
            _SI_UNIT[_COLUMN_KIND[c]] if c in _COLUMN_KIND else ds[c].attrs.get("units", "1")
            for c in cols
        ]
    )
    arrays = [np.asarray(ds[c].values, dtype=float) for c in cols]
    for i in range(ds.sizes["time"]):
        writer.writerow([repr(float(a[i])) for a in arrays])
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text("\n".join(lines) + "\n" + buf.getvalue(), encoding="utf-8")
    os.replace(tmp, path)


# ---- NetCDF -------------------------------------------------------------------------------
def _read_netcdf(path: Path) -> TestRecord:
    raw = load_dataset(path)
    ds = xr.Dataset(coords={"time": raw["time"].values.astype(float)})
    t_unit = raw["time"].attrs.get("units", "s")
    ds = ds.assign_coords(
        time=ds["time"].values * to_si(1.0, t_unit, "time", field_name=f"{path}: column 'time'")
    )
    for col in raw.data_vars:
        if raw[col].dims != ("time",):
            continue
        unit = str(raw[col].attrs.get("units", ""))
        kind = _COLUMN_KIND.get(str(col)) or _kind_of_unit(unit)
        if kind is None:
            ds[col] = ("time", raw[col].values)
            if unit:
                ds[col].attrs["units"] = unit
            continue
        if not unit:
            raise InputError(f"{path}: column {str(col)!r} has no 'units' attribute")
        factor = to_si(1.0, unit, kind, field_name=f"{path}: column {str(col)!r}")
        ds[col] = ("time", np.asarray(raw[col].values, dtype=float) * factor)
    header: dict[str, Any] = {}
    for key, value in raw.attrs.items():
        if key == "record_name":
            header["name"] = value
        elif key in _META_KIND or key == "programme":
            header[key] = value.item() if isinstance(value, np.generic) else value
        elif key.startswith("meta_"):
            header[key[5:]] = value
    return _record_from_header(header, ds, str(path))


# ---- public I/O ---------------------------------------------------------------------------
def load_record(path: str | os.PathLike) -> TestRecord:
    """Load a test record from CSV (``.csv``) or NetCDF (``.nc``), converting units to SI.

    Raises
    ------
    InputError
        Unknown unit, missing column, missing/non-numeric value (the message names the column
        and the row) or time not strictly increasing.
    """
    p = Path(path)
    if not p.exists():
        raise InputError(f"record file {str(p)!r} does not exist")
    suffix = p.suffix.lower()
    if suffix not in (".csv", ".nc", ".nc4", ".netcdf"):
        raise InputError(
            f"record file {str(p)!r}: suffix {suffix!r} is invalid: must be '.csv' or '.nc'"
        )
    try:
        return _read_csv(p) if suffix == ".csv" else _read_netcdf(p)
    except InputError:
        raise
    except UnicodeDecodeError:
        raise InputError(f"record file {str(p)!r} is invalid: not a UTF-8 text file") from None
    except Exception as exc:  # unreadable, truncated, not NetCDF, missing variables ...
        raise InputError(
            f"record file {str(p)!r} is invalid: cannot be read as a test record"
            f" ({type(exc).__name__}: {exc})"
        ) from None


def save_record(record: TestRecord, path: str | os.PathLike) -> Path:
    """Write ``record`` to CSV or NetCDF (chosen by the suffix), in SI units, atomically."""
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".csv":
        _write_csv(record, p)
        return p
    if suffix in (".nc", ".nc4", ".netcdf"):
        return save_dataset(record.to_dataset(), p)
    raise InputError(
        f"record file {str(p)!r}: suffix {suffix!r} is invalid: must be '.csv' or '.nc'"
    )


def _attr_number(value: Any) -> float | None:
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) and x > 0.0 else None


def record_from_result(
    result: Any,
    *,
    name: str,
    diameter: float | None = None,
    programme: str | None = None,
    V_peak: float | None = None,
    V_i: float | None = None,
    displacement_limit: float | None = None,
    t_cyclic_start: float = 0.0,
    cycle_period: float | None = None,
    metadata: Mapping[str, Any] | None = None,
) -> TestRecord:
    """Make a :class:`TestRecord` from a simulation result so that it can serve as a record.

    Parameters
    ----------
    result : xarray.Dataset or object with ``.data``
        Section-solver output: coordinate ``time`` [s] and variables ``y`` [m], ``z`` [m],
        optionally ``H``, ``V`` [N/m]. Other variables are
        dropped.
    name, diameter, programme, V_peak, V_i, displacement_limit, t_cyclic_start, cycle_period,
    metadata
        As in :class:`TestRecord` (SI units). Left as None, ``diameter``, ``programme``,
        ``V_peak``, ``displacement_limit`` and ``cycle_period`` are taken from the result's
        provenance attributes when present (``parameters["outer_diameter"]``, ``test`` or
        ``programme``, ``installation_load``, ``displacement_limit``, ``cycle_period``) and
        ``V_i`` from the first sample of V.
    """
    ds = result.data if hasattr(result, "data") and not isinstance(result, xr.Dataset) else result
    if not isinstance(ds, xr.Dataset):
        raise InputError("record_from_result: result must be an xarray.Dataset or have .data")
    keep = xr.Dataset(coords={"time": np.asarray(ds["time"].values, dtype=float)})
    for var in ("y", "z", "H", "V"):
        if var in ds.variables:
            keep[var] = ("time", np.asarray(ds[var].values, dtype=float))
    attrs = ds.attrs
    if diameter is None:
        try:
            diameter = float(json.loads(attrs["parameters"])["outer_diameter"])
        except (KeyError, TypeError, ValueError) as exc:
            raise InputError(
                "record_from_result: diameter is not given and not in the result's attributes"
            ) from exc
    if programme is None:
        programme = str(attrs.get("test", attrs.get("programme", "")))
    V_peak = V_peak if V_peak is not None else _attr_number(attrs.get("installation_load"))
    if displacement_limit is None:
        displacement_limit = _attr_number(attrs.get("displacement_limit"))
    if cycle_period is None:
        cycle_period = _attr_number(attrs.get("cycle_period"))
    if V_i is None and "V" in keep:
        v0 = float(keep["V"].values[0])
        V_i = v0 if v0 > 0.0 else None
    meta = dict(metadata or {})
    if "model" in ds.attrs:
        meta.setdefault("source_model", str(ds.attrs["model"]))
    if "parameters" in ds.attrs:
        meta.setdefault("source_parameters", str(ds.attrs["parameters"]))
    return TestRecord(
        name=name,
        data=keep,
        diameter=diameter,
        programme=programme,
        V_peak=V_peak,
        V_i=V_i,
        displacement_limit=displacement_limit,
        t_cyclic_start=t_cyclic_start,
        cycle_period=cycle_period,
        metadata=meta,
    )
