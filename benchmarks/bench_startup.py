"""Start-up cost of the commands a user types (issue 33 items 1–2; prints figures, not a test).

Whole-process runs, ``hyperfine`` style: each command is run ``--runs`` times (after one
unmeasured warm-up run) and the median and the minimum wall time are printed against the
target, with the CPU time (user + system) of the same runs. On a shared machine the minimum
and the CPU time are the better estimates of the cost on an idle one.

* ``onbottom --help`` (target ≤ 0.5 s);
* ``python -c "import onbottom"`` (no target of its own; numba, scipy, xarray and dask must
  not load — ``tests/unit/test_lazy_imports.py``);
* ``onbottom stability examples/stability_case.toml --json`` (target ≤ 1.0 s).

``--before DIR`` runs the same commands with another source tree (a ``src`` folder, e.g. one
exported with ``git archive <commit> src | tar -x -C /tmp/before``) in alternation with this
one (A B A B ...), so both see the same load.

``--first-run`` adds the cost a user pays once on a fresh install: numba compiles every
kernel a command calls when its cache is empty. Each command (``stability``, ``storm
examples/storm_case.toml``, ``storm examples/pipeline_case.toml``, ``assess
benchmarks/assess_tiny.toml``: one KP section, one short storm per evaluation) runs with
``NUMBA_CACHE_DIR`` pointed at a new empty folder, then again with that folder filled; the
difference is the compile cost (target ≤ 5 s per command).

For the start-up figures Python's own bytecode cache is kept in a temporary
``PYTHONPYCACHEPREFIX`` folder (an installed package has its ``.pyc`` files; this machine sets
``PYTHONDONTWRITEBYTECODE``), unless ``--no-bytecode`` is given.

    python benchmarks/bench_startup.py [--runs 10] [--before /tmp/before/src] [--first-run]
        [--skip-startup] [--only assess]
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"

STARTUP: tuple[tuple[str, list[str], float | None], ...] = (
    ("onbottom --help", ["-m", "onbottom", "--help"], 0.5),
    ('python -c "import onbottom"', ["-c", "import onbottom"], None),
    (
        "onbottom stability examples/stability_case.toml --json",
        ["-m", "onbottom", "stability", "examples/stability_case.toml", "--json"],
        1.0,
    ),
)
FIRST_RUN: tuple[tuple[str, list[str]], ...] = (
    ("stability", ["stability", "examples/stability_case.toml", "--json"]),
    ("storm (section)", ["storm", "examples/storm_case.toml", "--quiet", "--json"]),
    ("storm (pipeline)", ["storm", "examples/pipeline_case.toml", "--quiet", "--json"]),
    (
        "assess (tiny)",
        ["assess", "benchmarks/assess_tiny.toml", "--no-pdf", "--quiet", "--json"],
    ),
)
FIRST_RUN_TARGET_S = 5.0


def child_env(
    src: Path, pycache: Path | None = None, numba_cache: Path | None = None
) -> dict[str, str]:
    """The environment of a measured ``python`` child: ``src`` on its path, one numba thread,
    a bytecode cache folder ``pycache`` and a numba cache folder ``numba_cache`` if given."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(src)
    env.setdefault("NUMBA_NUM_THREADS", "1")
    if pycache is not None:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(pycache)
    if numba_cache is not None:
        env["NUMBA_CACHE_DIR"] = str(numba_cache)
    return env


CPU: dict[str, list[float]] = {}
"""CPU seconds (user + system) of each measured run, by label: less sensitive to the load."""


