"""A first run that compiles less: the numba compile of each command without the warm-up.

For each command, one whole process (``python -m onbottom ...``) with ``NUMBA_CACHE_DIR``
pointed at a new empty folder (the first run after an install, no ``onbottom warmup``), then
``--warm`` (default 2) more with that folder filled, the minimum kept (on a busy machine one
warm run of ``simulate`` read 6.0 CPU-s where the next read 1.7). The compile cost is the CPU
time (user + system of the child) of the cold run less the warm one, printed against the
target <= 5 CPU-s per command (issue: "the compile of each command without the warm-up
<= 5 s"), with the number of specialisations numba compiled and cached and the load average
(a shared machine: CPU time is the better figure).

Commands: ``stability`` (examples/stability_case.toml), ``storm`` on a pipe section
(examples/storm_case.toml) and on a pipeline (examples/pipeline_case.toml: the FE), ``assess``
on the tiny route (benchmarks/assess_tiny.toml), ``simulate`` (examples/section_case.toml:
the centrifuge section).

``--profile`` lists what each cold run compiled (numba's ``numba:compile`` events: function,
argument types, exclusive seconds; the same listener as ``first_run.py --profile``), which is
where fewer specialisations would come from.

    python benchmarks/compile_per_command.py [--only storm] [--warm 1] [--profile] [--src DIR]
    python benchmarks/compile_per_command.py --smoke     # CI: stability only, prints

``--src`` runs another source tree (``git archive <commit> src | tar -x -C /tmp/b``) for
before/after figures on the same machine.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from pathlib import Path

from bench_startup import child_env, run_child

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
FIRST_RUN = Path(__file__).resolve().parent / "first_run.py"
TARGET_S = 5.0

COMMANDS: tuple[tuple[str, list[str]], ...] = (
    ("stability", ["stability", "examples/stability_case.toml", "--json"]),
    ("storm (section)", ["storm", "examples/storm_case.toml", "--quiet", "--json"]),
    ("storm (pipeline)", ["storm", "examples/pipeline_case.toml", "--quiet", "--json"]),
    ("assess (tiny)", ["assess", "benchmarks/assess_tiny.toml", "--no-pdf", "--quiet", "--json"]),
    ("simulate (section)", ["simulate", "examples/section_case.toml", "--quiet"]),
)


def _args(cmd: list[str], out: Path) -> list[str]:
    """The CLI arguments of ``cmd`` writing under ``out`` (one process, no Dask workers)."""
    args = list(cmd)
    if cmd[0] == "storm":
        args += ["--output", str(out / f"{Path(cmd[1]).stem}.nc"), "--workers", "0"]
    elif cmd[0] == "assess":
        args += ["--out", str(out / "assess"), "--workers", "0"]
    elif cmd[0] == "simulate":
        args += ["-o", str(out / "section.nc")]
    return args


def measure(name: str, cmd: list[str], src: Path, warm: int, profile: bool) -> dict:
    with tempfile.TemporaryDirectory(prefix="onbottom-compile-") as tmp:
        cache, out = Path(tmp) / "numba", Path(tmp) / "out"
        cache.mkdir()
        out.mkdir()
        env = child_env(src, numba_cache=cache)
        args = _args(cmd, out)
        events = Path(tmp) / "events.json"
        cold_argv = (
            [str(FIRST_RUN), "--child", str(events), "--", *args]
            if profile
            else ["-m", "onbottom", *args]
        )
        load0 = os.getloadavg()[0]
        _, cold = run_child(cold_argv, env)
        cached = sum(1 for _ in cache.rglob("*.nbc"))
        warm_cpu = min(run_child(["-m", "onbottom", *args], env)[1] for _ in range(warm))
        load1 = os.getloadavg()[0]
        rows = json.loads(events.read_text()) if profile else []
    compile_s = cold - warm_cpu
    verdict = "met" if compile_s <= TARGET_S else "NOT met"
    print(
        f"{name:<19} cold {cold:6.2f} CPU-s  warm {warm_cpu:5.2f} CPU-s  compile"
        f" {compile_s:6.2f} CPU-s  target <= {TARGET_S:g}: {verdict};"
        f" {cached} specialisations cached  (load {load0:.2f}-{load1:.2f})"
    )
    if profile:
        total = sum(r["excl"] for r in rows)
        print(f"    {len(rows)} compiles, {total:.2f} s (exclusive times, in-process wall)")
        for r in sorted(rows, key=lambda r: -r["excl"])[:12]:
            print(f"    {r['excl']:6.2f}  {r['name']} [{r['args'][:60]}]")
    return {"name": name, "cold": cold, "warm": warm_cpu, "compile": compile_s}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", help="the commands whose name contains this")
    ap.add_argument("--warm", type=int, default=2, help="warm runs (the minimum is kept)")
    ap.add_argument("--profile", action="store_true", help="list what each cold run compiled")
    ap.add_argument("--src", type=Path, default=SRC, help="the source tree to run")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.only = args.only or "stability"
    print(
        f"python {sys.version.split()[0]}, {os.cpu_count()} cores, load average"
        f" {os.getloadavg()[0]:.2f}; src {args.src}; target <= {TARGET_S:g} CPU-s of"
        " compiling per command"
    )
    rows = [
        measure(name, cmd, args.src.resolve(), max(1, args.warm), args.profile)
        for name, cmd in COMMANDS
        if args.only is None or args.only in name
    ]
    met = sum(r["compile"] <= TARGET_S for r in rows)
    print(f"commands within the target: {met} of {len(rows)}")


if __name__ == "__main__":
    main()
