"""Verification of the DEM speed levers: sub-cycled stiff contacts, FIRE relaxation, cell order.

Each lever keeps the contact law; these tests check that the integrator is still right:
the sub-cycled step reproduces the plain step taken at the sub-step where only stiff contacts
act, conserves energy without dissipation, and keeps a disk on the pipe stable; FIRE reaches
the same unbalanced-force criterion at a static state; renumbering the disks changes nothing
but round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dem.config import ContactParameters, ContactSet
from onbottom.dem.engine import PipeState, Simulation, step_sizes
from onbottom.dem.preparation import settle
from onbottom.dem.sample import Sample

pytestmark = pytest.mark.verification

SOIL = ContactParameters(k_n=7.5e7, k_s=5e7, mu=0.4, mu_r=0.8)
TABLE3 = ContactSet(
    soil=SOIL, pipe=ContactParameters(1e9, 1e9, 0.3), wall=ContactParameters(1e9, 1e9, 0.0)
)
FRICTIONAL_WALLS = ContactSet(
    soil=SOIL, pipe=ContactParameters(1e9, 1e9, 0.3, 0.1), wall=ContactParameters(1e9, 1e9, 0.2)
)


def test_step_sizes_of_table3():
    """Sub-cycled: Δt from the soil stiffness, ⌈√(1e9/7.5e7)⌉ = 4 sub-steps, each ≤ plain Δt."""
    m = 2650 * math.pi * (0.19e-3) ** 2
    dt0, n0 = step_sizes(TABLE3, m, 0.5, False)
    dt1, n1 = step_sizes(TABLE3, m, 0.5, True)
    assert n0 == 1 and n1 == 4
    assert dt1 / dt0 == pytest.approx(math.sqrt(1e9 / 7.5e7))
    assert dt1 / n1 <= dt0


def _corner_disk(vx=0.3, omega=40.0):
    """One disk in the bottom-left corner, just clear of both walls, moving into them."""
    r = 1e-3
    pos = np.array([[r + 1e-7, r + 1e-7]])
    vel = np.array([[-vx, -0.05]])
    return Sample(pos, np.array([r]), (0.0, 0.02, 0.0, 0.02), velocities=vel, omega=[omega])


def test_subcycled_wall_contacts_equal_plain_steps_at_the_substep():
    """Only stiff contacts act: n sub-steps of Δt/n are the plain scheme at Δt/n.

    A disk bouncing into the bottom-left corner under 25 g, with wall friction, rolling
    resistance and local damping; the sub-cycled run (Δt, 4 sub-steps) and the plain run at
    Δt/4 agree to round-off (the summation order of gravity and wall forces differs).
    """
    s = _corner_disk()
    g = (0.0, -25 * 9.81)
    sub = Simulation(s, FRICTIONAL_WALLS, damping=0.7, gravity=g, nsub=4)
    plain = Simulation(s, FRICTIONAL_WALLS, damping=0.7, gravity=g, dt=sub.dt / 4)
    for _ in range(400):
        p0 = sub.pos.copy()
        sub.run(1)
        plain.run(4)
        np.testing.assert_allclose(sub.pos, plain.pos, rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(sub.vel, (sub.pos - p0) / sub.dt, rtol=1e-9, atol=1e-15)
    # the dynamics continue from the last sub-step's velocity (``vsub``); ``vel`` holds the
    # step's mean velocity, the displacement over the step / Δt
    np.testing.assert_allclose(sub.vsub[:, :2], plain.vel, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(sub.vsub[:, 2], plain.om, rtol=1e-9, atol=1e-9)
    assert sub.subflag[0] == 1
    np.testing.assert_allclose(sub.fsw, plain.fsw, rtol=1e-9, atol=1e-12)
    assert np.any(sub.fsw != 0.0)  # wall friction was exercised


def test_subcycled_pipe_contact_equals_plain_steps_at_the_substep():
    """A moving pipe pressing one disk onto the bottom wall: same equivalence, and the
    reported pipe force (mean over the sub-steps) is the mean of the plain steps' forces."""
    r = 1e-3
    s = Sample(np.array([[0.01, r]]), np.array([r]), (0.0, 0.02, 0.0, 0.02))
    # on the disk's axis: off it the disk is squeezed sideways, an unstable motion that
    # amplifies round-off exponentially
    pipe = PipeState(0.01, r + 2 * r + r + 1e-7, 2 * r, -0.05)
    g = (0.0, -25 * 9.81)
    sub = Simulation(s, FRICTIONAL_WALLS, damping=0.7, gravity=g, pipe=pipe, nsub=4)
    plain = Simulation(s, FRICTIONAL_WALLS, damping=0.7, gravity=g, pipe=pipe, dt=sub.dt / 4)
    pushed = False
    for _ in range(300):
        sub.run(1)
        fy = 0.0
        for _q in range(4):
            plain.run(1)
            fy += plain.pipe_force()[1] / 4
        # the pipe height is py + v·qΔt/4 in the sub-steps and accumulated in the plain run:
        # round-off only
        np.testing.assert_allclose(sub.pos, plain.pos, rtol=0, atol=1e-12 * r)
        assert sub.pipe_force()[1] == pytest.approx(fy, rel=1e-6, abs=1e-9)
        pushed = pushed or fy > 0.0
    assert pushed


