"""Published results of the penetration paper that a full-size DEM run is compared with.

Source: the penetration paper (centrifuge at 25 g and 2D DEM; "Penetration resistance
evolution characteristics and mesoscopic mechanism of submarine pipeline in sandy seabed"),
§4.2–4.3, Fig. 5, Fig. 8 and Conclusions (1)–(2). Values are read from
the text (the figures are not available as data), prototype scale (D = 0.5 m), and are
*approximate* ("about"). The resistances are the centrifuge curves the paper's DEM is validated
against; the paper says its DEM reproduces their trends "with discrepancies", not the values.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["PUBLISHED", "PublishedCase"]


@dataclass(frozen=True, slots=True)
class PublishedCase:
    """What the paper reports for one specimen.

    Attributes
    ----------
    name : str
        Preset name (``SM`` or ``SD``).
    resistance : dict of float → float
        Centrifuge resistance V [N/m, prototype] at embedment ratios w/D [-].
    heave_over_D : float
        Height of the surface heave beside the pipe / D at w = 0.5D (DEM, Fig. 8) [-].
    heave_extent_over_D : float
        Lateral range of the heave / D (DEM, Fig. 8; "about 2D", the same for both) [-].
    behaviour : str
        ``"hardening"`` or ``"periodic softening"`` of the V–w curve (Fig. 5, Conclusion 1).
    softening_stages : tuple of (float, float)
        Ranges of w/D in which the paper's DEM curve drops (§4.2); empty for hardening.
    """

    name: str
    resistance: dict[float, float]
    heave_over_D: float
    heave_extent_over_D: float
    behaviour: str
    softening_stages: tuple[tuple[float, float], ...] = field(default=())


PUBLISHED: dict[str, PublishedCase] = {
    "SM": PublishedCase(
        name="SM",
        resistance={0.05: 50e3, 0.4: 120e3, 0.5: 125e3},
        heave_over_D=0.15,
        heave_extent_over_D=2.0,
        behaviour="hardening",
    ),
    "SD": PublishedCase(
        name="SD",
        resistance={0.1: 75e3, 0.4: 106e3, 0.5: 150e3},
        heave_over_D=0.25,
        heave_extent_over_D=2.0,
        behaviour="periodic softening",
        softening_stages=((0.1, 0.2), (0.3, 0.4), (0.4, 0.5)),
    ),
}
"""The medium-dense (SM, D_r = 48 %) and dense (SD, D_r = 78 %) specimens."""
