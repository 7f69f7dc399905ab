"""First run on a fresh install: the numba compile cost of each command (issue 33 item 2).

Prints figures, not a test. Each command runs as a whole process (``python -m onbottom ...``)
with ``NUMBA_CACHE_DIR`` pointed at a new empty temporary folder (the cost a user pays once
after ``pip install``), then twice more with that folder filled (warm; the minimum is kept).
For each run: wall time and CPU time (user + system of the child,
``resource.getrusage(RUSAGE_CHILDREN)``), against the target of ≤ 5 s per command, with the
load average before and after (the machine is shared: CPU time is the better figure).

Commands: ``stability examples/stability_case.toml``, ``storm examples/storm_case.toml``
(pipe section, Verley & Sotberg sand, Morison), ``storm examples/pipeline_case.toml`` (the
pipeline FE), ``assess benchmarks/assess_tiny.toml`` (one KP section, the wake model, one
short storm per evaluation).

``--profile`` runs the cold process under numba's ``numba:compile`` event listener and prints
what compiled: each specialisation's function, argument types (abridged), inclusive time
(with the functions it compiled inside) and exclusive time (its own typing, lowering and
LLVM; the sum of exclusive times is the compile total), largest first. Compiling stays as
slow as it is without the listener (one callback per compile).

    python benchmarks/first_run.py [--only storm] [--profile] [--top 25] [--src DIR] [--warmup]

``--warmup`` then runs ``onbottom warmup`` (issue 33 item 2: the one-time compile the README's
set-up command does) from another empty cache — wall and CPU time, its worker processes
included — and each command's first run after it, with the number of numba compiles it
still does (0: the warm-up compiled everything the command uses), against the same target.

``--src`` runs another source tree (e.g. ``git archive <commit> src | tar -x -C /tmp/b``),
for before/after figures on the same machine.

Measured (2 shared cores, load 2.3–3.6, CPU seconds, before → after the issue 33 item 2
changes, two alternated rounds each): stability 0.6 → 0.7 first run (compiles nothing);
storm (section) 6.5/6.9 → 6.4/6.7 first, 1.7–1.9 warm, compiling 4.7/5.1 → 4.7/4.8;
storm (pipeline) 12.8/12.8 → 11.9/12.8 first, compiling 11.2/11.3 → 10.4/11.3; assess
(tiny) 8.0/8.1 → 8.0/8.0 first, compiling 6.1/6.0 → 6.1/5.9. numba's own typing, lowering
and LLVM work per operation dominate what remains (see ``--profile``).

With ``--warmup`` (same machine, load 1.4–3.2, one run): cold first runs stability 0.75,
storm (section) 6.97, storm (pipeline) 12.90, assess (tiny) 8.33 CPU-s (compiling 0.1, 5.1,
11.2, 6.2); ``onbottom warmup`` from an empty cache 50.3 CPU-s, 55.8 s wall on 2 processes
(a loaded machine; estimated 25–30 s wall on two free cores: half the CPU plus the
workers' start), 161 compiles; then first runs 0.74, 2.11,
2.10, 2.51 CPU-s, each with 0 compiles: the ≤ 5 s target is met by every command once the
warm-up has run.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# the same commands, environment and timing as bench_startup.py --first-run
from bench_startup import FIRST_RUN, FIRST_RUN_TARGET_S, child_env, first_run_args, run_child

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
TARGET_S = FIRST_RUN_TARGET_S
COMMANDS = FIRST_RUN


def _verdict(seconds: float) -> str:
    return "met" if seconds <= TARGET_S else "NOT met"


def measure(name: str, cmd: list[str], src: Path, profile: bool, top: int) -> None:
    with tempfile.TemporaryDirectory(prefix="onbottom-first-") as tmp:
        cache = Path(tmp) / "numba"
        out = Path(tmp) / "out"
        cache.mkdir()
        out.mkdir()
        env = child_env(src, numba_cache=cache)
        args = first_run_args(cmd, out)
        events = Path(tmp) / "events.json"
        cold_argv = ["-m", "onbottom", *args]
        if profile:
            cold_argv = [str(Path(__file__).resolve()), "--child", str(events), "--", *args]
        load0 = os.getloadavg()[0]
        cold_wall, cold_cpu = run_child(cold_argv, env)
        n_cached = sum(1 for _ in cache.rglob("*.nbc"))
        warm = [run_child(["-m", "onbottom", *args], env) for _ in range(2)]
        warm_wall = min(w for w, _ in warm)
        warm_cpu = min(c for _, c in warm)
        load1 = os.getloadavg()[0]
        print(
            f"{name:<17} load {load0:.2f}–{load1:.2f}, {n_cached} specialisations cached\n"
            f"  first run  wall {cold_wall:6.2f} s  CPU {cold_cpu:6.2f} s"
            f"   target ≤ {TARGET_S:g} s: {_verdict(cold_cpu)} (CPU)\n"
            f"  warm       wall {warm_wall:6.2f} s  CPU {warm_cpu:6.2f} s"
            f"   target ≤ {TARGET_S:g} s: {_verdict(warm_cpu)} (CPU)\n"
            f"  compiling  wall {cold_wall - warm_wall:6.2f} s"
            f"  CPU {cold_cpu - warm_cpu:6.2f} s"
            f"   target ≤ {TARGET_S:g} s: {_verdict(cold_cpu - warm_cpu)} (CPU)"
        )
        if profile:
            _print_profile(json.loads(events.read_text()), top)


def measure_warmup(src: Path, only: str | None) -> None:
    """``onbottom warmup`` from an empty cache, then each command's first run after it."""
    with tempfile.TemporaryDirectory(prefix="onbottom-warm-") as tmp:
        cache = Path(tmp) / "numba"
        out = Path(tmp) / "out"
        cache.mkdir()
        out.mkdir()
        env = child_env(src, numba_cache=cache)
        env.pop("NUMBA_NUM_THREADS", None)  # the warm-up's own processes, as a user runs it
        report = Path(tmp) / "warmup.json"
        load0 = os.getloadavg()[0]
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        proc = subprocess.run(
            [sys.executable, "-m", "onbottom", "warmup", "--json"],
            env=env, cwd=ROOT, capture_output=True, text=True, check=False,
        )  # fmt: skip
        wall = time.perf_counter() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)  # the warm-up's workers included
        if proc.returncode != 0:
            raise RuntimeError(f"onbottom warmup exited {proc.returncode}:\n{proc.stderr[-2000:]}")
        report.write_text(proc.stdout)
        data = json.loads(proc.stdout)
        cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        print(
            f"warm-up (onbottom warmup, empty cache, {data['processes']} processes)"
            f" load {load0:.2f}–{os.getloadavg()[0]:.2f}\n"
            f"  wall {wall:6.2f} s  CPU {cpu:6.2f} s (workers included),"
            f" {data['compiled']} compiles, {sum(1 for _ in cache.rglob('*.nbc'))} cached"
        )
        for t in data["targets"]:
            print(
                f"    {t['name']:<13} wall {t['wall_s']:5.1f} s  CPU {t['cpu_s']:5.1f} s"
                f"  {t['compiled']:3d} compiles  ({t['title']})"
            )
        print("first run of each command after the warm-up:")
        for name, cmd in COMMANDS:
            if only is not None and only not in name:
                continue
            args = first_run_args(cmd, out)
            events = Path(tmp) / "events.json"
            load0 = os.getloadavg()[0]
            argv = [str(Path(__file__).resolve()), "--child", str(events), "--", *args]
            first_wall, first_cpu = run_child(argv, env)
            rows = json.loads(events.read_text())
            compiled = sorted({r["name"].rsplit(".", 1)[-1] for r in rows})
            print(
                f"  {name:<17} wall {first_wall:6.2f} s  CPU {first_cpu:6.2f} s"
                f"   target ≤ {TARGET_S:g} s: {_verdict(first_cpu)} (CPU);"
                f" {len(rows)} compiles{': ' + ', '.join(compiled) if compiled else ''}"
                f"  (load {load0:.2f}–{os.getloadavg()[0]:.2f})"
            )


