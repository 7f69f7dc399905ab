"""Drained vertical penetration resistance of a pipe in sand (DNVGL-RP-F114 Eq 4.9).

Equations as implemented (plane strain, no shape factor; symbols in
:func:`drained_resistance`)::

    Q_v  = ½·γ'·N_γ·B² + z_0·γ'·N_q·d_q·B                                          (4.9)
    N_q  = exp(π·tan φ')·tan²(45° + φ'/2)
    d_q  = 1 + c_d·(z_0/B)·tan φ'·(1 − sin φ')²          c_d = 1.2 (F114 as transcribed)
    z_0  = 0                                             z < (D/2)·[1 − cos θ]
    z_0  = z − D/2 + [(D/2)/sin θ − B/2]·tan θ           otherwise,   θ = π/4 + φ'/2

``z_0`` is the surcharge depth: while the pipe lies inside the active Rankine wedge of its own
contact width there is no embedment (surcharge) term.

N_γ options (:data:`N_GAMMA_METHODS`)::

    vesic                2·(N_q + 1)·tan φ'                 Vesić (1973)
    meyerhof             (N_q − 1)·tan(1.4·φ')              Meyerhof (1963)
    davis_booker_rough   0.1054·exp(9.6·φ')   φ' in rad     Davis & Booker (1971), rough strip
    davis_booker_smooth  0.0663·exp(9.3·φ')   φ' in rad     Davis & Booker (1971), smooth strip
    brinch_hansen        1.5·(N_q − 1)·tan φ'               Brinch Hansen (1970)

Edition caveat: the equation number and the 1.2 depth coefficient follow third-party
transcriptions of DNVGL-RP-F114 (May 2017). Classical Brinch Hansen uses 2 in place of 1.2;
the coefficient is an option. See docs/theory/dnv_rp_f114.md.

Upper and lower bounds
----------------------
The standard's own definition of its "upper" and "lower" bound estimates could not be checked.
:class:`DrainedBounds` implements this explicit, documented definition instead:

* **lower bound** — the *lower* friction angle (e.g. the critical-state angle φ_cv) with the
  Davis & Booker **smooth** N_γ (the smallest of the exact plasticity solutions);
* **upper bound** — the *upper* friction angle (e.g. the peak angle of the sand at its density)
  with the Davis & Booker **rough** N_γ (the exact solution for a fully rough strip);
* both friction angles and both N_γ choices can be overridden; if only one friction angle is
  given, the bounds differ only by the base roughness (smooth vs rough).

The bounds are *estimates* spanning the parameter uncertainty, not rigorous plasticity bounds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onbottom._validate import (
    PIPE_DIAMETER_M,
    SOIL_UNIT_WEIGHT_N_M3,
    in_range,
    non_negative,
    one_of,
    plausible,
    positive,
    warn_outside,
)
from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Sand
from onbottom.soil.penetration_geometry import as_penetration, contact_width

__all__ = [
    "DEPTH_FACTOR_COEFFICIENT",
    "FRICTION_ANGLE_RANGE_DEG",
    "N_GAMMA_METHODS",
    "DrainedBounds",
    "DrainedPenetration",
    "bearing_factor_n_gamma",
    "bearing_factor_n_q",
    "depth_factor",
    "drained_resistance",
    "surcharge_depth",
]

N_GAMMA_METHODS: tuple[str, ...] = (
    "vesic",
    "meyerhof",
    "davis_booker_rough",
    "davis_booker_smooth",
    "brinch_hansen",
)
"""Names accepted for the N_γ expression."""

DEPTH_FACTOR_COEFFICIENT: float = 1.2
"""Default c_d of the depth factor d_q (DNVGL-RP-F114 as transcribed; Brinch Hansen: 2)."""

FRICTION_ANGLE_RANGE_DEG: tuple[float, float] = (20.0, 45.0)
"""φ' range [deg] outside which an :class:`OutOfRangeWarning` is emitted.

