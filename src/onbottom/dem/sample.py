"""A DEM specimen: disk positions, radii, kinematics and the box, with NetCDF save/load.

The container is backend-neutral (the numba engine and the optional LAMMPS backend both read
and write it). Model-scale SI units; disks of unit thickness (1 m).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from onbottom.errors import InputError
from onbottom.results import load_dataset, provenance, save_dataset

__all__ = ["Sample"]

_UNITS = {
    "x": ("disk centre abscissa", "m"),
    "y": ("disk centre ordinate (up)", "m"),
    "radius": ("disk radius", "m"),
    "vx": ("disk velocity, x", "m/s"),
    "vy": ("disk velocity, y", "m/s"),
    "omega": ("disk angular velocity (counter-clockwise)", "rad/s"),
    "theta": ("accumulated disk rotation (counter-clockwise)", "rad"),
    "contact_i": ("first disk of a contact", "1"),
    "contact_j": ("second disk of a contact (or wall/pipe code < 0)", "1"),
    "contact_fs": ("shear force history of the contact", "N"),
    "contact_mr": ("rolling moment history of the contact", "N*m"),
}


@dataclass
class Sample:
    """Disks in a box (model scale).

    Parameters
    ----------
    positions
        Disk centres, shape (n, 2) [m]; y is up, the box bottom is at ``box[2]``.
    radii
        Disk radii, shape (n,) [m].
    box
        ``(x_min, x_max, y_min, y_top)`` [m]: side walls at x_min/x_max, bottom wall at y_min;
        y_top is the nominal specimen top (no wall there).
    velocities
        Shape (n, 2) [m/s]; zeros if omitted.
    omega
        Angular velocities, shape (n,) [rad/s]; zeros if omitted.
    theta
        Accumulated rotations, shape (n,) [rad]; zeros if omitted.
    contacts
        Optional contact history: dict with ``i`` (int64), ``j`` (int64; negative codes for
        walls/pipe), ``fs`` [N], ``mr`` [N·m], all shape (m,).
    attrs
        Free metadata (stage, gravity factor, config JSON ...).
    """

    positions: np.ndarray
    radii: np.ndarray
    box: tuple[float, float, float, float]
    velocities: np.ndarray | None = None
    omega: np.ndarray | None = None
    theta: np.ndarray | None = None
    contacts: dict[str, np.ndarray] | None = None
    attrs: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.positions = np.ascontiguousarray(self.positions, dtype=np.float64)
        self.radii = np.ascontiguousarray(self.radii, dtype=np.float64)
        n = self.radii.shape[0]
        if self.positions.shape != (n, 2):
            raise InputError(
                f"positions shape = {self.positions.shape!r} is invalid: must be ({n}, 2)"
            )
        if n and not np.all(self.radii > 0.0):
            raise InputError("radii is invalid: every radius must be > 0")
        self.box = tuple(float(b) for b in self.box)  # type: ignore[assignment]
        if len(self.box) != 4 or not (self.box[0] < self.box[1] and self.box[2] < self.box[3]):
            raise InputError(f"box = {self.box!r} is invalid: need (x_min < x_max, y_min < y_top)")
        self.velocities = (
            np.zeros((n, 2))
            if self.velocities is None
            else np.ascontiguousarray(self.velocities, dtype=np.float64)
        )
        self.omega = (
            np.zeros(n) if self.omega is None else np.ascontiguousarray(self.omega, np.float64)
        )
        self.theta = (
            np.zeros(n) if self.theta is None else np.ascontiguousarray(self.theta, np.float64)
        )

    @property
    def n(self) -> int:
        """Number of disks."""
        return int(self.radii.shape[0])

    @property
    def width(self) -> float:
        """Box width [m]."""
        return self.box[1] - self.box[0]

    def solid_area(self) -> float:
        """Total disk area [m²] (overlaps not subtracted)."""
        return float(np.pi * np.sum(self.radii**2))

    def surface_height(self, n_bins: int = 40) -> float:
        """Mean height of the specimen surface [m]: median over bins of the top disk tops."""
        x = self.positions[:, 0]
        top = self.positions[:, 1] + self.radii
        edges = np.linspace(self.box[0], self.box[1], n_bins + 1)
        idx = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, n_bins - 1)
        tops = np.full(n_bins, np.nan)
        for b in range(n_bins):
            sel = idx == b
            if np.any(sel):
                tops[b] = top[sel].max()
        return float(np.nanmedian(tops))

    def void_ratio(self, top: float | None = None) -> float:
        """Bulk 2D void ratio [-] of the band one largest diameter clear of the bottom wall
        and of the (rough) surface; disks are clipped exactly at the band edges.

        ``top`` overrides the surface height [m] (e.g. a compaction lid).
        """
        from onbottom.dem.analysis import band_void_ratio

        top = self.surface_height() if top is None else top
        dmax = 2.0 * float(self.radii.max())
        return band_void_ratio(
            self.positions, self.radii, (self.box[0], self.box[1]), (self.box[2] + dmax, top - dmax)
        )

    def permuted(self, order: np.ndarray) -> Sample:
        """The same specimen renumbered: new disk k is old disk ``order[k]``.

        The contact history follows its disks; a pair whose order flips (new i > new j) is
        stored as (j, i) with the same shear force (the tangent flips with the normal, so the
        scalar is unchanged) and the opposite rolling moment (stored as the moment on i).
        """
        order = np.asarray(order, np.int64)
        if order.shape != (self.n,) or not np.array_equal(np.sort(order), np.arange(self.n)):
            raise InputError("order is invalid: must be a permutation of the disk indices")
        new_of_old = np.empty(self.n, np.int64)
        new_of_old[order] = np.arange(self.n)
        contacts = None
        if self.contacts is not None:
            i = new_of_old[np.asarray(self.contacts["i"], np.int64)]
            j_old = np.asarray(self.contacts["j"], np.int64)
            walls = j_old < 0
            j = np.where(walls, j_old, new_of_old[np.where(walls, 0, j_old)])
            fs = np.asarray(self.contacts["fs"], np.float64).copy()
            mr = np.asarray(self.contacts["mr"], np.float64).copy()
            flip = ~walls & (i > j)
            i, j = np.where(flip, j, i), np.where(flip, i, j)
            mr[flip] = -mr[flip]
            contacts = {"i": i, "j": j, "fs": fs, "mr": mr}
        return Sample(
            positions=self.positions[order],
            radii=self.radii[order],
            box=self.box,
            velocities=self.velocities[order],
            omega=self.omega[order],
            theta=self.theta[order],
            contacts=contacts,
            attrs=dict(self.attrs),
        )

    def cell_order(self, cell: float | None = None) -> np.ndarray:
        """Disk order by cells [-]: rows of cells of size ``cell`` [m] from the bottom, each
        row left to right, disks in a cell by index (stable). ``None`` → the largest diameter.

        Neighbours then lie within about one row (width/cell cells) of each other in memory.
        """
        if self.n == 0:
            return np.zeros(0, np.int64)
        cell = 2.0 * float(self.radii.max()) if cell is None else float(cell)
        cx = np.floor((self.positions[:, 0] - self.box[0]) / cell).astype(np.int64)
        cy = np.floor((self.positions[:, 1] - self.box[2]) / cell).astype(np.int64)
        cx -= cx.min()
        cy -= cy.min()
        return np.lexsort((np.arange(self.n), cx, cy)).astype(np.int64)

    def mass(self, density: float) -> np.ndarray:
        """Disk masses [kg] for unit thickness."""
        return density * np.pi * self.radii**2

    # ----------------------------------------------------------------- NetCDF
    def to_dataset(self) -> xr.Dataset:
        """xarray Dataset with dimension ``particle`` (and ``contact`` if history is kept)."""
        data = {
            "x": ("particle", self.positions[:, 0]),
            "y": ("particle", self.positions[:, 1]),
            "radius": ("particle", self.radii),
            "vx": ("particle", self.velocities[:, 0]),
            "vy": ("particle", self.velocities[:, 1]),
            "omega": ("particle", self.omega),
            "theta": ("particle", self.theta),
        }
        if self.contacts is not None:
            data["contact_i"] = ("contact", np.asarray(self.contacts["i"], np.int64))
            data["contact_j"] = ("contact", np.asarray(self.contacts["j"], np.int64))
            data["contact_fs"] = ("contact", np.asarray(self.contacts["fs"], np.float64))
            data["contact_mr"] = ("contact", np.asarray(self.contacts["mr"], np.float64))
        ds = xr.Dataset(data)
        for name, (long_name, units) in _UNITS.items():
            if name in ds:
                ds[name].attrs.update(long_name=long_name, units=units)
        attrs = provenance("dem.sample")
        attrs["box"] = json.dumps(list(self.box))
        attrs["sample_attrs"] = json.dumps(self.attrs, default=str)
        ds.attrs.update(attrs)
        return ds

    @classmethod
    def from_dataset(cls, ds: xr.Dataset) -> Sample:
        """Inverse of :meth:`to_dataset`."""
        contacts = None
        if "contact_i" in ds:
            contacts = {
                "i": ds["contact_i"].values.astype(np.int64),
                "j": ds["contact_j"].values.astype(np.int64),
                "fs": ds["contact_fs"].values.astype(np.float64),
                "mr": ds["contact_mr"].values.astype(np.float64),
            }
        return cls(
            positions=np.stack([ds["x"].values, ds["y"].values], axis=1),
            radii=ds["radius"].values,
            box=tuple(json.loads(ds.attrs["box"])),
            velocities=np.stack([ds["vx"].values, ds["vy"].values], axis=1),
            omega=ds["omega"].values,
            theta=ds["theta"].values,
            contacts=contacts,
            attrs=json.loads(ds.attrs.get("sample_attrs", "{}")),
        )

    def save(self, path: str | Path) -> Path:
        """Write atomically to NetCDF (``results.save_dataset``)."""
        return save_dataset(self.to_dataset(), path)

    @classmethod
    def load(cls, path: str | Path) -> Sample:
        """Read a file written by :meth:`save`."""
        return cls.from_dataset(load_dataset(path))
