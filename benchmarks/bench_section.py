"""Benchmark of the pipe-section solver: one Inclined 1 run (Youssef & Cassidy 2014).

Prints the wall time of one run after compilation (with and without building the xarray
Dataset), accepted steps, simulated load cycles per second, and the time of all 14 runs of
``onbottom reproduce`` without plots. Target: one Inclined 1 run < 50 ms on one core.

    python benchmarks/bench_section.py
"""

from __future__ import annotations

import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numpy as np

from onbottom._jit import call_literal
from onbottom.dynamics import _section_kernel as K
from onbottom.dynamics.centrifuge import (
    TESTS,
    build_pipe,
    build_programme,
    build_soil,
    run_centrifuge_test,
)
from onbottom.dynamics.section import section_mass

SMOKE = "--smoke" in sys.argv[1:]
"""Tiny size (CI: the script finishes and prints its figures)."""


def _best(fn, repeat: int) -> tuple[float, float]:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times), float(np.median(times))


def kernel_only(name: str = "Inclined 1") -> tuple[int, float]:
    """Run the numba loop alone (no Python wrapper, no Dataset); returns (steps, t_end)."""
    test = TESTS[name]
    prog = build_programme(test)
    soil = build_soil(test)
    st = np.zeros(K.N_SETTINGS)
    dt = prog.sample_interval
    st[:] = [0, dt, dt * 1e-7, 2e-3, 1e-10, 80, test.displacement_limit, 0, 0.5, 0.25, 0.0]
    st[K.ST_MASS] = section_mass(build_pipe(test))
    pt, ph, pv = (
        np.ascontiguousarray(a) for a in (prog.time, prog.horizontal_load, prog.vertical_load)
    )
    state = soil.initial_state().copy()
    dyn = np.zeros(K.N_DYN)
    dyn[K.D_DT] = dt
    rec = np.empty((4 * pt.size, K.N_REC))
    params = soil.packed_parameters()
    mid = int(soil.model_id)
    call_literal(K.initial_record, 1, mid, params, state, dyn, pt, ph, pv, st, rec, 0)
    n, _ = call_literal(K.integrate, 1, mid, params, state, dyn, pt, ph, pv, st, 1e30, rec, 1)
    return n - 1, float(dyn[K.D_T])


def main() -> None:
    t0 = time.perf_counter()
    res = run_centrifuge_test("Inclined 1")
    print(f"first call (includes numba compile or cache load): {time.perf_counter() - t0:.2f} s")
    best, med = _best(lambda: run_centrifuge_test("Inclined 1"), 2 if SMOKE else 30)
    cycles = res.cycles_to_limit
    print(f"Inclined 1 run_centrifuge_test: best {best * 1e3:.1f} ms, median {med * 1e3:.1f} ms")
    print(
        f"  steps {res.n_steps}, cycles simulated {cycles:.2f},"
        f" {cycles / best:.0f} load cycles/s, {res.n_steps / best:.3g} steps/s"
    )
    kbest, kmed = _best(kernel_only, 2 if SMOKE else 30)
    steps, _ = kernel_only()
    print(
        f"Inclined 1 numba loop only: best {kbest * 1e3:.2f} ms, median {kmed * 1e3:.2f} ms,"
        f" {cycles / kbest:.0f} load cycles/s, {steps / kbest:.3g} steps/s"
    )
    t0 = time.perf_counter()
    total_cycles = 0.0
    for ps in ("table2",) if SMOKE else ("table2", "recommended"):
        for name in list(TESTS)[:1] if SMOKE else TESTS:
            r = run_centrifuge_test(name, parameters=ps, after_limit="runaway_end")
            total_cycles += r.cycles_to_limit or 0.0
    wall = time.perf_counter() - t0
    print(
        f"{'1' if SMOKE else 'all 14'} reproduction runs (no plots): {wall:.2f} s,"
        f" {total_cycles / wall:.0f} cycles/s"
    )


if __name__ == "__main__":
    main()
