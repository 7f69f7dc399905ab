"""Wall time of ``onbottom assess`` on the embedded default route (issue 32 item 7).

Goal (issue 32): the default route, all levels, 10 seeds, in <= 5 min on 2 cores. Prints the
wall time of the whole study (numba compilation in the workers included: the kernels are
cached on disk after the first run, so run it twice to see both), and per section its task
time and the storms it ran (base runs + bisection). ``--route N`` repeats the example's
sections to N sections (KP shifted) to see the scaling.

Measured (2026-11-26, 2 cores shared with other jobs, loaded): default route, wake model, 10
seeds, 2 workers: 227 s wall (sections 116 / 131 / 90 s, 138-164 storms each). 20 sections
(the example's 3 repeated, 2 combinations each, Morison model, 10 seeds, 2 workers): 1594 s
wall, 156 s per section task (60-172 storms), ~1.6 s per 3.5-h storm under that load.

Run: ``PYTHONPATH=src python benchmarks/assess_route.py [--seeds 10] [--workers 2]
[--route 3] [--scheduler tcp://...]``.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from onbottom._casefile import read_toml
from onbottom.assess import assess, parse_route_case
from onbottom.cli.assess import example_path


def route(n_sections: int, seeds: int):
    doc, _ = read_toml(example_path())
    base = doc["route"]["sections"]
    secs = []
    for k in range(n_sections):
        s = dict(base[k % len(base)])
        s["name"] = f"{s['name']} {k // len(base)}" if n_sections > len(base) else s["name"]
        s["kp_start_km"], s["kp_end_km"] = 10.0 * k, 10.0 * (k + 1)
        secs.append(s)
    doc["route"]["sections"] = secs
    doc["dynamic"]["seeds"] = seeds
    return parse_route_case(doc)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--route", type=int, default=3, help="number of sections")
    ap.add_argument("--scheduler", default=None)
    args = ap.parse_args()
    case = route(args.route, args.seeds)
    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        a = assess(case, out=out, n_workers=args.workers, scheduler=args.scheduler)
        wall = time.perf_counter() - t0
    print(
        f"default route: {len(a.sections)} sections, {args.seeds} seeds, all levels,"
        f" {args.workers} workers{' at ' + args.scheduler if args.scheduler else ''}:"
        f" wall {wall:.1f} s"
    )
    busy = 0.0
    for s in a.sections:
        storms = (s["levels"].get("dynamic") or {}).get("storms", 0) + sum(
            len(b["seeds"]) for b in s["dynamic"].get("base", {}).values()
        )
        busy += s["wall_time_s"]
        print(f"  {s['name']:<24} task {s['wall_time_s']:7.1f} s  storms {storms:4d}")
    print(f"sum of section tasks {busy:.1f} s; mean per section {busy / len(a.sections):.1f} s")


if __name__ == "__main__":
    main()
