"""Verley & Sotberg energy-based sand model, its calcareous calibration and the F109 variant.

Sources
-------
* Verley, R. & Sotberg, T. (1994) "A soil resistance model for pipelines placed on sandy
  soils", J. Offshore Mech. Arct. Eng. 116(3):145–153 (first OMAE 1992). Eqs 1–10 below.
* Youssef, B.S. & Cassidy, M.J. (2014) "Calibration of Verley and Sotberg soil resistance model
  for pipelines placed on calcareous soils", ISOPE 2014, pp. 141–148: factors A, B, C
  (Eqs 11–15, Table 3) and region limits 0.01D / 0.25D / 0.75D (Fig. 10).
* DNV-RP-F109 (2010) §3.4.6: the same peak passive law with the switch at κ_s = 26.7 and
  F_R = γ'D²(z/D)^1.25 above it.

Symbols (SI): D outer diameter [m]; γ' submerged unit weight of the soil [N/m³]; V = W_s − F_L
vertical contact load [N/m]; W installation (largest virgin) vertical load [N/m]; K_s = γ'D²/V
[-]; z penetration of the invert [m]; E accumulated work per unit length [N]; s_max largest
|y − y0| reached in the current trough [m].

Equations 6 and 8 are *reconstructions* (the published arrangement could not be recovered from
the available text); they are the defaults and can be swapped by name. The behaviour at
region changes, the new-trough rule and the work integrand are interpretations. All of it is
listed in ``docs/theory/verley_sotberg.md``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from onbottom._validate import finite, in_range, one_of, positive, warn_outside
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil import _verley_sotberg_kernel as _k
from onbottom.soil._dispatch import MODEL_VERLEY_SOTBERG
from onbottom.soil._trough import RULE_ELASTOPLASTIC, RULE_LEGACY_ELASTIC
from onbottom.soil.base import S_REGION, S_Z, LateralResistanceModel

__all__ = [
    "B_PLACEMENTS",
    "KS_CALIBRATION_RANGE",
    "MAX_PENETRATION_BASES",
    "PASSIVE_LAWS",
    "PASSIVE_RULES",
    "PENETRATION_LAWS",
    "WORK_COUNTINGS",
    "WORK_INTEGRANDS",
    "WORK_LAWS",
    "VerleySotberg",
    "initial_penetration",
    "max_cyclic_penetration",
    "peak_passive_resistance",
    "residual_penetration_ratio",
    "stiffness_parameter",
    "work_penetration",
]

PASSIVE_LAWS: dict[str, int] = {
    "verley_sotberg": _k.PASSIVE_VERLEY_SOTBERG,
    "dnv_f109": _k.PASSIVE_DNV_F109,
}
"""Peak passive laws: V&S Eqs 3–4 (switch at K_s = 20) or DNV-RP-F109 §3.4.6 (26.7)."""

WORK_LAWS: dict[str, int] = {
    "reconstruction": _k.WORK_LAW_RECONSTRUCTION,
    "none": _k.WORK_LAW_NONE,
}
"""Penetration-from-work laws (Eq 6): our reconstruction, or none (z stays z_i)."""

PENETRATION_LAWS: dict[str, int] = {
    "reconstruction": _k.ZMAX_LAW_RECONSTRUCTION,
    "reconstruction_no_half": _k.ZMAX_LAW_NO_HALF,
}
"""Maximum cyclic penetration laws (Eq 8): with the factor 0.5, or the reading without it."""

WORK_COUNTINGS: dict[str, int] = {
    "load_reversal": _k.COUNT_LOAD_REVERSAL,
    "load_reversal_drift": _k.COUNT_LOAD_REVERSAL_DRIFT,
    "load_reversal_swept": _k.COUNT_LOAD_REVERSAL_SWEPT,
    "load_reversal_side": _k.COUNT_LOAD_REVERSAL_SIDE,
    "any_region2": _k.COUNT_ANY_REGION2,
    "swept_ground": _k.COUNT_SWEPT_GROUND,
    "two_sided": _k.COUNT_TWO_SIDED,
}
"""Which region-2 displacement increments add to the work E of Eq 6 [I]
(``docs/theory/verley_sotberg.md``, "Which increments count"); s = y − y0 about the trough:

* ``"load_reversal"`` (default): only in a trough where the load has reversed: the soil
  reaction R = F_f + F_r, which equilibrates the applied load while the pipe is at rest,
  changed sign beyond ±θ·μV (θ = ``reversal_fraction``, hysteresis). A one-way push never
  opens the gate.
* ``"load_reversal_drift"``: the gate, and once the pipe has turned in region 2, only ground
  within the amplitude of its turning points plus the longest half-cycle (swing between two
  turning points) it has made in the trough; a monotonic advance beyond that is taken as
  drift and does not count. It also cuts cyclic motion whose amplitude grows fast (a wave
  ramp): kept by name, not the default.
* ``"load_reversal_swept"``: the gate with the strict drift rule (no swing allowance).
* ``"load_reversal_side"``: the gate; once the pipe has turned in region 2, ground beyond its
  turning amplitude counts only on a swing that comes from the other side of the trough
  centre (a pipe that turns back and goes on, on the same side, is walking: drift).
* ``"any_region2"``: every region-2 increment (the first reading: a one-way push digs in).
* ``"swept_ground"``: only |s| within the largest turning-point excursion (bound, no gate).
* ``"two_sided"``: only |s| within the smaller of the two sides' turning excursions (bound).
"""

WORK_INTEGRANDS: dict[str, int] = {
    "total": _k.INTEGRAND_TOTAL,
    "passive": _k.INTEGRAND_PASSIVE,
}
"""Work integrand in region 2: total resistance F_h, or passive resistance F_r only."""

PASSIVE_RULES: dict[str, int] = {
    "elastoplastic": RULE_ELASTOPLASTIC,
    "legacy_elastic": RULE_LEGACY_ELASTIC,
}
"""How the passive force follows the envelope [I] (``docs/theory/verley_sotberg.md``):

* ``"elastoplastic"`` (default): push-only elastic–plastic. The envelope is a yield limit; the
  force changes by k_u·Δu inside it (k_u = F_r1/y1, the region-1 slope, so region 1 stays
  elastic as the papers say), follows the envelope when pushed onto it, unloads along k_u and
  never pulls (0 <= F_r <= F_env on the side s > 0, the mirror image for s < 0). Dissipative:
  no closed displacement path creates energy.
* ``"legacy_elastic"``: nonlinear-elastic restoring force sign(s)·F_env(|s|) at the current
  penetration (the rule of onbottom ≤ 0.1). Because F_env grows with z while the pipe is away
  from the trough centre, it returns more energy than it stored (negative net work on closed
  cycles): kept only as a named variant for comparison.