def run_child(args: list[str], env: dict[str, str], cwd: Path = ROOT) -> tuple[float, float]:
    """(wall, CPU) seconds of one whole ``python ARGS`` process (CPU: user + system of the
    child, ``resource.getrusage(RUSAGE_CHILDREN)``); an exit status other than 0 or 3 (ran,
    the result is not valid: a check fails) raises."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, *args], env=env, cwd=cwd, capture_output=True, text=True, check=False
    )
    elapsed = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode not in (0, 3):  # 3: ran, result not valid (a check fails)
        raise RuntimeError(f"{' '.join(args)} exited {proc.returncode}:\n{proc.stderr[-2000:]}")
    return elapsed, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def _run(args: list[str], env: dict[str, str], cwd: Path, label: str = "") -> float:
    elapsed, cpu = run_child(args, env, cwd)
    if label:
        CPU.setdefault(label, []).append(cpu)
    return elapsed


def first_run_args(cmd: list[str], out: Path) -> list[str]:
    """The CLI arguments of a :data:`FIRST_RUN` command writing its files under ``out``
    (storm and assess: one process, no Dask workers)."""
    args = list(cmd)
    if cmd[0] == "storm":
        args += ["--output", str(out / f"{Path(cmd[1]).stem}.nc"), "--workers", "0"]
    elif cmd[0] == "assess":
        args += ["--out", str(out / "assess"), "--workers", "0"]
    return args


def _fmt(times: list[float], target: float | None) -> str:
    med, low = statistics.median(times), min(times)
    verdict = ""
    if target is not None:
        verdict = f"  target ≤ {target:g} s: {'met' if med <= target else 'NOT met'} (median)"
        if med > target >= low:
            verdict += ", met by the minimum"
    return f"median {med:6.3f} s  min {low:6.3f} s  (n = {len(times)}){verdict}"


def startup(trees: dict[str, Path], runs: int, bytecode: bool) -> None:
    with tempfile.TemporaryDirectory(prefix="onbottom-pyc-") as tmp:
        envs = {
            label: child_env(src, Path(tmp) / label if bytecode else None)
            for label, src in trees.items()
        }
        for name, args, target in STARTUP:
            times: dict[str, list[float]] = {label: [] for label in trees}
            for env in envs.values():  # warm-up: file cache, .pyc files
                _run(args, env, ROOT)
            loads = []
            CPU.clear()
            for _ in range(runs):
                for label, env in envs.items():  # alternate: A B A B ...
                    times[label].append(_run(args, env, ROOT, label))
                loads.append(os.getloadavg()[0])
            print(f"{name}   (load average {min(loads):.2f}–{max(loads):.2f})")
            for label in trees:
                cpu = CPU[label]
                print(
                    f"  {label:>6}: {_fmt(times[label], target)}\n"
                    f"          CPU (user + system) median {statistics.median(cpu):6.3f} s"
                    f"  min {min(cpu):6.3f} s"
                )


def first_run(label: str, src: Path, only: str | None = None) -> None:
    print(
        f"\nfirst run from an empty numba cache, {label}"
        f" (target ≤ {FIRST_RUN_TARGET_S:g} s of compiling)"
    )
    with tempfile.TemporaryDirectory(prefix="onbottom-first-") as tmp:
        out = Path(tmp) / "out"
        out.mkdir()
        for name, cmd in FIRST_RUN:
            if only is not None and only not in name:
                continue
            cache = Path(tmp) / f"numba-{len(list(Path(tmp).iterdir()))}"
            cache.mkdir()
            # no bytecode prefix here: a fresh one would add the compiling of every .py file
            # (numpy, scipy, numba ...) to the first run
            env = child_env(src, None, cache)
            args = ["-m", "onbottom", *first_run_args(cmd, out)]
            load0 = os.getloadavg()[0]
            CPU.clear()
            cold = _run(args, env, ROOT, "cold")
            files = sum(1 for p in cache.rglob("*.nbc"))
            warm = min(_run(args, env, ROOT, "warm") for _ in range(2))
            load1 = os.getloadavg()[0]
            cpu_cold, cpu_warm = CPU["cold"][0], min(CPU["warm"])
            print(
                f"  {name:<17} first {cold:6.1f} s  warm {warm:5.1f} s"
                f"  compile {cold - warm:5.1f} s"
                f"  ({files} compiled specialisations cached; load {load0:.2f}–{load1:.2f})\n"
                f"  {'':<17} CPU: first {cpu_cold:6.1f} s  warm {cpu_warm:5.1f} s"
                f"  compile {cpu_cold - cpu_warm:5.1f} s"
            )
            shutil.rmtree(cache, ignore_errors=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10, help="measured runs per command (>= 10)")
    ap.add_argument("--before", type=Path, help="another src folder, run in alternation")
    ap.add_argument("--first-run", action="store_true", help="also the empty-cache compile cost")
    ap.add_argument("--no-bytecode", action="store_true", help="no .pyc cache (as this machine)")
    ap.add_argument("--skip-startup", action="store_true", help="only --first-run")
    ap.add_argument("--only", help="--first-run: the commands whose name contains this")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.runs = 1
    bytecode = not args.no_bytecode
    print(
        f"python {sys.version.split()[0]}, {os.cpu_count()} cores, load average"
        f" {os.getloadavg()[0]:.2f}, bytecode cache {'on' if bytecode else 'off'}"
    )
    trees = {"after": SRC}
    if args.before is not None:
        trees = {"before": args.before.resolve(), "after": SRC}
    if not args.skip_startup:
        startup(trees, args.runs, bytecode)
    if args.first_run:
        for label, src in trees.items():
            first_run(label, src, args.only)


if __name__ == "__main__":
    main()
