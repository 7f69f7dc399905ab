"""Cost of the corotational beam per element: ``assemble_internal`` of the pipeline FE.

The pipeline FE calls :func:`onbottom.dynamics.pipeline._beam_kernel.assemble_internal` once per
Newton iteration (forces only, or forces and the band tangent on an iteration that refactors).
This times it on the benchmark pipe of ``pipeline_storm.py`` (1 km, 2-m elements: 500 elements)
in a deformed state like a storm's: a smooth lateral deflection of a few diameters (chord
slopes up to ``--slope``), rotations near the chord's with a small scatter, a small axial
stretch. It prints ns per element for the forces alone and for forces + tangent, and beside
them the floor of the library ``atan2`` alone per element (the chord angle the element needs).

    NUMBA_NUM_THREADS=1 python benchmarks/beam_kernel_rate.py

Figures are CPU time of this process (``time.process_time``), the least of ``--repeat`` tries
(the figure a loaded machine distorts least).
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np
from numba import njit
from pipeline_profile import _beam  # the same timed loop as the pipeline's profile

from onbottom.dynamics.pipeline import _beam_kernel as B


@njit
def _atan2(reps, d, props):
    acc = 0.0
    for _ in range(reps):
        for e in range(props.shape[0]):
            i = 3 * e
            acc += math.atan2(d[i + 4] - d[i + 1], props[e, 0] + d[i + 3] - d[i])
    return acc


def state(n_el: int, l0: float, slope: float, seed: int = 0) -> np.ndarray:
    """Nodal displacements (u, v, θ) of a storm-like deformed pipe of ``n_el`` elements."""
    rng = np.random.default_rng(seed)
    x = l0 * np.arange(n_el + 1)
    length = x[-1]
    # a few lateral waves of amplitude a: slope up to a·k = slope
    k = 2.0 * np.pi * 5.0 / length
    a = slope / k
    v = a * np.sin(k * x) * np.sin(np.pi * x / length)
    dv = np.gradient(v, x)
    d = np.zeros(3 * (n_el + 1))
    d[0::3] = 1e-5 * x * (1.0 + rng.uniform(-0.1, 0.1, x.size))
    d[1::3] = v
    d[2::3] = dv + 1e-4 * rng.standard_normal(x.size)
    return d


def best_per_element(fn, reps: int, repeat: int, n_el: int) -> float:
    """ns per element: least CPU time of fn(reps) over ``repeat`` tries, less fn(0)'s."""
    fn(1)

    def least(m: int) -> float:
        t = np.inf
        for _ in range(repeat):
            c0 = time.process_time()
            fn(m)
            t = min(t, time.process_time() - c0)
        return t

    return max(least(reps) - least(0), 0.0) / (reps * n_el) * 1e9


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, default=500)
    ap.add_argument("--slope", type=float, default=0.03, help="largest chord slope dv/dx")
    ap.add_argument("--reps", type=int, default=4000, help="calls per timing")
    ap.add_argument("--repeat", type=int, default=7, help="timings (least kept)")
    ap.add_argument("--smoke", action="store_true", help="tiny size (CI: finishes, prints)")
    a = ap.parse_args()
    if a.smoke:
        a.elements, a.reps, a.repeat = 20, 10, 1
    print(f"load average: {os.getloadavg()}")
    n_el, l0 = a.elements, 2.0
    props = np.zeros((n_el, B.N_EL_PROPS))
    props[:, B.EL_L0] = l0
    props[:, B.EL_EA] = 5.0e9
    props[:, B.EL_EI] = 1.6e7
    props[:, B.EL_N0] = -2.0e5
    d = state(n_el, l0, a.slope)
    ndof = d.size
    f = np.zeros(ndof)
    ab = np.zeros((ndof, B.HALF_BAND + 1))
    fe, ke = np.zeros(6), np.zeros((6, 6))
    mom, nax = np.zeros(n_el + 1), np.zeros(n_el + 1)
    t_f = best_per_element(
        lambda m: _beam(m, np.bool_(False), d, props, f, ab, fe, ke, mom, nax),
        a.reps,
        a.repeat,
        n_el,
    )
    t_k = best_per_element(
        lambda m: _beam(m, np.bool_(True), d, props, f, ab, fe, ke, mom, nax),
        a.reps,
        a.repeat,
        n_el,
    )
    t_a = best_per_element(lambda m: _atan2(m, d, props), a.reps, a.repeat, n_el)
    print(f"{n_el} elements, chord slopes up to {a.slope:g}; CPU ns per element per call:")
    print(f"assemble_internal forces only: {t_f:.2f} ns/element")
    print(f"assemble_internal forces + tangent: {t_k:.2f} ns/element")
    print(f"library atan2 alone (floor of the old chord angle): {t_a:.2f} ns/element")


if __name__ == "__main__":
    main()
