"""Validation of the full-size DEM runs against the penetration paper (§4.2–4.3, Figs. 5, 8).

A full-size case (≈ 60k disks) takes 1.3–1.6 h on 2 cores (sub-cycled; 2.5 h plain), so it is not
rerun here: the tests read the committed summaries in ``docs/validation/dem/`` (written by
``onbottom dem summarize`` from the runs; how they were produced, on which commit and machine,
is in ``docs/validation/dem_penetration.md``) and skip a case whose summary is not there yet.

Tolerances, fixed before the runs:

* what the paper says its DEM reproduces — SM hardens (bin-mean V non-decreasing from 0.1D to
  0.3D to 0.5D, and no drop of more than 15 % below the running peak after 0.1D); SD softens
  periodically (at least two drops of more than 5 % below the running peak after 0.1D);
* heave: within ±0.1D of the paper's 0.15D (SM) and 0.25D (SD); SD heaves more than SM;
* resistance: bin-mean V at 0.4D and 0.5D within a factor 1.5 of the centrifuge values the
  paper validates its DEM against (120/125 kN/m SM, 106/150 kN/m SD) — the paper itself reports
  "discrepancies" between its DEM and the tests, so this is a consistency band, not a fit;
* the run is complete (0.5D) and quasi-static (inertial number ≤ 1e-3).

``SM-Dr48`` (SM at the paper's interior density, seed 3, zonally sub-cycled engine; the
tolerances below written on 2026-11-23 before its penetration ran): the same four checks as SM
(the paper's SM criteria: hardening, heave, resistance, complete/quasi-static) plus its
interior void ratio at 25 g within 0.227 ± 0.004 (D_r 44–52 %, the paper 48 %).

``SM-Dr48-seed4`` (the same preset, second seed 4, its summary files renamed from
``SM-Dr48_*``): the same checks as SM-Dr48, added on 2026-11-23 while its preparation ran,
before its penetration.

``SM-Dr48-seed6`` (the same preset, third seed 6, summary files renamed from ``SM-Dr48_*``;
the timed whole case with cell order before each compacted layer): the same checks as
SM-Dr48, added on 2026-11-23 before its preparation started.

``SM-Dr48-seed6-fire1g`` (seed 6 again, with ``Preparation.relaxation = "fire-1g"``: FIRE in
the 1 g stage only, started from seed 6's own compacted specimen; written on 2026-11-25
before its run): the same checks as SM-Dr48, and the lever's full-size equivalence with the
damped seed 6 — interior e at 25 g within 0.002 of seed 6's (the same compacted specimen:
the 3D-wide trial of FIRE in every equilibrium stage moved it by 0.0012), the bin means of
0–0.05D and 0.05–0.1D within 10 % of seed 6's (before the curves decorrelate; on SM-reduced
the first bins differ by 0.05 seed standard deviations), and the mean V over 0–0.5D within two
standard deviations of the three damped seeds' (3, 4, 6). *Outcome:* its specimen came out
0.0047 denser (interior e 0.2189 at 25 g), failing the first check and the 0.227 ± 0.004 band;
the penetration was not run, so the other checks were not made (strict xfail on the
preparation record, ``docs/validation/dem/levers/``).

``SM-Dr48-seed6-cstep`` (seed 6 with ``Numerics.compaction_dt_safety`` = 1.0: the compaction
at twice the preset's step, every later stage as the preset; a whole case from a fresh start,
the timed case of 2026-11-26; written on 2026-11-26 before its run): the SM-Dr48 checks
(complete/quasi-static, interior e 0.227 ± 0.004, heave, resistance at 0.4D and 0.5D; the
hardening criterion is reported with the other SM-Dr48 seeds once known), and the lever's
full-size equivalence with the three damped seeds at the preset's step (3, 4, 6 — a new
compaction path gives a new specimen, so the comparison is with the seeds' spread, not with
seed 6): interior e at 25 g within 0.002 of their mean (on SM-reduced, 36 seeds, the lever
moved it by +0.0001 ± 0.0002), and the mean V over 0–0.5D and over 0–0.1D each within two
standard deviations of the three seeds' means. *Outcome* (58.5 min, the case's own record
``levers/full_case_SM-Dr48_seed6_cstep10_stages.json``): complete, quasi-static, interior e
0.2238 (0.0004 from the seeds' mean), heave 0.129D, V at 0.5D 110.9 kN/m, mean V over
0–0.5D 66.6 kN/m (band 62.6–86.8) pass; **V over 0–0.1D (17.5 kN/m against the band
18.0–29.3) and V at 0.4D (78.7 kN/m, in a 52 % drop) fail**, and it does not harden (as the
preset's seeds): strict xfails with the measured reasons. The lever stays opt-in.

``SD-seed5`` (the dense preset, second seed 5, summary files renamed from ``SD_*``; written
on 2026-11-23 before its run, which then started over with the SD preset of that evening —
FIRE preparation, penetration sub-cycled at ``subcycle_dt_safety`` 0.25 — the tolerances
unchanged): the SD
checks (complete/quasi-static, periodic softening, heave, resistance at 0.4D and 0.5D, heaves
more than SM) plus its interior void ratio at 25 g within 0.197 ± 0.004 (D_r 74–82 %, the paper
78 %; seed 2 came out at 0.1941), and the paper's reading of its Figs 8, 10 and 11 — the dense
sand's drops are general-shear failures: every softening episode after 0.1D deeper than 10 %
has its band of rotated disks (event snapshots, ``onbottom.dem.summary.band_episodes``) reach
the surface, and there is at least one such episode.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from onbottom.dem.published import PUBLISHED
from onbottom.results import load_dataset

pytestmark = pytest.mark.validation

HERE = Path(__file__).resolve().parents[2] / "docs" / "validation" / "dem"


def _paper(name: str) -> str:
    """The paper's specimen a preset stands for (SM-Dr48 is SM at the paper's density)."""
    if name.startswith("SM-Dr48"):
        return "SM"
    return name.split("-seed")[0]


def _summary(name: str):
    path = HERE / f"{name}_summary.nc"
    if not path.exists():
        pytest.skip(f"full-size {name} not run yet ({path.name} absent)")
    return load_dataset(path)


def _episodes_after(ds, w_min: float, drop: float) -> list[tuple[float, float]]:
    """(w_peak, drop fraction) of the softening episodes after w_min deeper than ``drop``."""
    w = ds["softening_w_peak"].values
    frac = 1.0 - ds["softening_V_prototype_trough"].values / ds["softening_V_prototype_peak"].values
    return [(float(a), float(b)) for a, b in zip(w, frac, strict=True) if a > w_min and b > drop]


@pytest.mark.parametrize(
    "name",
    ["SM", "SD", "SM-Dr48", "SM-Dr48-seed4", "SM-Dr48-seed6", "SD-seed5", "SM-Dr48-seed6-cstep"],
)
def test_run_is_complete_and_quasi_static(name):
    ds = _summary(name)
    assert int(ds.attrs["complete"]) == 1
    assert float(ds.attrs["w_over_D_reached"]) >= 0.5 - 1e-3
    assert float(ds.attrs["inertial_number"]) <= 1e-3


_SM_SOFTENS = (
    "the full-size SM run (seed 1) rises overall (36.9 / 67.1 / 136.1 kN/m at 0.1 / 0.3 / 0.5D) "
    "but saw-tooths: drops of 22 % at 0.22-0.26D and 48 % at 0.29-0.35D (92 -> 48 kN/m), the "
    "paper's dense-sand behaviour. Our SM specimen is denser than the paper's (interior e = "
    "0.218 at 25 g vs 0.227: D_r about 57 % instead of 48 %); see "
    "docs/validation/dem_penetration.md"
)


_SM48_SOFTENS = (
    "at the paper's density too (SM-Dr48, interior e = 0.2248 at 25 g, D_r 50 %) the full-size "
    "medium-dense run rises overall (44.6 / 125.4 / 161.1 kN/m at 0.1 / 0.3 / 0.5D) but "
    "saw-tooths: drops of 21 % at 0.14-0.17D, 28 % at 0.19-0.20D, 34 % at 0.27-0.28D and 47 % at "
    "0.31-0.41D (131 -> 70 kN/m), none with a band of rotated disks reaching the surface (local "
    "shear under the pipe, as the paper describes for SM); see docs/validation/dem_penetration.md"
)


_SM48_SEED4_SOFTENS = (
    "the second SM-Dr48 seed (seed 4, interior e = 0.2241, D_r 51 %) rises overall too (42.7 / "
    "89.2 / 104.0 kN/m at 0.1 / 0.3 / 0.5D) and saw-tooths: drops of 42 % at 0.20-0.21D, 24 % "
    "at 0.34-0.36D and 32 % at 0.42-0.43D (131 -> 90 kN/m), none with a band reaching the "
    "surface (0 of 5); see docs/validation/dem_penetration.md"
)


_SM48_SEED6_SOFTENS = (
    "the third SM-Dr48 seed (seed 6, interior e = 0.2236, D_r 51 %) rises at every 0.1D "
    "(39.9 / 63.5 / 80.2 / 94.0 / 121.2 kN/m at 0.1-0.5D) but saw-tooths: drops of 28 % at "
    "0.19-0.21D, 22 % at 0.29-0.30D, 38 % at 0.33-0.35D (102 -> 63 kN/m), 21 % at 0.42-0.43D "
    "and 17 % at 0.48-0.49D, none with a band reaching the surface (0 of 9); see "
    "docs/validation/dem_penetration.md"
)


_CSTEP_SOFTENS = (
    "seed 6 with the compaction at twice the step (interior e = 0.2238) rises overall (38.5 / "
    "77.0 / 110.9 kN/m at 0.1 / 0.3 / 0.5D) and saw-tooths like the three preset seeds: drops "
    "of 17 % at 0.16-0.17D, 20 % at 0.20-0.22D, 29 % at 0.28-0.29D, 52 % at 0.32-0.43D "
    "(107 -> 52 kN/m) and 21 % at 0.47-0.48D, none with a band reaching the surface (0 of 6); "
    "see docs/validation/dem_penetration.md"
)


@pytest.mark.parametrize(
    "name",
    [
        pytest.param("SM", marks=pytest.mark.xfail(strict=True, reason=_SM_SOFTENS)),
        pytest.param("SM-Dr48", marks=pytest.mark.xfail(strict=True, reason=_SM48_SOFTENS)),
        pytest.param(
            "SM-Dr48-seed4", marks=pytest.mark.xfail(strict=True, reason=_SM48_SEED4_SOFTENS)
        ),
        pytest.param(
            "SM-Dr48-seed6", marks=pytest.mark.xfail(strict=True, reason=_SM48_SEED6_SOFTENS)
        ),
        pytest.param(
            "SM-Dr48-seed6-cstep", marks=pytest.mark.xfail(strict=True, reason=_CSTEP_SOFTENS)
        ),
    ],
)
def test_medium_dense_hardens(name):
    """The paper's SM criterion, on SM (D_r 57 %) and on SM-Dr48 (the paper's density)."""
    ds = _summary(name)
    v = [float(ds.attrs[f"V_prototype_at_{r:g}D"]) for r in (0.1, 0.3, 0.5)]
    assert v[0] <= v[1] <= v[2], v
    assert _episodes_after(ds, 0.1, 0.15) == []


@pytest.mark.parametrize(
    "name", ["SM-Dr48", "SM-Dr48-seed4", "SM-Dr48-seed6", "SM-Dr48-seed6-cstep"]
)
def test_medium_dense_at_the_paper_density_has_its_void_ratio(name):
    ds = _summary(name)
    assert abs(float(ds.attrs["initial_void_ratio"]) - 0.227) <= 0.004


@pytest.mark.parametrize("name", ["SD", "SD-seed5"])
def test_dense_softens_periodically(name):
    ds = _summary(name)
    assert len(_episodes_after(ds, 0.1, 0.05)) >= 2, ds.attrs["softening"]


def test_dense_second_seed_has_the_paper_void_ratio():
    ds = _summary("SD-seed5")
    assert abs(float(ds.attrs["initial_void_ratio"]) - 0.197) <= 0.004


_SD5_BANDS_LOCAL = (
    "the second SD seed (seed 5, interior e = 0.1942) softens periodically (drops of 63 % at "
    "0.15-0.22D, 49 % at 0.26-0.29D, 42 % at 0.32-0.34D, 47 % at 0.41-0.45D) but no drop has a "
    "band of disks rotated peak->trough joining the pipe to the surface, at 10 deg (clusters of "
    "5-41 disks at the pipe), 5 deg or 3 deg (clusters at the pipe of up to 545 disks): "
    "the drops are local shear under the pipe while the velocity field at 0.5D is a wedge "
    "flowing to the surface on both sides; see docs/validation/dem_penetration.md"
)


@pytest.mark.xfail(strict=True, reason=_SD5_BANDS_LOCAL)
def test_dense_drops_are_bands_reaching_the_surface():
    """Paper Figs 8, 10, 11: each marked SD drop is a general-shear band reaching the surface."""
    ds = _summary("SD-seed5")
    w = ds["band_w_peak"].values
    drop = ds["band_drop_percent"].values
    reach = ds["band_reaches_surface"].values
    major = (w > 0.1) & (drop > 10.0)
    assert major.any(), ds.attrs["softening"]
    assert reach[major].all(), list(zip(w[major], drop[major], reach[major], strict=True))


@pytest.mark.parametrize(
    "name",
    ["SM", "SD", "SM-Dr48", "SM-Dr48-seed4", "SM-Dr48-seed6", "SD-seed5", "SM-Dr48-seed6-cstep"],
)
def test_heave_height(name):
    ds = _summary(name)
    assert abs(float(ds.attrs["heave_peak_over_D"]) - PUBLISHED[_paper(name)].heave_over_D) <= 0.1


@pytest.mark.parametrize("name", ["SD", "SD-seed5"])
def test_dense_heaves_more(name):
    assert float(_summary(name).attrs["heave_peak_over_D"]) > float(
        _summary("SM").attrs["heave_peak_over_D"]
    )


_SD_PEAK_AT_0_4D = (
    "the full-size SD run (seed 2) softens periodically like the centrifuge test, but its "
    "cycles are out of phase with the test's: the DEM peaks at 0.41D (190 kN/m; bin mean 187 "
    "kN/m at 0.4D) and drops to 114 kN/m by 0.5D, where the test is in its 150 -> 100 kN/m "
    "trough at 0.35-0.4D (106 kN/m) and rises to 150 kN/m at 0.5D. The values bracket each "
    "other (DEM 187/116, test 106/150) but a point comparison at 0.4D falls outside x1.5; see "
    "docs/validation/dem_penetration.md"
)


_CSTEP_TROUGH_AT_0_4D = (
    "seed 6 with the compaction at twice the step is in its deepest drop at 0.4D (107 kN/m at "
    "0.32D down to 52 at 0.43D): bin mean 78.7 kN/m at 0.4D, x0.66 of the centrifuge's 120 "
    "(the band is x1/1.5 = 80); at 0.5D 110.9 (x0.89 of 125) passes. The preset's seeds gave "
    "85.6 (seed 3, also in a trough), 113.7 and 94.0 at 0.4D"
)


@pytest.mark.parametrize(
    ("name", "ratio"),
    [
        ("SM", 0.4),
        ("SM", 0.5),
        ("SM-Dr48", 0.4),
        ("SM-Dr48", 0.5),
        ("SM-Dr48-seed4", 0.4),
        ("SM-Dr48-seed4", 0.5),
        ("SM-Dr48-seed6", 0.4),
        ("SM-Dr48-seed6", 0.5),
        pytest.param(
            "SM-Dr48-seed6-cstep",
            0.4,
            marks=pytest.mark.xfail(strict=True, reason=_CSTEP_TROUGH_AT_0_4D),
        ),
        ("SM-Dr48-seed6-cstep", 0.5),
        pytest.param("SD", 0.4, marks=pytest.mark.xfail(strict=True, reason=_SD_PEAK_AT_0_4D)),
        ("SD", 0.5),
        ("SD-seed5", 0.4),
        ("SD-seed5", 0.5),
    ],
)
def test_resistance_within_factor_1_5_of_centrifuge(name, ratio):
    ds = _summary(name)
    dem = float(ds.attrs[f"V_prototype_at_{ratio:g}D"])
    paper = PUBLISHED[_paper(name)].resistance[ratio]
    assert paper / 1.5 <= dem <= 1.5 * paper, (dem, paper)


LEVERS = HERE / "levers"

_FIRE1G_DENSER = (
    "FIRE in the 1 g stage consolidates the full-size bed further than local damping: from the "
    "same compacted specimen (e 0.2338), 1 g 0.2205 against 0.2260 and 25 g 0.2189 against "
    "0.2236 (interior), 0.0047 denser, outside both the 0.002 of the lever check and the paper's "
    "0.227 +- 0.004 (SM-reduced, 12 seeds: within 0.0008; its 1 g stage is short). The damped "
    "stage meets the 1e-3 ratio while the bed still creeps. The penetration was not run; see "
    "docs/validation/dem_penetration.md"
)


def _stages(name: str) -> dict:
    return json.loads((LEVERS / name).read_text())


def test_fire_1g_at_full_size_starts_from_the_same_compaction_and_halves_the_1g_steps():
    """The lever's record: the compacted specimen is the damped run's (bitwise: same void
    ratio), and its 1 g stage took 190,000 plain steps against 374,500 sub-cycled ones."""
    lever = _stages("full_case_SM-Dr48_seed6_fire1g_preparation.json")
    damped = _stages("full_case_SM-Dr48_seed6_frictionless_stages.json")
    assert lever["relaxation"] == "fire-1g"
    assert lever["sample"]["void_ratio_compacted"] == damped["sample"]["void_ratio_compacted"]
    assert lever["compaction_from"]["compaction"] == damped["preparation"]["stages"]["compaction"]
    assert lever["preparation"]["stages"]["1g"]["steps"] == 190_000
    assert damped["preparation"]["stages"]["1g"]["steps"] == 374_500
    assert lever["sample"]["equilibrium_1g_converged"] == 1.0


@pytest.mark.xfail(strict=True, reason=_FIRE1G_DENSER)
def test_fire_1g_at_full_size_keeps_the_specimen():
    """The void-ratio checks fixed before the run (module docstring)."""
    e_lever = _stages("full_case_SM-Dr48_seed6_fire1g_preparation.json")["sample"]["void_ratio_Ng"]
    e_damped = float(_summary("SM-Dr48-seed6").attrs["initial_void_ratio"])
    assert abs(e_lever - e_damped) <= 0.002, (e_lever, e_damped)
    assert abs(e_lever - 0.227) <= 0.004, e_lever


_DAMPED_SEEDS = ("SM-Dr48", "SM-Dr48-seed4", "SM-Dr48-seed6")


def _mean_v(name: str, w_max: float) -> float:
    """Mean of the bin-mean prototype V [kN/m] over 0 < w/D < ``w_max``."""
    v = _summary(name)["V_prototype_mean"]
    return float(v.where(v["w_over_D"] < w_max).mean()) / 1e3


def test_compaction_step_at_full_size_keeps_the_void_ratio():
    """The compaction at twice the step: interior e within 0.002 of the damped seeds' mean."""
    e = float(_summary("SM-Dr48-seed6-cstep").attrs["initial_void_ratio"])
    ref = [float(_summary(n).attrs["initial_void_ratio"]) for n in _DAMPED_SEEDS]
    assert abs(e - sum(ref) / len(ref)) <= 0.002, (e, ref)


