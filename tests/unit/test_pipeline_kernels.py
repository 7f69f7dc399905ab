"""Unit tests of the pipeline FE kernels: banded LDLᵀ, corotational element, Python twins."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics.pipeline import _banded as BD
from onbottom.dynamics.pipeline import _beam_kernel as B
from onbottom.dynamics.pipeline import _pipeline_kernel as K


def _band_to_dense(ab):
    n, w1 = ab.shape
    a = np.zeros((n, n))
    for i in range(n):
        for k in range(w1):
            if i - k >= 0:
                a[i, i - k] = a[i - k, i] = ab[i, k]
    return a


def _random_band(n, w, rng, spd=True):
    ab = rng.normal(size=(n, w + 1))
    ab[:, 0] = (8.0 if spd else 0.5) * w + rng.uniform(0, 1, n)
    if not spd:
        ab[::3, 0] *= -1.0
    for i in range(n):
        for k in range(w + 1):
            if i - k < 0:
                ab[i, k] = 0.0
    return ab


@pytest.mark.parametrize("spd", [True, False])
def test_banded_ldl_solves_like_dense(spd):
    rng = np.random.default_rng(1)
    n, w = 40, 5
    ab = _random_band(n, w, rng, spd)
    a = _band_to_dense(ab)
    b = rng.normal(size=n)
    x_ref = np.linalg.solve(a, b)
    for factor, solve in ((BD.ldl_factor, BD.ldl_solve), (BD.ldl_factor_py, BD.ldl_solve_py)):
        f = ab.copy()
        neg = factor(f)
        assert neg >= 0
        assert (neg == 0) == spd
        x = b.copy()
        solve(f, x)
        np.testing.assert_allclose(x, x_ref, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("n", [6, 11, 30])
def test_banded_fixed_width_path_equals_the_general_one(n):
    """The unrolled path of half-bandwidth 5 does the general loop's operations in its order:
    the same band padded with a zero diagonal (w = 6, general path) gives the same factor and
    solution bit for bit."""
    rng = np.random.default_rng(7)
    ab = _random_band(n, BD.W_FIXED, rng, spd=False)
    wide = np.hstack([ab, np.zeros((n, 1))])
    f5, f6 = ab.copy(), wide.copy()
    assert BD.ldl_factor(f5) == BD.ldl_factor(f6)
    np.testing.assert_array_equal(f5, f6[:, : BD.W_FIXED + 1])
    b = rng.normal(size=n)
    x5, x6 = b.copy(), b.copy()
    BD.ldl_solve(f5, x5)
    BD.ldl_solve(f6, x6)
    np.testing.assert_array_equal(x5, x6)


def test_banded_zero_pivot_reported():
    ab = np.zeros((3, 6))
    ab[:, 0] = [1.0, 0.0, 1.0]
    assert BD.ldl_factor(ab) == -1


def _props(l0=2.0, ea=5e9, ei=5e7, n0=0.0, ne=1):
    p = np.zeros((ne, B.N_EL_PROPS))
    p[:, B.EL_L0] = l0
    p[:, B.EL_EA] = ea
    p[:, B.EL_EI] = ei
    p[:, B.EL_N0] = n0
    return p


@pytest.mark.parametrize("n0", [0.0, -2e5, 3e5])
def test_closed_form_tangent_matches_the_b_matrix_form(n0):
    """The expanded closed form equals Bᵀ D B + N z zᵀ/L + (M₁ + M₂)(r zᵀ + z rᵀ)/L²."""
    props = _props(n0=n0)
    rng = np.random.default_rng(5)
    for _ in range(5):
        d = rng.normal(scale=0.3, size=6)
        f1, f2 = np.zeros(6), np.zeros(6)
        k1, k2 = np.zeros((6, 6)), np.zeros((6, 6))
        B.element_force_tangent(d, 0, props, f1, k1, True)
        B.element_force_tangent_ref(d, 0, props, f2, k2, True)
        np.testing.assert_allclose(k1, k2, rtol=1e-12, atol=1e-12 * np.abs(k2).max())
        np.testing.assert_allclose(f1, f2, rtol=1e-12, atol=1e-12 * np.abs(f2).max())


@pytest.mark.parametrize("n0", [0.0, -2e5, 3e5])
def test_element_tangent_is_the_derivative_of_the_force(n0):
    """Consistent tangent: K·δ equals the central difference of f (large rotation state)."""
    props = _props(n0=n0)
    d = np.array([0.01, 0.3, 0.2, -0.02, 0.9, 0.35])
    fe = np.zeros(6)
    ke = np.zeros((6, 6))
    B.element_force_tangent(d, 0, props, fe, ke, True)
    h = 1e-7
    kfd = np.zeros((6, 6))
    for q in range(6):
        dp, dm = d.copy(), d.copy()
        dp[q] += h
        dm[q] -= h
        fp, fm = np.zeros(6), np.zeros(6)
        B.element_force_tangent(dp, 0, props, fp, ke * 0, False)
        B.element_force_tangent(dm, 0, props, fm, ke * 0, False)
        kfd[:, q] = (fp - fm) / (2 * h)
    np.testing.assert_allclose(ke, kfd, rtol=1e-5, atol=1e-5 * np.abs(ke).max())
    np.testing.assert_allclose(ke, ke.T, rtol=1e-12, atol=1e-6)


def test_element_force_is_the_gradient_of_the_energy():
    props = _props(n0=-1e5)
    d = np.array([0.0, 0.1, 0.05, 0.001, 0.25, -0.02])
    fe = np.zeros(6)
    B.element_force_tangent(d, 0, props, fe, np.zeros((6, 6)), False)
    h = 1e-7
    for q in range(6):
        dp, dm = d.copy(), d.copy()
        dp[q] += h
        dm[q] -= h
        g = (B.element_energy(dp, 0, props) - B.element_energy(dm, 0, props)) / (2 * h)
        assert g == pytest.approx(fe[q], rel=1e-5, abs=1e-3)


def test_twins_match_kernels():
    rng = np.random.default_rng(3)
    props = _props(ne=4, n0=-5e4)
    d = rng.normal(scale=0.05, size=15)
    f1, f2 = np.zeros(15), np.zeros(15)
    a1, a2 = np.zeros((15, 6)), np.zeros((15, 6))
    fe, ke = np.zeros(6), np.zeros((6, 6))
    m1, n1, m2, n2 = (np.zeros(5) for _ in range(4))
    B.assemble_internal(d, props, f1, a1, True, fe, ke, m1, n1)
    B.assemble_internal_py(d, props, f2, a2, True, fe.copy(), ke.copy(), m2, n2)
    np.testing.assert_allclose(m1, m2, rtol=1e-13)
    np.testing.assert_allclose(n1, n2, rtol=1e-13)
    mom, nax = np.zeros(5), np.zeros(5)
    B.node_section_forces(d, props, mom, nax)
    np.testing.assert_allclose(m1, mom, rtol=1e-13)
    np.testing.assert_allclose(n1, nax, rtol=1e-13)
    np.testing.assert_allclose(f1, f2, rtol=1e-13, atol=1e-6)
    np.testing.assert_allclose(a1, a2, rtol=1e-13, atol=1e-3)
    assert B.strain_energy(d, props) == pytest.approx(B.strain_energy_py(d, props), rel=1e-13)


@pytest.mark.parametrize("angle_deg", [0.0, 3.0, -5.0, 30.0, 120.0])
def test_rigid_motion_makes_no_strain(angle_deg):
    """Rigid translation (10 m) plus rotation: no internal force, energy, moment or axial force."""
    ne = 10
    props = _props(ne=ne, l0=2.0)
    x0 = 2.0 * np.arange(ne + 1)
    phi = math.radians(angle_deg)
    xr = 3.0 + x0 * math.cos(phi)
    yr = 10.0 + x0 * math.sin(phi)
    d = np.zeros(3 * (ne + 1))
    d[0::3] = xr - x0
    d[1::3] = yr
    d[2::3] = phi
    f = np.zeros(d.size)
    ab = np.zeros((d.size, 6))
    mm, nn = np.zeros(ne + 1), np.zeros(ne + 1)
    B.assemble_internal(d, props, f, ab, False, np.zeros(6), np.zeros((6, 6)), mm, nn)
    assert np.max(np.abs(f)) < 1e-3  # N (EA = 5e9 N: strains < 1e-12)
    assert abs(B.strain_energy(d, props)) < 1e-9
    mom, nax = np.zeros(ne + 1), np.zeros(ne + 1)
    B.node_section_forces(d, props, mom, nax)
    assert np.max(np.abs(mom)) < 1e-3 and np.max(np.abs(nax)) < 1e-3


def _chord_samples(rng, n):
    """(Δy, Δx) of chords: slopes within the series' range (uniform and log-uniform down to
    1e-12, both signs) and beyond it (steep, vertical, backwards, zero, NaN)."""
    t = np.concatenate([
        rng.uniform(-B.ATAN_T_MAX, B.ATAN_T_MAX, n),
        10.0 ** rng.uniform(-12.0, math.log10(B.ATAN_T_MAX), n) * rng.choice([-1.0, 1.0], n),
        [B.ATAN_T_MAX, -B.ATAN_T_MAX, 0.0, -0.0],
    ])  # fmt: skip
    dx = rng.uniform(0.5, 5.0, t.size)
    dy = t * dx
    beyond = np.array([[1.0, 1.0], [-1.0, 1.0], [1.0, 0.0], [-1.0, 0.0], [0.3, -2.0], [-0.3, -2.0],
                       [0.0, -2.0], [0.0, 0.0], [0.26, 2.0], [np.nan, 2.0]])  # fmt: skip
    return np.concatenate([dy, beyond[:, 0]]), np.concatenate([dx, beyond[:, 1]])


def test_chord_angle_is_atan2_within_an_ulp():
    """The series of :func:`chord_angle` (|Δy/Δx| <= ATAN_T_MAX, Δx > 0) gives the library's
    atan2 within 1 ulp (measured: equal in 80 % of 4·10⁵ samples, 1 ulp apart in the rest);
    beyond that range it is the library's atan2 itself. The twin gives the kernel's bits."""
    rng = np.random.default_rng(11)
    dy, dx = _chord_samples(rng, 20000)
    for y, x in zip(dy, dx, strict=True):
        ref = math.atan2(y, x)
        got = B.chord_angle(y, x)
        assert B.chord_angle_py(y, x) == got or (math.isnan(got) and math.isnan(ref))
        if math.isnan(ref):
            assert math.isnan(got)
        elif x > 0.0 and abs(y / x) <= B.ATAN_T_MAX:
            assert abs(got - ref) <= math.ulp(ref), (y, x, got, ref)
        else:
            assert got == ref


def _element_atan2(d, props):
    """The element's local forces and global force with the library's atan2 for the chord
    angle, as the kernel computed them before the series (reference, plain Python)."""
    l0, ea, ei, n0 = props[0]
    du = d[3] - d[0]
    dy = d[4] - d[1]
    dx = l0 + du
    ln = math.sqrt(dx * dx + dy * dy)
    il = 1.0 / ln
    c, s = dx * il, dy * il
    beta = math.atan2(dy, dx)
    ul = (du * (2.0 * l0 + du) + dy * dy) / (ln + l0)
    t1, t2 = d[2] - beta, d[5] - beta
    il0 = 1.0 / l0
    n = n0 + ea * ul * il0
    m1 = ei * il0 * (4.0 * t1 + 2.0 * t2)
    m2 = ei * il0 * (2.0 * t1 + 4.0 * t2)
    msum = (m1 + m2) * il
    fx, fy = n * c + msum * s, n * s - msum * c
    return np.array([-fx, -fy, m1, fx, fy, m2]), beta, ln, n, m1, m2


def test_element_forces_equal_the_atan2_form():
    """Against the library-atan2 form, over random element states (chords turned by up to
    ±π/2 both ways, local rotations θ − β up to 0.1 rad, stretch up to 1e-3): the forces differ
    only through the chord angle (≤ 1 ulp of β): |Δf| ≤ (6EI/L₀)·2ulp(β)·max(1, 2/L) plus a few
    ulp of the terms, and within 1e-12 of the largest force component."""
    rng = np.random.default_rng(12)
    worst = 0.0
    for k in range(3000):
        props = _props(l0=rng.uniform(0.5, 5.0), ea=5e9, ei=rng.uniform(1e6, 1e8),
                       n0=rng.uniform(-3e5, 3e5))  # fmt: skip
        l0 = props[0, B.EL_L0]
        phi = rng.uniform(-math.pi / 2, math.pi / 2) if k % 3 == 0 else rng.normal(scale=0.03)
        ln = l0 * (1.0 + rng.uniform(-1e-3, 1e-3))
        ua, va = rng.normal(scale=0.5, size=2)
        d = np.array([ua, va, 0.0, ua - l0 + ln * math.cos(phi), va + ln * math.sin(phi), 0.0])
        d[2], d[5] = phi + rng.uniform(-0.1, 0.1, 2) * 10.0 ** rng.uniform(-4, 0)
        ref, beta, ln_, n, m1, m2 = _element_atan2(d, props)
        fe, ke = np.zeros(6), np.zeros((6, 6))
        B.element_force_tangent(d, 0, props, fe, ke, False)
        kb = props[0, B.EL_EI] / l0
        eps = np.finfo(float).eps
        tol = 6.0 * kb * 2.0 * math.ulp(beta) * max(1.0, 2.0 / ln_)
        tol += 8.0 * eps * (abs(n) + abs(m1) + abs(m2) + abs(m1 + m2) / ln_)
        assert np.all(np.abs(fe - ref) <= tol), (d, fe - ref, tol)
        worst = max(worst, float(np.max(np.abs(fe - ref)) / np.max(np.abs(ref))))
    assert worst <= 1e-12


def test_assembly_equals_the_element_form_bit_for_bit():
    """assemble_internal writes each element's force and tangent straight into f and the band:
    the same numbers, bit for bit, as adding :func:`element_force_tangent`'s fe and ke element
    by element (forces only and with the tangent; mixed element properties)."""
    rng = np.random.default_rng(13)
    ne = 12
    props = _props(ne=ne, n0=-5e4)
    props[5:, B.EL_L0] = 1.5
    props[8:, B.EL_EI] = 2e7
    props[10:, B.EL_EA] = 3e9
    for scale in (1e-3, 0.05, 0.6):
        d = rng.normal(scale=scale, size=3 * (ne + 1))
        f0 = rng.normal(size=d.size)
        for want_k in (False, True):
            f, ab = f0.copy(), np.zeros((d.size, 6))
            mom, nax = np.zeros(ne + 1), np.zeros(ne + 1)
            B.assemble_internal(d, props, f, ab, want_k, np.zeros(6), np.zeros((6, 6)), mom, nax)
            f_ref, ab_ref = f0.copy(), np.zeros((d.size, 6))
            mom_ref, nax_ref = np.zeros(ne + 1), np.zeros(ne + 1)
            fe, ke = np.zeros(6), np.zeros((6, 6))
            for e in range(ne):
                n, m1, m2 = B.element_force_tangent(d, e, props, fe, ke, want_k)
                mom_ref[e] -= m1
                mom_ref[e + 1] += m2
                nax_ref[e] += n
                nax_ref[e + 1] += n
                i0 = 3 * e
                f_ref[i0 : i0 + 6] += fe
                if want_k:
                    for p in range(6):
                        for q in range(p + 1):
                            ab_ref[i0 + p, p - q] += ke[p, q]
            mom_ref[1:-1] *= 0.5
            nax_ref[1:-1] *= 0.5
            np.testing.assert_array_equal(f, f_ref)
            np.testing.assert_array_equal(ab, ab_ref)
            np.testing.assert_array_equal(mom, mom_ref)
            np.testing.assert_array_equal(nax, nax_ref)


def test_kinematics_interpolation():
    ku = np.array([[0.0, 1.0], [2.0, 3.0], [4.0, 5.0]], dtype=np.float32)
    ka = -ku
    uk, ak = np.zeros(2), np.zeros(2)
    K.kinematics_at(0.75, ku, ka, 0.0, 0.5, 0, 0, uk, ak)  # nt <= 0: the whole storm
    np.testing.assert_allclose(uk, [3.0, 4.0])
    np.testing.assert_allclose(ak, [-3.0, -4.0])
    K.kinematics_at(10.0, ku, ka, 0.0, 0.5, 0, 3, uk, ak)
    np.testing.assert_allclose(uk, [4.0, 5.0])
    # a window: samples 1 and 2 of a 3-sample storm give the whole array's values
    K.kinematics_at(0.75, ku[1:], ka[1:], 0.0, 0.5, 1, 3, uk, ak)
    np.testing.assert_allclose(uk, [3.0, 4.0])
    K.kinematics_at(10.0, ku[1:], ka[1:], 0.0, 0.5, 1, 3, uk, ak)
    np.testing.assert_allclose(uk, [4.0, 5.0])
    # a time outside the window gives NaN (never another sample's value)
    K.kinematics_at(0.25, ku[1:], ka[1:], 0.0, 0.5, 1, 3, uk, ak)
    assert np.isnan(uk).all() and np.isnan(ak).all()


def test_assemble_tangent_equals_the_full_evaluation():
    """The tangent rebuilt from stored nodal tangents equals evaluate(..., want_k=True)."""
    from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings
    from onbottom.dynamics.pipeline.solver import _kernel_settings
    from onbottom.hydro._force_contract import FO_SIZE, N_FORCE_STATE
    from onbottom.hydro.short_crested import regular_node_kinematics
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand
    from onbottom.soil.base import OUT_SIZE
    from onbottom.soil.verley_sotberg import VerleySotberg

    pipe = Pipe(
        outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=1e4))
    m = PipelineModel(
        pipe=pipe, length=40.0, element_length=4.0, soil=soil, end_conditions="spring",
        end_springs=(1e6, 1e5, 1e4),
    )  # fmt: skip
    a = m.arrays()
    n = m.x.size
    st = _kernel_settings(
        m, regular_node_kinematics(n, 1.0, 0.1, 1.0, 5.0), PipelineSettings(), 0.7
    )
    rng = np.random.default_rng(2)
    d1 = rng.normal(scale=0.01, size=3 * n)
    v1 = rng.normal(scale=0.1, size=3 * n)
    uk, ak = rng.normal(size=n), rng.normal(size=n)
    vc, ry = np.full(n, 450.0), np.full(n, 0.9)
    outs = []
    for full in (True, False):
        p, fh, fs = np.zeros(3 * n), np.zeros(3 * n), np.zeros(3 * n)
        ab = np.zeros((3 * n, 6))
        ktu, ktv = np.zeros(n), np.zeros(n)
        fst = np.zeros((n, N_FORCE_STATE))
        args = (int(a["model_ids"][0]), m.force_model.model_id,
                st, a["props"], a["nodes"], a["fixed"], a["spring"], a["model_ids"], a["sparams"],
                a["sstate"], a["axst"], m.force_model.parameter_table(1.0, 0.0), fst, 0.5,
                d1, v1, uk, ak, vc, ry, 7.0, full, p, fh, fs, ab, a["sstate"].copy(), fst.copy(),
                np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(6), np.zeros((6, 6)),
                np.zeros(OUT_SIZE), np.zeros(FO_SIZE), np.zeros(n), np.zeros(n), ktu,
                ktv)  # fmt: skip
        assert K.evaluate(*args)
        if not full:
            K.assemble_tangent(
                d1, a["props"], a["spring"], ab, np.zeros(6), np.zeros((6, 6)), np.zeros(n),
                np.zeros(n), ktu, ktv, np.zeros(3 * n),
            )  # fmt: skip
        outs.append((ab, p))
    np.testing.assert_array_equal(outs[0][0], outs[1][0])
    np.testing.assert_array_equal(outs[0][1], outs[1][1])
