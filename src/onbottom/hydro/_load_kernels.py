"""Numba kernels of the time-domain hydrodynamic loads and F109 load reductions (private).

Shared by the storm-section solver and the pipeline FE, so that both use the same force law.
Plain-Python twins: :mod:`onbottom.hydro.reductions` (reductions) and
:func:`onbottom.hydro.forces.horizontal_force` / :func:`onbottom.hydro.forces.lift_force`
(forces at ẏ = 0, r = 1); tests compare them.

Force law per unit length (docs/theory/storm_loads.md; DNV-RP-F109 (2017) §3.4 Morison form,
relative velocity as in CORUS-3D, Youssef & Cassidy 2014):

F_Y = r_y · [ ½ ρ_w D C_D (U + V − ẏ)|U + V − ẏ| + ρ_w (π D²/4) C_M U̇ ]
F_Z = r_z · ½ ρ_w D C_L (U + V)²

The added-mass term −ρ_w (π D²/4) C_a ÿ belongs with the mass on the left-hand side.
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def penetration_reduction_y(z_over_d):
    """r_pen,y = max(1 − 1.4 z_p/D, 0.3) (DNV-RP-F109 (2017) Eq 3.19); 1 for z_p <= 0."""
    if z_over_d <= 0.0:
        return 1.0
    return max(1.0 - 1.4 * z_over_d, 0.3)


@njit(cache=True)
def penetration_reduction_z(z_over_d):
    """r_pen,z = 1 for z_p/D <= 0.1, else max(1 − 1.3 (z_p/D − 0.1), 0) (F109 (2017) Eq 3.20)."""
    if z_over_d <= 0.1:
        return 1.0
    return max(1.0 - 1.3 * (z_over_d - 0.1), 0.0)


@njit(cache=True)
def morison_lateral(u, dudt, current, ydot, diameter, rho, cd, cm, r_y):
    """Lateral load F_Y [N/m] and its derivative dF_Y/dẏ [N·s/m²] (relative-velocity drag).

    u, dudt: wave-induced near-bed velocity [m/s] and acceleration [m/s²]; current V [m/s];
    ydot: pipe velocity [m/s]; diameter D [m]; rho ρ_w [kg/m³]; cd, cm: C_D, C_M [-];
    r_y: total lateral load reduction r_tot,y [-].
    """
    urel = u + current - ydot
    drag = 0.5 * rho * diameter * cd * urel * abs(urel)
    inertia = 0.25 * math.pi * rho * diameter * diameter * cm * dudt
    dfdydot = r_y * (-rho * diameter * cd * abs(urel))
    return r_y * (drag + inertia), dfdydot


@njit(cache=True)
def lift(u, current, diameter, rho, cl, r_z):
    """Lift F_Z = r_z · ½ ρ_w D C_L (U + V)² [N/m], positive upward."""
    s = u + current
    return r_z * (0.5 * rho * diameter * cl * s * s)
