"""Result conventions: variable names and units, provenance, atomic NetCDF files.

Every xarray Dataset that onbottom returns takes the ``long_name`` and ``units`` of its
variables from :data:`VARIABLES` (add an entry when you add a variable) and carries
provenance attributes made by :func:`provenance`.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from onbottom._version import __version__

__all__ = [
    "VARIABLES",
    "annotate",
    "clean_stale_temporaries",
    "load_dataset",
    "provenance",
    "save_dataset",
    "write_text_atomic",
]

VARIABLES: dict[str, tuple[str, str]] = {
    # name: (long_name, units)
    "time": ("time", "s"),
    "u": ("lateral displacement of the pipe", "m"),
    "u_dot": ("lateral velocity of the pipe", "m/s"),
    "w": ("penetration (embedment) of the pipe invert", "m"),
    "z": ("penetration (embedment) of the pipe invert", "m"),
    "H": ("applied horizontal load per unit length", "N/m"),
    "V": ("vertical contact load per unit length", "N/m"),
    "F_soil": ("total lateral soil resistance on the pipe", "N/m"),
    "F_friction": ("Coulomb friction part of the lateral resistance", "N/m"),
    "F_passive": ("passive part of the lateral resistance", "N/m"),
    "work": ("accumulated work in the current trough", "N"),
    "region": ("displacement region of the soil model", "1"),
    "Q_v": ("vertical penetration resistance per unit length", "N/m"),
    "z_over_D": ("normalised penetration z/D", "1"),
    "B": ("contact width of the pipe at the seabed", "m"),
    "Q_v_lower": ("lower estimate of the vertical penetration resistance", "N/m"),
    "Q_v_upper": ("upper estimate of the vertical penetration resistance", "N/m"),
    "soil_energy_stored": ("elastic energy stored in the soil springs", "J/m"),
    "soil_energy_dissipated": ("energy dissipated by the soil since the start", "J/m"),
    "peak_time": ("time of the peak horizontal load of a wave cycle", "s"),
    "H_peak": ("peak horizontal hydrodynamic load |F_Y| of a wave cycle", "N/m"),
    "F_Z_peak": ("lift at the peak horizontal load of a wave cycle", "N/m"),
    "V_peak": ("vertical contact load w_s - F_Z at the peak of a wave cycle", "N/m"),
    "load_angle": ("load angle atan(H/V) from the V axis at the peak of a wave cycle", "degree"),
    "fraction_20_45": ("fraction of wave cycles with load angle in [20, 45] degrees", "1"),
    "w_s": ("submerged weight of the pipe per unit length", "N/m"),
    # storm section (issue 12)
    "y": ("lateral displacement of the pipe section", "m"),
    "y_dot": ("lateral velocity of the pipe section", "m/s"),
    "F_hydro": ("horizontal hydrodynamic load on the pipe F_Y", "N/m"),
    "F_Z": ("hydrodynamic lift on the pipe", "N/m"),
    "U": ("wave-induced near-bed velocity normal to the pipe", "m/s"),
    "work_hydro": ("work of the hydrodynamic load on the pipe", "J/m"),
    "work_soil": ("work done by the pipe on the soil", "J/m"),
    "r_y": ("total horizontal load reduction r_tot,y", "1"),
    "r_z": ("total vertical load reduction r_tot,z", "1"),
    # pipeline FE (time × node; onbottom.dynamics.pipeline)
    "u_axial": ("axial displacement of the pipe", "m"),
    "moment": ("bending moment in the horizontal plane", "N m"),
    "axial_force": ("effective axial force (tension positive)", "N"),
    "strain": ("largest longitudinal fibre strain |N|/EA + |M|c/EI", "1"),
}


def provenance(model: str, parameters: Mapping[str, Any] | None = None, **extra: Any) -> dict:
    """Attributes recording what produced a result.

    Parameters
    ----------
    model
        Name of the model or solver.
    parameters
        Model parameters (SI); stored as a JSON string under ``parameters``.
    **extra
        Any further attributes (``seed``, ``standard_edition``, ...). Values that are not
        str/int/float are JSON-encoded so that the attributes survive NetCDF.
    """
    attrs: dict[str, Any] = {
        "onbottom_version": __version__,
        "model": model,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
    }
    if parameters is not None:
        attrs["parameters"] = json.dumps(dict(parameters), sort_keys=True, default=float)
    for k, v in extra.items():
        attrs[k] = (
            v
            if isinstance(v, (str, int, float, np.integer, np.floating))
            else json.dumps(v, default=str)
        )
    return attrs


def annotate(ds: xr.Dataset) -> xr.Dataset:
    """Fill ``long_name``/``units`` of variables and coordinates from :data:`VARIABLES`."""
    for name in list(ds.variables):
        if name in VARIABLES:
            long_name, units = VARIABLES[str(name)]
            ds[name].attrs.setdefault("long_name", long_name)
            ds[name].attrs.setdefault("units", units)
    return ds


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def clean_stale_temporaries(path: str | os.PathLike) -> list[Path]:
    """Remove temporary files ``<name>.*.tmp`` left beside ``path`` by a killed writer.

    Called by every atomic writer before it starts, so no temporary file survives a kill for
    longer than the next run writing the same file. Returns the files removed.
    """
    p = Path(path)
    removed = []
    if p.parent.is_dir():
        for tmp in p.parent.glob(glob_escape(p.name) + ".*.tmp"):
            try:
                tmp.unlink()
                removed.append(tmp)
            except OSError:
                pass
    return removed


def glob_escape(name: str) -> str:
    """``name`` with glob wild-cards escaped."""
    return "".join(f"[{c}]" if c in "*?[]" else c for c in name)


def _atomic_write(path: Path, write: Any) -> Path:
    """Call ``write(tmp)`` on a temporary file beside ``path``, then rename it to ``path``.

    The file gets the permissions of a normally created file (0666 less the umask, 0644 with
    the usual umask 022), not the 0600 of a temporary file; the folder is created if needed.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    clean_stale_temporaries(path)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        write(tmp)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


def save_dataset(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to NetCDF atomically (temporary file in the same folder, then rename).

    A reader never sees a half-written file, even if the process is killed mid-write; a
    temporary file left by a killed writer is removed the next time the same file is written.
    Permissions: 0666 less the umask (0644 usually); the folder is created if needed.
    """
    return _atomic_write(Path(path), lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf"))


def write_text_atomic(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically, as :func:`save_dataset`."""
    return _atomic_write(Path(path), lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))


def load_dataset(path: str | os.PathLike) -> xr.Dataset:
    """Load a NetCDF file written by :func:`save_dataset` fully into memory."""
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        return ds.load()
