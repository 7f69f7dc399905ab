"""Unit tests: one name per quantity in every result (y lateral, z penetration), and result
files written by onbottom 0.1 (u, u_dot, w) still open (docs/conventions.md)."""

from __future__ import annotations

import logging

import numpy as np
import xarray as xr

from onbottom import Pipe, Sand
from onbottom.dynamics.programmes import inclined_cyclic
from onbottom.dynamics.section import simulate_section
from onbottom.plotting.section import plot_penetration_path
from onbottom.results import LEGACY_NAMES, annotate, load_dataset, save_dataset, upgrade_names
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
    assert not set(LEGACY_NAMES) & set(res.data.data_vars)
    assert res.data["y"].attrs["units"] == "m" and res.data["y_dot"].attrs["units"] == "m/s"
    soil = VerleySotberg.silica(
        Pipe(outer_diameter=0.5, submerged_weight=2.0e3), Sand(submerged_unit_weight=1.0e4)
    )
    ds = path_response(soil, cyclic_path(0.05, 1.0, points_per_cycle=20), 2.0e3)
    assert {"y", "z"} <= set(ds.data_vars) and "u" not in ds


def _old_section_file(path):
    """A small section result as onbottom 0.1 wrote it (u, u_dot, w)."""
    t = np.array([0.0, 1.0, 2.0])
    ds = xr.Dataset(
        {
            "u": ("time", [0.0, 0.1, 0.3]),
            "u_dot": ("time", [0.0, 0.15, 0.2]),
            "w": ("time", [0.05, 0.051, 0.052]),
            "H": ("time", [0.0, 10.0, 5.0]),
        },
        coords={"time": t},
        attrs={"model": "simulate_section", "onbottom_version": "0.1.0"},
    )
    for name, (long_name, units) in {
        "u": ("lateral displacement of the pipe", "m"),
        "u_dot": ("lateral velocity of the pipe", "m/s"),
        "w": ("penetration (embedment) of the pipe invert", "m"),
    }.items():
        ds[name].attrs.update(long_name=long_name, units=units)
    save_dataset(ds, path)
    return ds


def test_a_0_1_section_file_opens_with_today_names(tmp_path, caplog):
    old = _old_section_file(tmp_path / "old.nc")
    with caplog.at_level(logging.INFO, logger="onbottom.results"):
        ds = load_dataset(tmp_path / "old.nc")
    assert {"y", "y_dot", "z", "H"} == set(ds.data_vars)
    np.testing.assert_array_equal(ds["y"].values, old["u"].values)
    np.testing.assert_array_equal(ds["y_dot"].values, old["u_dot"].values)
    np.testing.assert_array_equal(ds["z"].values, old["w"].values)
    assert ds["y"].attrs["units"] == "m" and ds["z"].attrs["units"] == "m"
    assert ds.attrs["renamed_variables"] == "u->y, u_dot->y_dot, w->z"
    assert "renamed" in caplog.text  # a note, not a warning
    # consumers take the renamed file as a new one
    ax = plot_penetration_path(ds, axes=None)
    np.testing.assert_array_equal(ax.lines[0].get_xdata(), old["u"].values)


def test_today_files_and_dem_records_are_left_alone():
    new = annotate(
        xr.Dataset({"y": ("time", [0.0, 1.0]), "z": ("time", [0.1, 0.1])}, coords={"time": [0, 1]})
    )
    assert upgrade_names(new) is new
    # the DEM penetration records keep the paper's w (no lateral u): not renamed
    dem = xr.Dataset({"w": ("record", [0.0, 1e-3]), "V": ("record", [0.0, 5.0])})
    assert upgrade_names(dem) is dem
    # a name already taken is not overwritten
    both = xr.Dataset({"u": ("time", [1.0]), "y": ("time", [2.0])})
    assert float(upgrade_names(both)["y"][0]) == 2.0