"""

B_PLACEMENTS: dict[str, int] = {
    "outside": _k.B_OUTSIDE,
    "inside": _k.B_INSIDE,
}

MAX_PENETRATION_BASES: dict[str, int] = {
    "as_laid": _k.ZMAX_BASE_AS_LAID,
    "trough": _k.ZMAX_BASE_TROUGH,
}
"""Which z_i the cap of Eq 8 (z2max/D = z_i/D + 0.5·[s/(K_s D)]^0.5) is measured from [I]:
``"as_laid"`` (default) the initial penetration of Eq 7 on virgin soil — the z_i the paper
defines (Youssef & Cassidy 2014 restate Eq 8 with the z_i of Eq 7), so cyclic motion of
amplitude s can never bury the pipe deeper than z_i + 0.5D·[s/(K_s D)]^0.5 however often it
breaks out and starts a new trough; ``"trough"`` the z_i of the current trough (z3 after a
breakout): the earlier rule, under which sustained sliding with reversals ratcheted z up by
the whole cap at every new trough (docs/theory/verley_sotberg.md, "Penetration under
sustained sliding")."""
"""Where the factor B of Youssef & Cassidy (2014) Eqs 13–14 stands [R]: ``"outside"`` the
bracket (z/D = z_i/D + B·0.23·[E/(γ'D³)]^0.5·[K_s s/D]^−0.31, default) or ``"inside"`` it
(0.23·[B·E/(γ'D³)]^0.5, 0.5·[B·s/(K_s D)]^0.5, i.e. an effective factor B^0.5)."""

KS_CALIBRATION_RANGE: tuple[float, float] = (0.1, 30.0)
"""Assumed range of K_s = γ'D²/V covered by the V&S data (PIPESTAB, AGA, DHI tests).

The exact range could not be checked against the 1994 paper; these bounds are an order-of-
magnitude envelope (open item in ``docs/theory/verley_sotberg.md``)."""

Z_OVER_D_RANGE: tuple[float, float] = (0.0, 0.5)
"""z/D range over which the power laws in z/D are used here (pipe at most half buried)."""

MAX_UNIT_WEIGHT = 2.0e6
"""Upper bound of γ' [N/m³]: 100 × a dense soil, so model-scale centrifuge inputs (γ'·N) pass."""

_SILICA_LIMITS = (0.02, 0.5, 1.0)
_CALCAREOUS_LIMITS = (0.01, 0.25, 0.75)


# ---- pure functions (SI) -------------------------------------------------------------------
def stiffness_parameter(
    submerged_unit_weight: float, diameter: float, vertical_load: float
) -> float:
    """Soil stiffness parameter K_s = γ'·D²/V (V&S Eq 5; DNV-RP-F109 κ_s).

    Parameters
    ----------
    submerged_unit_weight : float
        γ' [N/m³], > 0.
    diameter : float
        D [m], > 0.
    vertical_load : float
        V [N/m], > 0.

    Returns
    -------
    float
        K_s [-].
    """
    g = positive("submerged_unit_weight", submerged_unit_weight)
    d = positive("diameter", diameter)
    v = positive("vertical_load", vertical_load)
    return g * d * d / v


def initial_penetration(
    submerged_unit_weight: float, diameter: float, installation_load: float, C: float = 1.0
) -> float:
    """Initial penetration z_i [m] (V&S Eq 7; Youssef & Cassidy Eq 15 with C; F109 §3.4.6).

    z_i/D = C·0.037·(γ'D²/W)^(−0.67), W the largest vertical load carried on virgin soil.

    Parameters
    ----------
    submerged_unit_weight : float
        γ' [N/m³].
    diameter : float
        D [m].
    installation_load : float
        W [N/m] (pipe submerged weight × lay factor in design; V_peak in the centrifuge tests).
    C : float
        Calibration factor [-] (1 for silica, 0.98 calcareous, Youssef & Cassidy Table 3).
    """
    ks = stiffness_parameter(submerged_unit_weight, diameter, installation_load)
    positive("C", C)
    warn_outside("K_s", ks, *KS_CALIBRATION_RANGE, "Verley & Sotberg (1994) Eq 7")
    return diameter * C * 0.037 * ks ** (-0.67)


def peak_passive_resistance(
    submerged_unit_weight: float,
    diameter: float,
    vertical_load: float,
    penetration: float,
    A: float = 1.0,
    law: str = "verley_sotberg",
) -> float:
    """Passive resistance F_r [N/m] at penetration z (V&S Eqs 3–4; Y&C Eqs 11–12; F109).

    ``law="verley_sotberg"``: F_r = A·γ'D²(5.0 − 0.15K_s)(z/D)^1.25 for K_s ≤ 20, else
    A·2γ'D²(z/D)^1.25. ``law="dnv_f109"`` (DNV-RP-F109 §3.4.6): the quadratic up to
    κ_s = 26.7, then A·γ'D²(z/D)^1.25. With z = z2 this is F_r2, with z = z3 F_r3; F_r1 = 0.3F_r2.
    V <= 0 (lift-off) gives 0.

    Parameters
    ----------
    submerged_unit_weight, diameter : float
        γ' [N/m³], D [m].
    vertical_load : float
        V [N/m] (any sign).
    penetration : float
        z [m], >= 0.
    A : float
        Factor A [-] (1 silica, 0.25 calcareous).
    law : str
        See :data:`PASSIVE_LAWS`.
    """
    g = positive("submerged_unit_weight", submerged_unit_weight)
    d = positive("diameter", diameter)
    v = finite("vertical_load", vertical_load)
    z = in_range("penetration", penetration, 0.0, math.inf)
    positive("A", A)
    one_of("law", law, PASSIVE_LAWS)
    if v <= 0.0 or z == 0.0:
        return 0.0
    warn_outside("K_s", g * d * d / v, *KS_CALIBRATION_RANGE, "Verley & Sotberg (1994) Eqs 3-4")
    warn_outside("z/D", z / d, *Z_OVER_D_RANGE, "Verley & Sotberg (1994) Eqs 3-4")
    p = np.zeros(_k.N_PARAMS)
    p[_k.P_D], p[_k.P_GAMMA], p[_k.P_A] = d, g, A
    p[_k.P_PASSIVE_LAW] = PASSIVE_LAWS[law]
    return float(_k.peak_passive_py(p, z, v))


def residual_penetration_ratio(z2_over_d: float) -> float:
    """z3/z2 after breakout (V&S Eqs 9–10): 0.82 − 3.2·z2/D for z2/D ≤ 0.1, else 0.5."""
    x = in_range("z2_over_d", z2_over_d, 0.0, math.inf)
    warn_outside("z2/D", x, *Z_OVER_D_RANGE, "Verley & Sotberg (1994) Eqs 9-10")
    return float(_k.residual_ratio.py_func(x))


def work_penetration(
    initial_penetration: float,
    work: float,
    submerged_unit_weight: float,
    diameter: float,
    vertical_load: float,
    amplitude: float,
    B: float = 1.0,
    b_placement: str = "outside",
) -> float:
    """Penetration from accumulated work [m] (V&S Eq 6 / Y&C Eq 13, **reconstruction**).

    z/D = z_i/D + B·0.23·[E/(γ'D³)]^0.5·[K_s·s_max/D]^(−0.31).

    Parameters
    ----------
    initial_penetration : float
        z_i [m].
    work : float
        E [N] (N·m/m), >= 0.
    submerged_unit_weight, diameter, vertical_load : float
        γ' [N/m³], D [m], V [N/m] (> 0).
    amplitude : float
        s_max [m], > 0.
    B : float
        Factor B [-] (1 silica, 0.35 calcareous).
    b_placement : str
        "outside" (B·0.23·[...]^0.5) or "inside" (0.23·[B·...]^0.5), :data:`B_PLACEMENTS`.
    """
    ks = stiffness_parameter(submerged_unit_weight, diameter, vertical_load)
    e = in_range("work", work, 0.0, math.inf)
    s = positive("amplitude", amplitude)
    one_of("b_placement", b_placement, B_PLACEMENTS)
    if b_placement == "inside":
        B = B**0.5
    d = diameter
    return initial_penetration + B * 0.23 * d * (e / (submerged_unit_weight * d**3)) ** 0.5 * (
        ks * s / d
    ) ** (-0.31)


def max_cyclic_penetration(
    initial_penetration: float,
    submerged_unit_weight: float,
    diameter: float,
    vertical_load: float,
    amplitude: float,
    B: float = 1.0,
    law: str = "reconstruction",
    b_placement: str = "outside",
) -> float:
    """Largest penetration from cyclic motion of amplitude s_max [m] (V&S Eq 8 / Y&C Eq 14).

    **Reconstruction**: z2max/D = z_i/D + B·0.5·[s_max/(K_s·D)]^0.5 (``law="reconstruction"``);
    ``law="reconstruction_no_half"`` drops the factor 0.5. ``b_placement="inside"`` puts B
    inside the bracket (0.5·[B·s_max/(K_s·D)]^0.5).
    """
    ks = stiffness_parameter(submerged_unit_weight, diameter, vertical_load)
    s = positive("amplitude", amplitude)
    one_of("law", law, PENETRATION_LAWS)
    one_of("b_placement", b_placement, B_PLACEMENTS)
    if b_placement == "inside":
        B = B**0.5
    half = 0.5 if law == "reconstruction" else 1.0
    return initial_penetration + B * half * diameter * (s / (ks * diameter)) ** 0.5


# ---- model class ---------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class VerleySotberg(LateralResistanceModel):
    """Verley & Sotberg (1994) lateral resistance on sand: Coulomb friction + passive berm.

    R = F_f + F_r (Eq 1). F_f = μV by elastic–plastic return mapping (mobilised over
    ``mobilisation_displacement``). F_r is a restoring force about the centre y0 of the pipe's
    current trough, piecewise linear through (0, 0), (y1, F_r1), (y2, F_r2), (y3, F_r3) and
    constant beyond y3; F_r2 from Eqs 3–4 at the current penetration (frozen at z2 once y2 is
    passed), F_r1 = 0.3F_r2, F_r3 from Eqs 3–4 at z3 (Eqs 9–10). Penetration starts at z_i
    (Eq 7), grows with the work done in region 2 (Eq 6, capped by Eq 8), falls linearly from z2
    to z3 across region 3. After y3 a new trough starts where the pipe next reverses.

    Use :meth:`silica` or :meth:`calcareous` for the published parameter sets.

    Parameters
    ----------
    outer_diameter : float
        D [m], > 0.
    submerged_unit_weight : float
        γ' [N/m³], in (0, 2·10⁶] (model-scale centrifuge values γ'·N are allowed).
    friction_coefficient : float
        μ [-], in (0, 2].
    installation_load : float
        W [N/m], > 0: largest vertical load carried on virgin soil (Eq 7).
    A, B, C : float
        Calibration factors [-], in (0, 10]: A on F_r (Eqs 11–12), B on the penetration
        growth (Eqs 13–14), C on z_i (Eq 15). 1 for silica.
    region_limits_over_d : tuple of 3 floats
        y1/D, y2/D, y3/D [-], 0 < y1 < y2 < y3. Silica (0.02, 0.5, 1.0), calcareous
        (0.01, 0.25, 0.75).
    passive_law : str
        "verley_sotberg" (Eqs 3–4) or "dnv_f109" (DNV-RP-F109 §3.4.6).
    work_law : str
        "reconstruction" (Eq 6 as reconstructed) or "none" (no growth from work).
    max_penetration_law : str
        "reconstruction" (Eq 8 with 0.5) or "reconstruction_no_half".
    work_integrand : str
        "total" (E += |F_h Δy|) or "passive" (E += |F_r Δy|).
    mobilisation_displacement : float or None
        Friction mobilisation displacement δ [m], > 0 and < y1; None → 0.001·D.
    passive_rule : str
        "elastoplastic" (default, push-only elastic–plastic, dissipative) or
        "legacy_elastic" (restoring force on the envelope); see :data:`PASSIVE_RULES`.
    b_placement : str
        "outside" (default) or "inside" the bracket of Eqs 13–14; see :data:`B_PLACEMENTS`.
    max_penetration_base : str
        "as_laid" (default: Eq 8's cap about the z_i of Eq 7) or "trough" (about the current
        trough's z_i); see :data:`MAX_PENETRATION_BASES`.
    work_counting : str
        Which region-2 increments add to E: "load_reversal" (default),
        "load_reversal_drift", "load_reversal_swept", "load_reversal_side", "any_region2",
        "swept_ground" or "two_sided"; see :data:`WORK_COUNTINGS`.
    reversal_fraction : float
        θ [-], in (0, 1]: the load counts as reversed when the soil reaction R changes sign
        beyond ±θ·μV (hysteresis band of the load direction; default 0.5).
    variant : str
        Label stored in results ("silica", "calcareous", "f109", "custom").
    """

    name: ClassVar[str] = "verley_sotberg"
    reference: ClassVar[str] = (
        "Verley & Sotberg (1994) J. Offshore Mech. Arct. Eng. 116(3):145-153; "
        "Youssef & Cassidy (2014) ISOPE pp. 141-148; DNV-RP-F109 (2010) sec. 3.4.6"
    )
    state_size: ClassVar[int] = _k.N_STATE
    model_id: ClassVar[int] = MODEL_VERLEY_SOTBERG

    outer_diameter: float
    submerged_unit_weight: float
    friction_coefficient: float
    installation_load: float
    A: float = 1.0
    B: float = 1.0
    C: float = 1.0
    region_limits_over_d: tuple[float, float, float] = field(default=_SILICA_LIMITS)
    passive_law: str = "verley_sotberg"
    work_law: str = "reconstruction"
    max_penetration_law: str = "reconstruction"
    work_integrand: str = "total"
    mobilisation_displacement: float | None = None
    passive_rule: str = "elastoplastic"
    b_placement: str = "outside"
    max_penetration_base: str = "as_laid"
    work_counting: str = "load_reversal"
    reversal_fraction: float = 0.5
    variant: str = "custom"

    def __post_init__(self) -> None:
        cls = "VerleySotberg"
        positive(f"{cls}.outer_diameter", self.outer_diameter)
        in_range(
            f"{cls}.submerged_unit_weight",
            self.submerged_unit_weight,
            0.0,
            MAX_UNIT_WEIGHT,
            low_inclusive=False,
        )
        in_range(
            f"{cls}.friction_coefficient",
            self.friction_coefficient,
            0.0,
            2.0,
            low_inclusive=False,
        )
        positive(f"{cls}.installation_load", self.installation_load)
        for nm in ("A", "B", "C"):
            in_range(f"{cls}.{nm}", getattr(self, nm), 0.0, 10.0, low_inclusive=False)
        lim = tuple(self.region_limits_over_d)
        if len(lim) != 3:
            raise InputError(
                f"{cls}.region_limits_over_d = {self.region_limits_over_d!r} is invalid:"
                " expected three values y1/D < y2/D < y3/D"
            )
        for i, x in enumerate(lim):
            positive(f"{cls}.region_limits_over_d[{i}]", x)
        if not (lim[0] < lim[1] < lim[2]):
            raise InputError(
                f"{cls}.region_limits_over_d = {lim!r} is invalid: must satisfy"
                " 0 < y1/D < y2/D < y3/D"
            )
        object.__setattr__(self, "region_limits_over_d", tuple(float(x) for x in lim))
        one_of(f"{cls}.passive_law", self.passive_law, PASSIVE_LAWS)
        one_of(f"{cls}.work_law", self.work_law, WORK_LAWS)
        one_of(f"{cls}.max_penetration_law", self.max_penetration_law, PENETRATION_LAWS)
        one_of(f"{cls}.work_integrand", self.work_integrand, WORK_INTEGRANDS)
        one_of(f"{cls}.passive_rule", self.passive_rule, PASSIVE_RULES)
        one_of(f"{cls}.b_placement", self.b_placement, B_PLACEMENTS)
        one_of(f"{cls}.max_penetration_base", self.max_penetration_base, MAX_PENETRATION_BASES)
        one_of(f"{cls}.work_counting", self.work_counting, WORK_COUNTINGS)
        in_range(f"{cls}.reversal_fraction", self.reversal_fraction, 0.0, 1.0, low_inclusive=False)
        if self.mobilisation_displacement is not None:
            in_range(
                f"{cls}.mobilisation_displacement",
                self.mobilisation_displacement,
                0.0,
                self.y1,
                low_inclusive=False,
                high_inclusive=False,
            )
        warn_outside(
            "K_s (installation)",
            self.submerged_unit_weight * self.outer_diameter**2 / self.installation_load,
            *KS_CALIBRATION_RANGE,
            "Verley & Sotberg (1994) Eq 7",
            stacklevel=4,
        )

    # ---- constructors ------------------------------------------------------------------
    @classmethod
    def silica(
        cls, pipe: Pipe, sand: Sand, *, installation_load: float | None = None, **options: Any
    ) -> VerleySotberg:
        """Original silica-sand model: regions 0.02D/0.5D/1.0D, A = B = C = 1.

        ``installation_load`` W [N/m] defaults to the pipe submerged weight. ``options``
        are further fields (``passive_law``, ``work_law``, ...).
        """
        options.setdefault("region_limits_over_d", _SILICA_LIMITS)
        options.setdefault("variant", "silica")
        return cls._from(pipe, sand, installation_load, options)

    @classmethod
    def calcareous(
        cls,
        pipe: Pipe,
        sand: Sand,
        *,
        A: float = 0.25,
        B: float = 0.35,
        C: float = 0.98,
        installation_load: float | None = None,
        **options: Any,
    ) -> VerleySotberg:
        """Youssef & Cassidy (2014) calcareous calibration: regions 0.01D/0.25D/0.75D (Fig. 10),
        A = 0.25, B = 0.35, C = 0.98 (Table 3)."""
        options.setdefault("region_limits_over_d", _CALCAREOUS_LIMITS)
        options.setdefault("variant", "calcareous")
        return cls._from(pipe, sand, installation_load, {"A": A, "B": B, "C": C, **options})

    @classmethod
    def f109(
        cls, pipe: Pipe, sand: Sand, *, installation_load: float | None = None, **options: Any
    ) -> VerleySotberg:
        """Silica model with the DNV-RP-F109 §3.4.6 peak passive law (switch at κ_s = 26.7)."""
        options.setdefault("passive_law", "dnv_f109")
        options.setdefault("variant", "f109")
        return cls.silica(pipe, sand, installation_load=installation_load, **options)

    @classmethod
    def _from(
        cls, pipe: Pipe, sand: Sand, installation_load: float | None, options: dict[str, Any]
    ) -> VerleySotberg:
        w = pipe.submerged_weight if installation_load is None else installation_load
        options.setdefault("friction_coefficient", sand.friction_coefficient)
        return cls(
            outer_diameter=pipe.outer_diameter,
            submerged_unit_weight=sand.submerged_unit_weight,
            installation_load=w,
            **options,
        )

    # ---- derived quantities ------------------------------------------------------------
    @property
    def y1(self) -> float:
        """End of the elastic region y1 [m]."""
        return self.region_limits_over_d[0] * self.outer_diameter

    @property
    def y2(self) -> float:
        """End of the accumulation region y2 [m]."""
        return self.region_limits_over_d[1] * self.outer_diameter

    @property
    def y3(self) -> float:
        """End of the breakout region y3 [m]."""
        return self.region_limits_over_d[2] * self.outer_diameter

    @property
    def delta(self) -> float:
        """Friction mobilisation displacement δ [m]."""
        if self.mobilisation_displacement is None:
            return 1.0e-3 * self.outer_diameter
        return float(self.mobilisation_displacement)

    @property
    def initial_penetration(self) -> float:
        """z_i [m] of the first trough (Eq 7/15 with W = ``installation_load``)."""
        # Eq 7 without re-checking the range: __post_init__ warned once already
        ks = self.submerged_unit_weight * self.outer_diameter**2 / self.installation_load
        return self.outer_diameter * self.C * 0.037 * ks ** (-0.67)

    def peak_passive(self, vertical_load: float, penetration: float) -> float:
        """F_r [N/m] from Eqs 3–4 (or F109) with this model's A and passive law."""
        return peak_passive_resistance(
            self.submerged_unit_weight,
            self.outer_diameter,
            vertical_load,
            penetration,
            self.A,
            self.passive_law,
        )

    def backbone_points(
        self, vertical_load: float, penetration: float | None = None
    ) -> dict[str, float]:
        """Region limits and forces of the backbone for breakout from a trough with z2.

        Parameters
        ----------
        vertical_load : float
            V [N/m], > 0.
        penetration : float or None
            z2 [m]; None → z_i (no accumulated penetration).

        Returns
        -------
        dict
            y1, y2, y3 [m]; z_i, z2, z3 [m]; F_r1, F_r2, F_r3 [N/m]; F_f = μV [N/m]; K_s [-].
        """
        v = positive("vertical_load", vertical_load)
        zi = self.initial_penetration
        z2 = zi if penetration is None else in_range("penetration", penetration, 0.0, math.inf)
        z3 = residual_penetration_ratio(z2 / self.outer_diameter) * z2
        fr2 = self.peak_passive(v, z2)
        return {
            "y1": self.y1,
            "y2": self.y2,
            "y3": self.y3,
            "K_s": stiffness_parameter(self.submerged_unit_weight, self.outer_diameter, v),
            "z_i": zi,
            "z2": z2,
            "z3": z3,
            "F_r1": 0.3 * fr2,
            "F_r2": fr2,
            "F_r3": self.peak_passive(v, z3),
            "F_f": self.friction_coefficient * v,
        }

    def check_validity(self, vertical_load: Any, penetration: Any) -> None:
        """Warn (OutOfRangeWarning) if a run left the calibration ranges of the correlations.

        The kernel cannot warn; call this after a simulation with its vertical loads and
        penetrations. Checks K_s = γ'D²/V for V > 0 against :data:`KS_CALIBRATION_RANGE` and
        z/D against :data:`Z_OVER_D_RANGE`.

        Parameters
        ----------
        vertical_load : array-like
            V [N/m] along the run (V <= 0, lift-off, is ignored).
        penetration : array-like
            z [m] along the run.
        """
        v = np.asarray(vertical_load, dtype=float).ravel()
        v = v[v > 0.0]
        g, d = self.submerged_unit_weight, self.outer_diameter
        if v.size:
            ks = g * d * d / v
            src = "Verley & Sotberg (1994) Eqs 3-8"
            warn_outside("K_s (min)", float(ks.min()), *KS_CALIBRATION_RANGE, src)
            warn_outside("K_s (max)", float(ks.max()), *KS_CALIBRATION_RANGE, src)
        z = np.asarray(penetration, dtype=float).ravel()
        if z.size:
            warn_outside(
                "z/D (max)", float(z.max()) / d, *Z_OVER_D_RANGE, "Verley & Sotberg (1994)"
            )

    # ---- kernel contract ---------------------------------------------------------------
    @property
    def kernel(self):
        return _k.verley_sotberg_kernel

    @property
    def python_kernel(self):
        return _k.verley_sotberg_kernel_py

    def packed_parameters(self) -> np.ndarray:
        p = np.zeros(_k.N_PARAMS)
        p[_k.P_MU] = self.friction_coefficient
        p[_k.P_DELTA] = self.delta
        p[_k.P_D] = self.outer_diameter
        p[_k.P_GAMMA] = self.submerged_unit_weight
        p[_k.P_A] = self.A
        p[_k.P_B] = self.B
        p[_k.P_Y1] = self.y1
        p[_k.P_Y2] = self.y2
        p[_k.P_Y3] = self.y3
        p[_k.P_PASSIVE_LAW] = PASSIVE_LAWS[self.passive_law]
        p[_k.P_WORK_LAW] = WORK_LAWS[self.work_law]
        p[_k.P_ZMAX_LAW] = PENETRATION_LAWS[self.max_penetration_law]
        p[_k.P_WORK_INTEGRAND] = WORK_INTEGRANDS[self.work_integrand]
        p[_k.P_ZI] = self.initial_penetration
        p[_k.P_PASSIVE_RULE] = PASSIVE_RULES[self.passive_rule]
        p[_k.P_B_PLACEMENT] = B_PLACEMENTS[self.b_placement]
        p[_k.P_ZMAX_BASE] = MAX_PENETRATION_BASES[self.max_penetration_base]
        p[_k.P_WORK_COUNTING] = WORK_COUNTINGS[self.work_counting]
        p[_k.P_REVERSAL] = self.reversal_fraction
        return p

    def initial_state(self) -> np.ndarray:
        """Pipe at rest at y = 0 in its installation trough: z = z_i, region 1."""
        s = np.zeros(self.state_size)
        zi = self.initial_penetration
        s[S_Z] = zi
        s[_k.S_ZI] = zi
        s[S_REGION] = 1.0
        s[_k.S_PHASE] = _k.PHASE_TROUGH
        return s

    def parameters(self) -> Mapping[str, Any]:
        return {
            "variant": self.variant,
            "outer_diameter": self.outer_diameter,
            "submerged_unit_weight": self.submerged_unit_weight,
            "friction_coefficient": self.friction_coefficient,
            "installation_load": self.installation_load,
            "A": self.A,
            "B": self.B,
            "C": self.C,
            "region_limits_over_d": list(self.region_limits_over_d),
            "passive_law": self.passive_law,
            "work_law": self.work_law,
            "max_penetration_law": self.max_penetration_law,
            "work_integrand": self.work_integrand,
            "mobilisation_displacement": self.delta,
            "passive_rule": self.passive_rule,
            "b_placement": self.b_placement,
            "max_penetration_base": self.max_penetration_base,
            "work_counting": self.work_counting,
            "reversal_fraction": self.reversal_fraction,
        }
