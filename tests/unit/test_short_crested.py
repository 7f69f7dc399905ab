"""Short-crested single-summation kinematics along a pipeline."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.errors import InputError
from onbottom.hydro.short_crested import pipeline_kinematics, regular_node_kinematics
from onbottom.hydro.spreading import directions_cos_s, spreading_factor
from onbottom.hydro.storm_kinematics import seabed_velocity_parameters
from onbottom.inputs.storm import SeaState, Storm

SEA = SeaState(hs=4.0, tp=10.0, duration_s=3600.0)


def test_directions_follow_the_cos_s_density():
    u = np.random.default_rng(0).uniform(size=200_000)
    th = directions_cos_s(u, 90.0, 4.0) - math.pi / 2
    # E[cos²δ] = (s + 1)/(s + 2) for D ∝ cos^s δ
    assert np.mean(np.cos(th) ** 2) == pytest.approx(5.0 / 6.0, rel=3e-3)
    assert np.all(np.abs(th) <= math.pi / 2)
    np.testing.assert_array_equal(directions_cos_s(u[:5], 60.0, 0.0), math.radians(60.0))


def test_long_crested_normal_waves_are_in_phase_along_the_line():
    storm = Storm(stages=(SEA.with_duration(600.0),), seed=3)
    kin = pipeline_kinematics(storm, 20.0, np.array([0.0, 50.0, 500.0]))
    np.testing.assert_allclose(kin.velocity[:, 1], kin.velocity[:, 0], atol=1e-6)
    np.testing.assert_allclose(kin.velocity[:, 2], kin.velocity[:, 0], atol=1e-6)


@pytest.mark.parametrize(("direction", "s"), [(90.0, 0.0), (90.0, 4.0), (60.0, 8.0)])
def test_variance_tends_to_rd_squared_m0(direction, s):
    """Ergodic single summation: var(u_n) over a long record ≈ (R_D U_s/2)², R_D of F109."""
    sea = SeaState(hs=4.0, tp=10.0, duration_s=4 * 3600.0, direction_deg=direction, spreading_s=s)
    kin = pipeline_kinematics(Storm(stages=(sea,), seed=1), 20.0, np.array([0.0, 300.0]))
    normal = SeaState(hs=4.0, tp=10.0)  # long-crested, normal: U_s without reduction
    us = seabed_velocity_parameters(normal, 20.0)["significant_velocity"]
    rd = float(spreading_factor(s, wave_direction_deg=direction))
    var = np.var(kin.velocity.astype(float), axis=0)
    np.testing.assert_allclose(var, (rd * us / 2.0) ** 2, rtol=0.08)


def test_short_crested_sea_is_coherent_over_short_distances_only():
    sea = SeaState(hs=4.0, tp=10.0, duration_s=3 * 3600.0, spreading_s=2.0)
    x = np.array([0.0, 5.0, 400.0])
    u = pipeline_kinematics(Storm(stages=(sea,), seed=2), 20.0, x).velocity.astype(float)
    c = np.corrcoef(u.T)
    assert c[0, 1] > 0.9
    assert abs(c[0, 2]) < 0.3


def test_acceleration_is_the_time_derivative():
    storm = Storm(stages=(SEA.with_duration(300.0),), seed=0, build_up_s=60.0)
    kin = pipeline_kinematics(storm, 20.0, np.array([0.0, 100.0]), sample_interval=0.05)
    u = kin.velocity.astype(float)
    dudt = np.gradient(u, kin.dt, axis=0)
    a = kin.acceleration.astype(float)
    err = np.abs(dudt[5:-5] - a[5:-5]).max()
    assert err < 0.02 * np.abs(a).max()


def test_memory_is_float32_and_blocked():
    storm = Storm(stages=(SEA.with_duration(600.0),), seed=0)
    kin = pipeline_kinematics(storm, 20.0, np.linspace(0, 1000, 130), block_nodes=16)
    assert kin.velocity.dtype == np.float32
    assert kin.nbytes == 2 * 4 * kin.velocity.size


def test_regular_kinematics_and_errors():
    kin = regular_node_kinematics(3, 10.0, 0.1, 1.0, 5.0, x=np.array([0, 1, 2.0]), wavelength=4.0)
    assert kin.velocity.shape == (101, 3)
    assert kin.velocity[0, 1] == pytest.approx(math.sin(-math.pi / 2), abs=1e-6)
    with pytest.raises(InputError):
        pipeline_kinematics("storm", 20.0, np.zeros(2))  # type: ignore[arg-type]
