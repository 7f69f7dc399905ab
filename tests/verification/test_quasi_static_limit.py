"""Quasi-static limit of the section solver.

Loaded slowly enough for inertia to vanish, the dynamic section solver must follow the
quasi-static path of the same soil model: at every load sample the pipe sits where the soil
resistance equals the applied load, R(u; history, V) = H. The quasi-static integration is
written here independently of the solver: a load-controlled walk that, at each sample, moves
the pipe in committed increments of 2 mm (the solver's largest displacement increment) in the
direction of the out-of-balance load until R − H changes sign, then bisects inside the last
increment. Equilibrium lost for good (the walk passes the box limit) marks the limit.

Case: Inclined 1 (Table 2 parameters, sine cycles) with the cycle stretched 1000× (40 000 s):
the inertia force m·ü is then ~10⁻⁹ of the loads. Criteria (issue 14): cycles to the limit
within 0.05, maximum penetration within 2 %.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dynamics.centrifuge import (
    ADDED_MASS_COEFFICIENT,
    AMPLITUDE_STEP,
    build_pipe,
    build_soil,
    get_test,
)
from onbottom.dynamics.programmes import inclined_cyclic
from onbottom.dynamics.section import section_mass, simulate_section
from onbottom.soil.base import OUT_R, OUT_SIZE, OUT_Z, S_Z

pytestmark = pytest.mark.verification

STRETCH = 1000.0
POINTS_PER_CYCLE = 200
STEP = 2.0e-3  # m, committed walk increment (= SolverSettings.max_displacement_increment)


def _quasi_static(soil, prog, limit):
    """Return (cycles to the limit or None, max penetration) of the quasi-static path."""
    kernel = soil.kernel
    params = soil.packed_parameters()
    state = soil.initial_state()
    trial = np.empty_like(state)
    out = np.empty(OUT_SIZE)

    def resid(u, v, h):
        kernel(params, state, u, v, trial, out)
        return out[OUT_R] - h

    u = 0.0
    z_max = float(state[S_Z])
    t0 = float(prog.time[0])
    for t, h, v in zip(prog.time, prog.horizontal_load, prog.vertical_load, strict=True):
        r0 = resid(u, v, h)
        if r0 != 0.0:
            d = -math.copysign(1.0, r0)
            while True:
                u1 = u + d * STEP
                r1 = resid(u1, v, h)
                if math.copysign(1.0, r1) != math.copysign(1.0, r0) or r1 == 0.0:
                    lo, hi = u, u1  # root inside this increment: bisect from the committed state
                    for _ in range(60):
                        mid = 0.5 * (lo + hi)
                        if math.copysign(1.0, resid(mid, v, h)) == math.copysign(1.0, r0):
                            lo = mid
                        else:
                            hi = mid
                    u1 = 0.5 * (lo + hi)
                    resid(u1, v, h)
                    state[:] = trial
                    u = u1
                    break
                state[:] = trial  # commit the increment and walk on
                u = u1
                r0 = r1
                z_max = max(z_max, float(out[OUT_Z]))
                if abs(u) >= limit:
                    return (float(t) - t0) / prog.cycle_period, z_max
        else:
            state[:] = trial
        z_max = max(z_max, float(out[OUT_Z]))
    return None, z_max


@pytest.mark.slow
def test_slow_loading_matches_the_quasi_static_path():
    test = get_test("Inclined 1")
    prog = inclined_cyclic(
        test.vertical_load,
        AMPLITUDE_STEP,
        test.period * STRETCH,
        test.alpha_deg,
        16,
        shape="sine",
        points_per_cycle=POINTS_PER_CYCLE,
        installation_load=test.installation_load,
        name="Inclined 1 (slow)",
    )
    soil = build_soil(test, parameters="table2")
    res = simulate_section(
        prog,
        soil,
        mass=section_mass(build_pipe(test), ADDED_MASS_COEFFICIENT),
        displacement_limit=test.displacement_limit,
    )
    assert res.success and res.cycles_to_limit is not None
    cycles_qs, z_qs = _quasi_static(soil, prog, test.displacement_limit)
    assert cycles_qs is not None
    # the quasi-static limit is resolved to one load sample (1/200 cycle)
    assert abs(res.cycles_to_limit - cycles_qs) <= 0.05, (res.cycles_to_limit, cycles_qs)
    assert res.summary["max_penetration"] == pytest.approx(z_qs, rel=0.02)
