"""Fourier coefficient table: schema errors named, files round-trip, interpolation by hand."""

from __future__ import annotations

import importlib.util
import io
import math
import pathlib
import warnings

import numpy as np
import pytest

from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.hydro.fourier_table import FourierTable, coefficient_names

ROOT = pathlib.Path(__file__).resolve().parents[2]

HEADER = "K,M," + ",".join(coefficient_names(1))
UNITS = ",".join("-" for _ in HEADER.split(","))


def _csv(rows: list[str], header: str = HEADER, units: str = UNITS) -> io.StringIO:
    return io.StringIO("\n".join(["# source: unit test", header, units, *rows]) + "\n")


# a 2 x 2 grid, N = 1: Y_A0 = K + 10 M, the other coefficients fixed
GOOD = [
    "2,0,2,0.1,0.2,0.5,0,0",
    "2,0.5,7,0.1,0.2,0.5,0,0",
    "4,0,4,0.1,0.2,0.5,0,0",
    "4,0.5,9,0.1,0.2,0.5,0,0",
]


def test_read_and_bilinear_interpolation_by_hand():
    tab = FourierTable.from_csv(_csv(GOOD))
    assert tab.harmonics == 1 and tab.source == "unit test"
    np.testing.assert_array_equal(tab.k_grid, [2.0, 4.0])
    np.testing.assert_array_equal(tab.m_grid, [0.0, 0.5])
    # Y_A0 = K + 10 M is bilinear: exact at any interior point
    c = tab.coefficients_at(3.0, 0.25)
    assert c[0, 0] == pytest.approx(3.0 + 2.5, abs=1e-14)
    np.testing.assert_allclose(c[0, 1:], [0.1, 0.2])
    np.testing.assert_allclose(c[1], [0.5, 0.0, 0.0])
    # the normalised force at θ = π/2: A0 + A1 cos + B1 sin = 5.5 + 0.2
    cy, cz = tab.normalized_force(3.0, 0.25, np.array([math.pi / 2]))
    assert cy[0] == pytest.approx(5.7, abs=1e-14) and cz[0] == pytest.approx(0.5, abs=1e-14)
    with pytest.raises(ValueError):
        tab.coefficients[0, 0, 0, 0, 0] = 1.0  # immutable


