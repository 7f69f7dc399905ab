"""Coefficient tables of the Fourier force model: strict schema, validation, interpolation.

The Fourier force model (Sørensen, Bryndum & Jacobsen 1986; Bryndum, Jacobsen & Tsahalis
1992, JOMAE 114:231; the AGA/PRCI Level 3 approach) writes the force on a pipe on the seabed
in one half-cycle of the flow as

    F_Y = s · ½ρD U_m² [A₀ʸ + Σₙ₌₁ᴺ (Aₙʸ cos nθ + Bₙʸ sin nθ)],   θ = π τ / T_h ∈ [0, π]
    F_Z =     ½ρD U_m² [A₀ᶻ + Σₙ₌₁ᴺ (Aₙᶻ cos nθ + Bₙᶻ sin nθ)]

with coefficients that depend on K = U_m T / D and on the half-cycle's current ratio
M = s V / U_m (signed: > 0 when the half-cycle flows with the current, < 0 against it; a
regular-wave test at current ratio M gives the rows +M and −M), s = ±1 the half-cycle's
direction, τ the time since its zero crossing and T_h its duration
(``docs/theory/fourier_model.md``). The measured coefficient databases (DHI, AGA/PRCI) are
licensed: onbottom ships none of their numbers. The user supplies the table; the package ships
a **synthetic** example (:meth:`FourierTable.example`, computed from a Morison force with
invented K-dependent coefficients by ``tools/make_fourier_example.py``).

Table schema (CSV or NetCDF; the same column / variable names):

* CSV: ``#`` lines are comments (``# key: value`` lines are kept as metadata, ``source`` among
  them); then a header line, then a **units line** (every column dimensionless: ``-`` or
  ``1``), then one row per grid cell;
* columns ``K`` (> 0), ``M`` (in [−1, 1]), optionally ``k_over_D`` (roughness k/D >= 0), and
  the coefficients ``Y_A0, Y_A1, Y_B1, …, Y_AN, Y_BN, Z_A0, …, Z_BN`` for one harmonic order
  1 <= N <= :data:`MAX_HARMONICS`; no other column;
* rows sorted by (k_over_D, K, M), strictly increasing (a non-monotone grid is an error naming
  the row), every combination of the grid values present once (a missing cell is named);
* NetCDF: coordinates ``K``, ``M`` (and ``k_over_D``) with ``units`` "1" or "-", one
  variable per coefficient name over those dimensions, ``units`` "1" or "-"; NaN cells are
  missing cells.

Interpolation: bilinear over (K, M) (and linear in k/D), clamped to the grid's edges with an
:class:`~onbottom.errors.OutOfRangeWarning` outside it.
"""

from __future__ import annotations

import csv
import io
import math
import re
import warnings
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from onbottom._validate import file_token
from onbottom.errors import InputError, OutOfRangeWarning

__all__ = [
    "COMPONENTS",
    "MAX_HARMONICS",
    "FourierTable",
    "coefficient_names",
]

MAX_HARMONICS = 8
"""Largest harmonic order N accepted (the DHI database uses N <= 5)."""
COMPONENTS = ("Y", "Z")
"""Force components: Y lateral (in the half-cycle's flow direction), Z lift (upward)."""
DIMENSIONLESS = ("-", "1")
"""Unit strings accepted for the (dimensionless) columns."""
EXAMPLE_FILE = "fourier_example.csv"
"""Package data file of the synthetic example table."""

_COEF = re.compile(r"^([YZ])_([AB])(\d+)$")


def coefficient_names(harmonics: int) -> list[str]:
    """Column names of one table row's coefficients for harmonic order N, in storage order.

    Y_A0, Y_A1, Y_B1, …, Y_AN, Y_BN, then the same for Z.
    """
    names = []
    for c in COMPONENTS:
        names.append(f"{c}_A0")
        for n in range(1, harmonics + 1):
            names += [f"{c}_A{n}", f"{c}_B{n}"]
    return names


