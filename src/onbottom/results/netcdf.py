"""NetCDF result files: atomic writes with ``run_status``, checked reads.

:func:`save_dataset` writes a dataset under a temporary name and renames it, with the
attribute ``run_status = "complete"`` (``"partial"`` in the growing file of a chunked writer,
which never carries the final name); :func:`load_dataset` and :func:`check_result_file` refuse
a partial or unreadable file by name.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import xarray as xr

from onbottom.errors import InputError, ResultFileError
from onbottom.results import _nc4write
from onbottom.results.files import OutputSet, _atomic_write

__all__ = [
    "IN_MEMORY_MAX_BYTES",
    "RESTART_ADVICE",
    "RUN_STATUS_COMPLETE",
    "RUN_STATUS_PARTIAL",
    "check_result_file",
    "load_dataset",
    "netcdf_encoding",
    "save_dataset",
]

RUN_STATUS_COMPLETE = "complete"
"""``run_status`` attribute of a finished result file."""
RUN_STATUS_PARTIAL = "partial"
"""``run_status`` attribute of the growing file of an interrupted or running chunked writer."""

RESTART_ADVICE = (
    "rerun with --restart to discard it and start afresh (Python: delete the file, or pass"
    " resume='never' / restart=True)"
)


def save_dataset(
    ds: xr.Dataset,
    path: str | os.PathLike,
    *,
    run_status: str = RUN_STATUS_COMPLETE,
    compression_level: int = 0,
    group: OutputSet | None = None,
) -> Path:
    """Write ``ds`` to NetCDF atomically (temporary file in the same folder, then rename).

    A reader never sees a half-written file, even if the process is killed mid-write; a
    temporary file left by a killed writer is removed the next time the same file is written.
    The file carries the attribute ``run_status`` (default ``"complete"``; ``ds`` itself is
    not modified). Permissions: 0666 less the umask (0644 usually); the folder is created if
    needed. ``compression_level``: zlib (deflate) level of every data variable, 0 (none,
    default) to 9 (:func:`netcdf_encoding`).

    A dataset held in memory (no dask arrays) of numeric variables is written by a direct
    NetCDF-4 writer (:mod:`onbottom.results._nc4write`: the same file layout, attributes and
    encoding as xarray's h5netcdf store, which spends most of a storm record's write in
    per-variable bookkeeping; deflate by ISA-L when the ``isal`` package is installed); other
    in-memory datasets through xarray's h5netcdf store without the write lock
    (``Dataset.to_netcdf`` asks dask for its scheduler on every call, which imports
    ``distributed`` on the first).

    A dataset under :data:`IN_MEMORY_MAX_BYTES` is built in memory and written to disk by
    Python: HDF5 failing to write (a full disk) can crash the interpreter when the broken
    file is closed (exit 139); here it is an ``OSError`` naming the file. ``group``: an
    :class:`OutputSet` that renames it with the others.
    """
    out = ds.assign_attrs(run_status=run_status)
    encoding = netcdf_encoding(out, compression_level)
    if out.chunks:
        return _atomic_write(
            Path(path),
            lambda tmp: out.to_netcdf(tmp, engine="h5netcdf", encoding=encoding),
            group,
        )
    dump = _direct_dump(out, encoding) if _nc4write.writable(out) else _store_dump(out, encoding)
    if out.nbytes > IN_MEMORY_MAX_BYTES:
        return _atomic_write(Path(path), dump, group)

    def write(tmp: str) -> None:
        import io

        buf = io.BytesIO()
        dump(buf)
        with open(tmp, "wb") as fh:
            fh.write(buf.getbuffer())

    return _atomic_write(Path(path), write, group)


def _direct_dump(ds: xr.Dataset, encoding: dict[str, dict[str, Any]]) -> Any:
    """Writer of ``ds`` by the direct NetCDF-4 writer (:mod:`onbottom.results._nc4write`)."""
    levels = {name: int(enc["complevel"]) for name, enc in encoding.items()}
    return lambda target: _nc4write.write_nc4(ds, target, levels)


def _store_dump(ds: xr.Dataset, encoding: dict[str, dict[str, Any]]) -> Any:
    """Writer of ``ds`` through xarray's h5netcdf store, without the write lock."""

    def dump(target: Any) -> None:
        from xarray.backends import H5NetCDFStore

        store = H5NetCDFStore.open(target, mode="w", lock=False)
        try:
            ds.dump_to_store(store, encoding=encoding)
        finally:
            store.close()

    return dump


IN_MEMORY_MAX_BYTES = 256 * 2**20
"""Datasets up to this size [bytes] are encoded in memory before the file is written."""


def netcdf_encoding(ds: xr.Dataset, compression_level: int) -> dict[str, dict[str, Any]]:
    """xarray encoding that deflates every data variable of ``ds`` at ``compression_level``.

    ``compression_level``: 0 (none: an empty encoding) to 9 [-]; zlib with the byte shuffle
    filter, as netCDF-4 readers expect. Raises :class:`~onbottom.errors.InputError` outside 0–9.
    """
    level = compression_level
    if isinstance(level, bool) or level not in range(10):
        raise InputError(
            f"compression_level = {compression_level!r} is invalid: an integer in [0, 9]"
        )
    if level == 0:
        return {}
    return {
        str(name): {"zlib": True, "complevel": level, "shuffle": True}
        for name, v in ds.data_vars.items()
        if v.ndim > 0
    }


def _unreadable(
    path: Any, exc: BaseException, what: str, field: str | None, advice: str | None
) -> ResultFileError:
    reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return ResultFileError(
        f"{what} {str(path)!r} is unreadable (corrupt, truncated or not a NetCDF result:"
        f" {reason})" + (f"; {advice}" if advice else ""),
        field=field,
    )


def check_result_file(
    path: str | os.PathLike,
    *,
    allow_partial: bool = False,
    what: str = "result file",
    field: str | None = None,
    advice: str | None = None,
) -> dict[str, Any]:
    """Attributes of the NetCDF result ``path``; refuse an unreadable or partial file by name.

    Raises :class:`~onbottom.errors.ResultFileError` (its ``field`` set to ``field``; None
    lets the caller name it) when the file cannot be opened as NetCDF, or when it carries
    ``run_status = "partial"`` (an interrupted run) and ``allow_partial`` is false; ``advice``
    (e.g. :data:`RESTART_ADVICE` where a run writes the file) ends the message. A file
    without ``run_status`` (written before the attribute existed) is accepted.
    """
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            attrs = dict(ds.attrs)
    except FileNotFoundError:
        raise
    except Exception as exc:  # any damage: never a traceback
        raise _unreadable(path, exc, what, field, advice) from None
    if attrs.get("run_status") == RUN_STATUS_PARTIAL and not allow_partial:
        raise ResultFileError(
            f"{what} {str(path)!r} is partial (run_status = 'partial': written by a run that"
            " was interrupted, not a result); run the command that writes it again to"
            " complete it" + (f"; {advice}" if advice else ""),
            field=field,
        )
    return attrs


def load_dataset(path: str | os.PathLike, *, allow_partial: bool = False) -> xr.Dataset:
    """Load a NetCDF result fully into memory; refuse an unreadable or partial file.

    Raises :class:`~onbottom.errors.ResultFileError` as :func:`check_result_file` (a file
    marked ``run_status = "partial"`` is refused unless ``allow_partial``).
    """
    check_result_file(path, allow_partial=allow_partial)
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            return ds.load()
    except FileNotFoundError:
        raise
    except Exception as exc:  # any damage: never a traceback
        raise _unreadable(path, exc, "result file", None, None) from None
