"""Unit tests of the hindcast schema, storms and sectors (onbottom.metocean)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pyextremes")
pytest.importorskip("virocon")

from onbottom.errors import InputError
from onbottom.metocean.hindcast import read_hindcast, write_hindcast_csv
from onbottom.metocean.storms import (
    decluster,
    sector_edges,
    sector_mask,
    storm_peaks,
    threshold_for_rate,
)
from onbottom.metocean.synthetic import synthetic_hindcast

HEADER = "time,hs,tp,wave_direction_deg,current_speed,current_direction_deg\n"
UNITS = "UTC,m,s,deg,m/s,deg\n"
ROWS = [
    "2000-01-01T00:00:00Z,1.00,8.0,270.0,0.30,90.0",
    "2000-01-01T03:00:00Z,1.20,8.5,275.0,0.25,95.0",
    "2000-01-01T06:00:00Z,1.40,9.0,280.0,0.20,100.0",
    "2000-01-01T09:00:00Z,1.30,9.0,285.0,0.10,270.0",
]


def _csv(tmp_path, rows=ROWS, header=HEADER, units=UNITS, comment="# a comment\n"):
    p = tmp_path / "h.csv"
    p.write_text(comment + header + units + "\n".join(rows) + "\n", encoding="utf-8")
    return p


def test_reads_a_valid_file(tmp_path):
    h = read_hindcast(_csv(tmp_path))
    assert h.step_hours == 3.0
    np.testing.assert_allclose(h.hs, [1.0, 1.2, 1.4, 1.3])
    np.testing.assert_allclose(h.current_direction_deg, [90, 95, 100, 270])
    assert h.years == pytest.approx(4 * 3 / (24 * 365.2425))
    assert str(h.time[2]) == "2000-01-01T06:00:00"


def test_current_columns_are_optional_together(tmp_path):
    rows = [",".join(r.split(",")[:4]) for r in ROWS]
    h = read_hindcast(_csv(tmp_path, rows, "time,hs,tp,wave_direction_deg\n", "UTC,m,s,deg\n"))
    assert not h.has_current


def _error(tmp_path, **kw) -> InputError:
    with pytest.raises(InputError) as exc:
        read_hindcast(_csv(tmp_path, **kw))
    return exc.value


def test_gap_is_named_with_its_line_and_times(tmp_path):
    rows = [*ROWS[:2], ROWS[3]]  # 03:00 -> 09:00
    err = _error(tmp_path, rows=rows)
    msg = str(err)
    assert err.field == "time"
    assert "line 6" in msg and "03:00:00 → 2000-01-01T09:00:00 (6 h)" in msg and "3 h" in msg


def test_duplicate_time_is_named(tmp_path):
    rows = [*ROWS[:2], ROWS[1].replace("1.20", "1.25"), *ROWS[2:]]
    msg = str(_error(tmp_path, rows=rows))
    assert "duplicate" in msg and "line 6 (2000-01-01T03:00:00)" in msg


def test_time_out_of_order_is_named(tmp_path):
    rows = [ROWS[0], ROWS[2], ROWS[1], ROWS[3]]
    msg = str(_error(tmp_path, rows=rows))
    assert "not increasing" in msg and "line 6 (2000-01-01T03:00:00)" in msg


@pytest.mark.parametrize(
    ("column", "value", "field"),
    [
        (1, "-0.5", "hs"),
        (1, "45", "hs"),
        (2, "0", "tp"),
        (3, "400", "wave_direction_deg"),
        (4, "-1", "current_speed"),
        (5, "nan", "current_direction_deg"),
        (1, "", "hs"),
    ],
)
def test_impossible_value_is_named_with_column_line_and_time(tmp_path, column, value, field):
    parts = ROWS[2].split(",")
    parts[column] = value
    rows = [*ROWS[:2], ",".join(parts), ROWS[3]]
    err = _error(tmp_path, rows=rows)
    assert err.field == field
    assert "line 6 (2000-01-01T06:00:00)" in str(err)  # comment, header, units, 3 rows


def test_breaking_steepness_is_an_error(tmp_path):
    rows = [*ROWS[:2], "2000-01-01T06:00:00Z,6.0,4.0,280.0,0.20,100.0", ROWS[3]]
    err = _error(tmp_path, rows=rows)
    assert err.field == "tp" and "breaking limit 1/7" in str(err)


@pytest.mark.parametrize(
    ("units", "field"),
    [
        ("UTC,ft,s,deg,m/s,deg\n", "hs"),
        ("UTC,m,s,rad,m/s,deg\n", "wave_direction_deg"),
        ("UTC,m,s,deg,knots,deg\n", "current_speed"),
        ("UTC,m,s,deg,m/s\n", "units"),
    ],
)
def test_wrong_units_are_named(tmp_path, units, field):
    err = _error(tmp_path, units=units)
    assert err.field == field


def test_wrong_header_and_time_zone(tmp_path):
    err = _error(tmp_path, header="time,Hs,Tp,dir,u,udir\n")
    assert err.field == "header"
    rows = [ROWS[0].replace("Z", "+01:00"), *ROWS[1:]]
    assert _error(tmp_path, rows=rows).field == "time"


def test_csv_and_netcdf_round_trip(tmp_path):
    import xarray as xr

    d = synthetic_hindcast(years=0.2, seed=1)
    p = write_hindcast_csv(tmp_path / "s.csv", d, comments=("synthetic",))
    h = read_hindcast(p)
    np.testing.assert_allclose(h.hs, d["hs"], atol=0.005 + 1e-9)
    np.testing.assert_array_equal(h.time, d["time"])
    ds = xr.Dataset(
        {
            "hs": ("time", h.hs, {"units": "m"}),
            "tp": ("time", h.tp, {"units": "s"}),
            "wave_direction_deg": ("time", h.wave_direction_deg, {"units": "degree"}),
            "current_speed": ("time", h.current_speed, {"units": "m s-1"}),
            "current_direction_deg": ("time", h.current_direction_deg, {"units": "deg"}),
        },
        coords={"time": h.time.astype("datetime64[ns]")},
    )
    ds.to_netcdf(tmp_path / "s.nc")
    h2 = read_hindcast(tmp_path / "s.nc")
    np.testing.assert_array_equal(h2.hs, h.hs)
    ds["tp"].attrs["units"] = "min"
    ds.to_netcdf(tmp_path / "bad.nc")
    with pytest.raises(InputError) as exc:
        read_hindcast(tmp_path / "bad.nc")
    assert exc.value.field == "tp"


def test_decluster_by_hand():
    v = np.array([0, 5, 6, 0, 0, 0, 7, 0, 5, 0, 0, 0, 0, 0, 9, 9], dtype=float)
    # step 1 h, r = 2 h: exceedances of 4 at 1,2 | 6,8 (gap 2 h: same storm) | 14,15
    np.testing.assert_array_equal(decluster(v, 1.0, 4.0, 2.0), [2, 6, 14])
    np.testing.assert_array_equal(decluster(v, 1.0, 4.0, 1.0), [2, 6, 8, 14])
    assert decluster(v, 1.0, 10.0, 2.0).size == 0


def test_decluster_is_pyextremes_definition():
    import pandas as pd
    from pyextremes import get_extremes

    d = synthetic_hindcast(years=5.0, seed=3)
    s = pd.Series(d["hs"], index=pd.DatetimeIndex(d["time"].astype("datetime64[ns]")))
    for u, r in ((2.5, 24.0), (3.0, 48.0), (2.0, 72.0)):
        ref = get_extremes(s, "POT", threshold=u, r=f"{r}h")
        idx = decluster(d["hs"], 3.0, u, r)
        np.testing.assert_array_equal(s.index[idx], ref.index)
        np.testing.assert_array_equal(d["hs"][idx], ref.values)


def test_threshold_for_rate_meets_the_target_from_above():
    d = synthetic_hindcast(years=10.0, seed=4)
    u = threshold_for_rate(d["hs"], 3.0, 48.0, 10.0, 3.0)
    n = storm_peaks(d["hs"], 3.0, u, 48.0, 10.0).peak.size
    assert 25 <= n <= 30  # at most the target, within a few storms of it
    # tidal current: counts are not monotone in u (low u merges storms); still near target
    c = d["current_speed"]
    uc = threshold_for_rate(c, 3.0, 48.0, 10.0, 3.0)
    assert uc > np.median(c)
    assert 20 <= decluster(c, 3.0, uc, 48.0).size <= 30


def test_sectors():
    centres, half = sector_edges(8)
    np.testing.assert_allclose(centres, np.arange(8) * 45.0)
    np.testing.assert_allclose(half, 22.5)
    d = np.array([0.0, 22.4, 22.5, 337.5, 359.9, 180.0])
    assert sector_mask(d, 8, 0).tolist() == [True, True, False, True, True, False]
    assert sector_mask(d, 8, 4).tolist() == [False, False, False, False, False, True]
    assert sector_mask(d, 1, 0).all()
    total = sum(sector_mask(np.linspace(0, 359.99, 1000), 12, k).sum() for k in range(12))
    assert total == 1000
    with pytest.raises(InputError):
        sector_edges(0)


def test_missing_sea_states_are_empty_rows_and_partial_rows_are_named(tmp_path):
    rows = [*ROWS[:2], "2000-01-01T06:00:00Z,,,,,", ROWS[3], "2000-01-01T12:00:00Z,1.1,8.0,,,"]
    with pytest.raises(InputError, match=r"a missing sea state leaves every value") as e:
        read_hindcast(_csv(tmp_path, rows=rows))
    assert "line 8" in str(e.value) and e.value.field == "wave_direction_deg"
    h = read_hindcast(_csv(tmp_path, rows=rows[:4]))
    assert h.n_missing == 1 and h.observed.tolist() == [True, True, False, True]
    assert h.years == pytest.approx(3 * 3.0 / (24 * 365.2425))  # observed sea states only
    rows[1] = "2000-01-01T03:00:00Z,,8.5,275.0,0.25,95.0"  # hs missing, the rest not
    with pytest.raises(InputError, match="where the row's other values are given") as e:
        read_hindcast(_csv(tmp_path, rows=rows[:4]))
    assert "line 5" in str(e.value) and e.value.field == "hs"


def test_a_record_without_directions_is_omnidirectional_only(tmp_path):
    from onbottom.metocean.analysis import MetoceanOptions, analyse_hindcast

    rows = [",".join(r.split(",")[:3]) for r in ROWS]
    p = _csv(tmp_path, rows=rows, header="time,hs,tp\n", units="UTC,m,s\n")
    h = read_hindcast(p)
    assert not h.has_direction and not h.has_current
    out = write_hindcast_csv(
        tmp_path / "w.csv", {"time": h.time, "hs": h.hs, "tp": h.tp}, comments=("x",)
    )
    assert read_hindcast(out).hs.tolist() == h.hs.tolist()
    with pytest.raises(InputError, match="no wave_direction_deg column") as e:
        analyse_hindcast(h, MetoceanOptions(sectors=4))
    assert e.value.field == "sectors"


def test_the_shipped_ndbc_record_reads_with_its_source_and_licence():
    """examples/hindcast_ndbc_44007.csv (tools/ndbc_to_hindcast.py): 10 years hourly, the
    82 805 records of the benchmark's dataset A, the rest missing; no direction, no current."""
    from pathlib import Path

    p = Path(__file__).resolve().parents[2] / "examples" / "hindcast_ndbc_44007.csv"
    head = p.read_text(encoding="utf-8")[:1000]
    assert "National Data Buoy Center buoy 44007" in head and "public domain" in head
    h = read_hindcast(p)
    assert h.step_hours == 1.0 and h.hs.size - h.n_missing == 82805
    assert not h.has_direction and not h.has_current
    assert float(np.nanmax(h.hs)) == pytest.approx(7.10, abs=0.01)  # the benchmark's 7.0994
