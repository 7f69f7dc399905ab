"""Calibrate A, B, C, μ of the calcareous Verley & Sotberg model to a test record.

A virtual record of the Inclined 1 centrifuge test (Youssef & Cassidy 2014) is made with the
paper's Table 2 parameters plus 1 % measurement noise and written as CSV (the format of
docs/calibration.md). It is read back, an (A, μ) misfit map is swept as in the paper's
parametric study, and A, B, C, μ are fitted from a start far away (differential evolution +
least squares). Prints the fit with standard errors and the correlation matrix; writes the
record, the fitted TOML and two figures into ./calibration-example/.

    python examples/ex06_calibrate_verley_sotberg.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from onbottom.calibration.fit import calibrate, grid_search
from onbottom.calibration.objective import HISTORY_ONLY
from onbottom.calibration.paper import PAPER_TABLE2, default_parameters, virtual_record
from onbottom.calibration.records import load_record, save_record
from onbottom.calibration.simulators import CentrifugeSimulator
from onbottom.plotting.calibration import plot_fit, plot_misfit_map

out = Path("calibration-example")
out.mkdir(exist_ok=True)
truth = PAPER_TABLE2["Inclined 1"]  # A, B, C, μ used to make the record
simulator = CentrifugeSimulator()  # section solver, Inclined 1 load programme, γ' = 7.5 kN/m³

path = save_record(virtual_record("Inclined 1", truth, noise=0.01, seed=1), out / "inclined1.csv")
record = load_record(path)

# the paper's way: a parametric grid (here A × μ with B, C at their true values)
start = default_parameters(start={"A": 0.6, "B": 0.8, "C": 1.3, "mu": 1.0})
fixed_bc = default_parameters(start={"B": truth["B"], "C": truth["C"]})
grid = {"A": np.linspace(0.1, 0.5, 17), "mu": np.linspace(0.4, 0.7, 16)}
ds = grid_search(record, fixed_bc, grid, simulator=simulator, weights=HISTORY_ONLY)
print(f"grid minimum: A = {ds.attrs['best_A']:.3f}, mu = {ds.attrs['best_mu']:.3f}")

# global search + polish of all four parameters, from far away
result = calibrate(record, start, simulator=simulator, weights=HISTORY_ONLY, seed=0)
print(result.message)
for p in result.parameters:
    print(
        f"  {p.name:3s} = {p.value:.4f} ± {result.std_errors[p.name]:.4f}  (truth {truth[p.name]})"
    )
print("correlation", result.names)
print(np.array2string(result.correlation, precision=2))
(out / "fitted.toml").write_text(result.to_toml())

fig = plot_fit(record, simulator(record, result.values), labels=["fitted"])
fig.savefig(out / "fit_inclined1.png", dpi=110)
ax = plot_misfit_map(ds, "A", "mu", truth=truth)
ax.set_title("Inclined 1: misfit over A and μ (B, C true)")
ax.figure.savefig(out / "misfit_map_inclined1.png", dpi=110)
