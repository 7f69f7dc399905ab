"""DNVGL-RP-F114 vertical penetration: model selection, lay factor, embedment, curves.

This module gathers the F114 vertical-penetration models and adds what a design check needs:

* :func:`resistance_model` — the F114 model for a :class:`~onbottom.inputs.Sand` or
  :class:`~onbottom.inputs.Clay` seabed (drained Eq 4.9; undrained Model 1 Eqs 4.1–4.2 or
  Model 2 Eq 4.8);
* :func:`lay_factor` — touchdown (lay) load concentration factor
  ``k_lay = 0.6 + 0.4·(EI·K_v,sec/T_0²)^0.25 >= 1`` (F114 §4.3, as transcribed), valid for
  ``T_0 > (3·√EI·W)^(2/3)``;
* :func:`solve_embedment` — the shallowest ``0 < z <= D`` with ``Q_v(z) = k_lay·W``
  (``scipy.optimize.brentq``; fixed-point iteration on k_lay), raising
  :class:`~onbottom.errors.SolutionError` when ``k_lay·W > Q_v(D)``;
* :func:`penetration_curve` — an xarray Dataset of Q_v(z) with optional lower/upper bound
  curves (:class:`~onbottom.soil.penetration_sand.DrainedBounds` or any pair of models),
  units and provenance.

A *penetration model* here is any object with ``diameter`` [m], ``name``, ``resistance(z)``
returning Q_v [N/m] for an array of penetrations z [m] in ``[0, D]``, and ``parameters()``.
"""

from __future__ import annotations

import logging
import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from onbottom._validate import in_range, one_of, positive
from onbottom.errors import InputError, OutOfRangeWarning, SolutionError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.results import annotate, provenance
from onbottom.soil.penetration_clay import UndrainedModel1, UndrainedModel2
from onbottom.soil.penetration_geometry import as_penetration, contact_width
from onbottom.soil.penetration_sand import DrainedBounds, DrainedPenetration
from onbottom.status import Status

__all__ = [
    "STANDARD",
    "EmbedmentResult",
    "LayConditions",
    "PenetrationModel",
    "lay_factor",
    "lay_validity_tension",
    "penetration_curve",
    "resistance_model",
    "solve_embedment",
]

log = logging.getLogger(__name__)

STANDARD = "DNVGL-RP-F114 (May 2017), equations as transcribed by third parties"
"""Edition note stored in the provenance of every result."""


@runtime_checkable
class PenetrationModel(Protocol):
    """What :func:`solve_embedment` and :func:`penetration_curve` need from a model."""

    name: str
    diameter: float

    def resistance(self, z: ArrayLike) -> NDArray[np.float64]: ...

    def parameters(self) -> dict[str, Any]: ...


def resistance_model(
    pipe: Pipe,
    seabed: Sand | Clay,
    *,
    clay_model: int = 1,
    **kwargs: Any,
) -> DrainedPenetration | UndrainedModel1 | UndrainedModel2:
    """The DNVGL-RP-F114 vertical penetration model for ``pipe`` on ``seabed``.

    Parameters
    ----------
    pipe : Pipe
        Uses ``outer_diameter`` D [m].
    seabed : Sand or Clay
        Sand → drained Eq 4.9 (:class:`DrainedPenetration`); Clay → undrained Model 1 or 2.
    clay_model : int
        1 (bearing capacity, Eqs 4.1–4.2) or 2 (empirical, Eq 4.8); clay only.
    **kwargs
        Further model fields (``n_gamma``, ``roughness``, ...).

    Raises
    ------
    InputError
        For a rock seabed (F114/F109: no penetration on rock) or a bad ``clay_model``.
    """
    if isinstance(seabed, Rock):
        raise InputError(
            "seabed = Rock is invalid: rock is taken as non-penetrable (DNV-RP-F109 §3.4.6); "
            "allowed: Sand, Clay"
        )
    if isinstance(seabed, Sand):
        return DrainedPenetration.from_inputs(pipe, seabed, **kwargs)
    if isinstance(seabed, Clay):
        one_of("clay_model", str(clay_model), ("1", "2"))
        cls = UndrainedModel1 if int(clay_model) == 1 else UndrainedModel2
        return cls.from_inputs(pipe, seabed, **kwargs)
    raise InputError(f"seabed = {seabed!r} is invalid: must be a Sand or Clay")


