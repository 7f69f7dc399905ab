"""A storm climate of known parameters shared by the reliability tests (the DNV-RP-C205
H_s–T_p form of ``metocean.joint`` with round numbers; four direction sectors)."""

from __future__ import annotations

from onbottom.metocean.joint import JointModel
from onbottom.reliability.climate import StormClimate

JOINT = JointModel(
    hs_scale=1.0,
    hs_shape=1.35,
    hs_location=0.25,
    mu=(0.8, 1.27, 0.131),
    sigma=(0.1334, 0.0264, -0.1906),
)
CLIMATE = StormClimate(
    rate=3.0,
    threshold=4.0,
    gpd_scale=0.7,
    gpd_shape=-0.1,
    joint=JOINT,
    sectors=("N", "E", "S", "W"),
    sector_frequencies=(0.1, 0.2, 0.3, 0.4),
    sector_centres_deg=(0.0, 90.0, 180.0, 270.0),
)
