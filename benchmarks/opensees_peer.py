"""onbottom against OpenSees on the same pipeline problem: CPU time per node-step (issue 33
item 5).

The standing peer problem of :func:`onbottom.peers.opensees.peer_model` — 1 km, 500
corotational beam elements, elastic–perfectly plastic lateral and axial springs at every node,
a travelling sinusoidal user load, Δt = 0.1 s fixed, 600 s — run by onbottom
(``simulate_pipeline``, numba, warm) and by OpenSeesPy (``analyze``), paired and alternated
(the order swaps every pair), CPU time of the time integration only (model building outside
OpenSees's timing; onbottom's includes its Python set-up and envelopes, a few ms). Both at the
accuracy of the comparison (onbottom residual 1e-9·W_s·ℓ_e, OpenSees NormDispIncr 1e-10 m).
Prints the machine load (1-min load average) beside every run, the ratio per pair and the
median, and the agreement of the |y| envelopes.

Run: ``PYTHONPATH=src python benchmarks/opensees_peer.py [--elements 500] [--duration 600]
[--pairs 3] [--alpha 0]`` (needs ``pip install onbottom[peers]``).
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np

from onbottom.peers.opensees import import_opensees, peer_model, run_onbottom, run_opensees


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--elements", type=int, default=500)
    ap.add_argument("--length", type=float, default=1000.0, help="pipeline length [m]")
    ap.add_argument("--duration", type=float, default=600.0, help="simulated time [s]")
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--alpha", type=float, default=0.0, help="HHT-α (0: Newmark)")
    ap.add_argument(
        "--onbottom-tolerance", type=float, default=1e-9, help="residual / W_s·ℓ_e (default 1e-9)"
    )
    ap.add_argument(
        "--opensees-tolerance", type=float, default=1e-10, help="NormDispIncr [m] (default 1e-10)"
    )
    ap.add_argument("--save", help="write x and both envelopes of the last pair to this .npz")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    args = ap.parse_args()
    if args.smoke:
        args.elements, args.length, args.duration, args.pairs = 10, 20.0, 5.0, 1
    import_opensees()
    model = peer_model(args.elements, length=args.length)
    print(
        f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs;"
        f" load average {os.getloadavg()[0]:.2f}"
    )
    print(
        f"problem: {args.length:g} m, {args.elements} elements ({model.x.size} nodes),"
        f" {args.duration:g} s at Δt 0.1 s, α = {args.alpha:g}"
    )
    run_onbottom(peer_model(10, length=20.0), 1.0, alpha=args.alpha)  # load the numba cache
    print(
        f"tolerances: onbottom residual {args.onbottom_tolerance:g}·W_s·ℓ_e,"
        f" OpenSees NormDispIncr {args.opensees_tolerance:g} m"
    )
    runs = {
        "onbottom": lambda m, t, alpha: run_onbottom(
            m, t, alpha=alpha, force_tolerance=args.onbottom_tolerance
        ),
        "opensees": lambda m, t, alpha: run_opensees(
            m, t, alpha=alpha, tolerance=args.opensees_tolerance
        ),
    }
    per: dict[str, list[float]] = {k: [] for k in runs}
    ratios = []
    last = {}
    for k in range(args.pairs):
        order = ("onbottom", "opensees") if k % 2 == 0 else ("opensees", "onbottom")
        for name in order:
            load = os.getloadavg()[0]
            r = runs[name](model, args.duration, alpha=args.alpha)
            per[name].append(r.per_node_step)
            last[name] = r
            print(
                f"  pair {k} {name:9s}: {r.cpu_time:7.2f} s CPU, {r.n_steps} steps,"
                f" {r.per_node_step * 1e6:6.3f} µs per node-step (load {load:.2f}) {r.info}"
            )
        ratios.append(per["opensees"][-1] / per["onbottom"][-1])
        print(f"  pair {k}: OpenSees / onbottom = {ratios[-1]:.2f}")
    env_ob, env_os = last["onbottom"].max_abs_y, last["opensees"].max_abs_y
    diff = float(np.max(np.abs(env_ob - env_os)) / np.max(env_os))
    print(
        f"per node-step (median): onbottom {statistics.median(per['onbottom']) * 1e6:.3f} µs,"
        f" OpenSees {statistics.median(per['opensees']) * 1e6:.3f} µs;"
        f" ratio {statistics.median(ratios):.2f} (pairs {', '.join(f'{x:.2f}' for x in ratios)})"
    )
    print(
        f"envelopes: max |y| {np.max(env_os):.6f} m (OpenSees), {np.max(env_ob):.6f} m"
        f" (onbottom); largest difference over nodes / max |y| = {diff:.2e}"
    )
    print(f"load average at the end: {os.getloadavg()[0]:.2f}")
    if args.save:
        np.savez(args.save, x=model.x, onbottom=env_ob, opensees=env_os, alpha=args.alpha)


if __name__ == "__main__":
    main()
