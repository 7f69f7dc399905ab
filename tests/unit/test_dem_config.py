"""DEM configuration, sample container and post-processing (hand calculations)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onbottom.cases.dem import dem_config_from_json
from onbottom.dem.analysis import (
    band_void_ratio,
    circle_disk_overlap_area,
    inertial_number,
    surface_profile,
)
from onbottom.dem.config import (
    PRESETS,
    SD,
    SM,
    ContactParameters,
    Geometry,
    ParticleSizeDistribution,
    get_preset,
)
from onbottom.dem.engine import critical_time_step
from onbottom.dem.sample import Sample
from onbottom.errors import InputError


def test_presets_match_the_paper_table3():
    for cfg in (SM, SD):
        assert cfg.geometry.width == pytest.approx(13 * 0.02)
        assert cfg.geometry.height == pytest.approx(5.5 * 0.02)
        assert cfg.contacts.soil == ContactParameters(7.5e7, 5e7, 0.4, 0.8)
        assert cfg.contacts.pipe == ContactParameters(1e9, 1e9, 0.3, 0.0)
        assert cfg.contacts.wall == ContactParameters(1e9, 1e9, 0.0, 0.0)
        assert cfg.material.damping == 0.7
        assert cfg.material.density == 2650.0
        assert cfg.loading.gravity_factor == 25.0
        assert cfg.loading.pipe_velocity == 0.01
        assert cfg.loading.final_embedment_ratio == 0.5
    assert SM.target.relative_density == pytest.approx(0.48)
    assert SD.target.relative_density == pytest.approx(0.78)
    # paper: 58,710 and 60,150 disks; the uniform-by-number PSD gives them within 3 %
    assert SM.estimated_particle_count() == pytest.approx(58710, rel=0.03)
    assert SD.estimated_particle_count() == pytest.approx(60150, rel=0.03)
    assert set(PRESETS) == {"SM", "SD", "SM-reduced", "SD-reduced", "SM-Dr48"}


def test_psd_reproduces_d50_and_cu():
    for basis in ("number", "mass"):
        psd = ParticleSizeDistribution(0.68e-3, 1.67, basis)
        assert psd.quantile(0.5) == pytest.approx(0.68e-3)
        assert psd.quantile(0.6) / psd.quantile(0.1) == pytest.approx(1.67)
    rng = np.random.default_rng(0)
    d = ParticleSizeDistribution(0.68e-3, 1.67).sample_diameters(200_000, rng)
    assert np.median(d) == pytest.approx(0.68e-3, rel=0.01)
    assert np.quantile(d, 0.6) / np.quantile(d, 0.1) == pytest.approx(1.67, rel=0.01)
    dm = ParticleSizeDistribution(0.68e-3, 1.67, "mass").sample_diameters(200_000, rng)
    w = np.argsort(dm)
    cum = np.cumsum(dm[w] ** 2) / np.sum(dm**2)
    assert dm[w][np.searchsorted(cum, 0.5)] == pytest.approx(0.68e-3, rel=0.01)


def test_config_roundtrip_and_validation():
    assert dem_config_from_json(SM.to_json()) == SM
    assert get_preset("SD-reduced").name == "SD-reduced"
    with pytest.raises(InputError, match="k_n"):
        ContactParameters(-1.0, 1.0, 0.3)
    with pytest.raises(InputError, match="pipe_diameter"):
        Geometry(0.01, 0.1, 0.02)
    with pytest.raises(InputError, match="preset"):
        get_preset("XX")


def test_inertial_number_reproduces_paper_value():
    """Paper §4.1: I = 4.38e-4 for v = 0.01 m/s (SD: e = 0.197, N = 25, H = 5.5D)."""
    n = 0.197 / 1.197
    i = inertial_number(0.01, 0.11, 0.68e-3, 2650.0, n, 25.0)
    assert i == pytest.approx(4.38e-4, rel=0.02)


def test_critical_time_step_order_of_the_spec():
    m_min = 2650 * math.pi * (SM.psd.d_min / 2) ** 2
    dt = SM.numerics.dt_safety * critical_time_step(m_min, 1e9)
    assert 2e-7 < dt < 6e-7


def test_circle_disk_overlap_area_cases():
    x = np.array([0.0, 3.0, 1.0])
    y = np.zeros(3)
    r = np.array([0.5, 0.5, 1.0])
    a = circle_disk_overlap_area(0.0, 0.0, 1.0, x, y, r)
    assert a[0] == pytest.approx(math.pi * 0.25)  # inside
    assert a[1] == 0.0  # outside
    # two unit circles at distance 1: 2π/3 − √3/2
    assert a[2] == pytest.approx(2 * math.pi / 3 - math.sqrt(3) / 2)


def test_band_void_ratio_of_a_square_lattice():
    a = 1.0
    xs, ys = np.meshgrid(np.arange(10) + 0.5, np.arange(10) + 0.5)
    pos = np.stack([xs.ravel(), ys.ravel()], 1)
    r = np.full(100, 0.5)
    e = band_void_ratio(pos, r, (0.0, 10.0), (2.0, 8.0))
    assert e == pytest.approx((a * a - math.pi / 4) / (math.pi / 4))
    _, top = surface_profile(pos, r, (0.0, 10.0, 0.0, 10.0), 1.0)
    np.testing.assert_allclose(top, 10.0)


def test_sample_netcdf_roundtrip(tmp_path):
    rng = np.random.default_rng(1)
    s = Sample(
        rng.random((20, 2)),
        np.full(20, 0.01),
        (0.0, 1.0, 0.0, 1.0),
        contacts={
            "i": np.array([0, 1]),
            "j": np.array([3, -2]),
            "fs": np.array([1.5, -2.0]),
            "mr": np.array([0.1, 0.0]),
        },
        attrs={"stage": "test"},
    )
    path = s.save(tmp_path / "s.nc")
    t = Sample.load(path)
    np.testing.assert_array_equal(t.positions, s.positions)
    np.testing.assert_array_equal(t.contacts["j"], s.contacts["j"])
    assert t.attrs == {"stage": "test"}
    assert t.box == s.box
    with pytest.raises(InputError, match="positions"):
        Sample(np.zeros((3, 3)), np.ones(3), (0, 1, 0, 1))


def test_sd_presets_subcycle_the_penetration_only_at_half_the_step():
    """SD: plain step in the preparation, sub-cycled penetration at subcycle_dt_safety 0.25."""
    import dataclasses

    from onbottom.dem.config import PRESETS, Numerics
    from onbottom.dem.experiment import make_simulation

    sd = PRESETS["SD-reduced"]
    assert sd.numerics.subcycle and not sd.numerics.prep_subcycles
    assert sd.numerics.subcycled_dt_safety == 0.25
    assert PRESETS["SM-Dr48"].numerics.prep_subcycles
    assert PRESETS["SM"].numerics.subcycled_dt_safety == 0.5
    rng = np.random.default_rng(0)
    radii = np.full(4, 1e-3)
    sample = Sample(rng.random((4, 2)) * 0.1, radii, (0.0, 0.14, 0.0, 0.06))
    m_min = sd.material.density * math.pi * 1e-6
    sim = make_simulation(sd, sample, threads=1)
    assert sim.dt == pytest.approx(0.25 * critical_time_step(m_min, 7.5e7))
    assert sim.nsub == 4  # ceil(sqrt(1e9 / 7.5e7))
    plain = sd.replace(numerics=dataclasses.replace(sd.numerics, subcycle=False))
    sim = make_simulation(plain, sample, threads=1)
    assert sim.dt == pytest.approx(0.5 * critical_time_step(m_min, 1e9))
    assert sim.nsub == 1
    with pytest.raises(InputError, match="subcycle_dt_safety"):
        Numerics(subcycle_dt_safety=0.0)


def test_a_field_added_later_with_its_old_default_is_no_difference():
    from onbottom.dem.identity import differences

    saved = {"config": {"numerics": {"subcycle": True}}}
    now = {"config": {"numerics": {"subcycle": True, "subcycle_preparation": True}}}
    assert differences(saved, now) == []
    now["config"]["numerics"]["subcycle_preparation"] = False
    assert differences(saved, now) == [
        "config.numerics.subcycle_preparation: '(absent)' in the file, False now"
    ]
    now = {"config": {"numerics": {"subcycle": True, "subcycle_dt_safety": None}}}
    assert differences(saved, now) == []


def test_lid_pause_is_validated_and_defaults_to_the_committed_runs():
    from onbottom.dem.config import Preparation
    from onbottom.dem.identity import differences

    assert Preparation().lid_pause == "fixed"
    with pytest.raises(InputError, match="lid_pause"):
        Preparation(lid_pause="sometimes")
    saved = {"config": {"preparation": {"n_layers": 4}}}
    now = {"config": {"preparation": {"n_layers": 4, "lid_pause": "fixed"}}}
    assert differences(saved, now) == []


def test_fire_1g_relaxes_only_the_1g_stage_and_is_allowed_with_subcycling():
    """``relaxation = "fire-1g"``: FIRE in the 1 g stage only (at the plain step), so unlike
    ``"fire"`` it goes with a sub-cycled preparation; the values are validated by name."""
    import dataclasses

    from onbottom.dem.config import RELAXATIONS, Preparation

    p = Preparation(relaxation="fire-1g")
    assert [p.stage_relaxation(s) for s in ("layer", "1g", "Ng")] == ["damped", "fire", "damped"]
    f = Preparation(relaxation="fire")
    assert [f.stage_relaxation(s) for s in ("layer", "1g", "Ng")] == ["fire"] * 3
    assert "fire-1g" in RELAXATIONS
    assert PRESETS["SM-Dr48"].numerics.prep_subcycles
    ok = SM.replace(preparation=dataclasses.replace(SM.preparation, relaxation="fire-1g"))
    assert ok.preparation.relaxation == "fire-1g"
    with pytest.raises(InputError, match="relaxation"):
        SM.replace(preparation=dataclasses.replace(SM.preparation, relaxation="fire"))
    with pytest.raises(InputError, match="relaxation.*fire-2g"):
        Preparation(relaxation="fire-2g")


def test_compaction_step_is_validated_and_defaults_to_the_plain_step():
    import dataclasses

    from onbottom.dem.config import PRESETS, Numerics
    from onbottom.dem.identity import differences

    assert Numerics().compaction_dt_safety is None
    assert Numerics(dt_safety=0.4).compaction_step_safety == 0.4
    assert Numerics(compaction_dt_safety=1.0).compaction_step_safety == 1.0
    for bad in (0.0, -0.5, 1.5, float("nan"), "fast"):
        with pytest.raises(InputError, match="compaction_dt_safety"):
            Numerics(compaction_dt_safety=bad)
    sm = PRESETS["SM-reduced"]
    lever = dataclasses.replace(sm.numerics, compaction_dt_safety=1.0)
    with pytest.raises(InputError, match="compaction_dt_safety.*prep_friction = 0.3"):
        sm.replace(
            numerics=lever, preparation=dataclasses.replace(sm.preparation, prep_friction=0.3)
        )
    saved = {"config": {"numerics": {"subcycle": True}}}
    now = {"config": {"numerics": {"subcycle": True, "compaction_dt_safety": None}}}
    assert differences(saved, now) == []
    now["config"]["numerics"]["compaction_dt_safety"] = 1.0
    assert differences(saved, now) == [
        "config.numerics.compaction_dt_safety: '(absent)' in the file, 1.0 now"
    ]


def test_dem_config_file_reads_back_and_errors_name_the_key_and_file(tmp_path):
    import json

    from onbottom._casefile import CaseFileError
    from onbottom.cases.dem import load_dem_config

    p = tmp_path / "config.json"
    p.write_text(SM.to_json(), encoding="utf-8")
    assert load_dem_config(p) == SM
    doc = json.loads(SM.to_json())
    doc["geometry"]["widht"] = doc["geometry"].pop("width")
    p.write_text(json.dumps(doc, indent=1, sort_keys=True), encoding="utf-8")
    with pytest.raises(CaseFileError) as err:
        load_dem_config(p)
    assert err.value.field == "geometry.widht" and str(p) in str(err.value)
    assert "did you mean 'width'" in str(err.value)
    p.write_text('{\n  "name": "x",\n  "seed": \n}\n', encoding="utf-8")
    with pytest.raises(CaseFileError) as err:  # malformed JSON: the line the parser stopped at
        load_dem_config(p)
    assert err.value.line == 4 and str(p) in str(err.value)


def test_sample_and_run_loaders_name_the_file(tmp_path):
    from onbottom.cases.dem import load_run, load_sample

    p = tmp_path / "not_netcdf.nc"
    p.write_text("plain text", encoding="utf-8")
    with pytest.raises(InputError, match=r"--sample = .*not_netcdf.nc.* not a readable specimen"):
        load_sample(p)
    with pytest.raises(InputError, match=r"results = .*not_netcdf.nc.* not a readable NetCDF"):
        load_run(p)