def _print_profile(rows: list[dict], top: int) -> None:
    total = sum(r["excl"] for r in rows)
    print(f"  {len(rows)} compiles, {total:.2f} s in all (exclusive times sum)")
    print(f"  {'excl s':>7} {'incl s':>7}  function [argument types]")
    for r in sorted(rows, key=lambda r: -r["excl"])[:top]:
        print(f"  {r['excl']:7.2f} {r['incl']:7.2f}  {r['name']} [{r['args'][:70]}]")


def child(events: Path, cli_args: list[str]) -> int:
    """Run the CLI in this process, recording every numba compile (``--profile``)."""
    from numba.core import event

    rows: list[dict] = []
    stack: list[list[float]] = []  # [start, time spent in nested compiles]

    class Recorder(event.Listener):
        def on_start(self, ev):
            stack.append([time.perf_counter(), 0.0])

        def on_end(self, ev):
            t0, nested = stack.pop()
            incl = time.perf_counter() - t0
            if stack:
                stack[-1][1] += incl
            disp = ev.data["dispatcher"]
            fn = getattr(disp, "py_func", None)
            name = f"{fn.__module__}.{fn.__qualname__}" if fn is not None else repr(disp)
            args = ", ".join(str(a) for a in ev.data.get("args") or ())
            rows.append({"name": name, "args": args, "incl": incl, "excl": incl - nested})

    event.register("numba:compile", Recorder())
    from onbottom.cli.main import main

    try:
        rc = main(cli_args)
    finally:
        events.write_text(json.dumps(rows))
    return rc


def main() -> None:
    if len(sys.argv) > 2 and sys.argv[1] == "--child":
        sys.exit(child(Path(sys.argv[2]), sys.argv[4:]))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", help="the commands whose name contains this")
    ap.add_argument("--profile", action="store_true", help="list what compiled (first run)")
    ap.add_argument("--top", type=int, default=25, help="--profile: rows to print")
    ap.add_argument("--src", type=Path, default=SRC, help="the source tree to run")
    ap.add_argument(
        "--warmup",
        action="store_true",
        help="also: onbottom warmup from an empty cache, then each command's first run after it",
    )
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.only, args.warmup = args.only or "stability", False
    print(
        f"python {sys.version.split()[0]}, {os.cpu_count()} cores, load average"
        f" {os.getloadavg()[0]:.2f}; src {args.src}"
    )
    for name, cmd in COMMANDS:
        if args.only is None or args.only in name:
            measure(name, cmd, args.src.resolve(), args.profile, args.top)
    if args.warmup:
        measure_warmup(args.src.resolve(), args.only)


if __name__ == "__main__":
    main()
