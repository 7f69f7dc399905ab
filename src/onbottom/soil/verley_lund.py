"""Verley & Lund (1995) clay model as given in DNV-RP-F109 (2010) §3.4.6.

Sources
-------
* Verley, R. & Lund, K.M. (1995) "A soil resistance model for pipelines placed on clay
  soils", OMAE 1995, Vol. V, pp. 225–232.
* DNV-RP-F109 (2010, also 2017/2021) §3.4.6: initial penetration and passive resistance on clay.
* DNVGL-RP-F114 (2017) Tables 4-4 and 4-5: best-estimate breakout and residual mobilisation
  displacements (used here for the shape of the passive envelope; an interpretation).
* Bai, Y. & Bai, Q., *Subsea Pipelines and Risers* (2005), p. 107: validity S·G^0.3 < 2.5.

Symbols (SI): D [m]; W installation (largest) vertical load [N/m]; s_u undrained shear strength
[Pa]; γ_s clay unit weight [N/m³] (total/dry, see below); S = W/(D·s_u) [-];
G_c = s_u/(D·γ_s) [-]; z penetration [m]; F_C = V vertical contact load [N/m];
κ_c = s_u·D/F_C [-].

Initial penetration (F109 §3.4.6)::

    z_i/D = 0.0071·X^3.2 + 0.062·X^0.7,   X = S·G_c^0.3  ("product", default)
                                         or X = S/G_c^0.3 ("quotient")

The two readings differ by up to ~25 % in z for G_c ≈ 0.6. The product form is used by Bai
(2005, p. 107, "S·G^0.3 < 2.5") and by an independent open-source implementation; the
quotient form is how one reading of the F109 text has it. The choice is explicit
(``penetration_form``) and recorded in the parameters.

Passive resistance (F109 §3.4.6)::

    F_R/F_C = 4.1·κ_c/G_c^0.39·(z/D)^1.31   ⇔   F_R = 4.1·s_u·D·G_c^−0.39·(z/D)^1.31

(the vertical load cancels; V <= 0 still gives zero resistance: lift-off).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from onbottom._validate import in_range, one_of, positive, warn_outside
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay
from onbottom.soil import _verley_lund_kernel as _k
from onbottom.soil._dispatch import MODEL_VERLEY_LUND
from onbottom.soil._trough import PHASE_TROUGH, RULE_ELASTOPLASTIC, RULE_LEGACY_ELASTIC
from onbottom.soil.base import S_REGION, S_Z, LateralResistanceModel

__all__ = [
    "PENETRATION_FORMS",
    "UNIT_WEIGHTS",
    "VerleyLund",
    "clay_initial_penetration",
    "clay_passive_resistance",
    "penetration_group",
]

PENETRATION_FORMS: tuple[str, ...] = ("product", "quotient")
"""Readings of the F109 clay penetration group: S·G_c^0.3 (default) or S/G_c^0.3."""

UNIT_WEIGHTS: tuple[str, ...] = ("total", "submerged")
"""Unit weight used in G_c: total (dry/bulk) γ_s as in F109 (default) or submerged γ'."""

_PASSIVE_RULES: dict[str, int] = {
    "elastoplastic": RULE_ELASTOPLASTIC,
    "legacy_elastic": RULE_LEGACY_ELASTIC,
}

GROUP_VALIDITY_MAX = 2.5
"""Upper validity limit of the penetration fit in S·G^0.3 (Bai 2005, p. 107)."""


def penetration_group(
    load: float,
    diameter: float,
    undrained_shear_strength: float,
    unit_weight: float,
    form: str = "product",
) -> float:
    """Penetration group X = S·G_c^0.3 ("product") or S/G_c^0.3 ("quotient") [-].

    S = W/(D·s_u), G_c = s_u/(D·γ_s) (DNV-RP-F109 §3.4.6).

    Parameters
    ----------
    load : float
        W [N/m], > 0.
    diameter : float
        D [m], > 0.
    undrained_shear_strength : float
        s_u [Pa], > 0.
    unit_weight : float
        γ_s [N/m³], > 0 (F109: the total/dry unit weight of the clay).
    form : str
        "product" or "quotient".
    """
    w = positive("load", load)
    d = positive("diameter", diameter)
    su = positive("undrained_shear_strength", undrained_shear_strength)
    g = positive("unit_weight", unit_weight)
    one_of("form", form, PENETRATION_FORMS)
    s = w / (d * su)
    gc = su / (d * g)
    return s * gc**0.3 if form == "product" else s / gc**0.3


