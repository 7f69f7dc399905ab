"""Corotational 2-node planform beam element in numba (private), with Python twins.

Each node carries (u, v, θ): axial displacement along the initial pipe axis x [m], lateral
displacement y [m] and rotation about the vertical [rad]. Element with nodes a, b, initial
length L₀ (Crisfield, *Non-linear finite element analysis of solids and structures*, vol. 1,
1991, §7.3 "a simple co-rotational element"):

    current chord  Δx = L₀ + u_b − u_a, Δy = v_b − v_a, L = √(Δx² + Δy²), β = atan2(Δy, Δx)
                   (:func:`chord_angle`: a series for chords within ±7.1° of the axis)
    local strains  u_l = L − L₀ = ((u_b − u_a)(2L₀ + u_b − u_a) + Δy²)/(L + L₀)  (no cancellation)
                   θ₁ = θ_a − β, θ₂ = θ_b − β
    local forces   N = N₀ + EA u_l/L₀ (tension +),  M₁ = EI(4θ₁ + 2θ₂)/L₀, M₂ = EI(2θ₁ + 4θ₂)/L₀
    global force   f = N r + M₁(e₃ − z/L) + M₂(e₆ − z/L)
                   r = (−c, −s, 0, c, s, 0), z = (s, −c, 0, −s, c, 0), c = cos β, s = sin β
    tangent        K = Bᵀ D B + N z zᵀ/L + (M₁ + M₂)(r zᵀ + z rᵀ)/L²

B = [r; e₃ − z/L; e₆ − z/L], D = diag(EA/L₀, EI/L₀·[[4, 2], [2, 4]]). A rigid motion leaves
u_l, θ₁, θ₂ unchanged (no strain); lateral deflection stretches the chord (membrane tension).
N₀ is the initial effective axial force (tension positive; pressure and temperature give
N₀ < 0). Its potential is N₀·u_l, so the strain energy of an element is
E = N₀ u_l + ½ EA u_l²/L₀ + ½ [θ₁ θ₂] D_b [θ₁ θ₂]ᵀ.
"""

from __future__ import annotations

import math

from onbottom._jit import jitted_only, njit, pure_python

# element property columns
EL_L0 = 0  # initial length L₀ [m]
EL_EA = 1  # axial stiffness EA [N]
EL_EI = 2  # bending stiffness EI [N·m²]
EL_N0 = 3  # initial effective axial force N₀ [N] (tension +)
N_EL_PROPS = 4

NDOF_NODE = 3
HALF_BAND = 5  # half-bandwidth of the assembled matrix (3 DOFs × 2 nodes − 1)


ATAN_T_MAX = 0.125
"""Largest slope |t| = |Δy/Δx| whose chord angle :func:`chord_angle` takes from its series."""
_A3 = -1.0 / 3.0
_A5 = 1.0 / 5.0
_A7 = -1.0 / 7.0
_A9 = 1.0 / 9.0
_A11 = -1.0 / 11.0
_A13 = 1.0 / 13.0
_A15 = -1.0 / 15.0
_A17 = 1.0 / 17.0


@jitted_only
def chord_angle(dy, dx):
    """Angle β = atan2(Δy, Δx) [rad] of the chord (Δx, Δy) [m].

    A pipe's chords lie within a few degrees of its initial axis. For Δx > 0 and a slope
    t = Δy/Δx with |t| <= :data:`ATAN_T_MAX` (β within ±7.1°), β is the alternating series
    atan t = t − t³/3 + t⁵/5 − … + t¹⁷/17 (Abramowitz & Stegun 1964, Eq. 4.4.42), summed by
    Estrin's scheme in t² (a short dependency chain, where the library's atan2 is a call of
    several times the cost). The truncation error is below the first omitted term,
    |t|¹⁹/19 <= 3e-18·|t| (0.03 ulp); the correction to t is at most t²/3 <= 1/192 of it, so
    the result keeps the rounding of t = Δy/Δx itself: within 1.4 ulp of the exact angle and
    1 ulp of the library's atan2 (tests). Any other chord (steeper, backwards, NaN): the
    library's atan2.
    """
    if dx > 0.0:
        t = dy / dx
        t2 = t * t
        if t2 <= ATAN_T_MAX * ATAN_T_MAX:
            # Estrin's scheme: the pairs and powers in parallel (short dependency chain)
            t4 = t2 * t2
            p = (_A3 + t2 * _A5) + t4 * (_A7 + t2 * _A9)
            q = (_A11 + t2 * _A13) + t4 * (_A15 + t2 * _A17)
            return t + (t * t2) * (p + (t4 * t4) * q)
    return math.atan2(dy, dx)


