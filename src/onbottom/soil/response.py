"""Response of a lateral resistance model along a prescribed displacement path.

Drives a model's numba kernel point by point (each point committed), as in a displacement-
controlled element test, and returns an annotated xarray Dataset. Useful for backbone plots,
calibration against displacement-controlled tests and for checking a model before using it in
a load-controlled simulation.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from onbottom._validate import finite
from onbottom.errors import InputError
from onbottom.results import annotate, provenance
from onbottom.soil._path import drive_path
from onbottom.soil.base import (
    OUT_FRICTION,
    OUT_PASSIVE,
    OUT_R,
    OUT_REGION,
    OUT_SIZE,
    OUT_WORK,
    OUT_Z,
    LateralResistanceModel,
)

__all__ = ["cyclic_path", "path_response"]


def cyclic_path(amplitude: float, cycles: float, points_per_cycle: int = 400) -> np.ndarray:
    """Sinusoidal displacement path y = a·sin(2πt), t in (0, cycles] [m].

    Parameters
    ----------
    amplitude : float
        a [m], > 0.
    cycles : float
        Number of cycles, > 0.
    points_per_cycle : int
        Resolution, >= 8.
    """
    a = finite("amplitude", amplitude)
    c = finite("cycles", cycles)
    if a <= 0.0 or c <= 0.0:
        raise InputError(
            f"amplitude = {a!r}, cycles = {c!r} are invalid: both must be > 0 (range (0, inf))"
        )
    if int(points_per_cycle) < 8:
        raise InputError(f"points_per_cycle = {points_per_cycle!r} is invalid: must be >= 8")
    n = max(round(c * points_per_cycle), 1)
    t = np.linspace(0.0, c, n + 1)[1:]
    return a * np.sin(2.0 * np.pi * t)


def path_response(
    model: LateralResistanceModel, displacement: np.ndarray, vertical_load: float | np.ndarray
) -> xr.Dataset:
    """Drive ``model`` along ``displacement`` (starting from its initial state at y = 0).

    Parameters
    ----------
    model : LateralResistanceModel
        Any registered lateral model.
    displacement : array
        Lateral displacements y [m] of successive points (committed one after another).
    vertical_load : float or array
        V [N/m] at each point (scalar = constant).

    Returns
    -------
    xarray.Dataset
        Dimension ``step``; variables y (lateral displacement), V, F_soil, F_friction,
        F_passive, z, work, region,
        with units and provenance attributes.
    """
    y = np.ascontiguousarray(displacement, dtype=float).ravel()
    if y.size == 0 or not np.all(np.isfinite(y)):
        raise InputError("displacement is invalid: must be a non-empty array of finite values")
    v = np.ascontiguousarray(np.broadcast_to(np.asarray(vertical_load, dtype=float), y.shape))
    if not np.all(np.isfinite(v)):
        raise InputError("vertical_load is invalid: must be finite")
    v = v.copy()
    h = np.zeros((y.size, OUT_SIZE))
    drive_path(model.model_id, model.packed_parameters(), model.initial_state(), y, v, h)
    ds = xr.Dataset(
        {
            "y": ("step", y),
            "V": ("step", v),
            "F_soil": ("step", h[:, OUT_R]),
            "F_friction": ("step", h[:, OUT_FRICTION]),
            "F_passive": ("step", h[:, OUT_PASSIVE]),
            "z": ("step", h[:, OUT_Z]),
            "work": ("step", h[:, OUT_WORK]),
            "region": ("step", h[:, OUT_REGION]),
        },
        attrs=provenance(model.name, model.parameters(), reference=model.reference),
    )
    return annotate(ds)
