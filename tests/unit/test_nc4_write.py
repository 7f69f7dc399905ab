"""Unit tests: the direct NetCDF-4 writer of ``save_dataset`` gives the file xarray's own
writer gives — every variable, attribute, unit and the provenance read back equal with the
default engine — plain and compressed, and keeps the atomic write."""

from __future__ import annotations

import h5py
import numpy as np
import pytest
import xarray as xr

from onbottom import Pipe, Sand
from onbottom.dynamics.storm_section import StormSolverSettings, simulate_storm_section
from onbottom.hydro.storm_kinematics import storm_kinematics
from onbottom.inputs.storm import SeaState, Storm
from onbottom.results import _nc4write, annotate, load_dataset, provenance, save_dataset
from onbottom.soil.verley_sotberg import VerleySotberg


@pytest.fixture(scope="module")
def storm_record() -> xr.Dataset:
    """A short storm section run's records (the variables, units and provenance of any)."""
    pipe = Pipe(outer_diameter=0.4, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10e3))
    storm = Storm(stages=(SeaState(hs=3.0, tp=10.0, duration_s=600.0),))
    kin = storm_kinematics(storm, 13.0, diameter=0.4)
    settings = StormSolverSettings(record_interval=0.5)
    return simulate_storm_section(pipe, soil, kin, settings=settings).data


def _mixed() -> xr.Dataset:
    """Two dimensions, a dimension without a coordinate, a non-dimension coordinate, ints,
    booleans, a scalar, a NaN, attributes of every kind a result carries."""
    rng = np.random.default_rng(3)
    y = rng.standard_normal((7, 4))
    y[2, 1] = np.nan
    ds = xr.Dataset(
        {
            "y": (("time", "node"), y, {"units": "m", "long_name": "lateral displacement"}),
            "region": ("time", np.arange(7, dtype=np.int64)),
            "moved": ("time", np.arange(7) % 2 == 0),
            "w_s": ((), 1500.0, {"units": "N/m"}),
            "edge": ("side", [1.0, 2.0]),
            "strain": ("node", np.linspace(0.0, 1e-3, 4)),
        },
        coords={
            "time": ("time", np.arange(7) * 0.5, {"units": "s"}),
            "x": ("node", np.linspace(0.0, 30.0, 4), {"units": "m"}),
        },
        attrs={
            **provenance("test", {"a": 1.0}, seed=3, levels=[1, 2]),
            "count": np.int32(4),
            "ratio": 0.25,
            "limits": np.array([0.5, 1.0]),
        },
    )
    return annotate(ds)


def _reference(ds: xr.Dataset, path, level: int) -> xr.Dataset:
    """The same dataset written by xarray's h5netcdf store, read back."""
    enc = (
        {}
        if level == 0
        else {k: {"zlib": True, "complevel": level} for k, v in ds.data_vars.items() if v.ndim}
    )
    ds.assign_attrs(run_status="complete").to_netcdf(path, engine="h5netcdf", encoding=enc)
    with xr.open_dataset(path) as back:
        return back.load()


@pytest.mark.parametrize("level", [0, 4])
def test_storm_record_reads_back_identical_and_as_xarray_writes_it(tmp_path, storm_record, level):
    assert _nc4write.writable(storm_record)
    save_dataset(storm_record, tmp_path / "storm.nc", compression_level=level)
    with xr.open_dataset(tmp_path / "storm.nc") as back:  # the default engine
        back = back.load()
    assert back.identical(storm_record.assign_attrs(run_status="complete"))
    for name in storm_record.variables:  # units and long names, variable by variable
        assert back[name].attrs == storm_record[name].attrs
        np.testing.assert_array_equal(back[name].values, storm_record[name].values)
    assert back.attrs["model"] == storm_record.attrs["model"]
    assert back.attrs["onbottom_content_hash"] == storm_record.attrs["onbottom_content_hash"]
    assert back.identical(_reference(storm_record, tmp_path / "ref.nc", level))


