"""Per-sea-state Morison coefficients from a user table C_D, C_M, C_L over (K, M).

DNV-RP-F109 (2010/2017) §3.4 leaves the time-domain coefficients of a dynamic analysis to the
user ("coefficients depending on K, M, roughness and embedment"); a table of them, measured or
taken from the literature (e.g. Sarpkaya & Isaacson 1981; Sumer & Fredsøe 2006 for a cylinder
on a wall), is what an engineer has. This module reads such a table and gives the rule
(K, M) → (C_D, C_M, C_L) of :meth:`onbottom.hydro.force_model.MorisonLift.per_sea_state`.

CSV schema: ``#`` lines are comments; a header ``K,M,C_D,C_M,C_L``; a units line with ``-`` (or
``1``) in every column; then one row per grid cell, sorted by (K, M), every combination of the
K values and M values present once. K > 0 [-], M >= 0 [-], coefficients in [0, 10] [-].
Interpolation: bilinear in (K, M), clamped at the grid's edges with an
:class:`~onbottom.errors.OutOfRangeWarning` naming the sea state outside it.

Case files: ``[hydro] model = "morison"`` with ``coefficient_table = "file.csv"`` (a path
relative to the case file's folder).
"""

from __future__ import annotations

import csv
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from onbottom._validate import file_token, header_mismatch
from onbottom.errors import InputError, OutOfRangeWarning

__all__ = ["MorisonCoefficientTable"]

COLUMNS = ("K", "M", "C_D", "C_M", "C_L")
DIMENSIONLESS = ("-", "1")


