"""A pipe section on sand through a storm: Morison loads fed back by the pipe's motion.

Builds a 0.5 h build-up + 3 h storm from the peak sea state, runs the section with the
Verley & Sotberg sand model (DNV-RP-F109 load reductions updated from the current
penetration) and prints the maximum displacement and the F109 verdicts against 0.5D and 10D.
Run: ``python examples/ex09_storm_section.py`` (a few seconds after numba compilation).
"""

from __future__ import annotations

from onbottom.dynamics.storm_section import simulate_storm_section
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.inputs.storm import Current, SeaState, Storm
from onbottom.soil.verley_sotberg import VerleySotberg

pipe = Pipe(outer_diameter=0.3951, submerged_weight=1500.0)  # D [m], w_s [N/m]
soil = VerleySotberg.silica(pipe, Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6))
peak = SeaState(hs=4.68, tp=10.8, gamma=1.009, spreading_s=8.0)  # waves normal to the pipe
storm = Storm.standard(peak, build_up_hours=0.5, peak_hours=3.0, seed=0)
current = Current(velocity=0.91, reference_height=1.0, z0=5.2e-6)

res = simulate_storm_section(pipe, soil, storm, depth=13.0, current=current)
d = pipe.outer_diameter
print(res.message)
print(f"max |y| = {res.max_displacement:.3f} m = {res.max_displacement / d:.3f}D")
print(f"final y = {res.final_displacement:.3f} m")
print(
    f"penetration: {res.summary['min_penetration']:.3f} m -> {res.summary['max_penetration']:.3f} m"
)
for name, ok in res.criteria.items():
    print(f"F109 {name}: {'pass' if ok else 'fail'}")
e = res.summary
print(
    f"energy: hydro work {e['work_hydro']:.1f} J/m = soil {e['work_soil']:.1f} J/m"
    f" + kinetic {e['kinetic_energy']:.2e} J/m"
)
