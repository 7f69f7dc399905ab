"""Pipe-section time-domain simulation: Inclined test 1 of Youssef & Cassidy (2014).

Builds the load programme and the calcareous Verley & Sotberg soil by hand (what
``run_centrifuge_test("Inclined 1")`` does in one call), simulates, prints the summary and
writes a NetCDF file and a figure next to this script's working directory.

    python examples/ex03_section_time_domain.py
"""

from __future__ import annotations

from onbottom import Pipe, Sand
from onbottom.dynamics import inclined_cyclic, section_mass, simulate_section
from onbottom.plotting.section import plot_section_result
from onbottom.soil.verley_sotberg import VerleySotberg

V_PEAK, V_I = 42.98e3, 10.52e3  # installation and cyclic-phase vertical loads [N/m]

pipe = Pipe(outer_diameter=1.0, submerged_weight=V_I)  # D [m], W_s [N/m]
sand = Sand(submerged_unit_weight=7.5e3, friction_coefficient=0.48, kind="calcareous")
soil = VerleySotberg.calcareous(pipe, sand, A=0.25, B=0.35, C=0.79, installation_load=V_PEAK)

# H amplitude +0.25 kN/m per 40 s cycle; V = V_i − |H|/tan 30°
programme = inclined_cyclic(V_I, 0.25e3, 40.0, 30.0, 16, installation_load=V_PEAK)

result = simulate_section(
    programme,
    soil,
    mass=section_mass(pipe),  # pipe + added mass [kg/m]
    displacement_limit=3.0,  # box limit [m]
    after_limit="runaway_end",
)
print(result.message)
print(f"cycles to the 3 m limit: {result.cycles_to_limit:.2f} (test: 13.27)")
print({k: round(v, 4) for k, v in result.summary.items()})
result.save("inclined1_example.nc")
fig = plot_section_result(
    result,
    title="Inclined 1",
    installation_load=V_PEAK,
    cycle_period=40.0,
    displacement_limit=3.0,
)
fig.savefig("inclined1_example.png", dpi=100)
