"""Undrained vertical penetration resistance of a pipe in clay (DNVGL-RP-F114 §4.3.2).

Model 1 — bearing capacity with linearly increasing strength (F114 Eqs 4.1–4.2)::

    Q_v   = Q_v0·(1 + d_ca) + γ'·A_bm
    Q_v0  = F·(N_c·s_u0 + ρ·B/4)·B                      N_c = 5.14
    z_su0 = 0                                           z < (D/2)(1 − √2/2)
    z_su0 = z + (D/2)(√2 − 1) − B/2                     otherwise
    s_u0  = s_u,z=0 + ρ·z_su0
    d_ca  = 0.3·(s_u1/s_u2)·arctan(z_su0/B)
    s_u1  = (s_u,z=0 + s_u0)/2 ,   s_u2 = Q_v0/(B·N_c)

F is the Davis & Booker (1973) strength-heterogeneity factor, a function of
κ = ρ·B/s_u0, interpolated linearly between the smooth (r = 0) and rough (r = 1) curves with the
pipe roughness r (default 0.67). **F is an approximation made for onbottom**: the two curves
of Davis & Booker (1973, Géotechnique 23(4):551–563, strip footing) are represented by the
saturating form::

    F(κ) = 1 + a·κ/(κ + b)        rough: a = 0.876, b = 3.01      smooth: a = 0.563, b = 4.10

fitted by least squares to points read along the published curves for 0 <= κ <= 16 (the
curve shape was taken from a public digitisation, groundhog's ``penetration.py``, used as a
reference only; no code or data copied). The fit is within 0.67 % (rough) and 0.85 %
(smooth) of those points; it is *not* the standard's figure. κ > 16 is an extrapolation
(OutOfRangeWarning).

Model 2 — empirical, deep-water soft clay (F114 Eq 4.8)::

    Q_v = [ min(6·(z/D)^0.25, 3.4·(10·z/D)^0.5) + 1.5·γ'·A_bm/(D·s_u) ]·D·s_u

with s_u taken at the pipe invert, s_u = s_u,z=0 + ρ·z. It may underestimate the resistance for
z > D/2 (OutOfRangeWarning).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import (
    PIPE_DIAMETER_M,
    SOIL_UNIT_WEIGHT_N_M3,
    in_range,
    non_negative,
    plausible,
    positive,
)
from onbottom.errors import InputError, OutOfRangeWarning
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay
from onbottom.soil.penetration_geometry import as_penetration, contact_width, penetrated_area

__all__ = [
    "BEARING_FACTOR_NC",
    "DAVIS_BOOKER_KAPPA_MAX",
    "DEFAULT_ROUGHNESS",
    "UndrainedModel1",
    "UndrainedModel2",
    "davis_booker_factor",
]

BEARING_FACTOR_NC: float = 2.0 + math.pi
"""N_c = 2 + π ≈ 5.14 (Prandtl, smooth strip on homogeneous clay)."""

DEFAULT_ROUGHNESS: float = 0.67
"""Default pipe roughness r [-] between smooth (0) and rough (1)."""

DAVIS_BOOKER_KAPPA_MAX: float = 16.0
"""Largest κ = ρB/s_u0 covered by the fitted F curves; beyond it F is extrapolated."""

_F_ROUGH = (0.876, 3.01)
_F_SMOOTH = (0.563, 4.10)


def davis_booker_factor(kappa: ArrayLike, roughness: float = DEFAULT_ROUGHNESS) -> NDArray:
    """Davis & Booker (1973) strength-heterogeneity factor F [-] (approximation, see module).

    Parameters
    ----------
    kappa : array_like
        κ = ρ·B/s_u0 [-], >= 0.
    roughness : float
        r [-] in [0, 1]: 0 smooth, 1 rough; F is interpolated linearly in r.

    Returns
    -------
    ndarray
        F [-], 1 at κ = 0, increasing with κ (smooth → 1.56, rough → 1.88 as κ → ∞).
    """
    r = in_range("roughness", roughness, 0.0, 1.0)
    k = np.asarray(kappa, dtype=float)
    if np.any(k < 0.0) or not np.all(np.isfinite(k)):
        raise InputError("kappa is invalid: must be finite and >= 0 (κ = ρB/s_u0)")
    if k.size and float(k.max()) > DAVIS_BOOKER_KAPPA_MAX:
        warnings.warn(
            f"kappa = rho*B/s_u0 = {float(k.max()):.4g} is outside the range [0, "
            f"{DAVIS_BOOKER_KAPPA_MAX:g}] of the fitted Davis & Booker (1973) F curves "
            "(DNVGL-RP-F114 Model 1); F is extrapolated",
            OutOfRangeWarning,
            stacklevel=3,
        )
    f_rough = 1.0 + _F_ROUGH[0] * k / (k + _F_ROUGH[1])
    f_smooth = 1.0 + _F_SMOOTH[0] * k / (k + _F_SMOOTH[1])
    return f_smooth + r * (f_rough - f_smooth)


def _validate_clay(
    owner: str, diameter: float, su: float, gradient: float, unit_weight: float
) -> None:
    positive(f"{owner}.diameter", diameter)
    plausible(
        f"{owner}.diameter",
        diameter,
        error=PIPE_DIAMETER_M[0],
        usual=PIPE_DIAMETER_M[1],
        unit="m",
        what="the outer diameter of a pipeline",
        stacklevel=5,
    )
    positive(f"{owner}.su_mudline", su)
    if su > 1.0e6:
        raise InputError(
            f"{owner}.su_mudline = {float(su)!r} Pa is invalid: above the plausible 1e6 Pa"
            " (check the unit: Pa)"
        )
    non_negative(f"{owner}.su_gradient", gradient)
    plausible(
        f"{owner}.unit_weight",
        unit_weight,
        error=SOIL_UNIT_WEIGHT_N_M3[0],
        usual=SOIL_UNIT_WEIGHT_N_M3[1],
        unit="N/m³",
        what="γ' of seabed clays",
        stacklevel=5,
    )


def _clay_fields(pipe: Pipe, clay: Clay, kwargs: dict[str, Any]) -> dict[str, Any]:
    fields: dict[str, Any] = {
        "diameter": pipe.outer_diameter,
        "su_mudline": clay.undrained_shear_strength,
        "su_gradient": clay.strength_gradient,
        "unit_weight": clay.submerged_unit_weight,
    }
    fields.update(kwargs)
    return fields


@dataclass(frozen=True, kw_only=True)
class UndrainedModel1:
    """DNVGL-RP-F114 undrained Model 1 (bearing capacity, Eqs 4.1–4.2).

    Parameters
    ----------
    diameter : float
        Outer diameter D [m], > 0.
    su_mudline : float
        s_u at the original seabed s_u,z=0 [Pa], > 0.
    su_gradient : float
        ρ = ds_u/dz [Pa/m], >= 0.
    unit_weight : float
        Submerged unit weight γ' [N/m³], in (0, 30 000] (buoyancy term γ'·A_bm).
    roughness : float
        Pipe roughness r [-], in [0, 1]; default 0.67.
    bearing_factor : float
        N_c [-], > 0; default 2 + π.
    """

    name: ClassVar[str] = "dnvgl_rp_f114_undrained_model1"
    reference: ClassVar[str] = (
        "DNVGL-RP-F114 (May 2017) Eqs 4.1-4.2; F after Davis & Booker (1973), approximated"
    )

    diameter: float
    su_mudline: float
    su_gradient: float = 0.0
    unit_weight: float
    roughness: float = DEFAULT_ROUGHNESS
    bearing_factor: float = BEARING_FACTOR_NC

    def __post_init__(self) -> None:
        _validate_clay(
            "UndrainedModel1", self.diameter, self.su_mudline, self.su_gradient, self.unit_weight
        )
        in_range("UndrainedModel1.roughness", self.roughness, 0.0, 1.0)
        positive("UndrainedModel1.bearing_factor", self.bearing_factor)

    @classmethod
    def from_inputs(cls, pipe: Pipe, clay: Clay, **kwargs: Any) -> UndrainedModel1:
        """Build from :class:`~onbottom.inputs.Pipe` and :class:`~onbottom.inputs.Clay`
        (D, s_u at mudline, gradient, γ'); ``kwargs`` override any field."""
        return cls(**_clay_fields(pipe, clay, kwargs))

    def components(self, z: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Intermediate quantities at ``z`` [m]: B, z_su0 [m], s_u0 [Pa], κ, F, d_ca [-],
        Q_v0, Q_v [N/m], A_bm [m²]."""
        d = self.diameter
        zz = as_penetration(z, d)
        b = contact_width(zz, d)
        abm = penetrated_area(zz, d)
        threshold = 0.5 * d * (1.0 - math.sqrt(2.0) / 2.0)
        z_su0 = np.where(zz < threshold, 0.0, zz + 0.5 * d * (math.sqrt(2.0) - 1.0) - 0.5 * b)
        z_su0 = np.maximum(z_su0, 0.0)
        su0 = self.su_mudline + self.su_gradient * z_su0
        kappa = self.su_gradient * b / su0
        f = davis_booker_factor(kappa, self.roughness)
        nc = self.bearing_factor
        qv0 = f * (nc * su0 + self.su_gradient * b / 4.0) * b
        su1 = 0.5 * (self.su_mudline + su0)
        has_width = b > 0.0
        safe_b = np.where(has_width, b, 1.0)
        su2 = np.where(has_width, qv0 / (safe_b * nc), 1.0)
        dca = np.where(has_width, 0.3 * (su1 / su2) * np.arctan(z_su0 / safe_b), 0.0)
        qv = qv0 * (1.0 + dca) + self.unit_weight * abm
        return {
            "B": b,
            "A_bm": abm,
            "z_su0": z_su0,
            "s_u0": su0,
            "kappa": kappa,
            "F": f,
            "d_ca": dca,
            "Q_v0": qv0,
            "Q_v": qv,
        }

    def resistance(self, z: ArrayLike) -> NDArray[np.float64]:
        """Q_v(z) [N/m] for penetrations ``z`` [m] in ``[0, D]``."""
        return self.components(z)["Q_v"]

    def parameters(self) -> dict[str, Any]:
        """Model parameters (SI) for provenance."""
        return {
            "diameter": self.diameter,
            "su_mudline": self.su_mudline,
            "su_gradient": self.su_gradient,
            "unit_weight": self.unit_weight,
            "roughness": self.roughness,
            "bearing_factor": self.bearing_factor,
        }


@dataclass(frozen=True, kw_only=True)
class UndrainedModel2:
    """DNVGL-RP-F114 undrained Model 2 (empirical, deep-water soft clay, Eq 4.8).

    Parameters
    ----------
    diameter : float
        Outer diameter D [m], > 0.
    su_mudline : float
        s_u at the original seabed [Pa], > 0.
    su_gradient : float
        ds_u/dz [Pa/m], >= 0; s_u is evaluated at the pipe invert.
    unit_weight : float
        Submerged unit weight γ' [N/m³], in (0, 30 000].

    Notes
    -----
    An :class:`~onbottom.errors.OutOfRangeWarning` is emitted for z/D > 0.5, where the model
    may underestimate the resistance.
    """

    name: ClassVar[str] = "dnvgl_rp_f114_undrained_model2"
    reference: ClassVar[str] = "DNVGL-RP-F114 (May 2017) Eq 4.8, empirical soft clay"

    diameter: float
    su_mudline: float
    su_gradient: float = 0.0
    unit_weight: float

    def __post_init__(self) -> None:
        _validate_clay(
            "UndrainedModel2", self.diameter, self.su_mudline, self.su_gradient, self.unit_weight
        )

    @classmethod
    def from_inputs(cls, pipe: Pipe, clay: Clay, **kwargs: Any) -> UndrainedModel2:
        """Build from :class:`~onbottom.inputs.Pipe` and :class:`~onbottom.inputs.Clay`."""
        return cls(**_clay_fields(pipe, clay, kwargs))

    def components(self, z: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Intermediate quantities: s_u at the invert [Pa], A_bm [m²], the strength and
        buoyancy terms and Q_v [N/m]."""
        d = self.diameter
        zz = as_penetration(z, d)
        if zz.size and float(zz.max()) > 0.5 * d:
            warnings.warn(
                f"z/D = {float(zz.max()) / d:.3g} is outside the range [0, 0.5] of "
                "DNVGL-RP-F114 undrained Model 2 (Eq 4.8); it may underestimate the "
                "penetration resistance there",
                OutOfRangeWarning,
                stacklevel=3,
            )
        su = self.su_mudline + self.su_gradient * zz
        abm = penetrated_area(zz, d)
        ratio = zz / d
        strength = np.minimum(6.0 * ratio**0.25, 3.4 * np.sqrt(10.0 * ratio)) * d * su
        buoyancy = 1.5 * self.unit_weight * abm
        return {
            "s_u": su,
            "A_bm": abm,
            "Q_su": strength,
            "Q_buoyancy": buoyancy,
            "Q_v": strength + buoyancy,
        }

    def resistance(self, z: ArrayLike) -> NDArray[np.float64]:
        """Q_v(z) [N/m] for penetrations ``z`` [m] in ``[0, D]``."""
        return self.components(z)["Q_v"]

    def parameters(self) -> dict[str, Any]:
        """Model parameters (SI) for provenance."""
        return {
            "diameter": self.diameter,
            "su_mudline": self.su_mudline,
            "su_gradient": self.su_gradient,
            "unit_weight": self.unit_weight,
        }
