"""Wake force model: inputs, parameter rows, provenance, and the kernel against hand values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.hydro import _wake_kernel as wk
from onbottom.hydro._force_contract import (
    FO_DFY_DYD,
    FO_DFZ_DYD,
    FO_FY,
    FO_FZ,
    FO_SIZE,
    N_FORCE_STATE,
)
from onbottom.hydro.wake import FORCE_WAKE, WakeModel

RHO = 1025.0
D = 0.5


def _eval(params, state_old, t, u, dudt, vc, ydot=0.0):
    state_new = np.full(N_FORCE_STATE, np.nan)
    out = np.full(FO_SIZE, np.nan)
    wk.wake_kernel(params, state_old, t, u, dudt, vc, ydot, D, RHO, state_new, out)
    return state_new, out


def test_contract_constants():
    assert (FO_FY, FO_DFY_DYD, FO_FZ, FO_DFZ_DYD, FO_SIZE, N_FORCE_STATE) == (0, 1, 2, 3, 4, 16)
    assert FORCE_WAKE == 1
    assert wk.N_USED_STATE <= N_FORCE_STATE


def test_model_identity_and_added_mass():
    m = WakeModel()
    assert (m.name, m.model_id) == ("wake", 1)
    assert m.added_mass_coefficient == pytest.approx(2.29)
    assert WakeModel(added_mass=1.0).added_mass_coefficient == 1.0
    d = m.describe()
    assert d["reconstruction"] == 1
    assert d["force_model"] == "wake"
    assert "not the licensed" in d["force_model_source"]
    assert d["wake_ratio"] == m.wake_ratio


def test_parameter_table_rows_and_layout():
    m = WakeModel(lift_relative_velocity=True)
    table = m.parameter_table([5.0, 10.0, 0.0], [0.0, 0.5, np.inf])
    assert table.shape == (3, wk.N_PARAMS)
    assert table.dtype == np.float64 and table.flags.c_contiguous
    assert np.all(table == table[0])
    row = table[0]
    assert row[wk.P_CD_STEADY] == m.cd_steady
    assert row[wk.P_CL_STEADY] == m.cl_steady
    assert row[wk.P_CM] == m.cm
    assert row[wk.P_DCD] == m.drag_excess
    assert row[wk.P_DCL] == m.lift_excess
    assert row[wk.P_LAMBDA_D] == m.drag_relaxation
    assert row[wk.P_LAMBDA_L] == m.lift_relaxation
    assert row[wk.P_WAKE_RATIO] == m.wake_ratio
    assert row[wk.P_LAMBDA_W] == m.wake_decay
    assert row[wk.P_LIFT_RELATIVE] == 1.0
    assert row[wk.P_REVERSAL_TOL] == m.reversal_tolerance
    assert row[wk.P_SLACK_EXPONENT] == m.slack_exponent
    assert row[wk.P_SLACK_THRESHOLD] == m.slack_threshold
    assert row[wk.P_ONSET] == m.wake_onset
    off = m.without_wake().parameters()
    assert off[wk.P_DCD] == off[wk.P_DCL] == off[wk.P_WAKE_RATIO] == 0.0
    assert off[wk.P_CD_STEADY] == m.cd_steady


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"cd_steady": -0.1}, "cd_steady"),
        ({"cl_steady": 6.0}, "cl_steady"),
        ({"cm": 0.5}, "cm"),
        ({"cm": 11.0}, "cm"),
        ({"drag_excess": -2.0}, "drag_excess"),
        ({"lift_excess": 25.0}, "lift_excess"),
        ({"drag_relaxation": 0.0}, "drag_relaxation"),
        ({"lift_relaxation": -1.0}, "lift_relaxation"),
        ({"wake_decay": float("nan")}, "wake_decay"),
        ({"wake_ratio": 3.0}, "wake_ratio"),
        ({"added_mass": -0.1}, "added_mass"),
        ({"reversal_tolerance": 0.5}, "reversal_tolerance"),
        ({"slack_exponent": -1.0}, "slack_exponent"),
        ({"slack_threshold": 1.0}, "slack_threshold"),
        ({"wake_onset": 11.0}, "wake_onset"),
        ({"wake": 1}, "wake"),
        ({"lift_relative_velocity": "yes"}, "lift_relative_velocity"),
        ({"model_id": 0}, "model_id"),
    ],
)
def test_bad_inputs_named(kwargs, field):
    with pytest.raises(InputError, match=field):
        WakeModel(**kwargs)


@pytest.mark.parametrize(
    ("k", "m"),
    [([-1.0], [0.0]), ([np.nan], [0.0]), ([5.0], [-0.1]), ([5.0, 6.0], [0.0])],
)
def test_parameter_table_bad_k_m(k, m):
    with pytest.raises(InputError):
        WakeModel().parameter_table(k, m)


def test_first_call_is_morison_with_steady_coefficients():
    """A zero state at any t: no history, the forces of steady coefficients (hand values)."""
    m = WakeModel()
    p = m.parameters()
    s, out = _eval(p, np.zeros(N_FORCE_STATE), 123.4, 0.6, 0.2, 0.3, ydot=0.1)
    urel = 0.6 + 0.3 - 0.1
    fy = 0.5 * RHO * D * 1.0 * urel * abs(urel) + 0.25 * math.pi * RHO * D * D * 3.29 * 0.2
    assert out[FO_FY] == pytest.approx(fy, rel=1e-14)
    assert out[FO_DFY_DYD] == pytest.approx(-RHO * D * 1.0 * urel, rel=1e-14)
    assert out[FO_FZ] == pytest.approx(0.5 * RHO * D * 0.9 * 0.9**2, rel=1e-14)
    assert out[FO_DFZ_DYD] == 0.0
    assert s[wk.S_STARTED] == 1.0
    assert s[wk.S_T] == 123.4
    assert s[wk.S_DIST] == 0.0
    assert s[wk.S_SIGN] == 1.0
    assert s[wk.S_WAKE0] == 0.0
    assert s[wk.S_RELAX] == 0.0
    assert np.all(s[wk.N_USED_STATE :] == 0.0)


def test_reversal_hand_values():
    """One step across a reversal: crossing time, stroke, wake and coefficients by hand."""
    m = WakeModel()
    p = m.parameters()
    old = np.zeros(N_FORCE_STATE)
    old[wk.S_STARTED] = 1.0
    old[wk.S_T] = 10.0
    old[wk.S_Q] = 0.2
    old[wk.S_SIGN] = 1.0
    old[wk.S_DIST] = 3.0
    old[wk.S_PEAK] = 1.5
    old_copy = old.copy()
    s, out = _eval(p, old, 10.5, -0.6, -1.0, 0.0)
    assert np.array_equal(old, old_copy)  # state_old never written
    f = 0.2 / 0.8  # zero crossing at a quarter of the step
    assert s[wk.S_SIGN] == -1.0
    assert s[wk.S_N_REVERSALS] == 1.0
    assert s[wk.S_PREV_STROKE] == pytest.approx(3.0 + 0.5 * 0.2 * f * 0.5)
    dist = 0.5 * 0.6 * (1.0 - f) * 0.5
    assert s[wk.S_DIST] == pytest.approx(dist)
    assert s[wk.S_PEAK] == 0.6
    assert s[wk.S_WAKE0] == pytest.approx(m.wake_ratio * 1.5)
    assert s[wk.S_RELAX] == 1.0
    assert s[wk.S_STRENGTH] == 1.0
    # the old segment had no wake and no excess: nothing to blend out
    assert s[wk.S_W_END] == s[wk.S_CD_END] == s[wk.S_CL_END] == 0.0
    x = dist / D  # 0.225 D, inside the onset distance 0.3 D: φ = 3ξ² − 2ξ³, ξ = 0.75
    assert m.wake_onset == 0.3
    phi = 0.75**2 * (3.0 - 2.0 * 0.75)
    cd = m.cd_steady + phi * m.drag_excess * math.exp(-x / m.drag_relaxation)
    cl = m.cl_steady + phi * m.lift_excess * math.exp(-x / m.lift_relaxation)
    ue = -0.6 - phi * m.wake_ratio * 1.5 * math.exp(-x / m.wake_decay)
    fy = 0.5 * RHO * D * cd * ue * abs(ue) - 0.25 * math.pi * RHO * D * D * m.cm
    assert out[FO_FY] == pytest.approx(fy, rel=1e-13)
    assert out[FO_FZ] == pytest.approx(0.5 * RHO * D * cl * ue * ue, rel=1e-13)


def test_old_wake_is_blended_out_after_a_reversal():
    """Right after a reversal U_e and C_D continue the old segment's values (no jump)."""
    m = WakeModel()
    p = m.parameters()
    old = np.zeros(N_FORCE_STATE)
    old[[wk.S_STARTED, wk.S_T, wk.S_Q, wk.S_SIGN, wk.S_DIST, wk.S_PEAK, wk.S_TROUGH]] = [
        1.0, 10.0, 0.2, 1.0, 3.0, 1.5, 0.2,
    ]  # fmt: skip
    old[[wk.S_WAKE0, wk.S_RELAX, wk.S_STRENGTH]] = [0.4, 1.0, 1.0]
    s, _ = _eval(p, old, 10.5, -0.6, -1.0, 0.0)
    x_end = s[wk.S_PREV_STROKE] / D
    assert s[wk.S_W_END] == pytest.approx(0.4 * math.exp(-x_end / m.wake_decay), rel=1e-14)
    ex_d = m.drag_excess * math.exp(-x_end / m.drag_relaxation)
    assert s[wk.S_CD_END] == pytest.approx(ex_d, rel=1e-14)
    # at the instant of the reversal (s = 0) the new segment's forces equal the old one's
    s0 = s.copy()
    s0[wk.S_DIST] = 0.0
    w, exd, exl = wk._history_terms(
        p, -1.0, s0[wk.S_WAKE0], 1.0, s0[wk.S_W_END], s0[wk.S_CD_END], s0[wk.S_CL_END], 0.0
    )
    assert (w, exd, exl) == (s[wk.S_W_END], s[wk.S_CD_END], s[wk.S_CL_END])


