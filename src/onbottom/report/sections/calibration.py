"""Report section: calibration recovers known A, B, C, μ from a noisy synthetic record.

The same experiment as ``tests/verification/test_calibration_recovery.py``: the Inclined 1
test simulated with the paper's Table 2 values, resampled to 1 s, 1 % seeded Gaussian noise;
the global (differential evolution + least squares) calibration starts far away
(A, B, C, μ = 0.6, 0.8, 1.3, 1.0). Tolerances fixed before the run: |fitted − truth| ≤ 0.02
(A, B), 0.01 (C, μ), about a tenth of the spread of Table 2; the ±3 standard-error interval
must cover the truth.
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext, Table, within
from onbottom.report.registry import section

TOLERANCE = {"A": 0.02, "B": 0.02, "C": 0.01, "mu": 0.01}
"""Absolute tolerances on the recovered parameters [-]."""

START = {"A": 0.6, "B": 0.8, "C": 1.3, "mu": 1.0}
"""Start values of the search [-]."""


@section(
    "calibration",
    "Calibration: recovery of known parameters from a noisy record",
    order=40,
    slow=True,
)
def build(ctx: SectionContext) -> SectionContent:
    """Fit A, B, C, μ to a synthetic Inclined 1 record and compare with the truth."""
    from onbottom.calibration.fit import calibrate
    from onbottom.calibration.objective import HISTORY_ONLY
    from onbottom.calibration.paper import PAPER_TABLE2, default_parameters, virtual_record
    from onbottom.calibration.simulators import CentrifugeSimulator
    from onbottom.plotting.calibration import plot_fit

    truth = PAPER_TABLE2["Inclined 1"]
    sim = CentrifugeSimulator()
    rec = virtual_record("Inclined 1", truth, noise=0.01, seed=1, simulator=sim)
    res = calibrate(
        rec,
        default_parameters(start=START),
        simulator=sim,
        weights=HISTORY_ONLY,
        method="global",
        seed=0,
    )
    checks: list[Check] = [
        Check(
            name="calibration converged",
            value=res.message,
            reference="success",
            tolerance="success",
            status="pass" if res.success else "fail",
        )
    ]
    rows = []
    for name, tol in TOLERANCE.items():
        checks.append(
            within(
                f"recovered {name}",
                res.values[name],
                truth[name],
                atol=tol,
                tolerance=f"±{tol:g}",
                note="truth: Table 2, Inclined 1",
            )
        )
        lo, hi = res.interval(name, z=3.0)
        covered = lo <= truth[name] <= hi
        checks.append(
            Check(
                name=f"±3 s.e. interval of {name} covers the truth",
                value=f"{lo:.4f} – {hi:.4f}",
                reference=truth[name],
                tolerance="truth inside",
                status="pass" if covered else "fail",
            )
        )
        rows.append([name, START[name], truth[name], res.values[name], res.std_errors[name]])
    fig = plot_fit(rec, sim(rec, res.values), labels=["fitted"], title="Inclined 1 (synthetic)")
    figure = ctx.save_figure(
        fig,
        "fit",
        "The synthetic record (Table 2 truth + 1 % noise) and the simulation with the fitted"
        " parameters: penetration–displacement and displacement–time.",
        dpi=80,
    )
    return SectionContent(
        summary=(
            "A check of the calibration method: can A, B, C and μ be found again from a record"
            " whose true values are known? (The measured centrifuge records are not public;"
            " docs/validation/calibration.md.)"
        ),
        checks=checks,
        tables=[
            Table(
                caption=(
                    f"Parameters [-]: {res.n_evaluations} simulations,"
                    f" {res.wall_time:.1f} s, method {res.method}"
                ),
                columns=["parameter", "start", "truth", "fitted", "standard error"],
                rows=rows,
                digits=4,
            )
        ],
        figures=[figure],
        sources=["Youssef & Cassidy (2014) Table 2 (the truth)"],
    )
