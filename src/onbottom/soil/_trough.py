"""Numba helpers shared by the trough-based passive models (V&S sand, V&L clay) (private)."""

from __future__ import annotations

from onbottom._jit import jitted_only

__all__ = [
    "RULE_ELASTOPLASTIC",
    "RULE_LEGACY_ELASTIC",
    "envelope",
    "envelope_energy",
    "friction_energy",
    "overlap",
    "push_only_passive",
    "push_only_start",
    "region_of",
    "side_bounds",
    "sign",
    "spring_work",
]

RULE_ELASTOPLASTIC = 0
"""Passive rule: push-only elastic–plastic (dissipative; default)."""
RULE_LEGACY_ELASTIC = 1
"""Passive rule: nonlinear-elastic restoring force on the envelope (creates energy; variant)."""

PHASE_TROUGH = 0.0
"""Pipe inside its trough; the peak displacement has not been passed."""
PHASE_BREAKOUT = 1.0
"""Peak displacement passed, residual displacement not passed: the pipe climbs out."""
PHASE_OUT = 2.0
"""Residual displacement passed: out of the trough until the next reversal."""


@jitted_only
def envelope(a, fr1, fr2, fr3, y1, y2, y3):
    """Passive envelope magnitude and slope at distance ``a`` = |y − y0| from the trough centre.

    Piecewise linear through (0, 0), (y1, fr1), (y2, fr2), (y3, fr3), constant beyond y3;
    requires 0 < y1 <= y2 < y3 (a zero-length segment is skipped).
    """
    if a <= y1:
        k = fr1 / y1
        return k * a, k
    if a <= y2:
        k = (fr2 - fr1) / (y2 - y1)
        return fr1 + k * (a - y1), k
    if a <= y3:
        k = (fr3 - fr2) / (y3 - y2)
        return fr2 + k * (a - y2), k
    return fr3, 0.0


@jitted_only
def overlap(a, b, lo, hi):
    """Length of the segment between ``a`` and ``b`` that lies inside [lo, hi]."""
    lo2 = max(min(a, b), lo)
    hi2 = min(max(a, b), hi)
    if hi2 > lo2:
        return hi2 - lo2
    return 0.0


@jitted_only
def sign(x):
    """Sign of ``x`` as a float (0 for 0)."""
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return 0.0


@jitted_only
def region_of(a, y1, y2, y3):
    """Region code 1–4 of the distance ``a`` from the trough centre."""
    if a <= y1:
        return 1.0
    if a <= y2:
        return 2.0
    if a <= y3:
        return 3.0
    return 4.0


@jitted_only
def envelope_energy(a, fr1, fr2, fr3, y1, y2, y3):
    """∫₀^a envelope(x) dx [N·m/m]: energy of the nonlinear-elastic (legacy) passive spring."""
    e = 0.0
    x0 = 0.0
    f0 = 0.0
    for seg in range(3):
        if seg == 0:
            x1, f1 = y1, fr1
        elif seg == 1:
            x1, f1 = y2, fr2
        else:
            x1, f1 = y3, fr3
        if x1 <= x0:
            continue
        if a <= x1:
            fa = f0 + (f1 - f0) * (a - x0) / (x1 - x0)
            return e + 0.5 * (f0 + fa) * (a - x0)
        e += 0.5 * (f0 + f1) * (x1 - x0)
        x0 = x1
        f0 = f1
    return e + fr3 * (a - x0)


@jitted_only
def side_bounds(s_new, mag):
    """Admissible passive force interval at s_new: [0, mag] for s > 0, [−mag, 0] for s < 0."""
    if s_new > 0.0:
        return 0.0, mag
    if s_new < 0.0:
        return -mag, 0.0
    return 0.0, 0.0


@jitted_only
def push_only_start(p_old, s_new, mag):
    """Start of the elastic predictor: the committed force returned into the current bounds.

    The bounds move with the penetration, V and the side of the trough; a force left outside
    them (the envelope shrank) is first brought back onto them, so that a reversal unloads
    from the bound rather than from a force the soil can no longer carry.
    """
    lo, hi = side_bounds(s_new, mag)
    return min(max(p_old, lo), hi)


@jitted_only
def push_only_passive(p_old, dy, s_new, mag, slope, k_u):
    """Push-only elastic–plastic passive force and its tangent [I].

    Elastic predictor p_start + k_u·Δu (p_start: :func:`push_only_start`), then return to
    the admissible interval: [0, F_env(s)] on the side s > 0 of the trough centre,
    [−F_env(|s|), 0] on the side s < 0 (the berm can only push the pipe back towards the
    centre, never pull it). ``mag``/``slope`` are the envelope magnitude and slope at
    |s_new|; ``k_u`` the unloading (elastic) stiffness [N/m²]. The force on the yield surface
    follows the envelope; inside it, the elastic line.
    """
    lo, hi = side_bounds(s_new, mag)
    p_trial = min(max(p_old, lo), hi) + k_u * dy
    if p_trial > hi:
        if s_new > 0.0:
            return hi, slope
        return hi, 0.0
    if p_trial < lo:
        if s_new < 0.0:
            return lo, slope
        return lo, 0.0
    return p_trial, k_u


@jitted_only
def friction_energy(f, v_load, mu, delta):
    """Elastic energy f²/(2k) of the friction spring, k = μV/δ [N·m/m] (0 when lifted off)."""
    cap = mu * v_load
    if cap <= 0.0:
        return 0.0
    return 0.5 * f * f * delta / cap


@jitted_only
def spring_work(x_old, x_new, x_trial, k):
    """Work done on an elastic–plastic spring over one return-mapped increment [N·m/m].

    Force ``x_old`` → ``x_new`` with elastic predictor ``x_trial`` = x_old + k·Δu. The work
    is the change of the stored energy x²/(2k) plus the dissipation x_new·Δu_p with the
    plastic slip Δu_p = (x_trial − x_new)/k (exact for the piecewise-linear path of one
    increment: an unloading that reaches a zero bound returns exactly the stored energy, where
    the trapezoidal rule would return more). The dissipation is >= 0 because the return is to
    a bound on the side of the slip. 0 for k <= 0.
    """
    if k <= 0.0:
        return 0.0
    return (x_new * x_new - x_old * x_old) / (2.0 * k) + x_new * (x_trial - x_new) / k


@jitted_only
def elastoplastic_soil_work(f_old, f_new, p_old, p_new, s_new, mag, k_u, dy, v_load, mu, delta):
    """Work done on the soil over one increment by the friction and passive springs [N·m/m].

    Each spring's work along its own return-mapped increment (:func:`spring_work`), from the
    start force of its elastic predictor: the friction spring (stiffness μV/δ) from ``f_old``
    returned into ±μV, the push-only passive spring (unloading stiffness ``k_u``) from
    :func:`push_only_start`. ``f_new``/``p_new``: the committed friction and passive forces [N/m];
    ``s_new``, ``mag``: side and magnitude passed to :func:`push_only_start`; ``dy``: increment
    [m]; ``v_load``: vertical load [N/m] (no spring works when lifted off, V <= 0). Shared by
    the Verley & Sotberg and Verley & Lund kernels (``passive_rule="elastoplastic"``).
    """
    k_fr = 0.0
    f0 = 0.0
    if v_load > 0.0:
        cap = mu * v_load
        k_fr = cap / delta
        f0 = min(max(f_old, -cap), cap)
    w = spring_work(f0, f_new, f0 + k_fr * dy, k_fr)
    if v_load > 0.0:
        p0 = push_only_start(p_old, s_new, mag)
        w += spring_work(p0, p_new, p0 + k_u * dy, k_u)
    return w
