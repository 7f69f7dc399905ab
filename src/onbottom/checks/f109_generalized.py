"""DNV-RP-F109 generalized lateral stability method (§3.5): L_stable and L_10 from F109's tables.

Dimensionless groups (F109 (2010/2017) §3.5.2, Eqs 3.31–3.35; U_s and T_u at the pipe, V the
mean current over D normal to the pipe):

* K = U_s T_u / D — significant Keulegan–Carpenter number;
* M = V / U_s — steady-to-oscillatory velocity ratio;
* N = U_s / (g T_u) — spectral acceleration factor;
* L = w_s / (½ ρ_w D U_s²) — significant weight parameter (so that the pipe's specific
  gravity is s_g = 1 + (2/π) N K L exactly, :func:`specific_gravity`).

A pipe is "virtually stable" (lateral displacement ≤ 0.5D in the design storm) when
L ≥ L_stable, and moves at most 10D when L ≥ L_10 (F109 §3.5.3/§3.5.4).

Sand (F109 Tables 3-2, 3-3, 3-4; the tabulated quantity is L/(2 + M)²):

* L_stable, K ≤ 5: Table 3-2 in N (0.003 … 0.048) and M;
* L_stable, K ≥ 10: Table 3-3 in K (10 … 60) and M;
* L_stable, 5 < K < 10: linear in K between the K = 5 value (Table 3-2) and the K = 10 value
  (Table 3-3);
* L_10, K ≥ 5: Table 3-4 in K (5 … 100) and M.

Between nodes: linear interpolation in each variable (the linear rule F109 states for
5 < K < 10, applied inside the tables too; background knowledge, to confirm against the
standard). Edges as the tables are labelled (background knowledge, to confirm): the first M
row is "M ≤ 0.2", the last "M ≥ 10"; the last K column is "K ≥ 60" (Table 3-3) and "K ≥ 100"
(Table 3-4). Any other
point outside a table (N < 0.003 or N > 0.048 at K < 10; K < 5 for L_10) is **not covered**:
:class:`NotCoveredError` (functions) or a :class:`GeneralizedRequirement` with
``covered=False`` and the reason — never extrapolated, never NaN.

Clay (F109 Eq 3.36 for L_stable; Eq 3.37 with the C1, C2, C3, K_b tables for L_10): **not
covered here**. The one public transcription found of the coefficients is internally
inconsistent (its two copies disagree) and the closed form of Eq 3.36 could not be confirmed;
the clay functions say so by raising :class:`NotCoveredError` rather than giving an
unconfirmed number as F109's.

Provenance and confidence of each table: ``docs/theory/dnv_rp_f109.md`` (generalized
method). The tables are DNV content, reproduced from public transcriptions for checking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onbottom.constants import GRAVITY
from onbottom.errors import InputError, OnbottomError

__all__ = [
    "CRITERIA",
    "L10_SAND_K",
    "L10_SAND_M",
    "L10_SAND_TABLE",
    "LSTABLE_K5_N",
    "LSTABLE_K5_TABLE",
    "LSTABLE_K10_K",
    "LSTABLE_K10_TABLE",
    "LSTABLE_M",
    "GeneralizedRequirement",
    "NotCoveredError",
    "generalized_point",
    "generalized_requirement",
    "generalized_table",
    "l_10_clay",
    "l_10_sand",
    "l_stable_clay",
    "l_stable_sand",
    "specific_gravity",
]

CRITERIA: dict[str, str] = {"0.5D": "L_stable", "10D": "L_10"}
"""Allowable displacement → F109 weight parameter."""

LSTABLE_M = np.array([0.2, 0.4, 0.5, 0.6, 0.8, 1.0, 1.5, 2.0, 4.0, 10.0])
"""M rows of Tables 3-2, 3-3 and 3-4 (first row "M ≤ 0.2", last "M ≥ 10") [-]."""

LSTABLE_K5_N = np.array([0.003, 0.006, 0.012, 0.024, 0.048])
"""N columns of Table 3-2 (L_stable, K ≤ 5) [-]."""

LSTABLE_K10_K = np.array([10.0, 15.0, 20.0, 30.0, 40.0, 60.0])
"""K columns of Table 3-3 (L_stable, K ≥ 10; last column "K ≥ 60") [-]."""

L10_SAND_K = np.array([5.0, 10.0, 15.0, 20.0, 30.0, 40.0, 60.0, 100.0])
"""K columns of Table 3-4 (L_10, sand; last column "K ≥ 100") [-]."""

L10_SAND_M = LSTABLE_M
"""M rows of Table 3-4 [-]."""

# fmt: off
LSTABLE_K5_TABLE = np.array([
    [1.55, 1.45, 1.34, 1.24, 1.13],
    [2.00, 1.65, 1.34, 1.24, 1.13],
    [3.30, 2.60, 1.91, 1.24, 1.13],
    [3.75, 3.07, 2.38, 1.70, 1.13],
    [4.00, 3.45, 2.90, 2.36, 1.81],
    [3.90, 3.50, 3.10, 2.71, 2.31],
    [3.25, 3.13, 3.00, 2.88, 2.75],
    [2.75, 2.75, 2.75, 2.75, 2.75],
    [2.60, 2.60, 2.60, 2.60, 2.60],
    [2.50, 2.50, 2.50, 2.50, 2.50],
])
"""L_stable/(2 + M)²[M, N], sand, K ≤ 5 (F109 (2010/2017) Table 3-2). Confidence [V1]: one
public transcription; row shapes consistent with the K ≥ 10 table at M ≥ 2."""

LSTABLE_K10_TABLE = np.array([
    [1.50, 1.42, 1.35, 1.25, 1.22, 1.22],
    [1.82, 1.70, 1.61, 1.53, 1.50, 1.50],
    [2.19, 1.97, 1.83, 1.69, 1.61, 1.61],
    [2.65, 2.35, 2.18, 1.99, 1.85, 1.72],
    [3.05, 2.55, 2.32, 2.13, 2.01, 1.90],
    [3.05, 2.55, 2.40, 2.20, 2.06, 1.95],
    [2.65, 2.45, 2.36, 2.24, 2.11, 2.09],
    [2.50, 2.40, 2.35, 2.27, 2.22, 2.19],
    [2.45, 2.40, 2.39, 2.37, 2.37, 2.37],
    [2.50, 2.50, 2.50, 2.50, 2.50, 2.50],
])
"""L_stable/(2 + M)²[M, K], sand, K ≥ 10 (F109 (2010/2017) Table 3-3). Confidence [V2]: two
independent public transcriptions (Python and JavaScript) agree value for value."""

L10_SAND_TABLE = np.array([
    [0.20, 0.41, 0.61, 0.81, 0.69, 0.69, 0.69, 0.69],
    [0.31, 0.62, 0.93, 0.81, 0.75, 0.72, 0.70, 0.70],
    [0.34, 0.69, 1.03, 0.93, 0.83, 0.78, 0.75, 1.00],
    [0.79, 1.20, 1.13, 1.10, 1.07, 1.05, 1.03, 1.02],
    [0.85, 1.40, 1.37, 1.35, 1.33, 1.33, 1.32, 1.31],
    [1.60, 1.50, 1.47, 1.45, 1.43, 1.43, 1.42, 1.41],
    [1.80, 1.70, 1.67, 1.65, 1.63, 1.63, 1.62, 1.61],
    [1.90, 1.80, 1.77, 1.75, 1.73, 1.73, 1.72, 1.71],
    [2.10, 2.00, 1.97, 1.95, 1.93, 1.93, 1.92, 1.91],
    [2.50, 2.50, 2.50, 2.50, 2.50, 2.50, 2.50, 2.50],
])
"""L_10/(2 + M)²[M, K], sand (F109 (2010/2017) Table 3-4). Confidence [V1, disputed]: the
transcription used has the 8 K columns of the standard; a second public transcription (7
columns) differs in most cells (e.g. 0.12 against 0.20 at M ≤ 0.2, K = 5). Two cells look
like typing slips and are kept as transcribed, being the heavier reading: M = 0.5, K ≥ 100
(1.00 where the row falls to 0.75) and the M ≥ 10 row (2.50 against 1.91–2.10 at M = 4)."""
# fmt: on

SOURCE = "DNV-RP-F109 (2010; 2017 re-issue) §3.5"
_N_MIN, _N_MAX = float(LSTABLE_K5_N[0]), float(LSTABLE_K5_N[-1])
_CLAY_REASON = (
    "clay: F109 Eq 3.36 (L_stable) and Eq 3.37 with its C1/C2/C3/K_b tables (L_10) are not"
    " reproduced — the one public transcription found is internally inconsistent and could"
    " not be cross-checked"
)


class NotCoveredError(OnbottomError, ValueError):
    """The point lies outside F109's generalized tables (or a part not reproduced here).

    ``reason`` says which table and which variable; nothing is extrapolated."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


