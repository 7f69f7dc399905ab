"""DEM penetration resistance against the DNVGL-RP-F114 drained bounds (paper §4 comparison).

This module is where the DEM (``onbottom.dem``) and the soil models (``onbottom.soil``) meet:
neither imports the other, the plotting layer may import both.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from onbottom._validate import positive
from onbottom.plotting.dem import plot_resistance_with_bounds
from onbottom.soil.penetration_sand import DrainedBounds

__all__ = ["DEFAULT_DRY_UNIT_WEIGHT", "f114_bounds_for_dem", "plot_dem_against_f114"]

DEFAULT_DRY_UNIT_WEIGHT: dict[str, float] = {"SM": 15.9e3, "SD": 16.7e3}
"""Prototype dry unit weight γ_d [N/m³] of the centrifuge sand by preset — estimates from the
DEM relative densities and ρ_min/ρ_max of the test sand (spec dnv-reference.md §3.3; replace
with the paper's Table 1 values when available). Reduced presets use their parent's value."""


def f114_bounds_for_dem(
    results: xr.Dataset,
    *,
    unit_weight: float,
    phi_lower_deg: float = 33.0,
    phi_upper_deg: float = 40.0,
    n_points: int = 101,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """F114 lower/upper drained resistance at the prototype scale of a DEM run.

    Parameters
    ----------
    results : xarray.Dataset
        A DEM penetration result (attributes ``pipe_diameter`` [m, model scale] and
        ``gravity_factor`` N [-]); the prototype diameter is N·D.
    unit_weight : float
        Prototype (dry) unit weight of the sand γ_d [N/m³], > 0 (the tests were run dry).
    phi_lower_deg, phi_upper_deg : float
        Friction angles of the lower and upper estimates [deg]: φ_c = 33° of the test sand
        and about 40°, the peak angle implied by the paper's upper bound (F114 Eq 4.9).
    n_points : int
        Number of points on 0 <= w/D <= 0.5.

    Returns
    -------
    (w_over_D, lower, upper)
        Embedment ratios [-] and bound resistances at prototype scale [N/m].
    """
    positive("unit_weight", unit_weight)
    d_proto = float(results.attrs["pipe_diameter"]) * float(results.attrs["gravity_factor"])
    bounds = DrainedBounds.from_friction_angles(
        diameter=d_proto,
        unit_weight=unit_weight,
        lower_friction_angle_deg=phi_lower_deg,
        upper_friction_angle_deg=phi_upper_deg,
    )
    w_over_d = np.linspace(0.0, 0.5, n_points)
    z = w_over_d * d_proto
    return w_over_d, bounds.lower.resistance(z), bounds.upper.resistance(z)


def plot_dem_against_f114(
    results: xr.Dataset | list[xr.Dataset],
    *,
    unit_weight: float,
    phi_lower_deg: float = 33.0,
    phi_upper_deg: float = 40.0,
    reference: dict[str, dict[float, float]] | None = None,
) -> Figure:
    """DEM V–w/D curves (prototype kN/m) with the F114 lower/upper drained bounds shaded.

    ``reference``: published points by preset {w/D: V [N/m]} (see
    :data:`onbottom.dem.published.PUBLISHED`), drawn as markers.
    """
    runs = results if isinstance(results, list) else [results]
    w, lower, upper = f114_bounds_for_dem(
        runs[0], unit_weight=unit_weight, phi_lower_deg=phi_lower_deg, phi_upper_deg=phi_upper_deg
    )
    return plot_resistance_with_bounds(
        runs,
        w,
        lower,
        upper,
        bound_label=(
            f"DNVGL-RP-F114 (φ' {phi_lower_deg:g}°/{phi_upper_deg:g}°, "
            f"γ_d {unit_weight / 1e3:.3g} kN/m³)"
        ),
        reference=reference,
    )
