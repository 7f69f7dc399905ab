"""Force model interface and the kernel's force law against a plain-Python twin."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics import _storm_kernel as K
from onbottom.errors import InputError
from onbottom.hydro.force_model import ForceModel, MorisonLift


def test_defaults_and_protocol():
    fm = MorisonLift()
    assert isinstance(fm, ForceModel)
    assert (fm.cd, fm.cm, fm.cl) == (0.7, 3.29, 0.9)
    assert fm.added_mass_coefficient == pytest.approx(2.29)
    table = fm.coefficient_table(np.array([5.0, 20.0]), np.array([0.0, 0.5]))
    np.testing.assert_array_equal(table, [[0.7, 0.7], [3.29, 3.29], [0.9, 0.9]])
    d = fm.describe()
    assert d["cd"] == 0.7 and "not DNV-RP-F109" in d["force_model_source"]


def test_per_sea_state_rule_and_validation():
    def rule(k, m):
        return (0.5 + 0.01 * k, 3.29, 0.9 + m)

    fm = MorisonLift.per_sea_state(rule)
    table = fm.coefficient_table(np.array([10.0, 30.0]), np.array([0.1, 0.2]))
    np.testing.assert_allclose(table[0], [0.6, 0.8])
    np.testing.assert_allclose(table[2], [1.0, 1.1])
    assert fm.describe()["coefficient_rule"] == "rule"
    bad = MorisonLift.per_sea_state(lambda k, m: (float("nan"), 1.0, 1.0))
    with pytest.raises(InputError, match="rule"):
        bad.coefficient_table(np.array([1.0]), np.array([0.0]))
    with pytest.raises(InputError, match="MorisonLift.cd"):
        MorisonLift(cd=-1.0)
    with pytest.raises(InputError, match="MorisonLift.cl"):
        MorisonLift(cl=11.0)
    with pytest.raises(InputError, match="C_a"):
        MorisonLift(cm=0.5)


def _twin(u, dudt, vc, ydot, z, d, rho, cd, cm, cl, ryc, rzc):
    """Plain-Python force law (docs/theory/storm_section.md) with F109 Eqs 3.19-3.20."""
    zd = z / d
    rpy = 1.0 if zd <= 0 else max(1.0 - 1.4 * zd, 0.3)
    rpz = 1.0 if zd <= 0.1 else max(1.0 - 1.3 * (zd - 0.1), 0.0)
    ry, rz = ryc * rpy, rzc * rpz
    w = u + vc - ydot
    fy = ry * (0.5 * rho * d * cd * w * abs(w) + rho * math.pi * d * d / 4 * cm * dudt)
    fz = rz * 0.5 * rho * d * cl * (u + vc) ** 2
    return fy, -ry * rho * d * cd * abs(w), fz, ry, rz


@pytest.mark.parametrize("z", [0.0, 0.02, 0.08, 0.3])
@pytest.mark.parametrize(
    ("u", "dudt", "ydot"), [(1.2, 0.3, 0.0), (-0.7, -0.5, 0.2), (0.1, 2.0, 0.9)]
)
def test_kernel_force_law_matches_twin(z, u, dudt, ydot):
    st = np.zeros(K.N_SETTINGS)
    st[K.ST_D], st[K.ST_RHO], st[K.ST_CURRENT] = 0.4, 1025.0, 0.3
    st[K.ST_RY_CONST], st[K.ST_RZ_CONST], st[K.ST_USE_PEN] = 0.9, 0.7, 1.0
    coef = np.array([[0.7], [3.29], [0.9]])
    fy, dfdyd, fz, ry, rz = K.hydro_forces(st, coef, 0, u, dudt, ydot, z)
    ty, tdy, tz, try_, trz = _twin(u, dudt, 0.3, ydot, z, 0.4, 1025.0, 0.7, 3.29, 0.9, 0.9, 0.7)
    assert fy == pytest.approx(ty, rel=1e-13, abs=1e-12)
    assert dfdyd == pytest.approx(tdy, rel=1e-13, abs=1e-12)
    assert fz == pytest.approx(tz, rel=1e-13, abs=1e-12)
    assert (ry, rz) == pytest.approx((try_, trz), rel=1e-15)
    # the tangent is the derivative of F_Y in ẏ
    h = 1e-6
    fp = K.hydro_forces(st, coef, 0, u, dudt, ydot + h, z)[0]
    fm = K.hydro_forces(st, coef, 0, u, dudt, ydot - h, z)[0]
    assert dfdyd == pytest.approx((fp - fm) / (2 * h), rel=1e-5, abs=1e-6)


def test_kernel_flow_interpolation():
    u = np.array([0.0, 1.0, 4.0])
    a = np.array([1.0, 3.0, 5.0])
    assert K.flow_at(0.5, u, a, 1.0)[:2] == pytest.approx((0.5, 2.0))
    assert K.flow_at(1.25, u, a, 1.0)[:2] == pytest.approx((1.75, 3.5))
    assert K.flow_at(9.0, u, a, 1.0)[:2] == pytest.approx((4.0, 5.0))