@pytest.mark.parametrize("level", [0, 1, 9])
def test_mixed_dataset_round_trip_and_netcdf4_layout(tmp_path, level, monkeypatch):
    monkeypatch.setattr(_nc4write, "CHUNK_BYTES", 64)  # several chunks and an edge chunk
    ds = _mixed()
    assert _nc4write.writable(ds)
    save_dataset(ds, tmp_path / "m.nc", compression_level=level)
    back = load_dataset(tmp_path / "m.nc")
    assert back.identical(ds.assign_attrs(run_status="complete"))
    assert back.identical(_reference(ds, tmp_path / "ref.nc", level))
    assert back["moved"].dtype == bool and back["region"].dtype == np.int64
    with h5py.File(tmp_path / "m.nc") as f:  # the netCDF-4 data model on HDF5
        assert f["time"].attrs["CLASS"] == b"DIMENSION_SCALE"
        assert int(f["node"].attrs["_Netcdf4Dimid"]) == 1
        assert f["node"].attrs["NAME"].startswith(b"This is a netCDF dimension but not")
        assert list(f["y"].attrs["_Netcdf4Coordinates"]) == [0, 1]
        assert f["y"].attrs["coordinates"] == "x"
        assert "_NCProperties" in f.attrs
        y = f["y"]
        if level:
            assert y.compression == "gzip" and y.shuffle and y.chunks[0] < ds.sizes["time"]
            assert y.compression_opts == level
        else:
            assert y.compression is None


def test_datasets_outside_the_direct_writer_take_xarrays_store(tmp_path):
    ds = _mixed().assign(label=("side", np.array(["a", "b"])))
    ds["time"].encoding["chunksizes"] = (3,)
    assert not _nc4write.writable(ds)
    assert not _nc4write.writable(_mixed().assign_attrs(flag=True))
    save_dataset(ds, tmp_path / "s.nc", compression_level=2)
    back = load_dataset(tmp_path / "s.nc")
    assert list(back["label"].values) == ["a", "b"]
    np.testing.assert_array_equal(back["y"].values, ds["y"].values)


def test_a_loaded_result_saves_again_by_the_direct_writer(tmp_path):
    save_dataset(_mixed(), tmp_path / "a.nc", compression_level=3)
    again = load_dataset(tmp_path / "a.nc")
    assert _nc4write.writable(again.drop_encoding())
    save_dataset(again, tmp_path / "b.nc")
    assert load_dataset(tmp_path / "b.nc").identical(again)


def test_the_direct_write_is_atomic(tmp_path, monkeypatch):
    """A write that fails leaves neither the final name nor a temporary file."""
    save_dataset(_mixed(), tmp_path / "keep.nc")
    before = (tmp_path / "keep.nc").read_bytes()

    def broken(ds, target, compress):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(_nc4write, "write_nc4", broken)
    with pytest.raises(OSError, match="No space left on device"):
        save_dataset(_mixed(), tmp_path / "keep.nc")
    assert (tmp_path / "keep.nc").read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.nc"]


def test_large_datasets_are_written_straight_to_the_file(tmp_path, monkeypatch):
    """Above IN_MEMORY_MAX_BYTES the direct writer writes the temporary file itself."""
    from onbottom.results import netcdf

    monkeypatch.setattr(netcdf, "IN_MEMORY_MAX_BYTES", 0)
    save_dataset(_mixed(), tmp_path / "big.nc", compression_level=2)
    assert load_dataset(tmp_path / "big.nc").identical(_mixed().assign_attrs(run_status="complete"))


def test_an_empty_dimension_round_trips(tmp_path):
    ds = xr.Dataset(
        {"H_peak": ("cycle", np.zeros(0)), "w_s": ((), 1.0)}, coords={"cycle": np.zeros(0)}
    )
    for level in (0, 5):
        save_dataset(ds, tmp_path / f"e{level}.nc", compression_level=level)
        back = load_dataset(tmp_path / f"e{level}.nc")
        assert back.identical(ds.assign_attrs(run_status="complete"))