@njit(cache=True, inline="always")
def chord_kinematics(d, i, l0):
    """Chord of the element whose first DOF is ``i`` (initial length ``l0`` [m]): (L, 1/L,
    c, s, u_l, θ₁, θ₂) — its length, direction cosines, the elongation u_l = (L² − L₀²)/(L + L₀)
    [m] and the end rotations relative to the chord angle β [rad].

    Inlined into its callers' numba IR (:func:`element_local`, :func:`assemble_internal`):
    the element form and the assembly evaluate the same expressions in the same order.
    """
    du = d[i + 3] - d[i]
    dy = d[i + 4] - d[i + 1]
    dx = l0 + du
    ln = math.sqrt(dx * dx + dy * dy)
    il = 1.0 / ln
    c = dx * il
    s = dy * il
    beta = chord_angle(dy, dx)
    ul = (du * (2.0 * l0 + du) + dy * dy) / (ln + l0)
    return ln, il, c, s, ul, d[i + 2] - beta, d[i + 5] - beta


@njit(cache=True, inline="always")
def tangent_blocks(n, msum, il, ka, kb, c, s):
    """Entries of the element tangent's translational node block A (a00, a11, a01) and of
    ∂f_θ/∂(u, v) at node a (tu, tv), from the axial force ``n`` [N], (M₁ + M₂)/L ``msum``
    [N], 1/L ``il`` [1/m], EA/L₀ ``ka`` and EI/L₀ ``kb`` [N/m; N·m] and the chord's cosines.

    A = ka a aᵀ + (N/L + 12kb/L²) b bᵀ + (M₁ + M₂)/L² (a bᵀ + b aᵀ) with a = (c, s),
    b = (−s, c); ∂f_θ/∂(u, v) = −h z, h = 6kb/L: node a (−h s, h c), node b (h s, −h c).
    Inlined into :func:`element_force_tangent` and :func:`assemble_internal` (the same
    expressions in the same order).
    """
    bb = n * il + 12.0 * kb * il * il
    mm = msum * il
    a00 = ka * c * c + bb * s * s - 2.0 * mm * c * s
    a11 = ka * s * s + bb * c * c + 2.0 * mm * c * s
    a01 = (ka - bb) * c * s + mm * (c * c - s * s)
    h = 6.0 * kb * il
    return a00, a11, a01, -h * s, h * c


@jitted_only
def element_local(d, e, props):
    """Chord and local quantities of element ``e`` at nodal displacements ``d``.

    Returns (L, c, s, u_l, θ₁, θ₂, N, M₁, M₂).
    """
    l0 = props[e, EL_L0]
    ln, _il, c, s, ul, t1, t2 = chord_kinematics(d, NDOF_NODE * e, l0)
    il0 = 1.0 / l0
    eil = props[e, EL_EI] * il0
    n = props[e, EL_N0] + props[e, EL_EA] * ul * il0
    m1 = eil * (4.0 * t1 + 2.0 * t2)
    m2 = eil * (2.0 * t1 + 4.0 * t2)
    return ln, c, s, ul, t1, t2, n, m1, m2