@dataclass(frozen=True)
class GeneralizedRequirement:
    """F109 generalized requirement at one point.

    Attributes
    ----------
    soil : str
        ``"sand"`` or ``"clay"``.
    criterion : str
        ``"0.5D"`` (L_stable) or ``"10D"`` (L_10).
    K, M, N : float
        The point [-].
    covered : bool
        True where F109's tables give L at the point.
    L : float or None
        Required weight parameter L [-] (None where not covered).
    reason : str
        Which table (and interpolation) gave L, or why the point is not covered.
    source : str
        The clause and tables.
    """

    soil: str
    criterion: str
    K: float
    M: float
    N: float
    covered: bool
    L: float | None
    reason: str
    source: str

    def required_weight(self, diameter: float, us: float, water_density: float) -> float | None:
        """w_s = L ½ ρ_w D U_s² [N/m] (None where not covered); D [m], U_s [m/s], ρ_w
        [kg/m³]."""
        if self.L is None:
            return None
        return self.L * 0.5 * water_density * diameter * us**2


def specific_gravity(n: float, k: float, el: float) -> float:
    """Pipe specific gravity s_g = 1 + (2/π) N K L [-] (exact algebra of the F109 groups:
    N K L = 2 w_s/(ρ_w g D²) and buoyancy ρ_w g π D²/4)."""
    return 1.0 + (2.0 / math.pi) * n * k * el


