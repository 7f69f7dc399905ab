"""Reading a LAMMPS run back: the V–w curve (as an xarray Dataset) and the final disk state.

Part of the optional LAMMPS backend (:mod:`onbottom.dem.lammps_backend`). The curve has the
variable names and units of :func:`onbottom.dem.experiment.penetrate`'s record.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from onbottom.dem.experiment import _LONG
from onbottom.dem.lammps_case import LammpsPenetrationCase
from onbottom.dem.lammps_deck import LammpsDeck
from onbottom.results import provenance

__all__ = ["CURVE_VARIABLES", "read_curve", "read_final"]

CURVE_VARIABLES = {
    # the names, long names and units of onbottom.dem.experiment.penetrate's record (one table)
    **{k: _LONG[k] for k in ("time", "w", "w_over_D", "V", "H", "w_prototype", "V_prototype")},
    "n_contacts": ("number of disks touching the pipe", "1"),
}


def read_curve(case: LammpsPenetrationCase, deck: LammpsDeck, meta: dict[str, Any]) -> xr.Dataset:
    rows: list[list[float]] = []
    if deck.curve.exists():
        with open(deck.curve, encoding="ascii") as fh:
            rows = [[float(x) for x in ln.split()] for ln in fh if ln.strip() and ln[0] != "#"]
    arr = np.array(rows, dtype=np.float64).reshape(-1, 5)
    t0 = (case.n_ramp + case.n_settle) * case.dt
    D, N = case.pipe_diameter, case.gravity_factor
    w, V = arr[:, 1], arr[:, 2]
    ds = xr.Dataset(
        {
            "time": ("record", arr[:, 0] - t0),
            "w": ("record", w),
            "w_over_D": ("record", w / D),
            "V": ("record", V),
            "H": ("record", arr[:, 3]),
            "w_prototype": ("record", w * N),
            "V_prototype": ("record", V * N),
            "n_contacts": ("record", arr[:, 4].astype(np.int64)),
        }
    )
    for name, (long_name, units) in CURVE_VARIABLES.items():
        ds[name].attrs.update(long_name=long_name, units=units)
    ds.attrs.update(
        provenance(
            "dem.lammps_backend",
            case.parameters(),
            engine="LAMMPS",
            preset=case.name,
            n_particles=case.n,
            dt=case.dt,
            gravity_factor=N,
            pipe_diameter=D,
            surface0_at_pipe=case.surface_y,
            **meta,
        )
    )
    return ds


def read_final(deck: LammpsDeck, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    if not deck.final.exists():
        return None
    arr = np.loadtxt(deck.final, skiprows=9, ndmin=2)
    if arr.shape[0] != n:
        return None
    arr = arr[np.argsort(arr[:, 0])]
    return arr[:, 1:3].copy(), arr[:, 4:6].copy(), arr[:, 6].copy()
