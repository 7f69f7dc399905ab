"""Wall time of ``onbottom assess`` (issue 32 item 7), each figure printed against its target.

Targets (issue 32, on 2 cores):

* ``--route default``: the embedded example route (3 sections, 2 combinations each), all
  levels, 10 seeds: <= 5 min;
* ``--route big``: 20 sections (the example's 3 repeated, KP shifted), each in 3 conditions
  (installation, hydrotest, operation) × 2 load combinations = 6 storm cases, all levels:
  <= 30 min; ``--scheduler auto`` runs it on a Dask scheduler address (a ``dask scheduler``
  and a ``dask worker --nworkers N --nthreads 1`` started here as subprocesses) and prints the
  cost per section.
* ``--route big --fe every`` (the default ``--fe``; issue 45 item 2): the same with the
  pipeline FE checking every section's design, in the section's task (``[pipeline] sections =
  "every"``, ``mesh = "rule"``: length and element count by
  :func:`onbottom.assess.pipeline.fe_mesh`; the FE started from the section's accepted design,
  its storms stopped at the allowable): <= 10 min on 2 idle cores, linear in sections, the
  same on a Dask scheduler address (``--scheduler``). ``--fe governing`` runs the FE on the
  governing section only, ``--fe off`` not at all. A loaded machine cannot time the whole
  route: ``--route N`` runs N sections, and the CPU per section (every section's task, FE
  included) extrapolates to 20 (the sections are independent tasks: the cost is linear in
  sections; the printed figures say per section what was measured).

The numba kernels are cached on disk after a first run (the workers load them; a cold cache
adds tens of seconds of compilation per worker). The machine's load average is printed before
and after: on a shared machine every figure depends on it.

Run: ``PYTHONPATH=src nice python benchmarks/assess_route.py [--route default|big|N]
[--seeds 10] [--workers 2] [--scheduler auto|tcp://...]``.

Measured (2026-11-26, 2 cores shared with other agents' jobs, load average 18-20, run with
nice): default route, 10 seeds, 2 local workers, pipeline FE on: 276.5 s wall (target 300 s:
met); worker CPU 14.6 / 17.4 / 9.5 s per section, 71-88 storms each (0.18 s CPU per storm);
pipeline FE 63 s wall; rerun at load 10-11 (storms stopped at the allowable): 222.2 s wall,
40.7 s worker CPU, pipeline FE 43.5 s wall.
Big route (20 sections × 6 cases, --scheduler auto): 3103 s wall at load
average 22 falling to 8.5 (target 1800 s: not met; 233 storms per section, before the guess
fix); ``--route 3`` with this version: 215 storms, 34.5 / 40.9 / 25.5 s worker CPU per
section (0.156 s per storm) → ~680 s CPU for 20 sections, ~6 min on 2 free cores.
Idle machine, final code (load 0.4 -> 1.8): big route on --scheduler auto in 290.9 s wall
(target met), 27.1 s worker CPU and 218 storms per section, 0.124 s CPU per storm.
FE on every section (``--fe every``, mesh rule; 2026-11-29, 2 cores shared with 7 other jobs,
load average 9-15, run with nice): ``--route 3``, 2 local workers: 382 s wall, worker CPU
106.7 s (33.1 / 44.4 / 29.2 s per section, of which the FE 1.4 / 2.8 / 2.3 s: 18, 40 and 33
elements, every design passing the FE at once), main process 10.3 s; ``--route 6 --scheduler
auto``: 593 s wall, worker CPU 206.3 s (34.4 s per section: 1.93 times the 3-section CPU for
twice the sections, linear), FE 12.5 s in all. 20 sections at 34.5-39 s CPU each: 690-780 s of
CPU, ~345-390 s on 2 idle cores (target 600 s: met by extrapolation; not timed whole on the
loaded machine). A section whose design fails the FE adds ~1.5-3 s of CPU per raise trial.
Earlier version (bisection over the full range, no worst-first
order): default route 227 s at a lower load with 138-164 storms per section; 20 sections × 2
combinations (Morison): 1594 s.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import socket
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from onbottom.assess import assess
from onbottom.cases.assess import build_route, example_path, parse_route_case

TARGET_S = {"default": 300.0, "big": 1800.0}
TARGET_BIG_FE_S = 600.0
"""The big route with the pipeline FE checking every section: <= 10 min on 2 idle cores."""
BIG_SECTIONS = 20

# installation and hydrotest: a seasonal (1-year) sea state and current, F109 §3.4.3 for a
# temporary phase; operation: the 100-year wave with the 10-year current and the converse
CONDITIONS = (
    ("installation", (("1-yr wave + 1-yr current", 0.60, 0.85, 0.70),
                      ("1-yr current + 1-yr wave (swell)", 0.45, 1.00, 0.80))),
    ("hydrotest", (("1-yr wave + 1-yr current", 0.60, 0.85, 0.70),
                   ("1-yr current + 1-yr wave (swell)", 0.45, 1.00, 0.80))),
    ("operation", (("100-yr wave + 10-yr current", 1.0, 1.0, 1.0),
                   ("10-yr wave + 100-yr current", 0.85, 0.94, 1.25))),
)  # fmt: skip


def _three_conditions(section: dict, metocean: dict) -> dict:
    """The section with its own metocean and 3 conditions × 2 combinations."""
    s = {k: v for k, v in section.items() if k not in ("metocean", "combinations")}
    met = metocean[section["metocean"]] if "metocean" in section else section
    s["waves"], s["current"] = dict(met["waves"]), dict(met["current"])
    hs, tp, u = s["waves"]["hs"], s["waves"]["tp"], s["current"]["velocity"]
    s["combinations"] = [
        {"name": f"{cond}: {name}", "condition": cond, "hs": round(fh * hs, 3),
         "tp": round(ft * tp, 3), "current_velocity": round(fu * u, 3)}
        for cond, combos in CONDITIONS
        for name, fh, ft, fu in combos
    ]  # fmt: skip
    return s


def route(kind: str, seeds: int, fe: str = "governing"):
    """The benchmark route ``kind`` (default, big, or a number of sections) with ``seeds``
    storms per evaluation; ``fe``: the pipeline FE on every section's design (``every``, by
    the mesh rule), on the governing section only (``governing``, the route's ``[pipeline]``)
    or ``off``."""
    doc = tomllib.loads(example_path().read_text(encoding="utf-8"))
    base = doc["route"]["sections"]
    n = {"default": len(base), "big": BIG_SECTIONS}.get(kind) or int(kind)
    secs = []
    for k in range(n):
        s = dict(base[k % len(base)])
        if kind != "default":
            s = _three_conditions(s, doc.get("metocean", {}))
            s["name"] = f"{s['name']} {k // len(base)}"
            s["kp_start_km"], s["kp_end_km"] = 10.0 * k, 10.0 * (k + 1)
        secs.append(s)
    doc["route"]["sections"] = secs
    if kind != "default":
        doc.pop("metocean", None)
    doc["dynamic"]["seeds"] = seeds
    doc["levels"]["pipeline_fe"] = fe != "off"
    if fe == "every":
        doc["pipeline"] |= {"sections": "every", "mesh": "rule"}
    return build_route(parse_route_case(doc))


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def local_scheduler(workers: int):
    """A ``dask scheduler`` and ``dask worker`` started here; yields the scheduler address."""
    port = _free_port()
    addr = f"tcp://127.0.0.1:{port}"
    src = str(Path(__file__).resolve().parents[1] / "src")
    env = dict(os.environ, PYTHONPATH=src + os.pathsep + os.environ.get("PYTHONPATH", ""))
    dask = [sys.executable, "-m", "distributed.cli.dask_scheduler"]
    log = tempfile.TemporaryFile()
    sched = subprocess.Popen(
        [*dask, "--host", "127.0.0.1", "--port", str(port), "--dashboard-address", ":0"],
        env=env, stdout=log, stderr=log,
    )  # fmt: skip
    work = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_worker", addr, "--nworkers",
         str(workers), "--nthreads", "1", "--memory-limit", "0", "--no-dashboard"],
        env=env, stdout=log, stderr=log,
    )  # fmt: skip
    try:
        from distributed import Client

        with Client(addr, timeout=120) as c:
            c.wait_for_workers(workers, timeout=300)
        yield addr
    finally:
        for p in (work, sched):  # only the processes started here, by their handles
            p.terminate()
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--route", default="default", help="default, big, or a number of sections")
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--scheduler", default=None, help="a Dask address, or auto (start one)")
    ap.add_argument(
        "--fe", default="every", choices=("every", "governing", "off"),
        help="pipeline FE on every section's design (default), the governing one, or off",
    )  # fmt: skip
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.route, args.seeds, args.workers = "1", 1, 1
    built = route(args.route, args.seeds, args.fe)  # read and built before the clock starts
    ncomb = sum(len(s.storms) for s in built.sections)
    load0 = os.getloadavg()
    with contextlib.ExitStack() as stack:
        address = args.scheduler
        if address == "auto":
            address = stack.enter_context(local_scheduler(args.workers))
        out = stack.enter_context(tempfile.TemporaryDirectory())
        t0, c0 = time.perf_counter(), time.process_time()
        a = assess(built, out=out, n_workers=args.workers, scheduler=address)
        wall, main_cpu = time.perf_counter() - t0, time.process_time() - c0
    load1 = os.getloadavg()
    where = f"scheduler {address}" if address else f"{args.workers} local workers"
    target = TARGET_S.get(args.route)
    verdict = "" if target is None else (
        f" — target <= {target:.0f} s: {'MET' if wall <= target else 'NOT MET'}"
    )  # fmt: skip
    print(
        f"route {args.route!r}: {len(a.sections)} sections, {ncomb} storm cases, {args.seeds}"
        f" seeds, all levels, {where}: wall {wall:.1f} s{verdict}"
    )
    print(
        f"load average (1/5/15 min) before {load0[0]:.2f}/{load0[1]:.2f}/{load0[2]:.2f}, after"
        f" {load1[0]:.2f}/{load1[1]:.2f}/{load1[2]:.2f}; {os.cpu_count()} cores"
    )
    busy, cpu, storms_all = 0.0, 0.0, 0
    for s in a.sections:
        lv = s["levels"].get("dynamic") or {}
        base = sum(len(b["seeds"]) + 1 for b in s["dynamic"].get("base", {}).values())
        search = lv.get("storms", 0)
        trials = len((s["dynamic"].get("bisection") or {}).get("trials", []))
        busy += s["wall_time_s"]
        cpu += s.get("cpu_time_s", float("nan"))
        storms_all += base + search
        levels = ", ".join(
            f"{k} " + ("—" if v.get("value") is None else f"{1e3 * v['value']:.1f}")
            for k, v in s["levels"].items()
        )
        print(
            f"  {s['name']:<20} task {s['wall_time_s']:7.1f} s wall,"
            f" {s.get('cpu_time_s', float('nan')):6.1f} s CPU; storms {base + search:4d}"
            f" (given design + histories {base}, search {search} in {trials} trials);"
            f" minimum per level [mm or N/m x 1e3]: {levels}; design ({s['governing_level']})"
        )
    n = len(a.sections)
    print(
        f"cost per section: {busy / n:.1f} s of worker wall time (sum {busy:.1f} s),"
        f" {cpu / n:.1f} s of worker CPU (sum {cpu:.1f} s), {wall / n:.1f} s of study wall"
        f" time; {storms_all / n:.0f} storms; {cpu / max(storms_all, 1):.3f} s CPU per storm"
    )
    print(
        f"on 2 uncontended cores the sections' CPU alone would take ~{cpu / 2:.0f} s of wall"
        " time (sum of worker CPU / 2; the machine's load sets the rest)"
    )
    if args.fe == "every":
        in_process = args.workers == 0 and address is None  # the sections' CPU is the main's
        _print_fe_every(a, n, cpu, 0.0 if in_process else main_cpu, wall)
    elif a.pipeline:
        p = a.pipeline
        print(
            f"pipeline FE of {p['section']}: {p['n_nodes']} nodes, {p['wall_time_s']:.1f} s wall"
            f" (in the main process), max strain {100 * p['max_strain']:.3g} %"
        )


def _print_fe_every(a, n: int, cpu: float, main_cpu: float, wall: float) -> None:
    """The FE on every section: per section its mesh, verdict and cost, then the cost per
    section and the big route extrapolated against :data:`TARGET_BIG_FE_S`."""
    fe_cpu = 0.0
    for s in a.sections:
        p = s.get("pipeline_fe")
        if not p:
            print(f"  FE {s['name']:<20} not run (no design or no dynamic run)")
            continue
        m = p.get("mesh") or {}
        trials = len((p.get("search") or {}).get("trials", []))
        fe_cpu += p["cpu_time_s"]
        print(
            f"  FE {s['name']:<20} L {m.get('length', p['length_m']):6.1f} m,"
            f" {m.get('n_elements', p['n_nodes'] - 1):3d} elements (λ_p"
            f" {m.get('wavelength', float('nan')):.0f} m, 1/β"
            f" {1.0 / m['beta'] if m.get('beta') else float('inf'):.1f} m);"
            f" {'pass' if p['pass'] else 'FAIL'}{' raised' if p.get('raised') else ''}"
            f" ({trials} raise trials); {p['cpu_time_s']:.1f} s CPU"
        )
    per = (cpu + main_cpu) / n
    big = BIG_SECTIONS * per
    print(
        f"FE on every section: {n} sections, wall {wall:.1f} s, CPU {cpu + main_cpu:.1f} s"
        f" (workers {cpu:.1f} s of which FE {fe_cpu:.1f} s, main process {main_cpu:.1f} s);"
        f" {wall / n:.1f} s wall and {per:.1f} s CPU per section"
    )
    print(
        f"big route ({BIG_SECTIONS} sections, linear in sections: independent tasks):"
        f" {big:.0f} s CPU → ~{big / 2:.0f} s on 2 idle cores — target <="
        f" {TARGET_BIG_FE_S:.0f} s: {'MET' if big / 2 <= TARGET_BIG_FE_S else 'NOT MET'}"
        " (extrapolated from the CPU measured here)"
    )


if __name__ == "__main__":
    main()
