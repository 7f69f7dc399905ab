"""Kill-safe result files: written under a temporary name, renamed when complete.

Every writer (:func:`atomic_write`, :func:`write_text_atomic`, :func:`write_csv_atomic`,
:func:`save_figure`, and :func:`onbottom.results.netcdf.save_dataset`) writes a temporary file
beside the final one and renames it, so a file under its final name is always whole; an
:class:`OutputSet` renames several files together.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

__all__ = [
    "OutputSet",
    "atomic_write",
    "clean_stale_temporaries",
    "glob_escape",
    "save_figure",
    "write_csv_atomic",
    "write_text_atomic",
]


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
