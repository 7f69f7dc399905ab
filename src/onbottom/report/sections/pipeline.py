"""Report section: the pipeline finite-element model, two verification cases.

The cases and tolerances of ``tests/verification/test_pipeline_dynamics.py``:

* rigid slide: a 100 m line with free ends, loads in phase along it and weak friction
  (μ = 0.1) slides more than 10D as a rigid body: bending strain < 1e-12 and all nodes at
  the same final position to 1e-9 of the displacement;
* energy: a 200 m line with fixed ends on Verley & Sotberg sand under a regular wave
  (HHT α = 0): kinetic + strain energy = work of the hydrodynamic loads + work of the soil,
  to 1 % of the hydrodynamic work.

Needs :mod:`onbottom.dynamics.pipeline` and :mod:`onbottom.hydro.short_crested`.
"""

from __future__ import annotations

from onbottom.report.content import Check, SectionContent, SectionContext, Table
from onbottom.report.registry import section

REQUIRES = ("onbottom.dynamics.pipeline", "onbottom.hydro.short_crested")


@section(
    "pipeline",
    "Pipeline finite-element model: verification cases",
    order=70,
    slow=True,
    requires=REQUIRES,
)
def build(ctx: SectionContext) -> SectionContent:
    """Rigid slide and energy balance of the pipeline FE."""
    import numpy as np

    from onbottom.dynamics.pipeline import PipelineModel, PipelineSettings, simulate_pipeline
    from onbottom.hydro.short_crested import NodeKinematics, regular_node_kinematics
    from onbottom.inputs.pipe import Pipe
    from onbottom.inputs.soil import Sand
    from onbottom.soil.coulomb import CoulombFriction
    from onbottom.soil.verley_sotberg import VerleySotberg

    pipe = Pipe(
        outer_diameter=0.4, submerged_weight=600.0, bending_stiffness=5e7, axial_stiffness=5e9
    )
    d = pipe.outer_diameter

    # rigid slide
    m = PipelineModel(
        pipe=pipe,
        length=100.0,
        element_length=4.0,
        soil=CoulombFriction(friction_coefficient=0.1),
        end_conditions="free",
    )
    kin = regular_node_kinematics(m.x.size, 40.0, 0.05, 0.0, 10.0)
    kin = NodeKinematics(
        t0=0.0, dt=kin.dt, velocity=kin.velocity + np.float32(1.5), acceleration=kin.acceleration
    )
    slide = simulate_pipeline(m, kin, settings=PipelineSettings(dt_max=0.1, record_interval=5.0))
    spread = float(np.ptp(slide.data["y"].values[-1]))
    rigid_ok = (
        slide.success
        and slide.max_displacement > 10.0 * d
        and spread < 1e-9 * slide.max_displacement
        and slide.max_strain < 1e-12
    )

    # energy balance in a regular wave on sand
    m2 = PipelineModel(
        pipe=pipe,
        length=200.0,
        element_length=4.0,
        soil=VerleySotberg.silica(
            pipe, Sand(submerged_unit_weight=1.0e4, friction_coefficient=0.6)
        ),
        end_conditions="fixed",
    )
    wave = regular_node_kinematics(
        m2.x.size, 80.0, 0.05, 1.6, 10.0, ramp=30.0, x=m2.x, wavelength=400.0
    )
    storm = simulate_pipeline(m2, wave, settings=PipelineSettings(alpha=0.0, dt_max=0.05))
    s = storm.summary
    energy_ok = storm.success and abs(s["energy_residual"]) <= 0.01 * abs(s["work_hydro"])
    checks = [
        Check(
            name="rigid slide: > 10D, nodes together, no bending strain",
            value=f"{slide.max_displacement / d:.1f}D, spread {spread:.1e} m,"
            f" strain {slide.max_strain:.1e}",
            reference="> 10D, < 1e-9 × y_max, < 1e-12",
            tolerance="all three",
            status="pass" if rigid_ok else "fail",
        ),
        Check(
            name="energy: KE + SE − W_hydro − W_soil",
            value=s["energy_residual"],
            reference=0.0,
            tolerance=f"≤ 1 % of W_hydro ({0.01 * abs(s['work_hydro']):.1f} J)",
            status="pass" if energy_ok else "fail",
            unit="J",
        ),
    ]
    figures = []
    from onbottom.plotting.pipeline import plot_pipeline_result

    if storm.data is not None:
        figures.append(
            ctx.save_figure(
                plot_pipeline_result(storm, title="200 m line, regular wave, sand"),
                "regular_wave",
                "The 200 m line in a regular wave: envelopes, deflected shapes and the worst"
                " node's history.",
                dpi=80,
            )
        )
    table = Table(
        caption="Energy case (200 m, fixed ends, regular wave velocity amplitude 1.6 m/s, T 10 s)",
        columns=["quantity", "value"],
        rows=[
            ["max |y| [m]", storm.max_displacement],
            ["max bending strain [-]", storm.max_strain],
            ["work of the hydrodynamic loads [J]", s["work_hydro"]],
            ["work of the soil [J]", s["work_soil"]],
            ["energy residual [J]", s["energy_residual"]],
        ],
        digits=4,
    )
    return SectionContent(
        summary=(
            "Planform corotational beam on pipe–soil springs at every node, Morison loads with"
            " relative velocity, HHT-α time integration: two cases with exact answers."
        ),
        checks=checks,
        tables=[table],
        figures=figures,
        notes=["Theory: docs/theory/pipeline_fe.md; all cases: the verification tests."],
    )
