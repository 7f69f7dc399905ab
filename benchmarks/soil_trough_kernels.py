"""Throughput of the lateral soil kernels (Coulomb, Verley & Sotberg, Verley & Lund).

Drives each model along a random cyclic displacement path with `drive_path` (numba, dispatch
by model id) and prints nanoseconds per committed step. Not a test: numbers depend on the machine.

    python benchmarks/soil_trough_kernels.py [n_steps]
"""

from __future__ import annotations

import sys
import time

import numpy as np

from onbottom import Clay, Pipe, Rock, Sand
from onbottom.soil._path import drive_path
from onbottom.soil.base import OUT_SIZE
from onbottom.soil.factory import lateral_model


def main(n: int = 1_000_000) -> None:
    rng = np.random.default_rng(0)
    pipe = Pipe(outer_diameter=1.0, submerged_weight=10.52e3)
    u = np.cumsum(rng.normal(0.0, 0.005, n))
    v = 10.52e3 * (1.0 + 0.2 * rng.standard_normal(n))
    h = np.zeros((n, OUT_SIZE))
    cases = [
        ("coulomb", Rock(friction_coefficient=0.6)),
        ("verley_sotberg_silica", Sand(submerged_unit_weight=10.0e3)),
        ("verley_sotberg_calcareous", Sand(submerged_unit_weight=7.5e3)),
        (
            "verley_lund",
            Clay(undrained_shear_strength=10.0e3, submerged_unit_weight=6e3, unit_weight=16e3),
        ),
    ]
    for name, seabed in cases:
        m = lateral_model(name, pipe, seabed)
        p, s0 = m.packed_parameters(), m.initial_state()
        drive_path(m.model_id, p, s0, u[:10], v[:10], h[:10])  # compile / load cache
        t0 = time.perf_counter()
        drive_path(m.model_id, p, s0, u, v, h)
        dt = time.perf_counter() - t0
        print(f"{name:<28} {n:>9d} steps  {1e9 * dt / n:8.1f} ns/step")


if __name__ == "__main__":
    if sys.argv[1:] == ["--smoke"]:  # tiny size (CI: the script finishes and prints)
        main(1000)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
