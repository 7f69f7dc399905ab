"""Report section: the seven centrifuge tests of Youssef & Cassidy (2014).

Runs :func:`onbottom.study.youssef_cassidy.run_reproduction` (Table 2 and Table 3 parameters,
the default choices: γ' = 7.5 kN/m³, sine cycles, paper time axis) and shows the cycles to the
displacement limit against Table 1. The cycle counts are *judged* against the sensitivity
bands over the choices the paper leaves open (section ``centrifuge_bands``): a ±1-cycle check
of the default run alone depends on those guesses, so here the difference is shown for
information. Checked pass/fail: the qualitative Fig. 9 behaviour of Inclined 1, with the
assertions of ``tests/validation/test_youssef_cassidy_2014.py``.
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext, Table
from onbottom.report.registry import section

PAGE = "docs/validation/youssef_cassidy_2014.md"

KNOWN_DEVIATIONS = {
    "Inclined 4": "α not given by the paper, inferred 30° (assumption 1); see " + PAGE,
    "Inclined 5": "α not given by the paper, inferred 65°, outside Fig. 4's 20–45° envelope"
    " (assumption 1, low confidence); see " + PAGE,
    "Regular": "load histories reconstructed from the figures' first-cycle peaks (assumption 6;"
    " the paper's UWAHYDRO histories are not available); see " + PAGE,
    "Irregular": "load histories reconstructed from the figures' first-cycle peaks (assumption"
    " 6); see " + PAGE,
}
"""Why a test may miss the tolerance, as documented on the validation page."""


def _fig9_checks(result) -> list[Check]:
    """The Fig. 9 behaviour of Inclined 1 (tests/validation/test_youssef_cassidy_2014.py)."""
    import numpy as np

    d = result.data
    u, w, reg, h = (d[k].values for k in ("y", "z", "region", "H"))
    t = d["time"].values
    n = int(np.argmax(reg >= 3))  # before the first breakout (past y2 = 0.25 D)
    grows = np.diff(w[:n]) > 1e-7
    half_cycles = len({int(np.floor(x / 20.0)) for x in t[1:n][grows]})
    both_signs = bool((h[1:n][grows] > 0).any() and (h[1:n][grows] < 0).any())
    grow_ok = (
        n > 1
        and np.max(np.abs(u[:n])) < 0.25
        and np.all(np.diff(w[:n]) >= -1e-12)
        and w[n - 1] > 1.3 * w[0]
        and half_cycles >= 2
        and both_signs
    )
    in3 = reg == 3
    rises = bool(in3.any() and w[in3][-1] < w[in3][0] and w[-1] < 0.75 * np.max(w))
    c = result.cycles_to_limit
    u_start = float(np.interp(np.floor(c) * 40.0, t, u)) if c is not None else np.nan
    runaway = abs(u_start) < 0.6 and result.summary["final_displacement"] > 3.0
    return [
        Check(
            name="Inclined 1 (Fig. 9): penetration grows in the trough under small cycles",
            value=f"w {w[0]:.3f} → {w[n - 1]:.3f} m in {half_cycles} half-cycles",
            reference="> 1.3 × initial, ≥ 2 half-cycles, both load signs",
            tolerance="all",
            status="pass" if grow_ok else "fail",
        ),
        Check(
            name="Inclined 1 (Fig. 9): the pipe rises after sweeping its berm",
            value=f"final w {w[-1]:.3f} m, max {np.max(w):.3f} m",
            reference="w falls in region 3; final < 0.75 × max",
            tolerance="both",
            status="pass" if rises else "fail",
        ),
        Check(
            name="Inclined 1 (Fig. 9): runaway in the last cycle",
            value=f"|u| {abs(u_start):.2f} m at its start",
            reference="< 0.6 m, then past the 3.0 m box (paper: 0.4 → 3.0 m)",
            tolerance="both",
            status="pass" if runaway else "fail",
        ),
    ]


def _runs_table_and_checks(runs) -> tuple[list[list], list[Check]]:
    """Rows of every run (both parameter sets) and the cycles-to-limit checks (Table 2)."""
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
        checks.append(
            Check(
                name=f"{row.test}: cycles to the displacement limit (default choices)",
                value=row.cycles_model,
                reference=row.cycles_paper,
                tolerance="— (judged against the bands)",
                status="info",
                unit="cycles",
                note=KNOWN_DEVIATIONS.get(row.test, ""),
            )
        )
    return rows, checks


def _inclined_1_checks(inc1, inc1_result) -> list[Check]:
    """Fig. 9 behaviour, the runaway's end and the initial penetration of Inclined 1."""
    return [
        *_fig9_checks(inc1_result),
        Check(
            name="Inclined 1: displacement where the runaway stops",
            value=inc1.final_displacement,
            reference=inc1.final_displacement_paper_simulation,
            tolerance="none (the paper's own simulation; the box stopped the test at 3.0 m)",
            status="info",
            unit="m",
        ),
        Check(
            name="Inclined 1: initial penetration",
            value=inc1.initial_penetration,
            reference=inc1.initial_penetration_paper,
            tolerance="none (read from Fig. 9d, ≈; γ' not given, assumption 2)",
            status="info",
            unit="m",
        ),
    ]


