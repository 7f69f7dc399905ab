"""2D DEM of a pipe pushed into dense sand — a tiny, seconds-long version of the SD preset.

Prepares a small specimen (multi-layer under-compaction, 1 g then 25 g), pushes the pipe to
0.1D and prints the resistance at prototype scale and the inertial-number check. The paper's
full-size runs use ``onbottom dem penetrate --preset SD`` (hours on 2 cores, resumable).
Writes ``ex07_dem.nc`` and ``ex07_V_w.png``.

    python examples/ex07_dem_penetration.py
"""

from __future__ import annotations

from onbottom.dem.config import SD_REDUCED, Geometry, Loading, Preparation
from onbottom.dem.experiment import penetrate
from onbottom.dem.preparation import prepare_sample
from onbottom.plotting.dem import plot_resistance
from onbottom.results import save_dataset

config = SD_REDUCED.replace(
    name="tiny-SD",
    geometry=Geometry(width=0.06, height=0.02, pipe_diameter=0.02),  # model scale [m]
    preparation=Preparation(n_layers=2, max_settle_time=0.05),
    loading=Loading(gravity_factor=25.0, pipe_velocity=0.1, final_embedment_ratio=0.1),
)
sample = prepare_sample(config)
print(f"specimen: {sample.n} disks, void ratio {sample.void_ratio():.3f}")
ds = penetrate(config, sample, snapshots=(0.1,))
v = ds["V_prototype"].values
print(f"V at w = {float(ds['w_over_D'].values[-1]):.2f}D: {v[-1] / 1e3:.1f} kN/m (prototype)")
print(f"inertial number I = {ds.attrs['inertial_number']:.2e} (quasi-static needs < 1e-3)")
save_dataset(ds, "ex07_dem.nc")
plot_resistance(ds).savefig("ex07_V_w.png", dpi=100)
