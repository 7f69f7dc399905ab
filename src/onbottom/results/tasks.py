"""Per-task result store of runs of many independent tasks (:class:`TaskStore`)."""

from __future__ import annotations

import hashlib
import json
import os
import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from onbottom._version import __version__, content_hash
from onbottom.errors import ResultFileError
from onbottom.results.files import write_text_atomic
from onbottom.results.identity import checksum_json, identity_hash, verify_json_checksum
from onbottom.results.netcdf import RESTART_ADVICE

__all__ = ["TaskStore"]


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