def _strict_grid(name: str, values: np.ndarray) -> None:
    if values.ndim != 1 or values.size < 1:
        raise InputError(f"FourierTable.{name} is invalid: expected a 1-D grid of >= 1 values")
    if not np.all(np.isfinite(values)):
        raise InputError(f"FourierTable.{name} = {values.tolist()} is invalid: non-finite value")
    bad = np.nonzero(np.diff(values) <= 0.0)[0]
    if bad.size:
        i = int(bad[0])
        raise InputError(
            f"FourierTable.{name} is invalid: non-monotone grid, {values[i + 1]!r} follows"
            f" {values[i]!r} (grid values must increase strictly)"
        )


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float, copy=True)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class FourierTable:
    """An immutable, validated Fourier coefficient table (see the module docstring).

    Parameters
    ----------
    k_grid : array
        K = U_m T / D grid values [-], strictly increasing, > 0.
    m_grid : array
        Signed half-cycle current ratio M = s V / U_m grid values [-], strictly increasing,
        in [−1, 1].
    coefficients : array
        Shape (n_r, n_K, n_M, 2, 2N+1): roughness slice, K, M, component (Y, Z) and
        coefficient A₀, A₁, B₁, …, A_N, B_N [-]; finite.
    roughness_grid : array or None
        k/D values [-] of the roughness slices (strictly increasing, >= 0), or None for a
        table without a roughness axis (n_r = 1).
    source : str
        Where the numbers come from (kept in the provenance of every result).
    metadata : dict
        Other ``# key: value`` lines / NetCDF attributes of the file.
    """

    k_grid: np.ndarray
    m_grid: np.ndarray
    coefficients: np.ndarray
    roughness_grid: np.ndarray | None = None
    source: str = "user table"
    metadata: dict[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        k = _readonly(np.atleast_1d(np.asarray(self.k_grid, dtype=float)))
        m = _readonly(np.atleast_1d(np.asarray(self.m_grid, dtype=float)))
        _strict_grid("k_grid", k)
        _strict_grid("m_grid", m)
        if k[0] <= 0.0:
            raise InputError(f"FourierTable.k_grid = {k[0]!r} is invalid: K must be > 0")
        if m[0] < -1.0 or m[-1] > 1.0:
            raise InputError(
                f"FourierTable.m_grid = {m.tolist()} is invalid: the half-cycle current ratio"
                " M = s V / U_m must lie in [-1, 1] (a flow that does not reverse has no"
                " half-cycles; the model's quasi-steady law covers it)"
            )
        r = None
        if self.roughness_grid is not None:
            r = _readonly(np.atleast_1d(np.asarray(self.roughness_grid, dtype=float)))
            _strict_grid("roughness_grid", r)
            if r[0] < 0.0:
                raise InputError(f"FourierTable.roughness_grid = {r[0]!r} is invalid: k/D >= 0")
        c = np.asarray(self.coefficients, dtype=float)
        if c.ndim == 4:
            c = c[np.newaxis]
        nr = 1 if r is None else r.size
        if c.ndim != 5 or c.shape[:4] != (nr, k.size, m.size, 2) or c.shape[4] % 2 != 1:
            raise InputError(
                f"FourierTable.coefficients has shape {c.shape}: expected"
                f" ({nr}, {k.size}, {m.size}, 2, 2N+1)"
            )
        n = (c.shape[4] - 1) // 2
        if not 1 <= n <= MAX_HARMONICS:
            raise InputError(
                f"FourierTable harmonic order N = {n} is invalid: must lie in [1, {MAX_HARMONICS}]"
            )
        if not np.all(np.isfinite(c)):
            idx = tuple(int(i) for i in np.argwhere(~np.isfinite(c))[0])
            cell = f"K={k[idx[1]]:g}, M={m[idx[2]]:g}"
            if r is not None:
                cell = f"k_over_D={r[idx[0]]:g}, " + cell
            name = coefficient_names(n)[idx[3] * (2 * n + 1) + idx[4]]
            raise InputError(f"FourierTable: missing cell ({cell}): {name} is not finite")
        object.__setattr__(self, "k_grid", k)
        object.__setattr__(self, "m_grid", m)
        object.__setattr__(self, "roughness_grid", r)
        object.__setattr__(self, "coefficients", _readonly(c))
        object.__setattr__(self, "metadata", dict(self.metadata))

    # ------------------------------------------------------------------ properties
    @property
    def harmonics(self) -> int:
        """Harmonic order N of the table."""
        return (self.coefficients.shape[4] - 1) // 2

    @property
    def has_roughness(self) -> bool:
        """Whether the table has a roughness (k/D) axis."""
        return self.roughness_grid is not None

    # ------------------------------------------------------------------ interpolation
    @staticmethod
    def _weights(name: str, grid: np.ndarray, x: float, warn: bool) -> tuple[int, int, float]:
        if grid.size == 1 or x <= grid[0] or x >= grid[-1]:
            if warn and (x < grid[0] or x > grid[-1]):
                warnings.warn(
                    f"{name} = {x:.4g} is outside the Fourier table's grid"
                    f" [{grid[0]:g}, {grid[-1]:g}]; the coefficients are clamped to its edge",
                    OutOfRangeWarning,
                    stacklevel=4,
                )
            i = 0 if (grid.size == 1 or x <= grid[0]) else grid.size - 1
            return i, i, 0.0
        i = int(np.searchsorted(grid, x, side="right")) - 1
        return i, i + 1, float((x - grid[i]) / (grid[i + 1] - grid[i]))

    def at_roughness(self, k_over_d: float) -> FourierTable:
        """The 2-D (K, M) table at roughness k/D [-] (linear between slices, clamped + warning).

        A table without a roughness axis is returned unchanged.
        """
        if self.roughness_grid is None:
            return self
        x = float(k_over_d)
        if not math.isfinite(x) or x < 0.0:
            raise InputError(f"roughness k_over_D = {k_over_d!r} is invalid: must be >= 0")
        i0, i1, f = self._weights("k_over_D", self.roughness_grid, x, True)
        c = (1.0 - f) * self.coefficients[i0] + f * self.coefficients[i1]
        meta = dict(self.metadata, roughness_k_over_D=f"{x:g}")
        return FourierTable(self.k_grid, self.m_grid, c[np.newaxis], None, self.source, meta)

    def coefficients_at(self, keulegan_carpenter: float, current_ratio: float) -> np.ndarray:
        """Coefficients (2, 2N+1) at (K, M), bilinear, clamped with a warning outside the grid.

        keulegan_carpenter: K [-]; current_ratio: signed half-cycle M = s V / U_m [-].
        A table with a roughness axis must first be resolved with :meth:`at_roughness`.
        """
        if self.roughness_grid is not None:
            raise InputError(
                "FourierTable has a roughness axis: resolve it with at_roughness(k_over_D)"
            )
        ik0, ik1, fk = self._weights("K", self.k_grid, float(keulegan_carpenter), True)
        im0, im1, fm = self._weights("M", self.m_grid, float(current_ratio), True)
        c = self.coefficients[0]
        return (
            (1.0 - fk) * (1.0 - fm) * c[ik0, im0]
            + fk * (1.0 - fm) * c[ik1, im0]
            + (1.0 - fk) * fm * c[ik0, im1]
            + fk * fm * c[ik1, im1]
        )

    def normalized_force(
        self, keulegan_carpenter: float, current_ratio: float, theta: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """F_Y / (s ½ρD U_m²) and F_Z / (½ρD U_m²) at half-cycle phases θ [rad] in [0, π]."""
        c = self.coefficients_at(keulegan_carpenter, current_ratio)
        basis = fourier_basis(np.asarray(theta, dtype=float), self.harmonics)
        return basis @ c[0], basis @ c[1]

    # ------------------------------------------------------------------ rows
    def rows(self) -> list[dict[str, float]]:
        """The table as rows (dicts of column → value), in the schema's order."""
        names = coefficient_names(self.harmonics)
        out = []
        rough = [None] if self.roughness_grid is None else list(self.roughness_grid)
        for ir, r in enumerate(rough):
            for ik, k in enumerate(self.k_grid):
                for im, m in enumerate(self.m_grid):
                    row: dict[str, float] = {}
                    if r is not None:
                        row["k_over_D"] = float(r)
                    row["K"] = float(k)
                    row["M"] = float(m)
                    row.update(zip(names, self.coefficients[ir, ik, im].ravel(), strict=True))
                    out.append(row)
        return out

    @classmethod
    def from_rows(
        cls,
        rows: list[dict[str, float]],
        *,
        source: str = "user table",
        metadata: dict[str, str] | None = None,
        where: str = "row",
    ) -> FourierTable:
        """Build a table from rows (column → value) following the schema (errors named).

        Rows must be sorted by (k_over_D, K, M) strictly and cover the full grid.
        """
        if not rows:
            raise InputError("FourierTable: the table has no rows")
        columns = list(rows[0])
        n = _check_columns(columns)
        rough = "k_over_D" in columns
        names = coefficient_names(n)
        keys = []
        for i, row in enumerate(rows):
            if list(row) != columns:
                raise InputError(f"FourierTable {where} {i + 1}: columns differ from the header")
            for col, v in row.items():
                if not isinstance(v, float | int) or not math.isfinite(float(v)):
                    raise InputError(
                        f"FourierTable {where} {i + 1}: {col} = {v!r} is invalid:"
                        " expected a finite number (a missing value is a missing cell)"
                    )
            key = (float(row["k_over_D"]) if rough else 0.0, float(row["K"]), float(row["M"]))
            if keys and key <= keys[-1]:
                what = "duplicate cell" if key == keys[-1] else "non-monotone grid"
                raise InputError(
                    f"FourierTable {where} {i + 1}: {what}: (K={key[1]:g}, M={key[2]:g}"
                    + (f", k_over_D={key[0]:g}" if rough else "")
                    + ") must follow the previous row in increasing (k_over_D, K, M) order"
                )
            keys.append(key)
        r_vals = sorted({k[0] for k in keys})
        k_vals = sorted({k[1] for k in keys})
        m_vals = sorted({k[2] for k in keys})
        index = {key: i for i, key in enumerate(keys)}
        coef = np.empty((len(r_vals), len(k_vals), len(m_vals), 2, 2 * n + 1))
        for ir, r in enumerate(r_vals):
            for ik, k in enumerate(k_vals):
                for im, m in enumerate(m_vals):
                    i = index.get((r, k, m))
                    if i is None:
                        cell = f"K={k:g}, M={m:g}" + (f", k_over_D={r:g}" if rough else "")
                        raise InputError(
                            f"FourierTable: missing cell ({cell}): every combination of the"
                            " grid values needs a row"
                        )
                    coef[ir, ik, im] = np.array([rows[i][c] for c in names]).reshape(2, -1)
        return cls(
            np.array(k_vals),
            np.array(m_vals),
            coef,
            np.array(r_vals) if rough else None,
            source,
            dict(metadata or {}),
        )

    # ------------------------------------------------------------------ files
    @classmethod
    def from_csv(cls, path: str | Path | io.TextIOBase) -> FourierTable:
        """Read a CSV table (schema in the module docstring); errors name the line and field."""
        if isinstance(path, str | Path):
            text = Path(path).read_text(encoding="utf-8")
            label = str(path)
        else:
            text = path.read()
            label = "<stream>"
        meta: dict[str, str] = {}
        lines: list[tuple[int, str]] = []
        for no, line in enumerate(text.splitlines(), start=1):
            s = line.strip()
            if not s:
                continue
            if s.startswith("#"):
                body = s.lstrip("#").strip()
                if ":" in body:
                    key, value = body.split(":", 1)
                    if re.fullmatch(r"[A-Za-z_][\w ]*", key.strip()):
                        meta[key.strip()] = value.strip()
                continue
            lines.append((no, line))
        if len(lines) < 3:
            raise InputError(
                f"Fourier table {label}: expected a header line, a units line and >= 1 data row"
            )
        parsed = [(no, next(csv.reader([line]))) for no, line in lines]
        header = [h.strip() for h in parsed[0][1]]
        units = [u.strip() for u in parsed[1][1]]
        _check_columns(header)
        if len(units) != len(header):
            raise InputError(
                f"Fourier table {label} line {parsed[1][0]}: the units line has {len(units)}"
                f" entries for {len(header)} columns"
            )
        for col, unit in zip(header, units, strict=True):
            if unit not in DIMENSIONLESS:
                raise InputError(
                    f"Fourier table {label}: column {col} has unit {unit!r}: every column is"
                    f" dimensionless, write one of {', '.join(map(repr, DIMENSIONLESS))}"
                )
        rows = []
        for no, fields in parsed[2:]:
            if len(fields) != len(header):
                raise InputError(
                    f"Fourier table {label} line {no}: {len(fields)} fields for"
                    f" {len(header)} columns (a missing value is a missing cell)"
                )
            row: dict[str, float] = {}
            for col, v in zip(header, fields, strict=True):
                try:
                    row[col] = float(v)
                except ValueError:
                    raise InputError(
                        f"Fourier table {label} line {no}: {col} = {v.strip()!r} is invalid:"
                        " expected a number"
                    ) from None
            rows.append(row)
        source = meta.pop("source", label)
        return cls.from_rows(rows, source=source, metadata=meta, where=f"{label} data row")

    def to_csv(self, path: str | Path, *, comments: list[str] | None = None) -> None:
        """Write the table as CSV (schema of the module docstring; 17 significant digits)."""
        rows = self.rows()
        header = list(rows[0])
        lines = [f"# {c}" for c in (comments or [])]
        lines.append(f"# source: {self.source}")
        for k, v in self.metadata.items():
            lines.append(f"# {k}: {v}")
        lines.append(",".join(header))
        lines.append(",".join("-" for _ in header))
        for row in rows:
            lines.append(",".join(f"{row[c]:.17g}" for c in header))
        Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")

    @classmethod
    def from_netcdf(cls, path: str | Path) -> FourierTable:
        """Read a NetCDF table (coordinates K, M [, k_over_D]; one variable per coefficient)."""
        import xarray as xr

        with xr.open_dataset(path) as ds:
            ds = ds.load()
        label = str(path)
        dims = ["k_over_D", "K", "M"] if "k_over_D" in ds.coords else ["K", "M"]
        for name in dims:
            if name not in ds.coords:
                raise InputError(f"Fourier table {label}: missing coordinate {name}")
            unit = str(ds[name].attrs.get("units", ""))
            if unit not in DIMENSIONLESS:
                raise InputError(
                    f"Fourier table {label}: coordinate {name} has units {unit!r}: expected"
                    f" one of {', '.join(map(repr, DIMENSIONLESS))}"
                )
        n = _check_columns(dims + [str(v) for v in ds.data_vars])
        coef = np.empty((*(ds.sizes[d] for d in dims), 2, 2 * n + 1))
        for j, name in enumerate(coefficient_names(n)):
            var = ds[name]
            unit = str(var.attrs.get("units", ""))
            if unit not in DIMENSIONLESS:
                raise InputError(
                    f"Fourier table {label}: variable {name} has units {unit!r}: expected"
                    f" one of {', '.join(map(repr, DIMENSIONLESS))}"
                )
            if set(var.dims) != set(dims):
                raise InputError(
                    f"Fourier table {label}: variable {name} has dimensions {var.dims}:"
                    f" expected {tuple(dims)}"
                )
            coef[..., j // (2 * n + 1), j % (2 * n + 1)] = var.transpose(*dims).values
        attrs = {str(k): str(v) for k, v in ds.attrs.items()}
        source = attrs.pop("source", label)
        return cls(
            ds["K"].values,
            ds["M"].values,
            coef if len(dims) == 3 else coef[np.newaxis],
            ds["k_over_D"].values if len(dims) == 3 else None,
            source,
            attrs,
        )

    def to_netcdf(self, path: str | Path) -> None:
        """Write the table as NetCDF (the schema :meth:`from_netcdf` reads)."""
        import xarray as xr

        dims = ["K", "M"]
        coords: dict[str, Any] = {
            "K": ("K", self.k_grid, {"units": "1", "long_name": "Keulegan-Carpenter number"}),
            "M": ("M", self.m_grid, {"units": "1", "long_name": "half-cycle current ratio"}),
        }
        if self.roughness_grid is not None:
            dims = ["k_over_D", *dims]
            coords["k_over_D"] = ("k_over_D", self.roughness_grid, {"units": "1"})
        n = self.harmonics
        data = {}
        for j, name in enumerate(coefficient_names(n)):
            values = self.coefficients[..., j // (2 * n + 1), j % (2 * n + 1)]
            if self.roughness_grid is None:
                values = values[0]
            data[name] = (dims, values, {"units": "1"})
        ds = xr.Dataset(data, coords=coords, attrs={"source": self.source, **self.metadata})
        ds.to_netcdf(path, engine="h5netcdf")

    @classmethod
    def load(cls, path: str | Path) -> FourierTable:
        """Read a table from ``.csv`` or ``.nc`` (by the file's suffix)."""
        p = Path(path)
        if not p.is_file():
            raise InputError(f"Fourier table {str(p)!r} is invalid: no such file")
        if p.suffix.lower() == ".csv":
            return cls.from_csv(p)
        if p.suffix.lower() in (".nc", ".nc4", ".netcdf"):
            return cls.from_netcdf(p)
        raise InputError(f"Fourier table {str(p)!r} is invalid: expected a .csv or .nc file")

    @classmethod
    def example(cls) -> FourierTable:
        """The shipped **synthetic** example table (no measured or licensed numbers).

        Computed by ``tools/make_fourier_example.py`` from a Morison force with invented
        K-dependent coefficients (:func:`onbottom.hydro.fourier_fit.synthetic_morison_table`).
        """
        ref = resources.files("onbottom").joinpath("data", EXAMPLE_FILE)
        with ref.open("r", encoding="utf-8") as fh:
            return cls.from_csv(io.StringIO(fh.read()))

    def describe(self) -> dict[str, Any]:
        """Provenance attributes of the table."""
        d: dict[str, Any] = {
            "fourier_table_source": self.source,
            "fourier_table_harmonics": self.harmonics,
            "fourier_table_K_range": f"{self.k_grid[0]:g}..{self.k_grid[-1]:g}",
            "fourier_table_M_range": f"{self.m_grid[0]:g}..{self.m_grid[-1]:g}",
        }
        if self.roughness_grid is not None:
            d["fourier_table_k_over_D"] = ",".join(f"{r:g}" for r in self.roughness_grid)
        if "synthetic" in self.metadata:
            d["fourier_table_synthetic"] = self.metadata["synthetic"]
        return d


def fourier_basis(theta: np.ndarray, harmonics: int) -> np.ndarray:
    """Matrix (len θ, 2N+1) of 1, cos θ, sin θ, …, cos Nθ, sin Nθ (storage order)."""
    th = np.atleast_1d(np.asarray(theta, dtype=float))
    cols = [np.ones_like(th)]
    for n in range(1, harmonics + 1):
        cols += [np.cos(n * th), np.sin(n * th)]
    return np.column_stack(cols)


def _check_columns(columns: list[str]) -> int:
    """Validate the column names; return the harmonic order N."""
    seen = set()
    order = 0
    for col in columns:
        if col in seen:
            raise InputError(f"FourierTable: column {col!r} appears twice")
        seen.add(col)
        if col in ("K", "M", "k_over_D"):
            continue
        m = _COEF.match(col)
        if not m:
            raise InputError(
                f"FourierTable: unknown column {file_token(col, ('K', 'M', 'k_over_D'))}:"
                " expected K, M, k_over_D or"
                " coefficients named like Y_A0, Y_A1, Y_B1, Z_A0"
            )
        n = int(m.group(3))
        if m.group(2) == "B" and n == 0:
            raise InputError("FourierTable: column 'Y_B0'/'Z_B0' is invalid: B starts at n = 1")
        order = max(order, n)
    for col in ("K", "M"):
        if col not in seen:
            raise InputError(f"FourierTable: missing column {col!r}")
    if not 1 <= order <= MAX_HARMONICS:
        raise InputError(
            f"FourierTable harmonic order N = {order} is invalid: must lie in [1, {MAX_HARMONICS}]"
        )
    for name in coefficient_names(order):
        if name not in seen:
            raise InputError(f"FourierTable: missing column {name!r} (harmonic order {order})")
    return order