def test_outside_the_grid_is_clamped_with_a_named_warning():
    tab = FourierTable.from_csv(_csv(GOOD))
    with pytest.warns(OutOfRangeWarning, match="K = 10 is outside"):
        c = tab.coefficients_at(10.0, 0.0)
    assert c[0, 0] == pytest.approx(4.0)
    with pytest.warns(OutOfRangeWarning, match="M = -0.3"):
        c = tab.coefficients_at(2.0, -0.3)
    assert c[0, 0] == pytest.approx(2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tab.coefficients_at(4.0, 0.5)  # on the edge: no warning


@pytest.mark.parametrize(
    ("rows", "header", "units", "match"),
    [
        (GOOD, HEADER, UNITS.replace("-", "m/s", 1), "column K has unit 'm/s'"),
        (GOOD, HEADER, UNITS[:-2], "units line has 7 entries for 8 columns"),
        (GOOD, HEADER.replace(",Z_B1", ""), None, "missing column 'Z_B1'"),
        (GOOD, HEADER.replace("K,", "Kc,"), None, "unknown column 'Kc'"),
        (GOOD, HEADER.replace("M,", ""), None, "missing column 'M'"),
        ([GOOD[0], GOOD[2], GOOD[1], GOOD[3]], HEADER, UNITS, "row 3: non-monotone grid"),
        ([GOOD[0], GOOD[0], *GOOD[2:]], HEADER, UNITS, "row 2: duplicate cell"),
        (GOOD[:3], HEADER, UNITS, r"missing cell \(K=4, M=0.5\)"),
        ([*GOOD[:3], "4,0.5,9,0.1,,0.5,0,0"], HEADER, UNITS, "Y_B1 = '' is invalid"),
        ([*GOOD[:3], "4,0.5,9,0.1,0.2"], HEADER, UNITS, "5 fields for 8 columns"),
        ([*GOOD[:3], "4,0.5,nan,0.1,0.2,0.5,0,0"], HEADER, UNITS, "Y_A0 = nan"),
        (["2,0,1,0,0,0,0,0", "2,1.5,1,0,0,0,0,0"], HEADER, UNITS, "must lie in"),
        (["-1,0,1,0,0,0,0,0"], HEADER, UNITS, "K must be > 0"),
    ],
)
def test_schema_errors_are_named(rows, header, units, match):
    if units is None:
        units = ",".join("-" for _ in header.split(","))
    with pytest.raises(InputError, match=match):
        FourierTable.from_csv(_csv(rows, header, units))


def test_harmonic_order_limit_and_b0():
    header = "K,M," + ",".join(coefficient_names(9))
    row = "1,0," + ",".join("0" for _ in coefficient_names(9))
    with pytest.raises(InputError, match="harmonic order N = 9"):
        FourierTable.from_csv(_csv([row], header, ",".join("-" for _ in header.split(","))))
    header = HEADER + ",Y_B0"
    with pytest.raises(InputError, match="B starts at n = 1"):
        FourierTable.from_csv(_csv([GOOD[0] + ",0"], header, UNITS + ",-"))


def test_roughness_axis_linear_between_slices():
    header = "k_over_D," + HEADER
    rows = [f"0,{r}" for r in GOOD] + [f"0.01,{r.replace(',0.5,0,0', ',1.5,0,0')}" for r in GOOD]
    tab = FourierTable.from_csv(_csv(rows, header, UNITS + ",-"))
    assert tab.has_roughness
    with pytest.raises(InputError, match="at_roughness"):
        tab.coefficients_at(3.0, 0.0)
    flat = tab.at_roughness(0.005)
    assert flat.coefficients_at(3.0, 0.0)[1, 0] == pytest.approx(1.0)
    with pytest.warns(OutOfRangeWarning, match="k_over_D"):
        tab.at_roughness(0.05)


def test_csv_and_netcdf_round_trip(tmp_path):
    tab = FourierTable.from_csv(_csv(GOOD))
    tab.to_csv(tmp_path / "t.csv")
    back = FourierTable.load(tmp_path / "t.csv")
    np.testing.assert_array_equal(back.coefficients, tab.coefficients)
    assert back.source == "unit test"
    tab.to_netcdf(tmp_path / "t.nc")
    nc = FourierTable.load(tmp_path / "t.nc")
    np.testing.assert_array_equal(nc.coefficients, tab.coefficients)
    np.testing.assert_array_equal(nc.m_grid, tab.m_grid)
    assert nc.source == "unit test"
    with pytest.raises(InputError, match="no such file"):
        FourierTable.load(tmp_path / "missing.csv")
    with pytest.raises(InputError, match=r"expected a \.csv or \.nc"):
        (tmp_path / "t.txt").write_text("x")
        FourierTable.load(tmp_path / "t.txt")


def test_netcdf_bad_units_and_missing_cell(tmp_path):
    import xarray as xr

    tab = FourierTable.from_csv(_csv(GOOD))
    tab.to_netcdf(tmp_path / "t.nc")
    with xr.open_dataset(tmp_path / "t.nc") as ds:
        ds = ds.load()
    bad = ds.copy()
    bad["Y_A1"].attrs["units"] = "N/m"
    bad.to_netcdf(tmp_path / "bad.nc")
    with pytest.raises(InputError, match="variable Y_A1 has units 'N/m'"):
        FourierTable.load(tmp_path / "bad.nc")
    hole = ds.copy(deep=True)
    hole["Z_A0"][1, 0] = np.nan
    hole.to_netcdf(tmp_path / "hole.nc")
    with pytest.raises(InputError, match=r"missing cell \(K=4, M=0\): Z_A0"):
        FourierTable.load(tmp_path / "hole.nc")


def test_shipped_example_is_synthetic_and_reproducible():
    tab = FourierTable.example()
    assert tab.harmonics == 5
    assert "SYNTHETIC" in tab.source and tab.metadata["synthetic"] == "yes"
    assert tab.describe()["fourier_table_synthetic"] == "yes"
    spec = importlib.util.spec_from_file_location(
        "make_fourier_example", ROOT / "tools" / "make_fourier_example.py"
    )
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    again = mod.build()
    np.testing.assert_allclose(again.coefficients, tab.coefficients, rtol=1e-9, atol=1e-12)
    np.testing.assert_array_equal(again.k_grid, tab.k_grid)
    np.testing.assert_array_equal(again.m_grid, tab.m_grid)
