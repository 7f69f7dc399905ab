"""Force model interface and the kernel's force law against a plain-Python twin."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics import _storm_kernel as K
from onbottom.errors import InputError
from onbottom.hydro._force_contract import FO_DFY_DYD, FO_FY, FO_FZ, FO_SIZE, N_FORCE_STATE
from onbottom.hydro._morison_kernel import P_CD, P_CL, P_LIFT_REL
from onbottom.hydro.force_model import ForceModel, MorisonLift, parameter_rows


def test_defaults_and_protocol():
    fm = MorisonLift()
    assert isinstance(fm, ForceModel)
    assert (fm.cd, fm.cm, fm.cl) == (0.7, 3.29, 0.9)
    assert fm.added_mass_coefficient == pytest.approx(2.29)
    table = fm.parameter_table(np.array([5.0, 20.0]), np.array([0.0, 0.5]))
    np.testing.assert_array_equal(table, [[0.7, 3.29, 0.9, 0.0], [0.7, 3.29, 0.9, 0.0]])
    assert MorisonLift(lift_relative_velocity=True).parameter_table(1.0, 0.0)[0, P_LIFT_REL] == 1
    d = fm.describe()
    assert d["cd"] == 0.7 and "not DNV-RP-F109" in d["force_model_source"]


def test_per_sea_state_rule_and_validation():
    def rule(k, m):
        return (0.5 + 0.01 * k, 3.29, 0.9 + m)

    fm = MorisonLift.per_sea_state(rule)
    table = fm.parameter_table(np.array([10.0, 30.0]), np.array([0.1, 0.2]))
    np.testing.assert_allclose(table[:, P_CD], [0.6, 0.8])
    np.testing.assert_allclose(table[:, P_CL], [1.0, 1.1])
    assert fm.describe()["coefficient_rule"] == "rule"
    bad = MorisonLift.per_sea_state(lambda k, m: (float("nan"), 1.0, 1.0))
    with pytest.raises(InputError, match="rule"):
        bad.parameter_table(np.array([1.0]), np.array([0.0]))
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
    st[K.ST_FORCE_MODEL] = MorisonLift().model_id
    fp = MorisonLift().parameter_table(1.0, 0.0)
    fs, fs_new, fout = np.zeros(N_FORCE_STATE), np.zeros(N_FORCE_STATE), np.zeros(FO_SIZE)

    def loads(yd):
        K.forces(int(st[K.ST_FORCE_MODEL]), st, fp[0], fs, 3.0, u, dudt, yd, fs_new, fout)
        r_y, r_z = K.load_reductions(st, z)
        return r_y * fout[FO_FY], r_y * fout[FO_DFY_DYD], r_z * fout[FO_FZ], r_y, r_z

    fy, dfdyd, fz, ry, rz = loads(ydot)
    ty, tdy, tz, try_, trz = _twin(u, dudt, 0.3, ydot, z, 0.4, 1025.0, 0.7, 3.29, 0.9, 0.9, 0.7)
    assert fy == pytest.approx(ty, rel=1e-13, abs=1e-12)
    assert dfdyd == pytest.approx(tdy, rel=1e-13, abs=1e-12)
    assert fz == pytest.approx(tz, rel=1e-13, abs=1e-12)
    assert (ry, rz) == pytest.approx((try_, trz), rel=1e-15)
    # the tangent is the derivative of F_Y in ẏ
    h = 1e-6
    f_plus = loads(ydot + h)[0]
    f_minus = loads(ydot - h)[0]
    assert dfdyd == pytest.approx((f_plus - f_minus) / (2 * h), rel=1e-5, abs=1e-6)


def test_kernel_flow_interpolation():
    u = np.array([0.0, 1.0, 4.0])
    a = np.array([1.0, 3.0, 5.0])
    assert K.flow_at(0.5, u, a, 1.0)[:2] == pytest.approx((0.5, 2.0))
    assert K.flow_at(1.25, u, a, 1.0)[:2] == pytest.approx((1.75, 3.5))
    assert K.flow_at(9.0, u, a, 1.0)[:2] == pytest.approx((4.0, 5.0))


def test_parameter_rows_constant_and_blended():
    """One row for a constant model; per sample, blended with the normalised stage weights."""
    stages = [
        {"significant_velocity": 0.5, "mean_period": 8.0},
        {"significant_velocity": 1.0, "mean_period": 10.0},
    ]
    w = np.array([[0.0, 0.5, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.5, 1.0]])
    const = parameter_rows(MorisonLift(), w, stages, 0.2, 0.5)
    assert const.shape == (1, 4) and const.flags.c_contiguous

    def rule(k, m):
        return (0.01 * k, 3.29, m)

    rows = parameter_rows(MorisonLift.per_sea_state(rule), w, stages, 0.2, 0.5)
    assert rows.shape == (5, 4) and rows.flags.c_contiguous
    k = np.array([0.5 * 8.0 / 0.5, 10.0 / 0.5])  # K = U_s T_u / D
    m = np.array([0.2 / 0.5, 0.2 / 1.0])  # M = |V| / U_s
    np.testing.assert_allclose(rows[:, P_CD], [0.01 * k.mean(), 0.01 * k[0], 0.01 * k.mean(),
                                               0.01 * k[1], 0.01 * k[1]])  # fmt: skip
    np.testing.assert_allclose(rows[2, P_CL], m.mean())
    # without stages (regular waves, measured flow): constant models only
    np.testing.assert_array_equal(parameter_rows(MorisonLift(), None, [], 0.2, 0.5), const)
    with pytest.raises(InputError, match="stage_parameters"):
        parameter_rows(MorisonLift.per_sea_state(rule), None, [], 0.2, 0.5)
