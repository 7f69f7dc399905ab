"""Storm kinematics: spreading R_D, random-phase synthesis, envelope, current, sea-state fit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.hydro.spreading import spreading_factor
from onbottom.hydro.storm_kinematics import (
    current_normal_to_pipe,
    sea_state_for_velocity,
    seabed_velocity_parameters,
    storm_kinematics,
)
from onbottom.inputs.storm import Current, SeaState, Storm


@pytest.mark.parametrize("s", [2.0, 4.0, 8.0, 20.0])
def test_spreading_factor_normal_waves_closed_form(s):
    # waves normal to the pipe: R_D² = E[cos²θ] = (s + 1)/(s + 2) for the cos^s density
    r = spreading_factor(s, wave_direction_deg=90.0)
    assert r == pytest.approx(math.sqrt((s + 1) / (s + 2)), rel=1e-14)


def test_spreading_factor_long_crested_and_symmetry():
    assert spreading_factor(0.0, wave_direction_deg=90.0) == 1.0
    assert spreading_factor(0.0, wave_direction_deg=30.0) == pytest.approx(0.5)
    assert spreading_factor(0.0, wave_direction_deg=0.0) == pytest.approx(0.0, abs=1e-15)
    # the line of the waves only: mirrored directions give bitwise the same R_D
    for s in (0.0, 3.0, 8.0):
        for d in (20.0, 70.0, 90.0):
            ref = spreading_factor(s, wave_direction_deg=d)
            for m in (-d, 180.0 - d, 180.0 + d, 360.0 - d):
                assert spreading_factor(s, wave_direction_deg=m) == ref
    with pytest.raises(InputError):
        spreading_factor(-1.0, wave_direction_deg=90.0)
    with pytest.raises(TypeError):  # the direction is keyword-only: no swapped arguments
        spreading_factor(8.0, 90.0)  # type: ignore[misc]


@pytest.fixture(scope="module")
def kin():
    sea = SeaState(hs=4.0, tp=10.0, gamma=3.3, duration_s=3600.0)
    storm = Storm(stages=(sea,), build_up_s=600.0, seed=5)
    return storm_kinematics(storm, 20.0, diameter=0.5)


def test_synthesis_has_the_spectral_variance(kin):
    p = seabed_velocity_parameters(SeaState(hs=4.0, tp=10.0, gamma=3.3), 20.0)
    peak = kin.time >= 600.0
    us = 2.0 * float(np.std(kin.velocity[peak]))
    # one hour of record: the sample estimate of U_s = 2σ (F109: 2√M_0) is within a few percent
    assert us == pytest.approx(p["significant_velocity"], rel=0.05)
    assert kin.stage_parameters[0]["significant_velocity"] == pytest.approx(
        p["significant_velocity"]
    )


def test_acceleration_is_the_derivative_of_velocity(kin):
    fd = np.gradient(kin.velocity, kin.sample_interval)
    scale = float(np.max(np.abs(kin.acceleration)))
    inner = slice(10, -10)
    assert np.max(np.abs(fd[inner] - kin.acceleration[inner])) < 0.02 * scale


def test_build_up_envelope_and_seed(kin):
    assert kin.velocity[0] == 0.0
    assert kin.duration == 4200.0
    assert kin.time[-1] >= kin.duration
    early = np.abs(kin.velocity[kin.time < 60.0]).max()
    assert early < 0.2 * np.abs(kin.velocity).max()
    sea = SeaState(hs=4.0, tp=10.0, gamma=3.3, duration_s=3600.0)
    again = storm_kinematics(Storm(stages=(sea,), build_up_s=600.0, seed=5), 20.0, diameter=0.5)
    other = storm_kinematics(Storm(stages=(sea,), build_up_s=600.0, seed=6), 20.0, diameter=0.5)
    assert np.array_equal(again.velocity, kin.velocity)
    assert not np.allclose(other.velocity, kin.velocity)


def test_stage_weights_sum_to_one_and_blend():
    a = SeaState(hs=2.0, tp=8.0, duration_s=600.0)
    b = SeaState(hs=4.0, tp=10.0, duration_s=600.0)
    k = storm_kinematics(Storm(stages=(a, b), transition_s=100.0), 20.0, diameter=0.5)
    np.testing.assert_allclose(k.weights.sum(axis=0), 1.0, atol=1e-12)
    t = k.time
    assert np.all(k.weights[0][t < 550.0] == 1.0)
    assert np.all(k.weights[1][t > 650.0] == 1.0)
    mid = np.argmin(np.abs(t - 600.0))
    assert k.weights[0][mid] == pytest.approx(0.5, abs=0.01)


def test_direction_sign_and_current():
    sea90 = SeaState(hs=3.0, tp=9.0, duration_s=300.0, direction_deg=90.0)
    sea270 = SeaState(hs=3.0, tp=9.0, duration_s=300.0, direction_deg=270.0)
    k90 = storm_kinematics(Storm(stages=(sea90,)), 15.0, diameter=0.4)
    k270 = storm_kinematics(Storm(stages=(sea270,)), 15.0, diameter=0.4)
    np.testing.assert_array_equal(k270.velocity, -k90.velocity)
    c = Current(velocity=1.0, reference_height=1.0, z0=1e-5)
    v = current_normal_to_pipe(c, 0.4)
    # F109 Eq 3.3 by hand
    z0, d, zr = 1e-5, 0.4, 1.0
    hand = ((1 + z0 / d) * math.log(d / z0 + 1) - 1) / math.log(zr / z0 + 1)
    assert v == pytest.approx(hand, rel=1e-12)
    c270 = Current(velocity=1.0, direction_deg=270.0, z0=1e-5)
    assert current_normal_to_pipe(c270, 0.4) == pytest.approx(-hand, rel=1e-12)
    assert current_normal_to_pipe(None, 0.4) == 0.0
    with pytest.raises(InputError, match="z0"):
        current_normal_to_pipe(Current(velocity=1.0), 0.4)


def test_sea_state_for_velocity_hits_targets():
    sea, depth = sea_state_for_velocity(0.6, 9.0)
    p = seabed_velocity_parameters(sea, depth)
    assert p["significant_velocity"] == pytest.approx(0.6, rel=1e-3)
    assert p["mean_period"] == pytest.approx(9.0, rel=1e-3)
    assert math.sqrt(depth / 9.80665) / sea.tp == pytest.approx(0.1, rel=1e-9)


def test_bad_inputs():
    sea = SeaState(hs=3.0, tp=9.0, duration_s=300.0)
    with pytest.raises(InputError):
        storm_kinematics(sea, 15.0, diameter=0.4)
    with pytest.raises(InputError, match="depth"):
        storm_kinematics(Storm(stages=(sea,)), -1.0, diameter=0.4)
    with pytest.raises(InputError, match="omega_max_factor"):
        storm_kinematics(Storm(stages=(sea,)), 10.0, diameter=0.4, omega_max_factor=1.0)
