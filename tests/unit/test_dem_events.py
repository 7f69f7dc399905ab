"""Online softening detector (event snapshots) on synthetic V–w records."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dem.events import SofteningDetector
from onbottom.dem.summary import binned_resistance, softening_episodes
from onbottom.errors import InputError


def _sawtooth() -> tuple[np.ndarray, np.ndarray]:
    """Rising curve (+2 per bin) with drops of 10 %, 3 % and 20 % at known bins; 10 records per
    bin."""
    step = 0.005
    means = []
    v = 100.0
    for k in range(60):
        if k in (10, 11):  # drop 10 % (two bins down), peak at bin 9, trough at bin 11
            v *= 0.95 if k == 10 else 0.947
        elif k == 25:  # 3 %: below the 5 % criterion
            v *= 0.97
        elif k in (50, 51, 52):  # 20 %, lowest at bin 52, no recovery before the end
            v *= 0.93
        else:
            v += 2.0
        means.append(v)
    w = (np.arange(600) + 0.5) * step / 10
    rec = np.repeat(means, 10)
    # noise of zero mean in each bin: the bin means are exactly the saw-tooth
    rec = rec + np.tile([1.0, -1.0], 300) * 3.0
    return w, rec


def _stream(w, v, det):
    actions = []
    for a, b in zip(w, v, strict=True):
        actions += det.push(a, b)
    actions += det.close_bin()
    actions += [(a, det.bin) for a in det.finish()]
    return actions


def test_sawtooth_exact_events():
    w, v = _sawtooth()
    det = SofteningDetector(step=0.005, drop_fraction=0.05)
    actions = _stream(w, v, det)
    eps = np.array(det.episodes)
    assert eps.shape == (2, 4)  # the 3 % drop does not count
    np.testing.assert_allclose(eps[:, 0], [9.5 * 0.005, 49.5 * 0.005])  # peaks (bin centres)
    np.testing.assert_allclose(eps[:, 1], [11.5 * 0.005, 52.5 * 0.005])  # troughs
    confirms = [k for a, k in actions if a == "confirm"]
    ends = [k for a, k in actions if a == "end"]
    assert confirms == [11, 50]  # 10 %: confirmed in the 2nd bin down; 20 %: in the 1st
    # bin 9 = 120, bin 11 = 107.96: bin 18 (121.96) is the first back above the peak; the
    # second episode ends with the record
    assert ends == [18, 59]
    np.testing.assert_allclose(eps[0, 2:], [120.0, 120.0 * 0.95 * 0.947])


def test_detector_matches_the_summary_definition():
    rng = np.random.default_rng(3)
    w = np.linspace(0.0, 0.5, 4000)
    v = 1e3 * (w + 0.05 * np.sin(60 * w)) + rng.normal(0, 8.0, w.size)
    det = SofteningDetector(step=0.005, drop_fraction=0.03)
    _stream(w, v, det)
    c, mean, _, _ = binned_resistance(w, v, 0.005)
    ref = softening_episodes(c, mean, 0.03)
    assert len(ref) >= 3
    got = [tuple(e) for e in det.episodes]
    want = [(e.w_peak, e.w_trough, e.v_peak, e.v_trough) for e in ref]
    np.testing.assert_allclose(got, want, rtol=1e-12)


def test_state_round_trip_mid_record():
    import json

    w, v = _sawtooth()
    full = SofteningDetector()
    a_full = _stream(w, v, full)
    half = SofteningDetector()
    a = []
    for x, y in zip(w[:215], v[:215], strict=True):  # stops inside the first drop
        a += half.push(x, y)
    again = SofteningDetector.from_state(json.loads(json.dumps(half.state())))
    for x, y in zip(w[215:], v[215:], strict=True):
        a += again.push(x, y)
    a += again.close_bin()
    a += [(x, again.bin) for x in again.finish()]
    assert a == a_full
    assert again.episodes == full.episodes


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"step": 0.0}, "event_step"),
        ({"step": float("nan")}, "event_step"),
        ({"drop_fraction": 0.0}, "event_drop_fraction"),
        ({"drop_fraction": 1.0}, "event_drop_fraction"),
    ],
)
def test_bad_settings_are_named(kwargs, field):
    with pytest.raises(InputError, match=field):
        SofteningDetector(**kwargs)