def _check(name: str, value: float, positive: bool = True) -> float:
    v = float(value)
    if not math.isfinite(v) or (v <= 0.0 if positive else v < 0.0):
        rng = "> 0" if positive else ">= 0"
        raise InputError(f"{name} = {value!r} is invalid: must be finite and {rng}")
    return v


def _lin(x: float, grid: np.ndarray, values: np.ndarray) -> float:
    return float(np.interp(x, grid, values))


def _row_in_m(table: np.ndarray, m: float) -> np.ndarray:
    """The table interpolated linearly in M (M ≤ 0.2 → first row, M ≥ 10 → last row)."""
    mm = min(max(m, float(LSTABLE_M[0])), float(LSTABLE_M[-1]))
    return np.array([_lin(mm, LSTABLE_M, table[:, j]) for j in range(table.shape[1])])


def _k5(m: float, n: float) -> float:
    if not (_N_MIN <= n <= _N_MAX):
        raise NotCoveredError(
            f"sand L_stable at K <= 10 needs Table 3-2: N = {n:.4g} outside its columns"
            f" [{_N_MIN:g}, {_N_MAX:g}]"
        )
    return _lin(n, LSTABLE_K5_N, _row_in_m(LSTABLE_K5_TABLE, m))


def _k10(k: float, m: float) -> float:
    return _lin(min(k, float(LSTABLE_K10_K[-1])), LSTABLE_K10_K, _row_in_m(LSTABLE_K10_TABLE, m))


def l_stable_sand(K: float, M: float, N: float) -> float:
    """L_stable on sand [-] (F109 Tables 3-2/3-3, linear in K for 5 < K < 10).

    Parameters
    ----------
    K : float
        Significant Keulegan–Carpenter number U_s T_u / D [-], > 0.
    M : float
        Current ratio V / U_s [-], >= 0.
    N : float
        Spectral acceleration factor U_s / (g T_u) [-], > 0; used for K < 10 (Table 3-2,
        0.003 … 0.048; outside: :class:`NotCoveredError`).
    """
    k, m, n = _check("K", K), _check("M", M, positive=False), _check("N", N)
    scale = (2.0 + m) ** 2
    if k >= 10.0:
        return _k10(k, m) * scale
    a = _k5(m, n)
    if k <= 5.0:
        return a * scale
    b = _k10(10.0, m)
    return (a + (b - a) * (k - 5.0) / 5.0) * scale


def l_10_sand(K: float, M: float) -> float:
    """L_10 on sand [-] (F109 Table 3-4; K >= 5, K ≥ 100 → the K = 100 column).

    Parameters
    ----------
    K : float
        Significant Keulegan–Carpenter number [-]; K < 5: :class:`NotCoveredError`.
    M : float
        Current ratio V / U_s [-], >= 0.
    """
    k, m = _check("K", K), _check("M", M, positive=False)
    if k < float(L10_SAND_K[0]):
        raise NotCoveredError(f"sand L_10 (Table 3-4): K = {k:.4g} below its first column K = 5")
    kk = min(k, float(L10_SAND_K[-1]))
    return _lin(kk, L10_SAND_K, _row_in_m(L10_SAND_TABLE, m)) * (2.0 + m) ** 2


def l_stable_clay(K: float, M: float, N: float, G_c: float) -> float:
    """L_stable on clay (F109 Eq 3.36): not reproduced — always :class:`NotCoveredError`
    (see the module docstring). K, M, N, G_c = s_u/(D γ_s) [-] are validated first."""
    _check("K", K), _check("M", M, positive=False), _check("N", N), _check("G_c", G_c)
    raise NotCoveredError(_CLAY_REASON)


def l_10_clay(K: float, M: float, N: float, G_c: float) -> float:
    """L_10 on clay (F109 Eq 3.37 and its coefficient tables): not reproduced — always
    :class:`NotCoveredError` (see the module docstring)."""
    _check("K", K), _check("M", M, positive=False), _check("N", N), _check("G_c", G_c)
    raise NotCoveredError(_CLAY_REASON)


