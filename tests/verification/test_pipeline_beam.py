"""Verification of the pipeline beam against closed forms (static, membrane, frequencies).

Closed forms: shared/spec/on-bottom-stability.md ("Closed forms for tests"); string limit:
Irvine, *Cable Structures* (1981) §2.2 (shallow parabolic cable, H³ = EA q² L²/24).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg

from onbottom.dynamics.pipeline import _beam_kernel as B
from onbottom.dynamics.pipeline import _pipeline_kernel as K

pytestmark = pytest.mark.verification

EI = 5.0e7  # N·m²
EA = 5.0e9  # N
L = 100.0  # m


def _line(ne, ei=EI, ea=EA, n0=0.0, length=L):
    p = np.zeros((ne, B.N_EL_PROPS))
    p[:, B.EL_L0] = length / ne
    p[:, B.EL_EA] = ea
    p[:, B.EL_EI] = ei
    p[:, B.EL_N0] = n0
    return p


def _uniform_load(ne, q, length=L):
    ell = np.full(ne + 1, length / ne)
    ell[[0, -1]] *= 0.5
    f = np.zeros(3 * (ne + 1))
    f[1::3] = q * ell
    return f


def _static(ne, ends, q, ei=EI, ea=EA, steps=1, length=L):
    props = _line(ne, ei, ea, length=length)
    fixed = np.zeros(3 * (ne + 1))
    for node in (0, ne):
        j = 3 * node
        fixed[j : j + (3 if ends == "fixed" else 2)] = 1.0
    d = np.zeros(fixed.size)
    tol = 1e-7 * q * length / ne  # N
    its = K.static_solve(
        props, fixed, np.zeros(fixed.size), _uniform_load(ne, q, length), d, steps, 60, tol
    )
    assert its >= 0
    return d


@pytest.mark.parametrize(("ends", "factor"), [("fixed", 1.0 / 384.0), ("pinned", 5.0 / 384.0)])
def test_static_uniform_load_matches_closed_form(ends, factor):
    q = 0.05  # N/m → v_max ~ 1 mm on 100 m: membrane tension negligible (< 1e-4)
    d = _static(80, ends, q)
    v_max = d[1::3].max()
    assert v_max == pytest.approx(factor * q * L**4 / EI, rel=2e-3)


def test_static_deflection_converges_with_element_size():
    q = 0.05
    exact = 5.0 / 384.0 * q * L**4 / EI
    errs = [abs(_static(ne, "pinned", q)[1::3].max() - exact) for ne in (5, 10, 20)]
    # lumped nodal loads: second-order convergence (ratio 4 per halving)
    assert errs[1] < errs[0] / 3.0 and errs[2] < errs[1] / 3.0


def test_membrane_large_deflection_tends_to_the_string_limit():
    """Pinned ends held axially, EI ≈ 0: tension from stretching carries q (shallow string)."""
    q = 1000.0
    d = _static(100, "pinned", q, ei=1.0e4, steps=20)
    h = (EA * q * q * L * L / 24.0) ** (1.0 / 3.0)
    v_string = q * L * L / (8.0 * h)
    assert d[1::3].max() == pytest.approx(v_string, rel=0.01)
    # axial force ≈ the string tension H near mid-span
    mom, nax = np.zeros(101), np.zeros(101)
    B.node_section_forces(d, _line(100, 1.0e4, EA), mom, nax)
    assert nax[50] == pytest.approx(h, rel=0.01)


def test_natural_frequencies_of_a_tensioned_pinned_beam():
    """ω_n = (nπ/L)²√(EI/m)·√(1 + T L²/(n²π² EI)) within 0.5 % (lumped mass, 60 elements)."""
    ne = 60
    tension = 2.0e5
    m_lat = 400.0  # kg/m
    props = _line(ne, n0=tension)
    ndof = 3 * (ne + 1)
    d = np.zeros(ndof)
    ab = K.tangent_band(props, np.zeros(ndof), np.zeros(ndof), d)
    kk = np.zeros((ndof, ndof))
    for i in range(ndof):
        for k in range(6):
            if i - k >= 0:
                kk[i, i - k] = kk[i - k, i] = ab[i, k]
    ell = np.full(ne + 1, L / ne)
    ell[[0, -1]] *= 0.5
    mass = np.zeros(ndof)
    mass[0::3] = 300.0 * ell
    mass[1::3] = m_lat * ell
    mass[2::3] = 300.0 * 0.4**2 / 8.0 * ell
    free = np.ones(ndof, dtype=bool)
    free[[0, 1, ndof - 3, ndof - 2]] = False
    w2 = scipy.linalg.eigh(kk[np.ix_(free, free)], np.diag(mass[free]), eigvals_only=True)
    w = np.sqrt(np.sort(w2))
    for n in (1, 2, 3):
        exact = (n * math.pi / L) ** 2 * math.sqrt(EI / m_lat)
        exact *= math.sqrt(1.0 + tension * L * L / (n * n * math.pi**2 * EI))
        assert w[n - 1] == pytest.approx(exact, rel=5e-3)
