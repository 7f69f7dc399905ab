"""DNV-RP-F109 tables used by the absolute lateral static stability check.

* Peak load coefficients C*_Y and C*_Z against K* and M* (DNVGL-RP-F109 (2017) Tables 3-9
  and 3-10; 2010 edition Tables 3-9/3-10): two independent public transcriptions agree value
  for value. Bilinear interpolation in K* and M*.
  K* < 2.5: C*_Y = C*_Y(2.5)·2.5/K* (for M* <= 10 only: beyond, steady current, C*_Y = 1),
  C*_Z = C*_Z(2.5). K* > 140 or M* > 10: the edge value
  (both tables tend to their steady-flow values there) with an OutOfRangeWarning.
* Safety factors γ_SC by region, soil and safety class (2017 Tables 3-5 to 3-8).

The tables are DNV content, reproduced as in the public transcriptions for checking.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import one_of, warn_outside
from onbottom.errors import InputError

__all__ = [
    "CY_TABLE",
    "CZ_TABLE",
    "K_GRID",
    "M_GRID",
    "REGIONS",
    "SAFETY_CLASSES",
    "SAFETY_FACTORS",
    "peak_load_coefficients",
    "safety_factor",
]

K_GRID = np.array([2.5, 5.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 100.0, 140.0])
"""K* columns of Tables 3-9/3-10 [-]."""

M_GRID = np.array([0.0, 0.1, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0, 2.0, 5.0, 10.0])
"""M* rows of Tables 3-9/3-10 [-]."""

# fmt: off
CY_TABLE = np.array([
    [13.0, 6.80, 4.55, 3.33, 2.72, 2.40, 2.15, 1.95, 1.80, 1.52, 1.30],
    [10.7, 5.76, 3.72, 2.72, 2.20, 1.90, 1.71, 1.58, 1.49, 1.33, 1.22],
    [9.02, 5.00, 3.15, 2.30, 1.85, 1.58, 1.42, 1.33, 1.27, 1.18, 1.14],
    [7.64, 4.32, 2.79, 2.01, 1.63, 1.44, 1.33, 1.26, 1.21, 1.14, 1.09],
    [6.63, 3.80, 2.51, 1.78, 1.46, 1.32, 1.25, 1.19, 1.16, 1.10, 1.05],
    [5.07, 3.30, 2.27, 1.71, 1.43, 1.34, 1.29, 1.24, 1.18, 1.08, 1.00],
    [4.01, 2.70, 2.01, 1.57, 1.44, 1.37, 1.31, 1.24, 1.17, 1.05, 1.00],
    [3.25, 2.30, 1.75, 1.49, 1.40, 1.34, 1.27, 1.20, 1.13, 1.01, 1.00],
    [1.52, 1.50, 1.45, 1.39, 1.34, 1.20, 1.08, 1.03, 1.00, 1.00, 1.00],
    [1.11, 1.10, 1.07, 1.06, 1.04, 1.01, 1.00, 1.00, 1.00, 1.00, 1.00],
    [1.00, 1.00, 1.00, 1.00, 1.00, 1.00, 1.00, 1.00, 1.00, 1.00, 1.00],
])
"""C*_Y[M*, K*] (DNVGL-RP-F109 (2017) Table 3-9)."""

CZ_TABLE = np.array([
    [5.00, 5.00, 4.85, 3.21, 2.55, 2.26, 2.01, 1.81, 1.63, 1.26, 1.05],
    [3.87, 4.08, 4.23, 2.87, 2.15, 1.77, 1.55, 1.41, 1.31, 1.11, 0.97],
    [3.16, 3.45, 3.74, 2.60, 1.86, 1.45, 1.26, 1.16, 1.09, 1.00, 0.90],
    [3.01, 3.25, 3.53, 2.14, 1.52, 1.26, 1.10, 1.01, 0.99, 0.95, 0.90],
    [2.87, 3.08, 3.35, 1.82, 1.29, 1.11, 0.98, 0.90, 0.90, 0.90, 0.90],
    [2.21, 2.36, 2.59, 1.59, 1.20, 1.03, 0.92, 0.90, 0.90, 0.90, 0.90],
    [1.53, 1.61, 1.80, 1.18, 1.05, 0.97, 0.92, 0.90, 0.90, 0.90, 0.90],
    [1.05, 1.13, 1.28, 1.12, 0.99, 0.91, 0.90, 0.90, 0.90, 0.90, 0.90],
    [0.96, 1.03, 1.05, 1.00, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90],
    [0.91, 0.92, 0.93, 0.91, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90],
    [0.90, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90, 0.90],
])
"""C*_Z[M*, K*] (DNVGL-RP-F109 (2017) Table 3-10)."""
# fmt: on

SAFETY_CLASSES: tuple[str, ...] = ("low", "normal", "high")
"""Safety classes of DNV-OS-F101 / F109 §2."""

SAFETY_FACTORS: dict[str, dict[str, tuple[float, float, float]]] = {
    "north_sea_winter": {"sand": (0.98, 1.32, 1.67), "clay": (1.00, 1.40, 1.83)},
    "north_sea_cyclonic": {"sand": (0.95, 1.50, 2.16), "clay": (0.95, 1.56, 2.31)},
    "gulf_of_mexico_winter": {"sand": (0.95, 1.41, 1.99), "clay": (0.97, 1.50, 2.16)},
    "gulf_of_mexico_cyclonic": {"sand": (0.95, 1.64, 2.46), "clay": (0.93, 1.64, 2.54)},
}
"""γ_SC (low, normal, high) by region and soil for the absolute check (F109 (2017) Tables
3-5 to 3-8; "sand" covers sand and rock). Region keys: North Sea and Norwegian Sea winter
storms; North Sea cyclonic; Gulf of Mexico and Southern Ocean winter storms; Gulf of Mexico
and Australia cyclonic (labels as in the public transcription; check against the standard)."""

REGIONS: tuple[str, ...] = tuple(SAFETY_FACTORS)


def safety_factor(region: str, soil: str, safety_class: str) -> float:
    """γ_SC [-] for the absolute lateral stability check (F109 (2017) Tables 3-5 to 3-8).

    ``soil`` is ``"sand"``, ``"rock"`` (same column as sand) or ``"clay"``.
    """
    one_of("region", region, REGIONS)
    one_of("soil", soil, ("sand", "rock", "clay"))
    one_of("safety_class", safety_class, SAFETY_CLASSES)
    column = "clay" if soil == "clay" else "sand"
    return SAFETY_FACTORS[region][column][SAFETY_CLASSES.index(safety_class)]


def _interp2(table: NDArray, k: NDArray, m: NDArray) -> NDArray:
    ik = np.clip(np.searchsorted(K_GRID, k, side="right") - 1, 0, K_GRID.size - 2)
    im = np.clip(np.searchsorted(M_GRID, m, side="right") - 1, 0, M_GRID.size - 2)
    tk = (k - K_GRID[ik]) / (K_GRID[ik + 1] - K_GRID[ik])
    tm = (m - M_GRID[im]) / (M_GRID[im + 1] - M_GRID[im])
    a = table[im, ik] * (1 - tk) + table[im, ik + 1] * tk
    b = table[im + 1, ik] * (1 - tk) + table[im + 1, ik + 1] * tk
    return a * (1 - tm) + b * tm


def peak_load_coefficients(k_star: ArrayLike, m_star: ArrayLike) -> tuple[NDArray, NDArray]:
    """Peak horizontal and vertical load coefficients (C*_Y, C*_Z) [-], vectorised.

    Parameters
    ----------
    k_star : array_like
        K* = U* T*/D [-], > 0.
    m_star : array_like
        M* = V*/U* [-], >= 0 (inf allowed: current only → the M* = 10 row).
    """
    k = np.asarray(k_star, dtype=float)
    m = np.asarray(m_star, dtype=float)
    if np.any(~np.isfinite(k) | (k <= 0.0)):
        raise InputError(f"K* = {k!r} is invalid: must be finite and > 0")
    if np.any(np.isnan(m) | (m < 0.0)):
        raise InputError(f"M* = {m!r} is invalid: must be >= 0")
    k, m = np.broadcast_arrays(k, m)
    source = "DNV-RP-F109 (2017) Tables 3-9/3-10"
    warn_outside("K*", float(np.max(k)), 0.0, K_GRID[-1], source)
    finite_m = m[np.isfinite(m)]
    if finite_m.size:
        warn_outside("M*", float(np.max(finite_m)), 0.0, M_GRID[-1], source)
    kc = np.clip(k, K_GRID[0], K_GRID[-1])
    mc = np.clip(np.where(np.isfinite(m), m, M_GRID[-1]), M_GRID[0], M_GRID[-1])
    cy = _interp2(CY_TABLE, kc, mc)
    cz = _interp2(CZ_TABLE, kc, mc)
    # K* < 2.5 rule (C*_Y ∝ 1/K*, wave inertia) only inside the table's M* range: beyond
    # M* = 10 the flow is steady current, the M* >= 10 row is K*-independent (C*_Y = 1), and
    # the rule would send the load to infinity as U* → 0 (a deep-water pipe in a current
    # gave utilisations of 1e17). Choice where F109 is silent; see docs/theory.
    scale = (k < K_GRID[0]) & ~(m > M_GRID[-1])
    cy = np.where(scale, cy * K_GRID[0] / np.where(scale, k, 1.0), cy)
    return cy, cz
