"""Lateral soil models by name: one registry for case files, the CLI, sweeps and the report.

``SOIL_MODELS`` maps a model name to its entry (scipy's ``solve_ivp`` ``METHODS`` dict is the
model): the class, the builder from a pipe and a seabed, and the seabed types it accepts.

======================  ==============================================  ================
name                    model                                           seabed
======================  ==============================================  ================
coulomb                 :class:`~onbottom.soil.coulomb.CoulombFriction`  sand, clay, rock
verley_sotberg_silica   :meth:`VerleySotberg.silica`                    sand
verley_sotberg_calcareous :meth:`VerleySotberg.calcareous`              sand
verley_sotberg_f109     :meth:`VerleySotberg.f109`                      sand
verley_lund             :meth:`VerleyLund.from_seabed`                  clay
vh_parabolic            :class:`~onbottom.soil.vh_parabolic.ParabolicVH`  sand, clay, rock
======================  ==============================================  ================

The F109 case files name a seabed *kind* (``[seabed] model = "sand"``); :data:`SEABED_MODELS`
maps each kind to its default soil model, so the two vocabularies meet here. An unknown name is
an :class:`~onbottom.errors.InputError` naming the field and listing the choices. A new model
registers with :func:`register_soil_model`, its kernel with it (docs/contributing.md, "Add a
soil model"); :data:`SOIL_MODELS` is an :class:`onbottom.registry.Registry`, the same type as
the force models' and the design checks'.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from pydantic import BaseModel

from onbottom.errors import InputError
from onbottom.inputs.pipe import Pipe
from onbottom.inputs.soil import Clay, Rock, Sand
from onbottom.registry import Registry, options_schema
from onbottom.soil.base import LateralResistanceModel

__all__ = [
    "SEABED_MODELS",
    "SOIL_MODELS",
    "SoilModelEntry",
    "build_soil_model",
    "register_soil_model",
    "soil_model_entry",
    "soil_model_for_seabed",
    "soil_model_names",
]

Builder = Callable[..., LateralResistanceModel]


@dataclass(frozen=True)
class SoilModelEntry:
    """One registered soil model (an entry of :class:`onbottom.registry.Registry`).

    ``name`` (the case-file name), ``cls`` (a :class:`LateralResistanceModel` subclass),
    ``build(pipe, seabed, **options)`` (the model for a pipe on a seabed; options are the
    class's keyword arguments), ``seabeds`` (the seabed types accepted), ``description`` (one
    line), ``options`` (the pydantic schema of ``[soil.<name>]``), ``example`` (options that
    build a model for the conformance tests when the class needs some).
    """

    name: str
    cls: type
    build: Builder
    seabeds: tuple[type, ...]
    description: str = ""
    options: type[BaseModel] | None = None
    example: Mapping[str, Any] = field(default_factory=dict)


SOIL_MODELS: Registry[SoilModelEntry] = Registry("soil model", "soil.model")
"""Registered soil models by name (the built-in ones below; :func:`register_soil_model`)."""

SEABED_MODELS: dict[str, str] = {
    "sand": "verley_sotberg_silica",
    "calcareous": "verley_sotberg_calcareous",
    "clay": "verley_lund",
    "rock": "coulomb",
    "coulomb": "coulomb",
}
"""The soil model used for a case file's seabed kind ``[seabed] model`` (F109 commands)."""


def register_soil_model(
    name: str,
    cls: type,
    build: Builder | None = None,
    *,
    seabeds: tuple[type, ...] = (Sand, Clay, Rock),
    description: str = "",
    options: type[BaseModel] | None = None,
    kernel: Callable[..., None] | None = None,
    example: Mapping[str, Any] | None = None,
    replace: bool = False,
) -> SoilModelEntry:
    """Register soil model ``cls`` under ``name``; returns its entry.

    ``build(pipe, seabed, **options)`` defaults to ``cls(**options)``. ``options``, the schema
    of ``[soil.<name>]``, defaults to the class's fields (:func:`onbottom.registry.
    options_schema`). ``kernel``: the model's own numba kernel; it is added to the solvers'
    dispatch (:func:`onbottom.soil._dispatch.register_soil_kernel`) and ``cls.model_id`` set
    to its id — no other file to edit. Without it ``cls.model_id`` must name a kernel of the
    dispatch already. A name already taken is an error unless ``replace``.
    """
    if not (isinstance(cls, type) and issubclass(cls, LateralResistanceModel)):
        raise InputError(
            f"soil model {name!r}: cls = {cls!r} is invalid: a LateralResistanceModel subclass"
        )
    if name in SOIL_MODELS and not replace:
        raise InputError(f"soil model {name!r} is registered already (pass replace=True)")
    if build is None:

        def build(pipe: Pipe, seabed: Any, **options: Any) -> LateralResistanceModel:
            return cls(**options)

    if options is None:
        options = options_schema(cls, name=f"{cls.__name__}Options")
    from onbottom.soil._dispatch import _KERNELS, register_soil_kernel

    if kernel is not None:
        cls.model_id = register_soil_kernel(kernel)
    elif getattr(cls, "model_id", None) not in _KERNELS:
        raise InputError(
            f"soil model {name!r}: {cls.__name__}.model_id ="
            f" {getattr(cls, 'model_id', None)!r} names no kernel of the solvers' dispatch:"
            " pass kernel=<the model's numba kernel>"
        )
    entry = SoilModelEntry(
        name, cls, build, tuple(seabeds), description, options, dict(example or {})
    )
    return SOIL_MODELS.add(entry, replace=replace)