The Davis & Booker (1971) exponential N_γ fits were derived for about this range, and F114
Eq 4.9 is intended for sands; values outside it are extrapolations.
"""

_SOURCE = "DNVGL-RP-F114 (2017) Eq 4.9 drained penetration with the chosen N_γ"


def bearing_factor_n_q(friction_angle: ArrayLike) -> NDArray[np.float64]:
    """Prandtl–Reissner surcharge factor ``N_q = exp(π tan φ')·tan²(π/4 + φ'/2)`` [-].

    Parameters
    ----------
    friction_angle : array_like
        φ' [rad].
    """
    phi = np.asarray(friction_angle, dtype=float)
    return np.exp(np.pi * np.tan(phi)) * np.tan(np.pi / 4.0 + phi / 2.0) ** 2


def bearing_factor_n_gamma(friction_angle: ArrayLike, method: str) -> NDArray[np.float64]:
    """Self-weight bearing factor N_γ [-] by ``method`` (see :data:`N_GAMMA_METHODS`).

    Parameters
    ----------
    friction_angle : array_like
        φ' [rad].
    method : str
        One of ``vesic`` (Vesić 1973: 2(N_q+1)tanφ), ``meyerhof`` (Meyerhof 1963:
        (N_q−1)tan 1.4φ), ``davis_booker_rough`` (Davis & Booker 1971: 0.1054·e^{9.6φ}),
        ``davis_booker_smooth`` (0.0663·e^{9.3φ}), ``brinch_hansen`` (1.5(N_q−1)tanφ).
    """
    one_of("n_gamma", method, N_GAMMA_METHODS)
    phi = np.asarray(friction_angle, dtype=float)
    if method == "davis_booker_rough":
        return 0.1054 * np.exp(9.6 * phi)
    if method == "davis_booker_smooth":
        return 0.0663 * np.exp(9.3 * phi)
    nq = bearing_factor_n_q(phi)
    if method == "vesic":
        return 2.0 * (nq + 1.0) * np.tan(phi)
    if method == "meyerhof":
        return (nq - 1.0) * np.tan(1.4 * phi)
    return 1.5 * (nq - 1.0) * np.tan(phi)  # brinch_hansen


def surcharge_depth(z: ArrayLike, diameter: float, friction_angle: float) -> NDArray[np.float64]:
    """Surcharge (embedment) depth z_0 [m] with the Rankine active-wedge rule.

    ``z_0 = 0`` while ``z < (D/2)·(1 − cos θ)``, else
    ``z_0 = z − D/2 + [(D/2)/sin θ − B/2]·tan θ`` with ``θ = π/4 + φ'/2`` (DNVGL-RP-F114 §4.3.3
    as transcribed). Continuous at the threshold (z_0 = 0 there).

    Parameters
    ----------
    z : array_like
        Penetration [m], ``0 <= z <= D``.
    diameter : float
        D [m].
    friction_angle : float
        φ' [rad].
    """
    zz = as_penetration(z, diameter)
    d = float(diameter)
    theta = np.pi / 4.0 + friction_angle / 2.0
    b = contact_width(zz, d)
    z0 = zz - 0.5 * d + (0.5 * d / np.sin(theta) - 0.5 * b) * np.tan(theta)
    threshold = 0.5 * d * (1.0 - np.cos(theta))
    return np.where(zz < threshold, 0.0, np.maximum(z0, 0.0))


def depth_factor(
    z0: ArrayLike,
    width: ArrayLike,
    friction_angle: float,
    coefficient: float = DEPTH_FACTOR_COEFFICIENT,
) -> NDArray[np.float64]:
    """Depth factor ``d_q = 1 + c_d·(z_0/B)·tan φ'·(1 − sin φ')²`` [-].

    Parameters
    ----------
    z0 : array_like
        Surcharge depth z_0 [m].
    width : array_like
        Contact width B [m]; where B = 0, d_q = 1.
    friction_angle : float
        φ' [rad].
    coefficient : float
        c_d [-]; 1.2 per DNVGL-RP-F114 (as transcribed), 2 in Brinch Hansen (1970).
    """
    z0a = np.asarray(z0, dtype=float)
    b = np.asarray(width, dtype=float)
    ratio = np.divide(z0a, b, out=np.zeros(np.broadcast(z0a, b).shape), where=b > 0.0)
    s = math.sin(friction_angle)
    return 1.0 + coefficient * ratio * math.tan(friction_angle) * (1.0 - s) ** 2


def drained_resistance(
    z: ArrayLike,
    *,
    diameter: float,
    unit_weight: float,
    friction_angle_deg: float,
    n_gamma: str = "davis_booker_rough",
    depth_factor_coefficient: float = DEPTH_FACTOR_COEFFICIENT,
) -> NDArray[np.float64]:
    """Drained penetration resistance Q_v(z) [N/m] (DNVGL-RP-F114 Eq 4.9).

    Parameters
    ----------
    z : array_like
        Penetration of the invert [m], ``0 <= z <= D``.
    diameter : float
        Outer diameter D [m], > 0.
    unit_weight : float
        Effective unit weight γ' [N/m³], > 0 (submerged; dry unit weight for dry centrifuge
        samples).
    friction_angle_deg : float
        φ' [deg], in [15, 50]; OutOfRangeWarning outside :data:`FRICTION_ANGLE_RANGE_DEG`.
    n_gamma : str
        N_γ expression, one of :data:`N_GAMMA_METHODS`.
    depth_factor_coefficient : float
        c_d of d_q [-], >= 0 (default 1.2).

    Returns
    -------
    ndarray
        Q_v [N/m], same shape as ``z``.
    """
    return DrainedPenetration(
        diameter=diameter,
        unit_weight=unit_weight,
        friction_angle_deg=friction_angle_deg,
        n_gamma=n_gamma,
        depth_factor_coefficient=depth_factor_coefficient,
    ).resistance(z)


@dataclass(frozen=True, kw_only=True)
class DrainedPenetration:
    """DNVGL-RP-F114 Eq 4.9 drained penetration model for one friction angle and one N_γ.

    Parameters
    ----------
    diameter : float
        Outer diameter D [m], > 0.
    unit_weight : float
        Effective unit weight γ' [N/m³], in (0, 30 000].
    friction_angle_deg : float
        φ' [deg], in [15, 50] (OutOfRangeWarning outside [20, 45]).
    n_gamma : str
        N_γ expression (:data:`N_GAMMA_METHODS`); default ``davis_booker_rough``.
    depth_factor_coefficient : float
        c_d of the depth factor [-], >= 0; default 1.2 (F114), Brinch Hansen 2.
    """

    name: ClassVar[str] = "dnvgl_rp_f114_drained"
    reference: ClassVar[str] = "DNVGL-RP-F114 (May 2017) Eq 4.9, drained vertical penetration"

    diameter: float
    unit_weight: float
    friction_angle_deg: float
    n_gamma: str = "davis_booker_rough"
    depth_factor_coefficient: float = DEPTH_FACTOR_COEFFICIENT

    def __post_init__(self) -> None:
        positive("DrainedPenetration.diameter", self.diameter)
        plausible(
            "DrainedPenetration.diameter",
            self.diameter,
            error=PIPE_DIAMETER_M[0],
            usual=PIPE_DIAMETER_M[1],
            unit="m",
            what="the outer diameter of a pipeline",
            stacklevel=4,
        )
        plausible(
            "DrainedPenetration.unit_weight",
            self.unit_weight,
            error=SOIL_UNIT_WEIGHT_N_M3[0],
            usual=SOIL_UNIT_WEIGHT_N_M3[1],
            unit="N/m³",
            what="γ' of seabed sands (dry centrifuge sand up to ~17 kN/m³)",
            stacklevel=4,
        )
        in_range("DrainedPenetration.friction_angle_deg", self.friction_angle_deg, 15.0, 50.0)
        one_of("DrainedPenetration.n_gamma", self.n_gamma, N_GAMMA_METHODS)
        non_negative("DrainedPenetration.depth_factor_coefficient", self.depth_factor_coefficient)
        lo, hi = FRICTION_ANGLE_RANGE_DEG
        warn_outside("friction_angle_deg", self.friction_angle_deg, lo, hi, _SOURCE, stacklevel=4)

    @classmethod
    def from_inputs(cls, pipe: Pipe, sand: Sand, **kwargs: Any) -> DrainedPenetration:
        """Build from a :class:`~onbottom.inputs.Pipe` and a :class:`~onbottom.inputs.Sand`.

        Uses ``pipe.outer_diameter``, ``sand.submerged_unit_weight`` and
        ``sand.friction_angle_deg``; ``kwargs`` override any field.
        """
        fields: dict[str, Any] = {
            "diameter": pipe.outer_diameter,
            "unit_weight": sand.submerged_unit_weight,
            "friction_angle_deg": sand.friction_angle_deg,
        }
        fields.update(kwargs)
        return cls(**fields)

    @property
    def friction_angle(self) -> float:
        """φ' [rad]."""
        return math.radians(self.friction_angle_deg)

    @property
    def n_q(self) -> float:
        """N_q [-]."""
        return float(bearing_factor_n_q(self.friction_angle))

    @property
    def n_gamma_value(self) -> float:
        """N_γ [-] for the chosen expression."""
        return float(bearing_factor_n_gamma(self.friction_angle, self.n_gamma))

    def components(self, z: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Intermediate quantities at ``z`` [m]: B [m], z_0 [m], d_q [-], the self-weight and
        surcharge terms [N/m] and Q_v [N/m]."""
        zz = as_penetration(z, self.diameter)
        phi = self.friction_angle
        b = contact_width(zz, self.diameter)
        z0 = surcharge_depth(zz, self.diameter, phi)
        dq = depth_factor(z0, b, phi, self.depth_factor_coefficient)
        gamma_term = 0.5 * self.unit_weight * self.n_gamma_value * b * b
        surcharge_term = z0 * self.unit_weight * self.n_q * dq * b
        return {
            "B": b,
            "z_0": z0,
            "d_q": dq,
            "Q_gamma": gamma_term,
            "Q_q": surcharge_term,
            "Q_v": gamma_term + surcharge_term,
        }

    def resistance(self, z: ArrayLike) -> NDArray[np.float64]:
        """Q_v(z) [N/m] for penetrations ``z`` [m] in ``[0, D]``."""
        return self.components(z)["Q_v"]

    def parameters(self) -> dict[str, Any]:
        """Model parameters (SI) for provenance."""
        return {
            "diameter": self.diameter,
            "unit_weight": self.unit_weight,
            "friction_angle_deg": self.friction_angle_deg,
            "n_gamma": self.n_gamma,
            "depth_factor_coefficient": self.depth_factor_coefficient,
        }


@dataclass(frozen=True, kw_only=True)
class DrainedBounds:
    """Lower and upper drained penetration estimates (explicit definition, module docstring).

    Parameters
    ----------
    lower, upper : DrainedPenetration
        The two models; build them with :meth:`from_friction_angles` for the documented
        default definition.
    """

    definition: ClassVar[str] = (
        "lower: lower friction angle with Davis & Booker (1971) smooth N_gamma; "
        "upper: upper friction angle with Davis & Booker (1971) rough N_gamma "
        "(onbottom definition; the DNVGL-RP-F114 definition was not available)"
    )

    lower: DrainedPenetration
    upper: DrainedPenetration

    def __post_init__(self) -> None:
        if self.lower.diameter != self.upper.diameter:
            raise InputError(
                f"DrainedBounds.upper.diameter = {self.upper.diameter!r} is invalid: must equal "
                f"lower.diameter = {self.lower.diameter!r}"
            )

    @property
    def diameter(self) -> float:
        """D [m]."""
        return self.lower.diameter

    @classmethod
    def from_friction_angles(
        cls,
        *,
        diameter: float,
        unit_weight: float,
        lower_friction_angle_deg: float,
        upper_friction_angle_deg: float | None = None,
        lower_n_gamma: str = "davis_booker_smooth",
        upper_n_gamma: str = "davis_booker_rough",
        depth_factor_coefficient: float = DEPTH_FACTOR_COEFFICIENT,
    ) -> DrainedBounds:
        """Bounds from two friction angles.

        Parameters
        ----------
        diameter : float
            D [m].
        unit_weight : float
            γ' [N/m³].
        lower_friction_angle_deg : float
            φ' of the lower estimate [deg], e.g. the critical-state angle φ_cv.
        upper_friction_angle_deg : float or None
            φ' of the upper estimate [deg], e.g. the peak angle; None = same as the lower one
            (the bounds then reflect only the base roughness). Must be >= the lower angle.
        lower_n_gamma, upper_n_gamma : str
            N_γ expressions of the two estimates (:data:`N_GAMMA_METHODS`).
        depth_factor_coefficient : float
            c_d of d_q [-].
        """
        phi_up = (
            lower_friction_angle_deg
            if upper_friction_angle_deg is None
            else upper_friction_angle_deg
        )
        in_range(
            "upper_friction_angle_deg",
            phi_up,
            float(lower_friction_angle_deg),
            50.0,
        )
        common = {
            "diameter": diameter,
            "unit_weight": unit_weight,
            "depth_factor_coefficient": depth_factor_coefficient,
        }
        return cls(
            lower=DrainedPenetration(
                friction_angle_deg=lower_friction_angle_deg, n_gamma=lower_n_gamma, **common
            ),
            upper=DrainedPenetration(friction_angle_deg=phi_up, n_gamma=upper_n_gamma, **common),
        )

    def resistance(self, z: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(Q_v,lower, Q_v,upper)`` [N/m] at penetrations ``z`` [m]."""
        return self.lower.resistance(z), self.upper.resistance(z)

    def parameters(self) -> dict[str, Any]:
        """Parameters of both estimates and the bound definition."""
        return {
            "definition": self.definition,
            "lower": self.lower.parameters(),
            "upper": self.upper.parameters(),
        }
