"""Unit tests: which region-2 increments add to the work of V&S Eq 6 (``work_counting``).

Hand-made displacement paths through the kernel (the soil contract sees u and V only). The
load direction is read from the soil reaction R = F_f + F_r, which equilibrates the applied
load while the pipe is at rest: a reversal is a change of sign of R beyond ±θ·μV
(docs/theory/verley_sotberg.md, "Which increments count").
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from onbottom import InputError, Pipe, Sand
from onbottom.soil import _verley_sotberg_kernel as k
from onbottom.soil._path import drive_path
from onbottom.soil.base import OUT_R, OUT_SIZE, OUT_WORK, OUT_Z
from onbottom.soil.verley_sotberg import WORK_COUNTINGS, VerleySotberg

KN = 1.0e3


def _model(**kw):
    # D = 0.5 m: y1 = 0.01 m, y2 = 0.25 m, y3 = 0.5 m; δ = 0.5 mm
    pipe = Pipe(outer_diameter=0.5, submerged_weight=2.0 * KN)
    return VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10.0 * KN), **kw)


def _seg(a, b, n=400):
    return np.linspace(a, b, n + 1)[1:]


def _drive(m, u, v=2.0 * KN, state=None):
    u = np.asarray(u, dtype=float)
    h = np.zeros((u.size, OUT_SIZE))
    s0 = m.initial_state() if state is None else state
    s = drive_path(m.model_id, m.packed_parameters(), s0, u, np.full(u.size, v), h)
    return h, s


def test_default_is_load_reversal_and_names_are_validated():
    m = _model()
    assert m.work_counting == "load_reversal"
    assert m.reversal_fraction == 0.5
    assert set(WORK_COUNTINGS) == {
        "load_reversal",
        "load_reversal_drift",
        "load_reversal_swept",
        "load_reversal_side",
        "any_region2",
        "swept_ground",
        "two_sided",
    }
    with pytest.raises(InputError, match="work_counting"):
        _model(work_counting="cyclic")
    with pytest.raises(InputError, match="reversal_fraction"):
        _model(reversal_fraction=0.0)


def test_one_way_push_buys_no_penetration():
    """Monotonic push to 0.9·y2: the first reading digs in, every other reading does not."""
    u = _seg(0.0, 0.9 * 0.25, 2000)
    z_i = _model().initial_penetration
    for c in WORK_COUNTINGS:
        h, s = _drive(_model(work_counting=c), u)
        if c == "any_region2":
            assert h[-1, OUT_Z] > 1.5 * z_i
        else:
            assert h[-1, OUT_WORK] == 0.0, c
            assert h[-1, OUT_Z] == z_i, c
        assert s[k.S_GATE] == 0.0  # R stayed positive: no load reversal


def test_reversal_in_region_1_opens_the_gate_then_first_excursion_counts():
    """0 -> +y1/2 -> -y1/2 (R changes sign: reversal) -> 0.8·y2: all of region 2 counts."""
    y1 = 0.01
    u = np.concatenate([_seg(0.0, 0.5 * y1), _seg(0.5 * y1, -0.5 * y1), _seg(-0.5 * y1, 0.2)])
    h_any, _ = _drive(_model(work_counting="any_region2"), u)
    for c in ("load_reversal", "load_reversal_drift", "load_reversal_swept", "load_reversal_side"):
        h, s = _drive(_model(work_counting=c), u)
        assert s[k.S_GATE] == 1.0
        assert h[-1, OUT_WORK] == pytest.approx(h_any[-1, OUT_WORK], rel=1e-12)
        assert h[-1, OUT_Z] == pytest.approx(h_any[-1, OUT_Z], rel=1e-12)
        assert h[-1, OUT_Z] > _model().initial_penetration


def test_berm_pushing_back_is_not_a_load_reversal():
    """A small step back from the berm flips the friction but not the reaction R."""
    m = _model(friction_coefficient=0.05)  # μV = 100 N/m, below the berm's passive force
    v = 2.0 * KN
    h, s = _drive(m, _seg(0.0, 0.2, 2000), v)
    assert h[-1, OUT_R] > m.friction_coefficient * v
    h2, s2 = _drive(m, _seg(0.2, 0.2 - 4.0 * m.delta, 40), v, state=s)
    assert h2[-1, 1] < 0.0  # OUT_FRICTION: friction reversed (slid back by 4δ)
    assert h2[-1, OUT_R] > -m.reversal_fraction * m.friction_coefficient * v
    assert s2[k.S_GATE] == 0.0 and s2[k.S_LOAD_DIR] == 1.0
    # back to the centre: the berm is left behind, R = -μV: the load has reversed
    h3, s3 = _drive(m, _seg(0.2 - 4.0 * m.delta, 0.0, 400), v, state=s2)
    assert h3[-1, OUT_R] == pytest.approx(-m.friction_coefficient * v)
    assert s3[k.S_GATE] == 1.0 and s3[k.S_LOAD_DIR] == -1.0


def test_drift_rule_counts_ground_within_the_turns_plus_the_longest_swing():
    """After a turn in region 2, an advance onto new ground counts only up to the turning
    amplitude plus the longest half-cycle (load_reversal_drift), up to the turning amplitude
    (load_reversal_swept), or all of it (load_reversal, the default)."""
    y1, y2 = 0.01, 0.25
    a, b = 0.06, 0.04  # turn in region 2 at s = a, back to b, then push on to 0.95·y2
    opening = np.concatenate([_seg(0.0, 0.5 * y1), _seg(0.5 * y1, -0.5 * y1)])
    u = np.concatenate([opening, _seg(-0.5 * y1, a), _seg(a, b), _seg(b, 0.95 * y2, 4000)])
    n_push = 4000
    longest = a + 0.5 * y1  # the swing from -y1/2 up to a
    reach = {"load_reversal_drift": a + longest, "load_reversal_swept": a, "load_reversal": y2}
    for c, r in reach.items():
        h, s = _drive(_model(work_counting=c), u)
        assert s[k.S_TURNED2] == 1.0
        assert s[k.S_TP_POS] == pytest.approx(a)
        uu = u[-n_push:]
        w = h[-n_push:, OUT_WORK]
        grows = np.diff(w) > 0.0
        # the work grows while the push is inside the counted reach, and not beyond it
        assert grows[(uu[1:] > b + 1e-3) & (uu[1:] < r - 1e-3)].all(), c
        assert not grows[uu[1:] > r + 1e-3].any(), c


def test_side_rule_tells_walking_from_a_swing_through_the_centre():
    """load_reversal_side: after a turn on the same side (walking) new ground does not count;
    after a swing from the other side (cyclic, growing amplitude) it does."""
    y1 = 0.01
    opening = np.concatenate([_seg(0.0, 0.5 * y1), _seg(0.5 * y1, -0.5 * y1)])
    n = 4000
    walk = np.concatenate([opening, _seg(-0.5 * y1, 0.06), _seg(0.06, 0.04), _seg(0.04, 0.2, n)])
    swing = np.concatenate([opening, _seg(-0.5 * y1, 0.06), _seg(0.06, -0.2, n)])
    m = _model(work_counting="load_reversal_side")
    h, s = _drive(m, walk)
    uu, grows = walk[-n:], np.diff(h[-n:, OUT_WORK]) > 0.0
    assert s[k.S_TP_LAST] == pytest.approx(0.04)
    assert grows[(uu[1:] > 0.041) & (uu[1:] < 0.059)].all()
    assert not grows[uu[1:] > 0.061].any()
    h, s = _drive(m, swing)
    uu, grows = swing[-n:], np.diff(h[-n:, OUT_WORK]) > 0.0
    assert s[k.S_TP_LAST] == pytest.approx(0.06)  # last turn on the other side
    assert grows[(uu[1:] < -0.011) & (uu[1:] > -0.199)].all()


def test_new_trough_closes_the_gate():
    """After y3 and a reversal, the new trough has no turning points and a closed gate."""
    y1 = 0.01
    m = _model()
    u = np.concatenate(
        [_seg(0.0, 0.5 * y1), _seg(0.5 * y1, -0.5 * y1), _seg(-0.5 * y1, 0.6), _seg(0.6, 0.59)]
    )
    h, s = _drive(m, u)
    assert s[k.S_PHASE] == k.PHASE_TROUGH and s[k.S_Y0] == pytest.approx(0.6)
    assert s[k.S_TP_POS] == 0.0 and s[k.S_TURNED2] == 0.0 and s[k.S_HALF] == 0.0
    # stepping back reverses R (friction -μV, no passive yet): the new trough's own reversal
    assert s[k.S_GATE] == 1.0
    h2, s2 = _drive(m, _seg(0.59, 0.59 + 0.2, 2000), state=s)
    assert s2[k.S_GATE] == 1.0 and h2[-1, OUT_Z] >= h[-1, OUT_Z]


def test_swept_ground_and_two_sided_bounds():
    """swept_ground: |s| within the largest turn; two_sided: within the smaller side's turn."""
    u = np.concatenate([_seg(0.0, 0.1), _seg(0.1, -0.05), _seg(-0.05, 0.2, 2000)])
    n_push = 2000
    for c, r in (("swept_ground", 0.1), ("two_sided", 0.05)):
        h, _ = _drive(_model(work_counting=c), u)
        uu = u[-n_push:]
        grows = np.diff(h[-n_push:, OUT_WORK]) > 0.0
        assert grows[(uu[1:] > 0.011) & (uu[1:] < r - 1e-3)].all(), c
        assert not grows[uu[1:] > r + 1e-3].any(), c


def test_parameters_record_the_reading():
    m = dataclasses.replace(_model(), work_counting="swept_ground", reversal_fraction=0.25)
    p = m.parameters()
    assert p["work_counting"] == "swept_ground" and p["reversal_fraction"] == 0.25
    packed = m.packed_parameters()
    assert packed[k.P_WORK_COUNTING] == k.COUNT_SWEPT_GROUND
    assert packed[k.P_REVERSAL] == 0.25