@jitted_only
def element_force_tangent(d, e, props, fe, ke, want_k):
    """Global internal force ``fe`` (6) and, if ``want_k``, tangent ``ke`` (6×6) of element e.

    Returns the local forces (N, M₁, M₂).
    """
    ln, c, s, _ul, _t1, _t2, n, m1, m2 = element_local(d, e, props)
    il = 1.0 / ln
    msum = (m1 + m2) * il
    # f = N r − (M₁ + M₂) z/L + M₁ e₃ + M₂ e₆ ; r = (−c, −s, 0, c, s, 0), z = (s, −c, 0, −s, c, 0)
    fe[0] = -n * c - msum * s
    fe[1] = -n * s + msum * c
    fe[2] = m1
    fe[3] = n * c + msum * s
    fe[4] = n * s - msum * c
    fe[5] = m2
    if not want_k:
        return n, m1, m2
    l0 = props[e, EL_L0]
    ka = props[e, EL_EA] / l0
    kb = props[e, EL_EI] / l0
    # With a = (c, s), b = (−s, c): r = (−a, 0, a, 0), z = (−b, 0, b, 0) on (u, v, θ) of the
    # nodes; expanding Bᵀ D B gives 4kb(e₃e₃ᵀ + e₆e₆ᵀ) + 2kb(e₃e₆ᵀ + e₆e₃ᵀ) + 12kb/L² z zᵀ
    # − 6kb/L [(e₃ + e₆) zᵀ + z (e₃ + e₆)ᵀ]. Translational node blocks: ±A with
    # A = ka a aᵀ + (N/L + 12kb/L²) b bᵀ + (M₁ + M₂)/L² (a bᵀ + b aᵀ).
    a00, a11, a01, tu, tv = tangent_blocks(n, msum, il, ka, kb, c, s)
    for i in range(6):
        for j in range(6):
            ke[i, j] = 0.0
    for i0, sgn_i in ((0, 1.0), (3, -1.0)):
        for j0, sgn_j in ((0, 1.0), (3, -1.0)):
            sg = sgn_i * sgn_j
            ke[i0, j0] = sg * a00
            ke[i0, j0 + 1] = sg * a01
            ke[i0 + 1, j0] = sg * a01
            ke[i0 + 1, j0 + 1] = sg * a11
        for rot in (2, 5):
            ke[rot, i0] = sgn_i * tu
            ke[rot, i0 + 1] = sgn_i * tv
            ke[i0, rot] = sgn_i * tu
            ke[i0 + 1, rot] = sgn_i * tv
    ke[2, 2] = 4.0 * kb
    ke[5, 5] = 4.0 * kb
    ke[2, 5] = 2.0 * kb
    ke[5, 2] = 2.0 * kb
    return n, m1, m2


@jitted_only
def element_force_tangent_ref(d, e, props, fe, ke, want_k):
    """Reference form of :func:`element_force_tangent` (B^T D B + geometric terms; tests)."""
    ln, c, s, _ul, _t1, _t2, n, m1, m2 = element_local(d, e, props)
    r = (-c, -s, 0.0, c, s, 0.0)
    z = (s, -c, 0.0, -s, c, 0.0)
    il = 1.0 / ln
    for p in range(6):
        fe[p] = n * r[p] - (m1 + m2) * z[p] * il
    fe[2] += m1
    fe[5] += m2
    if not want_k:
        return n, m1, m2
    l0 = props[e, EL_L0]
    ka = props[e, EL_EA] / l0
    kb = props[e, EL_EI] / l0
    mm = (m1 + m2) * il * il
    for p in range(6):
        b1p = -z[p] * il + (1.0 if p == 2 else 0.0)
        b2p = -z[p] * il + (1.0 if p == 5 else 0.0)
        for q in range(6):
            b1q = -z[q] * il + (1.0 if q == 2 else 0.0)
            b2q = -z[q] * il + (1.0 if q == 5 else 0.0)
            v = ka * r[p] * r[q]
            v += kb * (4.0 * b1p * b1q + 2.0 * (b1p * b2q + b2p * b1q) + 4.0 * b2p * b2q)
            v += n * il * z[p] * z[q]
            v += mm * (r[p] * z[q] + z[p] * r[q])
            ke[p, q] = v
    return n, m1, m2


@jitted_only
def element_energy(d, e, props):
    """Strain energy of element e [J]: N₀u_l + ½EAu_l²/L₀ + ½θᵀD_bθ."""
    _ln, _c, _s, ul, t1, t2, _n, m1, m2 = element_local(d, e, props)
    l0 = props[e, EL_L0]
    return props[e, EL_N0] * ul + 0.5 * props[e, EL_EA] * ul * ul / l0 + 0.5 * (m1 * t1 + m2 * t2)


