"""Validation: the public DNV-RP-F109 design-sheet case (docs/validation/f109_design_sheet.md).

219.1 × 12.7 mm steel (7850 kg/m³), 5.5 mm corrosion coat (1335 kg/m³), 82.55 mm concrete
(3043.5 kg/m³), contents and sea water 1025 kg/m³; depth 13 m; H_s 4.68 m, T_p 10.8 s.

Tolerances, fixed from what each sheet value is:

* D, φ, γ, T_n, s_g are closed-form; the sheet prints them rounded to 4 significant figures:
  agreement to half a unit of the last printed digit (D: the sheet's 0.3951 is 0.3952
  truncated, 1.5e-4 m).
* U_s and T_u on the sheet are readings of F109's Figs 3-2/3-3 (U_s T_n/H_s ≈ 0.360 and
  T_u/T_p ≈ 0.850 at T_n/T_p = 0.107). Our direct integration, verified against the scalar
  integration in tests/unit/test_design_sea_state.py, gives 0.379 and 0.870: 5.3 % and 2.4 %
  above the sheet. No input of the integral explains this (a larger γ raises both further);
  it is taken to be the figure reading. The test guards the documented difference: ours above
  the sheet by less than 7 % (U_s) and 4 % (T_u) — a regression guard on a known
  discrepancy, not a claim of agreement.
"""

from __future__ import annotations

import math

import pytest

from onbottom.hydro.design_sea_state import design_oscillation
from onbottom.inputs import Layer
from onbottom.inputs.pipe_buildup import Contents, PipeBuildUp

pytestmark = pytest.mark.validation

BUILDUP = PipeBuildUp(
    steel_outer_diameter=0.2191,
    wall_thickness=0.0127,
    steel_density=7850.0,
    layers=(
        Layer(name="corrosion", thickness=0.0055, density=1335.0),
        Layer(name="concrete", thickness=0.08255, density=3043.5),
    ),
    contents=Contents.uniform(1025.0),
    seawater_density=1025.0,
)


def test_section_properties():
    p = BUILDUP.properties("operation")
    assert p.outer_diameter == pytest.approx(0.3951, abs=1.5e-4)
    assert p.specific_gravity == pytest.approx(2.7585, abs=5e-4)


def test_sea_state_closed_forms():
    o = design_oscillation(4.68, 10.8, 13.0, BUILDUP.outer_diameter, current_velocity=0.91)
    assert o.phi == pytest.approx(4.992, abs=5e-4)
    assert o.gamma == pytest.approx(1.009, abs=5e-4)
    assert o.tn == pytest.approx(1.151, abs=5e-4)
    assert o.tn == pytest.approx(math.sqrt(13.0 / 9.80665))


def test_bed_velocity_against_figure_readings():
    o = design_oscillation(4.68, 10.8, 13.0, BUILDUP.outer_diameter)
    du = float(o.us) / 1.463 - 1.0
    dt = float(o.tu) / 9.18 - 1.0
    assert 0.0 < du < 0.07
    assert 0.0 < dt < 0.04