def test_slack_hand_values():
    """|q| passes a minimum without a reversal (following current): a slack by hand."""
    m = WakeModel()
    p = m.parameters()
    old = np.zeros(N_FORCE_STATE)
    # segment peak 3.0, trough 1.0 at the previous sample (q_old = 1.0), now rising
    old[[wk.S_STARTED, wk.S_T, wk.S_Q, wk.S_SIGN, wk.S_DIST, wk.S_PEAK, wk.S_TROUGH]] = [
        1.0, 0.0, 1.0, 1.0, 40.0, 3.0, 1.0,
    ]  # fmt: skip
    s, _ = _eval(p, old, 0.1, 1.1, 1.0, 0.0)
    r = (3.0 - 1.0) / 3.0
    g = ((r - m.slack_threshold) / (1.0 - m.slack_threshold)) ** m.slack_exponent
    assert s[wk.S_STRENGTH] == pytest.approx(g, rel=1e-14)
    assert s[wk.S_SIGN] == 1.0 and s[wk.S_N_REVERSALS] == 0.0
    assert s[wk.S_PREV_STROKE] == 40.0
    assert s[wk.S_WAKE0] == pytest.approx(m.wake_ratio * (3.0 - 1.0) * g, rel=1e-14)
    assert s[wk.S_RELAX] == 0.0  # a slack makes a wake, no coefficient excess
    assert s[wk.S_DIST] == pytest.approx(0.5 * (1.0 + 1.1) * 0.1, rel=1e-14)
    assert s[wk.S_PEAK] == s[wk.S_TROUGH] == 1.1
    # a shallow minimum (depth below r_0) is no slack
    old[wk.S_TROUGH] = old[wk.S_Q] = 2.5
    s, _ = _eval(p, old, 0.1, 2.6, 1.0, 0.0)
    assert s[wk.S_STRENGTH] == 0.0 and s[wk.S_DIST] == pytest.approx(40.0 + 0.255)
    # a slack weaker than what is left of the present wake does not restart the history
    old[wk.S_TROUGH] = old[wk.S_Q] = 1.0
    old[wk.S_STRENGTH] = 1.0
    old[wk.S_DIST] = 0.1
    s, _ = _eval(p, old, 0.1, 1.1, 1.0, 0.0)
    assert s[wk.S_STRENGTH] == 1.0 and s[wk.S_DIST] == pytest.approx(0.1 + 0.105)


