"""Direct NetCDF-4 writer of in-memory datasets (private; used by ``save_dataset``).

xarray's h5netcdf store spends most of a small result's write in per-variable bookkeeping
(each attribute and dimension lookup goes through h5py's object layer several times); this
writer lays the same file out with h5py in one pass: the NetCDF-4 data model on HDF5 as the
netCDF-C library writes it (dimension scales with ``CLASS``/``NAME``, ``_Netcdf4Dimid`` on
each scale, ``_Netcdf4Coordinates`` on each variable with dimensions, a placeholder scale
for a dimension without a coordinate variable, creation order tracked, ``_NCProperties``).
The variables and attributes are encoded by xarray's own CF encoder (fill values, ``bool``,
times, the ``coordinates`` attribute), so ``xarray.open_dataset`` reads back what
``Dataset.to_netcdf`` would have written.

Compressed variables are deflated (zlib format) after the byte-shuffle filter, the filters
netCDF-4 readers expect, chunk by chunk in Python and stored with
``write_direct_chunk``: with the ``isal`` package (ISA-L's deflate, an order of magnitude
faster than zlib at a similar ratio) when it is installed, else with :mod:`zlib`.

:func:`writable` says whether a dataset is within what this writer covers (numeric
variables, attributes of strings and numbers, no storage settings of its own); the caller
falls back to xarray's h5netcdf store otherwise.
"""

from __future__ import annotations

import zlib
from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

__all__ = ["deflate_name", "writable", "write_nc4"]

_NOT_A_VARIABLE = "This is a netCDF dimension but not a netCDF variable."
# storage settings a dataset read from a file carries; a true value is one this writer
# does not reproduce (the caller then uses xarray's store)
_STORAGE_KEYS = frozenset(
    {
        "zlib", "szip", "zstd", "bzip2", "blosc", "shuffle", "complevel", "fletcher32",
        "chunksizes", "compression", "compression_opts", "szip_coding",
        "szip_pixels_per_block", "blosc_shuffle", "quantize_mode", "significant_digits",
        "least_significant_digit", "endian",
    }
)  # fmt: skip
_SAFE_KEYS = frozenset(
    {"dtype", "_FillValue", "missing_value", "scale_factor", "add_offset", "units",
     "calendar", "source", "original_shape", "contiguous", "preferred_chunks", "coordinates"}
)  # fmt: skip
CHUNK_BYTES = 2**20
"""Largest chunk of a compressed variable [bytes] (whole rows along the first dimension)."""

try:  # ISA-L deflate: zlib streams, about ten times zlib's speed at level 1
    from isal import isal_zlib as _deflate_module

    _DEFLATE = "isal"
except ImportError:  # pragma: no cover - the zlib fallback
    _deflate_module = zlib
    _DEFLATE = "zlib"


def deflate_name() -> str:
    """The deflate implementation in use: ``"isal"`` or ``"zlib"``."""
    return _DEFLATE


