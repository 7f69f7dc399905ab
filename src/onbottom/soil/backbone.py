"""The Verley & Sotberg backbone of one pipe on sand, with an optional cyclic path — the library
side of ``onbottom backbone``.

:func:`verley_sotberg_variant` builds the model by variant name, :func:`backbone_run` computes
the backbone (region limits, F_r1/F_r2/F_r3, z_i, z2, z3) and drives the model along a
sinusoidal displacement path, and :func:`backbone_validity` says where the result leaves the
model's validity (penetration above D/2: Verley & Sotberg 1994 fitted their tests below it).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from onbottom._validate import one_of
from onbottom.inputs import Pipe, Sand
from onbottom.soil.verley_sotberg import VerleySotberg

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "BACKBONE_VARIANTS",
    "BackboneRun",
    "backbone_run",
    "backbone_validity",
    "verley_sotberg_variant",
]

BACKBONE_VARIANTS = ("silica", "calcareous", "f109")
"""silica: Verley & Sotberg (1994); calcareous: Youssef & Cassidy (2014); f109: silica with the
DNV-RP-F109 §3.4.6 passive law."""

DEFAULT_AMPLITUDE_OVER_D = 0.1
"""Amplitude of the cyclic path when none is given, as a fraction of D."""


def verley_sotberg_variant(
    variant: str,
    pipe: Pipe,
    sand: Sand,
    *,
    installation_load: float | None = None,
    **factors: float,
) -> VerleySotberg:
    """The Verley & Sotberg model ``variant`` for ``pipe`` on ``sand``.

    Parameters
    ----------
    variant : str
        One of :data:`BACKBONE_VARIANTS` (:meth:`VerleySotberg.silica`,
        :meth:`VerleySotberg.calcareous`, :meth:`VerleySotberg.f109`).
    pipe : Pipe
        Outer diameter D [m]; its submerged weight [N/m] is the default installation load.
    sand : Sand
        Submerged unit weight γ' [N/m³] and friction μ [-].
    installation_load : float or None
        W [N/m] of the initial penetration z_i (Eq 7); None: ``pipe.submerged_weight``.
    **factors
        ``A``, ``B``, ``C`` [-] where given (the variant's defaults otherwise).
    """
    one_of("variant", variant, BACKBONE_VARIANTS)
    build = {
        "silica": VerleySotberg.silica,
        "calcareous": VerleySotberg.calcareous,
        "f109": VerleySotberg.f109,
    }[variant]
    return build(pipe, sand, installation_load=installation_load, **factors)


def backbone_validity(
    points: dict[str, float], diameter: float, final_penetration: float | None = None
) -> list[str]:
    """Where a backbone leaves the Verley & Sotberg model's validity: each of z_i, z2, z3 [m]
    of ``points`` and the path's ``final_penetration`` [m] above D/2 (``diameter`` D [m]).
    Empty when valid."""
    out = []
    for key in ("z_i", "z2", "z3"):
        z = float(points[key])
        if z > 0.5 * diameter:
            out.append(f"{key} = {z:.4g} m exceeds D/2 = {0.5 * diameter:.4g} m")
    if final_penetration is not None and float(final_penetration) > 0.5 * diameter:
        z = float(final_penetration)
        out.append(f"the path's penetration {z:.4g} m exceeds D/2 = {0.5 * diameter:.4g} m")
    return out


@dataclass(frozen=True, eq=False, slots=True)
class BackboneRun:
    """A backbone and its optional cyclic path (see :func:`backbone_run`).

    Attributes
    ----------
    variant : str
        The model variant.
    model : VerleySotberg
        The model.
    vertical_load : float
        V [N/m].
    points : dict
        :meth:`VerleySotberg.backbone_points`: y1, y2, y3, z_i, z2, z3 [m]; F_r1, F_r2, F_r3,
        F_f [N/m]; K_s [-].
    path : xarray.Dataset or None
        :func:`onbottom.soil.response.path_response` along the cyclic path (None without one).
    amplitude : float or None
        Amplitude of the path [m].
    cycles : float or None
        Cycles of the path.
    """

    variant: str
    model: VerleySotberg
    vertical_load: float
    points: dict[str, float]
    path: xr.Dataset | None = None
    amplitude: float | None = None
    cycles: float | None = None

    @property
    def diameter(self) -> float:
        """D [m]."""
        return self.model.outer_diameter

    def path_summary(self) -> dict[str, float] | None:
        """``amplitude`` [m], ``cycles``, ``final_penetration`` [m], ``max_resistance`` (largest
        |F_soil|) [N/m] and ``final_work`` [N] of the path; None without one."""
        if self.path is None:
            return None
        ds = self.path
        return {
            "amplitude": self.amplitude,
            "cycles": self.cycles,
            "final_penetration": float(ds["z"].values[-1]),
            "max_resistance": float(np.max(np.abs(ds["F_soil"].values))),
            "final_work": float(ds["work"].values[-1]),
        }

    def validity(self) -> list[str]:
        """:func:`backbone_validity` of the points and the path's final penetration."""
        path = self.path_summary()
        final = None if path is None else path["final_penetration"]
        return backbone_validity(self.points, self.diameter, final)

    def as_dict(self) -> dict[str, Any]:
        """``model``, ``parameters``, ``vertical_load`` [N/m], ``backbone`` (the points) and,
        with a path, ``path`` (:meth:`path_summary`); SI."""
        payload: dict[str, Any] = {
            "model": self.variant,
            "parameters": dict(self.model.parameters()),
            "vertical_load": self.vertical_load,
            "backbone": self.points,
        }
        path = self.path_summary()
        if path is not None:
            payload["path"] = path
        return payload


def backbone_run(
    variant: str,
    pipe: Pipe,
    sand: Sand,
    *,
    installation_load: float | None = None,
    factors: dict[str, float] | None = None,
    penetration: float | None = None,
    cycles: float | None = None,
    amplitude: float | None = None,
) -> BackboneRun:
    """The backbone of :func:`verley_sotberg_variant` at the vertical load V =
    ``pipe.submerged_weight`` [N/m], and optionally its response along a cyclic path.

    Parameters
    ----------
    variant, pipe, sand, installation_load
        As :func:`verley_sotberg_variant` (W [N/m]).
    factors : dict or None
        ``A``, ``B``, ``C`` [-] (a None value: the variant's default).
    penetration : float or None
        z2 [m] of the backbone; None: z_i.
    cycles : float or None
        Cycles of a sinusoidal displacement path (:func:`onbottom.soil.response.cyclic_path`,
        400 points a cycle); None: no path.
    amplitude : float or None
        Amplitude of the path [m]; None: 0.1·D.
    """
    given = {k: v for k, v in (factors or {}).items() if v is not None}
    model = verley_sotberg_variant(
        variant, pipe, sand, installation_load=installation_load, **given
    )
    v = pipe.submerged_weight
    points = model.backbone_points(v, penetration)
    if cycles is None:
        return BackboneRun(variant=variant, model=model, vertical_load=v, points=points)
    from onbottom.soil.response import cyclic_path, path_response

    amp = DEFAULT_AMPLITUDE_OVER_D * pipe.outer_diameter if amplitude is None else amplitude
    ds = path_response(model, cyclic_path(amp, cycles), v)
    return BackboneRun(
        variant=variant,
        model=model,
        vertical_load=v,
        points=points,
        path=ds,
        amplitude=amp,
        cycles=cycles,
    )
