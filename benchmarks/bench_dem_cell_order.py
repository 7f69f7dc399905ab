"""Cell order against the order a compaction leaves, paired, wall clock, all threads.

``bench_dem.py --cell-order`` measures one thread per CPU-second; this measures what a case
sees: a prepared specimen (``--sample``, one written with ``Numerics.sort_disks`` off, e.g.
``dem_full_case.py`` output of an older run) stepped as in a compaction (gravity off,
frictionless disks, the lid moving down at the preset's speed) as numbered and renumbered in
cell order, alternated ``--repeat`` times, printing particle-steps per wall-clock second with
the load average.

Run::

    python benchmarks/bench_dem_cell_order.py --sample runs/smdr48_s4/SM-Dr48_seed4_sample.nc
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np

from onbottom.dem.config import PRESETS, ContactParameters
from onbottom.dem.engine import Simulation, step_sizes
from onbottom.dem.sample import Sample


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sample")
    ap.add_argument("--preset", default="SM-Dr48", choices=sorted(PRESETS))
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        import tempfile

        from _smoke import tiny_lattice_sample

        args.steps, args.repeat = 5, 1
        args.sample = args.sample or tiny_lattice_sample(tempfile.mkdtemp())
    elif args.sample is None:
        ap.error("--sample is required")
    cfg = PRESETS[args.preset]
    s0 = Sample.load(args.sample)
    soil = cfg.contacts.soil
    frictionless = ContactParameters(soil.k_n, soil.k_s, 0.0, 0.0)
    m_min = cfg.material.density * math.pi * float(s0.radii.min()) ** 2
    dt, _ = step_sizes(cfg.contacts, m_min, cfg.numerics.dt_safety, False)
    rates: dict[str, list[float]] = {}
    for rep in range(args.repeat):
        for mode in ("as numbered", "cell order"):
            s = s0 if mode == "as numbered" else s0.permuted(s0.cell_order())
            sim = Simulation(
                s,
                cfg.contacts,
                density=cfg.material.density,
                damping=cfg.material.damping,
                dt=dt,
                skin=cfg.numerics.skin_ratio * float(2.0 * s.radii.min()),
                gravity=(0.0, 0.0),
            )
            sim.set_soil_contact(frictionless)
            top = float(np.max(sim.pos[:, 1] + sim.rad))
            sim.set_lid(top + 1e-4, -cfg.preparation.lid_speed, stop=top - 2e-4)
            sim.run(50)
            t0 = time.perf_counter()
            sim.run(args.steps)
            rate = args.steps * sim.n / (time.perf_counter() - t0)
            rates.setdefault(mode, []).append(rate)
            print(
                f"{rep} {mode}: {rate:.3g} particle-steps/s, {sim.threads} threads,"
                f" load {os.getloadavg()[0]:.2f}",
                flush=True,
            )
    for mode, r in rates.items():
        print(f"{mode}: best {max(r):.3g}, median {float(np.median(r)):.3g} particle-steps/s")


if __name__ == "__main__":
    main()
