"""Physical constants used across onbottom (SI units)."""

from __future__ import annotations

GRAVITY: float = 9.80665
"""Standard gravitational acceleration g [m/s²]."""

RHO_SEAWATER: float = 1025.0
"""Seawater density ρ_w [kg/m³] (DNV-RP-F109 typical value)."""

RHO_STEEL: float = 7850.0
"""Carbon-steel density [kg/m³]."""

KINEMATIC_VISCOSITY_SEAWATER: float = 1.19e-6
"""Kinematic viscosity of seawater at about 15 °C ν [m²/s]."""
