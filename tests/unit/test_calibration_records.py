"""Unit tests: test-record format, unit conversion, validation errors, writer round-trip."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from onbottom import InputError
from onbottom.calibration.records import (
    TestRecord,
    load_record,
    record_from_result,
    save_record,
    to_si,
)

CSV = """# onbottom test record v1
# name: Inclined 1
# programme: inclined_1
# diameter: 1000 mm
# V_peak: 42.98 kN/m
# V_i: 10.52 kN/m
# displacement_limit: 3.0 m
# cycle_period: 40 s
# operator: tester
time,H,V,y,z
s,kN/m,kN/m,m,mm
0.0,0.0,10.52,0.0,65.0
10.0,0.25,10.09,0.001,65.5
20.0,0.0,10.52,0.0005,66.0
"""


def _write(tmp_path, text, name="rec.csv"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_csv_units_converted_to_si(tmp_path):
    rec = load_record(_write(tmp_path, CSV))
    assert rec.name == "Inclined 1"
    assert rec.programme == "inclined_1"
    assert rec.diameter == pytest.approx(1.0)
    assert rec.V_peak == pytest.approx(42980.0)
    assert rec.V_i == pytest.approx(10520.0)
    assert rec.displacement_limit == 3.0
    assert rec.cycle_period == 40.0
    assert rec.metadata["operator"] == "tester"
    np.testing.assert_allclose(rec.data["H"].values, [0.0, 250.0, 0.0])
    np.testing.assert_allclose(rec.data["V"].values, [10520.0, 10090.0, 10520.0])
    np.testing.assert_allclose(rec.z, [0.065, 0.0655, 0.066])
    assert rec.data["z"].attrs["units"] == "m"
    assert rec.data["H"].attrs["units"] == "N/m"


def test_to_si_factors_and_unknown_unit():
    assert to_si(2.0, "kN/m", "force_per_length") == 2000.0
    assert to_si(5.0, "mm", "length") == pytest.approx(0.005)
    assert to_si(2.0, "min", "time") == 120.0
    assert to_si(7.5, "kN/m3", "unit_weight") == 7500.0
    with pytest.raises(InputError, match="'furlong'"):
        to_si(1.0, "furlong", "length")


def test_missing_value_names_column_and_row(tmp_path):
    text = CSV.replace("10.0,0.25,10.09,0.001,65.5", "10.0,0.25,,0.001,65.5")
    with pytest.raises(InputError, match=r"column 'V' row 1 \(line 13\)"):
        load_record(_write(tmp_path, text))


def test_nan_value_names_column_and_row(tmp_path):
    text = CSV.replace("20.0,0.0,10.52,0.0005,66.0", "20.0,0.0,10.52,0.0005,nan")
    with pytest.raises(InputError, match=r"column 'z' row 2"):
        load_record(_write(tmp_path, text))


def test_non_monotone_time_names_row(tmp_path):
    text = CSV.replace("20.0,0.0,10.52", "10.0,0.0,10.52")
    with pytest.raises(InputError, match=r"column 'time' row 2.*increase"):
        load_record(_write(tmp_path, text))


def test_unknown_column_unit_is_rejected(tmp_path):
    text = CSV.replace("s,kN/m,kN/m,m,mm", "s,kN/m,kN/m,m,inch")
    with pytest.raises(InputError, match=r"column 'z'.*'inch'"):
        load_record(_write(tmp_path, text))


def test_missing_required_column_and_header(tmp_path):
    text = CSV.replace("time,H,V,y,z", "time,H,V,y,x")
    with pytest.raises(InputError, match="'z' is missing"):
        load_record(_write(tmp_path, text))
    text = CSV.replace("# diameter: 1000 mm\n", "")
    with pytest.raises(InputError, match="diameter"):
        load_record(_write(tmp_path, text))


@pytest.mark.parametrize("suffix", [".csv", ".nc"])
def test_round_trip(tmp_path, suffix):
    rec = load_record(_write(tmp_path, CSV))
    out = save_record(rec, tmp_path / f"copy{suffix}")
    back = load_record(out)
    assert back.name == rec.name and back.programme == rec.programme
    for key in ("diameter", "V_peak", "V_i", "displacement_limit", "cycle_period"):
        assert getattr(back, key) == pytest.approx(getattr(rec, key))
    assert back.metadata["operator"] == "tester"
    for col in ("time", "H", "V", "y", "z"):
        np.testing.assert_allclose(back.data[col].values, rec.data[col].values, rtol=1e-15)


def test_record_is_immutable_and_copies_data():
    ds = xr.Dataset(
        {"y": ("time", np.zeros(3)), "z": ("time", np.ones(3))}, coords={"time": [0.0, 1, 2]}
    )
    rec = TestRecord(name="x", data=ds, diameter=1.0)
    ds["y"][0] = 5.0
    assert rec.y[0] == 0.0
    with pytest.raises(ValueError):
        rec.y[0] = 1.0
    with pytest.raises(AttributeError):
        rec.name = "y"  # type: ignore[misc]
    with pytest.raises(TypeError):
        rec.metadata["k"] = 1  # type: ignore[index]


def test_record_from_simulation_result():
    sim = xr.Dataset(
        {
            "y": ("time", [0.0, 0.1, 0.2]),
            "z": ("time", [0.05, 0.06, 0.07]),
            "H": ("time", [0.0, 1.0, 2.0]),
            "F_soil": ("time", [0.0, 1.0, 2.0]),
        },
        coords={"time": [0.0, 1.0, 2.0]},
        attrs={"model": "section"},
    )
    rec = record_from_result(sim, name="sim", diameter=1.0, V_i=1e4)
    assert set(rec.data.data_vars) == {"y", "z", "H"}
    assert rec.metadata["source_model"] == "section"


def test_invalid_metadata_rejected():
    ds = xr.Dataset(
        {"y": ("time", np.zeros(3)), "z": ("time", np.ones(3))}, coords={"time": [0.0, 1, 2]}
    )
    with pytest.raises(InputError, match="TestRecord.V_i"):
        TestRecord(name="x", data=ds, diameter=1.0, V_i=-1.0)
    bad = ds.copy()
    bad["y"] = ("time", [0.0, np.nan, 1.0])
    with pytest.raises(InputError, match="column 'y' row 1"):
        TestRecord(name="x", data=bad, diameter=1.0)


def test_records_without_y_and_z_are_refused_by_column_name(tmp_path):
    """Only today's names are read: a record naming its columns ``u``/``w`` is refused,
    naming the missing column."""
    old_csv = CSV.replace("time,H,V,y,z", "time,H,V,u,w")
    with pytest.raises(InputError, match="column 'y' is missing"):
        load_record(_write(tmp_path, old_csv, "old.csv"))
    ds = xr.Dataset(
        {"u": ("time", [0.0, 0.1]), "z": ("time", [0.05, 0.06])}, coords={"time": [0.0, 1.0]}
    )
    with pytest.raises(InputError, match="column 'y' is missing"):
        TestRecord(name="x", data=ds, diameter=1.0)


def test_record_from_result_keeps_the_name_it_is_given():
    """The record is named by ``name``, never by a variable it copies."""
    import xarray as xr

    from onbottom.calibration.records import record_from_result

    t = np.linspace(0.0, 1.0, 3)
    ds = xr.Dataset({c: ("time", np.zeros(3)) for c in ("y", "z", "H", "V")}, coords={"time": t})
    rec = record_from_result(ds, name="Inclined 1", diameter=1.0, programme="Inclined 1")
    assert rec.name == "Inclined 1"
