"""Energy: no closed displacement path creates energy in the soil models; the section solver
balances work in = kinetic + stored + dissipated.

Soil: the passive force of the trough models (V&S sand, V&L clay) is a push-only
elastic–plastic force (``passive_rule="elastoplastic"``, docs/theory/verley_sotberg.md). Its
net work over any closed path must be >= 0, and the dissipated energy the kernels report
(soil work ∫R du minus the elastic energy stored in the friction and passive springs) must
never decrease at constant V. The former rule (``"legacy_elastic"``, a nonlinear-elastic
restoring force on an envelope that grows with z) returned more than it stored: −1.83,
−5.09 and −20.17 J/m over one cycle of ±0.05, ±0.1, ±0.2 m with the Inclined 1 parameters;
that is asserted too, so the test can tell the two apart.

Solver: with Newmark average acceleration, ΔKE = trapezoidal work of (H − R) per step exactly
when the step equation is solved, so ∫H du = ½mv² + E_stored + E_dissipated to the solver
tolerance; asserted within 1e-3 of the work in.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from onbottom.dynamics.centrifuge import (
    ADDED_MASS_COEFFICIENT,
    build_pipe,
    build_programme,
    build_soil,
    get_test,
)
from onbottom.dynamics.section import SolverSettings, section_mass, simulate_section
from onbottom.soil import CoulombFriction
from onbottom.soil._path import drive_path
from onbottom.soil.base import OUT_DISSIPATED, OUT_PASSIVE, OUT_R, OUT_SIZE, OUT_STORED
from onbottom.soil.verley_lund import VerleyLund

pytestmark = pytest.mark.verification

INCLINED_1 = get_test("Inclined 1")


def _drive(model, u, v):
    u = np.asarray(u, dtype=float)
    v = np.broadcast_to(np.asarray(v, dtype=float), u.shape).copy()
    h = np.zeros((u.size, OUT_SIZE))
    drive_path(model.model_id, model.packed_parameters(), model.initial_state(), u, v, h)
    return h


def _net_work(u, force):
    """∫F du over the path from u = 0 (force 0 at the start) by the trapezoidal rule."""
    uu = np.concatenate([[0.0], u])
    ff = np.concatenate([[0.0], force])
    return float(np.sum(0.5 * (ff[1:] + ff[:-1]) * np.diff(uu)))


def _cycles(amplitude, n_cycles=1, n=4000):
    th = np.linspace(0.0, 2.0 * np.pi * n_cycles, n * n_cycles + 1)[1:]
    return amplitude * np.sin(th)


def _vs(rule):
    # the closed-cycle figures were stated with every region-2 increment counting in Eq 6
    # (work_counting="any_region2"); they concern the passive rule, not which work counts
    return build_soil(
        INCLINED_1, parameters="table2", passive_rule=rule, work_counting="any_region2"
    )


def _clay(rule="elastoplastic"):
    # D = 0.5 m, W = 1.5 kN/m, s_u = 5 kPa, γ_s = 16 kN/m³ (as tests/unit/test_verley_lund.py)
    return VerleyLund(
        outer_diameter=0.5,
        undrained_shear_strength=5.0e3,
        unit_weight=16.0e3,
        friction_coefficient=0.2,
        installation_load=1.5e3,
        passive_rule=rule,
    )


@pytest.mark.parametrize(
    ("amplitude", "legacy_work"), [(0.05, -1.834), (0.1, -5.095), (0.2, -20.166)]
)
def test_closed_cycle_passive_work_is_dissipative(amplitude, legacy_work):
    u = _cycles(amplitude)
    v = INCLINED_1.vertical_load
    new = _net_work(u, _drive(_vs("elastoplastic"), u, v)[:, OUT_PASSIVE])
    old = _net_work(u, _drive(_vs("legacy_elastic"), u, v)[:, OUT_PASSIVE])
    assert new > 0.0
    # the legacy variant creates energy (the defect the elastoplastic rule removes)
    assert old == pytest.approx(legacy_work, abs=2e-3)


@pytest.mark.parametrize("model", ["vs", "clay", "coulomb"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_dissipated_energy_never_decreases_at_constant_v(model, seed):
    rng = np.random.default_rng(seed)
    if model == "vs":
        m, v, scale = _vs("elastoplastic"), INCLINED_1.vertical_load, 0.3
    elif model == "clay":
        m, v, scale = _clay(), 1.5e3, 0.3
    else:
        m, v, scale = CoulombFriction(friction_coefficient=0.6), 5.0e3, 0.01
    # random walk with reversals of every size, excursions past breakout included
    steps = rng.normal(0.0, 1.0, 3000) * scale / 100.0
    u = np.cumsum(steps) + scale * np.sin(np.linspace(0.0, 12.0, steps.size))
    h = _drive(m, u, v)
    diss = h[:, OUT_DISSIPATED]
    energy = abs(diss[-1]) + 1.0
    assert np.all(np.diff(diss) >= -1e-9 * energy)
    assert np.all(h[:, OUT_STORED] >= 0.0)
    assert diss[-1] > 0.0


@pytest.mark.parametrize("model", ["vs", "clay", "coulomb"])
def test_stored_plus_dissipated_is_the_work_done_on_the_soil(model):
    """The kernels' bookkeeping (exact per return-mapped increment) against an independent
    trapezoidal ∫R du on a finely sampled smooth path (3 cycles of ±0.4 m, breakout included;
    the trapezoidal rule converges as O(Δu) at the kinks of elastic–plastic paths: 7e-6 of
    the total here)."""
    if model == "vs":
        m, v = _vs("elastoplastic"), INCLINED_1.vertical_load
    elif model == "clay":
        m, v = _clay(), 1.5e3
    else:
        m, v = CoulombFriction(friction_coefficient=0.6), 5.0e3
    u = _cycles(0.4, n_cycles=3, n=20000)
    h = _drive(m, u, v)
    work = _cumulative_work(u, h[:, OUT_R])
    booked = h[:, OUT_STORED] + h[:, OUT_DISSIPATED]
    assert np.max(np.abs(work - booked)) <= 1e-4 * abs(work[-1])


def _cumulative_work(u, force):
    uu = np.concatenate([[0.0], u])
    ff = np.concatenate([[0.0], force])
    return np.cumsum(0.5 * (ff[1:] + ff[:-1]) * np.diff(uu))


@pytest.mark.parametrize("model", ["vs", "clay"])
def test_closed_paths_create_no_energy(model):
    rng = np.random.default_rng(7)
    m, v = (_vs("elastoplastic"), INCLINED_1.vertical_load) if model == "vs" else (_clay(), 1.5e3)
    for _ in range(5):
        # a closed path from the installation state: out, back, a few random reversals, home
        pts = np.concatenate([[0.0], rng.uniform(-0.3, 0.3, 6), [0.0]])
        u = np.concatenate([np.linspace(a, b, 400)[1:] for a, b in itertools.pairwise(pts)])
        h = _drive(m, u, v)
        assert _net_work(u, h[:, OUT_PASSIVE]) >= -1e-9
        assert _net_work(u, h[:, OUT_R]) >= -1e-9


def test_legacy_clay_rule_is_kept_as_a_variant():
    u = _cycles(0.02, n_cycles=2)
    h = _drive(_clay("legacy_elastic"), u, 1.5e3)
    hp = _drive(_clay(), u, 1.5e3)
    # inside the rising branch both rules give the same force on first loading
    k = np.argmax(u) // 4
    assert h[k, OUT_PASSIVE] == pytest.approx(hp[k, OUT_PASSIVE], rel=1e-9)
    assert not np.allclose(h[:, OUT_PASSIVE], hp[:, OUT_PASSIVE])


def test_section_solver_energy_balance_newmark():
    test = INCLINED_1
    prog = build_programme(test)
    soil = build_soil(test, parameters="table2")
    mass = section_mass(build_pipe(test), ADDED_MASS_COEFFICIENT)
    res = simulate_section(
        prog,
        soil,
        mass=mass,
        displacement_limit=test.displacement_limit,
        settings=SolverSettings(integrator="newmark"),
    )
    assert res.success and res.cycles_to_limit is not None
    d = res.data
    u, h, v = d["y"].values, d["H"].values, d["y_dot"].values
    work_in = float(np.sum(0.5 * (h[1:] + h[:-1]) * np.diff(u)))
    kinetic = 0.5 * mass * v[-1] ** 2
    stored = float(d["soil_energy_stored"].values[-1])
    dissipated = float(d["soil_energy_dissipated"].values[-1])
    assert work_in > 0.0 and kinetic > 0.0 and dissipated > 0.0
    assert abs(work_in - (kinetic + stored + dissipated)) <= 1e-3 * work_in
    # On the inclined path V varies, and with it the stiffnesses μV/δ and F_r1(z, V)/y1: the
    # stored energy x²/(2k) is re-evaluated with the new k without work being done, which can
    # lower the dissipated energy by a little (2e-4 of it in total here; exactly 0 at constant
    # V, test above). Bound: 1e-3 of the dissipated energy.
    dd = np.diff(d["soil_energy_dissipated"].values)
    assert -np.sum(dd[dd < 0.0]) <= 1e-3 * dissipated
