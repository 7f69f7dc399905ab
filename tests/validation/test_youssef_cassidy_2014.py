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
from onbottom.study.centrifuge_bands import band_cases

pytestmark = pytest.mark.validation

# The Table 1 cycle counts are validated against *bands* over every choice the paper leaves
# open (tests/validation/test_centrifuge_bands.py): a ±1-cycle check of the default run alone
# held for Inclined 1 and 3 only with sine cycles on the paper's time axis (triangle cycles
# put Inclined 1 at +1.05, prototype time put Inclined 3 at -2.02), so it is not asserted.
#
# The Fig. 9 behaviour is asserted for the defaults and for each unstated choice varied alone
# (the one-at-a-time part of the Inclined 1 band). It holds for all of them except the
# passive-only work integrand: penetration then grows by only 12 % before breakout (test:
# 0.065 -> 0.09 m, +38 %) and the last cycle starts at |u| = 0.74 m (paper: about 0.4 m), so
# Fig. 9 disfavours that reading of Eq 6 -- a reason for the default (total resistance).


def _variant_id(case):
    default = next(c for c in _CASES if _n_changed(c) == 0)
    diff = [f"{k}={case[k]}" for k in _KEYS if case[k] != default[k]]
    return "default" if not diff else ",".join(diff)


_KEYS = ("shape", "time_basis", "gamma_kn", "b_placement", "max_penetration_law", "work_integrand")
_CASES = band_cases("Inclined 1", reduced=True)


def _n_changed(case):
    return sum(
        case[k] != v
        for k, v in {
            "shape": "sine",
            "time_basis": "paper",
            "gamma_kn": 7.5,
            "b_placement": "outside",
            "max_penetration_law": "reconstruction",
            "work_integrand": "total",
        }.items()
    )


def _disfavoured(res):
    """True for the variant Fig. 9 disfavours (its checks must then fail: asserted)."""
    return res.data.attrs["work_integrand_variant"] == "passive"


@pytest.fixture(scope="module", params=_CASES, ids=[_variant_id(c) for c in _CASES])
def inclined_1(request):
    c = request.param
    res = run_centrifuge_test(
        "Inclined 1",
        after_limit="runaway_end",
        shape=c["shape"],
        time_basis=c["time_basis"],
        gamma=c["gamma_kn"] * 1e3,
        soil_options={k: c[k] for k in ("b_placement", "max_penetration_law", "work_integrand")},
    )
    res.data.attrs["work_integrand_variant"] = c["work_integrand"]
    return res


def test_fig9_penetration_grows_under_small_cyclic_motion(inclined_1):
    if _disfavoured(inclined_1):
        with pytest.raises(AssertionError):
            _penetration_grows(inclined_1)
    else:
        _penetration_grows(inclined_1)


def _penetration_grows(inclined_1):
    d = inclined_1.data
    u, w, reg, h = (d[k].values for k in ("y", "z", "region", "H"))
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
    half = 0.5 * float(d.attrs["cycle_period"])
    assert len({int(np.floor(t / half)) for t in t_grow}) >= 2
    assert (h_grow > 0).any() and (h_grow < 0).any()


def test_fig9_pipe_rises_after_sweeping_its_berm(inclined_1):
    d = inclined_1.data
    w, reg = d["z"].values, d["region"].values
    in3 = reg == 3  # breakout region: penetration falls from z2 to z3
    assert in3.any()
    assert w[in3][-1] < w[in3][0]
    assert w[-1] < 0.75 * np.max(w)


def test_fig9_runaway_in_the_last_cycle(inclined_1):
    if _disfavoured(inclined_1):
        with pytest.raises(AssertionError):
            _runaway_in_last_cycle(inclined_1)
    else:
        _runaway_in_last_cycle(inclined_1)


def _runaway_in_last_cycle(inclined_1):
    d = inclined_1.data
    c = inclined_1.cycles_to_limit
    t_start_last = np.floor(c) * float(d.attrs["cycle_period"])
    u_start = np.interp(t_start_last, d["time"].values, d["y"].values)
    # paper: "the pipe displaced horizontally from approximately 0.4 m to 3.0 m in the last cycle"
    assert abs(u_start) < 0.6
    assert inclined_1.summary["final_displacement"] > TESTS["Inclined 1"].displacement_limit
