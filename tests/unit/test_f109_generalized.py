"""Unit tests: F109's generalized method (§3.5) from F109's tables
(:mod:`onbottom.checks.f109_generalized`).

Table nodes are read back exactly (the tabulated L/(2 + M)² times (2 + M)²); between nodes the
interpolation is worked by hand; at the edges the labelled rows/columns (M ≤ 0.2, M ≥ 10,
K ≥ 60, K ≥ 100) are used and anything else outside the tables is "not covered", never
extrapolated and never NaN.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.checks import f109_generalized as g
from onbottom.constants import GRAVITY
from onbottom.errors import InputError


def test_tables_shapes_and_grids():
    assert g.LSTABLE_K5_TABLE.shape == (g.LSTABLE_M.size, g.LSTABLE_K5_N.size)
    assert g.LSTABLE_K10_TABLE.shape == (g.LSTABLE_M.size, g.LSTABLE_K10_K.size)
    assert g.L10_SAND_TABLE.shape == (g.L10_SAND_M.size, g.L10_SAND_K.size)
    for grid in (g.LSTABLE_M, g.LSTABLE_K5_N, g.LSTABLE_K10_K, g.L10_SAND_K):
        assert np.all(np.diff(grid) > 0)


@pytest.mark.parametrize("i", range(10))
def test_lstable_k10_nodes_exact(i):
    m = float(g.LSTABLE_M[i])
    for j, k in enumerate(g.LSTABLE_K10_K):
        want = g.LSTABLE_K10_TABLE[i, j] * (2.0 + m) ** 2
        assert g.l_stable_sand(float(k), m, 0.5) == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("i", range(10))
def test_lstable_k5_nodes_exact(i):
    m = float(g.LSTABLE_M[i])
    for j, n in enumerate(g.LSTABLE_K5_N):
        want = g.LSTABLE_K5_TABLE[i, j] * (2.0 + m) ** 2
        assert g.l_stable_sand(5.0, m, float(n)) == pytest.approx(want, rel=1e-12)
        assert g.l_stable_sand(2.0, m, float(n)) == pytest.approx(want, rel=1e-12)  # K <= 5


@pytest.mark.parametrize("i", range(10))
def test_l10_sand_nodes_exact(i):
    m = float(g.L10_SAND_M[i])
    for j, k in enumerate(g.L10_SAND_K):
        want = g.L10_SAND_TABLE[i, j] * (2.0 + m) ** 2
        assert g.l_10_sand(float(k), m) == pytest.approx(want, rel=1e-12)


def test_published_cells():
    # a few cells as transcribed (Table 3-3: M = 0.8, K = 10 → 3.05; M = 2, K ≥ 60 → 2.19;
    # Table 3-2: M = 0.5, N = 0.012 → 1.91; Table 3-4: M = 1, K = 20 → 1.45)
    assert g.l_stable_sand(10.0, 0.8, 0.01) == pytest.approx(3.05 * 2.8**2)
    assert g.l_stable_sand(60.0, 2.0, 0.01) == pytest.approx(2.19 * 16.0)
    assert g.l_stable_sand(3.0, 0.5, 0.012) == pytest.approx(1.91 * 6.25)
    assert g.l_10_sand(20.0, 1.0) == pytest.approx(1.45 * 9.0)


def test_between_nodes_by_hand():
    # Table 3-3, K = 12.5 (between 10 and 15), M = 0.7 (between 0.6 and 0.8):
    # row 0.6: 2.65 + (2.35 - 2.65)/2 = 2.50; row 0.8: 3.05 + (2.55 - 3.05)/2 = 2.80;
    # M = 0.7: (2.50 + 2.80)/2 = 2.65; × (2.7)² = 19.3185
    assert g.l_stable_sand(12.5, 0.7, 0.01) == pytest.approx(2.65 * 2.7**2, rel=1e-12)
    # Table 3-2, N = 0.009 (between 0.006 and 0.012), M = 0.4: 1.65 + (1.34 - 1.65)/2 = 1.495
    assert g.l_stable_sand(4.0, 0.4, 0.009) == pytest.approx(1.495 * 2.4**2, rel=1e-12)
    # 5 < K < 10: K = 7 at M = 0.5, N = 0.006 — K = 5: 2.60 (Table 3-2); K = 10: 2.19 (3-3);
    # 2.60 + (2.19 - 2.60)·(7 - 5)/5 = 2.436; × 2.5²
    assert g.l_stable_sand(7.0, 0.5, 0.006) == pytest.approx(2.436 * 6.25, rel=1e-12)
    # Table 3-4, K = 50 (40 … 60), M = 1.5: 1.63 + (1.62 - 1.63)/2 = 1.625; × 3.5²
    assert g.l_10_sand(50.0, 1.5) == pytest.approx(1.625 * 12.25, rel=1e-12)
    # continuity at K = 5 and K = 10 of the 5 < K < 10 rule
    for m in (0.2, 0.5, 1.0, 4.0):
        assert g.l_stable_sand(5.0 + 1e-9, m, 0.006) == pytest.approx(
            g.l_stable_sand(5.0, m, 0.006), rel=1e-7
        )
        assert g.l_stable_sand(10.0 - 1e-9, m, 0.006) == pytest.approx(
            g.l_stable_sand(10.0, m, 0.006), rel=1e-7
        )


def test_validity_edges():
    # labelled edge rows and columns: M <= 0.2, M >= 10, K >= 60 (3-3), K >= 100 (3-4)
    assert g.l_stable_sand(20.0, 0.0, 0.01) / 4.0 == pytest.approx(1.35)
    assert g.l_stable_sand(20.0, 25.0, 0.01) / 27.0**2 == pytest.approx(2.50)
    assert g.l_stable_sand(200.0, 1.0, 0.01) / 9.0 == pytest.approx(1.95)
    assert g.l_10_sand(500.0, 0.2) / 2.2**2 == pytest.approx(0.69)
    # K >= 10 does not need N (Table 3-3 has no N): any N is accepted
    assert g.l_stable_sand(15.0, 0.5, 0.5) == g.l_stable_sand(15.0, 0.5, 0.0001)
    # outside: N below/above Table 3-2's columns at K < 10, K < 5 for L_10
    for n in (0.0029, 0.049):
        with pytest.raises(g.NotCoveredError, match="Table 3-2"):
            g.l_stable_sand(7.0, 0.5, n)
    with pytest.raises(g.NotCoveredError, match="Table 3-4"):
        g.l_10_sand(4.9, 0.5)
    # clay is not reproduced: a named refusal, never a number
    with pytest.raises(g.NotCoveredError, match="clay"):
        g.l_stable_clay(10.0, 0.5, 0.01, 0.5)
    with pytest.raises(g.NotCoveredError, match="clay"):
        g.l_10_clay(10.0, 0.5, 0.01, 0.5)
    # invalid inputs name the field
    with pytest.raises(InputError, match="K"):
        g.l_stable_sand(-1.0, 0.5, 0.01)
    with pytest.raises(InputError, match="M"):
        g.l_10_sand(10.0, math.nan)


def test_requirement_result():
    r = g.generalized_requirement("sand", "0.5D", 18.0, 0.4, 0.009)
    assert r.covered and r.L == pytest.approx(g.l_stable_sand(18.0, 0.4, 0.009))
    assert "Table 3-3" in r.reason and "§3.5" in r.source
    assert r.required_weight(0.3, 0.8, 1025.0) == pytest.approx(r.L * 0.5 * 1025 * 0.3 * 0.64)
    for soil, crit, k, n in (("sand", "0.5D", 7.0, 0.06), ("clay", "10D", 10.0, 0.01),
                             ("rock", "0.5D", 10.0, 0.01), ("sand", "user", 10.0, 0.01),
                             ("sand", "10D", 3.0, 0.01)):  # fmt: skip
        r = g.generalized_requirement(soil, crit, k, 0.5, n, G_c=0.5)
        assert not r.covered and r.L is None and r.reason
        assert r.required_weight(0.3, 0.8, 1025.0) is None
    with pytest.raises(AttributeError):
        r.L = 1.0  # frozen


def test_specific_gravity_identity():
    # s_g = 1 + (2/π) N K L for a pipe built from its own properties
    rho, d, us, tu = 1025.0, 0.35, 0.9, 9.0
    for ws in (150.0, 800.0, 2500.0):
        k, n = us * tu / d, us / (GRAVITY * tu)
        el = ws / (0.5 * rho * d * us**2)
        buoy = rho * GRAVITY * math.pi * d**2 / 4.0
        assert g.specific_gravity(n, k, el) == pytest.approx((ws + buoy) / buoy, rel=1e-12)
