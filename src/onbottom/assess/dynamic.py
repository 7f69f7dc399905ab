"""Dynamic level of a route section: storms over seeds, and the minimum weight by bisection.

Each evaluation builds the ``onbottom storm`` case of the section in one load combination
(:meth:`onbottom.assess.case.RouteCase.storm_document`) through its own loader
(:func:`onbottom.dynamics.storm_case.build_setup`) and runs the seeds with
:func:`onbottom.dynamics.storm_section.simulate_storm_section` (summary only), as
``onbottom storm --seeds N --workers 0`` does.

Minimum weight (concrete thickness, or submerged weight of a simple pipe). The design passes
when **every seed's** largest lateral displacement in **every** combination is at most the
allowable (0.5D, 10D — D of the trial design — or a user value in metres). The governing ratio
g(x) = max over combinations and seeds of max|y| / allowable is bisected on x in the design
range: the upper bound must pass (else no feasible design), the lower bound is returned when
it passes, and the bracket is halved until it is narrower than the tolerance; the passing end
is returned. The same seeds are used at every x (common random numbers), so g is a smooth
function of x for the bisection. A trial is decided as failing at its first seed above the
allowable (the remaining seeds are not run). More weight means less motion for a given flow,
but a thicker coat also adds diameter and load, so g need not be monotone: the bisection finds
a crossing, which :func:`scan_dynamic` (a dense scan) checks in the verification tests.
"""

from __future__ import annotations

import copy
import math
import warnings
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from onbottom._casefile import parse_case

__all__ = ["bisect_dynamic", "dynamic_ratio", "history", "run_seeds", "scan_dynamic"]


def _setup(doc: dict[str, Any]) -> Any:
    from onbottom.dynamics.storm_case import StormCase, build_setup

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return build_setup(parse_case(StormCase, doc), None)


def run_seeds(
    doc: dict[str, Any], seeds: list[int], *, allowable: float | None = None
) -> list[dict[str, Any]]:
    """Run the storm case ``doc`` for ``seeds`` in this process.

    Returns one row per seed run: seed, max_displacement [m], final_displacement [m], status,
    message, diameter [m]. With ``allowable`` [m] the loop stops after the first seed whose
    max displacement exceeds it.
    """
    from onbottom.dynamics.storm_section import simulate_storm_section

    setup = _setup(doc)
    kwargs = setup.kwargs()
    kwargs["settings"] = replace(setup.settings, record_interval=None)
    rows = []
    for seed in seeds:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = simulate_storm_section(
                setup.pipe, setup.soil, setup.storm.with_seed(int(seed)), **kwargs
            )
        rows.append(
            {
                "seed": int(seed),
                "max_displacement": float(r.max_displacement),
                "final_displacement": float(r.final_displacement),
                "status": int(r.status),
                "message": r.message,
                "diameter": float(setup.pipe.outer_diameter),
                "submerged_weight": float(setup.pipe.submerged_weight),
            }
        )
        if allowable is not None and r.max_displacement > allowable:
            break
    return rows


def history(doc: dict[str, Any], seed: int, *, points: int = 400) -> dict[str, list[float]]:
    """Time history of one seed of the storm case ``doc`` (the same run as in
    :func:`run_seeds`, recorded every ``record_interval`` = peak duration / ``points``):
    ``time`` [s], ``y`` lateral displacement [m], ``z`` penetration [m]."""
    from onbottom.dynamics.storm_section import simulate_storm_section

    setup = _setup(doc)
    total = 3600.0 * (doc["storm"]["build_up_hours"] + doc["storm"]["peak_hours"])
    settings = replace(setup.settings, record_interval=max(total / points, 0.1))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = simulate_storm_section(
            setup.pipe, setup.soil, setup.storm.with_seed(int(seed)),
            **(setup.kwargs() | {"settings": settings}),
        )  # fmt: skip
    if r.data is None:  # pragma: no cover - records were asked for
        return {"time": [], "y": [], "z": []}
    return {k: [float(v) for v in r.data[name].values]
            for k, name in (("time", "time"), ("y", "y"), ("z", "z"))}  # fmt: skip


def _trial_pipe(pipe_doc: dict[str, Any], variable: str, layer: str, x: float) -> dict:
    p = copy.deepcopy(pipe_doc)
    if variable == "submerged_weight":
        p["submerged_weight"] = float(x)
    else:
        for lay in p["layers"]:
            if lay["name"] == layer:
                lay["thickness"] = float(x)
    return p


def dynamic_ratio(
    storm_doc: Callable[[dict[str, Any]], list[dict[str, Any]]],
    pipe_doc: dict[str, Any],
    variable: str,
    layer: str,
    x: float,
    seeds: list[int],
    allowable: Callable[[float], float],
    *,
    early_stop: bool = True,
) -> tuple[float, int]:
    """g(x) = max over combinations and seeds of max|y|/allowable at design value ``x``, and
    the number of storms run. ``storm_doc(pipe)`` gives the storm documents of every
    combination for a trial ``[pipe]`` table; ``allowable(D)`` [m]."""
    trial = _trial_pipe(pipe_doc, variable, layer, x)
    worst, n = 0.0, 0
    for doc in storm_doc(trial):
        try:
            d = _setup(doc).pipe.outer_diameter
        except Exception:  # the trial pipe floats in this condition: fails
            return math.inf, n
        allow = allowable(d)
        rows = run_seeds(doc, seeds, allowable=allow if early_stop else None)
        n += len(rows)
        ratio = max(r["max_displacement"] for r in rows) / allow
        worst = max(worst, ratio)
        if early_stop and worst > 1.0:
            break
    return worst, n


def bisect_dynamic(
    evaluate: Callable[[float], tuple[float, int]],
    lo: float,
    hi: float,
    tol: float,
) -> dict[str, Any]:
    """Smallest x in [lo, hi] with ``evaluate(x)[0] <= 1`` by bisection (see the module).

    Returns value (None when the upper bound fails), status (0 found, 1 the lower bound
    passes, 2 none in range), bracket, trials [(x, g)], storms.
    """
    trials: list[tuple[float, float]] = []
    storms = 0

    def g(x: float) -> float:
        nonlocal storms
        v, n = evaluate(x)
        storms += n
        trials.append((float(x), float(v)))
        return v

    if g(hi) > 1.0:
        return {"value": None, "status": 2, "bracket": [lo, hi], "trials": trials,
                "storms": storms, "message": f"the upper bound {hi:g} fails"}  # fmt: skip
    if g(lo) <= 1.0:
        return {"value": lo, "status": 1, "bracket": [lo, lo], "trials": trials,
                "storms": storms, "message": f"the lower bound {lo:g} already passes"}  # fmt: skip
    a, b = lo, hi
    while b - a > tol:
        m = 0.5 * (a + b)
        if g(m) <= 1.0:
            b = m
        else:
            a = m
    return {"value": b, "status": 0, "bracket": [a, b], "trials": trials, "storms": storms,
            "message": f"bisection to {tol:g}"}  # fmt: skip


def scan_dynamic(
    evaluate: Callable[[float], tuple[float, int]], xs: np.ndarray
) -> tuple[np.ndarray, float | None]:
    """g at every x of ``xs`` and the smallest x passing (None if none): the dense-scan check
    of :func:`bisect_dynamic`."""
    gs = np.array([evaluate(float(x))[0] for x in xs])
    ok = np.flatnonzero(gs <= 1.0)
    return gs, (float(xs[ok[0]]) if ok.size else None)
