"""Report section: the seven centrifuge tests of Youssef & Cassidy (2014).

Runs :func:`onbottom.study.youssef_cassidy.run_reproduction` (Table 2 and Table 3 parameters,
γ' = 7.5 kN/m³) and checks the cycles to the displacement limit against Table 1 with the
tolerance of ``tests/validation/test_youssef_cassidy_2014.py``: ±1 load cycle, Table 2
parameters, nothing tuned. Every test is checked, including those the project documents as
outside that tolerance (the note says why, with the page that discusses it); Table 3 rows are
shown for information.
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext, Table
from onbottom.report.registry import section

TOLERANCE_CYCLES = 1.0
"""Tolerance on the cycles to the displacement limit [load cycles]."""

PAGE = "docs/validation/youssef_cassidy_2014.md"

KNOWN_DEVIATIONS = {
    "Inclined 2": "documented deviation (xfail in the validation tests): friction-only sliding"
    " load below cycle 12's amplitude; see " + PAGE,
    "Inclined 4": "α not given by the paper, inferred 30° (assumption 1); see " + PAGE,
    "Inclined 5": "α not given by the paper, inferred 65°, outside Fig. 4's 20–45° envelope"
    " (assumption 1, low confidence); see " + PAGE,
    "Regular": "load histories reconstructed from the figures' first-cycle peaks (assumption 6;"
    " the paper's UWAHYDRO histories are not available); see " + PAGE,
    "Irregular": "load histories reconstructed from the figures' first-cycle peaks (assumption"
    " 6); see " + PAGE,
}
"""Why a test may miss the tolerance, as documented on the validation page."""


@section("centrifuge", "Youssef & Cassidy (2014): the seven centrifuge tests", order=20)
def build(ctx: SectionContext) -> SectionContent:
    """Run the seven tests with Table 2 and Table 3 parameters; check cycles to the limit."""
    import matplotlib.pyplot as plt
    import numpy as np

    from onbottom.plotting.section import reproduction_figure
    from onbottom.study.youssef_cassidy import run_reproduction

    runs = run_reproduction(parameter_sets=("table2", "recommended"))
    checks: list[Check] = []
    rows = []
    for row, _ in runs:
        label = "Table 2" if row.parameter_set == "table2" else "Table 3"
        rows.append(
            [
                row.test,
                label,
                row.A,
                row.B,
                row.C,
                row.mu,
                row.alpha_deg,
                row.cycles_model,
                row.cycles_paper,
                row.cycles_difference,
                row.initial_penetration,
                row.max_penetration,
                row.final_displacement,
            ]
        )
        if row.parameter_set != "table2":
            continue
        ok = row.cycles_difference is not None and abs(row.cycles_difference) <= TOLERANCE_CYCLES
        checks.append(
            Check(
                name=f"{row.test}: cycles to the displacement limit",
                value=row.cycles_model,
                reference=row.cycles_paper,
                tolerance="±1 cycle",
                status="pass" if ok else "fail",
                unit="cycles",
                note="" if ok else KNOWN_DEVIATIONS.get(row.test, ""),
            )
        )
    inc1 = next(r for r, _ in runs if r.test == "Inclined 1" and r.parameter_set == "table2")
    checks.append(
        Check(
            name="Inclined 1: displacement where the runaway stops",
            value=inc1.final_displacement,
            reference=inc1.final_displacement_paper_simulation,
            tolerance="none (the paper's own simulation; the box stopped the test at 3.0 m)",
            status="info",
            unit="m",
        )
    )
    checks.append(
        Check(
            name="Inclined 1: initial penetration",
            value=inc1.initial_penetration,
            reference=inc1.initial_penetration_paper,
            tolerance="none (read from Fig. 9d, ≈; γ' not given, assumption 2)",
            status="info",
            unit="m",
        )
    )

    # cycles, model against Table 1, for both parameter sets
    names = [r.test for r, _ in runs if r.parameter_set == "table2"]
    x = np.arange(len(names))
    fig, ax = plt.subplots(figsize=(7.0, 3.8))
    paper = [r.cycles_paper for r, _ in runs if r.parameter_set == "table2"]
    for k, (ps, lab) in enumerate(
        (("table2", "model, Table 2"), ("recommended", "model, Table 3"))
    ):
        vals = [
            np.nan if r.cycles_model is None else r.cycles_model
            for r, _ in runs
            if r.parameter_set == ps
        ]
        ax.bar(x + (k - 0.5) * 0.27, vals, width=0.27, label=lab, color=f"C{k}")
    ax.errorbar(
        x + 0.4,
        paper,
        yerr=TOLERANCE_CYCLES,
        fmt="k_",
        ms=12,
        capsize=3,
        label="Table 1 (test) ± 1 cycle",
    )
    ax.set_xticks(x, names, rotation=20)
    ax.set_ylabel("load cycles to the displacement limit")
    ax.grid(axis="y", alpha=0.3)
    ax.legend(fontsize=8)
    figs = [
        ctx.save_figure(
            fig,
            "cycles",
            "Cycles to the displacement limit: model (Table 2 and Table 3 parameters) and test"
            " (Table 1) with the ±1-cycle tolerance.",
        )
    ]
    inc1_result = next(
        res for r, res in runs if r.test == "Inclined 1" and r.parameter_set == "table2"
    )
    figs.append(
        ctx.save_figure(
            reproduction_figure(inc1, inc1_result),
            "inclined_1",
            "Inclined 1 with its Table 2 parameters: load path, penetration and displacement"
            " (compare the paper's Fig. 9).",
            dpi=80,
        )
    )
    table = Table(
        caption="All runs (γ' = 7.5 kN/m³; lengths in m, α in degrees)",
        columns=[
            "test",
            "parameters",
            "A",
            "B",
            "C",
            "μ",
            "α [°]",
            "cycles model",
            "cycles Table 1",
            "Δ cycles",
            "z_i [m]",
            "max w [m]",
            "final u [m]",
        ],
        rows=rows,
        digits=2,
    )
    return SectionContent(
        summary=(
            "A rigid pipe section under each test's load-controlled programme, resisted by the"
            " Verley & Sotberg model with the calcareous calibration, run with the calibrated"
            " Table 2 parameters (checked) and the Table 3 recommended values (shown)."
        ),
        checks=checks,
        tables=[table],
        figures=figs,
        notes=[
            "Assumptions where the paper is silent (α of tests 4–5, γ', cycle shape, time axis,"
            " mass, regular/irregular histories) and their effect on the cycle counts are"
            f" tabulated in {PAGE}.",
            "The project claims agreement within ±1 cycle for Inclined 1 and 3 only"
            " (tests/validation/test_youssef_cassidy_2014.py); the other rows are checked with"
            " the same tolerance so that the report shows where the model stands.",
        ],
        sources=[
            "Youssef, B.S. & Cassidy, M.J. (2014), ISOPE 2014, pp. 141–148: Tables 1–3, Fig. 9",
        ],
    )
