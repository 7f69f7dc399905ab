"""Report section: generalized-stability curves from dynamic storm runs, when committed.

A curve sweep (:mod:`onbottom.study.stability_curves`, ``onbottom curves CASE``) needs of the
order of 10⁴ storms (the committed 256-point sweeps: about 7,000 storms each, 28 and 37 min
wall on 2 loaded cores, as their ``wall_time_s`` attributes record), too long for a report
run. The report shows the sweeps committed as NetCDF files (written by ``onbottom curves``) in
package data ``onbottom/data/stability_curves/`` (``src/onbottom/data/stability_curves/`` in the
repository): a table of L_stable and L_10 per (soil, N, M, K) and the curves, each file with the
statistic its L is (:func:`~onbottom.study.stability_curves.curve_statistic`: a fractile and the
median of each seed's own L, or the former mean of maxima) and its seed count. Without such a
file the section says so. There is no pass/fail here: the comparison with F109's generalized
tables (:mod:`onbottom.checks.f109_generalized`) is a validation page of its own
(docs/validation/dynamic_curves_vs_f109.md).
"""

from __future__ import annotations

from pathlib import Path

from onbottom.report.content import Check, SectionContent, SectionContext, Table
from onbottom.report.registry import section

REQUIRES = ("onbottom.study.stability_curves",)

FOLDER = "onbottom/data/stability_curves"
"""Where committed sweeps (NetCDF from ``onbottom curves``) are looked for (package data)."""


def sweep_folder() -> Path:
    """The folder of the shipped sweeps (package data)."""
    from importlib.resources import files as package_files

    return Path(str(package_files("onbottom") / "data" / "stability_curves"))


@section("stability_curves", "Stability curves from dynamic runs", order=80, requires=REQUIRES)
def build(ctx: SectionContext) -> SectionContent:
    """Tabulate and plot every committed curve sweep."""
    from onbottom.results import load_dataset
    from onbottom.study.stability_curves import curve_statistic, curves_table

    folder = sweep_folder()
    files = sorted(folder.glob("*.nc")) if folder.is_dir() else []
    if not files:
        return SectionContent(
            summary="No committed stability-curve sweep: a sweep of about 7,000 storms takes half"
            " an hour on 2 cores (the committed ones: 28 and 37 min wall), so the report shows"
            f" the NetCDF files of `onbottom curves` committed in {FOLDER}/.",
            checks=[
                Check(
                    name="committed sweeps",
                    value=0,
                    reference=None,
                    tolerance="—",
                    status="info",
                )
            ],
        )
    from onbottom.plotting.storm import plot_stability_curves

    tables, figures = [], []
    flagged = 0
    costs = []
    stats = []
    for path in files:
        ds = load_dataset(path)
        stat = curve_statistic(ds)
        stats.append(f"{path.stem}: {stat['label']}")
        if "wall_time_s" in ds.attrs and "total_storms" in ds.attrs:
            costs.append(
                f"{path.stem}: {int(ds.attrs['total_storms']):,} storms in"
                f" {float(ds.attrs['wall_time_s']) / 60.0:.0f} min wall on"
                f" {int(ds.attrs.get('workers', 1))} workers"
            )
        rows = curves_table(ds)
        flagged += sum(
            1 for r in rows if any(v for k, v in r.items() if k.endswith("_out_of_range"))
        )
        cols = list(rows[0]) if rows else ["soil"]
        tables.append(
            Table(
                caption=f"{path.name}: weight parameter L at the 0.5D and 10D criteria;"
                f" L = {stat['label']}"
                " (*_out_of_range = 1: the storms deciding the point buried the pipe beyond"
                " the soil model's range, z > D/2)",
                columns=cols,
                rows=[[r[c] for c in cols] for r in rows],
                digits=3,
            )
        )
        figures.append(
            ctx.save_figure(
                plot_stability_curves(ds, title=f"{path.stem}: L = {stat['label']}"),
                path.stem,
                f"{path.name}: L/(2 + M)² against K for each soil and M; open red"
                " markers: points outside the soil model's range.",
            )
        )
    if len(files) > 1:
        from onbottom.plotting.storm import plot_curves_against_m

        sweeps = {p.stem: load_dataset(p) for p in files}
        for crit in ("L_stable", "L_10"):
            figures.append(
                ctx.save_figure(
                    plot_curves_against_m(sweeps, criterion=crit),
                    f"curves_against_M_{crit}",
                    f"{crit}/(2 + M)² against M, one colour per K, one line style per"
                    f" committed sweep ({', '.join(sweeps)}): the form in which F109's"
                    " generalized method is discussed (at K >= 10 L rises with M to a peak"
                    " near M ≈ 0.8–1, then settles; at low M L falls as K grows).",
                )
            )
    return SectionContent(
        summary="Weight parameter L = w_s/(½ρDU_s²) at which the largest lateral displacement"
        " of a storm reaches 0.5D (L_stable) and 10D (L_10). Statistic of each file:"
        f" {'; '.join(stats)}."
        + (f" Cost of the committed sweeps (from the files): {'; '.join(costs)}." if costs else ""),
        checks=[
            Check(
                name="committed sweeps",
                value=len(files),
                reference=None,
                tolerance="—",
                status="info",
            ),
            *(
                Check(
                    name=f"statistic of {path.stem}",
                    value=s.split(": ", 1)[1],
                    reference=None,
                    tolerance="—",
                    status="info",
                )
                for path, s in zip(files, stats, strict=True)
            ),
            Check(
                name="curve points outside the soil model's range",
                value=flagged,
                reference=None,
                tolerance="—",
                status="info",
            ),
        ],
        tables=tables,
        figures=figures,
        notes=["Construction of each point and the choices made: docs/theory/storm_section.md."],
    )
