"""Verification of the 2D DEM engine: analytic solutions, Python twin, conservation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dem import _kernels as K
from onbottom.dem._reference import ReferenceSystem
from onbottom.dem.config import ContactParameters, ContactSet
from onbottom.dem.engine import PipeState, Simulation
from onbottom.dem.sample import Sample

pytestmark = pytest.mark.verification

SOIL = ContactParameters(k_n=7.5e7, k_s=5e7, mu=0.4, mu_r=0.8)
TABLE3 = ContactSet(
    soil=SOIL,
    pipe=ContactParameters(1e9, 1e9, 0.3),
    wall=ContactParameters(1e9, 1e9, 0.0),
)


def _box_sample(n=14, seed=3, r=1e-3, width=0.012, height=0.02):
    rng = np.random.default_rng(seed)
    cols = int(width / (2.3 * r))
    pos = np.array([[(k % cols + 0.6) * 2.3 * r, (k // cols + 0.6) * 2.3 * r] for k in range(n)])
    radii = r * (0.8 + 0.4 * rng.random(n))
    vel = 0.05 * rng.standard_normal((n, 2))
    om = 20.0 * rng.standard_normal(n)
    return Sample(pos, radii, (0.0, width, 0.0, height), velocities=vel, omega=om)


def test_kernel_matches_python_twin():
    """Walls, lid, pipe, friction, rolling, damping, gravity: kernel == plain-Python twin."""
    s = _box_sample()
    contacts = ContactSet(
        soil=SOIL, pipe=ContactParameters(1e9, 1e9, 0.3, 0.1), wall=ContactParameters(1e9, 1e9, 0.2)
    )
    sim = Simulation(
        s,
        contacts,
        damping=0.7,
        gravity=(0.0, -25 * 9.81),
        pipe=PipeState(0.006, 0.0098, 0.003, -1.0),
    )
    sim.set_lid(0.0128, -0.05)
    ref = ReferenceSystem(sim.prm, sim.pos, sim.vel, sim.om, sim.rad, sim.mass, sim.inert)
    for _ in range(800):
        sim.run(1)
        ref.step()
    assert sim.rebuilds >= 1
    # round-off differs (summation order, sign(v) of the local damping near v = 0) and
    # grows over the 800 stiff steps; 1e-6 relative is far below any physics difference
    scale = np.abs(ref.vel).max()
    np.testing.assert_allclose(sim.pos, ref.pos, rtol=0, atol=1e-10)
    np.testing.assert_allclose(sim.vel, ref.vel, rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(sim.om, ref.om, rtol=0, atol=1e-6 * np.abs(ref.om).max())
    fx, fy = sim.pipe_force()
    assert abs(fy) > 0.0
    assert fx == pytest.approx(ref.pipe_force[0], rel=1e-5, abs=1e-5 * abs(fy))
    assert fy == pytest.approx(ref.pipe_force[1], rel=1e-5)


def test_two_disk_normal_collision_period():
    """Head-on collision lasts half a period of the contact spring: π√(m_eff/k_n)."""
    r = 1e-3
    s = Sample(
        np.array([[0.01, 0.01], [0.01 + 2 * r + 1e-8, 0.01]]),
        np.array([r, r]),
        (0, 0.02, 0, 0.02),
        velocities=np.array([[0.01, 0.0], [-0.01, 0.0]]),
    )
    sim0 = Simulation(s, TABLE3, damping=0.0, gravity=(0, 0))
    sim = Simulation(s, TABLE3, damping=0.0, gravity=(0, 0), dt=sim0.dt / 50)
    inside = 0
    seen = False
    for _ in range(100000):
        sim.run(1)
        ov = 2 * r - np.hypot(*(sim.pos[1] - sim.pos[0]))
        if ov > 0:
            inside += 1
            seen = True
        elif seen:
            break
    m_eff = sim.mass[0] / 2
    expected = math.pi * math.sqrt(m_eff / SOIL.k_n)
    assert inside * sim.dt == pytest.approx(expected, abs=2 * sim.dt)
    # elastic: velocities reversed
    np.testing.assert_allclose(sim.vel[:, 0], [-0.01, 0.01], rtol=1e-3)


def _single_disk(beta_deg, v0, mu_r, mu=0.5):
    r = 1e-3
    m = 2650 * math.pi * r * r
    g = 9.81
    kn = 1e9
    ov = m * g * math.cos(math.radians(beta_deg)) / kn
    s = Sample(
        np.array([[0.05, r - ov]]),
        np.array([r]),
        (0.0, 1.0, 0.0, 0.01),
        velocities=np.array([[v0, 0.0]]),
        omega=np.array([-v0 / r]),
    )
    wall = ContactParameters(kn, kn, mu, mu_r)
    b = math.radians(beta_deg)
    return Simulation(
        s,
        ContactSet(soil=SOIL, pipe=wall, wall=wall),
        damping=0.0,
        gravity=(g * math.sin(b), -g * math.cos(b)),
    )


def test_rolling_resistance_stops_disk_on_flat():
    """Rolling at the moment cap: a = −(2/3)μ_r g, stopping distance 3v0²/(4μ_r g)."""
    mu_r, v0, g = 0.1, 0.05, 9.81
    sim = _single_disk(0.0, v0, mu_r)
    x0 = sim.pos[0, 0]
    t_stop = v0 / (2.0 / 3.0 * mu_r * g)
    sim.run(int(1.3 * t_stop / sim.dt))
    dist = sim.pos[0, 0] - x0
    assert dist == pytest.approx(3 * v0**2 / (4 * mu_r * g), rel=0.02)
    assert abs(sim.vel[0, 0]) < 0.01 * v0


@pytest.mark.parametrize("beta_deg", [3.0, 5.0])
def test_rolling_resistance_holds_disk_below_critical_slope(beta_deg):
    """Below β_c = atan(μ_r) (= 5.71° for μ_r = 0.1) the disk stays put."""
    sim = _single_disk(beta_deg, 0.0, 0.1)
    x0 = sim.pos[0, 0]
    sim.run(int(0.05 / sim.dt))
    assert abs(sim.pos[0, 0] - x0) < 1e-3 * sim.rad[0]


def test_rolling_resistance_disk_rolls_above_critical_slope():
    """Above β_c it rolls with a = g(sin β − μ_r cos β)/(1 + I/(m r²))."""
    beta, mu_r, g = 8.0, 0.1, 9.81
    sim = _single_disk(beta, 0.0, mu_r)
    x0 = sim.pos[0, 0]
    t = 0.05
    sim.run(int(t / sim.dt))
    b = math.radians(beta)
    a = g * (math.sin(b) - mu_r * math.cos(b)) / 1.5
    assert sim.pos[0, 0] - x0 == pytest.approx(0.5 * a * t * t, rel=0.03)


def _energy(sim):
    kin = sim.kinetic_energy()
    el = 0.0
    n = sim.n
    for i in range(n):
        for j in range(i + 1, n):
            ov = sim.rad[i] + sim.rad[j] - np.hypot(*(sim.pos[j] - sim.pos[i]))
            if ov > 0:
                el += 0.5 * SOIL.k_n * ov**2
    x0, x1, y0 = sim.box[0], sim.box[1], sim.box[2]
    for ov in (
        sim.rad - (sim.pos[:, 0] - x0),
        sim.rad - (x1 - sim.pos[:, 0]),
        sim.rad - (sim.pos[:, 1] - y0),
    ):
        el += 0.5 * 1e9 * np.sum(np.clip(ov, 0, None) ** 2)
    return kin + el


def test_energy_conserved_without_damping_and_friction():
    s = _box_sample(n=14, seed=5)
    s.velocities[:] *= 10.0
    s.omega[:] = 0.0
    frictionless = ContactSet(
        soil=ContactParameters(7.5e7, 5e7, 0.0, 0.0),
        pipe=ContactParameters(1e9, 1e9, 0.0),
        wall=ContactParameters(1e9, 1e9, 0.0),
    )
    sim0 = Simulation(s, frictionless, damping=0.0, gravity=(0, 0))
    # leapfrog: velocities are half a step behind the positions, so the measured energy
    # fluctuates by O(Δt) during collisions; a tenth of the usual step keeps that < 1e-3
    sim = Simulation(s, frictionless, damping=0.0, gravity=(0, 0), dt=sim0.dt / 10)
    e0 = _energy(sim)
    for _ in range(40):
        sim.run(2000)
        assert _energy(sim) == pytest.approx(e0, rel=1e-3)
    assert sim.rebuilds > 1


def _pressed_pair(extra=None, **kw):
    """Disk 1 resting on fixed disk 0 under strong gravity, sliding sideways."""
    r = 1e-3
    g = 1e4
    m = 2650 * math.pi * r * r
    ov = m * g / SOIL.k_n
    pos = [[0.01, 0.01], [0.01, 0.01 + 2 * r - ov]]
    vel = [[0.0, 0.0], [0.02, 0.0]]
    if extra is not None:
        pos.append(extra[0])
        vel.append(extra[1])
    n = len(pos)
    s = Sample(np.array(pos), np.full(n, r), (0, 0.03, 0, 0.04), velocities=np.array(vel))
    sim = Simulation(s, TABLE3, damping=0.0, gravity=(0, -g), **kw)
    sim.fixed[0] = True
    return sim


def test_shear_history_survives_neighbour_list_rebuilds():
    """A sheared pair gives bitwise the same history with a rebuild at every step."""
    a = _pressed_pair()
    b = _pressed_pair()
    for _ in range(300):
        a.run(1)
        b.run(1)
        b.rebuild()
    assert b.rebuilds > 300
    assert a.fs[0] != 0.0
    assert a.mr[0] != 0.0
    assert a.fs[0] == b.fs[0]
    assert a.mr[0] == b.mr[0]
    np.testing.assert_array_equal(a.pos, b.pos)


def test_history_survives_a_skin_triggered_rebuild():
    """The history of a contact that stays closed is carried over by the sorted merge."""
    sim = _pressed_pair(extra=([0.02, 0.02], [1.0, 0.0]), skin=1e-4)
    twin = _pressed_pair(extra=([0.02, 0.02], [1.0, 0.0]), skin=1.0)  # never rebuilds
    reb0 = sim.rebuilds
    while sim.rebuilds == reb0:
        sim.run(1)
        twin.run(1)
    for _ in range(20):
        sim.run(1)
        twin.run(1)
    assert twin.rebuilds == 1
    k = int(np.flatnonzero(sim.nbr[sim.start[0] : sim.start[1]] == 1)[0]) + sim.start[0]
    kt = int(np.flatnonzero(twin.nbr[twin.start[0] : twin.start[1]] == 1)[0]) + twin.start[0]
    assert sim.fs[k] != 0.0
    assert sim.fs[k] == twin.fs[kt]
    assert sim.mr[k] == twin.mr[kt]


def test_pipe_force_is_sum_of_its_contact_forces():
    s = _box_sample(n=14, seed=7)
    sim = Simulation(
        s, TABLE3, damping=0.7, gravity=(0, -9.81), pipe=PipeState(0.006, 0.0098, 0.003, -1.0)
    )
    for _ in range(50):
        sim.run(20)
        fx, fy = sim.pipe_force()
        px, py, pr = sim.prm[K.P_PIPE_X], sim.prm[K.P_PIPE_Y], sim.prm[K.P_PIPE_R]
        # contact forces of the last step, from the positions before the last update
        pos_prev = sim.pos - sim.dt * sim.vel
        py_prev = py - sim.prm[K.P_PIPE_V] * sim.dt
        d = np.hypot(px - pos_prev[:, 0], py_prev - pos_prev[:, 1])
        ov = sim.rad + pr - d
        touch = ov > 0
        nx = (px - pos_prev[:, 0]) / d
        ny = (py_prev - pos_prev[:, 1]) / d
        fs = sim.fsw[:, K.PIPE]
        gx = np.sum((1e9 * ov * nx + fs * ny)[touch])
        gy = np.sum((1e9 * ov * ny - fs * nx)[touch])
        assert fx == pytest.approx(gx, rel=1e-9, abs=1e-9 * max(1.0, abs(gy)))
        assert fy == pytest.approx(gy, rel=1e-9, abs=1e-12)


def test_result_independent_of_thread_count():
    s = _box_sample(n=14, seed=9)
    runs = []
    for threads in (1, 2):
        sim = Simulation(s, TABLE3, gravity=(0, -9.81), threads=threads)
        sim.run(60)
        runs.append(sim.pos.copy())
    np.testing.assert_array_equal(runs[0], runs[1])


def test_branch_free_pair_law_equals_contact_update_bitwise():
    """The flat pair loop (selects instead of branches) gives the bits of ``contact_update``.

    Random pairs around contact (open and closed), random velocities and histories, many of
    them beyond the shear and rolling caps.
    """
    rng = np.random.default_rng(4)
    m = 4000
    r = 1e-3 * (0.8 + 0.4 * rng.random(2 * m))
    pos = np.zeros((2 * m, 2))
    gap = (r[:m] + r[m:]) * (1.0 + 0.02 * rng.standard_normal(m))
    ang = 2 * np.pi * rng.random(m)
    pos[m:, 0] = gap * np.cos(ang)
    pos[m:, 1] = gap * np.sin(ang)
    vel = 0.1 * rng.standard_normal((2 * m, 2))
    om = 100.0 * rng.standard_normal(2 * m)
    owner = np.arange(m, dtype=np.uint32)
    nbr = np.arange(m, 2 * m, dtype=np.uint32)
    fs0 = 2.0 * rng.standard_normal(m)
    mr0 = 2e-3 * rng.standard_normal(m)
    dt, kn, ks, mu, mur = 1e-6, 7.5e7, 5e7, 0.4, 0.8
    fs, mr = fs0.copy(), mr0.copy()
    cfx, cfy, cmag = np.empty(m), np.empty(m), np.empty(m)
    K._pair_entries(0, m, owner, nbr, pos, vel, om, r, fs, mr, cfx, cfy, cmag, True, dt, kn, ks,
                    mu, mur)  # fmt: skip
    closed = capped = 0
    for k in range(m):
        i, j = k, m + k
        dx, dy = pos[j] - pos[i]
        rsum = r[i] + r[j]
        if dx * dx + dy * dy >= rsum * rsum:
            assert (fs[k], mr[k], cfx[k], cfy[k], cmag[k]) == (0.0, 0.0, 0.0, 0.0, 0.0)
            continue
        d = np.sqrt(dx * dx + dy * dy)
        nx, ny = dx / d, dy / d
        tx, ty = -ny, nx
        vt = (vel[j, 0] - vel[i, 0]) * tx + (vel[j, 1] - vel[i, 1]) * ty
        vt -= om[j] * r[j] + om[i] * r[i]
        rbar = r[i] * r[j] / rsum
        fn, f, mm = K.contact_update(
            nx, ny, rsum - d, vt, om[j] - om[i], rbar, kn, ks, mu, mur, fs0[k], mr0[k], dt
        )
        assert fs[k] == f and mr[k] == mm
        assert cfx[k] == -fn * nx + f * tx and cfy[k] == -fn * ny + f * ty
        assert cmag[k] == np.sqrt(fn * fn + f * f)
        closed += 1
        capped += abs(f) == mu * fn
    assert closed > m // 3 and capped > 0


def test_frictionless_pair_law_equals_the_full_law_at_zero_friction():
    """The compaction's normal-only law (μ = μ_r = 0) gives the full law's forces and zero
    histories from any start (equal as numbers: a ±0 shear term can only flip a zero's sign).
    """
    rng = np.random.default_rng(5)
    m = 4000
    r = 1e-3 * (0.8 + 0.4 * rng.random(2 * m))
    pos = np.zeros((2 * m, 2))
    gap = (r[:m] + r[m:]) * (1.0 + 0.02 * rng.standard_normal(m))
    ang = 2 * np.pi * rng.random(m)
    pos[m:, 0] = gap * np.cos(ang)
    pos[m:, 1] = gap * np.sin(ang)
    pos[m : m + 50, 0] = 0.0  # exactly vertical pairs: a zero force component
    vel = 0.1 * rng.standard_normal((2 * m, 2))
    om = 100.0 * rng.standard_normal(2 * m)
    owner = np.arange(m, dtype=np.uint32)
    nbr = np.arange(m, 2 * m, dtype=np.uint32)
    fs0 = 2.0 * rng.standard_normal(m)
    mr0 = 2e-3 * rng.standard_normal(m)
    dt, kn, ks = 1e-6, 7.5e7, 5e7
    out = {}
    for name in ("full", "normal"):
        fs, mr = fs0.copy(), mr0.copy()
        cfx, cfy, cmag = np.empty(m), np.empty(m), np.empty(m)
        if name == "full":
            K._pair_entries(0, m, owner, nbr, pos, vel, om, r, fs, mr, cfx, cfy, cmag, True, dt,
                            kn, ks, 0.0, 0.0)  # fmt: skip
        else:
            K._pair_entries_frictionless(0, m, owner, nbr, pos, r, fs, mr, cfx, cfy, cmag, True, kn)
        out[name] = (fs, mr, cfx, cfy, cmag)
    for a, b in zip(out["full"], out["normal"], strict=True):
        np.testing.assert_array_equal(a, b)
    fs, mr, cfx, cfy, cmag = out["normal"]
    closed = cmag > 0.0
    assert closed.sum() > m // 3 and not fs.any() and not mr.any()
    np.testing.assert_allclose(np.hypot(cfx, cfy)[closed], cmag[closed], rtol=1e-15)


@pytest.mark.parametrize("nsub", [1, 4])
def test_boundary_skip_gives_the_bits_of_the_full_boundary_pass(nsub):
    """Disks clear of the walls, lid and pipe skip their contact laws (``stiff`` flag).

    Every call of ``run`` starts with the full pass for every disk, so 400 calls of one step
    never skip; one call of 400 steps skips whenever a disk is clear and carries no wall,
    lid or pipe history. Disks bounce on the walls, the lid and the moving pipe (all with
    friction, the pipe with rolling resistance), closing and opening these contacts; the two
    must agree bit for bit (positions, velocities, wall and pipe histories, pipe force), with
    zonal sub-cycling off and on.
    """
    s = _box_sample(n=14, seed=11)
    contacts = ContactSet(
        soil=SOIL, pipe=ContactParameters(1e9, 1e9, 0.3, 0.1), wall=ContactParameters(1e9, 1e9, 0.2)
    )
    runs = []
    for calls, steps in ((400, 1), (1, 400)):
        sim = Simulation(
            s,
            contacts,
            damping=0.7,
            gravity=(0.0, -25 * 9.81),
            pipe=PipeState(0.006, 0.0098, 0.003, -1.0),
            nsub=nsub,
        )
        sim.set_lid(0.0128, -0.05)
        closed = np.zeros(sim.fsw.shape, bool)
        closings = openings = 0
        for _ in range(calls):
            sim.run(steps)
            now = sim.fsw != 0.0
            closings += np.count_nonzero(now & ~closed)
            openings += np.count_nonzero(closed & ~now)
            closed = now
        runs.append(sim)
        if calls > 1:
            assert closings >= 3 and openings >= 3, (closings, openings)
    a, b = runs
    for name in ("pos", "vel", "om", "fsw", "mrw", "pfx", "pfy"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    assert a.pipe_force() == b.pipe_force()
