"""Cost of one call of the Verley & Sotberg soil kernel, called as the pipeline FE calls it.

The pipeline FE calls the soil kernel of every node once per Newton iteration (about 2.3 per
step) from the node's committed state, through
:func:`onbottom.soil.kernel_contract.lateral_step_node` with a literal model id and borrowed
row views (:func:`onbottom._jit.row_view`), and commits the trial states once the step is
accepted. This benchmark does the same on a synthetic but realistic state sequence: the
benchmark pipe of ``pipeline_storm.py`` on silica sand, nodes whose lateral motion is an
irregular wave-period oscillation of amplitude 0.005 D to 3 D (from region 1 only to breakout
and out of the trough), a vertical load that varies with the wave (with lift-off at the largest
amplitude), Δt = 0.1 s, alternately two and three kernel calls per step (the last at the
step's displacement, the others a small Newton error away from it). It prints the CPU time
per kernel call [ns] (``time.process_time``, best of ``--repeat``).

``--src DIR`` (a folder holding an ``onbottom`` package) or ``--base REV`` (a git revision of
this repository, extracted with ``git archive``) measures that code too, in paired, alternating
subprocess runs, and prints the ratio:

    NUMBA_NUM_THREADS=1 python benchmarks/soil_kernel_rate.py --base main
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

LABEL = "V&S kernel, pipeline calling pattern:"


def node_paths(n_nodes: int, n_steps: int, d: float, ws: float):
    """Displacements [n_steps, n_nodes] and contact loads of the benchmark's nodes."""
    rng = np.random.default_rng(0)
    t = 0.1 * np.arange(n_steps)[:, None]
    amp = d * np.geomspace(0.005, 3.0, n_nodes)[None, :]
    ramp = np.minimum(1.0, t / (0.5 * t[-1] + 1e-9))
    y = np.zeros((n_steps, n_nodes))
    for period in (9.0, 10.5, 12.3, 7.7):
        phase = rng.uniform(0.0, 2.0 * np.pi, n_nodes)[None, :]
        y += 0.4 * np.sin(2.0 * np.pi * t / period + phase)
    y = amp * ramp * y + 0.05 * amp * ramp * t / (t[-1] + 1e-9)
    lift = 1.2 * amp / (3.0 * d)
    v = ws * (1.0 - lift * ramp * np.sin(2.0 * np.pi * t / 10.5 + 0.7))
    return y, v


def measure(n_nodes: int, n_steps: int, repeat: int) -> float:
    """Best CPU time per kernel call [ns] over ``repeat`` runs of the node sequence."""
    from onbottom._jit import borrow, njit, row_view
    from onbottom.soil.base import OUT_SIZE
    from onbottom.soil.kernel_contract import lateral_step_node

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from pipeline_storm import model_of

    soil = model_of(500).soil
    model_id = int(soil.model_id)

    @njit
    def run(soil_id, model_ids, sparams, s0, y, v, noise, state, trial, out):
        n_steps, n_nodes = y.shape
        state[:, :] = s0
        calls = 0
        for k in range(n_steps):
            n_it = 2 + (k % 2)
            for it in range(n_it):
                err = noise[k] if it < n_it - 1 else 0.0
                for i in range(n_nodes):
                    lateral_step_node(
                        soil_id, model_ids[i], row_view(sparams, i), row_view(state, i),
                        y[k, i] + err, v[k, i], row_view(trial, i), borrow(out),
                    )  # fmt: skip
                    calls += 1
            state[:, :] = trial
        return calls

    from numba import literally

    @njit
    def entry(soil_id, *args):
        literally(soil_id)
        return run(soil_id, *args)

    d = float(soil.outer_diameter)
    y, v = node_paths(n_nodes, n_steps, d, float(soil.installation_load))
    noise = 1e-4 * d * np.random.default_rng(1).standard_normal(n_steps)
    sparams = np.ascontiguousarray(np.tile(soil.packed_parameters(), (n_nodes, 1)))
    s0 = np.ascontiguousarray(np.tile(soil.initial_state(), (n_nodes, 1)))
    state, trial = np.empty_like(s0), np.empty_like(s0)
    mids = np.full(n_nodes, model_id, dtype=np.int64)
    out = np.empty(OUT_SIZE)
    args = (mids, sparams, s0, y, v, noise, state, trial, out)
    entry(model_id, *args)  # compile
    best = np.inf
    calls = 1
    for _ in range(repeat):
        c0 = time.process_time()
        calls = entry(model_id, *args)
        best = min(best, time.process_time() - c0)
    return 1e9 * best / calls


def _child(src: str, n_nodes: int, n_steps: int, repeat: int) -> float:
    env = dict(os.environ)
    env["PYTHONPATH"] = src
    env.setdefault("NUMBA_NUM_THREADS", "1")
    cmd = [sys.executable, __file__, "--measure", f"{n_nodes},{n_steps},{repeat}"]
    res = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    return float(res.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, default=50)
    ap.add_argument("--steps", type=int, default=4000)
    ap.add_argument("--repeat", type=int, default=5, help="runs per measurement (best kept)")
    ap.add_argument("--pairs", type=int, default=3, help="paired runs with --src/--base")
    ap.add_argument("--src", help="folder holding another onbottom package to compare")
    ap.add_argument("--base", help="git revision to compare (extracted with git archive)")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    ap.add_argument("--measure", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.measure:
        n_nodes, n_steps, repeat = (int(x) for x in a.measure.split(","))
        print(measure(n_nodes, n_steps, repeat))
        return
    if a.smoke:
        a.nodes, a.steps, a.repeat = 5, 100, 1
    this_src = str(ROOT / "src")
    if not (a.src or a.base):
        ns = measure(a.nodes, a.steps, a.repeat)
        print(f"{LABEL} {ns:.1f} ns/call ({a.nodes} nodes x {a.steps} steps)")
        return
    with tempfile.TemporaryDirectory() as tmp:
        other = a.src
        if a.base:
            archive = subprocess.run(
                ["git", "archive", a.base, "src"], cwd=ROOT, capture_output=True, check=True
            ).stdout
            subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
            other = os.path.join(tmp, "src")
        size = (a.nodes, a.steps, a.repeat)
        this, that = [], []
        for _ in range(a.pairs):
            that.append(_child(other, *size))
            this.append(_child(this_src, *size))
        print(f"{LABEL} {min(this):.1f} ns/call this code ({this_src})")
        print(f"{LABEL} {min(that):.1f} ns/call other code ({a.base or other})")
        print(f"this / other: {min(this) / min(that):.3f} (best of {a.pairs} paired runs)")
        print(f"load average: {os.getloadavg()}")


if __name__ == "__main__":
    main()
