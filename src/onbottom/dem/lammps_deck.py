"""Writing the LAMMPS deck: the experiment as LAMMPS sees it, its input file and data file.

Part of the optional LAMMPS backend (:mod:`onbottom.dem.lammps_backend`): the input deck
(``in.penetration``) and the data file holding the prepared specimen (``disks.data``) of a
:class:`~onbottom.dem.lammps_case.LammpsPenetrationCase`.

Mapping (see ``docs/theory/dem_lammps.md`` for the full table)
-------------------------------------------------------------
* ``units si``, ``dimension 2``, ``atom_style sphere``, ``boundary f fm p``.
* Disks of unit thickness: LAMMPS turns the data-file *density* into a mass with
  ``4/3·π·r³`` whatever the dimension, so the data file carries
  ``ρ_LAMMPS = ρ·π·r²·(1 m) / (4/3·π·r³) = 3ρ/(4r)``, which gives m = ρ·π·r²·1 m exactly;
  ``fix nve/sphere disc`` then uses I = ½·m·r².
* Soil–soil: ``pair_style granular`` with ``hooke k_n 0`` (no dashpot),
  ``tangential linear_history k_s 0 μ`` and ``rolling sds k_s 0 μ_r``. LAMMPS's SDS rolling
  spring acts on the rolling displacement ξ_r = ∫R̄·(ω_i − ω_j)×n dt with force k_roll·ξ_r and
  moment R̄·k_roll·ξ_r, capped at μ_roll·F_n in force (μ_roll·R̄·F_n in moment). With
  k_roll = k_s this is M_r = k_s·R̄²·Δθ, the PFC ``rrlinear`` law.
* Walls: ``fix wall/gran ... xplane`` / ``yplane`` with ``hooke k_n 0`` and the wall friction
  (μ = 0 in the paper); a rolling term only if the wall's μ_r > 0 (R̄ = r).
* Pipe: a ``region cylinder`` (``side out``, ``units box``) moved by an equal-style variable,
  used by ``fix wall/gran/region ... contacts``; the per-particle contact forces of that fix
  are summed (``compute reduce``) to get the force on the pipe, V = −ΣF_y (per metre).
* Local damping: ``fix damping/cundall α α`` (defined last, after gravity and the walls, so
  that it acts on the total unbalanced force and moment).
* ``fix gravity`` with an equal-style magnitude for the 1 g → N g ramp.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from onbottom.dem.lammps_case import LammpsContact, LammpsPenetrationCase

__all__ = ["LammpsDeck", "write_lammps_case"]


# --------------------------------------------------------------------------- deck writer
@dataclass(frozen=True)
class LammpsDeck:
    """Files of a written case.

    Attributes
    ----------
    directory
        Folder of the case.
    input
        The LAMMPS input script (``in.penetration``).
    data
        The data file with the disks (``disks.data``).
    curve
        Where the run writes the V–w curve (``curve.txt``).
    final
        Where the run writes the final particle state (``final.dump``).
    """

    directory: Path
    input: Path
    data: Path
    curve: Path
    final: Path


def _fmt(x: float) -> str:
    return repr(float(x))


def _contact_args(c: LammpsContact) -> str:
    """``hooke``/``tangential``/``rolling`` keywords of a granular model, no dashpots."""
    if c.mu > 0.0 and c.k_s > 0.0:
        tang = f"tangential linear_history {_fmt(c.k_s)} 0.0 {_fmt(c.mu)}"
    else:  # frictionless: no shear force at all
        tang = "tangential linear_nohistory 0.0 0.0"
    args = f"hooke {_fmt(c.k_n)} 0.0 damping velocity {tang}"
    if c.mu_r > 0.0 and c.k_s > 0.0:
        args += f" rolling sds {_fmt(c.k_s)} 0.0 {_fmt(c.mu_r)}"
    return args


def _write_data(case: LammpsPenetrationCase, path: Path, y_hi: float) -> None:
    """Data file for ``atom_style sphere`` with the 2D (unit-thickness) density convention."""
    n = case.n
    r = case.radii
    # LAMMPS: mass = density·4/3·π·r³ in any dimension → density for m = ρ·π·r²·1 m
    dens = case.masses / (4.0 / 3.0 * math.pi * r**3)
    ids = np.arange(1, n + 1)
    cols = np.column_stack(
        [ids, np.ones(n), 2.0 * r, dens, case.positions[:, 0], case.positions[:, 1], np.zeros(n)]
    )
    x0, x1, y0, _ = case.box
    with open(path, "w", encoding="ascii") as fh:
        fh.write("onbottom DEM specimen (disks of unit thickness; density = 3*rho/(4*r))\n\n")
        fh.write(f"{n} atoms\n1 atom types\n\n")
        fh.write(f"{_fmt(x0)} {_fmt(x1)} xlo xhi\n")
        fh.write(f"{_fmt(y0)} {_fmt(y_hi)} ylo yhi\n")
        fh.write("-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n")
        np.savetxt(fh, cols, fmt=["%d", "%d", "%.17g", "%.17g", "%.17g", "%.17g", "%.1f"])
        if case.velocities is not None or case.omega is not None:
            vel = np.zeros((n, 2)) if case.velocities is None else case.velocities
            om = np.zeros(n) if case.omega is None else case.omega
            vcols = np.column_stack([ids, vel[:, 0], vel[:, 1], np.zeros(n), np.zeros(n)])
            vcols = np.column_stack([vcols, np.zeros(n), om])
            fh.write("\nVelocities\n\n")
            np.savetxt(fh, vcols, fmt=["%d"] + ["%.17g"] * 6)


def write_lammps_case(case: LammpsPenetrationCase, directory: str | os.PathLike[str]) -> LammpsDeck:
    """Write the input deck and the data file of ``case`` into ``directory``.

    The deck is self-contained (relative file names): ``cd directory && lmp -in
    in.penetration`` or ``mpirun -np 4 lmp -in in.penetration`` runs it.
    """
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    deck = LammpsDeck(
        directory=d,
        input=d / "in.penetration",
        data=d / "disks.data",
        curve=d / "curve.txt",
        final=d / "final.dump",
    )
    x0, x1, y0, y_top = case.box
    D = case.pipe_diameter
    R = 0.5 * D
    yc0 = case.pipe_start_centre_y
    top = max(float(np.max(case.positions[:, 1] + case.radii)), y_top, yc0 + R)
    y_hi = top + 2.0 * D  # shrink-wrapped upwards (fm) if disks fly higher
    _write_data(case, deck.data, y_hi)

    g1 = case.gravity
    gN = case.gravity * case.gravity_factor
    n_ramp, n_settle, n_pen = case.n_ramp, case.n_settle, case.n_penetration
    n0 = n_ramp + n_settle  # step at which the pipe starts moving
    vel = case.pipe_velocity
    every = int(case.record_every)
    lines = [
        "# onbottom 2D DEM pipe penetration -- generated by onbottom.dem.lammps_backend",
        f"# case: {case.name}; {case.n} disks; dt = {case.dt:.6g} s",
        "units           si",
        "dimension       2",
        "boundary        f fm p",
        "atom_style      sphere",
        "atom_modify     map array",
        "comm_modify     vel yes",
        "newton          off",
        f"read_data       {deck.data.name}",
        "",
        "# soil-soil: linear normal spring (no dashpot), incremental shear spring capped at",
        "# mu*Fn, SDS rolling spring k_roll = k_s (M_r = k_s*Rbar^2*dtheta, cap mu_r*Rbar*Fn)",
        "pair_style      granular",
        f"pair_coeff      * * {_contact_args(case.soil)}",
        f"neighbor        {_fmt(case.skin)} bin",
        "neigh_modify    delay 0 every 1 check yes",
        f"timestep        {_fmt(case.dt)}",
        "",
        f"variable        g equal {_fmt(gN)}",
        "fix             grav all gravity v_g vector 0 -1 0",
        "",
        "# rigid walls: side walls and bottom (rolling term only if the wall mu_r > 0)",
        f"fix             wside all wall/gran granular {_contact_args(case.wall)}"
        f" xplane {_fmt(x0)} {_fmt(x1)}",
        f"fix             wbot all wall/gran granular {_contact_args(case.wall)}"
        f" yplane {_fmt(y0)} NULL",
        "",
        "# the pipe: a cylinder region (particles outside); the forces of step s use the",
        "# displacement v*(s-n0-1)*dt, as onbottom's engine (force first, then move)",
        f"variable        pdy equal -{_fmt(vel)}*(step-{n0 + 1})*(step>{n0 + 1})*dt",
        f"region          piperegion cylinder z {_fmt(case.pipe_x)} {_fmt(yc0)} {_fmt(R)} "
        "INF INF side out move NULL v_pdy NULL units box",
        f"fix             pipe all wall/gran/region granular {_contact_args(case.pipe)}"
        " region piperegion contacts",
        "compute         pipeforce all reduce sum f_pipe[2] f_pipe[3] f_pipe[1]",
        "variable        V equal -c_pipeforce[2]",
        "variable        H equal -c_pipeforce[1]",
        "variable        ncontact equal c_pipeforce[3]",
        f"variable        w equal {_fmt(case.pipe_start_embedment)}-v_pdy",
        "variable        t equal time",
        "compute         ke all ke  # translational only (erotate/sphere assumes spheres)",
        "",
        "fix             integrate all nve/sphere disc",
        "fix             planar all enforce2d",
        "# local (Cundall) damping last: it scales the total unbalanced force and moment",
        f"fix             damp all damping/cundall {_fmt(case.damping)} {_fmt(case.damping)}",
        "",
        "thermo_style    custom step time v_g v_w v_V c_ke",
        "thermo_modify   format float %.10g norm no lost error",
        f"thermo          {max(every * 50, 1000)}",
    ]
    if n_ramp > 0:
        lines += [
            "",
            f"# stage 1: gravity ramp 1 g -> {case.gravity_factor:g} g",
            f"variable        g equal {_fmt(g1)}*(1.0+{_fmt(case.gravity_factor - 1.0)}*ramp(0,1))",
            f"run             {n_ramp}",
            f"variable        g equal {_fmt(gN)}",
        ]
    if n_settle > 0:
        lines += [
            "",
            "# stage 2: settle at full gravity, pipe at rest",
            f"run             {n_settle}",
        ]
    if n_pen > 0:
        lines += [
            "",
            "# stage 3: penetration; record t, w, V, H and the number of pipe contacts",
            f"fix             curve all print {every} "
            '"${t} ${w} ${V} ${H} ${ncontact}" '
            f'file {deck.curve.name} screen no title "# time w V H n_contacts"',
            f"run             {n_pen}",
        ]
    lines += [
        "",
        f"write_dump      all custom {deck.final.name} id x y radius vx vy omegaz "
        "modify sort id format float %.17g",
    ]
    deck.input.write_text("\n".join(lines) + "\n", encoding="ascii")
    return deck
