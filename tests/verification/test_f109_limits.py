"""Verification of the F109 design layer against limits and identities."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.hydro.design_sea_state import significant_bed_velocity
from onbottom.hydro.flow_synthesis import bed_velocity_record
from onbottom.hydro.spreading import spreading_factor

pytestmark = pytest.mark.verification


def test_shallow_water_limit():
    # kd → 0: G(ω) → √(g/d), so U_s → 2√(g/d)·√M_0(η) = (H_s/2)·√(g/d) (m0 = H_s²/16)
    d, hs = 2.0, 0.5
    us, _ = significant_bed_velocity(hs, 40.0, d)
    assert us == pytest.approx(0.5 * hs * math.sqrt(9.80665 / d), rel=0.01)


def test_deep_water_filters_the_bed_velocity():
    us, tu = significant_bed_velocity(4.0, 8.0, [10.0, 30.0, 100.0, 300.0])
    assert np.all(np.diff(us) < 0.0) and us[-1] < 1e-3 * us[0]
    assert np.all(np.diff(tu) > 0.0)  # deep water keeps only the long waves


def test_spreading_limits():
    assert spreading_factor(1000.0, wave_direction_deg=30.0) == pytest.approx(
        0.5, rel=2e-3
    )  # → long-crested
    # isotropic-like s → 0+: R_D² → ½ for any direction
    assert spreading_factor(1e-9, wave_direction_deg=10.0) == pytest.approx(
        math.sqrt(0.5), rel=1e-6
    )


def test_synthesised_record_has_the_spectral_variance():
    # a non-repeating 3-h random-phase record has standard deviation U_s/2 and a mean
    # zero up-crossing period T_u (to sampling error, a few per cent)
    hs, tp, d, gamma = 3.0, 10.0, 15.0, 2.0
    us, tu = significant_bed_velocity(hs, tp, d, gamma)
    n = math.ceil(5.0 * 10_800.0 / tp)
    t, u, _ = bed_velocity_record(hs, tp, d, gamma, 0, n, 10_800.0, 40)
    assert np.std(u) == pytest.approx(float(us) / 2.0, rel=0.03)
    n_up = np.count_nonzero((u[:-1] < 0) & (u[1:] >= 0))
    assert t[-1] / n_up == pytest.approx(float(tu), rel=0.03)
