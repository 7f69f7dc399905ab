"""Write examples/hindcast_synthetic.csv: 25 years of 3-hourly sea states and current drawn
from known distributions (onbottom.metocean.synthetic.EXAMPLE_MODEL, seed 2026).

    python3 tools/make_synthetic_hindcast.py [OUT.csv]

H_s: 3-parameter Weibull (α = 1.0 m, β = 1.35, γ = 0.25 m) through a Gaussian AR(1) score of
24 h correlation time; T_p|H_s log-normal in the DNV-RP-C205 §3.6.3 form; directions by
weather regimes (storms mostly from W–NW); current: M2 tide plus a wind-driven part. See
docs/theory/metocean.md for the model and what the example's known answers are.
"""

from __future__ import annotations

import sys
from pathlib import Path

from onbottom.metocean.hindcast import write_hindcast_csv
from onbottom.metocean.synthetic import EXAMPLE_MODEL, synthetic_hindcast

SEED = 2026
YEARS = 25.0
STEP_HOURS = 3.0


def main(out: str = "examples/hindcast_synthetic.csv") -> Path:
    """Draw the series and write it; returns the path."""
    m = EXAMPLE_MODEL
    data = synthetic_hindcast(m, years=YEARS, step_hours=STEP_HOURS, seed=SEED)
    comments = (
        "Synthetic hindcast (NOT measured data) for onbottom's metocean example:"
        " tools/make_synthetic_hindcast.py",
        f"{YEARS:g} years, {STEP_HOURS:g}-hourly, seed {SEED}; H_s Weibull(alpha={m.hs_scale},"
        f" beta={m.hs_shape}, gamma={m.hs_location}) via a Gaussian AR(1) score"
        f" (tau={m.tau_hours:g} h)",
        f"ln T_p | H_s ~ N(a0 + a1 H^a2, b0 + b1 exp(b2 H)), a=({m.tp_a0}, {m.tp_a1},"
        f" {m.tp_a2}), b=({m.tp_b0}, {m.tp_b1}, {m.tp_b2}) (DNV-RP-C205 3.6.3 form)",
        "wave_direction_deg: coming from; current_direction_deg: going to (clockwise from N)",
    )
    return write_hindcast_csv(out, data, comments=comments)


if __name__ == "__main__":
    print(main(*sys.argv[1:]))
