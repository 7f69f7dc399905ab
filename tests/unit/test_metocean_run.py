"""Unit test: :mod:`onbottom.metocean.run` — the design table, notes, fragments and files of
``onbottom metocean``, called directly (no command line)."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

pytest.importorskip("pyextremes")
pytest.importorskip("virocon")

from onbottom.metocean import (
    Hindcast,
    MetoceanOptions,
    run_metocean_analysis,
    synthetic_hindcast,
    write_metocean_outputs,
)


def _hindcast(current: bool = True) -> Hindcast:
    d = synthetic_hindcast(years=10.0, seed=5)
    return Hindcast(
        time=d["time"],
        hs=d["hs"],
        tp=d["tp"],
        wave_direction_deg=d["wave_direction_deg"],
        current_speed=d["current_speed"] if current else None,
        current_direction_deg=d["current_direction_deg"] if current else None,
        source="synthetic 10 y",
    )


@pytest.fixture(scope="module")
def run():
    options = MetoceanOptions(sectors=2, return_periods=(1.0, 10.0, 100.0))
    return run_metocean_analysis(_hindcast(), options, pipe_heading_deg=90.0, current_height=2.0)


def test_table_notes_and_fragments(run):
    assert [r.sector for r in run.rows] == ["omni", *run.result.sectors]
    assert run.source == "synthetic 10 y" and run.success
    # 100 years from a 10-year record is past 4 record lengths: the first note says so
    assert run.notes[0].startswith("return periods up to 100 years from a 10.0-year record")
    # every sector either has its fragment or a note saying why not
    for row in run.rows:
        assert row.sector in run.fragments or any(
            n.startswith(f"no case_{row.sector}.toml") for n in run.notes
        )
    frag = tomllib.loads(run.fragments["omni"])
    omni = run.rows[0]
    assert frag["waves"]["hs"] == pytest.approx(round(omni.at("hs", 100), 2))
    assert frag["current"]["velocity"] == pytest.approx(round(omni.at("current", 10), 3))
    assert frag["current"]["reference_height"] == 2.0
    assert frag["waves"]["direction_deg"] == 90.0  # omni: waves normal to the pipe


def test_summary_is_the_table_in_si(run):
    payload = run.as_dict(["a.csv"])
    assert payload["files"] == ["a.csv"] and payload["notes"] == run.notes
    assert payload["return_periods"] == [1.0, 10.0, 100.0]
    assert payload["years"] == pytest.approx(10.0, abs=1e-3)
    omni = payload["table"][0]
    assert omni["centre_deg"] is None  # the record has no centre: NaN is written as None
    np.testing.assert_allclose(omni["hs"], run.rows[0].hs)
    assert payload["contour_max_hs"]["100"] == pytest.approx(
        float(run.result.contours[100.0][0].max())
    )


def test_no_fragments_without_current_or_the_f109_periods():
    hc = _hindcast(current=False)
    r = run_metocean_analysis(hc, MetoceanOptions(sectors=1, return_periods=(1.0, 10.0)))
    assert r.fragments == {}
    # ξ̂ = −0.38 from 29 storms of 10 years: the tail guard's two notes come after
    assert all(n.startswith("H_s omni: ") for n in r.notes[1:]) and len(r.notes) == 3
    assert r.notes[:1] == [
        "no case_*.toml: the F109 combinations need the 10- and 100-year values and a"
        " current in the hindcast"
    ]  # 10 years from 10 years: no extrapolation note
    assert r.as_dict()["current_model"] is None
    assert r.as_dict()["table"][0]["current"] is None


def test_writes_table_fragments_and_netcdf(run, tmp_path):
    import xarray as xr

    files = write_metocean_outputs(run, tmp_path / "new")
    names = [f.name for f in files]
    assert names[0] == "design_table.csv" and names[-1] == "metocean.nc"
    assert names[1:-1] == [f"case_{s}.toml" for s in run.fragments]
    assert (tmp_path / "new" / "case_omni.toml").read_text() == run.fragments["omni"]
    lines = (tmp_path / "new" / "design_table.csv").read_text().splitlines()
    assert len(lines) == 2 + len(run.rows)
    ds = xr.load_dataset(tmp_path / "new" / "metocean.nc")
    value = ds["hs_return_value"].sel(sector="omni").values
    np.testing.assert_allclose(value, run.rows[0].hs)
    assert all(math.isfinite(v) for v in value)


def test_sector_without_storms_gets_notes_not_a_fragment():
    d = synthetic_hindcast(years=10.0, seed=5)
    hc = Hindcast(
        time=d["time"],
        hs=d["hs"],
        tp=d["tp"],
        wave_direction_deg=np.full(d["hs"].size, 10.0),  # every sea from N
        current_speed=d["current_speed"],
        current_direction_deg=d["current_direction_deg"],
    )
    r = run_metocean_analysis(hc, MetoceanOptions(sectors=4))
    assert list(r.fragments) == ["omni", "N"] and r.success
    # per sector, in the table's order: why it has no values, then why no fragment
    assert r.notes[1:3] == [
        "H_s E: 0 storms above u = inf (< 10)",
        "no case_E.toml: sector E: too few storms for 10- and 100-year values (NaN in the table)",
    ]
    assert [n.split(":")[0] for n in r.notes[3:] if not n.startswith("H_s omni")] == [
        "H_s S",
        "no case_S.toml",
        "H_s W",
        "no case_W.toml",
    ]