def clay_initial_penetration(
    load: float,
    diameter: float,
    undrained_shear_strength: float,
    unit_weight: float,
    form: str = "product",
) -> float:
    """Initial penetration on clay z_i [m] (Verley & Lund 1995; DNV-RP-F109 §3.4.6).

    z_i/D = 0.0071·X^3.2 + 0.062·X^0.7 with X from :func:`penetration_group`. Warns
    (OutOfRangeWarning) for X > 2.5, where the fit over-predicts (Bai 2005, p. 107).
    """
    x = penetration_group(load, diameter, undrained_shear_strength, unit_weight, form)
    warn_outside(f"penetration group ({form})", x, 0.0, GROUP_VALIDITY_MAX, "Verley & Lund (1995)")
    return diameter * (0.0071 * x**3.2 + 0.062 * x**0.7)


def clay_passive_resistance(
    penetration: float, diameter: float, undrained_shear_strength: float, unit_weight: float
) -> float:
    """Passive resistance on clay F_R [N/m] (Verley & Lund 1995; DNV-RP-F109 §3.4.6).

    F_R = 4.1·s_u·D·G_c^−0.39·(z/D)^1.31, G_c = s_u/(D·γ_s).
    """
    z = in_range("penetration", penetration, 0.0, math.inf)
    d = positive("diameter", diameter)
    su = positive("undrained_shear_strength", undrained_shear_strength)
    g = positive("unit_weight", unit_weight)
    warn_outside("z/D", z / d, 0.0, 0.5, "Verley & Lund (1995) passive resistance")
    gc = su / (d * g)
    return 4.1 * su * d * gc ** (-0.39) * (z / d) ** 1.31


