"""Lateral pipe–soil resistance: the Verley & Sotberg model, silica and calcareous.

Prints the backbone (region limits, F_r1/F_r2/F_r3, z_i, z3) of the silica model (V&S 1994)
and of the Youssef & Cassidy (2014) calcareous calibration for the same pipe and sand, then
drives the calcareous model along a growing cyclic displacement path and reports how the
penetration grows. Writes ``ex01_path.png``.

    python examples/ex01_soil_models.py
"""

from __future__ import annotations

import numpy as np

from onbottom import Pipe, Sand, VerleySotberg
from onbottom.plotting.backbone import plot_path_response
from onbottom.soil import path_response

pipe = Pipe(outer_diameter=1.0, submerged_weight=10.52e3)  # D [m], W_s [N/m]
sand = Sand(submerged_unit_weight=7.5e3, friction_coefficient=0.48, kind="calcareous")

for soil in (
    VerleySotberg.silica(pipe, sand, installation_load=42.98e3),
    VerleySotberg.calcareous(pipe, sand, installation_load=42.98e3),  # Table 3 A, B, C
):
    pts = soil.backbone_points(10.52e3)  # at V = V_i [N/m], breakout from z2 = z_i
    print(soil.variant, "regions/D:", soil.parameters()["region_limits_over_d"])
    print({k: round(float(v), 5) for k, v in pts.items()})

soil = VerleySotberg.calcareous(pipe, sand, installation_load=42.98e3)
t = np.linspace(0.0, 8.0, 4000)  # 8 cycles, amplitude growing to 0.2 m
u = 0.025 * np.ceil(t + 1e-9) * np.sin(2.0 * np.pi * t)
ds = path_response(soil, u, np.full(u.size, 10.52e3))
z = ds["z"].values
print(f"penetration: z_i = {z[0]:.4f} m → {z.max():.4f} m after 8 growing cycles")
assert np.all(np.diff(z) >= -1e-12), "penetration never decreases inside the trough"
plot_path_response(ds).savefig("ex01_path.png", dpi=100)
