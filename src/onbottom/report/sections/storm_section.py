"""Report section: a pipe section on sand through a design storm (the ex09 case).

A 0.5 h build-up + 3 h storm from the peak sea state of the F109 design sheet (H_s 4.68 m,
T_p 10.8 s, γ 1.009, spreading s = 8, 0.91 m/s current, 13 m of water), pipe D = 0.3951 m,
w_s = 1500 N/m, Verley & Sotberg silica sand (γ'_s 10 kN/m³, μ 0.6), F109 load reductions
from the current penetration (:func:`onbottom.dynamics.storm_section.simulate_storm_section`).

Checked: the solver finishes, and the energy balance W_hydro = ½Mẏ² + W_soil holds to
1e-7 of W_hydro (the tolerance of ``tests/verification/test_storm_section.py``). The F109
displacement verdicts (0.5D, 10D) are results, shown for information.
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext, Table
from onbottom.report.registry import section

REQUIRES = ("onbottom.dynamics.storm_section", "onbottom.inputs.storm")

ENERGY_RTOL = 1e-7
"""Energy balance tolerance relative to the hydrodynamic work [-]."""


@section(
    "storm_section",
    "Storm section: a pipe section through a design storm",
    order=60,
    slow=True,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Run the ex09 storm case; check completion and the energy balance."""
    from onbottom.dynamics.storm_section import simulate_storm_section
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand
    from onbottom.inputs.storm import Current, SeaState, Storm
    from onbottom.soil.verley_sotberg import VerleySotberg

    pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)
    soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6))
    peak = SeaState(hs=4.68, tp=10.8, gamma=1.009, spreading_s=8.0)
    storm = Storm.standard(peak, build_up_hours=0.5, peak_hours=3.0, seed=0)
    current = Current(velocity=0.91, reference_height=1.0, z0=5.2e-6)
    res = simulate_storm_section(pipe, soil, storm, depth=13.0, current=current)
    s = res.summary
    d = pipe.outer_diameter
    balance = s["work_hydro"] - s["work_soil"] - s["kinetic_energy"]
    checks = [
        Check(
            name="solver finishes the storm",
            value=res.message,
            reference="success",
            tolerance="success",
            status="pass" if res.success else "fail",
        ),
        Check(
            name="energy: W_hydro − W_soil − ½Mẏ²",
            value=balance,
            reference=0.0,
            tolerance=f"≤ {ENERGY_RTOL:g} × W_hydro ({ENERGY_RTOL * s['work_hydro']:.2e} J/m)",
            status="pass" if abs(balance) <= ENERGY_RTOL * abs(s["work_hydro"]) else "fail",
            unit="J/m",
        ),
    ]
    for name, ok in res.criteria.items():
        checks.append(
            Check(
                name=f"F109 criterion {name}",
                value="met" if ok else "not met",
                reference=None,
                tolerance="— (a design result)",
                status="info",
            )
        )
    figures = []
    from onbottom.plotting.storm import plot_storm_result

    if res.data is not None:
        figures.append(
            ctx.save_figure(
                plot_storm_result(res, title="ex09 storm case"),
                "history",
                "Displacement, penetration and loads through the storm.",
                dpi=80,
            )
        )
    table = Table(
        caption="Storm result",
        columns=["quantity", "value"],
        rows=[
            ["max |y| [m]", res.max_displacement],
            ["max |y| / D [-]", res.max_displacement / d],
            ["final y [m]", res.final_displacement],
            ["penetration min [m]", s.get("min_penetration")],
            ["penetration max [m]", s.get("max_penetration")],
            ["hydrodynamic work [J/m]", s["work_hydro"]],
            ["work on the soil [J/m]", s["work_soil"]],
        ],
        digits=4,
    )
    return SectionContent(
        summary=(
            "A rigid pipe section under Morison drag/inertia and lift from a seeded storm,"
            " with the F109 load reductions updated from its penetration, resisted by the"
            " Verley & Sotberg sand model (examples/ex09_storm_section.py)."
        ),
        checks=checks,
        tables=[table],
        figures=figures,
        notes=["Theory and choices: docs/theory/storm_section.md."],
        sources=["DNV-RP-F109 (2017) §3.4–3.5 (dynamic lateral stability)"],
    )
