"""Benchmark: DNVGL-RP-F114 penetration curves and the embedment solver (prints figures)."""

from __future__ import annotations

import sys
import time

import numpy as np

from onbottom.soil.penetration_clay import UndrainedModel1
from onbottom.soil.penetration_f114 import LayConditions, solve_embedment
from onbottom.soil.penetration_sand import DrainedPenetration

SMOKE = "--smoke" in sys.argv[1:]
"""Tiny size (CI: the script finishes and prints its figures)."""


def _best(fn, repeat: int = 5) -> float:
    times = []
    for _ in range(1 if SMOKE else repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    sand = DrainedPenetration(diameter=0.5, unit_weight=16.7e3, friction_angle_deg=36)
    clay = UndrainedModel1(diameter=0.5, su_mudline=2e3, su_gradient=3e3, unit_weight=6e3)
    z = np.linspace(0.0, 0.5, 1000 if SMOKE else 1_000_000)
    for name, model in (("sand Eq 4.9", sand), ("clay Model 1", clay)):
        t = _best(lambda m=model: m.resistance(z))
        print(f"{name:14s} Q_v on 1e6 points: {t * 1e3:7.1f} ms ({z.size / t:.3g} points/s)")
        t = _best(lambda m=model: solve_embedment(m, 5e3), repeat=20)
        print(f"{name:14s} solve_embedment:   {t * 1e3:7.2f} ms")
        lay = LayConditions(bending_stiffness=1e8, bottom_tension=5e5)
        t = _best(lambda m=model, lay=lay: solve_embedment(m, 5e3, lay=lay), repeat=20)
        print(f"{name:14s} ... with k_lay:     {t * 1e3:7.2f} ms")


if __name__ == "__main__":
    main()
