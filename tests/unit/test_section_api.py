"""Unit tests: simulate_section inputs, statuses, outputs and NetCDF round trip."""

from __future__ import annotations

import numpy as np
import pytest

from onbottom import InputError, Pipe
from onbottom.dynamics.programmes import from_arrays, inclined_cyclic
from onbottom.dynamics.section import SolverSettings, section_mass, simulate_section
from onbottom.results import load_dataset
from onbottom.soil.coulomb import CoulombFriction


def _prog():
    return inclined_cyclic(1000.0, 100.0, 10.0, 90.0, 8)  # μV = 500: slides from cycle 6


def test_section_mass_is_pipe_plus_added_mass():
    pipe = Pipe(outer_diameter=1.0, submerged_weight=10.52e3, mass=1500.0)
    assert section_mass(pipe, 2.29) == pytest.approx(1500.0 + 2.29 * 1025.0 * np.pi / 4.0)
    assert section_mass(pipe, 0.0) == 1500.0


def test_statuses_and_outputs(tmp_path):
    soil = CoulombFriction(friction_coefficient=0.5)
    end = simulate_section(_prog(), soil, mass=100.0)
    assert end.success and end.status == 1 and end.cycles_to_limit is None
    assert end.data["time"].values[-1] == pytest.approx(80.0)
    stop = simulate_section(_prog(), soil, mass=100.0, displacement_limit=0.5)
    assert stop.status == 2 and 5.0 < stop.cycles_to_limit < 8.0
    assert abs(stop.data["y"].values[-1]) >= 0.5
    cont = simulate_section(
        _prog(), soil, mass=100.0, displacement_limit=0.5, after_limit="continue"
    )
    assert cont.status == 1 and cont.cycles_to_limit == pytest.approx(stop.cycles_to_limit)
    # records: friction + passive = soil force, units and provenance
    ds = stop.data
    np.testing.assert_allclose(ds["F_friction"] + ds["F_passive"], ds["F_soil"])
    assert ds["H"].attrs["units"] == "N/m" and ds.attrs["model"] == "simulate_section"
    back = load_dataset(stop.save(tmp_path / "s.nc"))
    np.testing.assert_array_equal(back["y"].values, ds["y"].values)
    assert stop.summary["max_abs_displacement"] >= 0.5


def test_lift_off_runs_free():
    # V <= 0: no resistance; H = 100 N/m on m = 100 kg/m accelerates at 1 m/s²
    prog = from_arrays([0.0, 2.0], [100.0, 100.0], [-1.0, -1.0])
    res = simulate_section(
        prog,
        CoulombFriction(friction_coefficient=0.5),
        mass=100.0,
        settings=SolverSettings(integrator="newmark", dt_max=0.01, max_displacement_increment=1.0),
    )
    assert res.data["y"].values[-1] == pytest.approx(2.0, rel=1e-9)


def test_bad_inputs():
    soil = CoulombFriction(friction_coefficient=0.5)
    with pytest.raises(InputError, match="mass"):
        simulate_section(_prog(), soil, mass=0.0)
    with pytest.raises(InputError, match="LoadProgramme"):
        simulate_section({"t": [0, 1]}, soil, mass=1.0)
    with pytest.raises(InputError, match="after_limit"):
        simulate_section(_prog(), soil, mass=1.0, after_limit="bounce")
    with pytest.raises(InputError, match="integrator"):
        SolverSettings(integrator="rk4")
    with pytest.raises(InputError, match="dt_min"):
        simulate_section(_prog(), soil, mass=1.0, settings=SolverSettings(dt_max=0.1, dt_min=1.0))
