"""Misfit between a test record and a simulation of it.

Youssef & Cassidy (2014) chose A, B, C and μ so that a simulation reproduced the *initial
penetration*, the *maximum penetration* and the *maximum horizontal displacement* behaviour of
each centrifuge test. The objective here makes that judgement explicit and weighted. Each term
is dimensionless (normalised as below); the residual vector ``r`` holds ``sqrt(weight)·term``
and the misfit is ``Σ r²``, so the same vector serves least squares and scalar optimisers.

=====================  ==========================================================  =========
term                   definition                                                  scale
=====================  ==========================================================  =========
initial_penetration    w at ``t_cyclic_start`` (simulated − measured)               w_meas
max_penetration        max w over the record's samples                             w_meas
u_history              u_sim resampled (linear interpolation, held at the ends)   u_scale
                       onto the record's time base; one residual per sample,
                       each divided by sqrt(N) so that Σ r² = mean square
w_history              the same for w                                               w_scale
max_displacement       max |u|                                                      u_scale
time_to_limit          first time |u| reaches the displacement limit, measured     T_meas
                       from ``t_cyclic_start`` (cycles = time / cycle period)
=====================  ==========================================================  =========

Penetrations and maximum displacement of the simulation are taken from its resampled series
(a peak between two record samples is invisible in the record too); the time to the limit from
the full-resolution simulation. u_scale is the displacement limit (or max |u| measured);
w_scale is max w measured; T_meas the measured time to the limit. Penetration scales are
floored at 1 % of D so that a record with (almost) no penetration does not divide by zero.

Time to the limit is a non-smooth function of the parameters (it jumps by a cycle when the
pipe just fails to reach the limit in one cycle). A run that never reaches the limit gets the
continuous surrogate ``T_end·(1 + (limit − max|u|)/limit)`` — the record length stretched by
the shortfall — so that the term still grows smoothly as the response falls short.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
import xarray as xr

from onbottom._validate import non_negative
from onbottom.calibration.records import TestRecord
from onbottom.errors import InputError

__all__ = [
    "FAILED_RESIDUAL",
    "HISTORY_ONLY",
    "TERMS",
    "Misfit",
    "MisfitWeights",
    "evaluate_misfit",
    "failed_residuals",
    "record_features",
    "residual_labels",
    "residuals",
    "time_to_limit",
]

TERMS = (
    "initial_penetration",
    "max_penetration",
    "u_history",
    "w_history",
    "max_displacement",
    "time_to_limit",
)
"""Names of the misfit terms, in residual-vector order."""

FAILED_RESIDUAL = 10.0
"""Residual given to every component when a simulation fails (terms are O(0.1) when good)."""


@dataclass(frozen=True, kw_only=True, slots=True)
class MisfitWeights:
    """Weights of the misfit terms (>= 0; 0 switches a term off).

    Parameters
    ----------
    initial_penetration, max_penetration, u_history, w_history, max_displacement, \
