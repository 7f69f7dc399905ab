"""Speed of the LAMMPS backend: particle-steps per second for a settled bed, 1 and 2 MPI ranks.

Usage::

    python benchmarks/bench_dem_lammps.py                  # the bed of bench_dem.py (~60k)
    python benchmarks/bench_dem_lammps.py --polydisperse   # the paper's grading, 60k disks
    python benchmarks/bench_dem_lammps.py --sample bed.nc  # a bed saved with Sample.save
    python benchmarks/bench_dem_lammps.py --ranks 1 2 4 --steps 4000

Default bed: the one of ``benchmarks/bench_dem.py`` (onbottom's engine), so the figures
compare directly: ~60,000 equal disks (d = 0.74 mm) on a triangular lattice in the paper's
13D × 5.5D box, each touching its six neighbours with a 1e-4·r overlap, under 25 g with the
paper's contact parameters (Table 3), local damping 0.7, the pipe parked one diameter above.

``--polydisperse``: 60,000 disks of the paper's grading (d50 = 0.68 mm, Cu = 1.67) on a
hexagonal lattice of pitch d_max, let settle ``--settle`` steps under 25 g, then timed; that
bed is still compacting, so it rebuilds neighbour lists more often (conservative figure).

The figure is LAMMPS's own "Loop time" of the timed run (set-up and file I/O excluded). On a
shared machine other processes lower it; the load average is printed next to it.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import tempfile
from pathlib import Path

import numpy as np

from onbottom.dem import lammps_backend as lb
from onbottom.dem.config import SM
from onbottom.dem.sample import Sample


def equal_bed(width: float = 0.26, height: float = 0.11, d: float = 0.74e-3) -> Sample:
    """The bed of ``bench_dem.py``: equal disks on a triangular lattice, 1e-4·r overlaps."""
    h = d * math.sqrt(3.0) / 2.0
    rows = int((height - d) / h)
    cols = int((width - d) / d)
    pts = [
        ((c + 0.5 + 0.5 * (r % 2)) * d, 0.5 * d + r * h)
        for r in range(rows)
        for c in range(cols - (r % 2))
    ]
    pos = np.array(pts)
    return Sample(pos, np.full(len(pos), 0.5 * d * (1 + 1e-4)), (0.0, width, 0.0, height))


def graded_bed(n_disks: int, seed: int = 0) -> Sample:
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
    ap.add_argument("--polydisperse", action="store_true", help="graded bed (see above)")
    ap.add_argument("--disks", type=int, default=60_000, help="disks of the graded bed")
    ap.add_argument("--sample", type=Path, help="a settled bed saved with Sample.save")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--settle", type=int, default=None, help="settling steps before timing")
    ap.add_argument("--steps", type=int, default=2000, help="timed steps")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        import sys

        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from bench_dem import lattice_bed

        args.ranks, args.steps, args.settle = [1], 20, 0
        args.sample = None
        sample = lattice_bed(width=0.02, height=0.01)
    elif args.sample:
        sample = Sample.load(args.sample)
    elif args.polydisperse:
        sample = graded_bed(args.disks)
    else:
        sample = equal_bed()
    if args.settle is None:
        args.settle = 3000 if args.polydisperse else 0
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
        bed = sample
        if args.settle > 0:
            settled = lb.run_lammps_case(pre, Path(tmp) / "settle", mode="subprocess")
            if not settled.success or settled.final_sample is None:
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
            load = os.getloadavg()[0]
            print(
                f"{procs} MPI rank(s): {steps} steps x {atoms} disks in {sec:.2f} s "
                f"-> {rate:.3g} particle-steps/s ({rate / procs:.3g} per rank); "
                f"load average {load:.1f} on {os.cpu_count()} cores"
            )


if __name__ == "__main__":
    main()
