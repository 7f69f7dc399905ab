"""Compressed NetCDF output (issue 33 item 4): same numbers, smaller files, checked level."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
from onbottom.errors import InputError
from onbottom.hydro.short_crested import regular_node_kinematics
from onbottom.inputs.pipe import Pipe
from onbottom.results import load_dataset, netcdf_encoding, save_dataset
from onbottom.soil.coulomb import CoulombFriction


def _dataset(n=4000):
    t = 0.5 * np.arange(n)
    return xr.Dataset(
        {
            "y": ("time", 0.1 * np.sin(0.01 * t), {"units": "m"}),
            "region": ("time", np.repeat([1.0, 2.0], n // 2), {"units": "1"}),
        },
        coords={"time": ("time", t, {"units": "s"})},
        attrs={"model": "test"},
    )


@pytest.mark.parametrize("level", [0, 1, 9])
def test_save_dataset_round_trip_is_exact_at_every_level(tmp_path, level):
    ds = _dataset()
    path = save_dataset(ds, tmp_path / f"c{level}.nc", compression_level=level)
    back = load_dataset(path)
    for name in ("y", "region", "time"):
        np.testing.assert_array_equal(back[name].values, ds[name].values)
        assert back[name].attrs["units"] == ds[name].attrs["units"]
    assert back.attrs["run_status"] == "complete" and back.attrs["model"] == "test"
    assert bool(back["y"].encoding.get("zlib", False)) == (level > 0)


def test_compression_makes_a_smooth_record_smaller(tmp_path):
    ds = _dataset()
    plain = save_dataset(ds, tmp_path / "plain.nc").stat().st_size
    small = save_dataset(ds, tmp_path / "small.nc", compression_level=6).stat().st_size
    assert small < 0.7 * plain


@pytest.mark.parametrize("bad", [-1, 10, 2.5, True, "4"])
def test_compression_level_outside_0_to_9_is_named(bad):
    with pytest.raises(InputError, match="compression_level"):
        netcdf_encoding(_dataset(10), bad)


def test_pipeline_records_compressed_equal_the_plain_ones(tmp_path):
    pipe = Pipe(
        outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    m = PipelineModel(
        pipe=pipe, length=40.0, element_length=4.0, soil=CoulombFriction(friction_coefficient=0.5)
    )
    kin = regular_node_kinematics(m.x.size, 30.0, 0.05, 1.5, 10.0, ramp=10.0, x=m.x)
    runs = {}
    for level in (0, 5):
        st = PipelineSettings(record_interval=0.5, chunk_duration=7.0, compression_level=level)
        runs[level] = simulate_pipeline(m, kin, settings=st, output=tmp_path / f"p{level}.nc")
    a, b = (runs[k].open_dataset() for k in (0, 5))
    np.testing.assert_array_equal(a["y"].values, b["y"].values)
    assert b["y"].encoding.get("zlib") and not a["y"].encoding.get("zlib")
    # the level is output format, not part of the run
    assert runs[0].run_id == runs[5].run_id
    with pytest.raises(InputError, match="compression_level"):
        PipelineSettings(compression_level=12)
