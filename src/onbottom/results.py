"""Result conventions: variable names and units, provenance, kill-safe result files.

Every xarray Dataset that onbottom returns takes the ``long_name`` and ``units`` of its
variables from :data:`VARIABLES` (add an entry when you add a variable) and carries
provenance attributes made by :func:`provenance`.

Kill-safe files: every result file is written under a temporary name and renamed
when complete (:func:`save_dataset`, :func:`write_text_atomic`, :func:`write_csv_atomic`,
:func:`save_figure`), so a file under its final name is always whole; a NetCDF result carries
``run_status = "complete"`` (``"partial"`` in the growing file of a chunked writer, which never
carries the final name) and :func:`load_dataset` refuses a partial or unreadable file by name.
Runs that resume hash their inputs into a *run identity* (:func:`identity_hash`); runs of many
independent tasks keep each finished task in a :class:`TaskStore` (one small JSON file per
task) so an interrupted run resumes without repeating them.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import hashlib
import json
import logging
import os
import re
import tempfile
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from onbottom._version import __version__, content_hash, git_commit
from onbottom.errors import InputError, ResultFileError

__all__ = [
    "IN_MEMORY_MAX_BYTES",
    "LEGACY_NAMES",
    "RESTART_ADVICE",
    "RUN_STATUS_COMPLETE",
    "RUN_STATUS_PARTIAL",
    "VARIABLES",
    "OutputSet",
    "RunIdentity",
    "TaskStore",
    "annotate",
    "atomic_write",
    "check_result_file",
    "checksum_json",
    "clean_stale_temporaries",
    "identity_hash",
    "load_dataset",
    "provenance",
    "run_identity",
    "save_dataset",
    "save_figure",
    "upgrade_names",
    "verify_json_checksum",
    "write_csv_atomic",
    "write_text_atomic",
]

logger = logging.getLogger(__name__)

RUN_STATUS_COMPLETE = "complete"
"""``run_status`` attribute of a finished result file."""
RUN_STATUS_PARTIAL = "partial"
"""``run_status`` attribute of the growing file of an interrupted or running chunked writer."""

RESTART_ADVICE = (
    "rerun with --restart to discard it and start afresh (Python: delete the file, or pass"
    " resume='never' / restart=True)"
)

VARIABLES: dict[str, tuple[str, str]] = {
    # name: (long_name, units)
    "time": ("time", "s"),
    # one name per quantity (docs/conventions.md): y lateral, z penetration (0.1: u, w)
    "y": ("lateral displacement of the pipe section", "m"),
    "y_dot": ("lateral velocity of the pipe section", "m/s"),
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
    # storm section
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


LEGACY_NAMES: dict[str, str] = {"u": "y", "u_dot": "y_dot", "w": "z"}
"""Variable names of onbottom 0.1 results and their names since (``docs/conventions.md``).

0.1 wrote the centrifuge section's results (``simulate_section``), the soil path response
(``path_response``) and calibration test records with ``u`` (lateral displacement),
``u_dot`` (its velocity) and ``w`` (penetration); every result now says ``y``, ``y_dot``
and ``z``, as the storm section, the pipeline and DNV-RP-F109 do."""


def upgrade_names(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with the 0.1 variable names (:data:`LEGACY_NAMES`) renamed; ``ds`` if none.

    Applied by :func:`load_dataset` (and the test-record reader), so a file written by 0.1
    opens with today's names. Only a dataset holding the 0.1 lateral displacement ``u``
    is renamed (the DEM penetration records keep their paper's ``w``, and have no ``u``); a
    name already taken is left alone. The renamed dataset says so in its attribute
    ``renamed_variables`` (``"u->y, w->z"``) and in an INFO log line — a note, not a
    warning: the file is valid and nothing needs doing.
    """
    if "u" not in ds.variables:
        return ds
    renames = {
        old: new
        for old, new in LEGACY_NAMES.items()
        if old in ds.variables and new not in ds.variables
    }
    if not renames:
        return ds
    out = ds.rename(renames)
    for new in renames.values():
        if new in VARIABLES:
            out[new].attrs["long_name"] = VARIABLES[new][0]
    note = ", ".join(f"{old}->{new}" for old, new in renames.items())
    out.attrs["renamed_variables"] = note
    logger.info("opened a result written by onbottom 0.1: variables renamed %s", note)
    return out


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

    Besides the version, the attributes hold ``onbottom_content_hash`` (the SHA-256 of the
    package's source and data files, :func:`onbottom._version.content_hash`: the version
    string alone does not change between commits) and, from a git checkout,
    ``onbottom_git_commit``.
    """
    attrs: dict[str, Any] = {
        "onbottom_version": __version__,
        "onbottom_content_hash": content_hash(),
        "model": model,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
    }
    commit = git_commit()
    if commit:
        attrs["onbottom_git_commit"] = commit
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


def _named_os_error(exc: OSError, path: Path) -> OSError:
    """``exc`` as an ``OSError`` naming ``path`` (the final name, not the temporary one) and
    the system's short reason (``No space left on device``), for a one-line message."""
    errno_ = exc.errno if isinstance(exc.errno, int) else None
    reason = os.strerror(errno_) if errno_ else (str(exc).splitlines()[0] or type(exc).__name__)
    err = OSError(errno_, f"cannot write it: {reason}; nothing was written under that name")
    err.filename = str(path)
    return err


