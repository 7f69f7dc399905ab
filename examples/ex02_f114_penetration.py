"""DNVGL-RP-F114 vertical penetration: drained sand with bounds, and undrained clay.

Sand: the centrifuge case of the penetration paper (prototype D = 0.5 m, dry sand
γ_d ≈ 16.7 kN/m³, φ' 33° (critical state) to 40° (peak)): resistance curve with the lower and
upper estimates, and the embedment under 60 kN/m. Clay: Model 2 (Eq 4.8) for a soft clay.
Writes ``ex02_penetration.png``.

    python examples/ex02_f114_penetration.py
"""

from __future__ import annotations

import numpy as np

from onbottom import Clay, Pipe
from onbottom.plotting.penetration import plot_penetration_curve
from onbottom.soil import (
    DrainedBounds,
    DrainedPenetration,
    UndrainedModel2,
    penetration_curve,
    solve_embedment,
)

sand = DrainedPenetration(diameter=0.5, unit_weight=16.7e3, friction_angle_deg=36.0)
bounds = DrainedBounds.from_friction_angles(
    diameter=0.5, unit_weight=16.7e3, lower_friction_angle_deg=33.0, upper_friction_angle_deg=40.0
)
embedment = solve_embedment(sand, 60e3)  # applied vertical load [N/m]
ds = penetration_curve(sand, bounds=bounds, embedment=embedment)
for r in (0.1, 0.3, 0.5):
    i = int(np.argmin(abs(ds["z_over_D"].values - r)))
    q, lo, hi = (ds[k].values[i] / 1e3 for k in ("Q_v", "Q_v_lower", "Q_v_upper"))
    print(f"z/D = {r}: Q_v = {q:6.1f} kN/m  (lower {lo:5.1f}, upper {hi:6.1f})")
print(f"sand: {embedment.message}: z = {embedment.z:.4f} m (z/D = {embedment.z / 0.5:.3f})")
fig, _ = plot_penetration_curve(ds)
fig.savefig("ex02_penetration.png", dpi=100)

pipe = Pipe(outer_diameter=0.5, submerged_weight=2.0e3)
clay = Clay(
    undrained_shear_strength=3e3,
    strength_gradient=1.5e3,
    submerged_unit_weight=6e3,
    unit_weight=16e3,
)
clay_model = UndrainedModel2.from_inputs(pipe, clay)
res = solve_embedment(clay_model, pipe.submerged_weight)
print(f"clay (Model 2): z = {res.z:.4f} m under W_s = 2 kN/m")
