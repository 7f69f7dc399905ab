"""Unit tests: Coulomb friction kernel (hand calculations) and its Python twin."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom import InputError
from onbottom.soil._path import drive_path, drive_path_py
from onbottom.soil.base import OUT_R, OUT_SIZE, OUT_TANGENT
from onbottom.soil.coulomb import CoulombFriction


def _drive(model, u, v):
    h = np.zeros((len(u), OUT_SIZE))
    drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h


def test_elastic_then_sliding_then_reversal():
    m = CoulombFriction(friction_coefficient=0.5, mobilisation_displacement=0.002)
    u = np.array([0.001, 0.0025, 0.010, 0.009, 0.005, 0.0])
    v = np.full(u.size, 1000.0)
    h = _drive(m, u, v)
    # k = μV/δ = 250 000 N/m²; cap = 500 N/m
    np.testing.assert_allclose(h[:, OUT_R], [250.0, 500.0, 500.0, 250.0, -500.0, -500.0])
    np.testing.assert_allclose(h[:, OUT_TANGENT], [250e3, 0.0, 0.0, 250e3, 0.0, 0.0])


def test_lift_off_gives_zero_resistance():
    m = CoulombFriction(friction_coefficient=0.5)
    h = _drive(m, np.array([0.01, 0.02]), np.array([-10.0, 0.0]))
    assert np.all(h[:, OUT_R] == 0.0)


def test_numba_kernel_equals_python_twin_on_random_path():
    rng = np.random.default_rng(7)
    m = CoulombFriction(friction_coefficient=0.7, mobilisation_displacement=0.003)
    u = np.cumsum(rng.normal(0, 0.002, 500))
    v = 800.0 + 300.0 * rng.standard_normal(500)
    h1 = _drive(m, u, v)
    h2 = np.zeros_like(h1)
    drive_path_py(m.python_kernel, m.packed_parameters(), m.initial_state(), u, v, h2)
    np.testing.assert_allclose(h1, h2, rtol=1e-12, atol=1e-9)


def test_bad_parameters():
    with pytest.raises(InputError, match="mobilisation_displacement"):
        CoulombFriction(friction_coefficient=0.5, mobilisation_displacement=0.0)