# --------------------------------------------------------------------------------------------
# Lay factor
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True, slots=True)
class LayConditions:
    """Pipe-lay conditions for the touchdown load concentration factor.

    Parameters
    ----------
    bending_stiffness : float
        EI of the pipe [N·m²], > 0.
    bottom_tension : float
        Horizontal bottom (lay) tension T_0 [N], > 0.
    """

    bending_stiffness: float
    bottom_tension: float

    def __post_init__(self) -> None:
        positive("LayConditions.bending_stiffness", self.bending_stiffness)
        positive("LayConditions.bottom_tension", self.bottom_tension)

    @classmethod
    def from_pipe(cls, pipe: Pipe, bottom_tension: float) -> LayConditions:
        """Use ``pipe.bending_stiffness`` (must be > 0) and the given T_0 [N]."""
        positive("Pipe.bending_stiffness", pipe.bending_stiffness)
        return cls(bending_stiffness=pipe.bending_stiffness, bottom_tension=bottom_tension)


def lay_validity_tension(bending_stiffness: float, submerged_weight: float) -> float:
    """Lowest bottom tension [N] for which the lay factor applies: ``(3·√EI·W)^(2/3)``.

    Parameters
    ----------
    bending_stiffness : float
        EI [N·m²].
    submerged_weight : float
        W [N/m].
    """
    ei = positive("bending_stiffness", bending_stiffness)
    w = positive("submerged_weight", submerged_weight)
    return (3.0 * math.sqrt(ei) * w) ** (2.0 / 3.0)


def lay_factor(
    *,
    bending_stiffness: float,
    secant_stiffness: float,
    bottom_tension: float,
    submerged_weight: float | None = None,
) -> float:
    """Touchdown lay factor ``k_lay = max(1, 0.6 + 0.4·(EI·K_v,sec/T_0²)^0.25)`` [-].

    DNVGL-RP-F114 (2017) §4.3 as transcribed by two independent codes; the floor of 1 is
    part of the expression (``>= 1``).

    Parameters
    ----------
    bending_stiffness : float
        EI [N·m²], > 0.
    secant_stiffness : float
        K_v,sec = Q_v(z)/z [N/m²], > 0 (secant vertical soil stiffness at the embedment).
    bottom_tension : float
        T_0 [N], > 0.
    submerged_weight : float or None
        W [N/m]; if given, an :class:`OutOfRangeWarning` is emitted when
        ``T_0 <= (3·√EI·W)^(2/3)`` (outside the stated validity).
    """
    ei = positive("bending_stiffness", bending_stiffness)
    k = positive("secant_stiffness", secant_stiffness)
    t0 = positive("bottom_tension", bottom_tension)
    if submerged_weight is not None:
        t_min = lay_validity_tension(ei, submerged_weight)
        if t0 <= t_min:
            warnings.warn(
                f"bottom_tension = {t0:.4g} N is outside the validity of the DNVGL-RP-F114 lay "
                f"factor, which needs T_0 > (3·sqrt(EI)·W)^(2/3) = {t_min:.4g} N",
                OutOfRangeWarning,
                stacklevel=2,
            )
    return max(1.0, 0.6 + 0.4 * (ei * k / (t0 * t0)) ** 0.25)


# --------------------------------------------------------------------------------------------
# Embedment solver
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class EmbedmentResult:
    """Embedment for a vertical load (returned by :func:`solve_embedment`).

    Attributes
    ----------
    z : float
        Embedment of the invert [m].
    diameter : float
        D [m].
    resistance : float
        Q_v(z) [N/m] (equals ``design_load`` to solver tolerance).
    load : float
        Static vertical load W [N/m] as given.
    lay_factor : float
        k_lay [-] (1 without lay conditions).
    iterations : int
        Fixed-point iterations on k_lay (1 without lay conditions).
    success : bool
        True when converged (``status.success``).
    status : Status
        :attr:`~onbottom.status.Status.CONVERGED` (6), or
        :attr:`~onbottom.status.Status.NOT_CONVERGED` (−5) when the lay-factor iteration did not
        converge (the last iterate is returned).
    message : str
        Human-readable outcome.
    model : str
        Name of the penetration model.
    """

    z: float
    diameter: float
    resistance: float
    load: float
    lay_factor: float
    iterations: int
    success: bool
    status: Status
    message: str
    model: str
    history: tuple[float, ...] = field(default=(), repr=False)

    @property
    def z_over_d(self) -> float:
        """z/D [-]."""
        return self.z / self.diameter

    @property
    def design_load(self) -> float:
        """k_lay·W [N/m]."""
        return self.lay_factor * self.load

    def as_dict(self) -> dict[str, Any]:
        """Plain dictionary (SI) for JSON output."""
        return {
            "z": self.z,
            "z_over_D": self.z_over_d,
            "Q_v": self.resistance,
            "load": self.load,
            "lay_factor": self.lay_factor,
            "design_load": self.design_load,
            "iterations": self.iterations,
            "success": self.success,
            "status": int(self.status),
            "message": self.message,
            "model": self.model,
        }


