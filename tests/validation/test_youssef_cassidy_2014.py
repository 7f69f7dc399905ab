"""Validation against Youssef & Cassidy (2014): Table 1 cycle counts and Fig. 9 behaviour.

The cycle counts of Table 1 are checked against sensitivity bands in
``test_centrifuge_bands.py``; this file checks the qualitative Fig. 9 behaviour of Inclined 1
with the default choices (γ' = 7.5 kN/m³, sine cycles, paper time axis, Table 2 parameters;
docs/validation/youssef_cassidy_2014.md). Nothing is tuned here.
"""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dynamics.centrifuge import TESTS, run_centrifuge_test

pytestmark = pytest.mark.validation

# The Table 1 cycle counts are validated against *bands* over every choice the paper leaves
# open (tests/validation/test_centrifuge_bands.py): a ±1-cycle check of the default run alone
# held for Inclined 1 and 3 only with sine cycles on the paper's time axis (triangle cycles
# put Inclined 1 at +1.05, prototype time put Inclined 3 at -2.02), so it is not asserted.


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
