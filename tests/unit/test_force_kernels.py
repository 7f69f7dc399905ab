"""The stateful force-model kernel contract (hydro/_force_dispatch) on the Morison kernel."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from onbottom.hydro._force_contract import (
    FO_DFY_DYD,
    FO_DFZ_DYD,
    FO_FY,
    FO_FZ,
    FO_SIZE,
    N_FORCE_STATE,
)
from onbottom.hydro._force_dispatch import FORCE_MORISON, force_step
from onbottom.hydro._morison_kernel import (
    N_PARAMS,
    P_CD,
    P_CL,
    P_CM,
    P_LIFT_REL,
    morison_kernel,
    morison_twin,
)
from onbottom.hydro.forces import MorisonCoefficients, horizontal_force, lift_force

D, RHO = 0.4, 1025.0
FLOWS = list(
    itertools.product(
        (-1.3, -0.2, 0.0, 0.7, 2.1), (-0.9, 0.0, 0.4), (-0.5, 0.0, 0.3), (-0.6, 0.0, 0.25)
    )
)


def _params(cd=0.7, cm=3.29, cl=0.9, rel=0.0):
    p = np.zeros(N_PARAMS)
    p[P_CD], p[P_CM], p[P_CL], p[P_LIFT_REL] = cd, cm, cl, rel
    return p


def _call(fn, p, u, a, vc, yd, state=None):
    s_old = np.zeros(N_FORCE_STATE) if state is None else state
    s_new = np.zeros(N_FORCE_STATE)
    out = np.full(FO_SIZE, np.nan)
    fn(p, s_old, 12.5, u, a, vc, yd, D, RHO, s_new, out)
    return out, s_new


@pytest.mark.parametrize("rel", [0.0, 1.0])
def test_kernel_matches_twin_to_round_off(rel):
    p = _params(rel=rel)
    for u, a, vc, yd in FLOWS:
        k, _ = _call(morison_kernel, p, u, a, vc, yd)
        t, _ = _call(morison_twin, p, u, a, vc, yd)
        assert np.all(np.isfinite(k))  # rule 2: every out slot written; rule 4: finite
        np.testing.assert_allclose(k, t, rtol=1e-14, atol=1e-10)


def test_kernel_matches_force_formulas_at_rest():
    """At ẏ = 0 the kernel equals hydro.forces (F109 §3.4 Morison and lift, r = 1)."""
    c = MorisonCoefficients(drag=0.7, inertia=3.29, lift=0.9)
    for u, a, vc, _yd in FLOWS:
        k, _ = _call(morison_kernel, _params(), u, a, vc, 0.0)
        assert k[FO_FY] == pytest.approx(
            float(horizontal_force(u, a, vc, D, c, density=RHO)), rel=1e-13, abs=1e-10
        )
        assert k[FO_FZ] == pytest.approx(
            float(lift_force(u, vc, D, c, density=RHO)), rel=1e-13, abs=1e-10
        )


@pytest.mark.parametrize("rel", [0.0, 1.0])
def test_derivatives_match_finite_difference(rel):
    p = _params(rel=rel)
    h = 1e-6
    for u, a, vc, yd in FLOWS:
        k, _ = _call(morison_kernel, p, u, a, vc, yd)
        if abs(u + vc - yd) < 10 * h:
            continue  # |U + V − ẏ| has a kink at 0
        kp, _ = _call(morison_kernel, p, u, a, vc, yd + h)
        km, _ = _call(morison_kernel, p, u, a, vc, yd - h)
        assert k[FO_DFY_DYD] <= 0.0
        for f, df in ((FO_FY, FO_DFY_DYD), (FO_FZ, FO_DFZ_DYD)):
            fd = (kp[f] - km[f]) / (2 * h)
            assert k[df] == pytest.approx(fd, rel=1e-6, abs=1e-5)


@pytest.mark.parametrize("rel", [0.0, 1.0])
def test_mirror_symmetry_exact(rel):
    p = _params(rel=rel)
    for u, a, vc, yd in FLOWS:
        k, _ = _call(morison_kernel, p, u, a, vc, yd)
        m, _ = _call(morison_kernel, p, -u, -a, -vc, -yd)
        assert m[FO_FY] == -k[FO_FY]
        assert m[FO_FZ] == k[FO_FZ]
        assert m[FO_DFY_DYD] == k[FO_DFY_DYD]


def test_state_old_untouched_and_dispatch_identical():
    p = _params(rel=1.0)
    s_old = np.linspace(1.0, 2.0, N_FORCE_STATE)  # not a Morison state: must be ignored
    keep = s_old.copy()
    for u, a, vc, yd in FLOWS:
        k, s_new = _call(morison_kernel, p, u, a, vc, yd, state=s_old)
        d = np.full(FO_SIZE, np.nan)
        force_step(FORCE_MORISON, p, s_old, 12.5, u, a, vc, yd, D, RHO, s_new, d)
        assert np.array_equal(k, d)
        assert np.array_equal(s_old, keep)
        assert np.array_equal(s_new, np.zeros(N_FORCE_STATE))  # stateless: slots unused


def test_unknown_model_id_gives_nan():
    out = np.zeros(FO_SIZE)
    force_step(99, _params(), np.zeros(N_FORCE_STATE), 0.0, 1.0, 0.0, 0.0, 0.0, D, RHO,
               np.zeros(N_FORCE_STATE), out)  # fmt: skip
    assert all(math.isnan(x) for x in out)


def test_relative_velocity_drag_vanishes_when_pipe_moves_with_flow():
    out, _ = _call(morison_kernel, _params(cd=1.0, rel=1.0), 1.0, 0.0, 0.5, 1.5)
    assert out[FO_FY] == 0.0 and out[FO_DFY_DYD] == 0.0 and out[FO_FZ] == 0.0
    out, _ = _call(morison_kernel, _params(), -0.5, 0.0, 0.5, 0.3)
    assert out[FO_FZ] == 0.0  # lift on U + V without relative velocity
    out, _ = _call(morison_kernel, _params(cl=0.9), 1.0, 0.0, 0.0, 0.0)
    assert out[FO_FZ] == pytest.approx(0.5 * RHO * D * 0.9)
