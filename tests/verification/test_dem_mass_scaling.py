"""Verification of inertial mass scaling (``Simulation(inertial_mass_floor=…)``,
``Numerics.penetration_mass_floor``).

Scaling changes only the mass that divides a disk's force (and its moment of inertia),
never its weight nor the contact law: the kernel follows the plain-Python twin with the same
split of the two masses, a free fall accelerates at (m/m_inertial)·g, a collision lasts half
a period of the spring on the inertial masses, a static state carries the true weights,
and a floor below every mass changes no bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.dem._reference import ReferenceSystem
from onbottom.dem.config import PRESETS, ContactParameters, ContactSet, Numerics
from onbottom.dem.engine import PipeState, Simulation, step_sizes
from onbottom.dem.experiment import make_simulation
from onbottom.dem.identity import dem_identity, differences
from onbottom.dem.preparation import settle
from onbottom.dem.sample import Sample
from onbottom.errors import InputError

pytestmark = pytest.mark.verification

SOIL = ContactParameters(k_n=7.5e7, k_s=5e7, mu=0.4, mu_r=0.8)
TABLE3 = ContactSet(
    soil=SOIL, pipe=ContactParameters(1e9, 1e9, 0.3), wall=ContactParameters(1e9, 1e9, 0.0)
)
RHO = 2650.0


def _box_sample(n=14, seed=3, r=1e-3, width=0.012, height=0.02):
    rng = np.random.default_rng(seed)
    cols = int(width / (2.3 * r))
    pos = np.array([[(k % cols + 0.6) * 2.3 * r, (k // cols + 0.6) * 2.3 * r] for k in range(n)])
    radii = r * (0.8 + 0.4 * rng.random(n))
    vel = 0.05 * rng.standard_normal((n, 2))
    om = 20.0 * rng.standard_normal(n)
    return Sample(pos, radii, (0.0, width, 0.0, height), velocities=vel, omega=om)


def test_scaled_kernel_matches_python_twin():
    """Walls, lid, pipe, friction, rolling, damping, 25 g, masses scaled: kernel == twin."""
    s = _box_sample()
    contacts = ContactSet(
        soil=SOIL, pipe=ContactParameters(1e9, 1e9, 0.3, 0.1), wall=ContactParameters(1e9, 1e9, 0.2)
    )
    m = RHO * math.pi * s.radii**2
    floor = float(np.quantile(m, 0.7))  # most disks scaled, some not
    sim = Simulation(
        s,
        contacts,
        damping=0.7,
        gravity=(0.0, -25 * 9.81),
        pipe=PipeState(0.006, 0.0098, 0.003, -1.0),
        inertial_mass_floor=floor,
        # the unscaled step (as test_dem_engine's twin test): the same simulated time, so
        # that round-off grows as much as there (the larger default step is chaotic sooner)
        dt=Simulation(s, contacts).dt,
    )
    sim.set_lid(0.0128, -0.05)
    assert np.array_equal(sim.mass, m)  # the weights stay true
    assert np.array_equal(sim.inertial_mass, np.maximum(m, floor))
    ref = ReferenceSystem(
        sim.prm, sim.pos, sim.vel, sim.om, sim.rad, sim.mass, sim.inert, sim.inertial_mass
    )
    for _ in range(800):
        sim.run(1)
        ref.step()
    assert sim.rebuilds >= 1
    scale = np.abs(ref.vel).max()
    np.testing.assert_allclose(sim.pos, ref.pos, rtol=0, atol=1e-10)
    np.testing.assert_allclose(sim.vel, ref.vel, rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(sim.om, ref.om, rtol=0, atol=1e-6 * np.abs(ref.om).max())


def test_floor_below_every_mass_changes_no_bit():
    """max(m, floor) = m for every disk: the same bits as the unscaled engine."""
    s = _box_sample(n=30, seed=5)
    m_min = RHO * math.pi * float(s.radii.min()) ** 2
    runs = []
    for floor in (0.0, 0.5 * m_min):
        sim = Simulation(s, TABLE3, damping=0.7, gravity=(0.0, -9.81), inertial_mass_floor=floor)
        sim.run(2000)
        runs.append((sim.pos.copy(), sim.vel.copy(), sim.om.copy()))
    for a, b in zip(runs[0], runs[1], strict=True):
        assert np.array_equal(a, b)


def test_free_fall_accelerates_at_the_weight_over_the_inertial_mass():
    """Undamped, in the air: v(t) = −(m/m_inertial)·g·t (leapfrog is exact for constant F)."""
    r = 1e-3
    m = RHO * math.pi * r * r
    s = Sample(np.array([[0.01, 0.01]]), np.array([r]), (0.0, 0.02, 0.0, 0.02))
    for factor in (1.0, 4.0):
        sim = Simulation(
            s, TABLE3, damping=0.0, gravity=(0.0, -9.81), inertial_mass_floor=factor * m
        )
        sim.run(100)
        assert sim.vel[0, 1] == pytest.approx(-9.81 / factor * 100 * sim.dt, rel=1e-12)


def test_collision_lasts_half_a_period_of_the_inertial_masses():
    """Head-on, undamped, frictionless: contact time π·√(m_eff/k_n) with the inertial m_eff."""
    r = 1e-3
    m = RHO * math.pi * r * r
    floor = 3.0 * m
    v0 = 0.1
    s = Sample(
        np.array([[0.005 - r - 1e-6, 0.01], [0.005 + r + 1e-6, 0.01]]),
        np.array([r, r]),
        (0.0, 0.01, 0.0, 0.02),
        velocities=np.array([[v0, 0.0], [-v0, 0.0]]),
    )
    contacts = ContactSet(
        soil=ContactParameters(7.5e7, 5e7, 0.0, 0.0),
        pipe=TABLE3.pipe,
        wall=TABLE3.wall,
    )
    sim = Simulation(s, contacts, damping=0.0, gravity=(0.0, 0.0), inertial_mass_floor=floor)
    t_in = t_out = None
    for _ in range(20000):
        sim.run(1)
        gap = sim.pos[1, 0] - sim.pos[0, 0] - 2 * r
        if t_in is None and gap < 0:
            t_in = sim.time
        if t_in is not None and gap >= 0:
            t_out = sim.time
            break
    assert t_out is not None
    expected = math.pi * math.sqrt(0.5 * floor / 7.5e7)
    assert t_out - t_in == pytest.approx(expected, abs=2 * sim.dt)
    # elastic: the speeds come back (to the half-step velocity's O(Δt) error), momentum zero
    assert sim.vel[0, 0] == pytest.approx(-v0, rel=5e-3)
    assert sim.vel[0, 0] + sim.vel[1, 0] == pytest.approx(0.0, abs=1e-12)


def test_static_column_carries_the_true_weights():
    """A column of disks settled with scaled inertia: the floor carries Σ m_i·g exactly."""
    r = np.array([0.9e-3, 0.6e-3, 1.1e-3, 0.7e-3])
    y = np.cumsum(2 * r) - r + 1e-5 * np.arange(1, 5)
    s = Sample(np.column_stack([np.full(4, 0.005), y]), r, (0.0, 0.01, 0.0, 0.02))
    m = RHO * math.pi * r**2
    for floor in (0.0, float(m.max())):
        sim = Simulation(
            s, TABLE3, damping=0.7, gravity=(0.0, -25 * 9.81), inertial_mass_floor=floor
        )
        ok, ratio = settle(sim, 1e-6, 0.2, min_time=1e-3)
        assert ok, ratio
        # overlap with the floor: k_n·δ = total weight of the column
        base = int(np.argmin(sim.pos[:, 1]))
        overlap = sim.rad[base] - sim.pos[base, 1]
        assert 1e9 * overlap == pytest.approx(float(m.sum()) * 25 * 9.81, rel=1e-5)


def test_step_follows_the_lightest_inertial_mass():
    s = _box_sample()
    m = RHO * math.pi * s.radii**2
    floor = float(m.max())
    sim = Simulation(s, TABLE3, inertial_mass_floor=floor, nsub=4)
    dt, nsub = step_sizes(TABLE3, floor, 0.5, True)
    assert sim.dt == pytest.approx(dt) and nsub == 4
    assert sim.dt / Simulation(s, TABLE3, nsub=4).dt == pytest.approx(math.sqrt(floor / m.min()))


def test_penetration_mass_floor_sets_the_penetration_step():
    """Floor 1.0 on the SM-reduced preset: Δt grows by d_max/d_min of the specimen."""
    cfg = PRESETS["SM-reduced"]
    s = _box_sample(n=40, seed=2)
    base = make_simulation(cfg, s)
    scaled_cfg = cfg.replace(numerics=Numerics(subcycle=True, penetration_mass_floor=1.0))
    scaled = make_simulation(scaled_cfg, s)
    ratio = float(s.radii.max() / s.radii.min())
    assert scaled.dt / base.dt == pytest.approx(ratio)
    assert np.array_equal(scaled.mass, base.mass)
    assert scaled.inertial_mass.min() == pytest.approx(scaled.mass.max())


@pytest.mark.parametrize("value", [-0.1, 1.5, float("nan")])
def test_bad_mass_floor_is_a_named_error(value):
    with pytest.raises(InputError, match="penetration_mass_floor"):
        Numerics(penetration_mass_floor=value)
    with pytest.raises(InputError, match="inertial_mass_floor"):
        Simulation(_box_sample(n=3), TABLE3, inertial_mass_floor=min(value, -0.1))


def test_files_written_before_the_field_match_the_unscaled_default():
    cfg = PRESETS["SM-reduced"]
    ident = dem_identity(cfg, "penetration").fields
    old = {**ident, "config": dict(ident["config"])}
    old["config"]["numerics"] = {
        k: v for k, v in ident["config"]["numerics"].items() if k != "penetration_mass_floor"
    }
    assert differences(old, ident) == []
    scaled = cfg.replace(numerics=Numerics(subcycle=True, penetration_mass_floor=1.0))
    assert differences(old, dem_identity(scaled, "penetration").fields) != []


# --------------------------------------------------------------- the preparation's stages
def _tiny(**numerics):
    from onbottom.dem.config import SD_REDUCED, Geometry, Loading, Preparation

    return SD_REDUCED.replace(
        name="tiny",
        geometry=Geometry(width=0.06, height=0.02, pipe_diameter=0.02),
        preparation=Preparation(n_layers=2, max_settle_time=0.05),
        loading=Loading(gravity_factor=25.0, pipe_velocity=0.1, final_embedment_ratio=0.05),
        numerics=Numerics(subcycle=True, **numerics),
    )


def _recorded_steps(monkeypatch) -> list[tuple[float, float]]:
    """(Δt, lightest inertial mass) of every settle the preparation calls."""
    from onbottom.dem import preparation

    calls: list[tuple[float, float]] = []
    original = preparation.settle

    def recording(sim, *args, **kwargs):
        calls.append((sim.dt, float(sim.inertial_mass.min())))
        return original(sim, *args, **kwargs)

    monkeypatch.setattr(preparation, "settle", recording)
    return calls


def test_equilibrium_floor_scales_the_1g_and_Ng_stages_only(monkeypatch):
    """The layers keep the true masses and the plain step (the compaction is the preset's,
    bit for bit); the 1 g and N g stages step d_max/d_min longer on scaled inertia. (Whether
    they end in the same state is a question for the validation runs: on this 2-layer
    specimen, whose 1 g stage reaches its time cap either way, they do not.)"""
    from onbottom.dem.preparation import prepare_sample

    base_cfg, cfg = _tiny(), _tiny(equilibrium_mass_floor=1.0)
    recorded = _recorded_steps(monkeypatch)
    base = prepare_sample(base_cfg)
    base_calls = list(recorded)
    s = prepare_sample(cfg)
    calls = recorded[len(base_calls) :]
    n_l = cfg.preparation.n_layers
    assert calls[:n_l] == base_calls[:n_l]
    assert s.attrs["void_ratio_compacted"] == base.attrs["void_ratio_compacted"]
    d = 2 * s.radii
    for (dt, m), (dt0, m0) in zip(calls[n_l:], base_calls[n_l:], strict=True):
        assert dt / dt0 == pytest.approx(float(d.max() / d.min()))
        assert m == pytest.approx(RHO * math.pi * float(s.radii.max()) ** 2)
        assert m0 == pytest.approx(RHO * math.pi * float(s.radii.min()) ** 2)
    assert s.attrs["dt"] / base.attrs["dt"] == pytest.approx(float(d.max() / d.min()))


def test_default_floors_keep_the_preparation_bits():
    """Floors of 0 (the default) and floors below the lightest disk: the same specimen."""
    from onbottom.dem.preparation import prepare_sample

    a = prepare_sample(_tiny())
    b = prepare_sample(_tiny(equilibrium_mass_floor=1e-3))  # (d_max/d_min)² ≈ 6.5 < 1e3
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.contacts["fs"], b.contacts["fs"])


def test_lammps_backend_refuses_scaled_masses():
    from onbottom.dem.lammps_backend import LammpsPenetrationCase

    cfg = PRESETS["SM-reduced"]
    scaled = cfg.replace(numerics=Numerics(subcycle=True, penetration_mass_floor=0.5))
    with pytest.raises(InputError, match="penetration_mass_floor"):
        LammpsPenetrationCase.from_config(scaled, _box_sample(n=5))
