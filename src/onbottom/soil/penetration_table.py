"""DNVGL-RP-F114 penetration models from soil values, and the table, embedment and curve of one
model — the library side of ``onbottom penetration``.

* :func:`drained_estimates` — the drained (sand, F114 Eq 4.9) best estimate and its lower and
  upper estimates (:class:`~onbottom.soil.penetration_sand.DrainedBounds`);
* :func:`undrained_model` — the undrained (clay) Model 1 (Eqs 4.1–4.2) or Model 2 (Eq 4.8);
* :func:`penetration_run` — Q_v at given z/D, the embedment for a load (with the lay factor)
  and the notes where the solution leaves the model's validity, and a curve to draw or save.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from onbottom.errors import OutOfRangeWarning
from onbottom.soil.penetration_clay import DEFAULT_ROUGHNESS, UndrainedModel1, UndrainedModel2
from onbottom.soil.penetration_f114 import (
    EmbedmentResult,
    LayConditions,
    PenetrationModel,
    penetration_curve,
    solve_embedment,
)
from onbottom.soil.penetration_sand import (
    DEPTH_FACTOR_COEFFICIENT,
    DrainedBounds,
    DrainedPenetration,
)
from onbottom.status import Status

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "PenetrationRun",
    "drained_estimates",
    "penetration_run",
    "undrained_model",
]

CURVE_POINTS = 201
"""Points of the curve drawn or saved by :func:`penetration_run`."""


def drained_estimates(
    *,
    diameter: float,
    unit_weight: float,
    friction_angle_deg: float,
    lower_friction_angle_deg: float | None = None,
    upper_friction_angle_deg: float | None = None,
    n_gamma: str = "davis_booker_rough",
    lower_n_gamma: str = "davis_booker_smooth",
    upper_n_gamma: str = "davis_booker_rough",
    depth_factor_coefficient: float = DEPTH_FACTOR_COEFFICIENT,
) -> tuple[DrainedPenetration, DrainedBounds]:
    """The drained best estimate and its lower and upper estimates (onbottom's documented
    definition: lower φ_lower with Davis & Booker smooth N_γ, upper φ_upper with Davis &
    Booker rough N_γ; DNVGL-RP-F114 Eq 4.9).

    Parameters
    ----------
    diameter : float
        Pipe outer diameter D [m].
    unit_weight : float
        Effective unit weight γ' [N/m³].
    friction_angle_deg : float
        φ' of the best estimate [deg].
    lower_friction_angle_deg, upper_friction_angle_deg : float or None
        φ' of the lower and upper estimates [deg] (e.g. φ_cv and the peak angle); None: the
        best estimate's.
    n_gamma, lower_n_gamma, upper_n_gamma : str
        N_γ expressions of the three estimates
        (:data:`~onbottom.soil.penetration_sand.N_GAMMA_METHODS`).
    depth_factor_coefficient : float
        Coefficient c_d of the depth factor d_q [-] (F114: 1.2).
    """
    model = DrainedPenetration(
        diameter=diameter,
        unit_weight=unit_weight,
        friction_angle_deg=friction_angle_deg,
        n_gamma=n_gamma,
        depth_factor_coefficient=depth_factor_coefficient,
    )
    lower = friction_angle_deg if lower_friction_angle_deg is None else lower_friction_angle_deg
    upper = friction_angle_deg if upper_friction_angle_deg is None else upper_friction_angle_deg
    bounds = DrainedBounds.from_friction_angles(
        diameter=diameter,
        unit_weight=unit_weight,
        lower_friction_angle_deg=lower,
        upper_friction_angle_deg=upper,
        lower_n_gamma=lower_n_gamma,
        upper_n_gamma=upper_n_gamma,
        depth_factor_coefficient=depth_factor_coefficient,
    )
    return model, bounds


def undrained_model(
    model: int | str,
    *,
    diameter: float,
    su_mudline: float,
    unit_weight: float,
    su_gradient: float = 0.0,
    roughness: float = DEFAULT_ROUGHNESS,
) -> UndrainedModel1 | UndrainedModel2:
    """DNVGL-RP-F114 undrained Model 1 (bearing capacity, Eqs 4.1–4.2) or Model 2 (empirical
    soft clay, Eq 4.8).

    Parameters
    ----------
    model : int or str
        1 or 2.
    diameter : float
        D [m].
    su_mudline : float
        Undrained shear strength at the mudline s_u0 [Pa].
    unit_weight : float
        Effective unit weight γ' [N/m³].
    su_gradient : float
        Strength gradient ρ [Pa/m].
    roughness : float
        Pipe roughness r in [0, 1] (Model 1 only).
    """
    from onbottom._validate import one_of

    one_of("model", str(model), ("1", "2"))
    common = {
        "diameter": diameter,
        "su_mudline": su_mudline,
        "su_gradient": su_gradient,
        "unit_weight": unit_weight,
    }
    if str(model) == "1":
        return UndrainedModel1(roughness=roughness, **common)
    return UndrainedModel2(**common)


@dataclass(frozen=True, eq=False, slots=True)
class PenetrationRun:
    """Q_v at the asked penetrations, the embedment and its validity (see
    :func:`penetration_run`).

    Attributes
    ----------
    model : PenetrationModel
        The best-estimate model.
    bounds : DrainedBounds or None
        Its lower and upper estimates (drained only).
    table : xarray.Dataset
        :func:`~onbottom.soil.penetration_f114.penetration_curve` at the asked z/D.
    embedment : EmbedmentResult or None
        The embedment for the load (None without one).
    validity : list of str
        Range warnings raised at the embedment's solution and the solver's message when it did
        not converge; empty when valid.
    curve : xarray.Dataset or None
        A 201-point curve to draw or save (when asked).
    """

    model: Any
    bounds: DrainedBounds | None
    table: xr.Dataset
    embedment: EmbedmentResult | None = None
    validity: tuple[str, ...] = ()
    curve: xr.Dataset | None = None

    def rows(self) -> dict[str, np.ndarray]:
        """The table's columns: ``z_over_D`` [-], ``z`` [m], ``B`` [m], ``Q_v`` [N/m] and, with
        bounds, ``Q_v_lower``, ``Q_v_upper`` [N/m]."""
        t = self.table
        rows = {k: t[k].values for k in ("z_over_D", "z", "B", "Q_v")}
        if "Q_v_lower" in t:
            rows["Q_v_lower"] = t["Q_v_lower"].values
            rows["Q_v_upper"] = t["Q_v_upper"].values
        return rows

    def embedment_dict(self) -> dict[str, Any] | None:
        """:meth:`EmbedmentResult.as_dict`, with ``success`` false, ``status`` −3
        (:attr:`~onbottom.status.Status.OUTSIDE_VALIDITY`) and the notes in ``message`` when the
        solution is outside the model's validity; None without an embedment."""
        if self.embedment is None:
            return None
        emb = self.embedment.as_dict()
        if self.validity:
            emb["success"] = False
            emb["status"] = int(Status.OUTSIDE_VALIDITY)
            emb["message"] = "outside the model's validity at the solution: " + "; ".join(
                self.validity
            )
        return emb