time_to_limit : float
        Weight of each term [-] (see the module docstring for the terms).
    """

    initial_penetration: float = 1.0
    max_penetration: float = 1.0
    u_history: float = 1.0
    w_history: float = 1.0
    max_displacement: float = 1.0
    time_to_limit: float = 1.0

    def __post_init__(self) -> None:
        total = 0.0
        for f in fields(self):
            total += non_negative(f"MisfitWeights.{f.name}", getattr(self, f.name))
        if total <= 0.0:
            raise InputError("MisfitWeights are invalid: at least one weight must be > 0")

    def as_dict(self) -> dict[str, float]:
        return {f.name: float(getattr(self, f.name)) for f in fields(self)}


@dataclass(frozen=True, kw_only=True, slots=True)
class Misfit:
    """Misfit of one simulation against one record.

    Attributes
    ----------
    terms : dict
        Unweighted normalised terms (history terms as RMS) [-].
    contributions : dict
        ``weight · term²`` per term (history terms: weight · mean square) [-].
    total : float
        Σ contributions = Σ residuals² [-].
    measured, simulated : dict
        Features of the record and of the simulation (SI: m, s; ``cycles_to_limit`` [-]).
    """

    terms: dict[str, float]
    contributions: dict[str, float]
    total: float
    measured: dict[str, float]
    simulated: dict[str, float]


HISTORY_ONLY = MisfitWeights(
    initial_penetration=0.0, max_penetration=0.0, max_displacement=0.0, time_to_limit=0.0
)
"""Weights that fit the u and w histories only. Use them for noisy records: the scalar
features of a noisy signal are biased (the maximum of w picks the largest noise excursion, the
first crossing of the limit comes early) while the history residuals average the noise out,
and for standard errors (see :mod:`onbottom.calibration.fit`)."""


def time_to_limit(t: np.ndarray, u: np.ndarray, limit: float, t0: float = 0.0) -> float:
    """First time after ``t0`` at which |u| reaches ``limit`` (linear interpolation) [s].

    Measured from ``t0``. If |u| never reaches the limit, returns the continuous surrogate
    ``(t_end − t0)·(1 + (limit − max|u|)/limit)``.
    """
    t = np.asarray(t, dtype=float)
    a = np.abs(np.asarray(u, dtype=float))
    mask = t >= t0
    t, a = t[mask], a[mask]
    if t.size == 0:
        return math.nan
    hit = np.flatnonzero(a >= limit)
    if hit.size == 0:
        return (t[-1] - t0) * (1.0 + (limit - float(a.max())) / limit)
    i = int(hit[0])
    if i == 0:
        return t[0] - t0
    frac = (limit - a[i - 1]) / (a[i] - a[i - 1])
    return t[i - 1] + frac * (t[i] - t[i - 1]) - t0


def _series(ds: xr.Dataset, name: str) -> np.ndarray:
    if name not in ds:
        raise InputError(f"simulated result has no variable {name!r} (has {list(ds.variables)})")
    return np.asarray(ds[name].values, dtype=float)


def record_features(
    t: np.ndarray,
    u: np.ndarray,
    w: np.ndarray,
    *,
    t_cyclic_start: float,
    displacement_limit: float | None,
    cycle_period: float | None,
) -> dict[str, float]:
    """Scalar features of a response: penetrations [m], displacements [m], time/cycles to limit."""
    feats = {
        "initial_penetration": float(np.interp(t_cyclic_start, t, w)),
        "max_penetration": float(np.max(w)),
        "max_displacement": float(np.max(np.abs(u))),
    }
    if displacement_limit is not None:
        ttl = time_to_limit(t, u, displacement_limit, t_cyclic_start)
        feats["time_to_limit"] = ttl
        if cycle_period is not None:
            feats["cycles_to_limit"] = ttl / cycle_period
    return feats


def _simulated_dataset(simulated: Any) -> xr.Dataset:
    if isinstance(simulated, xr.Dataset):
        return simulated
    data = getattr(simulated, "data", None)
    if isinstance(data, xr.Dataset):
        return data
    raise InputError("simulated must be an xarray.Dataset or a result with .data")


def _scales(record: TestRecord) -> dict[str, float]:
    floor = 0.01 * record.diameter
    w_meas = record.z
    u_scale = record.displacement_limit or float(np.max(np.abs(record.y)))
    return {
        "w_init": max(abs(float(np.interp(record.t_cyclic_start, record.time, w_meas))), floor),
        "w_max": max(float(np.max(np.abs(w_meas))), floor),
        "u": max(u_scale, floor),
    }


def _active_terms(record: TestRecord, weights: MisfitWeights) -> list[str]:
    w = weights.as_dict()
    names = [n for n in TERMS if w[n] > 0.0]
    if record.displacement_limit is None and "time_to_limit" in names:
        names.remove("time_to_limit")
    return names


def residual_labels(record: TestRecord, weights: MisfitWeights) -> list[str]:
    """Label of each component of :func:`residuals` (history terms: ``u_history[i]``)."""
    labels: list[str] = []
    n = record.time.size
    for name in _active_terms(record, weights):
        if name.endswith("_history"):
            labels.extend(f"{name}[{i}]" for i in range(n))
        else:
            labels.append(name)
    return labels


def failed_residuals(record: TestRecord, weights: MisfitWeights) -> np.ndarray:
    """Residual vector for a failed simulation: every component :data:`FAILED_RESIDUAL`."""
    return np.full(len(residual_labels(record, weights)), FAILED_RESIDUAL)


def _compute(
    record: TestRecord, simulated: Any, weights: MisfitWeights
) -> tuple[np.ndarray, Misfit]:
    ds = _simulated_dataset(simulated)
    t_sim = _series(ds, "time")
    u_sim = _series(ds, "y")
    w_sim = _series(ds, "z")
    if t_sim.size < 2 or not np.all(np.isfinite(u_sim)) or not np.all(np.isfinite(w_sim)):
        raise InputError("simulated result has fewer than 2 samples or non-finite y/z")
    t = record.time
    meas = record_features(
        t,
        record.y,
        record.z,
        t_cyclic_start=record.t_cyclic_start,
        displacement_limit=record.displacement_limit,
        cycle_period=record.cycle_period,
    )
    # penetrations and displacement from the simulation resampled onto the record's time
    # base (a short peak between two record samples is invisible in the record too); the time
    # to the limit from the full-resolution simulation (it is interpolated within a step)
    u_rs = np.interp(t, t_sim, u_sim)
    w_rs = np.interp(t, t_sim, w_sim)
    sim = record_features(
        t,
        u_rs,
        w_rs,
        t_cyclic_start=record.t_cyclic_start,
        displacement_limit=None,
        cycle_period=None,
    )
    if record.displacement_limit is not None:
        ttl = time_to_limit(t_sim, u_sim, record.displacement_limit, record.t_cyclic_start)
        sim["time_to_limit"] = ttl
        if record.cycle_period is not None:
            sim["cycles_to_limit"] = ttl / record.cycle_period
    sc = _scales(record)
    wts = weights.as_dict()
    n = t.size
    parts: list[np.ndarray] = []
    terms: dict[str, float] = {}
    contrib: dict[str, float] = {}
    for name in _active_terms(record, weights):
        if name == "initial_penetration":
            r = np.array([(sim[name] - meas[name]) / sc["w_init"]])
        elif name == "max_penetration":
            r = np.array([(sim[name] - meas[name]) / sc["w_max"]])
        elif name == "max_displacement":
            r = np.array([(sim[name] - meas[name]) / sc["u"]])
        elif name == "time_to_limit":
            r = np.array([(sim[name] - meas[name]) / max(meas[name], 1e-12)])
        elif name == "u_history":
            r = (u_rs - record.y) / (sc["u"] * math.sqrt(n))
        else:  # w_history
            r = (w_rs - record.z) / (sc["w_max"] * math.sqrt(n))
        terms[name] = float(np.sqrt(np.sum(r**2)))
        weighted = math.sqrt(wts[name]) * r
        contrib[name] = float(np.sum(weighted**2))
        parts.append(weighted)
    vec = np.concatenate(parts) if parts else np.zeros(0)
    return vec, Misfit(
        terms=terms,
        contributions=contrib,
        total=float(np.sum(vec**2)),
        measured=meas,
        simulated=sim,
    )


def residuals(
    record: TestRecord, simulated: Any, weights: MisfitWeights | None = None
) -> np.ndarray:
    """Weighted normalised residual vector of ``simulated`` against ``record``.

    Parameters
    ----------
    record : TestRecord
        The measured (or reference) test.
    simulated : xarray.Dataset or result with ``.data``
        Simulation of the same test: ``time`` [s], ``u`` [m], ``w`` (or ``z``) [m], on any
        time base (resampled onto the record's by linear interpolation).
    weights : MisfitWeights or None
        Term weights (default all 1).

    Returns
    -------
    numpy.ndarray
        Components labelled by :func:`residual_labels`; the misfit is ``Σ r²``.
    """
    return _compute(record, simulated, weights or MisfitWeights())[0]


def evaluate_misfit(
    record: TestRecord, simulated: Any, weights: MisfitWeights | None = None
) -> Misfit:
    """Misfit of ``simulated`` against ``record`` with its terms and features (see module)."""
    return _compute(record, simulated, weights or MisfitWeights())[1]