@jitted_only
def assemble_internal(d, props, f, ab, want_k, fe, ke, moment, axial):
    """Add the internal forces of all elements to ``f`` and (``want_k``) tangents to band ``ab``.

    ``ab[i, k]`` holds the lower band A[i, i − k]. The nodal bending moment and axial force
    (see :func:`node_section_forces`) are written to ``moment`` and ``axial`` (length n_nodes)
    on the way. ``fe`` (6) and ``ke`` (6×6), work arrays of the element form, are not used:
    the element's force and its tangent's 21 lower entries (:func:`element_force_tangent`,
    same expressions in the same order) go straight into ``f`` and ``ab``. The quotients of
    the element properties (1/L₀, EA/L₀, EI/L₀) are computed again only where a property
    differs from the previous element's (equal operands, equal quotient: a uniform pipe
    divides once per call, not per element).
    """
    n_el = props.shape[0]
    for i in range(moment.shape[0]):
        moment[i] = 0.0
        axial[i] = 0.0
    # operands of the quotients last computed (NaN: none yet)
    q_l0 = math.nan
    k_l0 = math.nan
    k_ea = math.nan
    k_ei = math.nan
    il0 = 0.0
    ka = 0.0
    kb = 0.0
    for e in range(n_el):
        i0 = NDOF_NODE * e
        l0 = props[e, EL_L0]
        if l0 != q_l0:
            q_l0 = l0
            il0 = 1.0 / l0
        _ln, il, c, s, ul, t1, t2 = chord_kinematics(d, i0, l0)
        ea = props[e, EL_EA]
        ei = props[e, EL_EI]
        eil = ei * il0
        n = props[e, EL_N0] + ea * ul * il0
        m1 = eil * (4.0 * t1 + 2.0 * t2)
        m2 = eil * (2.0 * t1 + 4.0 * t2)
        moment[e] -= m1
        moment[e + 1] += m2
        axial[e] += n
        axial[e + 1] += n
        msum = (m1 + m2) * il
        # node b's force (node a's is its negative): N (c, s) + (M₁ + M₂)/L (s, −c)
        fx = n * c + msum * s
        fy = n * s - msum * c
        f[i0] -= fx
        f[i0 + 1] -= fy
        f[i0 + 2] += m1
        f[i0 + 3] += fx
        f[i0 + 4] += fy
        f[i0 + 5] += m2
        if want_k:
            if l0 != k_l0 or ea != k_ea or ei != k_ei:
                k_l0 = l0
                k_ea = ea
                k_ei = ei
                ka = ea / l0
                kb = ei / l0
            a00, a11, a01, tu, tv = tangent_blocks(n, msum, il, ka, kb, c, s)
            k4 = 4.0 * kb
            # row i0 + p, column i0 + q (q <= p) at ab[i0 + p, p - q]
            ab[i0, 0] += a00
            ab[i0 + 1, 1] += a01
            ab[i0 + 1, 0] += a11
            ab[i0 + 2, 2] += tu
            ab[i0 + 2, 1] += tv
            ab[i0 + 2, 0] += k4
            ab[i0 + 3, 3] -= a00
            ab[i0 + 3, 2] -= a01
            ab[i0 + 3, 1] -= tu
            ab[i0 + 3, 0] += a00
            ab[i0 + 4, 4] -= a01
            ab[i0 + 4, 3] -= a11
            ab[i0 + 4, 2] -= tv
            ab[i0 + 4, 1] += a01
            ab[i0 + 4, 0] += a11
            ab[i0 + 5, 5] += tu
            ab[i0 + 5, 4] += tv
            ab[i0 + 5, 3] += 2.0 * kb
            ab[i0 + 5, 2] -= tu
            ab[i0 + 5, 1] -= tv
            ab[i0 + 5, 0] += k4
    for i in range(1, moment.shape[0] - 1):
        moment[i] *= 0.5
        axial[i] *= 0.5


@jitted_only
def strain_energy(d, props):
    """Total strain energy of the beam [J]."""
    s = 0.0
    for e in range(props.shape[0]):
        s += element_energy(d, e, props)
    return s


@jitted_only
def node_section_forces(d, props, moment, axial):
    """Bending moment [N·m] and effective axial force [N] at the nodes.

    Element end moments M₁ (node a) and M₂ (node b) act on the element; the internal bending
    moment is −M₁ at a and M₂ at b (positive for curvature of positive sign, EI·v''). Interior
    nodes take the mean of the two elements; a single element's own value at an end node.
    With no elements, both are zero.
    """
    n_nodes = moment.shape[0]
    for i in range(n_nodes):
        moment[i] = 0.0
        axial[i] = 0.0
    n_el = props.shape[0]
    if n_el == 0:
        return
    for e in range(n_el):
        _ln, _c, _s, _ul, _t1, _t2, n, m1, m2 = element_local(d, e, props)
        moment[e] += -m1
        moment[e + 1] += m2
        axial[e] += n
        axial[e + 1] += n
    for i in range(1, n_nodes - 1):
        moment[i] *= 0.5
        axial[i] *= 0.5


element_force_tangent_py = pure_python(element_force_tangent)
"""Plain-Python twin of :func:`element_force_tangent`."""
assemble_internal_py = pure_python(assemble_internal)
"""Plain-Python twin of :func:`assemble_internal`."""
strain_energy_py = pure_python(strain_energy)
"""Plain-Python twin of :func:`strain_energy`."""
chord_angle_py = pure_python(chord_angle)
"""Plain-Python twin of :func:`chord_angle`."""