def penetration_run(
    model: PenetrationModel,
    z_over_d: ArrayLike,
    *,
    bounds: DrainedBounds | None = None,
    load: float | None = None,
    lay: LayConditions | None = None,
    curve: bool = False,
) -> PenetrationRun:
    """Q_v of ``model`` (and its ``bounds``) at ``z_over_d``, the embedment for ``load`` and a
    curve.

    Parameters
    ----------
    model : PenetrationModel
        The best-estimate F114 model.
    z_over_d : array_like
        Penetrations of the table as z/D [-], in [0, 1].
    bounds : DrainedBounds or None
        Lower and upper estimates, tabulated beside.
    load : float or None
        Vertical load W [N/m]: :func:`~onbottom.soil.penetration_f114.solve_embedment`
        (raises :class:`~onbottom.errors.SolutionError` when k_lay·W > Q_v(D)).
    lay : LayConditions or None
        EI [N·m²] and bottom tension [N] of the lay factor.
    curve : bool
        Also compute a 201-point curve up to the larger of z/D = 0.5, the table's deepest point
        and 1.1 times the embedment (at most z/D = 1).

    The range warnings (:class:`~onbottom.errors.OutOfRangeWarning`) raised at the embedment's
    solution become :attr:`PenetrationRun.validity` and are warned again.
    """
    levels = np.asarray(z_over_d, dtype=float)
    d = model.diameter
    table = penetration_curve(model, levels * d, bounds=bounds)
    embedment = None
    validity: list[str] = []
    if load is not None:
        with warnings.catch_warnings(record=True) as at_solution:
            warnings.simplefilter("always", OutOfRangeWarning)
            embedment = solve_embedment(model, load, lay=lay)
        validity = list(dict.fromkeys(str(w.message) for w in at_solution))
        for w in at_solution:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        if not embedment.success:
            validity.append(embedment.message)
    full = None
    if curve:
        zmax = max(0.5, float(levels.max()))
        if embedment is not None:
            zmax = max(zmax, min(1.0, 1.1 * embedment.z_over_d))
        full = penetration_curve(
            model, bounds=bounds, embedment=embedment, n=CURVE_POINTS, z_over_d_max=zmax
        )
    return PenetrationRun(
        model=model,
        bounds=bounds,
        table=table,
        embedment=embedment,
        validity=tuple(validity),
        curve=full,
    )
