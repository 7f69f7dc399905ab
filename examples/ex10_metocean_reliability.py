"""From a hindcast to a probability: the storm climate of the synthetic hindcast, and the
annual probability that a pipe exceeds the DNV-RP-F109 absolute stability criterion.

1. ``examples/hindcast_synthetic.csv`` (25 years, 3-hourly, known distributions) is analysed
   as ``onbottom metocean`` does (omnidirectional here): POT/GPD return values of H_s with
   95 % intervals, the DNV-RP-C205 H_s–T_p model.
2. Its storms become uncertain inputs (:class:`onbottom.reliability.StormClimate`): Poisson
   storms, GPD peak H_s, log-normal T_p | H_s — with an uncertain friction coefficient.
3. The limit state of one storm is the *unfactored* F109 absolute lateral stability check,
   g = 1 − (F*_Y + μF*_Z)/(μw_s + F_R), waves normal to the pipe, a 0.35 m/s current: a static
   criterion (breakout under the design load), not the dynamic displacement of issue 34 item 3.
   FORM gives the design point and the importance of each input; importance sampling the
   probability with its CV; P_annual = 1 − exp(−λ p), P_50 years = 1 − (1 − P_annual)^50.
4. Beside it, the F109 return-period check (100-year H_s, median T_p, γ_SC) on the same pipe.

Writes ``ex10_contours.png``.

    python examples/ex10_metocean_reliability.py
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from onbottom.checks import absolute_lateral_stability
from onbottom.errors import OutOfRangeWarning
from onbottom.inputs import Layer, Sand
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp
from onbottom.metocean import MetoceanOptions, analyse_hindcast, read_hindcast
from onbottom.plotting.metocean import plot_contours
from onbottom.reliability import (
    StormClimate,
    UncertainParameter,
    estimate_failure_probability,
    lifetime_probability,
)

HINDCAST = Path(__file__).resolve().parent / "hindcast_synthetic.csv"
DEPTH = 45.0  # m
CURRENT = 0.35  # m/s at 3 m above the seabed

result = analyse_hindcast(read_hindcast(HINDCAST), MetoceanOptions(sectors=1))
omni = result.hs["omni"]
for rp, v, lo, hi in zip(omni.return_periods, omni.value, omni.lower, omni.upper, strict=True):
    print(f"{rp:>5g}-year H_s = {v:.2f} m (95 % interval {lo:.2f}–{hi:.2f} m)")
climate = StormClimate.from_result(result)
print(
    f"storms: {climate.rate:.2f} a year above {climate.threshold:.2f} m, GPD sigma ="
    f" {climate.gpd_scale:.3f} m, xi = {climate.gpd_shape:.3f}"
)

pipe = PipeBuildUp(
    steel_outer_diameter=0.2191,  # m
    wall_thickness=0.0127,  # m
    layers=(
        Layer(name="corrosion", thickness=0.0055, density=1335.0),
        Layer(name="concrete", thickness=0.12, density=3043.5),
    ),
    contents=Contents.uniform(180.0),  # kg/m³, dense-phase gas
).pipe("operation")


def check(hs: float, tp: float, mu: float):
    """The F109 absolute lateral stability check of one sea state."""
    sand = Sand(submerged_unit_weight=10.0e3, friction_coefficient=mu, d50=0.25e-3)
    return absolute_lateral_stability(
        pipe,
        sand,
        hs=hs,
        tp=tp,
        depth=DEPTH,
        current_velocity=CURRENT,
        current_reference_height=3.0,
    )


def limit_state(x: np.ndarray) -> np.ndarray:
    """g = 1 − unfactored lateral utilisation, per row (u_hs, u_tp, friction coefficient)."""
    ss = climate.sea_state(x[:, :2])
    out = np.empty(len(x))
    for i, (hs, tp, mu) in enumerate(zip(ss["hs"], ss["tp"], x[:, 2], strict=True)):
        r = check(float(hs), float(tp), float(mu))
        out[i] = 1.0 - r.utilisation_lateral / r.gamma_sc
    return out


# sampled storms reach K* beyond the F109 tables (140) and κ_s beyond Verley & Sotberg's range:
# the check extrapolates there, as the warnings would say once per sample
warnings.simplefilter("ignore", OutOfRangeWarning)
inputs = [
    *climate.parameters(),
    UncertainParameter("friction_coefficient", "normal", {"mean": 0.6, "std": 0.06}),
]
form = estimate_failure_probability(limit_state, inputs, method="form")
u_star = np.array([[form.design_point["u_hs"], form.design_point["u_tp"]]])
dp = climate.sea_state(u_star)
print(
    f"FORM: p per storm = {form.probability:.3g} (beta = {form.reliability_index:.2f}),"
    f" design storm H_s = {dp['hs'][0]:.2f} m, T_p = {dp['tp'][0]:.2f} s,"
    f" mu = {form.design_point['friction_coefficient']:.3f}"
)
print("importance factors:", {k: round(v, 3) for k, v in form.importance.items()})
imp = estimate_failure_probability(limit_state, inputs, method="importance", target_cv=0.1)
annual = climate.annual_probability(imp.probability)
print(
    f"importance sampling: p per storm = {imp.probability:.3g} (CV {imp.cv:.3f},"
    f" {imp.evaluations} checks, 95 % interval [{imp.low:.3g}, {imp.high:.3g}]);"
    f" annual = {annual:.3g}; 50 years ="
    f" {lifetime_probability(annual, 50.0):.3g}"
)

hs100 = float(omni.value[list(omni.return_periods).index(100.0)])
tp100 = float(result.joint.tp_quantile(hs100, 0.5))
r100 = check(hs100, tp100, 0.6)
print(
    f"F109 return-period check (100-year H_s {hs100:.2f} m, T_p {tp100:.2f} s, gamma_SC"
    f" {r100.gamma_sc:.2f}): utilisation {r100.utilisation:.3f}"
    f" ({'passes' if r100.passes else 'fails'})"
)

fig = plot_contours(result, title="synthetic hindcast: IFORM contours and the FORM design storm")
fig.axes[0].plot(dp["tp"], dp["hs"], "r*", ms=14, label="FORM design storm (absolute check)")
fig.axes[0].legend(fontsize=8, loc="upper left")
fig.savefig("ex10_contours.png", dpi=100)
print("wrote ex10_contours.png")
