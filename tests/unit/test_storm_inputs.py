"""Unit tests of the storm input objects (onbottom.inputs.storm)."""

from __future__ import annotations

import dataclasses
import math

import pytest

from onbottom.errors import InputError
from onbottom.inputs.storm import Current, SeaState, Storm


def test_sea_state_defaults_and_gamma_rule():
    s = SeaState(hs=4.0, tp=10.0)
    assert s.duration_s == 10800.0
    assert s.long_crested
    # φ = 10/2 = 5 → γ = 1 (DNV-RP-C205 §3.5.5.5)
    assert s.peak_enhancement == 1.0
    # φ = 8/2 = 4 → γ = exp(5.75 − 4.6)
    assert SeaState(hs=4.0, tp=8.0).peak_enhancement == pytest.approx(math.exp(1.15))
    assert SeaState(hs=4.0, tp=6.0).peak_enhancement == 5.0
    assert SeaState(hs=4.0, tp=6.0, gamma=3.3).peak_enhancement == 3.3
    assert SeaState(hs=4.0, tp=6.0, spectrum="pierson-moskowitz").peak_enhancement == 1.0


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"hs": 0.0, "tp": 10.0}, "SeaState.hs"),
        ({"hs": 4.0, "tp": -1.0}, "SeaState.tp"),
        ({"hs": 4.0, "tp": 10.0, "gamma": 9.0}, "SeaState.gamma"),
        ({"hs": 4.0, "tp": 10.0, "spectrum": "bretschneider"}, "SeaState.spectrum"),
        ({"hs": 4.0, "tp": 10.0, "spectrum": "pierson-moskowitz", "gamma": 2.0}, "gamma"),
        ({"hs": 4.0, "tp": 10.0, "duration_s": 0.0}, "SeaState.duration_s"),
        ({"hs": 4.0, "tp": 10.0, "direction_deg": 400.0}, "SeaState.direction_deg"),
        ({"hs": 4.0, "tp": 10.0, "spreading_s": -1.0}, "SeaState.spreading_s"),
        ({"hs": float("nan"), "tp": 10.0}, "SeaState.hs"),
    ],
)
def test_sea_state_rejects_bad_input(kwargs, field):
    with pytest.raises(InputError, match=field.replace(".", r"\.")):
        SeaState(**kwargs)


def test_sea_state_is_frozen():
    s = SeaState(hs=4.0, tp=10.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.hs = 5.0  # type: ignore[misc]


def test_standard_storm_is_half_hour_build_up_and_three_hour_peak():
    peak = SeaState(hs=5.0, tp=11.0, duration_s=100.0)
    st = Storm.standard(peak, seed=7)
    assert st.build_up_s == 1800.0
    assert st.decay_s == 0.0
    assert st.stages[0].duration_s == 10800.0
    assert st.duration_s == 12600.0
    assert st.stage_start_times == (1800.0,)
    assert st.seed == 7
    assert st.peak.hs == 5.0
    assert st.with_seed(3).seed == 3


def test_storm_stages_sequence_and_validation():
    a = SeaState(hs=3.0, tp=9.0, duration_s=3600.0)
    b = SeaState(hs=5.0, tp=11.0, duration_s=7200.0)
    st = Storm(stages=[a, b, a], decay_s=600.0)
    assert isinstance(st.stages, tuple)
    assert st.stage_start_times == (0.0, 3600.0, 10800.0)
    assert st.duration_s == 3600.0 + 7200.0 + 3600.0 + 600.0
    assert st.peak is b
    with pytest.raises(InputError, match="Storm.stages"):
        Storm(stages=())
    with pytest.raises(InputError, match=r"Storm.stages\[1\]"):
        Storm(stages=(a, 3.0))
    with pytest.raises(InputError, match="Storm.seed"):
        Storm(stages=(a,), seed=-1)
    with pytest.raises(InputError, match="Storm.seed"):
        Storm(stages=(a,), seed=1.5)
    with pytest.raises(InputError, match="Storm.transition_s"):
        Storm(stages=(a, b), transition_s=5000.0)
    with pytest.raises(InputError, match="peak_hours"):
        Storm.standard(a, peak_hours=0.0)


def test_current_validation():
    c = Current(velocity=0.5)
    assert c.reference_height == 1.0 and c.direction_deg == 90.0 and c.z0 is None
    with pytest.raises(InputError, match="Current.velocity"):
        Current(velocity=-0.1)
    with pytest.raises(InputError, match="Current.z0"):
        Current(velocity=0.5, z0=0.0)
    with pytest.raises(InputError, match="Current.reference_height"):
        Current(velocity=0.5, reference_height=0.0)