def _deflate(data: bytes, level: int) -> bytes:
    if _DEFLATE == "isal":
        # ISA-L levels 0-3: zlib levels 1-3 -> 1, 4-6 -> 2, 7-9 -> 3
        return _deflate_module.compress(data, min(3, (level + 2) // 3))
    return zlib.compress(data, level)


def _plain_attr(value: Any) -> bool:
    if isinstance(value, str):
        return True
    if isinstance(value, (bool, np.bool_)):
        return False
    if isinstance(value, (int, float, np.integer, np.floating)):
        return True
    if isinstance(value, (list, tuple)):
        value = np.asarray(value)
    return isinstance(value, np.ndarray) and value.dtype.kind in "iuf" and value.ndim <= 1


def writable(ds: xr.Dataset) -> bool:
    """True when :func:`write_nc4` covers ``ds``: numeric or boolean variables in memory,
    attributes of strings and numbers, no unlimited dimension, no storage settings."""
    if ds.chunks or ds.encoding.get("unlimited_dims"):
        return False
    for name, var in ds.variables.items():
        if not isinstance(name, str) or var.dtype.kind not in "biuf":
            return False
        if var.dtype.kind != "b" and not var.dtype.isnative:
            return False
        for key, value in var.encoding.items():
            if key in _STORAGE_KEYS:
                if value not in (None, False, 0):
                    return False
            elif key not in _SAFE_KEYS:
                return False
        if not all(_plain_attr(v) for v in var.attrs.values()):
            return False
        if name in ds.dims and var.dims != (name,):
            return False
    return all(isinstance(k, str) and _plain_attr(v) for k, v in ds.attrs.items())


def _encoded(ds: xr.Dataset) -> tuple[dict[str, Any], dict[str, Any]]:
    """Variables and attributes as xarray's NetCDF-4 store would write them."""
    from xarray import conventions

    variables, attrs = conventions.encode_dataset_coordinates(ds)
    return conventions.cf_encoder(variables, attrs)


def _set_attrs(h5: Any, attrs: Mapping[str, Any], dtype: np.dtype | None = None) -> None:
    for key, value in attrs.items():
        if key == "_FillValue":
            h5.attrs[key] = np.array([value], dtype=dtype)
        elif isinstance(value, str):
            h5.attrs[key] = value
        else:
            h5.attrs[key] = np.atleast_1d(np.asarray(value))


def _write_deflated(dset: Any, data: np.ndarray, level: int) -> None:
    """Store ``data`` in ``dset`` (chunked along its first axis, shuffle + deflate filters
    declared) chunk by chunk: shuffled and deflated here, written with write_direct_chunk."""
    rows = dset.chunks[0]
    size = data.itemsize
    for start in range(0, data.shape[0], rows):
        block = data[start : start + rows]
        if block.shape[0] < rows:  # an edge chunk is stored whole (HDF5 pads it)
            full = np.zeros((rows, *data.shape[1:]), dtype=data.dtype)
            full[: block.shape[0]] = block
            block = full
        raw = np.ascontiguousarray(block).view(np.uint8).reshape(-1, size)
        offset = (start,) + (0,) * (data.ndim - 1)
        dset.id.write_direct_chunk(offset, _deflate(raw.T.tobytes(), level), 0)


def write_nc4(ds: xr.Dataset, target: Any, compress: Mapping[str, int]) -> None:
    """Write ``ds`` (:func:`writable`) as a NetCDF-4 file to ``target`` (a path or a binary
    file object); ``compress``: deflate level of each variable to compress (1–9)."""
    import h5py

    variables, attrs = _encoded(ds)
    dims: dict[str, int] = {}
    for var in variables.values():
        for d, n in zip(var.dims, var.shape, strict=True):
            dims.setdefault(str(d), int(n))
    dim_id = {d: i for i, d in enumerate(dims)}
    with h5py.File(target, "w", track_order=True) as f:
        f.attrs["_NCProperties"] = np.bytes_(
            f"version=2,h5py={h5py.version.version},hdf5={h5py.version.hdf5_version}"
        )
        scales: dict[str, Any] = {}
        for d, n in dims.items():
            if d in variables:
                continue
            placeholder = f.create_dataset(d, shape=(n,), dtype=">f4", track_order=True)
            placeholder.attrs["_Netcdf4Dimid"] = np.int32(dim_id[d])
            placeholder.make_scale(f"{_NOT_A_VARIABLE}{n:10d}")
            scales[d] = placeholder
        created = []
        for name, var in variables.items():
            data = np.asarray(var.values)
            fill = var.attrs.get("_FillValue")
            opts: dict[str, Any] = {"track_order": True}
            if fill is not None:
                opts["fillvalue"] = np.asarray(fill, dtype=data.dtype)
            level = compress.get(name, 0)
            if level and data.ndim > 0 and data.size > 0:
                rows = max(1, min(data.shape[0], CHUNK_BYTES // max(1, data[0].nbytes)))
                opts.update(
                    chunks=(rows, *data.shape[1:]),
                    compression="gzip",
                    compression_opts=level,
                    shuffle=True,
                )
                dset = f.create_dataset(name, shape=data.shape, dtype=data.dtype, **opts)
                _write_deflated(dset, data, level)
            else:
                dset = f.create_dataset(name, data=data, **opts)
            if var.dims == (name,):
                dset.make_scale(name)
                dset.attrs["_Netcdf4Dimid"] = np.int32(dim_id[name])
                scales[name] = dset
            if var.dims:
                ids = [dim_id[str(d)] for d in var.dims]
                dset.attrs["_Netcdf4Coordinates"] = np.array(ids, dtype=np.int32)
            _set_attrs(dset, var.attrs, data.dtype)
            created.append((dset, var.dims, name))
        for dset, vdims, name in created:
            for i, d in enumerate(vdims):
                if not (vdims == (name,) and d == name):
                    dset.dims[i].attach_scale(scales[str(d)])
        _set_attrs(f, attrs)
