"""DNV-RP-F109 design checks from Python: pipe build-up, design sea state, absolute lateral
stability, the minimum concrete thickness, and the V–H envelope of the peak loads.

The pipe and sea state are the public F109 design-sheet case (219.1 × 12.7 mm steel, 5.5 mm
corrosion coat, 82.55 mm concrete; 13 m of water, H_s 4.68 m, T_p 10.8 s, 0.91 m/s current).
Writes ``ex08_vh_envelope.png``. The same checks from a case file:
``onbottom stability examples/stability_case.toml``.

    python examples/ex08_f109_design.py
"""

from __future__ import annotations

from onbottom.checks import absolute_lateral_stability
from onbottom.checks.design import NoFeasibleDesignError, design_concrete_thickness
from onbottom.hydro.design_sea_state import design_oscillation, significant_bed_velocity
from onbottom.hydro.load_envelope import load_envelope
from onbottom.inputs import Layer, Sand
from onbottom.inputs.environment import Environment, LoadCombination
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.inputs.storm import Current, SeaState
from onbottom.plotting.load_envelope import plot_load_envelope

buildup = PipeBuildUp(
    steel_outer_diameter=0.2191,  # m
    wall_thickness=0.0127,  # m
    layers=(
        Layer(name="corrosion", thickness=0.0055, density=1335.0),
        Layer(name="concrete", thickness=0.08255, density=3043.5),
    ),
    contents=Contents.uniform(1025.0),  # kg/m³
)
p = buildup.properties("operation")
print(
    f"D = {p.outer_diameter:.4f} m, w_s = {p.submerged_weight:.1f} N/m, "
    f"s_g = {p.specific_gravity:.4f}, EI = {p.bending_stiffness:.3e} N m², "
    f"EA = {p.axial_stiffness:.3e} N"
)

# U_s and T_u for a whole set of sea states at once (no frequency grid to build)
us, tu = significant_bed_velocity([3.0, 4.68, 6.0], [9.0, 10.8, 12.0], 13.0)
print("U_s [m/s]:", us.round(3), " T_u [s]:", tu.round(2))

o = design_oscillation(
    4.68, 10.8, 13.0, p.outer_diameter, current_velocity=0.91, submerged_weight=p.submerged_weight
)
print(
    f"design sheet: gamma = {o.gamma:.4f}, T_n = {o.tn:.4f} s, U_s = {o.us:.4f} m/s, "
    f"T_u = {o.tu:.4f} s, U* = {o.u_star:.3f} m/s, V* = {o.v_star:.3f} m/s, K* = {o.k_star:.1f}"
)

sand = Sand(submerged_unit_weight=10.0e3, friction_coefficient=0.6)
r = absolute_lateral_stability(
    buildup.pipe("operation"), sand, hs=4.68, tp=10.8, depth=13.0, current_velocity=0.91
)
verdict = "passes" if r.passes else "fails"
print(f"absolute lateral stability: utilisation {r.utilisation:.3f} ({verdict})")

# the same pipe in 40 m of water: how much concrete does it need?
combos = [
    LoadCombination(
        name="100-yr wave + 10-yr current",
        sea_state=SeaState(hs=5.0, tp=11.0),
        current=Current(velocity=0.35, reference_height=3.0),
    )
]
try:
    res = design_concrete_thickness(
        buildup, sand, Environment(water_depth=40.0), combos, thickness_max=0.15
    )
    print(f"minimum concrete thickness in 40 m: {res.value * 1e3:.1f} mm ({res.governing_check})")
except NoFeasibleDesignError as exc:
    print(f"no concrete thickness up to 150 mm passes: {exc}")

env = load_envelope(
    hs=4.68,
    tp=10.8,
    depth=13.0,
    diameter=p.outer_diameter,
    submerged_weight=p.submerged_weight,
    current=float(o.v_star),
    r_y=r.r_y,
    r_z=r.r_z,
    seed=0,
)
print(f"V-H envelope: {100 * env.fraction_between(20, 45):.1f}% of {env.n_cycles} cycles in 20-45°")
fig = plot_load_envelope([env], ["design sheet, 3 h, seed 0"])
fig.savefig("ex08_vh_envelope.png", dpi=100)
