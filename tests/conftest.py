"""Shared fixtures: reference pipes and soils from the papers."""

from __future__ import annotations

import pytest

from onbottom.inputs import Pipe, Sand


@pytest.fixture
def centrifuge_pipe() -> Pipe:
    """Youssef & Cassidy (2014) prototype pipe: D = 1.0 m, V_i = 10.52 kN/m (Inclined 1)."""
    return Pipe(outer_diameter=1.0, submerged_weight=10.52e3)


@pytest.fixture
def calcareous_sand() -> Sand:
    """Calcareous sand with γ' = 7.5 kN/m³ (the spec's worked-number value)."""
    return Sand(submerged_unit_weight=7.5e3, friction_coefficient=0.48, kind="calcareous")