@dataclass(frozen=True, kw_only=True)
class VerleyLund(LateralResistanceModel):
    """Verley & Lund (1995) clay: Coulomb friction + passive resistance of the trough.

    R = μV (elastic–plastic return mapping) + F_r. F_r is a restoring force about the centre
    y0 of the current trough: it rises linearly to F_R(z_t) at the breakout displacement
    y_brk = (b0 + b1·z_t/D)·D (DNVGL-RP-F114 Table 4-4 best estimate: b0 = 0.02, b1 = 0.25),
    then falls linearly to F_R(z_res) at y_res (F114 Table 4-5 best estimate 1.5D) while z
    falls from z_t to z_res = ``residual_penetration_ratio``·z_i; beyond y_res it stays at
    F_R(z_res). When the pipe, beyond y_res, next reverses, a new trough starts there with
    z_t = z_res. The penetration does not grow with cyclic motion (the F109 summary of
    Verley & Lund gives no growth law); all of this is our interpretation.

    Parameters
    ----------
    outer_diameter : float
        D [m], > 0.
    undrained_shear_strength : float
        s_u [Pa], > 0 (mudline value).
    unit_weight : float
        γ_s [N/m³] used in G_c, in (0, 3·10⁶] (the total/dry unit weight for F109;
        model-scale centrifuge values γ_s·N are allowed).
    friction_coefficient : float
        μ [-], in (0, 2].
    installation_load : float
        W [N/m], > 0, in S = W/(D s_u).
    penetration_form : str
        "product" (S·G^0.3, default) or "quotient" (S/G^0.3).
    breakout_over_d : tuple of 2 floats
        (b0, b1) [-] of y_brk = (b0 + b1·z/D)·D, b0 > 0, b1 >= 0.
    residual_over_d : float
        y_res/D [-], larger than the breakout displacement of the first trough.
    residual_penetration_ratio : float
        z_res/z_i [-], in [0, 1].
    mobilisation_displacement : float or None
        Friction mobilisation δ [m], > 0; None → 0.001·D.
    passive_rule : str
        "elastoplastic" (default: push-only elastic–plastic passive force, unloading stiffness
        F_R/y_brk, dissipative) or "legacy_elastic" (nonlinear-elastic restoring force on the
        envelope, kept as a named variant; it can create energy on closed paths).
        See :data:`onbottom.soil.verley_sotberg.PASSIVE_RULES`.
    """

    name: ClassVar[str] = "verley_lund"
    reference: ClassVar[str] = (
        "Verley & Lund (1995) OMAE 1995 V:225-232; DNV-RP-F109 (2010) sec. 3.4.6; "
        "DNVGL-RP-F114 (2017) Tables 4-4, 4-5"
    )
    state_size: ClassVar[int] = _k.N_STATE
    model_id: ClassVar[int] = MODEL_VERLEY_LUND

    outer_diameter: float
    undrained_shear_strength: float
    unit_weight: float
    friction_coefficient: float
    installation_load: float
    penetration_form: str = "product"
    breakout_over_d: tuple[float, float] = (0.02, 0.25)
    residual_over_d: float = 1.5
    residual_penetration_ratio: float = 0.5
    mobilisation_displacement: float | None = None
    passive_rule: str = "elastoplastic"

    def __post_init__(self) -> None:
        cls = "VerleyLund"
        one_of(f"{cls}.passive_rule", self.passive_rule, _PASSIVE_RULES)
        positive(f"{cls}.outer_diameter", self.outer_diameter)
        positive(f"{cls}.undrained_shear_strength", self.undrained_shear_strength)
        in_range(f"{cls}.unit_weight", self.unit_weight, 0.0, 3.0e6, low_inclusive=False)
        in_range(
            f"{cls}.friction_coefficient",
            self.friction_coefficient,
            0.0,
            2.0,
            low_inclusive=False,
        )
        positive(f"{cls}.installation_load", self.installation_load)
        one_of(f"{cls}.penetration_form", self.penetration_form, PENETRATION_FORMS)
        b = tuple(self.breakout_over_d)
        if len(b) != 2:
            raise InputError(
                f"{cls}.breakout_over_d = {self.breakout_over_d!r} is invalid: expected (b0, b1)"
            )
        positive(f"{cls}.breakout_over_d[0]", b[0])
        in_range(f"{cls}.breakout_over_d[1]", b[1], 0.0, math.inf)
        object.__setattr__(self, "breakout_over_d", (float(b[0]), float(b[1])))
        in_range(f"{cls}.residual_penetration_ratio", self.residual_penetration_ratio, 0.0, 1.0)
        # validity of the penetration fit, warned once here (Bai 2005: S·G^0.3 < 2.5)
        x = penetration_group(
            self.installation_load,
            self.outer_diameter,
            self.undrained_shear_strength,
            self.unit_weight,
            self.penetration_form,
        )
        warn_outside(
            f"penetration group ({self.penetration_form})",
            x,
            0.0,
            GROUP_VALIDITY_MAX,
            "Verley & Lund (1995)",
            stacklevel=4,
        )
        zi = self.initial_penetration
        y_brk = (b[0] + b[1] * zi / self.outer_diameter) * self.outer_diameter
        in_range(
            f"{cls}.residual_over_d",
            self.residual_over_d,
            y_brk / self.outer_diameter,
            math.inf,
            low_inclusive=False,
        )
        if self.mobilisation_displacement is not None:
            in_range(
                f"{cls}.mobilisation_displacement",
                self.mobilisation_displacement,
                0.0,
                y_brk,
                low_inclusive=False,
                high_inclusive=False,
            )

    @classmethod
    def from_seabed(
        cls,
        pipe: Pipe,
        clay: Clay,
        *,
        installation_load: float | None = None,
        unit_weight: str = "total",
        **options: Any,
    ) -> VerleyLund:
        """Build from a :class:`Pipe` and a :class:`Clay`.

        ``unit_weight`` selects γ_s in G_c: "total" (``Clay.unit_weight``, as F109 asks) or
        "submerged" (``Clay.submerged_unit_weight``). ``installation_load`` W [N/m] defaults to
        the pipe submerged weight.
        """
        one_of("unit_weight", unit_weight, UNIT_WEIGHTS)
        g = clay.unit_weight if unit_weight == "total" else clay.submerged_unit_weight
        options.setdefault("friction_coefficient", clay.friction_coefficient)
        return cls(
            outer_diameter=pipe.outer_diameter,
            undrained_shear_strength=clay.undrained_shear_strength,
            unit_weight=g,
            installation_load=pipe.submerged_weight
            if installation_load is None
            else installation_load,
            **options,
        )

    # ---- derived quantities ------------------------------------------------------------
    @property
    def initial_penetration(self) -> float:
        """z_i [m] (F109 §3.4.6 with W = ``installation_load``)."""
        x = penetration_group(
            self.installation_load,
            self.outer_diameter,
            self.undrained_shear_strength,
            self.unit_weight,
            self.penetration_form,
        )
        return self.outer_diameter * (0.0071 * x**3.2 + 0.062 * x**0.7)

    @property
    def delta(self) -> float:
        """Friction mobilisation displacement δ [m]."""
        if self.mobilisation_displacement is None:
            return 1.0e-3 * self.outer_diameter
        return float(self.mobilisation_displacement)

    @property
    def g_c(self) -> float:
        """G_c = s_u/(D·γ_s) [-]."""
        return self.undrained_shear_strength / (self.outer_diameter * self.unit_weight)

    def passive(self, penetration: float) -> float:
        """F_R [N/m] at penetration z [m]."""
        return clay_passive_resistance(
            penetration, self.outer_diameter, self.undrained_shear_strength, self.unit_weight
        )

    def breakout_displacement(self, penetration: float) -> float:
        """y_brk [m] for a trough of penetration z [m]."""
        b0, b1 = self.breakout_over_d
        return (b0 + b1 * penetration / self.outer_diameter) * self.outer_diameter

    def backbone_points(self, vertical_load: float) -> dict[str, float]:
        """Backbone of the installation trough in the keys of the V&S backbone (for plots).

        y1 = y2 = y_brk (no accumulation region), y3 = y_res; F_r1 = F_r2 = F_R(z_i),
        F_r3 = F_R(z_res); F_f = μV [N/m]; z_i, z2 = z_i, z3 = z_res [m].
        """
        v = positive("vertical_load", vertical_load)
        zi = self.initial_penetration
        z_res = self.residual_penetration_ratio * zi
        y_brk = self.breakout_displacement(zi)
        fr = self.passive(zi)
        return {
            "y1": y_brk,
            "y2": y_brk,
            "y3": self.residual_over_d * self.outer_diameter,
            "z_i": zi,
            "z2": zi,
            "z3": z_res,
            "F_r1": fr,
            "F_r2": fr,
            "F_r3": self.passive(z_res),
            "F_f": self.friction_coefficient * v,
        }

    # ---- kernel contract ---------------------------------------------------------------
    @property
    def kernel(self):
        return _k.verley_lund_kernel

    @property
    def python_kernel(self):
        return _k.verley_lund_kernel_py

    def packed_parameters(self) -> np.ndarray:
        d = self.outer_diameter
        p = np.zeros(_k.N_PARAMS)
        p[_k.P_MU] = self.friction_coefficient
        p[_k.P_DELTA] = self.delta
        p[_k.P_D] = d
        p[_k.P_KR] = 4.1 * self.undrained_shear_strength * d * self.g_c ** (-0.39)
        p[_k.P_BRK0], p[_k.P_BRK1] = self.breakout_over_d
        p[_k.P_YRES] = self.residual_over_d * d
        zi = self.initial_penetration
        p[_k.P_ZRES] = self.residual_penetration_ratio * zi
        p[_k.P_ZI] = zi
        p[_k.P_PASSIVE_RULE] = _PASSIVE_RULES[self.passive_rule]
        return p

    def initial_state(self) -> np.ndarray:
        """Pipe at rest at y = 0 in its installation trough: z = z_i, region 1."""
        s = np.zeros(self.state_size)
        zi = self.initial_penetration
        s[S_Z] = zi
        s[_k.S_ZT] = zi
        s[S_REGION] = 1.0
        s[_k.S_PHASE] = PHASE_TROUGH
        return s

    def parameters(self) -> Mapping[str, Any]:
        return {
            "outer_diameter": self.outer_diameter,
            "undrained_shear_strength": self.undrained_shear_strength,
            "unit_weight": self.unit_weight,
            "friction_coefficient": self.friction_coefficient,
            "installation_load": self.installation_load,
            "penetration_form": self.penetration_form,
            "breakout_over_d": list(self.breakout_over_d),
            "residual_over_d": self.residual_over_d,
            "residual_penetration_ratio": self.residual_penetration_ratio,
            "mobilisation_displacement": self.delta,
            "passive_rule": self.passive_rule,
        }
