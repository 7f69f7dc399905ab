"""Simulators for calibration: parameter values → simulated test (section solver).

A simulator is a picklable callable ``simulator(record, params) -> result`` where ``params``
maps parameter names to values. The Verley & Sotberg calcareous parameters are named
``A``, ``B``, ``C`` (scaling factors, Youssef & Cassidy 2014), ``mu`` (Coulomb friction
coefficient μ) and ``gamma`` (submerged unit weight of the soil γ' [N/m³]).

* :class:`CentrifugeSimulator` — the centrifuge test preset named by ``record.programme``
  (:func:`onbottom.dynamics.centrifuge.run_centrifuge_test`).
* :class:`RecordedLoadSimulator` — drives the section solver with the record's own H(t), V(t)
  (any test with recorded loads; installation load ``record.V_peak``).

Simulators never print; warnings of out-of-range correlations raised inside a run are caught
and logged once per simulator instance (a calibration evaluates thousands of runs).
"""

from __future__ import annotations

import logging
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from onbottom.calibration.records import TestRecord
from onbottom.errors import InputError, OutOfRangeWarning

__all__ = ["CentrifugeSimulator", "RecordedLoadSimulator"]

logger = logging.getLogger(__name__)

_KNOWN = ("A", "B", "C", "mu", "gamma")


def _check_names(params: Mapping[str, float]) -> None:
    unknown = set(params) - set(_KNOWN)
    if unknown:
        raise InputError(
            f"parameters {sorted(unknown)} are not simulator parameters; known: {list(_KNOWN)}"
        )


def _quiet(fn: Any, *args: Any, **kwargs: Any) -> Any:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OutOfRangeWarning)
        out = fn(*args, **kwargs)
    for w in caught:
        logger.debug("simulation warning: %s", w.message)
    return out


@dataclass(frozen=True, kw_only=True)
class CentrifugeSimulator:
    """Simulate a Youssef (2012) centrifuge test preset with given A, B, C, μ, γ'.

    Parameters
    ----------
    gamma : float or None
        Submerged unit weight γ' [N/m³] used when ``params`` has no ``gamma``; None = the
        preset's default.
    dt : float or None
        Largest time step [s] passed to the preset (None = its default).
    options : mapping
        Further keyword arguments of ``run_centrifuge_test``.
    """

    gamma: float | None = None
    dt: float | None = None
    options: Mapping[str, Any] | None = None

    def __call__(self, record: TestRecord, params: Mapping[str, float]) -> Any:
        from onbottom.dynamics.centrifuge import run_centrifuge_test

        _check_names(params)
        if not record.programme:
            raise InputError(
                f"record {record.name!r} names no centrifuge programme (header 'programme')"
            )
        kwargs: dict[str, Any] = dict(self.options or {})
        kwargs.update(params)
        if "gamma" not in kwargs and self.gamma is not None:
            kwargs["gamma"] = self.gamma
        if self.dt is not None:
            kwargs.setdefault("dt", self.dt)
        return _quiet(run_centrifuge_test, record.programme, **kwargs)


@dataclass(frozen=True, kw_only=True)
class RecordedLoadSimulator:
    """Drive the section solver with the record's measured H(t), V(t).

    Parameters
    ----------
    gamma : float
        Submerged unit weight γ' [N/m³] used when ``params`` has no ``gamma``.
    mass : float or None
        Section mass incl. added mass [kg/m]; None = pipe of the record's diameter with
        specific gravity from V_i (see :func:`onbottom.dynamics.section.section_mass`).
    """

    gamma: float = 7.5e3
    mass: float | None = None

    def __call__(self, record: TestRecord, params: Mapping[str, float]) -> Any:
        from onbottom.dynamics.programmes import from_arrays
        from onbottom.dynamics.section import section_mass, simulate_section
        from onbottom.inputs import Pipe, Sand
        from onbottom.soil.verley_sotberg import VerleySotberg

        _check_names(params)
        for col in ("H", "V"):
            if col not in record.data:
                raise InputError(f"record {record.name!r} has no {col!r} column to drive the run")
        if record.V_peak is None or record.V_i is None:
            raise InputError(f"record {record.name!r} needs V_peak and V_i in its header")
        gamma = float(params.get("gamma", self.gamma))
        pipe = Pipe(outer_diameter=record.diameter, submerged_weight=record.V_i)
        sand = Sand(
            submerged_unit_weight=gamma,
            friction_coefficient=float(params.get("mu", 0.6)),
            kind="calcareous",
        )
        programme = from_arrays(
            record.time,
            record.data["H"].values,
            record.data["V"].values,
            installation_load=record.V_peak,
            cycle_period=record.cycle_period,
            name=record.name,
        )

        def run() -> Any:
            soil = VerleySotberg.calcareous(
                pipe,
                sand,
                A=float(params.get("A", 0.25)),
                B=float(params.get("B", 0.35)),
                C=float(params.get("C", 0.98)),
                installation_load=record.V_peak,
            )
            return simulate_section(
                programme,
                soil,
                mass=self.mass if self.mass is not None else section_mass(pipe),
                displacement_limit=record.displacement_limit,
            )

        return _quiet(run)
