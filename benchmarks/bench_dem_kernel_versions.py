"""Time per step of two versions of the DEM engine on the same states, paired and alternated.

For a kernel change that must not change the results (issue #15's bitwise levers): the same
full-size states are stepped by the engine of this checkout and by the one of another source
tree (``--other-src``, for instance a ``git worktree`` of the commit before the change), in
separate processes, alternated ``--repeat`` times in ABBA order (use an even count) so that a
drift of the machine's rate hits both alike, and the end states are compared bit for bit.
Each state is one of

- ``compaction``: a compacted specimen stepped as in a compaction (gravity off, the lid moving
  down, the preset's preparation contacts, plain step);
- ``penetration``: a penetration checkpoint with the preset's numerics (sub-cycled or plain).

Prints ms per step, particle-steps/s and the ratio per state and thread count, with the load.

Run::

    git worktree add /tmp/old <commit>
    python benchmarks/bench_dem_kernel_versions.py --other-src /tmp/old/src \\
        --sample runs/smdr48_s6/SM-Dr48_seed6_sample.nc --preset SM-Dr48 \\
        --checkpoint runs/smdr48_s6/checkpoints/SM-Dr48_seed6_0.5051.nc
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

_CHILD = r"""
import json, math, sys, time
import numpy as np
from onbottom.dem import _kernels as K
from onbottom.dem.config import PRESETS, ContactParameters
from onbottom.dem.engine import Simulation, step_sizes
from onbottom.dem.sample import Sample
a = json.loads(sys.argv[1])
cfg = PRESETS[a["preset"]]
num = cfg.numerics
if a["state"] == "penetration":
    from onbottom.dem.experiment import _load_checkpoint
    sim, *_ = _load_checkpoint(a["path"], cfg, a["threads"])
    m_min = cfg.material.density * math.pi * float(sim.rad.min()) ** 2
    safety = num.subcycled_dt_safety if num.subcycle else num.dt_safety
    sim.prm[K.P_DT] = step_sizes(cfg.contacts, m_min, safety, num.subcycle)[0]
else:
    s = Sample.load(a["path"])
    s = Sample(s.positions, s.radii, s.box)
    m_min = cfg.material.density * math.pi * float(s.radii.min()) ** 2
    dt = step_sizes(cfg.contacts, m_min, num.dt_safety, False)[0]
    sim = Simulation(s, cfg.contacts, density=cfg.material.density,
                     damping=cfg.material.damping, dt=dt,
                     skin=num.skin_ratio * 2.0 * float(s.radii.min()), gravity=(0.0, 0.0),
                     threads=a["threads"])
    soil = cfg.contacts.soil  # the compaction's contacts: the preparation's friction, no rolling
    sim.set_soil_contact(ContactParameters(soil.k_n, soil.k_s, cfg.preparation.prep_friction, 0.0))
    top = float(np.max(s.positions[:, 1] + s.radii))
    sim.set_lid(top + 1e-5, -0.5, stop=top - 3e-4)
sim.run(50)
t0 = time.perf_counter()
sim.run(a["steps"])
wall = time.perf_counter() - t0
np.save(a["out"], np.concatenate([sim.pos.ravel(), sim.vel.ravel(), sim.om, sim.fsw.ravel()]))
print(json.dumps({"wall": wall, "n": sim.n, "nsub": sim.nsub}))
"""


def _run(src: Path, args: dict) -> dict:
    env = dict(os.environ, PYTHONPATH=str(src), OMP_WAIT_POLICY="PASSIVE")
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, json.dumps(args)],
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    if out.returncode != 0:
        raise SystemExit(f"the engine of {src} failed:\n{out.stderr[-3000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--other-src", type=Path, help="src/ of the other version (required)")
    ap.add_argument("--preset", default="SM-Dr48")
    ap.add_argument("--sample", type=Path, help="compacted specimen (.nc): compaction state")
    ap.add_argument("--checkpoint", type=Path, help="penetration checkpoint: penetration state")
    ap.add_argument("--steps", type=int, default=1500)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", default="2,1", help="comma-separated thread counts")
    ap.add_argument("--tmp", type=Path, default=Path("/tmp/bench_dem_kernel_versions"))
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    here = Path(__file__).resolve().parents[1] / "src"
    if args.smoke:  # this checkout against itself on a small lattice bed
        import tempfile

        from _smoke import tiny_lattice_sample

        args.tmp = Path(tempfile.mkdtemp(prefix="bench_dem_kernel_versions_"))
        args.other_src = args.other_src or here
        args.sample = args.sample or tiny_lattice_sample(args.tmp)
        args.steps, args.repeat, args.threads = 5, 2, "1"
    elif args.other_src is None:
        ap.error("--other-src is required")
    states = [("compaction", args.sample), ("penetration", args.checkpoint)]
    states = [(s, p) for s, p in states if p is not None]
    if not states:
        raise SystemExit("give --sample and/or --checkpoint")
    args.tmp.mkdir(parents=True, exist_ok=True)
    versions = {"this": here, "other": args.other_src.resolve()}
    print(f"this: {here}\nother: {versions['other']}\n{os.cpu_count()} cores")
    for state, path in states:
        for threads in (int(t) for t in args.threads.split(",")):
            best: dict[str, float] = {}
            for rep in range(args.repeat):
                # ABBA: the first version of a pair runs at another moment of a drifting
                # machine rate than the second; swapping the order every repeat cancels a
                # linear drift (on 2026-11-25 the rate rose 20 % over six runs of a series)
                order = list(versions.items())[:: -1 if rep % 2 else 1]
                for name, src in order:
                    out = args.tmp / f"{state}_{threads}_{name}.npy"
                    job = dict(
                        preset=args.preset, state=state, path=str(path), threads=threads,
                        steps=args.steps, out=str(out),
                    )  # fmt: skip
                    r = _run(src, job)
                    ms = 1e3 * r["wall"] / args.steps
                    best[name] = min(best.get(name, np.inf), ms)
                    print(
                        f"{state:11s} {threads} thr  rep {rep} {name:5s}: {ms:.3f} ms/step,"
                        f" {r['n'] / ms * 1e3:.3g} particle-steps/s (nsub {r['nsub']}),"
                        f" load {os.getloadavg()[0]:.2f}",
                        flush=True,
                    )
            a = np.load(args.tmp / f"{state}_{threads}_this.npy")
            b = np.load(args.tmp / f"{state}_{threads}_other.npy")
            same = "same bits" if np.array_equal(a, b) else "DIFFERENT results"
            print(
                f"best {state} {threads} thr: this {best['this']:.3f} ms, other"
                f" {best['other']:.3f} ms, ratio {best['other'] / best['this']:.2f}; {same}"
            )


if __name__ == "__main__":
    main()