def test_sign_change_below_tolerance_is_not_a_reversal():
    p = WakeModel(reversal_tolerance=0.01).parameters()
    old = np.zeros(N_FORCE_STATE)
    old[[wk.S_STARTED, wk.S_T, wk.S_Q, wk.S_SIGN, wk.S_PEAK]] = [1.0, 0.0, 0.5, 1.0, 1.0]
    s, _ = _eval(p, old, 0.1, -0.005, 0.0, 0.0)  # |q| = 0.5 % of the peak
    assert s[wk.S_SIGN] == 1.0
    assert s[wk.S_N_REVERSALS] == 0.0
    s, _ = _eval(p, old, 0.1, -0.02, 0.0, 0.0)
    assert s[wk.S_SIGN] == -1.0
    assert s[wk.S_N_REVERSALS] == 1.0


def test_lift_relative_velocity_option():
    p = WakeModel(lift_relative_velocity=True).parameters()
    _, out = _eval(p, np.zeros(N_FORCE_STATE), 0.0, 1.0, 0.0, 0.0, ydot=0.4)
    assert out[FO_FZ] == pytest.approx(0.5 * RHO * D * 0.9 * 0.6**2, rel=1e-14)
    assert out[FO_DFZ_DYD] == pytest.approx(-RHO * D * 0.9 * 0.6, rel=1e-14)