def _quiet_resistance(model: PenetrationModel, z: NDArray[np.float64]) -> NDArray[np.float64]:
    """Q_v without range warnings (used while scanning; the solution is re-checked)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OutOfRangeWarning)
        return np.asarray(model.resistance(z), dtype=float)


def _root(model: PenetrationModel, target: float, grid: NDArray[np.float64], rtol: float) -> float:
    """Shallowest z in (0, D] with Q_v(z) = target (grid scan, then brentq)."""
    q = _quiet_resistance(model, grid)
    d = model.diameter
    if not q[-1] >= target:
        raise SolutionError(
            f"no embedment in (0, D] = (0, {d:g}] m balances the vertical load "
            f"{target:.6g} N/m: it exceeds the resistance at full embedment "
            f"Q_v(D) = {q[-1]:.6g} N/m ({model.name})"
        )
    i = int(np.argmax(q >= target))
    if q[i] == target:
        return float(grid[i])
    lo = 0.0 if i == 0 else float(grid[i - 1])  # Q_v(0) = 0 < target
    hi = float(grid[i])

    def f(zz: float) -> float:
        return float(_quiet_resistance(model, np.array(zz))) - target

    return float(
        brentq(f, lo, hi, xtol=1e-14 * d, rtol=max(rtol, 4.0 * np.finfo(float).eps), maxiter=200)
    )


def solve_embedment(
    model: PenetrationModel,
    load: float,
    *,
    lay: LayConditions | None = None,
    n_scan: int = 400,
    tolerance: float = 1e-9,
    max_iterations: int = 100,
) -> EmbedmentResult:
    """Embedment z with ``Q_v(z) = k_lay·W`` for ``0 < z <= D``.

    Parameters
    ----------
    model : PenetrationModel
        Penetration model (e.g. from :func:`resistance_model`).
    load : float
        Static vertical load W [N/m], > 0 (e.g. the submerged weight).
    lay : LayConditions or None
        If given, the load is multiplied by the lay factor
        ``k_lay(EI, K_v,sec = Q_v(z)/z, T_0)`` and z is found by fixed-point iteration
        ``z_{n+1} = Q_v⁻¹(k_lay(z_n)·W)`` starting from the static embedment.
    n_scan : int
        Grid points in (0, D] scanned to bracket the *shallowest* root before brentq.
    tolerance : float
        Relative tolerance on z for brentq and for the lay-factor iteration, in (0, 0.01].
    max_iterations : int
        Maximum fixed-point iterations on k_lay.

    Returns
    -------
    EmbedmentResult

    Raises
    ------
    SolutionError
        If the (factored) load exceeds Q_v(D): no embedment in (0, D] balances it.
    """
    w = positive("load", load)
    d = positive("model.diameter", model.diameter)
    if int(n_scan) < 2:
        raise InputError(f"n_scan = {n_scan!r} is invalid: must be >= 2")
    in_range("tolerance", tolerance, 0.0, 1e-2, low_inclusive=False)
    if int(max_iterations) < 1:
        raise InputError(f"max_iterations = {max_iterations!r} is invalid: must be >= 1")
    grid = np.linspace(0.0, d, int(n_scan) + 1)[1:]

    z = _root(model, w, grid, tolerance)
    k = 1.0
    history = [z]
    iterations = 1
    status, message = Status.CONVERGED, "converged"
    if lay is not None:
        t_min = lay_validity_tension(lay.bending_stiffness, w)
        if lay.bottom_tension <= t_min:
            warnings.warn(
                f"bottom_tension = {lay.bottom_tension:.4g} N is outside the validity of the "
                f"DNVGL-RP-F114 lay factor, which needs T_0 > (3·sqrt(EI)·W)^(2/3) = "
                f"{t_min:.4g} N",
                OutOfRangeWarning,
                stacklevel=2,
            )
        status = Status.NOT_CONVERGED
        message = f"lay-factor iteration did not converge in {max_iterations} steps"
        for iterations in range(1, int(max_iterations) + 1):  # noqa: B007
            q = float(_quiet_resistance(model, np.array(z)))
            k = lay_factor(
                bending_stiffness=lay.bending_stiffness,
                secant_stiffness=q / z,
                bottom_tension=lay.bottom_tension,
            )
            z_new = _root(model, k * w, grid, tolerance)
            history.append(z_new)
            converged = abs(z_new - z) <= 10.0 * tolerance * z_new
            z = z_new
            if converged:
                status, message = Status.CONVERGED, f"converged (k_lay = {k:.4g})"
                break
        if not status.success:
            log.warning("solve_embedment: %s", message)
    # Evaluate once more with warnings on, so that range checks apply at the solution.
    q_final = float(np.asarray(model.resistance(np.array(z))))
    return EmbedmentResult(
        z=z,
        diameter=d,
        resistance=q_final,
        load=w,
        lay_factor=k,
        iterations=iterations,
        success=status.success,
        status=status,
        message=message,
        model=str(model.name),
        history=tuple(history),
    )


# --------------------------------------------------------------------------------------------
# Curves
# --------------------------------------------------------------------------------------------
def _bound_models(
    bounds: DrainedBounds | Sequence[PenetrationModel] | None,
) -> tuple[PenetrationModel, PenetrationModel, dict[str, Any]] | None:
    if bounds is None:
        return None
    if isinstance(bounds, DrainedBounds):
        return bounds.lower, bounds.upper, bounds.parameters()
    lower, upper = bounds
    return (
        lower,
        upper,
        {
            "definition": "user-given lower and upper models",
            "lower": {"model": lower.name, **lower.parameters()},
            "upper": {"model": upper.name, **upper.parameters()},
        },
    )


def penetration_curve(
    model: PenetrationModel,
    z: ArrayLike | None = None,
    *,
    bounds: DrainedBounds | Sequence[PenetrationModel] | None = None,
    embedment: EmbedmentResult | None = None,
    n: int = 101,
    z_over_d_max: float = 0.5,
) -> xr.Dataset:
    """Q_v(z) as an xarray Dataset with units and provenance.

    Parameters
    ----------
    model : PenetrationModel
        The (best-estimate) model; its curve is ``Q_v``.
    z : array_like or None
        Penetrations [m] in [0, D]; default ``n`` points from 0 to ``z_over_d_max·D``.
    bounds : DrainedBounds or (lower, upper) models or None
        Adds ``Q_v_lower`` and ``Q_v_upper``; their definition is stored in the attribute
        ``bound_definition``. Models must share the diameter of ``model``.
    embedment : EmbedmentResult or None
        Stored as attributes ``embedment_z``, ``embedment_load``, ``embedment_lay_factor``.
    n : int
        Number of points of the default grid, >= 2.
    z_over_d_max : float
        End of the default grid as z/D, in (0, 1].

    Returns
    -------
    xarray.Dataset
        Coordinate ``z`` [m] (with ``z_over_D``), variables ``Q_v``, ``B`` and optionally
        ``Q_v_lower``/``Q_v_upper`` [N/m].
    """
    d = float(model.diameter)
    if z is None:
        if int(n) < 2:
            raise InputError(f"n = {n!r} is invalid: must be >= 2")
        zmax = in_range("z_over_d_max", z_over_d_max, 0.0, 1.0, low_inclusive=False)
        zz = np.linspace(0.0, zmax * d, int(n))
    else:
        zz = np.atleast_1d(as_penetration(z, d)).ravel()
    ds = xr.Dataset(
        {
            "Q_v": ("z", np.asarray(model.resistance(zz), dtype=float)),
            "B": ("z", contact_width(zz, d)),
        },
        coords={"z": zz, "z_over_D": ("z", zz / d)},
    )
    extra: dict[str, Any] = {"standard": STANDARD, "diameter": d}
    pair = _bound_models(bounds)
    if pair is not None:
        lower, upper, info = pair
        for m, label in ((lower, "lower"), (upper, "upper")):
            if not math.isclose(float(m.diameter), d, rel_tol=1e-12):
                raise InputError(
                    f"bounds.{label}.diameter = {m.diameter!r} is invalid: must equal the "
                    f"model diameter {d:g} m"
                )
        ds["Q_v_lower"] = ("z", np.asarray(lower.resistance(zz), dtype=float))
        ds["Q_v_upper"] = ("z", np.asarray(upper.resistance(zz), dtype=float))
        extra["bound_definition"] = info["definition"]
        extra["bounds"] = info
    if embedment is not None:
        extra["embedment_z"] = embedment.z
        extra["embedment_load"] = embedment.load
        extra["embedment_lay_factor"] = embedment.lay_factor
    annotate(ds)
    ds.attrs.update(provenance(str(model.name), model.parameters(), **extra))
    return ds
