"""Report section: the full-size DEM penetration runs, from their committed summaries.

A full-size run (≈ 60k disks, 3.6e6 steps) takes hours, so the report reads the summaries in
``docs/validation/dem/`` (written by ``onbottom dem summarize``; how, on which commit and
machine: ``docs/validation/dem_penetration.md``) and applies the tolerances of
``tests/validation/test_dem_full_size.py``, fixed before the runs:

* SM hardens (bin-mean V non-decreasing 0.1D → 0.3D → 0.5D, no drop > 15 % after 0.1D); SD
  softens periodically (≥ 2 drops > 5 % after 0.1D);
* heave within ±0.1D of the paper's 0.15D (SM) and 0.25D (SD); SD heaves more than SM;
* bin-mean V at 0.4D and 0.5D within a factor 1.5 of the paper's centrifuge values;
* the run is complete (0.5D) and quasi-static (inertial number ≤ 1e-3).
"""

from __future__ import annotations

from pathlib import Path

from onbottom.report.content import Check, SectionContent, SectionContext, Table
from onbottom.report.registry import section

PAGE = "docs/validation/dem_penetration.md"

KNOWN = {
    "SM hardens": "documented deviation (xfail): the SM specimen is denser than the paper's"
    " (D_r ≈ 57 % instead of 48 %) and saw-tooths like dense sand; see " + PAGE,
    ("SD", 0.4): "documented deviation (xfail): the SD softening cycles are out of phase with"
    " the test's (DEM peak at 0.41D, test trough at 0.35–0.4D); see " + PAGE,
}

FIGURES = (
    ("dem_V_w_f114.png", "DEM resistance (prototype) with the F114 bounds and the paper's values."),
    ("dem_heave.png", "Surface heave beside the pipe at 0.5D, SM and SD."),
)


def _summary_dir(ctx: SectionContext) -> Path | None:
    if ctx.repo_root is None:
        return None
    d = ctx.repo_root / "docs" / "validation" / "dem"
    return d if d.is_dir() else None


def _episodes_after(ds, w_min: float, drop: float) -> list[tuple[float, float]]:
    w = ds["softening_w_peak"].values
    frac = 1.0 - ds["softening_V_prototype_trough"].values / ds["softening_V_prototype_peak"].values
    return [(float(a), float(b)) for a, b in zip(w, frac, strict=True) if a > w_min and b > drop]


def _no_summaries() -> SectionContent:
    """The section when the committed summaries are not there (no source checkout)."""
    return SectionContent(
        summary="The committed DEM summaries (docs/validation/dem/) are not found: this"
        " onbottom does not run from a source checkout.",
        checks=[
            Check(
                name="DEM summaries present",
                value=None,
                reference="docs/validation/dem/",
                tolerance="present",
                status="info",
            )
        ],
    )


def _specimen(name: str, d) -> tuple[list[Check], list]:
    """One specimen's checks (complete and quasi-static, heave, V at 0.4D and 0.5D) and its
    table row."""
    from onbottom.dem.published import PUBLISHED

    checks: list[Check] = []
    complete = int(d.attrs["complete"]) == 1 and float(d.attrs["w_over_D_reached"]) >= 0.499
    inertial = float(d.attrs["inertial_number"])
    checks.append(
        Check(
            name=f"{name}: complete to 0.5D and quasi-static",
            value=f"w/D {float(d.attrs['w_over_D_reached']):.3f}, I = {inertial:.1e}",
            reference="w/D ≥ 0.5, I ≤ 1e-3",
            tolerance="both",
            status="pass" if complete and inertial <= 1e-3 else "fail",
        )
    )
    heave = float(d.attrs["heave_peak_over_D"])
    ref = PUBLISHED[name].heave_over_D
    checks.append(
        Check(
            name=f"{name}: heave peak / D",
            value=heave,
            reference=ref,
            tolerance="±0.1",
            status="pass" if abs(heave - ref) <= 0.1 else "fail",
            note="paper Fig. 8 (DEM)",
        )
    )
    for ratio in (0.4, 0.5):
        v = float(d.attrs[f"V_prototype_at_{ratio:g}D"]) / 1e3
        paper = PUBLISHED[name].resistance[ratio] / 1e3
        ok = paper / 1.5 <= v <= 1.5 * paper
        checks.append(
            Check(
                name=f"{name}: V at {ratio:g}D",
                value=v,
                reference=paper,
                tolerance="within ×1.5",
                status="pass" if ok else "fail",
                unit="kN/m",
                note="" if ok else KNOWN.get((name, ratio), ""),
            )
        )
    row = [
        name,
        int(d.attrs["n_particles"]),
        int(d.attrs["seed"]),
        *[float(d.attrs[f"V_prototype_at_{r:g}D"]) / 1e3 for r in (0.1, 0.3, 0.5)],
        heave,
        int(d.attrs["softening_episodes"]),
    ]
    return checks, row