def test_calibration_inputs_named():
    from onbottom.hydro.wake_calibration import (
        compare_with_tables,
        fit_wake_model,
        regular_peak_coefficients,
    )

    m = WakeModel()
    with pytest.raises(InputError, match="k_star"):
        regular_peak_coefficients(m, 0.0, 0.0)
    with pytest.raises(InputError, match="m_star"):
        regular_peak_coefficients(m, 5.0, -1.0)
    with pytest.raises(InputError, match="n_cycles"):
        regular_peak_coefficients(m, 5.0, 0.0, n_cycles=1)
    with pytest.raises(InputError, match="steps_per_cycle"):
        regular_peak_coefficients(m, 5.0, 0.0, steps_per_cycle=8)
    with pytest.raises(InputError, match="tables"):
        compare_with_tables(m, [5.0, 10.0], [0.0], np.ones((2, 2)), np.ones((2, 2)))
    with pytest.raises(InputError, match="free"):
        fit_wake_model([5.0], [0.0], np.ones((1, 1)), np.ones((1, 1)), free=("name",))


def test_regular_protocol_steady_limits():
    """Wake off, K* large: C_Y → C_D∞ (+ the inertia's small share), C_Z → C_L∞ exactly."""
    from onbottom.hydro.wake_calibration import regular_peak_coefficients

    m = WakeModel().without_wake()
    cy, cz = regular_peak_coefficients(m, [1000.0, 1000.0], [0.0, 10.0])
    # F_Y peak of C_D sin² + a cos with a = π² C_M / K: C_D + a²/(4 C_D) for a < 2 C_D
    a = math.pi**2 * 3.29 / 1000.0
    assert cy[0] == pytest.approx(1.0 + a * a / 4.0, rel=1e-5)
    assert cz[0] == pytest.approx(0.9, rel=1e-9)
    assert cz[1] == pytest.approx(0.9, rel=1e-9)