def _cycles_figure(runs):
    """Cycles to the limit, model against Table 1, for both parameter sets."""
    import matplotlib.pyplot as plt
    import numpy as np

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
    ax.plot(x + 0.4, paper, "ko", label="Table 1 (test)")
    ax.set_xticks(x, names, rotation=20)
    ax.set_ylabel("load cycles to the displacement limit")
    ax.grid(axis="y", alpha=0.3)
    ax.legend(fontsize=8)
    return fig


RUNS_COLUMNS = [
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
]
"""Columns of the table of every run."""


@section("centrifuge", "Youssef & Cassidy (2014): the seven centrifuge tests", order=20)
def build(ctx: SectionContext) -> SectionContent:
    """Run the seven tests with Table 2 and Table 3 parameters; check cycles to the limit."""
    from onbottom.plotting.section import reproduction_figure
    from onbottom.study.youssef_cassidy import run_reproduction

    runs = run_reproduction(parameter_sets=("table2", "recommended"))
    rows, checks = _runs_table_and_checks(runs)
    inc1, inc1_result = next(
        (r, res) for r, res in runs if r.test == "Inclined 1" and r.parameter_set == "table2"
    )
    checks += _inclined_1_checks(inc1, inc1_result)
    figs = [
        ctx.save_figure(
            _cycles_figure(runs),
            "cycles",
            "Cycles to the displacement limit: model (Table 2 and Table 3 parameters, default"
            " choices) and test (Table 1).",
        ),
        ctx.save_figure(
            reproduction_figure(inc1, inc1_result),
            "inclined_1",
            "Inclined 1 with its Table 2 parameters: load path, penetration and displacement"
            " (compare the paper's Fig. 9).",
            dpi=80,
        ),
    ]
    table = Table(
        caption="All runs (γ' = 7.5 kN/m³; lengths in m, α in degrees)",
        columns=RUNS_COLUMNS,
        rows=rows,
        digits=2,
    )
    return SectionContent(
        summary=(
            "A rigid pipe section under each test's load-controlled programme, resisted by the"
            " Verley & Sotberg model with the calcareous calibration, run with the calibrated"
            " Table 2 parameters and the Table 3 recommended values, with the default choices"
            " where the paper is silent."
        ),
        checks=checks,
        tables=[table],
        figures=figs,
        notes=[
            "Assumptions where the paper is silent (α of tests 4–5, γ', cycle shape, time axis,"
            " mass, regular/irregular histories) and their effect on the cycle counts are"
            f" tabulated in {PAGE}.",
            "Cycle counts are judged against the sensitivity bands (section"
            " centrifuge_bands), not against ±1 cycle of this one run: the run depends on"
            " choices the paper does not state.",
        ],
        sources=[
            "Youssef, B.S. & Cassidy, M.J. (2014), ISOPE 2014, pp. 141–148: Tables 1–3, Fig. 9",
        ],
    )