class OutputSet:
    """Result files written together: each under a temporary name, all renamed at the end.

    A writer given ``group=`` (:func:`write_text_atomic`, :func:`save_dataset`, …) writes its
    temporary file and leaves it; :meth:`commit` renames them all (``with OutputSet() as g:``
    commits on success). If any write fails (a full disk), :meth:`discard` removes every
    temporary file: no file of the set appears under its final name, so a half-written set
    never looks complete.
    """

    def __init__(self) -> None:
        self._pending: list[tuple[str, Path]] = []

    def add(self, tmp: str, path: Path) -> None:
        self._pending.append((tmp, path))

    def commit(self) -> list[Path]:
        """Rename every temporary file to its final name; returns the final names."""
        done = []
        for tmp, path in self._pending:
            os.replace(tmp, path)
            done.append(path)
        self._pending = []
        return done

    def discard(self) -> None:
        """Remove every temporary file not yet renamed."""
        for tmp, _ in self._pending:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        self._pending = []

    def __enter__(self) -> OutputSet:
        return self

    def __exit__(self, exc_type: Any, *exc: Any) -> None:
        if exc_type is None:
            self.commit()
        else:
            self.discard()


def _atomic_write(path: Path, write: Any, group: OutputSet | None = None) -> Path:
    """Call ``write(tmp)`` on a temporary file beside ``path``, then rename it to ``path``.

    The file gets the permissions of a normally created file (0666 less the umask, 0644 with
    the usual umask 022), not the 0600 of a temporary file; the folder is created if needed.
    With ``group`` the rename waits for ``group.commit()``. A write that fails (a full disk)
    removes the temporary file and raises ``OSError`` naming ``path``.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    clean_stale_temporaries(path)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    os.close(fd)
    keep = False
    try:
        try:
            write(tmp)
            os.chmod(tmp, 0o666 & ~_umask())
            if group is None:
                os.replace(tmp, path)
            else:
                group.add(tmp, path)
                keep = True
        except OSError as exc:
            raise _named_os_error(exc, path) from None
    finally:
        if not keep and os.path.exists(tmp):
            os.unlink(tmp)
    return path


def atomic_write(path: str | os.PathLike, write: Any, *, group: OutputSet | None = None) -> Path:
    """Call ``write(tmp)`` on a temporary file beside ``path``, then rename it to ``path``.

    For writers the helpers below do not cover (a GIF, a binary format); ``tmp`` ends in
    ``.tmp``. The folder is created if needed; a temporary file left by a killed writer is
    removed the next time the same file is written. ``group``: an :class:`OutputSet` that
    renames it with the others.
    """
    return _atomic_write(Path(path), write, group)


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

    A dataset held in memory (no dask arrays) is written through xarray's h5netcdf store
    without the write lock: ``Dataset.to_netcdf`` asks dask for its scheduler on every call,
    which imports ``distributed`` on the first (more CPU than the integration of a 3.5-h storm).
    The file is the same.

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

    def dump(target: Any) -> None:
        from xarray.backends import H5NetCDFStore

        store = H5NetCDFStore.open(target, mode="w", lock=False)
        try:
            out.dump_to_store(store, encoding=encoding)
        finally:
            store.close()

    if out.nbytes > IN_MEMORY_MAX_BYTES:
        return _atomic_write(Path(path), dump, group)

    def write(tmp: str) -> None:
        import io

        buf = io.BytesIO()
        dump(buf)
        with open(tmp, "wb") as fh:
            fh.write(buf.getbuffer())

    return _atomic_write(Path(path), write, group)


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


def write_text_atomic(
    path: str | os.PathLike, text: str, *, group: OutputSet | None = None
) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically, as :func:`save_dataset`."""
    return _atomic_write(
        Path(path), lambda tmp: Path(tmp).write_text(text, encoding="utf-8"), group
    )


def write_csv_atomic(
    path: str | os.PathLike,
    rows: Sequence[Mapping[str, Any]],
    fieldnames: Sequence[str],
    *,
    group: OutputSet | None = None,
) -> Path:
    """Write ``rows`` as a CSV table (header ``fieldnames``) atomically."""
    import csv

    def write(tmp: str) -> None:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.DictWriter(fh, fieldnames=list(fieldnames))
            w.writeheader()
            w.writerows(rows)

    return _atomic_write(Path(path), write, group)


