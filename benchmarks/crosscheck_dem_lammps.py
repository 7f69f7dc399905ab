"""Cross-check of a whole preset: onbottom's engine and LAMMPS on the same prepared specimen.

Usage::

    python benchmarks/crosscheck_dem_lammps.py --preset SD-reduced           # ~5 min here
    python benchmarks/crosscheck_dem_lammps.py --preset SM-reduced --sample sm.nc --np 2

The specimen is prepared by onbottom (``prepare_sample``; or loaded with ``--sample``), its
contact history is dropped (a LAMMPS data file cannot carry it) and both engines push the pipe
from first contact to the preset's final embedment (``penetrate`` and ``run_lammps_case``).
Prints V (model and prototype scale) at w/D = 0.05, 0.1, ..., 0.5 for both, windowed means,
and the wall-clock times. DEM runs are chaotic, so expect agreement of the windowed means
within the spread of repeated runs (see ``docs/theory/dem_lammps.md``), not point by point.
"""

from __future__ import annotations

import argparse
import itertools
import tempfile
import time
from pathlib import Path

import numpy as np

from onbottom.dem import experiment, lammps_backend, preparation
from onbottom.dem.config import PRESETS, get_preset
from onbottom.dem.sample import Sample


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--preset", choices=sorted(PRESETS), default="SD-reduced")
    ap.add_argument("--sample", type=Path, help="prepared specimen (Sample.save)")
    ap.add_argument("--save-sample", type=Path, help="save the prepared specimen here")
    ap.add_argument("--np", dest="n_procs", type=int, default=1, help="LAMMPS MPI ranks")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()

    config = get_preset(args.preset)
    if args.smoke:
        from _smoke import tiny_dem_config

        config = tiny_dem_config()
    t0 = time.perf_counter()
    sample = Sample.load(args.sample) if args.sample else preparation.prepare_sample(config)
    t_prep = time.perf_counter() - t0
    if args.save_sample:
        sample.save(args.save_sample)
    bed = Sample(sample.positions, sample.radii, sample.box, attrs=sample.attrs)  # no history
    D = config.geometry.pipe_diameter
    N = config.loading.gravity_factor
    print(f"{config.name}: {bed.n} disks (prepared in {t_prep:.0f} s)")

    t0 = time.perf_counter()
    ds_e = experiment.penetrate(config, bed, snapshots=())
    t_e = time.perf_counter() - t0
    case = lammps_backend.LammpsPenetrationCase.from_config(config, bed)
    with tempfile.TemporaryDirectory() as tmp:
        res = lammps_backend.run_lammps_case(case, tmp, n_procs=args.n_procs)
    if not res.success:
        raise SystemExit(res.message)
    ds_l = res.curve
    print(f"engine: {t_e:.0f} s; LAMMPS ({args.n_procs} rank(s)): {res.wall_time:.0f} s")
    print(f"{'w/D':>5} {'V engine':>12} {'V LAMMPS':>12}   (prototype kN/m = V·N/1e3, N = {N:g})")
    for r in np.arange(0.05, config.loading.final_embedment_ratio + 1e-9, 0.05):
        ve = np.interp(r * D, ds_e.w.values, ds_e.V.values) * N / 1e3
        vl = np.interp(r * D, ds_l.w.values, ds_l.V.values) * N / 1e3
        print(f"{r:5.2f} {ve:12.1f} {vl:12.1f}")
    print("windowed means (prototype kN/m):")
    edges = np.arange(0.0, config.loading.final_embedment_ratio + 1e-9, 0.1)
    for lo, hi in itertools.pairwise(edges):
        me = ds_e.V.values[(ds_e.w.values >= lo * D) & (ds_e.w.values < hi * D)].mean()
        ml = ds_l.V.values[(ds_l.w.values >= lo * D) & (ds_l.w.values < hi * D)].mean()
        print(
            f"  {lo:.1f}-{hi:.1f}D: engine {me * N / 1e3:8.1f}  LAMMPS {ml * N / 1e3:8.1f}"
            f"  ratio {ml / me:5.3f}"
        )


if __name__ == "__main__":
    main()
