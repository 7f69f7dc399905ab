"""Unit tests: one name per quantity in every result (y lateral, z penetration;
docs/conventions.md)."""

from __future__ import annotations

from onbottom import Pipe, Sand
from onbottom.dynamics.programmes import inclined_cyclic
from onbottom.dynamics.section import simulate_section
from onbottom.soil.coulomb import CoulombFriction
from onbottom.soil.response import cyclic_path, path_response
from onbottom.soil.verley_sotberg import VerleySotberg


def test_section_and_path_results_name_the_displacement_y_and_the_penetration_z():
    res = simulate_section(
        inclined_cyclic(1000.0, 100.0, 10.0, 90.0, 2),
        CoulombFriction(friction_coefficient=0.5),
        mass=100.0,
    )
    assert {"y", "y_dot", "z"} <= set(res.data.data_vars)
    assert not {"u", "u_dot", "w"} & set(res.data.data_vars)
    assert res.data["y"].attrs["units"] == "m" and res.data["y_dot"].attrs["units"] == "m/s"
    soil = VerleySotberg.silica(
        Pipe(outer_diameter=0.5, submerged_weight=2.0e3), Sand(submerged_unit_weight=1.0e4)
    )
    ds = path_response(soil, cyclic_path(0.05, 1.0, points_per_cycle=20), 2.0e3)
    assert {"y", "z"} <= set(ds.data_vars) and "u" not in ds
