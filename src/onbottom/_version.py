"""Package version (single source: pyproject.toml) and the package's content hash.

The version string alone does not say what made a result (it stays the same across commits),
so every result and every run identity also carries :func:`content_hash`: a SHA-256 of the
installed package's own files (sources and package data), the same for a checkout and for a
wheel built from it. :func:`git_commit` adds the commit when running from a git checkout.
:func:`file_hash` is the content hash of a data file a run reads (curve sweeps, coefficient
tables, hindcasts, storm series).
"""

from __future__ import annotations

import hashlib
import os
from functools import cache
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

try:
    __version__ = version("onbottom")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.1.0+unknown"

__all__ = [
    "__version__",
    "code_hash",
    "content_hash",
    "file_hash",
    "git_commit",
    "package_files",
    "short_hash",
]

PACKAGE_ROOT = Path(__file__).resolve().parent
"""The folder of the imported ``onbottom`` package (``src/onbottom`` or site-packages)."""

_SKIP_DIRS = {"__pycache__"}
_SKIP_SUFFIXES = (".pyc", ".pyo", ".nbi", ".nbc", ".tmp", ".lock", ".swp", "~")


def package_files(root: str | os.PathLike | None = None) -> list[str]:
    """Relative paths (``/``-separated, sorted) of the files :func:`content_hash` covers.

    Every file under the package folder ``root`` (default: this package) except caches and
    transient files: ``__pycache__`` folders, hidden files and folders, compiled bytecode,
    numba's cache files, temporary files (``*.tmp``), lock and editor files.
    """
    base = PACKAGE_ROOT if root is None else Path(root)
    out = []
    for folder, dirs, names in os.walk(base):
        dirs[:] = [d for d in dirs if d not in _SKIP_DIRS and not d.startswith(".")]
        for n in names:
            if n.startswith(".") or n.endswith(_SKIP_SUFFIXES):
                continue
            out.append(Path(folder, n).relative_to(base).as_posix())
    return sorted(out)


def _tree_hashes(root: Path) -> tuple[str, str]:
    """(all files, Python sources only) SHA-256 of :func:`package_files` under ``root``."""
    every, code = hashlib.sha256(), hashlib.sha256()
    for rel in package_files(root):
        data = (root / rel).read_bytes()
        head = rel.encode() + b"\0%d\0" % len(data)
        for h in (every, code) if rel.endswith(".py") else (every,):
            h.update(head)
            h.update(data)
    return every.hexdigest(), code.hexdigest()


@cache
def _hashes() -> tuple[str, str]:
    return _tree_hashes(PACKAGE_ROOT)


def content_hash() -> str:
    """SHA-256 (hex) of the installed package's source and data files (computed once).

    Sorted relative paths and bytes of :func:`package_files`: any edit of a module, a
    template or a package data file changes it; a wheel built from a checkout has the
    checkout's hash. About 10–20 ms, once per process, when first asked for.
    """
    return _hashes()[0]


def code_hash() -> str:
    """SHA-256 (hex) of the package's Python sources only (computed with
    :func:`content_hash`): the key of numba's cache folder (``onbottom._jit``), which a
    change of package data (curve sweeps, templates) does not touch."""
    return _hashes()[1]


def short_hash() -> str:
    """The first 16 hex digits of :func:`content_hash` (folder names, report lines)."""
    return content_hash()[:16]


@cache
def git_commit() -> str | None:
    """The commit checked out when running from a git checkout (``src/onbottom`` in a work
    tree), else None. Read from the ``.git`` files (no ``git`` process); None on anything
    unexpected (a packed or detached layout it cannot read is simply not reported)."""
    try:
        top = PACKAGE_ROOT.parent.parent
        git = top / ".git"
        if git.is_file():  # a linked work tree: "gitdir: <path>"
            line = git.read_text(encoding="utf-8").strip()
            if not line.startswith("gitdir:"):
                return None
            git = (top / line.split(":", 1)[1].strip()).resolve()
        if not git.is_dir():
            return None
        head = (git / "HEAD").read_text(encoding="utf-8").strip()
        if not head.startswith("ref:"):
            return head if len(head) == 40 else None
        ref = head.split(":", 1)[1].strip()
        common = git
        if (git / "commondir").is_file():
            common = (git / (git / "commondir").read_text(encoding="utf-8").strip()).resolve()
        for d in (git, common):
            f = d / ref
            if f.is_file():
                return f.read_text(encoding="utf-8").strip() or None
        packed = common / "packed-refs"
        if packed.is_file():
            for row in packed.read_text(encoding="utf-8").splitlines():
                parts = row.split()
                if len(parts) == 2 and parts[1] == ref:
                    return parts[0]
    except (OSError, ValueError, UnicodeDecodeError):
        return None
    return None


_FILE_HASHES: dict[tuple[str, int, int], str] = {}


def file_hash(path: str | os.PathLike) -> str:
    """SHA-256 (hex) of the bytes of the data file ``path`` (remembered per path, size and
    modification time within a process). Raises ``OSError`` when it cannot be read."""
    p = os.path.realpath(path)
    st = os.stat(p)
    key = (p, st.st_size, st.st_mtime_ns)
    got = _FILE_HASHES.get(key)
    if got is None:
        h = hashlib.sha256()
        with open(p, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
        got = _FILE_HASHES[key] = h.hexdigest()
    return got
