"""F109 load reductions and their numba kernels against hand calculations."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro import _load_kernels as K
from onbottom.hydro.reductions import penetration_reduction, trench_reduction


def test_penetration_reduction_hand_values():
    r_y, r_z = penetration_reduction(np.array([0.0, 0.05, 0.1, 0.2, 0.5]))
    np.testing.assert_allclose(r_y, [1.0, 0.93, 0.86, 0.72, 0.3])
    np.testing.assert_allclose(r_z, [1.0, 1.0, 1.0, 0.87, 0.48])


def test_penetration_reduction_kernels_match_twin():
    z = np.linspace(0.0, 0.5, 51)
    r_y, r_z = penetration_reduction(z)
    for zi, ry, rz in zip(z, r_y, r_z, strict=True):
        assert K.penetration_reduction_y(zi) == pytest.approx(ry, abs=1e-15)
        assert K.penetration_reduction_z(zi) == pytest.approx(rz, abs=1e-15)


def test_penetration_reduction_range():
    with pytest.raises(InputError, match="z_over_d"):
        penetration_reduction(-0.1)
    with pytest.warns(OutOfRangeWarning, match="z_p/D"):
        r_y, r_z = penetration_reduction(0.8)
    assert float(r_y) == 0.3
    assert float(r_z) == pytest.approx(0.09)


def test_trench_reduction_hand_values():
    r_y, r_z = trench_reduction(0.5, 21.0)
    assert r_y == pytest.approx(1.0 - 0.18 * 16.0**0.25 * 0.5**0.42)
    assert r_z == pytest.approx(1.0 - 0.14 * 16.0**0.43 * 0.5**0.46)
    assert trench_reduction(0.0, 30.0) == (1.0, 1.0)
    with pytest.raises(InputError, match="wall_angle_deg"):
        trench_reduction(0.5, 60.0)
