"""Validation against Youssef & Cassidy (2014): Table 1 cycle counts and Fig. 9 behaviour.

Tolerance: the cycles to reach the displacement limit within ±1 load cycle of Table 1, with the
paper's calibrated Table 2 parameters and our documented assumptions (γ' = 7.5 kN/m³, sine
cycles, paper time axis, docs/validation/youssef_cassidy_2014.md). Nothing is tuned here.
"""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dynamics.centrifuge import TESTS, run_centrifuge_test

pytestmark = pytest.mark.validation

_INCLINED_2_REASON = (
    "model reaches the limit in cycle 13 (12.30 cycles) instead of 13.75: on the 30° path the "
    "friction-only sliding load μV_i/(1 + μ/tan α) = 2.82 kN/m is below the 3.0 kN/m amplitude "
    "of cycle 12, and the passive resistance the calcareous model builds once the pipe slides "
    "(A = 0.25, z ≈ 0.15 m: about 0.8 kN/m) cannot hold 3.25 kN/m in cycle 13 (a friction-only "
    "run gives the same 12.30). The test pipe probably held because it had embedded and built "
    "passive resistance during the earlier small cycles, which V&S's rigid–plastic friction "
    "(no motion below μV) does not produce; see docs/validation/youssef_cassidy_2014.md"
)


@pytest.mark.parametrize(
    "name",
    [
        "Inclined 1",
        pytest.param("Inclined 2", marks=pytest.mark.xfail(strict=True, reason=_INCLINED_2_REASON)),
        "Inclined 3",
    ],
)
def test_cycles_to_displacement_limit_within_one_cycle(name):
    res = run_centrifuge_test(name, parameters="table2")
    assert res.success and res.cycles_to_limit is not None
    assert abs(res.cycles_to_limit - TESTS[name].cycles_used) <= 1.0, res.cycles_to_limit


@pytest.fixture(scope="module")
def inclined_1():
    return run_centrifuge_test("Inclined 1", after_limit="runaway_end")


def test_fig9_penetration_grows_under_small_cyclic_motion(inclined_1):
    d = inclined_1.data
    u, w, reg, h = (d[k].values for k in ("u", "w", "region", "H"))
    pre = slice(0, int(np.argmax(reg >= 3)))  # before the first breakout (past y2 = 0.25 D)
    # penetration only grows while the pipe stays in its trough (|u| < 0.25 m) ...
    assert np.max(np.abs(u[pre])) < 0.25
    assert np.all(np.diff(w[pre]) >= -1e-12)
    assert w[pre][-1] > 1.3 * w[0]
    # ... and it grows in more than one half-cycle of H (steps with the load reversals)
    n = pre.stop
    grows = np.diff(w[:n]) > 1e-7
    t_grow = d["time"].values[1:n][grows]
    h_grow = h[1:n][grows]
    assert len({int(np.floor(t / 20.0)) for t in t_grow}) >= 2
    assert (h_grow > 0).any() and (h_grow < 0).any()


def test_fig9_pipe_rises_after_sweeping_its_berm(inclined_1):
    d = inclined_1.data
    w, reg = d["w"].values, d["region"].values
    in3 = reg == 3  # breakout region: penetration falls from z2 to z3
    assert in3.any()
    assert w[in3][-1] < w[in3][0]
    assert w[-1] < 0.75 * np.max(w)


def test_fig9_runaway_in_the_last_cycle(inclined_1):
    d = inclined_1.data
    c = inclined_1.cycles_to_limit
    t_start_last = np.floor(c) * 40.0
    u_start = np.interp(t_start_last, d["time"].values, d["u"].values)
    # paper: "the pipe displaced horizontally from approximately 0.4 m to 3.0 m in the last cycle"
    assert abs(u_start) < 0.6
    assert inclined_1.summary["final_displacement"] > TESTS["Inclined 1"].displacement_limit