def _gas(seed=5, n=14):
    rng = np.random.default_rng(seed)
    r = 1e-3
    cols = int(0.012 / (2.3 * r))
    pos = np.array([[(k % cols + 0.6) * 2.3 * r, (k // cols + 0.6) * 2.3 * r] for k in range(n)])
    radii = r * (0.8 + 0.4 * rng.random(n))
    vel = 0.5 * rng.standard_normal((n, 2))
    return Sample(pos, radii, (0.0, 0.012, 0.0, 0.02), velocities=vel)


def _energy(sim):
    kin = sim.kinetic_energy()
    el = 0.0
    c = sim.contact_forces()
    el += 0.5 * np.sum(c["fn"] ** 2) / 7.5e7
    x0, x1, y0 = sim.box[0], sim.box[1], sim.box[2]
    for ov in (
        sim.rad - (sim.pos[:, 0] - x0),
        sim.rad - (x1 - sim.pos[:, 0]),
        sim.rad - (sim.pos[:, 1] - y0),
    ):
        el += 0.5 * 1e9 * np.sum(np.clip(ov, 0, None) ** 2)
    return kin + el


def test_subcycled_energy_conserved_without_damping_and_friction():
    """Gas of disks in a box (soil and wall collisions), no damping, no friction: no drift.

    The soil step is the sub-cycled default ratio (√(1e9/7.5e7) × the plain step) over 10,
    as in the engine's plain energy test; 20,000 steps with many wall collisions. A resonance
    of the multiple time stepping would show as a growing energy.
    """
    frictionless = ContactSet(
        soil=ContactParameters(7.5e7, 5e7, 0.0, 0.0),
        pipe=ContactParameters(1e9, 1e9, 0.0),
        wall=ContactParameters(1e9, 1e9, 0.0),
    )
    s = _gas()
    sim0 = Simulation(s, frictionless, damping=0.0, gravity=(0, 0), nsub=4)
    sim = Simulation(s, frictionless, damping=0.0, gravity=(0, 0), dt=sim0.dt / 10, nsub=4)
    e0 = _energy(sim)
    rel = []
    for _ in range(40):
        sim.run(500)
        rel.append(_energy(sim) / e0 - 1.0)
    rel = np.array(rel)
    # leapfrog fluctuation (the sub-cycled disks' velocities are a sub-step, not a step,
    # behind their positions); the constant-force variant of the sub-cycling drifted by
    # +1.6 % here, the r-RESPA impulse form measured 1.7e-3 peak, 1.3e-4 mean at the end
    assert np.abs(rel).max() < 3e-3
    assert abs(rel[-10:].mean()) < 5e-4  # no drift
    assert sim.rebuilds > 1


def test_subcycled_sticking_column_on_the_pipe_follows_the_plain_run():
    """Two small disks stacked on the pipe crest under 25 g, no damping, pipe friction 0.3,
    kicked sideways: the stiffest mode of a case (a disk sticking on the pipe, translation +
    rotation, ω² ≈ 3k/m, ω·Δt ≈ π at the sub-cycled step with dt_safety 0.5) sits where the
    impulse sub-cycling could resonate. The sub-cycled run (soil step, 4 sub-steps) must
    follow the plain run (stiff step): no energy growth beyond the plain run's (the column
    slowly tips, in both), same tipping displacement. Tolerance: 5 % over 5 ms (about 2,000
    soil steps of an exponentially growing tipping mode; measured 0.2–3.5 % for dt_safety
    0.3–0.5)."""
    r = 0.19e-3
    big = 2e-3
    m = 2650 * math.pi * r * r
    g = 25 * 9.81
    c0 = np.array([0.01, 0.005 + big + r - 2 * m * g / 1e9])
    c1 = c0 + np.array([0.0, 2 * r - m * g / 7.5e7])
    s = Sample(
        np.array([c0, c1]),
        np.full(2, r),
        (0.0, 0.02, 0.0, 0.02),
        velocities=np.array([[1e-3, 0.0], [0.0, 0.0]]),
    )
    pipe = PipeState(0.01, 0.005, big, 0.0)
    runs = []
    for nsub in (1, 4):
        sim = Simulation(s, TABLE3, damping=0.0, gravity=(0.0, -g), pipe=pipe, nsub=nsub)
        ke = []
        while sim.time < 0.005:
            sim.run(50)
            ke.append(sim.kinetic_energy())
        runs.append((np.array(ke), sim.pos[0, 0] - 0.01, sim))
    (ke_p, x_p, plain), (ke_s, x_s, sub) = runs
    assert sub.dt / plain.dt == pytest.approx(math.sqrt(1e9 / 7.5e7))
    assert ke_s.max() == pytest.approx(ke_p.max(), rel=0.05)
    assert x_s == pytest.approx(x_p, rel=0.05)
    assert np.any(sub.fsw[:, 4] != 0.0)  # the pipe contact carried shear


def _pile(seed=2):
    """About 60 disks dropped loosely into a box: a gravity collapse to equilibrium."""
    rng = np.random.default_rng(seed)
    r = 0.5e-3
    cols = 12
    n = 60
    pos = np.array(
        [[(k % cols + 0.5) * 2.2 * r, (k // cols + 0.5) * 2.2 * r + 1e-5] for k in range(n)]
    )
    radii = r * (0.7 + 0.6 * rng.random(n))
    return Sample(pos, radii, (0.0, cols * 2.2 * r, 0.0, 0.03))


_STALLS = pytest.mark.xfail(
    strict=True,
    reason="known defect: with sub-cycled walls local damping of the intra-step swing holds "
    "resting disks with a net force; the ratio stalls near 1e-2 (the preparation therefore "
    "never sub-cycles)",
)


@pytest.mark.parametrize(
    ("method", "nsub"),
    [
        ("damped", 1),
        ("fire", 1),
        pytest.param("damped", 4, marks=_STALLS),
        pytest.param("fire", 4, marks=_STALLS),
    ],
)
def test_relaxation_reaches_the_equilibrium_criterion(method, nsub):
    """Damped and FIRE both bring a pile under 25 g below the ratio 1e-3 and the state is
    static: cycled on with the paper's local damping it stays near the criterion and no
    disk moves by more than 1 % of the smallest radius (FIRE alone met the ratio while still
    moving by 1.5 %: ``settle`` therefore confirms a FIRE state with local damping). With
    sub-cycled walls it fails (strict xfail, reason above)."""
    s = _pile()
    sim = Simulation(s, TABLE3, damping=0.7, gravity=(0.0, -25 * 9.81), nsub=nsub)
    ok, r = settle(sim, 1e-3, 0.5, check_every=200, min_time=2e-3, relaxation=method)
    assert ok and r < 1e-3
    assert sim.fire[0] == 0.0  # left damped
    p0 = sim.pos.copy()
    sim.run(2000)
    assert sim.unbalanced_ratio() < 1e-2
    assert np.abs(sim.pos - p0).max() < 0.01 * sim.rad.min()


def test_cell_order_changes_results_by_round_off_only():
    """A sheared pile with history, renumbered in cell order: the same motion to round-off.

    Pair histories whose order flips must keep F_s and negate M_r (the test would fail
    at the first step otherwise)."""
    s = _pile(seed=4)
    sim = Simulation(s, TABLE3, damping=0.7, gravity=(0.0, -25 * 9.81))
    sim.run(3000)
    settled = sim.to_sample()
    assert np.any(settled.contacts["mr"] != 0.0)
    order = settled.cell_order()[::-1].copy()  # reversed: every pair flips
    moved = settled.permuted(order)
    a = Simulation(settled, TABLE3, damping=0.7, gravity=(0.0, -25 * 9.81))
    b = Simulation(moved, TABLE3, damping=0.7, gravity=(0.0, -25 * 9.81))
    for sim_ in (a, b):
        sim_.vel[:, 0] += 0.05  # shear the pile against the walls
    for _ in range(20):
        a.run(25)
        b.run(25)
        np.testing.assert_allclose(b.pos, a.pos[order], rtol=0, atol=1e-12 * a.rad.max())
    np.testing.assert_allclose(b.om, a.om[order], rtol=1e-6, atol=1e-6 * np.abs(a.om).max())


def test_cell_order_is_a_row_major_permutation():
    s = _pile()
    order = s.cell_order()
    assert np.array_equal(np.sort(order), np.arange(s.n))
    y = s.positions[order, 1]
    cell = 2 * s.radii.max()
    rows = np.floor(y / cell)
    assert np.all(np.diff(rows) >= 0)
    assert np.array_equal(s.permuted(order).permuted(np.argsort(order)).positions, s.positions)
