"""Unit tests: result conventions (provenance, atomic NetCDF) and the input-check helpers."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest
import xarray as xr

from onbottom import InputError, OutOfRangeWarning, __version__
from onbottom._validate import in_range, non_negative, one_of, positive, warn_outside
from onbottom.results import annotate, load_dataset, provenance, save_dataset


def test_provenance_records_version_model_parameters_and_seed():
    attrs = provenance("verley_sotberg", {"A": 0.25, "mu": 0.48}, seed=3, note={"x": 1})
    assert attrs["onbottom_version"] == __version__
    assert attrs["model"] == "verley_sotberg"
    assert json.loads(attrs["parameters"]) == {"A": 0.25, "mu": 0.48}
    assert attrs["seed"] == 3
    assert json.loads(attrs["note"]) == {"x": 1}


def test_annotate_and_atomic_round_trip(tmp_path):
    ds = xr.Dataset({"y": ("time", np.arange(3.0))}, coords={"time": [0.0, 1.0, 2.0]})
    ds.attrs.update(provenance("test"))
    annotate(ds)
    assert ds["y"].attrs["units"] == "m" and ds["time"].attrs["units"] == "s"
    path = save_dataset(ds, tmp_path / "sub" / "run.nc")
    assert path.exists()
    assert not list(path.parent.glob("*.tmp"))
    back = load_dataset(path)
    # the file carries its completion status (issue 31)
    xr.testing.assert_identical(back, ds.assign_attrs(run_status="complete"))


def test_failed_write_leaves_no_partial_file(tmp_path):
    ds = xr.Dataset({"bad": ("x", np.array([object()], dtype=object))})
    with pytest.raises(Exception):  # noqa: B017 - whatever the writer raises
        save_dataset(ds, tmp_path / "bad.nc")
    assert list(tmp_path.iterdir()) == []


def test_validators_messages():
    assert positive("a", 2) == 2.0
    assert non_negative("a", 0) == 0.0
    with pytest.raises(InputError, match=r"a = 1\.5 is invalid: must lie in \(0, 1\]"):
        in_range("a", 1.5, 0.0, 1.0, low_inclusive=False)
    with pytest.raises(InputError, match="must be one of 'x', 'y'"):
        one_of("kind", "z", ("x", "y"))


def test_warn_outside_range():
    with pytest.warns(OutOfRangeWarning, match=r"outside the calibration range \[0, 1\] of Src"):
        warn_outside("K_s", 2.0, 0.0, 1.0, "Src")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warn_outside("K_s", 0.5, 0.0, 1.0, "Src")


# --------------------------------------------------------------------------------------------
# files and checks of issue #10
# --------------------------------------------------------------------------------------------
def test_saved_files_have_ordinary_permissions_and_stale_temporaries_go(tmp_path):
    import os
    import stat

    import xarray as xr

    from onbottom.results import save_dataset, write_text_atomic

    target = tmp_path / "new" / "folder" / "r.nc"  # folders are created
    stale = target.parent / "r.nc.k1ll3d.tmp"
    target.parent.mkdir(parents=True)
    stale.write_bytes(b"half a file")
    old = os.umask(0o022)
    try:
        save_dataset(xr.Dataset({"x": ("i", [1.0])}), target)
        text = write_text_atomic(tmp_path / "t" / "a.csv", "a,b\n")
    finally:
        os.umask(old)
    assert stat.S_IMODE(target.stat().st_mode) == 0o644
    assert stat.S_IMODE(text.stat().st_mode) == 0o644
    assert not stale.exists() and sorted(p.name for p in target.parent.iterdir()) == ["r.nc"]


def test_integer_never_truncates():
    from onbottom._validate import integer

    assert integer("n", 16) == 16 and integer("n", 16.0) == 16
    for bad in (16.7, float("nan"), True, "16"):
        with pytest.raises(InputError, match="n = "):
            integer("n", bad)
    with pytest.raises(InputError, match=r"must lie in \[1, 5\]"):
        integer("n", 0, 1, 5)


def test_plausible_errors_and_warnings():
    from onbottom._validate import plausible

    kw = {"error": (1.0, 10.0), "usual": (2.0, 5.0), "unit": "m", "what": "a length"}
    assert plausible("L", 3.0, **kw) == 3.0
    with pytest.warns(OutOfRangeWarning, match="L = 7 m is unusual"):
        plausible("L", 7.0, **kw)
    with pytest.raises(InputError, match=r"L = 500.0 m is invalid: must lie in the plausible"):
        plausible("L", 500.0, **kw)