_CSTEP_SOFTER_START = (
    "the first 0.1D of the lever's full-size run is softer than the preset's three seeds: "
    "mean V over 0-0.1D 17.5 kN/m against 26.9, 22.5 and 21.6 (mean 23.7, sd 2.8: band "
    "18.0-29.3), V at 0.05D 15.2 against 24.9, 21.0, 25.3. Over 0-0.5D it is inside (66.6 "
    "against 74.7 +- 2 x 6.1) and its void ratio matches (0.2238 against 0.2242). On "
    "SM-reduced (36 seeds) the lever's 0-0.05D bin was the only early one below the preset's "
    "(-3.6 kN/m, 0.96 paired standard errors): a softer surface layer, the one the lid "
    "compacts last, is the likely reading. The lever stays opt-in"
)


@pytest.mark.parametrize(
    "w_max",
    [
        pytest.param(0.1, marks=pytest.mark.xfail(strict=True, reason=_CSTEP_SOFTER_START)),
        0.5 + 1e-9,
    ],
)
def test_compaction_step_at_full_size_within_the_seed_scatter(w_max):
    """Mean V over 0-0.1D and 0-0.5D within two standard deviations of seeds 3, 4, 6."""
    lever = _mean_v("SM-Dr48-seed6-cstep", w_max)
    ref = [_mean_v(n, w_max) for n in _DAMPED_SEEDS]
    mean = sum(ref) / len(ref)
    sd = (sum((r - mean) ** 2 for r in ref) / (len(ref) - 1)) ** 0.5
    assert abs(lever - mean) <= 2.0 * sd, (lever, ref)