def save_figure(
    fig: Any, path: str | os.PathLike, *, group: OutputSet | None = None, **savefig_kw: Any
) -> Path:
    """``fig.savefig(path, **savefig_kw)`` atomically (the format follows the suffix)."""
    p = Path(path)
    fmt = savefig_kw.pop("format", None) or (p.suffix[1:].lower() or None)
    return _atomic_write(p, lambda tmp: fig.savefig(tmp, format=fmt, **savefig_kw), group)


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
    marked ``run_status = "partial"`` is refused unless ``allow_partial``). A file written by
    onbottom 0.1 opens with today's variable names (:func:`upgrade_names`).
    """
    check_result_file(path, allow_partial=allow_partial)
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            return upgrade_names(ds.load())
    except FileNotFoundError:
        raise
    except Exception as exc:  # any damage: never a traceback
        raise _unreadable(path, exc, "result file", None, None) from None


# ---------------------------------------------------------------------------------------------
# run identity and per-task stores
# ---------------------------------------------------------------------------------------------
_ADDRESS = re.compile(r" at 0x[0-9a-fA-F]+")


def identity_hash(meta: Any, *arrays: Any) -> str:
    """SHA-256 (hex) of ``meta`` as canonical JSON, then of the bytes of ``arrays``.

    The run identity of every resumable result: ``meta`` holds the inputs (JSON-able; other
    objects count by ``str``, memory addresses removed), ``arrays`` large numeric inputs
    (hashed by their bytes in C order). Equal inputs give equal hashes in any process.
    """
    h = hashlib.sha256()
    text = json.dumps(meta, sort_keys=True, default=str)
    h.update(_ADDRESS.sub("", text).encode())
    for a in arrays:
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


@dataclass(frozen=True)
class RunIdentity:
    """The identity of a resumable run (checkpoint, chunk files, result file).

    ``fields``: the inputs that determine the run (JSON-able; written to files where they are
    compared field by field, as the DEM does); ``digest``: :func:`identity_hash` of the fields
    and the large arrays (written as ``run_id``, as the pipeline does).
    """

    fields: dict[str, Any]
    digest: str

    @property
    def fingerprint(self) -> str:
        """The first 16 hex digits of :attr:`digest` (a short name for a file's attributes)."""
        return self.digest[:16]


def run_identity(fields: Mapping[str, Any], *arrays: Any) -> RunIdentity:
    """The run identity of every resumable solver: the pipeline FE and the DEM.

    ``fields``: the inputs (model, settings, versions, …) as a JSON-able mapping; ``arrays``:
    large numeric inputs hashed by their bytes (kinematics). One function, one format:
    :class:`RunIdentity` (fields + sha256 digest). The fields get ``onbottom_content``, the
    package's content hash (:func:`onbottom._version.content_hash`), unless they hold it:
    a checkpoint or result of other code is another run.
    """
    meta = dict(fields)
    meta.setdefault("onbottom_content", content_hash())
    return RunIdentity(fields=meta, digest=identity_hash(meta, *arrays))


CHECKSUM_KEY = "checksum"
"""Key of the SHA-256 that seals a JSON result file (:func:`checksum_json`)."""


def _canonical_digest(doc: Mapping[str, Any]) -> str:
    body = {k: v for k, v in doc.items() if k != CHECKSUM_KEY}
    text = json.dumps(body, sort_keys=True, allow_nan=True)
    return "sha256:" + hashlib.sha256(text.encode()).hexdigest()


def checksum_json(doc: Mapping[str, Any], *, default: Any = None, indent: int | None = 1) -> str:
    """The JSON text of ``doc`` sealed with a checksum (key ``"checksum"``).

    The checksum is the SHA-256 of the document's canonical JSON (sorted keys) as it reads
    back; :func:`verify_json_checksum` recomputes it, so a file edited by hand (a result
    changed, a key removed) is told apart from one onbottom wrote. ``default``: as
    :func:`json.dumps` (objects JSON cannot encode).
    """
    obj = json.loads(json.dumps(dict(doc), default=default, allow_nan=True))
    obj.pop(CHECKSUM_KEY, None)
    obj[CHECKSUM_KEY] = _canonical_digest(obj)
    return json.dumps(obj, indent=indent, allow_nan=True)


def verify_json_checksum(doc: Mapping[str, Any]) -> bool | None:
    """True when the checksum of a JSON document read back (``json.loads`` of
    :func:`checksum_json`'s text) matches its content, False when it does not (the file was
    edited), None when the document carries none (written before checksums existed)."""
    got = doc.get(CHECKSUM_KEY)
    if got is None:
        return None
    return got == _canonical_digest(doc)


def _task_name(key: Any) -> str:
    text = json.dumps(key, sort_keys=True, default=str)
    safe = re.sub(r"[^A-Za-z0-9._=-]+", "_", text).strip("_")[:60]
    return f"{safe}-{hashlib.sha256(text.encode()).hexdigest()[:12]}.json"


class TaskStore:
    """Finished tasks of a run of many independent tasks: one small JSON file per task.

    Each finished task is written (atomically) to ``folder/<key>.json`` with its result and
    the task's run identity (:func:`identity_hash` of the run's ``identity`` and the task
    key), the moment it finishes; a run interrupted at any moment (Ctrl-C, kill -9) resumes
    with :meth:`load`, which returns the tasks already done. A file of another run (other
    inputs) or an unreadable one is a :class:`~onbottom.errors.ResultFileError` with the
    ``--restart`` advice; ``restart=True`` empties the folder first. :meth:`remove` deletes
    the folder once the run's result file is written.

    Parameters
    ----------
    folder : path
        The store (created on the first :meth:`put`).
    identity : any
        JSON-able inputs of the run (e.g. the case file's text and the options).
    restart : bool
        Discard what the folder holds.
    what : str
        Name of a task in messages ("seed", "curve point").
    """

    def __init__(
        self, folder: str | os.PathLike, identity: Any, *, restart: bool = False, what="task"
    ):
        self.folder = Path(folder)
        self.identity = identity_hash(
            {"onbottom_version": __version__, "onbottom_content": content_hash(), "run": identity}
        )
        self.what = what
        if self.folder.exists() and not self.folder.is_dir():
            raise ResultFileError(
                f"task store {str(self.folder)!r} is invalid: it is a file, expected a folder;"
                f" {RESTART_ADVICE}",
                field="output",
            )
        if restart:
            self.clear()

    def _task_identity(self, key: Any) -> str:
        return identity_hash({"run": self.identity, "task": key})

    def _files(self) -> list[Path]:
        return sorted(self.folder.glob("*.json")) if self.folder.is_dir() else []

    def load(self, keys: Iterable[Any]) -> dict[int, Any]:
        """``{index in keys: result}`` of the tasks of ``keys`` already finished."""
        out: dict[int, Any] = {}
        for i, key in enumerate(keys):
            f = self.folder / _task_name(key)
            if not f.exists():
                continue
            try:
                doc = json.loads(f.read_text(encoding="utf-8"))
                ident, result = doc["identity"], doc["result"]
            except (OSError, ValueError, KeyError, TypeError) as exc:
                raise ResultFileError(
                    f"{self.what} file {str(f)!r} is unreadable ({type(exc).__name__});"
                    f" {RESTART_ADVICE}",
                    field="output",
                ) from None
            if verify_json_checksum(doc) is False:
                raise ResultFileError(
                    f"{self.what} file {str(f)!r} was changed after onbottom wrote it (its"
                    f" checksum does not match its content); {RESTART_ADVICE}",
                    field="output",
                )
            if ident != self._task_identity(key):
                raise ResultFileError(
                    f"{self.what} file {str(f)!r} belongs to another run (its run identity"
                    f" {str(ident)[:12]}… differs from {self._task_identity(key)[:12]}…: other"
                    f" inputs); {RESTART_ADVICE}, or give another --output",
                    field="output",
                )
            out[i] = result
        return out

    def put(self, key: Any, result: Any) -> Path:
        """Record the finished task ``key`` (atomic write of one small file)."""
        doc = {"identity": self._task_identity(key), "key": key, "result": result}
        text = checksum_json(doc, default=_json_default, indent=None)
        return write_text_atomic(self.folder / _task_name(key), text)

    def clear(self) -> None:
        """Remove every task file (and temporaries) of the folder."""
        if not self.folder.is_dir():
            return
        for f in list(self.folder.glob("*.json")) + list(self.folder.glob("*.tmp")):
            f.unlink(missing_ok=True)

    def remove(self) -> None:
        """Delete the folder and its task files (after the run's result is written)."""
        TaskStore.delete(self.folder)

    @staticmethod
    def delete(folder: str | os.PathLike) -> None:
        """Delete the task files of ``folder`` (and the folder when nothing else is in it)."""
        f = Path(folder)
        if not f.is_dir():
            return
        for x in list(f.glob("*.json")) + list(f.glob("*.tmp")):
            x.unlink(missing_ok=True)
        try:
            f.rmdir()
        except OSError:
            pass  # something else lives there: leave it


def _json_default(obj: Any) -> Any:
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating):
        return float(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    return str(obj)
