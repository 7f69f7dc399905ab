"""A force model's loads on a fixed pipe (hydro/fixed_pipe.py): the Morison model against its
closed form, the kernel against its plain-Python twin (wake model, state carried), and the
cycle peaks of the envelope (the data of the design report's V–H diagram)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom._jit import pure_python
from onbottom.errors import InputError
from onbottom.hydro._fixed_pipe_kernel import fixed_pipe_record
from onbottom.hydro.fixed_pipe import fixed_pipe_envelope, fixed_pipe_loads
from onbottom.hydro.force_model import MorisonLift, parameter_rows
from onbottom.hydro.storm_kinematics import StormKinematics
from onbottom.hydro.wake import WakeModel

D, RHO, VC = 0.4, 1025.0, 0.3


def _flow(n_periods: int = 6, period: float = 10.0, amp: float = 1.2) -> StormKinematics:
    dt = period / 40.0  # the crests fall on samples
    t = dt * np.arange(n_periods * 40 + 1)
    w = 2.0 * math.pi / period
    u, a = amp * np.sin(w * t), amp * w * np.cos(w * t)
    return StormKinematics(
        sample_interval=dt, velocity=u, acceleration=a, current=VC, duration=float(t[-1]),
        weights=np.ones((1, t.size)),
        stage_parameters=[{"significant_velocity": amp, "mean_period": period,
                           "spreading_factor": 1.0}],
    )  # fmt: skip


def test_morison_on_a_fixed_pipe_is_its_closed_form():
    """ẏ = 0: F_Y = ½ρD C_D (U+V)|U+V| + ρπD²/4 C_M U̇, F_Z = ½ρD C_L (U+V)² (hand formula)."""
    kin = _flow()
    m = MorisonLift(cd=1.1, cm=2.5, cl=0.8)
    t, fy, fz = fixed_pipe_loads(m, kin, diameter=D, density=RHO)
    q = kin.velocity + VC
    inertia = RHO * math.pi * D**2 / 4.0 * 2.5 * kin.acceleration
    hand_y = 0.5 * RHO * D * 1.1 * q * np.abs(q) + inertia
    np.testing.assert_allclose(fy, hand_y, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(fz, 0.5 * RHO * D * 0.8 * q**2, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(t, kin.sample_interval * np.arange(q.size))


def test_kernel_equals_its_plain_python_twin_with_state():
    kin = _flow(n_periods=3)
    m = WakeModel()
    rows = parameter_rows(m, kin.weights, kin.stage_parameters, kin.current, D)
    args = (rows, kin.sample_interval, kin.velocity, kin.acceleration, VC, D, RHO)
    fy, fz = np.empty_like(kin.velocity), np.empty_like(kin.velocity)
    _t, fy_jit, fz_jit = fixed_pipe_loads(m, kin, diameter=D, density=RHO)
    pure_python(fixed_pipe_record)(m.model_id, *args, fy, fz)
    np.testing.assert_allclose(fy_jit, fy, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(fz_jit, fz, rtol=1e-12, atol=1e-9)
    # the wake model carries state: its loads differ from the Morison form's in the same flow
    _t, fy_m, _fz = fixed_pipe_loads(MorisonLift(), kin, diameter=D, density=RHO)
    assert np.max(np.abs(fy_jit - fy_m)) > 1e-3 * np.max(np.abs(fy_m))


def test_envelope_takes_one_peak_per_cycle_with_the_reductions():
    kin = _flow(n_periods=6)
    m = MorisonLift(cd=1.0, cm=0.0, cl=1.0, added_mass=0.0)
    env = fixed_pipe_envelope(m, kin, diameter=D, submerged_weight=800.0, density=RHO,
                              r_y=0.5, r_z=0.7)  # fmt: skip
    # up-crossings of U at t = T, 2T, ..., 5T (U = 0 at t = 0 is no crossing): 4 complete cycles
    assert env.n_cycles == 4
    peak = 0.5 * RHO * D * (1.2 + VC) ** 2  # drag alone: largest at the crest, U = 1.2 m/s
    np.testing.assert_allclose(env.horizontal, 0.5 * peak, rtol=1e-9)
    np.testing.assert_allclose(env.lift, 0.7 * peak, rtol=1e-9)  # lift at the same instant
    np.testing.assert_allclose(env.vertical, 800.0 - env.lift)


def test_bad_inputs_are_named():
    with pytest.raises(InputError, match="force_model"):
        fixed_pipe_loads(object(), _flow(), diameter=D, density=RHO)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="r_y"):
        fixed_pipe_envelope(MorisonLift(), _flow(), diameter=D, submerged_weight=1.0,
                            density=RHO, r_y=1.5)  # fmt: skip
