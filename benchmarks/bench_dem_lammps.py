"""Speed of the LAMMPS backend: particle-steps per second for a settled bed, 1 and 2 MPI ranks.

Usage::

    python benchmarks/bench_dem_lammps.py                 # 60k disks (as the paper's SM)
    python benchmarks/bench_dem_lammps.py --disks 15000   # a smaller bed
    python benchmarks/bench_dem_lammps.py --sample bed.nc # a bed saved with Sample.save
    python benchmarks/bench_dem_lammps.py --ranks 1 2 4 --steps 4000

Without ``--sample`` the bed is the paper's box width (13D, D = 20 mm) filled with 60,000
disks of the paper's grading (d50 = 0.68 mm, Cu = 1.67, uniform by number) on a hexagonal
lattice of pitch d_max, let settle under 25 g for ``--settle`` steps, then timed. Such a bed
is dense (3–5 contacts per disk) but still compacting slowly, so it rebuilds its neighbour
lists more often than a fully settled specimen: the figure is conservative. For the exact
settled specimen, pass ``--sample`` with a bed from ``onbottom.dem.preparation``. The figure
is LAMMPS's own "Loop time" of the timed run (set-up and file I/O excluded), with the pipe
present (parked one diameter above the bed).
"""

from __future__ import annotations

import argparse
import math
import re
import tempfile
from pathlib import Path

import numpy as np

from onbottom.dem import lammps_backend as lb
from onbottom.dem.config import SM
from onbottom.dem.sample import Sample


def lattice_bed(n_disks: int, seed: int = 0) -> Sample:
    """About ``n_disks`` disks of the SM grading on a hexagonal lattice of pitch d_max.

    The box has the paper's width (13D); the height follows from the number of disks (the
    lattice is looser than the paper's specimen, so 60k disks stand higher than 5.5D).
    """
    g, psd = SM.geometry, SM.psd
    width = g.width
    pitch = psd.d_max * 1.001
    ncol = int(width / pitch)
    rng = np.random.default_rng(seed)
    xs, ys = [], []
    row, n = 0, 0
    while n < n_disks:
        off = 0.5 * pitch if row % 2 else 0.0
        n_here = min(ncol - (1 if row % 2 else 0), n_disks - n)
        xs.append(0.5 * pitch + off + pitch * np.arange(n_here))
        ys.append(np.full(n_here, 0.5 * pitch + row * pitch * math.sqrt(3) / 2))
        n += n_here
        row += 1
    pos = np.column_stack([np.concatenate(xs), np.concatenate(ys)])
    radii = 0.5 * psd.sample_diameters(pos.shape[0], rng)
    height = float(pos[:, 1].max() + pitch)
    return Sample(positions=pos, radii=radii, box=(0.0, width, 0.0, height))


def loop_rate(log_path: Path) -> tuple[float, int, int, int]:
    """(seconds, ranks, steps, atoms) of the longest run ('Loop time' line) in a LAMMPS log."""
    pat = re.compile(r"Loop time of ([\d.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
    hits = pat.findall(log_path.read_text())
    sec, procs, steps, atoms = max(hits, key=lambda h: int(h[2]))
    return float(sec), int(procs), int(steps), int(atoms)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--disks", type=int, default=60_000, help="number of disks of the bed")
    ap.add_argument("--sample", type=Path, help="a settled bed saved with Sample.save")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--settle", type=int, default=3000, help="settling steps before timing")
    ap.add_argument("--steps", type=int, default=2000, help="timed steps")
    args = ap.parse_args()

    sample = Sample.load(args.sample) if args.sample else lattice_bed(args.disks)
    park = -SM.geometry.pipe_diameter  # pipe one diameter above the surface, at rest
    base = lb.LammpsPenetrationCase.from_config(
        SM, sample, pipe_start_embedment=park, final_embedment=park
    )
    print(
        f"bed: {sample.n} disks, box {sample.width * 1e3:.0f} mm wide, dt = {base.dt:.3g} s; "
        f"{args.settle} settling steps, then {args.steps} timed steps"
    )
    with tempfile.TemporaryDirectory() as tmp:
        # settle once (1 rank), then time every rank count from the same settled state
        pre = lb.LammpsPenetrationCase.from_config(
            SM,
            sample,
            settle_time=args.settle * base.dt,
            pipe_start_embedment=park,
            final_embedment=park,
            surface_y=base.surface_y,
        )
        settled = lb.run_lammps_case(pre, Path(tmp) / "settle", mode="subprocess")
        if not settled.success:
            raise SystemExit(settled.message)
        bed = settled.final_sample
        for ranks in args.ranks:
            case = lb.LammpsPenetrationCase.from_config(
                SM,
                bed,
                settle_time=args.steps * base.dt,
                pipe_start_embedment=park,
                final_embedment=park,
                surface_y=base.surface_y,
                dt=base.dt,
            )
            res = lb.run_lammps_case(case, Path(tmp) / f"np{ranks}", n_procs=ranks)
            if not res.success:
                print(f"{ranks} rank(s): failed: {res.message[:300]}")
                continue
            sec, procs, steps, atoms = loop_rate(res.deck.directory / "log.lammps")
            rate = atoms * steps / sec
            print(
                f"{procs} MPI rank(s): {steps} steps x {atoms} disks in {sec:.2f} s "
                f"-> {rate:.3g} particle-steps/s ({rate / procs:.3g} per rank)"
            )


if __name__ == "__main__":
    main()