def _behaviour(ds: dict) -> list[Check]:
    """SM hardens, SD softens periodically, SD heaves more than SM (of the specimens there)."""
    checks: list[Check] = []
    if "SM" in ds:
        v = [float(ds["SM"].attrs[f"V_prototype_at_{r:g}D"]) / 1e3 for r in (0.1, 0.3, 0.5)]
        hardens = v[0] <= v[1] <= v[2] and _episodes_after(ds["SM"], 0.1, 0.15) == []
        checks.append(
            Check(
                name="SM hardens (paper: medium-dense sand)",
                value=" / ".join(f"{x:.1f}" for x in v),
                reference="non-decreasing, no drop > 15 %",
                tolerance="both",
                status="pass" if hardens else "fail",
                unit="kN/m at 0.1/0.3/0.5D",
                note="" if hardens else KNOWN["SM hardens"],
            )
        )
    if "SD" in ds:
        n = len(_episodes_after(ds["SD"], 0.1, 0.05))
        checks.append(
            Check(
                name="SD softens periodically (paper: dense sand)",
                value=n,
                reference="≥ 2 drops > 5 % after 0.1D",
                tolerance="≥ 2",
                status="pass" if n >= 2 else "fail",
                unit="drops",
            )
        )
    if "SM" in ds and "SD" in ds:
        hm, hd = (float(ds[k].attrs["heave_peak_over_D"]) for k in ("SM", "SD"))
        checks.append(
            Check(
                name="SD heaves more than SM",
                value=f"{hd:.3f} > {hm:.3f}",
                reference="SD > SM",
                tolerance="order",
                status="pass" if hd > hm else "fail",
            )
        )
    return checks


ROWS_COLUMNS = [
    "specimen",
    "particles",
    "seed",
    "V at 0.1D",
    "V at 0.3D",
    "V at 0.5D",
    "heave / D",
    "softening drops",
]
"""Columns of the table of the full-size runs."""


@section("dem", "2D DEM penetration: the full-size runs (committed summaries)", order=90)
def build(ctx: SectionContext) -> SectionContent:
    """Apply the full-size DEM tolerances to the committed summaries."""
    from onbottom.results import load_dataset

    folder = _summary_dir(ctx)
    if folder is None:
        return _no_summaries()
    ds = {}
    checks: list[Check] = []
    rows = []
    for name in ("SM", "SD"):
        path = folder / f"{name}_summary.nc"
        if not path.exists():
            checks.append(
                Check(
                    name=f"{name} summary present",
                    value=None,
                    reference=path.name,
                    tolerance="present",
                    status="info",
                    note="full-size run not done yet",
                )
            )
            continue
        ds[name] = load_dataset(path)
        found, row = _specimen(name, ds[name])
        checks += found
        rows.append(row)
    checks += _behaviour(ds)
    figs = [ctx.copy_figure(folder / f, cap) for f, cap in FIGURES if (folder / f).exists()]
    return SectionContent(
        summary=(
            "A pipe pushed into medium-dense (SM) and dense (SD) sand at 25 g in the 2D DEM,"
            " compared with what the penetration paper reports for its centrifuge tests and its"
            " DEM. The runs are not repeated here; their summaries are committed."
        ),
        checks=checks,
        tables=[
            Table(
                caption="Full-size runs (prototype V [kN/m])",
                columns=ROWS_COLUMNS,
                rows=rows,
                digits=2,
            )
        ],
        figures=figs,
        notes=[f"How the runs were made (commit, machine, run time): {PAGE}."],
        sources=["penetration paper §4.2–4.3, Figs. 5 and 8, via onbottom.dem.published"],
    )
