"""Speed of the F109 design layer (prints figures; not a test).

* significant_bed_velocity over a scatter of sea states (vectorised, one call);
* one absolute lateral stability check;
* one minimum-concrete design solve (51-point scan + brentq, 3 combinations);
* one 3-h V–H load envelope (FFT synthesis, 40 steps per T_p).

Timings are wall-clock medians of a few repeats and depend on the machine's load: report
``uptime`` with them.

    python benchmarks/f109_design.py
"""

from __future__ import annotations

import os
import statistics
import sys
import time

import numpy as np

from onbottom.checks import absolute_lateral_stability
from onbottom.checks.design import design_concrete_thickness
from onbottom.hydro.design_sea_state import significant_bed_velocity
from onbottom.hydro.load_envelope import load_envelope
from onbottom.inputs import Layer, Sand
from onbottom.inputs.environment import Environment, f109_combinations
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.inputs.storm import Current, SeaState

SMOKE = "--smoke" in sys.argv[1:]
"""Tiny size (CI: the script finishes and prints its figures)."""


def _median(fn, repeats: int = 3) -> float:
    times = []
    for _ in range(1 if SMOKE else repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    print(f"load average: {os.getloadavg()}")
    hs, tp = np.meshgrid(np.linspace(1.0, 10.0, 100), np.linspace(6.0, 16.0, 100))
    t = _median(lambda: significant_bed_velocity(hs, tp, 30.0))
    print(f"significant_bed_velocity, {hs.size} sea states: {t * 1e3:.0f} ms")
    for n in (100, 1000):
        t = _median(lambda n=n: significant_bed_velocity(hs.ravel()[:n], tp.ravel()[:n], 30.0))
        print(f"significant_bed_velocity, {n} sea states: {t * 1e3:.1f} ms")
    b = PipeBuildUp(
        steel_outer_diameter=0.2191,
        wall_thickness=0.0127,
        layers=(
            Layer(name="corrosion", thickness=0.0055, density=1335.0),
            Layer(name="concrete", thickness=0.05, density=3043.5),
        ),
        contents=Contents(operation=180.0),
    )
    sand = Sand(submerged_unit_weight=10.0e3)
    pipe = b.pipe()
    t = _median(
        lambda: absolute_lateral_stability(
            pipe, sand, hs=5.0, tp=11.0, depth=40.0, current_velocity=0.35
        ),
        10,
    )
    print(f"absolute_lateral_stability, one call: {t * 1e3:.2f} ms")
    combos = f109_combinations(
        wave_100=SeaState(hs=5.0, tp=11.0),
        wave_10=SeaState(hs=4.2, tp=10.3),
        current_100=Current(velocity=0.5, reference_height=3.0),
        current_10=Current(velocity=0.35, reference_height=3.0),
    )
    env = Environment(water_depth=40.0)
    res = None

    def solve() -> None:
        nonlocal res
        res = design_concrete_thickness(b, sand, env, combos, thickness_max=0.15)

    t = _median(solve)
    print(
        f"design_concrete_thickness (2 combinations, 4 conditions): {t:.2f} s"
        f" -> {res.value * 1e3:.1f} mm"
    )
    t = _median(
        lambda: load_envelope(
            hs=4.68, tp=10.8, depth=13.0, diameter=0.3952, submerged_weight=2168.0, current=0.76
        )
    )
    print(f"load_envelope, 3 h record at T_p/40: {t:.2f} s")


if __name__ == "__main__":
    main()