@dataclass(frozen=True, eq=False, repr=False)
class MorisonCoefficientTable:
    """C_D, C_M, C_L [-] on a (K, M) grid; call it as ``table(K, M) -> (C_D, C_M, C_L)``.

    Parameters
    ----------
    k : array
        K = U_s T_u / D grid [-], strictly increasing, > 0.
    m : array
        M = V / U_s grid [-], strictly increasing, >= 0.
    coefficients : array
        Shape (3, n_K, n_M): C_D, C_M, C_L [-], each in [0, 10].
    source : str
        Provenance (file name or description).
    """

    k: np.ndarray
    m: np.ndarray
    coefficients: np.ndarray
    source: str = field(default="user table")

    def __post_init__(self) -> None:
        k = np.asarray(self.k, dtype=float)
        m = np.asarray(self.m, dtype=float)
        c = np.asarray(self.coefficients, dtype=float)
        if k.ndim != 1 or k.size < 1 or not np.all(np.isfinite(k)) or np.any(k <= 0.0):
            raise InputError(f"MorisonCoefficientTable.k = {k!r} is invalid: K values > 0")
        if m.ndim != 1 or m.size < 1 or not np.all(np.isfinite(m)) or np.any(m < 0.0):
            raise InputError(f"MorisonCoefficientTable.m = {m!r} is invalid: M values >= 0")
        for name, g in (("k", k), ("m", m)):
            if np.any(np.diff(g) <= 0.0):
                raise InputError(
                    f"MorisonCoefficientTable.{name} = {g.tolist()} is invalid: strictly"
                    " increasing values needed"
                )
        if c.shape != (3, k.size, m.size):
            raise InputError(
                f"MorisonCoefficientTable.coefficients has shape {c.shape}: expected"
                f" (3, {k.size}, {m.size})"
            )
        if not np.all(np.isfinite(c)) or np.any(c < 0.0) or np.any(c > 10.0):
            raise InputError(
                "MorisonCoefficientTable.coefficients are invalid: every C_D, C_M, C_L must lie"
                " in [0, 10]"
            )
        object.__setattr__(self, "k", k)
        object.__setattr__(self, "m", m)
        object.__setattr__(self, "coefficients", c)

    @classmethod
    def from_csv(cls, path: str | Path) -> MorisonCoefficientTable:
        """Read the CSV schema of the module docstring; errors name the file, line and column."""
        p = Path(path)
        rows: list[tuple[int, list[str]]] = []
        for no, line in enumerate(p.read_text(encoding="utf-8").splitlines(), start=1):
            s = line.strip()
            if s and not s.startswith("#"):
                rows.append((no, [x.strip() for x in next(csv.reader([s]))]))
        if len(rows) < 3:
            raise InputError(
                f"Morison coefficient table {p.name}: expected a header line, a units line and"
                " >= 1 data row"
            )
        header, units = rows[0][1], rows[1][1]
        if tuple(header) != COLUMNS:
            raise InputError(
                f"Morison coefficient table {p.name} line {rows[0][0]}: the header is"
                f" invalid ({header_mismatch(header, COLUMNS)}): expected {','.join(COLUMNS)}"
            )
        if len(units) != len(COLUMNS) or any(u not in DIMENSIONLESS for u in units):
            shown = ", ".join(file_token(u, DIMENSIONLESS) for u in units[: len(COLUMNS) + 1])
            raise InputError(
                f"Morison coefficient table {p.name} line {rows[1][0]}: units {shown} are"
                " invalid: every column is dimensionless, write '-' or '1'"
            )
        data = []
        for no, vals in rows[2:]:
            if len(vals) != len(COLUMNS):
                raise InputError(
                    f"Morison coefficient table {p.name} line {no}: {len(vals)} values for"
                    f" {len(COLUMNS)} columns"
                )
            try:
                row = [float(v) for v in vals]
            except ValueError:
                raise InputError(
                    f"Morison coefficient table {p.name} line {no}: a value is not a number"
                ) from None
            if not all(math.isfinite(v) for v in row):
                raise InputError(f"Morison coefficient table {p.name} line {no}: a value is NaN")
            data.append((no, row))
        ks = sorted({r[0] for _, r in data})
        ms = sorted({r[1] for _, r in data})
        c = np.full((3, len(ks), len(ms)), np.nan)
        prev = None
        for no, r in data:
            key = (r[0], r[1])
            if prev is not None and key <= prev:
                raise InputError(
                    f"Morison coefficient table {p.name} line {no}: rows must be sorted by (K, M)"
                    f" without repeats; (K, M) = {key} follows {prev}"
                )
            prev = key
            c[:, ks.index(r[0]), ms.index(r[1])] = r[2:]
        missing = np.argwhere(np.isnan(c[0]))
        if missing.size:
            i, j = missing[0]
            raise InputError(
                f"Morison coefficient table {p.name}: the cell K = {ks[i]:g}, M = {ms[j]:g} is"
                f" missing ({len(missing)} missing): give every combination of K and M"
            )
        return cls(np.array(ks), np.array(ms), c, source=p.name)

    @property
    def __name__(self) -> str:  # provenance of MorisonLift.describe() (``coefficient_rule``)
        return f"MorisonCoefficientTable({self.source})"

    def __repr__(self) -> str:
        return f"MorisonCoefficientTable({self.source}: {self.k.size} K x {self.m.size} M)"

    def __call__(self, k: float, m: float) -> tuple[float, float, float]:
        """(C_D, C_M, C_L) [-] at K, M (bilinear; clamped with a warning outside the grid)."""
        kk = min(max(k, self.k[0]), self.k[-1])
        mm = min(max(m, self.m[0]), self.m[-1])
        if kk != k or mm != m:
            warnings.warn(
                f"K = {k:.4g}, M = {m:.4g} lie outside the Morison coefficient table"
                f" {self.source} (K {self.k[0]:g}..{self.k[-1]:g}, M {self.m[0]:g}.."
                f"{self.m[-1]:g}); the edge coefficients are used",
                OutOfRangeWarning,
                stacklevel=2,
            )
        out = []
        for c in self.coefficients:
            along_m = [float(np.interp(mm, self.m, row)) for row in c]
            out.append(float(np.interp(kk, self.k, along_m)))
        return out[0], out[1], out[2]
