"""Dynamic level of a route section: storms over seeds, and the minimum weight.

Each evaluation runs the seeds of one load combination's
:class:`~onbottom.dynamics.storm_setup.StormSetup` (built by :mod:`onbottom.cases.assess`
through the ``onbottom storm`` loader: the section in that combination, the same case as
``onbottom storm`` on the section's storm document) with
:func:`onbottom.dynamics.storm_section.simulate_storm_section` (summary only), as
``onbottom storm --seeds N --workers 0`` does; a trial design's setups come from the
section's :data:`~onbottom.assess.route.TrialStorm`.

Minimum weight (concrete thickness, or submerged weight of a simple pipe). The design passes
when **every seed's** largest lateral displacement in **every** combination is at most the
allowable (0.5D, 10D — D of the trial design — or a user value in metres). The governing ratio
g(x) = max over combinations and seeds of max|y| / allowable is searched on x in the design
range: the upper bound must pass (else no feasible design), the lower bound is returned when
it passes, and the bracket [failing, passing] is narrowed below the tolerance; the passing
end is returned. :func:`bisect_dynamic` halves the bracket; :func:`search_dynamic` (used by
``onbottom assess``) climbs from below, see Cost. The same seeds are used at every x (common
random numbers). A trial is decided as failing at its first seed above the allowable (the
remaining seeds are not run). More weight means less motion for a given flow, but a thicker
coat also adds diameter and load, and near a runaway one seed can move more at a heavier
weight, so g need not be monotone: each search finds a crossing, which :func:`scan_dynamic`
(a dense scan) checks in the verification tests.

Cost. A failing trial stops at its first seed above the allowable, so it
costs one storm when the seeds are tried worst first (:class:`DynamicTrials` orders the
(combination, seed) pairs by their ratio at the previous trial); a passing trial costs every
storm (combinations × seeds). :func:`search_dynamic` therefore starts from what is already
known — the runs at the given design (every seed: an exact g), the absolute (and generalized)
design as the first guess of a passing weight, the flotation minimum as the lower bound — and
approaches the crossing from below in steps of at most the tolerance: failing trials (about
one storm each) until the first passing one (every storm), which closes the bracket — about
one passing trial instead of the half of log2(range/tol) trials of a bisection that pass; the
first passing value above a failing one is also the smallest one on that grid, where g need
not be monotone. The design is confirmed by one more trial a tolerance heavier (a design whose
next heavier step fails is not robust: near a runaway one seed can move more at a heavier
weight; measured on the 6-case benchmark section: 14 mm passed, 21 mm failed). The storm
kinematics are not cached across trials: their synthesis is
about 5 % of a storm (0.03 s of 0.5–0.9 s, measured), and they depend on D through the current
averaged over the pipe.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from onbottom.dynamics.storm_setup import StormSetup
from onbottom.status import Status

__all__ = [
    "DynamicTrials",
    "bisect_dynamic",
    "dynamic_ratio",
    "history",
    "run_seeds",
    "scan_dynamic",
    "search_dynamic",
]


def run_seeds(
    setup: StormSetup, seeds: list[int], *, allowable: float | None = None
) -> list[dict[str, Any]]:
    """Run the storm ``setup`` for ``seeds`` in this process.

    Returns one row per seed run: seed, max_displacement [m], final_displacement [m], status,
    message, diameter [m]. With ``allowable`` [m] the loop stops after the first seed whose
    max displacement exceeds it.
    """
    from onbottom.dynamics.storm_section import simulate_storm_section

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


def history(
    setup: StormSetup, seed: int, *, duration: float, points: int = 400
) -> dict[str, list[float]]:
    """Time history of one seed of the storm ``setup`` (the same run as in :func:`run_seeds`,
    recorded every ``record_interval`` = ``duration`` [s] (of the storm) / ``points``, at least
    0.1 s): ``time`` [s], ``y`` lateral displacement [m], ``z`` penetration [m]."""
    from onbottom.dynamics.storm_section import simulate_storm_section

    settings = replace(setup.settings, record_interval=max(duration / points, 0.1))
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


def dynamic_ratio(
    trial: Callable[[int, float], StormSetup],
    combinations: int,
    x: float,
    seeds: list[int],
    allowable: Callable[[float], float],
    *,
    early_stop: bool = True,
) -> tuple[float, int]:
    """g(x) = max over combinations and seeds of max|y|/allowable at design value ``x``, and
    the number of storms run. ``trial(k, x)`` gives the storm setup of combination ``k`` (of
    ``combinations``) at a trial design (:data:`~onbottom.assess.route.TrialStorm`);
    ``allowable(D)`` [m]."""
    worst, n = 0.0, 0
    for k in range(combinations):
        try:
            setup = trial(k, x)
        except Exception:  # the trial pipe floats in this condition: fails
            return math.inf, n
        allow = allowable(setup.pipe.outer_diameter)
        rows = run_seeds(setup, seeds, allowable=allow if early_stop else None)
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

    Returns value (None when the upper bound fails), status (a :class:`~onbottom.status.Status`:
    ``CONVERGED`` found, ``AT_BOUND`` the lower bound passes, ``NO_SOLUTION`` none in range),
    bracket, trials [(x, g)], storms.
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
        return {"value": None, "status": Status.NO_SOLUTION, "bracket": [lo, hi],
                "trials": trials, "storms": storms,
                "message": f"the upper bound {hi:g} fails"}  # fmt: skip
    if g(lo) <= 1.0:
        return {"value": lo, "status": Status.AT_BOUND, "bracket": [lo, lo], "trials": trials,
                "storms": storms, "message": f"the lower bound {lo:g} already passes"}  # fmt: skip
    a, b = lo, hi
    while b - a > tol:
        m = 0.5 * (a + b)
        if g(m) <= 1.0:
            b = m
        else:
            a = m
    return {"value": b, "status": Status.CONVERGED, "bracket": [a, b], "trials": trials,
            "storms": storms, "message": f"bisection to {tol:g}"}  # fmt: skip


def scan_dynamic(
    evaluate: Callable[[float], tuple[float, int]], xs: np.ndarray
) -> tuple[np.ndarray, float | None]:
    """g at every x of ``xs`` and the smallest x passing (None if none): the dense-scan check
    of :func:`bisect_dynamic`."""
    gs = np.array([evaluate(float(x))[0] for x in xs])
    ok = np.flatnonzero(gs <= 1.0)
    return gs, (float(xs[ok[0]]) if ok.size else None)


# ---- the cost-aware search -----------------------------------------------------------------------
STOP_MARGIN = 1.0001
"""A trial storm of :class:`DynamicTrials` stops when |y| reaches this × the allowable: its
ratio is then above 1 (a fail) without running the rest of a storm in which the moving pipe
forces small steps."""


class DynamicTrials:
    """g(x) of a trial design with the (combination, seed) pairs run worst first.

    ``trial(k, x)`` gives the storm setup of combination ``k`` (of ``combinations``) at a trial
    design (as in :func:`dynamic_ratio`); ``allowable(D)`` [m]. Calling the object with x returns
    (g, storms run); with ``early_stop`` a trial stops at the first pair above the allowable
    (g is then that pair's ratio, a lower bound of the maximum), and each storm stops once |y|
    passes :data:`STOP_MARGIN` × the allowable (the ratio of a failing pair is then about
    1.0001, a lower bound; a passing pair's ratio is exact). The ratio of every pair run is
    kept, and the next trial runs the pairs in decreasing order of their last ratio, so a
    failing trial usually costs one storm. :meth:`prime` seeds the order with runs already made
    (the given design).
    """

    def __init__(
        self,
        trial: Callable[[int, float], StormSetup],
        combinations: int,
        seeds: list[int],
        allowable: Callable[[float], float],
    ) -> None:
        self.trial, self.combinations = trial, int(combinations)
        self.seeds = [int(s) for s in seeds]
        self.allowable = allowable
        self.last: dict[tuple[int, int], float] = {}

    def prime(self, ratios: dict[tuple[int, int], float]) -> None:
        """Known ratios per (combination index, seed), e.g. from the given design."""
        self.last.update(ratios)

    def __call__(self, x: float, *, early_stop: bool = True) -> tuple[float, int]:
        from onbottom.dynamics.storm_section import simulate_storm_section

        setups: dict[int, Any] = {}
        pairs = [(k, s) for k in range(self.combinations) for s in self.seeds]
        pairs.sort(key=lambda p: -self.last.get(p, math.inf))  # never run first: first
        worst, n = 0.0, 0
        for k, seed in pairs:
            if k not in setups:
                try:
                    setups[k] = self.trial(k, x)
                except Exception:  # the trial pipe floats in this condition: fails
                    return math.inf, n
            setup = setups[k]
            allow = self.allowable(setup.pipe.outer_diameter)
            kwargs = setup.kwargs()
            settings = replace(setup.settings, record_interval=None)
            if early_stop:  # a storm is decided once |y| passes the allowable: stop there
                stop = STOP_MARGIN * allow / setup.pipe.outer_diameter
                if settings.stop_displacement_over_d is None or (
                    stop < settings.stop_displacement_over_d
                ):
                    settings = replace(settings, stop_displacement_over_d=stop)
            kwargs["settings"] = settings
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                r = simulate_storm_section(
                    setup.pipe, setup.soil, setup.storm.with_seed(seed), **kwargs
                )
            n += 1
            ratio = float(r.max_displacement) / allow
            self.last[(k, seed)] = ratio
            worst = max(worst, ratio)
            if early_stop and ratio > 1.0:
                break
        return worst, n


class _Points:
    """g(x) memoised: every trial (x, g) in order, the storms run, and the points known."""

    def __init__(self, evaluate: Callable[[float], tuple[float, int]]) -> None:
        self.evaluate = evaluate
        self.trials: list[tuple[float, float]] = []
        self.storms = 0
        self.pts: dict[float, float] = {}

    def __call__(self, x: float) -> float:
        x = float(x)
        if x in self.pts:
            return self.pts[x]
        v, n = self.evaluate(x)
        self.storms += n
        self.trials.append((x, float(v)))
        self.pts[x] = float(v)
        return float(v)

    def result(self, value: float | None, status: Status, bracket: list, message: str, **more):
        return {"value": value, "status": status, "bracket": bracket, "trials": self.trials,
                "storms": self.storms, **more, "message": message}  # fmt: skip


def _passing_end(
    g: _Points, lo: float, hi: float, guesses: list[float] | tuple, failing: list[float]
) -> float | None:
    """The passing end b of the bracket: the lightest known passing value, else the first
    guess that passes (in increasing order, skipping those at or below a known failure), else
    ``hi`` (None: ``hi`` fails). Failing guesses are added to ``failing``."""
    passing = sorted(x for x, v in g.pts.items() if v <= 1.0)
    b = passing[0] if passing else None
    for x in sorted(guesses):  # only without a known passing design: the climb from below
        if b is not None:  # needs a passing end to stop at, not a tight one
            break
        if lo < x < hi and not any(f >= x for f in failing):
            if g(x) <= 1.0:
                b = x
                break
            failing.append(x)
    if b is None:
        if g(hi) > 1.0:
            return None
        b = hi
    return b


def _ascend(
    g: _Points, a: float, b: float, tol: float, max_steps: int, levels_k: int, max_trials: int
) -> tuple[float, float]:
    """Narrow the bracket [a failing, b passing] from below to ``tol`` (see
    :func:`search_dynamic`): the new bracket."""
    # ``tol * (1 + 1e-9)``: a bracket wider than ``tol`` by round-off only is closed (it
    # would give n = 1, a step onto b, and no progress); n >= 2 puts every first trial
    # strictly inside the bracket, so each pass narrows it.
    while b - a > tol * (1.0 + 1e-9) and len(g.trials) < max_trials:
        width = b - a
        n = max(2, math.ceil(width / tol - 1e-9))
        step = width / n if n <= max_steps else width / levels_k
        x = a + step
        while x < b - 1e-12 * max(1.0, abs(b)) and len(g.trials) < max_trials:
            if g(x) <= 1.0:
                b = x
                break
            a = x
            x = a + step
    return a, b


def _first_failing_above(
    g: _Points, b: float, tol: float, hi: float, confirm: int, max_trials: int
) -> float | None:
    """The first of the next ``confirm`` values above ``b`` (steps of ``tol``) that fails
    (None: they pass, or lie above ``hi``)."""
    for k in range(1, confirm + 1):
        x = b + k * tol
        if x > hi or len(g.trials) >= max_trials:
            break
        if g(x) > 1.0:
            return x
    return None


def search_dynamic(
    evaluate: Callable[[float], tuple[float, int]],
    lo: float,
    hi: float,
    tol: float,
    *,
    known: list[tuple[float, float]] | tuple = (),
    guesses: list[float] | tuple = (),
    max_steps: int = 32,
    levels_k: int = 16,
    confirm: int = 1,
    max_trials: int = 200,
) -> dict[str, Any]:
    """Smallest x in [lo, hi] with g(x) <= 1, to ``tol``, spending few passing trials.

    ``evaluate(x)`` → (g, storms) as :class:`DynamicTrials`; ``known``: (x, g) already
    evaluated with every seed (the given design); ``guesses``: values expected to pass (the
    absolute and generalized designs), tried in increasing order before ``hi`` when no known
    value passes (a passing guess costs every storm and only bounds the climb). The bracket
    [a, b] (a fails, b passes) is then narrowed from below: trials at a + step, a + 2 step, ...
    until one passes, with step = (b − a)/⌈(b − a)/tol⌉ when that is at most ``max_steps``
    steps (one pass closes the bracket to ``tol``), else (b − a)/``levels_k`` and a finer
    ascent in the new bracket. The design found is then confirmed: the next ``confirm`` values
    above it (steps of ``tol``) must pass too — g is not monotone near a runaway (one seed can
    run away at a heavier design and not at a lighter one); where one fails the ascent goes on
    above it (``non_monotone`` lists those values). Returns the keys of
    :func:`bisect_dynamic` (value, status CONVERGED/AT_BOUND/NO_SOLUTION, bracket, trials,
    storms, message).

    Stages: the points known → the passing end → the failing end → ascent and confirmation,
    repeated above a value that fails the confirmation.
    """
    g = _Points(evaluate)
    for x, v in known:
        if lo - 1e-12 <= x <= hi + 1e-12:
            g.pts[float(x)] = float(v)
    failing = sorted(x for x, v in g.pts.items() if v > 1.0)
    b = _passing_end(g, lo, hi, guesses, failing)
    if b is None:
        return g.result(None, Status.NO_SOLUTION, [lo, hi], f"the upper bound {hi:g} fails")
    below = [f for f in failing if f < b]
    a = max(below) if below else None
    if a is None:
        if g(lo) <= 1.0:
            return g.result(lo, Status.AT_BOUND, [lo, lo], f"the lower bound {lo:g} already passes")
        a = lo
    above: list[float] = []  # failing designs found above a passing one (g not monotone)
    while True:
        a, b = _ascend(g, a, b, tol, max_steps, levels_k, max_trials)
        bad = _first_failing_above(g, b, tol, hi, confirm, max_trials)
        if bad is None:
            break
        above.append(bad)
        ok = sorted(x for x, v in g.pts.items() if v <= 1.0 and x > bad)
        if ok:
            a, b = bad, ok[0]
        elif bad < hi and g(hi) <= 1.0:
            a, b = bad, hi
        else:
            msg = (
                f"no design in range passes with its next heavier step: {bad:g} fails above"
                f" the passing {b:g}, and the upper bound {hi:g} fails"
            )
            return g.result(None, Status.NO_SOLUTION, [bad, hi], msg, non_monotone=above)
    note = (
        ""
        if not above
        else "; g is not monotone: " + ", ".join(f"{x:g}" for x in above) + " failed above a"
        " passing design, the search went on above them"
    )
    msg = (
        f"ascent to {tol:g} from below, confirmed by the next {confirm} step(s) above (failing"
        f" trials stop at their first seed above the allowable){note}"
    )
    return g.result(b, Status.CONVERGED, [a, b], msg, non_monotone=above)