def soil_model_names() -> tuple[str, ...]:
    """The registered names, in registration order."""
    return SOIL_MODELS.names()


def soil_model_entry(name: str, *, where: str = "soil.model") -> SoilModelEntry:
    """The entry of ``name``; an :class:`InputError` naming ``where`` and the choices."""
    return SOIL_MODELS.entry(name, where=where)


def build_soil_model(
    name: str, pipe: Pipe, seabed: Sand | Clay | Rock, *, where: str = "soil.model", **options
) -> LateralResistanceModel:
    """Soil model ``name`` for ``pipe`` on ``seabed`` (options: the class's keywords).

    A seabed type the model does not accept is an :class:`InputError` naming ``where``.
    """
    entry = soil_model_entry(name, where=where)
    if not isinstance(seabed, entry.seabeds):
        kinds = ", ".join(t.__name__ for t in entry.seabeds)
        field = where.rsplit(".", 1)[0] + ".seabed" if "." in where else "seabed"
        raise InputError(
            f"{field} = {type(seabed).__name__} is invalid for model {name!r}: must be one"
            f" of {kinds}"
        )
    return entry.build(pipe, seabed, **options)


def soil_model_for_seabed(
    kind: str, pipe: Pipe, seabed: Sand | Clay | Rock, *, where: str = "seabed.model"
) -> LateralResistanceModel:
    """The default soil model of a seabed kind (:data:`SEABED_MODELS`)."""
    if kind not in SEABED_MODELS:
        raise InputError(
            f"{where} = {kind!r} is invalid: choose one of {', '.join(map(repr, SEABED_MODELS))}"
        )
    return build_soil_model(SEABED_MODELS[kind], pipe, seabed, where=where)


def _register_builtin() -> None:
    from onbottom.soil.coulomb import CoulombFriction
    from onbottom.soil.verley_lund import VerleyLund
    from onbottom.soil.verley_sotberg import VerleySotberg
    from onbottom.soil.vh_parabolic import ParabolicVH

    register_soil_model(
        "coulomb",
        CoulombFriction,
        lambda pipe, seabed, **o: CoulombFriction.from_seabed(seabed, **o),
        description="Coulomb friction (rock: DNV-RP-F109 §3.4.6)",
    )
    register_soil_model(
        "verley_sotberg_silica",
        VerleySotberg,
        VerleySotberg.silica,
        seabeds=(Sand,),
        description="Verley & Sotberg (1994), silica sand",
    )
    register_soil_model(
        "verley_sotberg_calcareous",
        VerleySotberg,
        VerleySotberg.calcareous,
        seabeds=(Sand,),
        description="Verley & Sotberg (1994), calcareous sand (A, B, C factors)",
    )
    register_soil_model(
        "verley_sotberg_f109",
        VerleySotberg,
        VerleySotberg.f109,
        seabeds=(Sand,),
        description="Verley & Sotberg with the DNV-RP-F109 passive law",
    )
    register_soil_model(
        "verley_lund",
        VerleyLund,
        VerleyLund.from_seabed,
        seabeds=(Clay,),
        description="Verley & Lund (1995), clay",
    )
    register_soil_model(
        "vh_parabolic",
        ParabolicVH,
        _build_vh_parabolic,
        description="parabolic V–H force-resultant test model (two-DOF contract)",
        example={"bearing_capacity": 2.0e4},
    )


def _build_vh_parabolic(pipe: Pipe, seabed: Any, **options: Any) -> LateralResistanceModel:
    from onbottom.soil.vh_parabolic import ParabolicVH

    if "bearing_capacity" not in options:
        raise InputError(
            "lateral_model.bearing_capacity is missing: model 'vh_parabolic' needs the"
            " vertical capacity V_p [N/m], in (0, inf]"
        )
    return ParabolicVH.from_seabed(seabed, **options)


_register_builtin()
