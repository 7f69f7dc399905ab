"""Loose-layer generators of the preparation (hand checks: no overlaps, inside the box,
porosity, the kernel against its plain-Python twin)."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.dem._generation import rsa_positions, rsa_positions_python
from onbottom.dem.config import SM, Preparation
from onbottom.dem.preparation import LOOSE_POROSITY, _lattice, _random_layer, draw_diameters
from onbottom.errors import InputError


def _min_gap(pos: np.ndarray, diam: np.ndarray) -> float:
    r = diam / 2.0
    i, j = np.triu_indices(len(r), 1)
    d = np.hypot(pos[i, 0] - pos[j, 0], pos[i, 1] - pos[j, 1])
    return float(np.min(d - r[i] - r[j]))


def test_rsa_kernel_equals_its_python_twin():
    rng = np.random.default_rng(4)
    diam = np.sort(rng.uniform(0.4e-3, 1.0e-3, 100))[::-1].copy()
    u = rng.random((20_000, 2))
    a, ta = rsa_positions(diam, 0.0, 0.012, 0.001, 0.008, u, 500)
    b, tb = rsa_positions_python(diam, 0.0, 0.012, 0.001, 0.008, u, 500)
    assert ta == tb
    np.testing.assert_array_equal(a, b)
    assert not np.isnan(a).any()


def test_rsa_kernel_reports_a_disk_without_place():
    diam = np.full(3, 1.0e-3)
    u = np.random.default_rng(0).random((1000, 2))
    pos, _ = rsa_positions(diam, 0.0, 1.0e-3, 0.0, 1.0e-3, u, 50)  # room for one disk only
    assert not np.isnan(pos[0]).any()
    assert np.isnan(pos[1:]).all()


@pytest.mark.parametrize("generate", [_random_layer, _lattice])
def test_layers_are_loose_non_overlapping_and_inside(generate):
    diam = draw_diameters(SM, np.random.default_rng(1))[:1500]
    width, base = 0.065, 0.004
    pos = generate(diam, 0.0, width, base, np.random.default_rng(2))
    r = diam / 2.0
    assert _min_gap(pos, diam) >= 0.0
    assert np.all(pos[:, 0] - r >= 0.0) and np.all(pos[:, 0] + r <= width)
    assert np.all(pos[:, 1] - r >= base)
    porosity = 1.0 - np.sum(np.pi * r**2) / (width * (np.max(pos[:, 1] + r) - base))
    if generate is _random_layer:
        # the band's porosity (by construction), measured to the highest disk top
        assert porosity == pytest.approx(LOOSE_POROSITY, abs=0.01)
    else:
        assert porosity > 0.6  # rows 1.05·d_max apart


def test_random_layer_is_isotropic():
    """No preferred direction: the branch vectors of near pairs are as often horizontal as
    vertical (the lattice's are all one or the other)."""
    diam = draw_diameters(SM, np.random.default_rng(5))[:3000]
    pos = _random_layer(diam, 0.0, 0.08, 0.0, np.random.default_rng(6))
    r = diam / 2.0
    i, j = np.triu_indices(len(r), 1)
    dx, dy = pos[j, 0] - pos[i, 0], pos[j, 1] - pos[i, 1]
    near = np.hypot(dx, dy) < r[i] + r[j] + 0.1e-3
    c2 = np.cos(2.0 * np.arctan2(dy[near], dx[near]))  # fabric: <cos 2θ> = 0 if isotropic
    assert near.sum() > 1000
    assert abs(float(np.mean(c2))) < 0.05


def test_layer_generation_is_validated():
    assert Preparation().layer_generation == "lattice"
    with pytest.raises(InputError, match="layer_generation"):
        Preparation(layer_generation="hex")