def _describe(soil: str, criterion: str, k: float) -> str:
    if soil == "clay":
        return "F109 Eq 3.36/3.37"
    if criterion == "10D":
        return "F109 Table 3-4 (L_10/(2+M)², linear in K and M)"
    if k >= 10.0:
        return "F109 Table 3-3 (L_stable/(2+M)², K >= 10, linear in K and M)"
    if k <= 5.0:
        return "F109 Table 3-2 (L_stable/(2+M)², K <= 5, linear in N and M)"
    return "F109 Tables 3-2 and 3-3, linear in K between K = 5 and K = 10"


def generalized_requirement(
    soil: str,
    criterion: str,
    K: float,
    M: float,
    N: float,
    G_c: float | None = None,
) -> GeneralizedRequirement:
    """F109's generalized requirement at one point, never raising for an uncovered point.

    Parameters
    ----------
    soil : str
        ``"sand"`` or ``"clay"`` (anything else: not covered, with the reason).
    criterion : str
        ``"0.5D"`` (L_stable) or ``"10D"`` (L_10); anything else: not covered.
    K, M, N : float
        The F109 groups [-] (K > 0, M >= 0, N > 0; invalid values raise
        :class:`~onbottom.errors.InputError`).
    G_c : float or None
        Clay strength parameter s_u/(D γ_s) [-] (clay only).
    """
    k, m, n = _check("K", K), _check("M", M, positive=False), _check("N", N)
    base = {"soil": soil, "criterion": criterion, "K": k, "M": m, "N": n, "source": SOURCE}
    if criterion not in CRITERIA:
        return GeneralizedRequirement(
            **base, covered=False, L=None,
            reason=f"allowable {criterion!r}: F109's generalized method gives 0.5D and 10D only",
        )  # fmt: skip
    try:
        if soil == "sand":
            el = l_stable_sand(k, m, n) if criterion == "0.5D" else l_10_sand(k, m)
        elif soil == "clay":
            if G_c is None:
                raise NotCoveredError(_CLAY_REASON)
            el = (l_stable_clay if criterion == "0.5D" else l_10_clay)(k, m, n, G_c)
        else:
            raise NotCoveredError(
                f"seabed {soil!r}: F109's generalized method covers sand and clay only"
            )
    except NotCoveredError as exc:
        return GeneralizedRequirement(**base, covered=False, L=None, reason=exc.reason)
    return GeneralizedRequirement(**base, covered=True, L=el, reason=_describe(soil, criterion, k))


def generalized_point(details: dict, water_density: float) -> dict[str, float] | None:
    """The F109 groups of an absolute-lateral check row's ``details`` (``diameter`` D [m],
    ``us`` U_s [m/s], ``tu`` T_u [s], ``v_star`` V [m/s], ``submerged_weight`` w_s [N/m]):
    K, M, N, L_actual, U_s and D (None without wave flow at the pipe); ρ_w [kg/m³]."""
    d, us, tu = details["diameter"], details["us"], details["tu"]
    v = details.get("v_star", 0.0)
    if us <= 0.0 or tu <= 0.0:
        return None
    return {
        "K": us * tu / d,
        "M": v / us,
        "N": us / (GRAVITY * tu),
        "L_actual": details["submerged_weight"] / (0.5 * water_density * d * us**2),
        "U_s": us,
        "diameter": d,
    }


def generalized_table(rows: list, soil: str | None, water_density: float) -> list[dict]:
    """Both criteria of F109's generalized method for every absolute-lateral row of
    :func:`onbottom.checks.design.run_checks` (what ``onbottom stability`` reports): per
    combination the point, L_stable and L_10 (None where not covered, with the reason) and
    the utilisations L_required/L_actual. ``soil``: ``"sand"``, ``"clay"`` or None (a seabed
    F109's generalized method does not cover)."""
    out = []
    for r in rows:
        if r.name != "absolute_lateral" or "us" not in r.details:
            continue
        p = generalized_point(r.details, water_density)
        row: dict = {"combination": r.combination, "condition": r.condition, "point": p}
        for crit, key in CRITERIA.items():
            if p is None:
                req = None
                reason = "no wave flow at the pipe (U_s = 0)"
            elif soil is None:
                req, reason = None, "seabed not covered by F109's generalized method (§3.5)"
            else:
                req = generalized_requirement(soil, crit, p["K"], p["M"], p["N"])
                reason = req.reason
            el = None if req is None else req.L
            row[key] = el
            row[f"{key}_reason"] = reason
            row[f"utilisation_{crit}"] = None if el is None or p is None else el / p["L_actual"]
        out.append(row)
    return out
