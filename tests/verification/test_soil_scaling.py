"""Verification: centrifuge scaling of the trough models (model at N·g vs prototype).

Model scale (N = 50): lengths and displacements D/N, unit weight γ'·N, force per unit length
V/N, stresses (s_u) unchanged. The same displacement path must give identical z/D, F/(γ'D²)
and E/(γ'D³) (docs/conventions.md, centrifuge scaling).
"""

from __future__ import annotations

import numpy as np
import pytest

from onbottom.soil._path import drive_path
from onbottom.soil.base import OUT_PASSIVE, OUT_R, OUT_SIZE, OUT_WORK, OUT_Z
from onbottom.soil.verley_lund import VerleyLund
from onbottom.soil.verley_sotberg import VerleySotberg

N = 50.0
pytestmark = pytest.mark.verification


def _path(d):
    """Cyclic path of growing amplitude (0.05D → 1.5D) then a return: visits all regions."""
    t = np.linspace(0.0, 12.0, 6001)[1:]
    return d * (0.05 + 0.12 * t) * np.sin(2.0 * np.pi * t)


def _drive(model, u, v):
    h = np.zeros((u.size, OUT_SIZE))
    drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h


def _vs(d, gamma, w):
    return VerleySotberg(
        outer_diameter=d,
        submerged_unit_weight=gamma,
        friction_coefficient=0.6,
        installation_load=w,
        A=0.25,
        B=0.35,
        C=0.98,
        region_limits_over_d=(0.01, 0.25, 0.75),
    )


def test_verley_sotberg_scale_invariance():
    d, gamma, w, v0 = 1.0, 7.5e3, 42.98e3, 10.52e3
    proto = _vs(d, gamma, w)
    model = _vs(d / N, gamma * N, w / N)
    u = _path(d)
    v = v0 * (1.0 + 0.2 * np.cos(np.linspace(0.0, 40.0, u.size)))
    hp = _drive(proto, u, v)
    hm = _drive(model, u / N, v / N)
    assert np.ptp(hp[:, OUT_Z]) > 0.01 * d  # penetration did change along the path
    for h, dd, g in ((hp, d, gamma), (hm, d / N, gamma * N)):
        h[:, OUT_Z] /= dd
        h[:, [OUT_R, OUT_PASSIVE]] /= g * dd**2
        h[:, OUT_WORK] /= g * dd**3
    cols = [OUT_Z, OUT_R, OUT_PASSIVE, OUT_WORK]
    np.testing.assert_allclose(hm[:, cols], hp[:, cols], rtol=1e-9, atol=1e-12)


def test_verley_lund_scale_invariance():
    d, su, gs, w = 0.8, 4.0e3, 16.0e3, 3.0e3
    kw = {"friction_coefficient": 0.2, "undrained_shear_strength": su}
    proto = VerleyLund(outer_diameter=d, unit_weight=gs, installation_load=w, **kw)
    model = VerleyLund(outer_diameter=d / N, unit_weight=gs * N, installation_load=w / N, **kw)
    u = _path(d)
    v = np.full(u.size, w)
    hp = _drive(proto, u, v)
    hm = _drive(model, u / N, v / N)
    for h, dd in ((hp, d), (hm, d / N)):
        h[:, OUT_Z] /= dd
        h[:, [OUT_R, OUT_PASSIVE]] /= su * dd
    np.testing.assert_allclose(
        hm[:, [OUT_Z, OUT_R, OUT_PASSIVE]],
        hp[:, [OUT_Z, OUT_R, OUT_PASSIVE]],
        rtol=1e-9,
        atol=1e-12,
    )
