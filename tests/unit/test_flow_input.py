"""Flow as input (issue 30 item 4): regular Airy wave, measured velocity series, and the
checks that make an empty or inconsistent StormKinematics a named error."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from onbottom.constants import GRAVITY
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro.flow_input import (
    linear_wave_validity,
    read_velocity_series,
    regular_wave_flow,
    velocity_series,
)
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.inputs.storm import Current


# ---- regular wave: hand calculations ---------------------------------------------------------
def test_regular_wave_deep_water_limit_by_hand():
    # kd = ω²d/g ≈ 12.6: tanh(kd) = 1 to 1e-10, k = ω²/g, U_w = πH/(T sinh kd) ≈ 2πH/T·e^{-kd}
    h, t, d = 3.0, 8.0, 200.0
    w = 2.0 * math.pi / t
    k = w * w / GRAVITY
    u_hand = 2.0 * math.pi * h / t * math.exp(-k * d)
    with warnings.catch_warnings():
        warnings.simplefilter("error", OutOfRangeWarning)
        u, a, dts, info = regular_wave_flow(h, t, d, duration=16.0)
    assert info["amplitude"] == pytest.approx(u_hand, rel=1e-9)
    assert info["wave_length"] == pytest.approx(2.0 * math.pi / k, rel=1e-9)
    assert dts == pytest.approx(t / 50.0)
    assert u[0] == pytest.approx(u_hand, rel=1e-9)  # U = U_w cos ωt
    assert a[12] == pytest.approx(-w * u_hand * math.sin(w * 12 * dts), rel=1e-9)


def test_regular_wave_shallow_water_limit_by_hand():
    # kd ≈ 0.047: U_w → (H/2)·√(g/d) with relative error ≈ (kd)²/3 < 1e-3
    h, t, d = 0.002, 60.0, 2.0  # small H: Ursell number < 30, linear theory applies
    with warnings.catch_warnings():
        warnings.simplefilter("error", OutOfRangeWarning)
        info = linear_wave_validity(h, t, d)
        _u, _a, _dts, p = regular_wave_flow(h, t, d, duration=120.0)
    assert info["kd"] < 0.05
    assert p["amplitude"] == pytest.approx(0.5 * h * math.sqrt(GRAVITY / d), rel=1e-3)
    assert info["wave_length"] == pytest.approx(t * math.sqrt(GRAVITY * d), rel=1e-3)


def test_regular_wave_intermediate_depth_against_own_dispersion_solution():
    h, t, d = 2.0, 10.0, 50.0
    w = 2.0 * math.pi / t
    k = w * w / GRAVITY
    for _ in range(200):  # fixed point k = ω²/(g tanh kd), independent of wave_number()
        k = w * w / (GRAVITY * math.tanh(k * d))
    kin = StormKinematics.regular(h, t, d, duration=60.0, diameter=0.5, direction_deg=30.0)
    u_w = math.pi * h / (t * math.sinh(k * d))
    assert kin.stage_parameters[0]["significant_velocity"] == pytest.approx(0.5 * u_w, rel=1e-9)
    assert kin.stage_parameters[0]["mean_period"] == t
    assert kin.velocity[0] == pytest.approx(0.5 * u_w, rel=1e-9)  # sin 30° = 0.5
    assert kin.duration == pytest.approx(60.0)


def test_regular_wave_build_up_and_acceleration_consistent():
    u, a, dts, _ = regular_wave_flow(2.0, 10.0, 30.0, duration=60.0, build_up_s=20.0)
    assert u[0] == 0.0
    # U̇ is the derivative of U (central differences agree to O(Δt²))
    fd = np.gradient(u, dts)
    t = np.arange(u.size) * dts
    smooth = (np.abs(t - 20.0) > 2.0 * dts) & (t > dts) & (t < t[-1] - dts)  # not at the kink
    assert np.max(np.abs(fd[smooth] - a[smooth])) < 0.02 * np.max(np.abs(a))


def test_regular_wave_validity_warning_and_breaking_error():
    with pytest.warns(OutOfRangeWarning, match="Ursell"):
        info = linear_wave_validity(3.0, 14.0, 10.0)
    assert info["ursell"] >= 30.0
    with pytest.raises(InputError, match="Miche"):
        linear_wave_validity(20.0, 8.0, 100.0)  # H/λ ≈ 0.2 > 1/7
    with pytest.raises(InputError, match="height"):
        regular_wave_flow(-1.0, 8.0, 100.0, duration=10.0)


# ---- measured series --------------------------------------------------------------------------
def _csv(tmp_path, text, name="flow.csv"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_series_reader_reads_and_differentiates(tmp_path):
    t = np.arange(0.0, 20.0 + 1e-9, 0.1) + 5.0
    u = 0.8 * np.sin(2 * np.pi * t / 10.0)
    body = "\n".join(f"{ti:.6f},{ui:.12f}" for ti, ui in zip(t, u, strict=True))
    p = _csv(tmp_path, "# a flume record\nt [s], U [m/s]\n" + body + "\n")
    vs = read_velocity_series(p)
    assert vs.t0 == pytest.approx(5.0) and vs.sample_interval == pytest.approx(0.1)
    assert not vs.acceleration_given
    exact = 0.8 * 2 * np.pi / 10.0 * np.cos(2 * np.pi * t / 10.0)
    # second-order central differences: error ≈ (ωΔt)²/6 of the amplitude
    assert np.max(np.abs(vs.acceleration - exact)) < 2e-3 * np.max(np.abs(exact))
    kin = StormKinematics.from_series(p, diameter=0.5)
    sp = kin.stage_parameters[0]
    assert sp["significant_velocity"] == pytest.approx(2 * 0.8 / math.sqrt(2), rel=1e-2)
    assert sp["mean_period"] == pytest.approx(10.0, rel=1e-2)
    assert kin.duration == pytest.approx(20.0)


def test_series_reader_keeps_a_given_acceleration(tmp_path):
    p = _csv(tmp_path, "time [s],velocity [m/s],dU/dt [m/s^2]\n0,0,1\n0.5,0.5,1\n1,1,1\n")
    vs = read_velocity_series(p)
    assert vs.acceleration_given and np.all(vs.acceleration == 1.0)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("t [s],U [m/s]\n0,0\n1,nan\n2,0\n", r"U = nan at line 3"),
        ("t [s],U [m/s]\n0,0\n1,\n2,0\n", r"U = nan at line 3"),
        ("t [s],U [m/s]\n0,0\n1,0\n1,0\n2,0\n", r"t = 1.0 s at line 4 duplicates"),
        ("t [s],U [m/s]\n0,0\n2,0\n1,0\n3,0\n", r"t = 1.0 s at line 4 goes back"),
        ("t [s],U [m/s]\n0,0\n1,0\n2,0\n5,0\n6,0\n", r"2.0 → 5.0 s \(line 5\).*gap"),
        ("t [ms],U [m/s]\n0,0\n1,0\n2,0\n", r"column t unit \[ms\] is invalid"),
        ("t [s],U [knots]\n0,0\n1,0\n2,0\n", r"column U unit \[knots\]"),
        ("t,U [m/s]\n0,0\n1,0\n2,0\n", r"'t' has no unit"),
        ("t [s],V [m/s]\n0,0\n1,0\n2,0\n", r"column 2 'V \[m/s\]' is unknown"),
        ("t [s],dU/dt [m/s^2]\n0,0\n1,0\n2,0\n", r"column U is missing"),
        ("t [s],U [m/s]\n0,0\n1,0\n", r"too few"),
        ("t [s],U [m/s]\n0,0\n1,abc\n2,0\n", r"line 3: U = 'abc' is invalid"),
        ("t [s],U [m/s]\n0,0\n1,0,3\n2,0\n", r"line 3: 3 value"),
        ("", r"empty file"),
    ],
)
def test_series_reader_errors_are_named(tmp_path, text, match):
    p = _csv(tmp_path, text)
    with pytest.raises(InputError, match=match):
        read_velocity_series(p)


def test_series_sampling_tolerance_and_arrays():
    t = np.array([0.0, 1.0, 2.002, 3.0])
    with pytest.raises(InputError, match="sampling_tolerance"):
        velocity_series(t, np.zeros(4))
    vs = velocity_series(t, np.zeros(4), sampling_tolerance=1e-2)
    assert vs.source == "arrays"
    with pytest.raises(InputError, match="column dU/dt has 3 values"):
        velocity_series(t, np.zeros(4), np.zeros(3), sampling_tolerance=1e-2)
    with pytest.raises(InputError, match="series"):
        StormKinematics.from_series(np.zeros(4), diameter=0.5)


def test_series_with_current(tmp_path):
    p = _csv(tmp_path, "t [s],U [m/s]\n0,0.1\n1,0.2\n2,0.1\n3,0.0\n")
    cur = Current(velocity=0.5, reference_height=0.25, z0=1e-5)
    kin = StormKinematics.from_series(p, diameter=0.5, current=cur)
    assert 0.4 < kin.current < 0.5  # mean of the log profile over D below the reference


# ---- StormKinematics consistency ----------------------------------------------------------------
def _kin(**kw):
    n = 11
    base = {
        "sample_interval": 1.0,
        "velocity": np.zeros(n),
        "acceleration": np.zeros(n),
        "current": 0.3,
        "duration": 10.0,
        "weights": np.ones((1, n)),
        "stage_parameters": [{"significant_velocity": 0.0, "mean_period": 1.0}],
    }
    return StormKinematics(**{**base, **kw})


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"stage_parameters": []}, r"stage_parameters = \[\] is invalid"),
        ({"weights": np.ones((2, 11))}, r"weights has shape \(2, 11\)"),
        ({"velocity": np.zeros(0), "acceleration": np.zeros(0)}, r"velocity has shape"),
        ({"acceleration": np.zeros(5)}, r"acceleration has shape"),
        ({"duration": 20.0}, r"duration = 20.0 s is invalid"),
        ({"sample_interval": 0.0}, r"sample_interval = 0.0"),
        ({"velocity": np.r_[np.zeros(10), np.nan]}, r"velocity\[10\] = nan"),
        ({"current": math.inf}, r"current = inf"),
        (
            {"stage_parameters": [{"significant_velocity": 1.0, "mean_period": 0.0}]},
            r"stage_parameters\[0\].mean_period = 0.0",
        ),
        (
            {"stage_parameters": [{"mean_period": 5.0}]},
            r"stage_parameters\[0\].significant_velocity = None",
        ),
    ],
)
def test_empty_or_inconsistent_kinematics_is_a_named_error(kw, match):
    with pytest.raises(InputError, match=match):
        _kin(**kw)


def test_consistent_kinematics_builds():
    assert _kin().time[-1] == 10.0


def test_regular_wave_along_a_pipeline_travels_at_its_angle():
    from onbottom.hydro.short_crested import long_crested_node_kinematics

    kin = StormKinematics.regular(
        2.0, 10.0, 30.0, duration=60.0, diameter=0.5, direction_deg=60.0, build_up_s=10.0
    )
    lam = kin.stage_parameters[0]["wave_length"]
    half = 0.5 * lam / math.cos(math.radians(60.0))  # half a wave length along the line
    x = np.array([0.0, half, 2.0 * half])
    nk = long_crested_node_kinematics(kin, 3, x)
    amp = np.max(np.abs(kin.velocity))
    np.testing.assert_allclose(nk.velocity[:, 0], kin.velocity, atol=1e-6 * amp)
    np.testing.assert_allclose(nk.acceleration[:, 0], kin.acceleration, atol=1e-5 * amp)
    np.testing.assert_allclose(nk.velocity[:, 1], -kin.velocity, atol=1e-5 * amp)  # phase π
    np.testing.assert_allclose(nk.velocity[:, 2], kin.velocity, atol=1e-5 * amp)  # phase 2π
    # normal incidence or a measured record: every node in phase
    normal = StormKinematics.regular(2.0, 10.0, 30.0, duration=20.0, diameter=0.5)
    nk2 = long_crested_node_kinematics(normal, 3, x)
    assert np.all(nk2.velocity == nk2.velocity[:, :1])
