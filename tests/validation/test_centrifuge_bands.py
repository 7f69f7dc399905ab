"""Validation of the Table 1 cycle counts against sensitivity bands (Youssef & Cassidy 2014).

The paper leaves the cycle shape, the time basis, γ', the placement of B in Eqs 13/14, the
reading of Eq 8, the work integrand and α of tests 4–5 unstated. The band of a test is the
range of cycles to the displacement limit over the full grid of those choices
(:mod:`onbottom.study.centrifuge_bands`, Table 2 parameters). Verdict asserted: Table 1 lies
inside the band — the only statement that holds whatever the unstated choices are. Defaults
and why: :data:`onbottom.study.centrifuge_bands.CHOICES`.

The full grid (1152 runs) is too slow for every run of the suite; the committed
``docs/validation/bands/centrifuge_bands.csv`` is checked against a recomputed subset here
(one-at-a-time variations of two tests) and against the full grids of two tests in a slow test.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from onbottom.dynamics.centrifuge import TESTS
from onbottom.study.centrifuge_bands import (
    _ORDER,
    band_cases,
    compute_bands,
    read_csv,
    summarise,
)

pytestmark = pytest.mark.validation

CSV = Path(__file__).resolve().parents[2] / "docs" / "validation" / "bands" / "centrifuge_bands.csv"
TOL_CYCLES = 1e-5  # the CSV keeps 6 decimals


@pytest.fixture(scope="module")
def committed():
    return read_csv(CSV)


def _key(r):
    return (r.test, *(getattr(r, k) for k in _ORDER))


def _check_against_committed(rows, committed):
    table = {_key(r): r for r in committed}
    for r in rows:
        c = table[_key(r)]
        if r.cycles_model is None:
            assert c.cycles_model is None, _key(r)
        else:
            assert c.cycles_model == pytest.approx(r.cycles_model, abs=TOL_CYCLES), _key(r)
        assert c.max_penetration == pytest.approx(r.max_penetration, abs=1e-6), _key(r)
        assert c.is_default == r.is_default


def test_committed_csv_has_every_grid_point(committed):
    expected = {(c["test"], *(c[k] for k in _ORDER)) for n in TESTS for c in band_cases(n)}
    assert {_key(r) for r in committed} == expected
    assert sum(r.is_default for r in committed) == len(TESTS)


@pytest.mark.parametrize("name", ["Inclined 1", "Regular"])
def test_committed_band_matches_a_recomputed_subset(committed, name):
    rows = compute_bands([name], reduced=True)
    assert len(rows) > 5
    _check_against_committed(rows, committed)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["Inclined 2", "Irregular"])
def test_committed_band_matches_the_full_recomputed_grid(committed, name):
    rows = compute_bands([name])
    assert len(rows) == len(band_cases(name))
    _check_against_committed(rows, committed)


_OUTSIDE_REASON = {
    "Regular": (
        "band 19.20–21.71 groups against 46.22: with 'cycle n = n × first' and a first-cycle"
        " F_V of 0.3 kN/m the vertical load would reach zero (lift-off) at n = 37 < 46, so the"
        " paper's counting unit (sub-cycles?) or first-cycle loads differ from the stated"
        " protocol; our Morison stand-ins for the UWAHYDRO histories are also uncertain"
    ),
    "Irregular": (
        "band 11.43–14.18 groups against 31.25: lift-off at n ≈ 30 < 31.25 under the stated"
        " 10 %-per-group growth with the first-cycle F_V read from Fig. 8; counting unit and"
        " load histories uncertain (see docs/validation/youssef_cassidy_2014.md)"
    ),
}


@pytest.mark.parametrize(
    "name",
    [
        *(n for n in TESTS if n not in _OUTSIDE_REASON),
        *(
            pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=r))
            for n, r in _OUTSIDE_REASON.items()
        ),
    ],
)
def test_table1_cycles_lie_inside_the_band(committed, name):
    (s,) = [x for x in summarise(committed) if x.test == name]
    assert s.n_not_reached == 0
    assert s.cycles_min <= TESTS[name].cycles_used <= s.cycles_max, (s.cycles_min, s.cycles_max)


def test_default_run_lies_inside_its_band(committed):
    for s in summarise(committed):
        assert s.cycles_min <= s.cycles_default <= s.cycles_max


def test_cli_bands_serial_json_matches_committed(tmp_path, capsys, committed):
    import json

    from onbottom.cli.main import main

    code = main(
        [
            "reproduce",
            "--bands",
            "--workers",
            "0",
            "--band-test",
            "Regular",
            "--out",
            str(tmp_path),
            "--json",
        ]
    )
    assert code == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["n_runs"] == len(band_cases("Regular"))
    (band,) = payload["bands"]
    (ref,) = [s for s in summarise(committed) if s.test == "Regular"]
    assert band["cycles_min"] == pytest.approx(ref.cycles_min, abs=TOL_CYCLES)
    assert band["cycles_max"] == pytest.approx(ref.cycles_max, abs=TOL_CYCLES)
    assert (tmp_path / "centrifuge_bands.csv").exists()
    assert (tmp_path / "centrifuge_bands.md").exists()


@pytest.mark.slow
@pytest.mark.dask
def test_bands_on_dask_equal_the_serial_ones():
    from onbottom.study.engine import ParallelMap, dask_client

    serial = compute_bands(["Irregular"], reduced=True)
    with dask_client(n_workers=2) as client:
        parallel = compute_bands(["Irregular"], reduced=True, mapper=ParallelMap(client))
    assert parallel == serial
